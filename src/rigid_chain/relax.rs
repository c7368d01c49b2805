//! Static relaxation of a segment, and the paper's *previous method* for the connected
//! geometry (a straight cable dragged into place).

use nalgebra::{Point3, Rotation3, UnitQuaternion, Vector3};

use super::build::{SegmentShape, SubSegmentModel, checked_pose};
use super::error::{RigidChainError, invalid};
use super::settings::{ConvergenceWindow, DynamicsSettings};
use super::world::CableWorld;
use crate::cable::CableSpec;
use crate::geometry::connected::MAX_SUB_SEGMENTS;
use crate::pose::Pose;

/// A segment at rest (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Relaxation {
    /// `S + 1` nodes from the start guide origin to the end guide origin (m).
    pub nodes: Vec<Point3<f64>>,
    /// `S + 1` node frames (see [`CableWorld::segment_frames`]).
    pub frames: Vec<Rotation3<f64>>,
    /// The `S` sub-segment bodies' poses (see [`CableWorld::sub_segment_poses`]).
    pub sub_segments: Vec<Pose>,
    /// Steps simulated (all phases).
    pub steps: usize,
    /// Simulated time (s).
    pub simulated_time_s: f64,
    /// Largest node displacement within the last convergence window (m).
    pub final_window_motion_m: f64,
}

/// How a [`settle`] ended: at rest after this many steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settled {
    /// Steps the world has taken in total (not only while settling).
    pub steps: usize,
    /// Simulated time of the world (s).
    pub simulated_time_s: f64,
    /// Largest node displacement within the last convergence window (m), over all segments.
    pub final_window_motion_m: f64,
}

/// Relaxes one segment from `shape` to static equilibrium, both ends clamped, until the
/// convergence `window` says it is at rest.
///
/// Errors: invalid input ([`CableWorld::new`]), [`RigidChainError::BlowUp`], or
/// [`RigidChainError::NotConverged`] when the time budget runs out.
pub fn relax(
    cable: &CableSpec,
    shape: &SegmentShape,
    settings: &DynamicsSettings,
    window: &ConvergenceWindow,
) -> Result<Relaxation, RigidChainError> {
    let mut world = CableWorld::new(cable, std::slice::from_ref(shape), settings)?;
    let settled = settle(&mut world, window)?;
    Ok(relaxation_of(&world, &settled))
}

/// Steps `world` — guides and robot held at their last targets — until no node of any
/// segment moves more than `window.max_motion_m` within a window of `window.window_s`.
///
/// Errors: [`RigidChainError::BlowUp`], or [`RigidChainError::NotConverged`] when
/// `window.max_time_s` of simulated time pass without a quiet window.
pub fn settle(
    world: &mut CableWorld,
    window: &ConvergenceWindow,
) -> Result<Settled, RigidChainError> {
    window.validate()?;
    let dt = world.settings().time_step_s;
    let window_steps = steps_for(window.window_s, dt);
    let budget = world
        .steps()
        .saturating_add(steps_for(window.max_time_s, dt));
    let mut motion = f64::INFINITY;
    while world.steps() < budget {
        let reference = all_nodes(world);
        motion = 0.0;
        for _ in 0..window_steps {
            world.step()?;
            motion = motion.max(largest_displacement(&reference, &all_nodes(world)));
        }
        if motion <= window.max_motion_m {
            return Ok(Settled {
                steps: world.steps(),
                simulated_time_s: world.time_s(),
                final_window_motion_m: motion,
            });
        }
    }
    Err(RigidChainError::NotConverged {
        steps: world.steps(),
        time_s: world.time_s(),
        window_motion_m: motion,
        threshold_m: window.max_motion_m,
    })
}

/// The nodes of every segment, one after the other.
fn all_nodes(world: &CableWorld) -> Vec<Point3<f64>> {
    (0..world.segment_count())
        .flat_map(|m| world.segment_nodes(m).unwrap_or_default())
        .collect()
}

/// Segment 0 of a settled world.
fn relaxation_of(world: &CableWorld, settled: &Settled) -> Relaxation {
    Relaxation {
        nodes: world.segment_nodes(0).unwrap_or_default(),
        frames: world.segment_frames(0).unwrap_or_default(),
        sub_segments: world.sub_segment_poses(0).unwrap_or_default(),
        steps: settled.steps,
        simulated_time_s: settled.simulated_time_s,
        final_window_motion_m: settled.final_window_motion_m,
    }
}

/// How the straight cable of [`connect_linear`] is dragged into place.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearConnect {
    /// Time over which the far end is moved from the straight cable's end to the end guide
    /// (s, simulated); the motion follows a smoothstep profile (zero speed at both ends).
    pub move_time_s: f64,
    /// When the cable counts as settled afterwards.
    pub settle: ConvergenceWindow,
}

impl Default for LinearConnect {
    /// One second of motion (the paper's figure shows 100 steps, about 1.7 s at PhysX's
    /// default 60 Hz), then the default convergence window.
    fn default() -> Self {
        Self {
            move_time_s: 1.0,
            settle: ConvergenceWindow::default(),
        }
    }
}

