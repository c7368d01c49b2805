//! The cable at the motion's first pose: per segment the connected geometry, then the
//! quasi-static equilibrium — the shape the attachment test judges — so the simulation
//! starts at rest instead of swinging.

use super::MotionTestError;
use super::plan::Plan;
use super::report::{Failure, FailureCause};
use crate::geometry::{ConnectError, connect, sag_direction};
use crate::pose::Pose;
use crate::setup::Setup;
use crate::statics::sliding::{ThroughEquilibrium, solve_through};
use crate::statics::swivel::{SwivelThrough, solve_through_swivel};
use crate::statics::{
    Equilibrium, FarEnd, RodParameters, SolverOptions, StaticSolver, StaticsError,
};

/// Why there is no initial shape: the candidate's failure and, for a segment too short at
/// the first pose, that segment and the stretch it would need.
pub(super) struct NoStart {
    pub failure: Failure,
    pub too_short: Option<(usize, f64)>,
}

/// The initial shapes: per simulated segment its equilibrium (for a piece through a sliding
/// guide or out of a retraction, the cable as judged, and the solution behind it).
pub(super) struct Shapes {
    pub equilibria: Vec<Equilibrium>,
    pub throughs: Vec<Option<ThroughEquilibrium>>,
}

/// The equilibrium of every simulated segment between `guides` (segments + 1 world poses)
/// at `time_s`, the links at `links`; `Ok(Err(_))` when the candidate has no initial shape
/// (a segment too short, no connected geometry, no equilibrium).
pub(super) fn equilibria(
    setup: &Setup,
    plan: &Plan,
    (guides, links): (&[Pose], &[Pose]),
    time_s: f64,
) -> Result<Result<Shapes, NoStart>, MotionTestError> {
    let sag = sag_direction(&setup.gravity_m_s2);
    let pitch = setup.cable.sub_segment_pitch_m;
    let params = RodParameters::new(&setup.cable, setup.gravity_m_s2);
    let mut solver = StaticSolver::default();
    let mut shapes = Vec::with_capacity(plan.segments.len());
    let mut throughs = Vec::with_capacity(plan.segments.len());
    for (j, planned) in plan.segments.iter().enumerate() {
        let segment = planned.setup_index;
        let (start, end) = (&guides[j], &guides[j + 1]);
        let no_start = |cause, problem: String, too_short| NoStart {
            failure: Failure {
                cause,
                reason: format!(
                    "segment {} at the first pose (t = {time_s} s): {problem}",
                    setup.segment_name(segment)
                ),
                segment: Some(segment),
            },
            too_short,
        };
        if let Some(split) = planned.swivel {
            let clamp = setup.guide_world_pose(links, split.guide, 0);
            let swivel = SwivelThrough::new(clamp, &split, planned.sub_segments);
            let solved = solve_through_swivel(
                &mut solver,
                &planned.rod(&params),
                (start, &swivel, end),
                None,
                &SolverOptions::STRESS_CHECK,
            );
            let (cause, problem) = match solved {
                Ok((equilibrium, _)) => {
                    shapes.push(equilibrium);
                    throughs.push(None);
                    continue;
                }
                Err(e) => through_failure(e),
            };
            return Ok(Err(no_start(cause, problem, None)));
        }
        if let Some((g, kind, stored)) = setup.slide_of(segment) {
            let through = setup.guide_world_pose(links, g, 0);
            let solved = solve_through(
                &planned.rod(&params),
                (kind, stored),
                (start, &through, end),
                (planned.sub_segments, pitch),
                None,
                &SolverOptions::STRESS_CHECK,
            );
            let (cause, problem) = match solved {
                Ok(solved) => {
                    shapes.push(Equilibrium {
                        nodes: solved.nodes.clone(),
                        frames: Vec::new(),
                        twist_rad: 0.0,
                        energy: Default::default(),
                        iterations: 0,
                        residual_n: 0.0,
                    });
                    throughs.push(Some(solved));
                    continue;
                }
                Err(e) => through_failure(e),
            };
            return Ok(Err(no_start(cause, problem, None)));
        }
        let geometry = match connect(start, end, planned.sub_segments, pitch, &sag) {
            Ok(geometry) => geometry,
            Err(source @ ConnectError::InvalidInput { .. }) => {
                return Err(MotionTestError::Geometry {
                    segment: setup.segment_name(segment),
                    source,
                });
            }
            Err(
                e @ ConnectError::TooShort {
                    required_stretch, ..
                },
            ) => {
                let too_short = Some((segment, required_stretch));
                return Ok(Err(no_start(
                    FailureCause::TooShort,
                    e.to_string(),
                    too_short,
                )));
            }
            Err(e @ ConnectError::NoSolution { .. }) => {
                return Ok(Err(no_start(
                    FailureCause::NoInitialShape,
                    e.to_string(),
                    None,
                )));
            }
        };
        let params = planned.rod(&params);
        let solved = solver.solve(
            &params,
            start,
            &FarEnd::Clamped(*end),
            &geometry.nodes,
            Some(geometry.twist_correction_rad),
            &SolverOptions::STRESS_CHECK,
        );
        match solved {
            Ok(equilibrium) => {
                shapes.push(equilibrium);
                throughs.push(None);
            }
            Err(source @ StaticsError::InvalidInput { .. }) => {
                return Err(MotionTestError::Statics {
                    segment: setup.segment_name(segment),
                    source,
                });
            }
            Err(e @ StaticsError::NotConverged { .. }) => {
                let problem = format!("no static equilibrium: {e}");
                return Ok(Err(no_start(FailureCause::NoInitialShape, problem, None)));
            }
        }
    }
    Ok(Ok(Shapes {
        equilibria: shapes,
        throughs,
    }))
}

/// Why a piece through a guide has no initial shape: too short to reach through it, or no
/// equilibrium.
fn through_failure(e: StaticsError) -> (FailureCause, String) {
    match e {
        StaticsError::InvalidInput { .. } => (FailureCause::TooShort, e.to_string()),
        StaticsError::NotConverged { .. } => (
            FailureCause::NoInitialShape,
            format!("no static equilibrium: {e}"),
        ),
    }
}
