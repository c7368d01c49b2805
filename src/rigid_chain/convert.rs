//! Conversions between the crate's nalgebra `f64` types and rapier's glam `f32` types.
//!
//! rapier3d (default `f32` build) exposes `glam` vectors and quaternions through
//! `rapier3d::math`; everything outside this module speaks nalgebra `f64`.

use nalgebra::{Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use rapier3d::math::{Pose as RapierPose, Rotation as RapierRotation, Vector as RapierVector};

use crate::pose::Pose;

/// A vector in rapier's single precision.
pub(super) fn to_rapier_vector(v: &Vector3<f64>) -> RapierVector {
    RapierVector::new(v.x as f32, v.y as f32, v.z as f32)
}

/// A point in rapier's single precision.
pub(super) fn to_rapier_point(p: &Point3<f64>) -> RapierVector {
    to_rapier_vector(&p.coords)
}

/// A rotation in rapier's single precision, renormalised after rounding.
pub(super) fn to_rapier_rotation(q: &UnitQuaternion<f64>) -> RapierRotation {
    let c = q.quaternion().coords; // (i, j, k, w)
    RapierRotation::from_xyzw(c.x as f32, c.y as f32, c.z as f32, c.w as f32).normalize()
}

/// A pose in rapier's single precision.
pub(super) fn to_rapier_pose(pose: &Pose) -> RapierPose {
    RapierPose::from_parts(
        to_rapier_vector(&pose.translation.vector),
        to_rapier_rotation(&pose.rotation),
    )
}

/// A rapier vector as an nalgebra vector.
pub(super) fn from_rapier_vector(v: RapierVector) -> Vector3<f64> {
    Vector3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// A rapier rotation as an nalgebra unit quaternion (renormalised in double precision).
pub(super) fn from_rapier_rotation(q: RapierRotation) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(
        f64::from(q.w),
        f64::from(q.x),
        f64::from(q.y),
        f64::from(q.z),
    ))
}

/// A rapier pose as a crate pose.
pub(super) fn from_rapier_pose(pose: &RapierPose) -> Pose {
    Pose::from_parts(
        Translation3::from(from_rapier_vector(pose.translation)),
        from_rapier_rotation(pose.rotation),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;

    #[test]
    fn poses_survive_the_round_trip_to_single_precision() {
        let pose = pose_from_xyz_rpy([0.3, -0.2, 0.81], [0.4, -1.2, 2.9]);
        let back = from_rapier_pose(&to_rapier_pose(&pose));
        assert!((back.translation.vector - pose.translation.vector).norm() < 1e-7);
        assert!(back.rotation.angle_to(&pose.rotation) < 1e-6);
        let v = Vector3::new(0.1, 0.2, -0.3);
        let rotated =
            from_rapier_vector(to_rapier_pose(&pose).transform_vector(to_rapier_vector(&v)));
        assert!((rotated - pose.rotation * v).norm() < 1e-6);
    }
}