/// The connected geometry by the paper's *previous method* (its Fig. 1): a straight cable of
/// `sub_segments` sub-segments is clamped at `start`, lying along the start guide's +z; its
/// far end, held by a kinematic guide, is moved — position linearly, orientation along the
/// shortest rotation, both with a smoothstep time profile — into the `end` guide's pose over
/// `plan.move_time_s`, and the cable is then let settle.
///
/// Errors: invalid input (also guides farther apart than the cable's natural length),
/// [`RigidChainError::BlowUp`] and [`RigidChainError::NotConverged`].
pub fn connect_linear(
    cable: &CableSpec,
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    settings: &DynamicsSettings,
    plan: &LinearConnect,
) -> Result<Relaxation, RigidChainError> {
    let (start, end) = check_linear_input(cable, start, end, sub_segments, plan)?;
    let straight = StraightCable::new(&start, sub_segments, cable.sub_segment_pitch_m);
    let mut world = CableWorld::new(cable, &[straight.shape(&start)], settings)?;
    let move_steps = steps_for(plan.move_time_s, settings.time_step_s);
    for i in 1..=move_steps {
        let progress = smoothstep(i as f64 / move_steps as f64);
        world.move_guides(&[start, interpolate(&straight.end, &end, progress)])?;
        world.step()?;
    }
    world.move_guides(&[start, end])?;
    let settled = settle(&mut world, &plan.settle)?;
    Ok(relaxation_of(&world, &settled))
}

/// The checked guide poses of [`connect_linear`].
fn check_linear_input(
    cable: &CableSpec,
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    plan: &LinearConnect,
) -> Result<(Pose, Pose), RigidChainError> {
    plan.settle.validate()?;
    if !(plan.move_time_s.is_finite() && plan.move_time_s >= 0.0) {
        return Err(invalid(format!(
            "move time {} s must be finite and ≥ 0",
            plan.move_time_s
        )));
    }
    if !(1..=MAX_SUB_SEGMENTS).contains(&sub_segments) {
        return Err(invalid(format!(
            "{sub_segments} sub-segments: need between 1 and {MAX_SUB_SEGMENTS}"
        )));
    }
    let (start, end) = (
        checked_pose(start, "start guide")?,
        checked_pose(end, "end guide")?,
    );
    let natural = sub_segments as f64 * SubSegmentModel::new(cable)?.pitch_m;
    let distance = (end.translation.vector - start.translation.vector).norm();
    if distance > natural * (1.0 + 1e-9) {
        return Err(invalid(format!(
            "the guides are {:.1} mm apart but the cable is only {:.1} mm long",
            distance * 1e3,
            natural * 1e3
        )));
    }
    Ok((start, end))
}

/// The straight cable the previous method starts from, along the start guide's +z.
struct StraightCable {
    nodes: Vec<Point3<f64>>,
    frames: Vec<Rotation3<f64>>,
    /// The pose of its far end: at the last node, oriented like the start guide.
    end: Pose,
}

impl StraightCable {
    fn new(start: &Pose, sub_segments: usize, pitch: f64) -> Self {
        let axis = start.rotation * Vector3::z();
        let at = |length: f64| start.translation.vector + axis * length;
        let nodes: Vec<Point3<f64>> = (0..=sub_segments)
            .map(|k| Point3::from(at(k as f64 * pitch)))
            .collect();
        Self {
            frames: vec![start.rotation.to_rotation_matrix(); nodes.len()],
            end: Pose::from_parts(at(sub_segments as f64 * pitch).into(), start.rotation),
            nodes,
        }
    }

    fn shape(&self, start: &Pose) -> SegmentShape<'_> {
        SegmentShape {
            start_guide: *start,
            end_guide: self.end,
            nodes: &self.nodes,
            frames: &self.frames,
        }
    }
}

/// Whole steps covering `time_s` (at least 1).
fn steps_for(time_s: f64, dt: f64) -> usize {
    let steps = (time_s / dt).ceil();
    if steps.is_finite() && steps >= 1.0 {
        steps.min(usize::MAX as f64) as usize
    } else {
        1
    }
}

/// `3t² − 2t³`: from 0 to 1 with zero slope at both ends.
fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The pose a fraction `t` of the way from `a` to `b`: translation linear, rotation along
/// the shortest arc (`exp(t·log(b·a⁻¹))·a`, defined even for half turns).
pub fn interpolate(a: &Pose, b: &Pose, t: f64) -> Pose {
    let translation = a.translation.vector.lerp(&b.translation.vector, t);
    let delta = b.rotation * a.rotation.inverse();
    let rotation = UnitQuaternion::from_scaled_axis(delta.scaled_axis() * t) * a.rotation;
    Pose::from_parts(translation.into(), rotation)
}

/// Largest distance between corresponding nodes (m); infinite if the counts differ.
fn largest_displacement(a: &[Point3<f64>], b: &[Point3<f64>]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;

    #[test]
    fn interpolation_ends_at_both_poses_and_handles_a_half_turn() {
        let a = pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]);
        let b = pose_from_xyz_rpy([0.2, 0.0, -0.1], [std::f64::consts::PI, 0.0, 0.0]);
        assert!(interpolate(&a, &b, 0.0).rotation.angle_to(&a.rotation) < 1e-12);
        let end = interpolate(&a, &b, 1.0);
        assert!(end.rotation.angle_to(&b.rotation) < 1e-12);
        assert!((end.translation.vector - b.translation.vector).norm() < 1e-15);
        let half = interpolate(&a, &b, 0.5);
        assert!((half.rotation.angle_to(&a.rotation) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn smoothstep_and_step_counts() {
        assert_eq!(smoothstep(0.0), 0.0);
        assert_eq!(smoothstep(1.0), 1.0);
        assert!((smoothstep(0.5) - 0.5).abs() < 1e-15);
        assert_eq!(steps_for(1.0, 0.25), 4);
        assert_eq!(steps_for(0.0, 0.25), 1);
        assert_eq!(steps_for(f64::NAN, 0.25), 1);
    }
}
