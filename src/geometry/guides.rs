//! The input of [`super::connect`], validated: the two guide frames, the cable's sub-segment
//! count and pitch, and the sag direction.

use nalgebra::{Point3, Rotation3, Unit, UnitQuaternion, Vector3};

use super::error::{ConnectError, MAX_SUB_SEGMENTS};
use crate::pose::Pose;

/// Positions, tangents (+z) and reference normals (+x) of the two guides.
pub(crate) struct GuidePair {
    pub(crate) start_point: Point3<f64>,
    pub(crate) end_point: Point3<f64>,
    pub(crate) start_tangent: Unit<Vector3<f64>>,
    pub(crate) end_tangent: Unit<Vector3<f64>>,
    pub(crate) start_normal: Unit<Vector3<f64>>,
    pub(crate) end_normal: Unit<Vector3<f64>>,
}

impl GuidePair {
    /// The guide frames of a connect call; rejects non-finite poses and zero quaternions.
    pub(crate) fn from_poses(start: &Pose, end: &Pose) -> Result<Self, ConnectError> {
        let (start_point, start_rotation) = guide_parts(start, "start")?;
        let (end_point, end_rotation) = guide_parts(end, "end")?;
        Ok(Self {
            start_point,
            end_point,
            start_tangent: Unit::new_unchecked(start_rotation * Vector3::z()),
            end_tangent: Unit::new_unchecked(end_rotation * Vector3::z()),
            start_normal: Unit::new_unchecked(start_rotation * Vector3::x()),
            end_normal: Unit::new_unchecked(end_rotation * Vector3::x()),
        })
    }
}

/// The origin and (re-normalized) rotation of a guide pose, rejecting non-finite values.
fn guide_parts(pose: &Pose, which: &str) -> Result<(Point3<f64>, Rotation3<f64>), ConnectError> {
    let point = Point3::from(pose.translation.vector);
    let quaternion = pose.rotation.into_inner();
    let finite = point
        .iter()
        .chain(quaternion.coords.iter())
        .all(|v| v.is_finite());
    let norm = quaternion.norm();
    if !finite || norm.is_nan() || norm <= 1e-6 {
        return Err(ConnectError::InvalidInput {
            what: format!("{which} guide pose is not a finite rigid transform"),
        });
    }
    let rotation = UnitQuaternion::new_unchecked(quaternion / norm).to_rotation_matrix();
    Ok((point, rotation))
}

/// The sag direction, re-normalized; rejects zero and non-finite vectors.
pub(crate) fn check_sag(sag: &Unit<Vector3<f64>>) -> Result<Unit<Vector3<f64>>, ConnectError> {
    let finite = sag.iter().all(|v| v.is_finite());
    match Unit::try_new(sag.into_inner(), 1e-6) {
        Some(unit) if finite => Ok(unit),
        _ => Err(ConnectError::InvalidInput {
            what: "sag direction must be a finite, non-zero vector".into(),
        }),
    }
}

/// Rejects a cable of no sub-segments, too many, or a pitch that is not finite and positive.
pub(crate) fn check_cable(sub_segments: usize, pitch_m: f64) -> Result<(), ConnectError> {
    let invalid = |what: String| Err(ConnectError::InvalidInput { what });
    if sub_segments == 0 {
        return invalid("a segment needs at least one sub-segment".into());
    }
    if sub_segments > MAX_SUB_SEGMENTS {
        return invalid(format!(
            "{sub_segments} sub-segments exceed the limit {MAX_SUB_SEGMENTS}"
        ));
    }
    if !(pitch_m.is_finite() && pitch_m > 0.0) {
        return invalid(format!(
            "sub-segment pitch {pitch_m} m must be finite and > 0"
        ));
    }
    if !(sub_segments as f64 * pitch_m).is_finite() {
        return invalid("natural cable length is not finite".into());
    }
    Ok(())
}
