//! The stepping loop: the robot and the guides follow the motion, the cable follows the
//! guides, every step is measured.

use super::clearance::ClearanceQuery;
use super::initial::equilibria;
use super::plan::Plan;
use super::report::{Failure, FailureCause};
use super::tracker::{ForceAt, SegmentMeasure, Tracker};
use super::{MotionTestError, MotionTestOptions};
use crate::rigid_chain::{CableWorld, ContactSummary, DynamicsError, SegmentShape, StepRecord};
use crate::motion::Motion;
use crate::pose::Pose;
use crate::progress;
use crate::setup::Setup;
use crate::statics::Equilibrium;
use crate::stress::{ClampZone, GuideEnd, min_bend_radius, stretch, zone_sub_segments};
use nalgebra::{Point3, Vector3};

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
    /// Per simulated segment, the clamp zones: checked by neither the clearance nor the
    /// simulation's contacts.
    pub clamp_zones: Vec<Vec<ClampZone>>,
}

/// How a simulation ended: a failure of the candidate (not a limit violation, which the
/// tracker holds), and the number of steps taken.
pub(super) struct Ended {
    pub failure: Option<Failure>,
    pub steps: usize,
}

impl Context<'_> {
    /// Builds the initial shape, then steps through the motion and the settle tail.
    pub fn simulate(&self, tracker: &mut Tracker) -> Result<Ended, MotionTestError> {
        let t0 = self.motion.times_s()[0];
        let links = self.link_poses(t0)?;
        let guides = self.plan.guide_poses(self.setup, &links);
        let shapes = match equilibria(self.setup, &self.plan, &guides, t0, tracker)? {
            Ok(shapes) => shapes,
            Err(failure) => return Ok(ended(Some(failure), 0)),
        };
        tracker.record(t0, &self.measure_initial(&links, &guides, &shapes, t0)?);
        if self.options.stop_at_first_violation && tracker.violated() {
            return Ok(ended(None, 0));
        }
        let mut world = match self.world(&guides, &shapes) {
            Ok(world) => world,
            Err(failure) => return Ok(ended(Some(failure), 0)),
        };
        world
            .add_robot(&self.setup.robot, &links)
            .map_err(MotionTestError::Dynamics)?;
        self.step_through(&mut world, tracker)
    }

    /// Steps `world` to the motion's end plus the settle tail.
    fn step_through(
        &self,
        world: &mut CableWorld,
        tracker: &mut Tracker,
    ) -> Result<Ended, MotionTestError> {
        let t0 = self.motion.times_s()[0];
        let dt = self.options.settings.time_step_s;
        let total = self.step_count();
        progress::begin("motion test", total as u64);
        let ended = self.steps(world, tracker, t0, dt, total);
        progress::end();
        ended
    }

    /// Steps 1 … `total` of [`Self::step_through`], reporting each to [`progress`].
    fn steps(
        &self,
        world: &mut CableWorld,
        tracker: &mut Tracker,
        t0: f64,
        dt: f64,
        total: usize,
    ) -> Result<Ended, MotionTestError> {
        for k in 1..=total {
            progress::advance(1);
            let t = t0 + k as f64 * dt;
            let links = self.link_poses(t)?;
            world
                .move_guides(&self.plan.guide_poses(self.setup, &links))
                .and_then(|()| world.move_robot(&links))
                .map_err(MotionTestError::Dynamics)?;
            let record = match world.step() {
                Ok(record) => record,
                Err(e @ DynamicsError::BlowUp { .. }) => {
                    return Ok(ended(Some(self.diverged(&e, t)), k));
                }
                Err(e) => return Err(MotionTestError::Dynamics(e)),
            };
            tracker.record(t, &self.measure_step(world, &links, &record, t)?);
            if self.options.stop_at_first_violation && tracker.violated() {
                return Ok(ended(None, k));
            }
        }
        Ok(ended(None, total))
    }

    /// Steps for the motion (its last step reaches or passes the last sample) plus the tail.
    pub fn step_count(&self) -> usize {
        let dt = self.options.settings.time_step_s;
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

    /// The simulation, from the equilibria; a shape it refuses is a failed candidate.
    fn world(&self, guides: &[Pose], shapes: &[Equilibrium]) -> Result<CableWorld, Failure> {
        let segment_shapes: Vec<SegmentShape> = shapes
            .iter()
            .enumerate()
            .map(|(j, eq)| SegmentShape {
                start_guide: guides[j],
                end_guide: guides[j + 1],
                nodes: &eq.nodes,
                frames: &eq.frames,
            })
            .collect();
        let refused = |e: DynamicsError| Failure {
            cause: FailureCause::NoInitialShape,
            reason: format!("the simulation refused the initial shape: {e}"),
            segment: None,
        };
        let mut world = CableWorld::new(&self.setup.cable, &segment_shapes, &self.options.settings)
            .map_err(refused)?;
        for (j, (zones, eq)) in self.clamp_zones.iter().zip(shapes).enumerate() {
            let sub_segments = eq.nodes.len() - 1;
            for zone in zones {
                let n = zone_sub_segments(&eq.nodes, zone.end, zone.length_m);
                let range = match zone.end {
                    GuideEnd::Start => 0..n,
                    GuideEnd::End => sub_segments - n..sub_segments,
                };
                world
                    .ignore_contacts(j, range, zone.link)
                    .map_err(refused)?;
            }
        }
        Ok(world)
    }

    /// The metrics of the equilibria (no contact force: nothing is simulated yet).
    fn measure_initial(
        &self,
        links: &[Pose],
        guides: &[Pose],
        shapes: &[Equilibrium],
        time_s: f64,
    ) -> Result<Vec<SegmentMeasure>, MotionTestError> {
        let pitch = self.setup.cable.sub_segment_pitch_m;
        let axis = |pose: &Pose| pose.rotation * Vector3::z();
        let mut measures = Vec::with_capacity(shapes.len());
        for (j, (planned, eq)) in self.plan.segments.iter().zip(shapes).enumerate() {
            let segment = planned.setup_index;
            let natural = planned.sub_segments as f64 * pitch;
            measures.push(SegmentMeasure {
                segment,
                clearance: self
                    .clearance
                    .segment(links, j, &eq.nodes, (segment, time_s))?,
                stretch: stretch(&eq.nodes, natural),
                bend: min_bend_radius(&eq.nodes, &axis(&guides[j]), &axis(&guides[j + 1]), pitch),
                contact: None,
                max_joint_gap_m: 0.0,
                nodes: eq.nodes.clone(),
            });
        }
        Ok(measures)
    }

    /// The metrics of the simulated cable after a step.
    fn measure_step(
        &self,
        world: &CableWorld,
        links: &[Pose],
        record: &StepRecord,
        time_s: f64,
    ) -> Result<Vec<SegmentMeasure>, MotionTestError> {
        let zone_m = self.setup.thresholds.clamp_zone_m;
        let mut measures = Vec::with_capacity(record.segments.len());
        for (j, (planned, rec)) in self.plan.segments.iter().zip(&record.segments).enumerate() {
            let segment = planned.setup_index;
            let nodes = world.segment_nodes(j).unwrap_or_default();
            measures.push(SegmentMeasure {
                segment,
                clearance: self
                    .clearance
                    .segment(links, j, &nodes, (segment, time_s))?,
                stretch: rec.stretch,
                bend: rec.min_bend,
                contact: force_outside_zones(&rec.contact, &nodes, zone_m),
                max_joint_gap_m: rec.max_joint_gap_m,
                nodes,
            });
        }
        Ok(measures)
    }

    /// The failure of a blow-up at `time_s`, naming the setup's segment.
    fn diverged(&self, error: &DynamicsError, time_s: f64) -> Failure {
        let (detail, segment) = match error {
            DynamicsError::BlowUp {
                segment,
                sub_segment,
                quantity,
                value,
                bound,
                ..
            } => {
                let setup_segment = self
                    .plan
                    .segments
                    .get(*segment)
                    .map_or(*segment, |s| s.setup_index);
                let place = sub_segment.map_or(String::new(), |s| format!(", sub-segment {s}"));
                let detail = format!(
                    "segment C{}{place}: {quantity} = {value:.4e} exceeds the sanity bound {bound:.4e}",
                    setup_segment + 1
                );
                (detail, Some(setup_segment))
            }
            other => (other.to_string(), None),
        };
        Failure {
            cause: FailureCause::Diverged,
            reason: format!("simulation diverged at t = {time_s:.4} s ({detail})"),
            segment,
        }
    }
}

