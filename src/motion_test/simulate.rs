//! The motion test as one loop: the robot and the guides follow the motion, the cable
//! follows the guides, and every instant is measured and kept by the tracker.

use super::clearance::ClearanceQuery;
use super::engine::{Cable, SegmentState};
use super::initial::{Shapes, equilibria};
use super::plan::Plan;
use super::report::{Failure, FailureCause};
use super::tracker::{SegmentMeasure, Tracker};
use super::{MotionTestError, MotionTestOptions};
use crate::motion::Motion;
use crate::pose::Pose;
use crate::progress;
use crate::setup::Setup;
use crate::statics::{RodParameters, clamp_loads};
use crate::stress::{bend_profile, curvature_vectors_per_m, stretch};
use nalgebra::Vector3;

/// Rounds of solving the pieces at rest and balancing the torques at the rotating clamps
/// between them: the twist bends a piece only slightly, so the turn settles in a few.
const TURN_BALANCE_ROUNDS: usize = 4;

/// How often (s of the motion) the loads on the clamps are taken.
pub(super) const LOAD_SAMPLE_S: f64 = 0.02;

/// Slack (in steps) when rounding a duration to whole steps, so that a duration of exactly
/// `n` steps is not rounded up to `n + 1` by floating-point noise.
const STEP_ROUNDING: f64 = 1e-9;

/// What a run needs, borrowed or prepared once.
pub(super) struct Context<'a> {
    pub setup: &'a Setup,
    pub plan: Plan,
    pub motion: &'a Motion,
    pub options: &'a MotionTestOptions,
    pub clearance: ClearanceQuery,
}

/// How a simulation ended: a failure of the candidate (not a limit violation, which the
/// tracker holds), and the number of steps taken.
pub(super) struct Ended {
    pub failure: Option<Failure>,
    pub steps: usize,
}

