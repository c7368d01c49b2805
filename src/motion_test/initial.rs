//! The cable at the motion's first pose: per segment the connected geometry, then the
//! quasi-static equilibrium, so the simulation starts at rest instead of swinging.

use super::MotionTestError;
use super::plan::Plan;
use super::report::{Failure, FailureCause};
use super::tracker::Tracker;
use crate::geometry::{ConnectError, ConnectedGeometry, connect, sag_direction};
use crate::pose::Pose;
use crate::setup::Setup;
use crate::statics::{
    Equilibrium, RodParameters, SegmentStart, SolverOptions, StaticsError, solve_cable,
};

/// The equilibrium of every simulated segment between `guides` (segments + 1 world poses),
/// `Ok(Err(failure))` when the candidate has no initial shape (a segment too short, no
/// connected geometry, no equilibrium). A too-short segment's required stretch is recorded
/// in `tracker` at `time_s`.
pub(super) fn equilibria(
    setup: &Setup,
    plan: &Plan,
    guides: &[Pose],
    time_s: f64,
    tracker: &mut Tracker,
) -> Result<Result<Vec<Equilibrium>, Failure>, MotionTestError> {
    let geometries = match connected(setup, plan, guides, time_s, tracker)? {
        Ok(geometries) => geometries,
        Err(failure) => return Ok(Err(failure)),
    };
    let starts: Vec<SegmentStart> = geometries
        .iter()
        .enumerate()
        .map(|(j, geometry)| SegmentStart {
            start: guides[j],
            end: guides[j + 1],
            nodes: &geometry.nodes,
            twist_rad: Some(geometry.twist_correction_rad),
        })
        .collect();
    let params = RodParameters::new(&setup.cable, setup.gravity_m_s2);
    let mut shapes = Vec::with_capacity(starts.len());
    for (j, result) in solve_cable(&params, &starts, &SolverOptions::STRESS_CHECK)
        .into_iter()
        .enumerate()
    {
        let segment = plan.segments[j].setup_index;
        match result {
            Ok(equilibrium) => shapes.push(equilibrium),
            Err(source @ StaticsError::InvalidInput { .. }) => {
                return Err(MotionTestError::Statics { segment, source });
            }
            Err(e @ StaticsError::NotConverged { .. }) => {
                return Ok(Err(Failure {
                    cause: FailureCause::NoInitialShape,
                    reason: format!(
                        "segment C{}: no static equilibrium at the first pose (t = {time_s} s): {e}",
                        segment + 1
                    ),
                    segment: Some(segment),
                }));
            }
        }
    }
    Ok(Ok(shapes))
}

/// The connected geometry of every simulated segment, the cable bowing towards gravity.
fn connected(
    setup: &Setup,
    plan: &Plan,
    guides: &[Pose],
    time_s: f64,
    tracker: &mut Tracker,
) -> Result<Result<Vec<ConnectedGeometry>, Failure>, MotionTestError> {
    let sag = sag_direction(&setup.gravity_m_s2);
    let pitch = setup.cable.sub_segment_pitch_m;
    let mut geometries = Vec::with_capacity(plan.segments.len());
    for (j, planned) in plan.segments.iter().enumerate() {
        let segment = planned.setup_index;
        match connect(
            &guides[j],
            &guides[j + 1],
            planned.sub_segments,
            pitch,
            &sag,
        ) {
            Ok(geometry) => geometries.push(geometry),
            Err(source @ ConnectError::InvalidInput { .. }) => {
                return Err(MotionTestError::Geometry { segment, source });
            }
            Err(
                e @ ConnectError::TooShort {
                    required_stretch, ..
                },
            ) => {
                tracker.record_too_short(time_s, segment, required_stretch);
                return Ok(Err(Failure {
                    cause: FailureCause::TooShort,
                    reason: format!(
                        "segment C{} at the first pose (t = {time_s} s): {e}",
                        segment + 1
                    ),
                    segment: Some(segment),
                }));
            }
            Err(e @ ConnectError::NoSolution { .. }) => {
                return Ok(Err(Failure {
                    cause: FailureCause::NoInitialShape,
                    reason: format!(
                        "segment C{} at the first pose (t = {time_s} s): {e}",
                        segment + 1
                    ),
                    segment: Some(segment),
                }));
            }
        }
    }
    Ok(Ok(geometries))
}
