//! Node frames of a connected geometry: rotation-minimizing frames along the nodes from the
//! start guide's frame, then a linear twist about the tangents so that the last frame is the
//! end guide's frame.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};

use super::hermite::HermiteCurve;
use super::rmf::{frame, rotation_minimizing_normals};

/// Frames (columns: normal, binormal, tangent) at the `nodes`, which sit at the curve
/// parameters `params`, and the twist `Δψ` (rad) spread over them.
///
/// The tangents are the exact curve tangents at the nodes' parameters (the guide axes at the
/// ends); the double-reflection RMF carries `start_normal` along; the twist mismatch to
/// `end_normal` is measured with `atan2` on the principal branch `(−π, π]`, and frame `k` is
/// turned about its tangent by `Δψ·k/S`.
pub(crate) fn guided_frames(
    curve: &HermiteCurve,
    params: &[f64],
    nodes: &[Point3<f64>],
    start_normal: Unit<Vector3<f64>>,
    end_normal: &Unit<Vector3<f64>>,
) -> (Vec<Rotation3<f64>>, f64) {
    let tangents = node_tangents(curve, params, nodes);
    let normals = rotation_minimizing_normals(nodes, &tangents, start_normal);
    let twist = normals
        .last()
        .zip(tangents.last())
        .map_or(0.0, |(normal, tangent)| {
            twist_mismatch(&frame(normal, tangent), end_normal)
        });
    (twisted_frames(&normals, &tangents, twist), twist)
}

/// Unit tangents at the nodes: the guide axes at both ends, `p'/|p'|` inside; at a cusp
/// (`p' = 0`) the direction of the neighbouring chord pair instead.
fn node_tangents(
    curve: &HermiteCurve,
    params: &[f64],
    nodes: &[Point3<f64>],
) -> Vec<Unit<Vector3<f64>>> {
    let last = params.len() - 1;
    let mut tangents = Vec::with_capacity(params.len());
    for (k, &t) in params.iter().enumerate() {
        let tangent = match k {
            0 => Some(curve.start_tangent()),
            _ if k == last => Some(curve.end_tangent()),
            _ => curve
                .unit_tangent(t)
                .or_else(|| Unit::try_new(nodes[k + 1] - nodes[k - 1], f64::MIN_POSITIVE)),
        };
        let fallback = tangents.last().copied().unwrap_or(curve.start_tangent());
        tangents.push(tangent.unwrap_or(fallback));
    }
    tangents
}

/// Angle (rad) about the frame's tangent that turns its normal onto `target_normal`, on the
/// principal branch `(−π, π]`: an exact half turn is reported as `+π`, never `−π`.
pub(crate) fn twist_mismatch(frame: &Rotation3<f64>, target_normal: &Unit<Vector3<f64>>) -> f64 {
    let m = frame.matrix();
    let (normal, binormal) = (m.column(0), m.column(1));
    principal_angle(target_normal.dot(&binormal), target_normal.dot(&normal))
}

/// `atan2(y, x)` on `(−π, π]`: `atan2` itself returns `−π` for `y = −0`, `x < 0`.
fn principal_angle(y: f64, x: f64) -> f64 {
    let angle = y.atan2(x);
    if angle <= -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        angle
    }
}

/// Frames from the normals and tangents, frame `k` turned about its own tangent by
/// `twist · k / S`, so the first frame is kept and the last turns by the whole `twist`. The
/// angles advance by a fixed step, so their sines and cosines follow by rotation recurrence,
/// re-seeded exactly every few frames to bound round-off; the last frame is always seeded
/// exactly.
fn twisted_frames(
    normals: &[Vector3<f64>],
    tangents: &[Unit<Vector3<f64>>],
    twist: f64,
) -> Vec<Rotation3<f64>> {
    const RESEED_INTERVAL: usize = 16;
    let last = normals.len().saturating_sub(1);
    let step = twist / last.max(1) as f64;
    let (step_sin, step_cos) = step.sin_cos();
    let (mut sin, mut cos) = (0.0, 1.0);
    let mut frames = Vec::with_capacity(normals.len());
    for (k, (normal, tangent)) in normals.iter().zip(tangents).enumerate() {
        if k == 0 {
            frames.push(frame(normal, tangent));
            continue;
        }
        (sin, cos) = if k % RESEED_INTERVAL == 0 || k == last {
            (step * k as f64).sin_cos()
        } else {
            (
                sin * step_cos + cos * step_sin,
                cos * step_cos - sin * step_sin,
            )
        };
        let binormal = tangent.cross(normal);
        let twisted_normal = normal * cos + binormal * sin;
        let twisted_binormal = binormal * cos - normal * sin;
        frames.push(Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[
            twisted_normal,
            twisted_binormal,
            tangent.into_inner(),
        ])));
    }
    frames
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn a_half_turn_twist_is_reported_as_plus_pi() {
        let frame = Rotation3::identity();
        // atan2(−0, −1) = −π: the branch cut itself.
        let target = Unit::new_unchecked(Vector3::new(-1.0, -0.0, 0.0));
        assert_eq!(principal_angle(-0.0, -1.0), PI);
        assert_eq!(twist_mismatch(&frame, &target), PI);
        let quarter = Unit::new_unchecked(Vector3::new(0.0, 1.0, 0.0));
        assert!((twist_mismatch(&frame, &quarter) - FRAC_PI_2).abs() < 1e-15);
    }
}