impl Context<'_> {
    /// The initial equilibrium, then the motion and the settle tail step by step: each
    /// instant measured and recorded, until the end or (when asked) the first violation.
    pub fn simulate(&self, tracker: &mut Tracker) -> Result<Ended, MotionTestError> {
        let t0 = self.motion.times_s()[0];
        let dt = self.options.time_step_s();
        let mut links = self.link_poses(t0)?;
        // The cable's turn in each rotating clamp between two pieces: balanced at rest
        // (a few rounds of solving the pieces and balancing their torques), then carried
        // step to step.
        let mut turns = vec![0.0; self.plan.segments.len() + 1];
        let rounds = if self.plan.shares_turns() {
            TURN_BALANCE_ROUNDS
        } else {
            1
        };
        let declared = self.plan.guide_poses(self.setup, &links);
        let mut shapes = Shapes {
            equilibria: Vec::new(),
            throughs: Vec::new(),
        };
        let mut guides = Vec::new();
        for round in 0..rounds {
            guides = declared.clone();
            self.plan.turned(&mut guides, &turns);
            shapes = match equilibria(self.setup, &self.plan, (&guides, &links), t0)? {
                Ok(shapes) => shapes,
                Err(no_start) => {
                    if let Some((segment, required)) = no_start.too_short {
                        tracker.record_too_short(t0, segment, required);
                    }
                    return Ok(ended(Some(no_start.failure), 0));
                }
            };
            if round + 1 < rounds {
                let mut twists: Vec<f64> = shapes.equilibria.iter().map(|s| s.twist_rad).collect();
                self.plan.balance_turns(&mut turns, &mut twists);
            }
        }
        let pitch_m = self.setup.cable.sub_segment_pitch_m;
        let mut states: Vec<SegmentState> = (shapes.equilibria.iter())
            .zip(&shapes.throughs)
            .map(|(shape, through)| match through {
                Some(through) => SegmentState {
                    nodes: through.nodes.clone(),
                    pitch_m: through.pitch_m,
                    from: through.from,
                    slid: Some(through.slid.reading()),
                    contact: None,
                    max_joint_gap_m: 0.0,
                    twist_rad: Some(0.0),
                },
                None => SegmentState {
                    nodes: shape.nodes.clone(),
                    pitch_m,
                    from: None,
                    slid: None,
                    contact: None,
                    max_joint_gap_m: 0.0,
                    twist_rad: Some(shape.twist_rad),
                },
            })
            .collect();
        let start = Cable::start(
            &self.options.engine,
            (self.setup, &self.plan),
            self.clearance.zones(),
            (&guides, &links),
            (&shapes.equilibria, &shapes.throughs),
        )?;
        let mut cable = match start {
            Ok(cable) => cable,
            Err(failure) => return Ok(ended(Some(failure), 0)),
        };
        let total = self.step_count();
        progress::begin("motion test", total as u64);
        let mut result = Ok(ended(None, total));
        let mut loads_due_s = f64::NEG_INFINITY;
        for k in 0..=total {
            let t = t0 + k as f64 * dt;
            if k > 0 {
                progress::advance(1);
                links = self.link_poses(t)?;
                guides = self.plan.guide_poses(self.setup, &links);
                self.plan.turned(&mut guides, &turns);
                states = match cable.advance(&guides, &links)? {
                    Ok(states) => states,
                    Err(diverged) => {
                        let failure = self.diverged(diverged.segment, &diverged.detail, t);
                        result = Ok(ended(Some(failure), k));
                        break;
                    }
                };
            }
            // Clamp loads cost a dozen energy evaluations per clamp: taken every
            // LOAD_SAMPLE_S of the motion, not every step.
            let with_loads = t >= loads_due_s - 1e-9 || k == total;
            if with_loads {
                loads_due_s = t + LOAD_SAMPLE_S;
            }
            if self.plan.shares_turns() {
                // Balanced after the step: the twists as the turned clamps give them.
                let mut twists: Vec<f64> =
                    states.iter().map(|s| s.twist_rad.unwrap_or(0.0)).collect();
                self.plan.balance_turns(&mut turns, &mut twists);
                for (state, twist) in states.iter_mut().zip(twists) {
                    state.twist_rad = state.twist_rad.map(|_| twist);
                }
                let shared: Vec<(&str, f64)> = (0..turns.len())
                    .filter(|&i| self.plan.shared_turn[i])
                    .map(|i| {
                        let guide = self.plan.segments[i].start.0;
                        (self.setup.guides[guide].name.as_str(), turns[i])
                    })
                    .collect();
                tracker.record_turns(t, &shared);
            }
            let measures = self.measure(&links, &guides, &mut states, t, with_loads)?;
            tracker.record(t, &measures);
            if self.options.stop_at_first_violation && tracker.violated() {
                result = Ok(ended(None, k));
                break;
            }
        }
        progress::end();
        result
    }

    /// Steps for the motion (its last step reaches or passes the last sample) plus the tail;
    /// none for a check of the first pose alone.
    pub fn step_count(&self) -> usize {
        if self.options.first_pose_only {
            return 0;
        }
        let dt = self.options.time_step_s();
        let steps = |duration: f64| (duration / dt - STEP_ROUNDING).ceil().max(0.0) as usize;
        steps(self.motion.duration_s()) + steps(self.options.settle_tail_s)
    }

    /// Link poses at `time_s` (joints interpolated between samples, held after the end).
    fn link_poses(&self, time_s: f64) -> Result<Vec<Pose>, MotionTestError> {
        self.setup
            .robot
            .link_poses(&self.motion.joints_at(time_s))
            .map_err(|source| MotionTestError::Kinematics { time_s, source })
    }

    /// The three metrics of every segment, from its nodes alone, as the attachment test
    /// judges a static shape (the nodes move into the measure), its twist, and `with_loads`
    /// the loads on its clamps.
    fn measure(
        &self,
        links: &[Pose],
        guides: &[Pose],
        states: &mut [SegmentState],
        time_s: f64,
        with_loads: bool,
    ) -> Result<Vec<SegmentMeasure>, MotionTestError> {
        let axis = |pose: &Pose| pose.rotation * Vector3::z();
        let params = RodParameters::new(&self.setup.cable, self.setup.gravity_m_s2);
        let mut measures = Vec::with_capacity(states.len());
        for (j, (planned, state)) in self.plan.segments.iter().zip(states).enumerate() {
            let segment = planned.setup_index;
            let nodes = std::mem::take(&mut state.nodes);
            let pitch = state.pitch_m;
            let start = state.from.as_ref().unwrap_or(&guides[j]);
            let natural = nodes.len().saturating_sub(1) as f64 * pitch;
            let (bend, curvatures) =
                bend_profile(&nodes, &axis(start), &axis(&guides[j + 1]), pitch);
            // The bending each conductor feels, for the cable's life (only when it has a
            // life curve: 12 conductors per joint at every step).
            let bending = match self.setup.cable.datasheet.predicts_life() {
                true => curvature_vectors_per_m(
                    &nodes,
                    &start.rotation.to_rotation_matrix(),
                    &axis(&guides[j + 1]),
                    state.twist_rad.unwrap_or(0.0),
                    pitch,
                ),
                false => Vec::new(),
            };
            // The loads of a piece through a sliding guide are not one rod's between its
            // clamps; through a swivel they are (its end clamps' terms do not reach the
            // swivel's node), the cable free to turn.
            let rod = planned.through.is_none() || planned.swivel.is_some();
            let loads = state
                .twist_rad
                .filter(|_| with_loads && rod)
                .and_then(|twist| {
                    let mut params = planned.rod(&params);
                    if planned.swivel.is_some() {
                        params.holds = params.holds.turning();
                    }
                    let (start, end) =
                        clamp_loads(&params, &guides[j], Some(&guides[j + 1]), &nodes, twist);
                    Some((start, end?))
                });
            measures.push(SegmentMeasure {
                pitch_m: pitch,
                slid: state.slid,
                twist_rad: state.twist_rad,
                loads,
                segment,
                clearance: self.clearance.segment(links, j, &nodes).map_err(|source| {
                    MotionTestError::Clearance {
                        segment: self.setup.segment_name(segment),
                        time_s,
                        source,
                    }
                })?,
                stretch: stretch(&nodes, natural),
                bend,
                curvatures_per_m: curvatures,
                curvature_vectors_per_m: bending,
                contact: state.contact,
                max_joint_gap_m: state.max_joint_gap_m,
                nodes,
            });
        }
        Ok(measures)
    }

    /// The failure of a diverging simulation at `time_s`, naming the setup's segment.
    fn diverged(&self, simulated: Option<usize>, detail: &str, time_s: f64) -> Failure {
        let segment = simulated.and_then(|j| self.plan.segments.get(j).map(|s| s.setup_index));
        let place = segment.map_or(String::new(), |m| {
            format!("segment {}: ", self.setup.segment_name(m))
        });
        Failure {
            cause: FailureCause::Diverged,
            reason: format!("simulation diverged at t = {time_s:.4} s ({place}{detail})"),
            segment,
        }
    }
}

fn ended(failure: Option<Failure>, steps: usize) -> Ended {
    Ended { failure, steps }
}