/// The sub-segment with the largest contact force among those outside `zone_m` of cable
/// (arc length along `nodes`) from either guide; `None` without any force there. Inside a
/// zone the cable legitimately touches its guide's link, and the summary does not say which
/// link a force comes from (only for the most loaded sub-segment), so zones are left out
/// whole; the clearance still checks them against the other links.
fn force_outside_zones(
    contact: &ContactSummary,
    nodes: &[Point3<f64>],
    zone_m: f64,
) -> Option<ForceAt> {
    let forces = &contact.per_sub_segment_n;
    let (first, last) = (
        zone_sub_segments(nodes, GuideEnd::Start, zone_m),
        forces
            .len()
            .saturating_sub(zone_sub_segments(nodes, GuideEnd::End, zone_m)),
    );
    let (sub_segment, force_n) = (first..last)
        .filter_map(|k| forces.get(k).map(|&f| (k, f)))
        .filter(|&(_, f)| f > 0.0)
        .fold(None, |best: Option<(usize, f64)>, (k, f)| match best {
            Some((_, largest)) if largest >= f => best,
            _ => Some((k, f)),
        })?;
    let link = contact
        .max
        .filter(|m| m.sub_segment == sub_segment)
        .map(|m| m.link);
    Some(ForceAt {
        sub_segment,
        force_n,
        link,
    })
}

fn ended(failure: Option<Failure>, steps: usize) -> Ended {
    Ended { failure, steps }
}
