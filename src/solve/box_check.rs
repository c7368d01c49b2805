//! A mounting checked over an axis-range box, independently of the search: each piece of the
//! path solved cold (from its connected geometry, [`Evaluator::check_at`]) at every pose of a
//! grid over the joints that shape it, clearance against every link. The search tests
//! pieces at its own grid ([`JointRanges::grid`], continued from length to length); this
//! check is the reference it is measured against, at a finer step.

use super::options::SolveError;
use crate::attachment::Evaluator;
use crate::motion::{JointRanges, combination_count, combinations, traversed_joints};
use crate::path::{CablePath, Pv};
use crate::setup::Setup;
use nalgebra::Vector3;
use rayon::prelude::*;

/// Gravity directions closer than this fraction of the grid step count as one (the search
/// keeps 3° at its 10° step).
pub const GRAVITY_RESOLUTION_PER_STEP: f64 = 0.3;

/// The most poses the box check ([`super::check_ranges`], [`super::allowed_ranges`]) solves
/// one piece at.
pub const MAX_BOX_CHECK_POSES: usize = 2_000_000;

/// One piece of the path over the box.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PieceOverBox {
    /// The piece (`C3`).
    pub segment: String,
    /// The poses it was solved at.
    pub poses: usize,
    /// Its least bend radius over them (mm).
    pub least_bend_radius_mm: f64,
    /// Its least clearance to the robot over them (mm), when measured.
    pub least_clearance_mm: Option<f64>,
    /// The first pose (in grid order) where it violates a limit, if one.
    pub failure: Option<BoxFailure>,
}

/// Where a piece fails over the box.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BoxFailure {
    /// The joints that shape the piece at that pose (name, deg or mm).
    pub joints: Vec<(String, f64)>,
    /// What failed, for people.
    pub reason: String,
}

/// A path over a box: every piece's verdict.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BoxCheck {
    /// The grid's step (degrees; millimetres for a prismatic joint).
    pub step_deg: f64,
    /// Per piece with a cable.
    pub pieces: Vec<PieceOverBox>,
}

impl BoxCheck {
    /// Every piece held every limit at every pose.
    pub fn holds(&self) -> bool {
        self.pieces.iter().all(|p| p.failure.is_none())
    }
}

/// Each piece of `path` over `ranges`: the joints from the base to its start link and those
/// between its links on a grid of `step_deg`, poses whose gravity direction in the start
/// link and whose joints between the links repeat an earlier one's (to
/// [`GRAVITY_RESOLUTION_PER_STEP`] of the step) solved once, the other joints at the box's
/// middle. Refused beyond `max_poses` poses for one piece.
pub fn check_box(
    setup: &Setup,
    path: &CablePath,
    ranges: &JointRanges,
    step_deg: f64,
    max_poses: usize,
) -> Result<BoxCheck, SolveError> {
    let checker = PieceChecker::new(setup, path, step_deg, max_poses)?;
    let pieces = (checker.pieces.iter())
        .map(|piece| checker.over(piece, ranges))
        .collect::<Result<_, _>>()?;
    Ok(BoxCheck { step_deg, pieces })
}

/// The pieces of one path, each solved cold over a box's grid ([`check_box`]'s method), for
/// any box: what the allowed ranges of a mounting ask of many boxes in turn.
pub(super) struct PieceChecker<'a> {
    setup: &'a Setup,
    /// The path's pieces with a cable, from the base end.
    pub(super) pieces: Vec<CheckedPiece>,
    evaluator: Evaluator<'a>,
    /// Gravity's direction in the world (unit, or zero without gravity).
    pub(super) down: Vector3<f64>,
    step_deg: f64,
    max_poses: usize,
}

/// One piece of the path and the joints that shape it.
pub(super) struct CheckedPiece {
    /// Its segment (an index into the setup's).
    pub(super) m: usize,
    pv: Pv,
    /// The link it starts on (an index into the robot's links).
    pub(super) start_link: usize,
    /// The joints (joint-vector indices) from the base up to its start link, not between its
    /// links: they turn gravity in the start link.
    pub(super) upstream: Vec<usize>,
    /// The joints between its links: they place its end link against its start link.
    pub(super) between: Vec<usize>,
}

