//! The attachment test of a piece through a sliding guide, out of a retraction or through a
//! swivel clamp between two pieces: the pieces on either side of the guide are one piece of
//! the search (its length the total between the clamps), solved from scratch at every pose
//! by the split (or travel) of least energy (docs/architecture.md, "Sliding guides and
//! retractions"), or, through a swivel clamp, as one cable held there at the split the setup
//! gives ([`crate::setup::Setup::swivel_of`]), from the previous pose's shape in a sweep.

use super::evaluate::{Evaluator, Scene, Solved};
use super::verdict::{Check, Rejection};
use crate::pose::Pose;
use crate::statics::swivel::{SwivelThrough, solve_through_swivel};
use crate::statics::{Holds, RodParameters, StaticSolver, StaticsError, sliding};

impl Evaluator<'_> {
    /// The equilibrium of a piece of segment `m` (a span through a sliding guide, a
    /// retraction's outlet or a swivel clamp) of `sub_segments` between `guides`, held by its
    /// clamps as `holds`, in `scene`. In a sweep, `last` is the previous pose's: its split is
    /// searched around first, or (swivel) its shape starts the solve; else the whole range,
    /// or the connected geometry (the attachment test: a verdict that depends on nothing
    /// else).
    pub(super) fn solve_through(
        &self,
        (m, holds): (usize, Holds),
        guides: &(Pose, Pose),
        (sub_segments, last): (usize, Option<&Solved>),
        scene: &Scene<'_>,
    ) -> Result<Solved, Check> {
        let setup = self.setup;
        let rod = RodParameters {
            gravity_m_s2: scene.gravity_m_s2,
            holds,
            ..self.rod
        };
        if let Some(split) = setup.swivel_of(m, sub_segments) {
            let clamp = setup.guide_world_pose(scene.link_poses, split.guide, 0);
            let swivel = SwivelThrough::new(clamp, &split, sub_segments);
            let (solved, solves) = solve_through_swivel(
                &mut StaticSolver::default(),
                &rod,
                (&guides.0, &swivel, &guides.1),
                last.map(|l| l.nodes.as_slice()),
                &self.solver,
            )
            .map_err(rejected)?;
            (0..solves).for_each(|_| self.count_static_solve(m));
            return Ok(Solved {
                nodes: solved.nodes,
                connected: Vec::new(),
                twist_rad: solved.twist_rad,
                pitch_m: setup.cable.sub_segment_pitch_m,
                from: None,
                slid_m: None,
            });
        }
        let near_m = last.and_then(|l| l.slid_m);
        let Some((g, kind, stored)) = setup.slide_of(m) else {
            return Err(Check::fail(
                Rejection::Diverged,
                "not a piece through a sliding guide".into(),
                None,
            ));
        };
        let through = setup.guide_world_pose(scene.link_poses, g, 0);
        let solved = sliding::solve_through(
            &rod,
            (kind, stored),
            (&guides.0, &through, &guides.1),
            (sub_segments, setup.cable.sub_segment_pitch_m),
            near_m,
            &self.solver,
        );
        let solved = solved.map_err(rejected)?;
        (0..solved.solves).for_each(|_| self.count_static_solve(m));
        Ok(Solved {
            nodes: solved.nodes,
            connected: Vec::new(),
            twist_rad: 0.0,
            pitch_m: solved.pitch_m,
            from: solved.from,
            slid_m: Some(solved.slid.reading().amount_m),
        })
    }
}

/// A piece that cannot reach through its guide is too short; any other failure diverged.
fn rejected(e: StaticsError) -> Check {
    match e {
        StaticsError::InvalidInput { .. } => Check::fail(Rejection::TooShort, e.to_string(), None),
        _ => Check::fail(Rejection::Diverged, e.to_string(), None),
    }
}
