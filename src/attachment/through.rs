//! The attachment test of a piece through a sliding guide or out of a retraction: the pieces
//! on either side of the guide are one piece of the search (its length the total between
//! the clamps), solved from scratch at every pose by the split (or travel) of least energy
//! (docs/architecture.md, "Sliding guides and retractions").

use super::evaluate::{Evaluator, Scene, Solved};
use super::verdict::{Check, Rejection};
use crate::pose::Pose;
use crate::statics::{Holds, RodParameters, sliding};

impl Evaluator<'_> {
    /// The equilibrium of a piece of segment `m` (a span through a sliding guide or a
    /// retraction's outlet) of `sub_segments` between `guides`, held by its clamps as
    /// `holds`, in `scene`; searched around `near_m` first (a sweep's previous pose's split),
    /// else over the whole range (the attachment test: a verdict that depends on nothing
    /// else).
    pub(super) fn solve_through(
        &self,
        (m, holds): (usize, Holds),
        guides: &(Pose, Pose),
        (sub_segments, near_m): (usize, Option<f64>),
        scene: &Scene<'_>,
    ) -> Result<Solved, Check> {
        let setup = self.setup;
        let Some((g, kind, stored)) = setup.slide_of(m) else {
            return Err(Check::fail(
                Rejection::Diverged,
                "not a piece through a sliding guide".into(),
                None,
            ));
        };
        let through = setup.guide_world_pose(scene.link_poses, g, 0);
        let rod = RodParameters {
            gravity_m_s2: scene.gravity_m_s2,
            holds,
            ..self.rod
        };
        let solved = sliding::solve_through(
            &rod,
            (kind, stored),
            (&guides.0, &through, &guides.1),
            (sub_segments, setup.cable.sub_segment_pitch_m),
            near_m,
            &self.solver,
        );
        match solved {
            Ok(solved) => {
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
            Err(e @ crate::statics::StaticsError::InvalidInput { .. }) => {
                Err(Check::fail(Rejection::TooShort, e.to_string(), None))
            }
            Err(e) => Err(Check::fail(Rejection::Diverged, e.to_string(), None)),
        }
    }
}
