//! Rotation-minimizing frames by the double-reflection method (Wang, Jüttler, Zheng, Liu,
//! "Computation of rotation minimizing frames", ACM TOG 27(1), 2008).
//!
//! A rotation-minimizing frame carries a normal along a curve without spinning it about the
//! tangent — the torsion-free reference a cable's twist is measured against. Each step maps the
//! frame at `x_i` to `x_{i+1}` by two reflections: the first in the plane bisecting the chord
//! (it carries point, tangent and normal across), the second in the plane that takes the
//! reflected tangent onto the exact tangent `t_{i+1}`. Fed with exact tangents the global error
//! is fourth order in the step.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};

/// Largest round-off drift of the normal (squared length from 1, plus its component along the
/// tangent) tolerated before it is re-orthonormalized.
const NORM_DRIFT_LIMIT: f64 = 1e-14;
/// Squared norms below this are treated as zero (a repeated point or tangent).
const DEGENERATE_SQUARED_NORM: f64 = 1e-300;

/// Frames along a polyline, one per point, as rotations with columns `(r, t × r, t)`:
/// normal, binormal, tangent.
///
/// `points` and `tangents` (exact curve tangents at the points) are paired up to the shorter
/// of the two. `first_normal` is made orthogonal to the first tangent (Gram–Schmidt); if it is
/// parallel to it, some normal is chosen. A repeated point skips the first reflection and a
/// tangent that the first reflection already maps exactly (`c2 ≈ 0`) skips the second, so no
/// input can divide by zero.
pub fn double_reflection(
    points: &[Point3<f64>],
    tangents: &[Unit<Vector3<f64>>],
    first_normal: Unit<Vector3<f64>>,
) -> Vec<Rotation3<f64>> {
    rotation_minimizing_normals(points, tangents, first_normal)
        .iter()
        .zip(tangents)
        .map(|(normal, tangent)| frame(normal, tangent))
        .collect()
}

/// The normals of [`double_reflection`]'s frames, one per point.
///
/// Each step's two mirrors depend only on the points and tangents, so they are prepared
/// first (see [`ReflectionPair`]); the normal then passes through both reflections with two
/// independent dot products, a chain of dependent operations half as long as reflecting
/// twice in turn.
pub(crate) fn rotation_minimizing_normals(
    points: &[Point3<f64>],
    tangents: &[Unit<Vector3<f64>>],
    first_normal: Unit<Vector3<f64>>,
) -> Vec<Vector3<f64>> {
    let count = points.len().min(tangents.len());
    let mut normals = Vec::with_capacity(count);
    if count == 0 {
        return normals;
    }
    let mut normal = orthogonal_normal(&first_normal, &tangents[0]);
    normals.push(normal);
    for i in 0..count - 1 {
        let next_tangent = tangents[i + 1];
        let pair = ReflectionPair::new(points[i + 1] - points[i], &tangents[i], &next_tangent);
        normal = pair.apply(&normal);
        // Reflections preserve lengths and angles; only round-off drift needs removing. The
        // check is off the critical path (the branch is predicted), and the projection and
        // square root are paid only when the drift shows (or the input is degenerate).
        let drift = next_tangent.dot(&normal).abs() + (normal.norm_squared() - 1.0).abs();
        if drift.is_nan() || drift > NORM_DRIFT_LIMIT {
            normal = orthogonal_normal(&Unit::new_unchecked(normal), &next_tangent);
        }
        normals.push(normal);
    }
    normals
}

/// One double-reflection step: `x ↦ R₂ R₁ x` with `Rᵢ x = x − (uᵢ·x) vᵢ`, `uᵢ = (2/|vᵢ|²) vᵢ`;
/// `v₁` is the chord, `v₂` the gap between the next tangent and the reflected tangent. A
/// mirror that is ~zero is skipped (`uᵢ = 0`).
struct ReflectionPair {
    first: Vector3<f64>,
    first_scaled: Vector3<f64>,
    second: Vector3<f64>,
    second_scaled: Vector3<f64>,
    /// `u₂·v₁`.
    coupling: f64,
}

impl ReflectionPair {
    #[inline]
    fn new(
        chord: Vector3<f64>,
        tangent: &Unit<Vector3<f64>>,
        next_tangent: &Unit<Vector3<f64>>,
    ) -> Self {
        let (first, first_scaled) = mirror(chord);
        let reflected_tangent = tangent.into_inner() - first_scaled.dot(tangent) * first;
        let (second, second_scaled) = mirror(next_tangent.into_inner() - reflected_tangent);
        Self {
            first,
            first_scaled,
            coupling: second_scaled.dot(&first),
            second,
            second_scaled,
        }
    }

