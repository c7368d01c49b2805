//! The paper's previous way to shape a piece, kept as the baseline the Hermite start is
//! measured against: a straight cable dragged into the end clamp and relaxed in rapier3d.

use super::evaluate::Evaluator;
use super::verdict::{Check, Rejection};
use crate::pose::Pose;
use nalgebra::{Point3, Vector3};

impl Evaluator<'_> {
    /// The piece relaxed from a straight cable; without the `rigid-chain` feature, refused.
    #[cfg(not(feature = "rigid-chain"))]
    pub(super) fn relaxed(
        &self,
        _start: &Pose,
        _end: &Pose,
        _sub_segments: usize,
        _gravity_m_s2: Vector3<f64>,
    ) -> Result<Vec<Point3<f64>>, Check> {
        Err(Check::fail(
            Rejection::Diverged,
            "the linear method relaxes in rapier3d: build with the rigid-chain feature".into(),
            None,
        ))
    }

    /// The piece dragged straight into the end clamp and relaxed in rapier3d.
    #[cfg(feature = "rigid-chain")]
    pub(super) fn relaxed(
        &self,
        start: &Pose,
        end: &Pose,
        sub_segments: usize,
        gravity_m_s2: Vector3<f64>,
    ) -> Result<Vec<Point3<f64>>, Check> {
        use crate::rigid_chain::{
            ConvergenceWindow, DynamicsSettings, LinearConnect, SegmentShape, connect_linear, relax,
        };
        let cable = &self.setup.cable;
        let settings = DynamicsSettings::relaxation(gravity_m_s2);
        if let Some(check) = too_short(start, end, sub_segments, cable.sub_segment_pitch_m) {
            return Err(check);
        }
        let diverged = |e: crate::rigid_chain::RigidChainError| {
            Check::fail(Rejection::Diverged, e.to_string(), None)
        };
        let linear = connect_linear(
            cable,
            start,
            end,
            sub_segments,
            &settings,
            &LinearConnect::default(),
        )
        .map_err(diverged)?;
        let shape = SegmentShape {
            start_guide: *start,
            end_guide: *end,
            nodes: &linear.nodes,
            frames: &linear.frames,
        };
        let relaxed =
            relax(cable, &shape, &settings, &ConvergenceWindow::default()).map_err(diverged)?;
        Ok(relaxed.nodes)
    }
}

/// The too-short check of [`connect`](crate::geometry::connect) for the linear method, which
/// has no such test.
#[cfg(feature = "rigid-chain")]
fn too_short(start: &Pose, end: &Pose, sub_segments: usize, pitch: f64) -> Option<Check> {
    let distance = (end.translation.vector - start.translation.vector).norm();
    let natural = sub_segments as f64 * pitch;
    (distance >= natural).then(|| {
        super::verdict::connect_failure(crate::geometry::ConnectError::TooShort {
            distance_m: distance,
            natural_length_m: natural,
            required_stretch: distance / natural,
        })
    })
}
