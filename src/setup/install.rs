//! The cable as installed: each piece laid untwisted along its route at a stated robot pose.
//!
//! A clamp holds the cable's cross-section, so what twists a piece is the turn of its end
//! clamp about the cable axis relative to its start clamp. With `install_joints_deg` in the
//! setup, nobody writes that reference by hand: at the installation pose each piece is laid
//! along its connected geometry (the least-bent smooth route of its length, the shape the
//! statics start from) with its start clamp's cross-section carried along the route without
//! spin (a rotation-minimizing frame), and the end clamp takes whatever turn the cable arrives
//! with. Numerically: the connected geometry's twist mismatch Δψ at the end clamp is removed
//! by turning that clamp's frame by −Δψ about the cable axis. A piece whose cable cannot reach
//! between its clamps at the installation pose is laid along the clamps' Hermite curve at the
//! guide distance instead (it is never installed there, but its twist reference stays
//! defined). Without `install_joints_deg`, the configurations' declared +x axes are the twist
//! references, as written.

use super::Setup;
use crate::geometry::frames::twist_mismatch;
use crate::geometry::{HermiteCurve, connect, double_reflection, sag_direction};
use crate::pose::Pose;
use nalgebra::{Isometry3, Point3, Translation3, Unit, UnitQuaternion, Vector3};

/// Points the Hermite fallback route is sampled at.
const FALLBACK_SAMPLES: usize = 64;

/// The robot pose at which the cable is installed.
#[derive(Debug, Clone, PartialEq)]
pub struct Installation {
    /// The joint vector (rad / m).
    pub joints: Vec<f64>,
    /// The world pose of every link at `joints`.
    pub link_poses: Vec<Pose>,
}

impl Setup {
    /// The pose a setup is shown and sampled at before any motion: the installation pose
    /// (rad / m), or every joint at 0 when the setup states none.
    pub fn reference_joints(&self) -> Vec<f64> {
        match &self.installation {
            Some(installation) => installation.joints.clone(),
            None => vec![0.0; self.robot.dof()],
        }
    }

    /// World poses of segment `m`'s start and end clamps for the configurations `(start, end)`
    /// of its guides and a cable of `sub_segments`, with the links at `link_poses`: the end
    /// clamp turned about the cable axis by the twist reference of the installed cable (see
    /// the module documentation). Use these, not the bare configuration poses, wherever a
    /// piece of cable is solved.
    pub fn clamp_poses(
        &self,
        link_poses: &[Pose],
        m: usize,
        sub_segments: usize,
        (start, end): (usize, usize),
    ) -> (Pose, Pose) {
        let (a, b) = self.segment_guides(m);
        (
            self.guide_world_pose(link_poses, a, start),
            self.guide_world_pose(link_poses, b, end)
                * self.end_clamp_turn(m, sub_segments, (start, end)),
        )
    }

    /// The turn about the cable axis that [`Setup::clamp_poses`] applies to the end clamp's
    /// declared pose (right-multiplied): by −Δψ of [`Setup::installed_twist_rad`]. It does not
    /// depend on the robot's pose, so loops over poses compute it once.
    pub fn end_clamp_turn(&self, m: usize, sub_segments: usize, pair: (usize, usize)) -> Pose {
        turn_about_axis(-self.installed_twist_rad(m, sub_segments, pair))
    }

    /// The angle Δψ (rad, principal branch) between the end clamp's declared +x axis and the
    /// cross-section of a cable of `sub_segments` laid untwisted from the start clamp along
    /// its route at the installation pose, about the cable axis at the end clamp. 0 without an
    /// installation pose or for `sub_segments = 0`.
    pub fn installed_twist_rad(
        &self,
        m: usize,
        sub_segments: usize,
        (start, end): (usize, usize),
    ) -> f64 {
        let Some(installation) = &self.installation else {
            return 0.0;
        };
        if sub_segments == 0 {
            return 0.0;
        }
        let (a, b) = self.segment_guides(m);
        let start_pose = self.guide_world_pose(&installation.link_poses, a, start);
        let end_pose = self.guide_world_pose(&installation.link_poses, b, end);
        let sag = sag_direction(&self.gravity_m_s2);
        let pitch = self.cable.sub_segment_pitch_m;
        match connect(&start_pose, &end_pose, sub_segments, pitch, &sag) {
            Ok(route) => route.twist_correction_rad,
            Err(_) => hermite_twist(&start_pose, &end_pose),
        }
    }
}

/// A pose turning a frame by `angle_rad` about its own z axis.
pub fn turn_about_axis(angle_rad: f64) -> Pose {
    Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle_rad),
    )
}

/// The twist mismatch along the Hermite curve between the clamps with tangent scale equal to
/// their distance, by the rotation-minimizing frame (principal branch).
fn hermite_twist(start: &Pose, end: &Pose) -> f64 {
    let point = |p: &Pose| Point3::from(p.translation.vector);
    let axis = |p: &Pose| Unit::new_normalize(p.rotation * Vector3::z());
    let distance = (end.translation.vector - start.translation.vector).norm();
    let curve = HermiteCurve::new(point(start), axis(start), point(end), axis(end), distance);
    let parameters = (0..=FALLBACK_SAMPLES).map(|k| k as f64 / FALLBACK_SAMPLES as f64);
    let (points, tangents): (Vec<_>, Vec<_>) = parameters
        .map(|t| {
            let tangent = curve.unit_tangent(t).unwrap_or_else(|| axis(start));
            (curve.point(t), tangent)
        })
        .unzip();
    let start_normal = Unit::new_normalize(start.rotation * Vector3::x());
    let frames = double_reflection(&points, &tangents, start_normal);
    frames.last().map_or(0.0, |last| {
        twist_mismatch(last, &Unit::new_normalize(end.rotation * Vector3::x()))
    })
}