    /// `R₂ R₁ x`, with `u₂·(R₁ x) = u₂·x − (u₁·x)(u₂·v₁)` so that both dot products with `x`
    /// are independent.
    #[inline]
    fn apply(&self, x: &Vector3<f64>) -> Vector3<f64> {
        let along_first = self.first_scaled.dot(x);
        let along_second = self.second_scaled.dot(x) - along_first * self.coupling;
        x - along_first * self.first - along_second * self.second
    }
}

/// `v` and `(2/|v|²) v` of a mirror, both zero if `v` is ~zero or not finite (no reflection).
#[inline]
fn mirror(v: Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let c = v.norm_squared();
    if c.is_nan() || c <= DEGENERATE_SQUARED_NORM || c.is_infinite() {
        (Vector3::zeros(), Vector3::zeros())
    } else {
        (v, (2.0 / c) * v)
    }
}

/// Unit vector orthogonal to `tangent`, as close as possible to `normal`; removes the
/// round-off drift of repeated reflections.
#[inline]
fn orthogonal_normal(normal: &Unit<Vector3<f64>>, tangent: &Unit<Vector3<f64>>) -> Vector3<f64> {
    let projected = normal.into_inner() - tangent.dot(normal) * tangent.into_inner();
    match Unit::try_new(projected, 1e-150) {
        Some(unit) => unit.into_inner(),
        // Parallel (or non-finite) input: any normal will do.
        None => any_orthogonal(tangent),
    }
}

/// Some unit vector orthogonal to `v`, built from the axis `v` is least aligned with.
fn any_orthogonal(v: &Unit<Vector3<f64>>) -> Vector3<f64> {
    let axis = if v.x.abs() <= v.y.abs() && v.x.abs() <= v.z.abs() {
        Vector3::x()
    } else if v.y.abs() <= v.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    let candidate = v.cross(&axis);
    candidate.try_normalize(1e-150).unwrap_or(Vector3::x())
}

/// Rotation with columns `(normal, tangent × normal, tangent)`.
#[inline]
pub(crate) fn frame(normal: &Vector3<f64>, tangent: &Unit<Vector3<f64>>) -> Rotation3<f64> {
    let binormal = tangent.cross(normal);
    Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[
        *normal,
        binormal,
        tangent.into_inner(),
    ]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_line_keeps_its_frame() {
        let direction = Unit::new_normalize(Vector3::new(1.0, 2.0, -0.5));
        let normal = Unit::new_normalize(direction.cross(&Vector3::z()));
        let points: Vec<_> = (0..30)
            .map(|i| Point3::origin() + (0.01 * i as f64) * direction.into_inner())
            .collect();
        let frames = double_reflection(&points, &vec![direction; 30], normal);
        assert_eq!(frames.len(), 30);
        for frame in &frames {
            assert!((frame.matrix() - frames[0].matrix()).abs().max() < 1e-15);
        }
        assert!((frames[0] * Vector3::x() - normal.into_inner()).norm() < 1e-15);
    }

    #[test]
    fn frames_are_proper_rotations_with_the_given_tangents() {
        let points: Vec<_> = (0..20)
            .map(|i| {
                let s = i as f64 * 0.1;
                Point3::new(s.cos(), s.sin() * s, 0.3 * s)
            })
            .collect();
        let tangents: Vec<_> = points
            .windows(2)
            .map(|w| Unit::new_normalize(w[1] - w[0]))
            .chain(std::iter::once(Unit::new_normalize(Vector3::new(
                0.0, 1.0, 0.1,
            ))))
            .collect();
        let frames = double_reflection(&points, &tangents, Vector3::x_axis());
        for (frame, tangent) in frames.iter().zip(&tangents) {
            let m = frame.matrix();
            assert!((m.transpose() * m - Matrix3::identity()).abs().max() < 1e-14);
            assert!((m.determinant() - 1.0).abs() < 1e-14);
            assert!((m.column(2) - tangent.into_inner()).norm() < 1e-15);
        }
    }

    #[test]
    fn degenerate_input_does_not_fail() {
        let tangent = Vector3::z_axis();
        let points = [Point3::origin(); 3];
        let reversed = [tangent, -tangent, tangent];
        let frames = double_reflection(&points, &reversed, tangent);
        assert_eq!(frames.len(), 3);
        assert!(
            frames
                .iter()
                .all(|f| f.matrix().iter().all(|v| v.is_finite()))
        );
        assert!(double_reflection(&[], &[], tangent).is_empty());
    }
}