impl<'a> PieceChecker<'a> {
    /// Refused when the step is not > 0 or `path` does not fit `setup`.
    pub(super) fn new(
        setup: &'a Setup,
        path: &'a CablePath,
        step_deg: f64,
        max_poses: usize,
    ) -> Result<Self, SolveError> {
        if !(step_deg.is_finite() && step_deg > 0.0) {
            return Err(SolveError::Options(format!(
                "the grid step {step_deg} must be > 0"
            )));
        }
        path.check(setup)
            .map_err(|e| SolveError::Options(format!("the path does not fit the setup: {e}")))?;
        let robot = &setup.robot;
        let name = |l: usize| robot.links[l].name.as_str();
        let mut pieces = Vec::new();
        for (m, pv) in path.pieces().filter(|(_, pv)| pv.sub_segments > 0) {
            let (a, b) = setup.segment_guides(m);
            let (body_a, body_b) = (setup.guides[a].body, setup.guides[b].body);
            let between = traversed_joints(robot, name(body_a), name(body_b))?;
            let mut upstream: Vec<usize> = traversed_joints(robot, name(0), name(body_a))?;
            upstream.retain(|j| !between.contains(j));
            pieces.push(CheckedPiece {
                m,
                pv,
                start_link: body_a,
                upstream,
                between,
            });
        }
        Ok(PieceChecker {
            setup,
            pieces,
            evaluator: Evaluator::new(setup, crate::attachment::ConnectMethod::Hermite)?,
            down: (setup.gravity_m_s2)
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::zeros),
            step_deg,
            max_poses,
        })
    }

    /// `piece` over `ranges`.
    pub(super) fn over(
        &self,
        piece: &CheckedPiece,
        ranges: &JointRanges,
    ) -> Result<PieceOverBox, SolveError> {
        let (setup, robot, step_deg) = (self.setup, &self.setup.robot, self.step_deg);
        let (m, pv, body_a) = (piece.m, piece.pv, piece.start_link);
        let (upstream, between) = (&piece.upstream, &piece.between);
        let same = (GRAVITY_RESOLUTION_PER_STEP * step_deg).to_radians().cos();
        let grid = |joints: &[usize]| -> Vec<(usize, Vec<f64>)> {
            (joints.iter())
                .map(|&j| (j, ranges.grid_values(robot, j, step_deg)))
                .collect()
        };
        let (up, along) = (grid(upstream), grid(between));
        let count = combination_count;
        let max_poses = self.max_poses;
        if count(&up).max(count(&along)) > max_poses as f64 {
            return Err(SolveError::Options(format!(
                "{}: {:.0} combinations of the joints up to its start link and {:.0} of those \
                 between its links at {step_deg}° (more than {max_poses}): give a coarser step \
                 or narrower ranges",
                setup.segment_name(m),
                count(&up),
                count(&along)
            )));
        }
        // Every combination of the upstream joints, the last fastest; one kept per gravity
        // direction in the start link (to the resolution), then every combination of the
        // joints between the links with each.
        let mut directions: Vec<(Vec<f64>, Vector3<f64>)> = Vec::new();
        for joints in combinations(&ranges.centre(), &up) {
            let poses = robot
                .link_poses(&joints)
                .map_err(|e| SolveError::Options(e.to_string()))?;
            let g = poses[body_a].rotation.inverse_transform_vector(&self.down);
            if directions.iter().all(|(_, h)| h.dot(&g) < same) {
                directions.push((joints, g));
            }
        }
        if directions.len() as f64 * count(&along) > max_poses as f64 {
            return Err(SolveError::Options(format!(
                "{}: {} gravity directions × {:.0} places between its links at {step_deg}° \
                 (more than {max_poses} poses): give a coarser step or narrower ranges",
                setup.segment_name(m),
                directions.len(),
                count(&along)
            )));
        }
        let kept: Vec<Vec<f64>> = (directions.iter())
            .flat_map(|(base, _)| combinations(base, &along))
            .collect();
        let shaping: Vec<usize> = upstream.iter().chain(between).copied().collect();
        // The links placed where each pose is solved: a grid may have millions of poses.
        let checks: Vec<crate::attachment::Check> = kept
            .par_iter()
            .map(|joints| {
                let poses = robot.link_poses(joints)?;
                Ok(self.evaluator.check_at(m, &pv, &poses))
            })
            .collect::<Result<_, crate::robot::JointVectorError>>()
            .map_err(|e| SolveError::Options(e.to_string()))?;
        let metrics = checks.iter().filter_map(|c| c.metrics.as_ref());
        let least_bend_radius_mm = metrics
            .clone()
            .map(|x| x.min_bend_radius_m * 1e3)
            .fold(f64::INFINITY, f64::min);
        let least_clearance_mm = metrics
            .filter_map(|x| x.clearance_m)
            .map(|c| c * 1e3)
            .reduce(f64::min);
        let failure = (kept.iter().zip(&checks)).find(|(_, c)| !c.passed());
        Ok(PieceOverBox {
            segment: setup.segment_name(m),
            poses: kept.len(),
            least_bend_radius_mm,
            least_clearance_mm,
            failure: failure.map(|(joints, check)| BoxFailure {
                joints: (shaping.iter())
                    .map(|&j| {
                        let joint = robot.actuated_joint(j);
                        (joint.name.clone(), joints[j] * joint.kind.display_unit().0)
                    })
                    .collect(),
                reason: check
                    .detail
                    .clone()
                    .unwrap_or_else(|| "no equilibrium".into()),
            }),
        })
    }
}
