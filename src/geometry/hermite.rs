//! Cubic Hermite curve between two guide positions, optionally bowed sideways, its arc length,
//! the shape parameter that gives it a prescribed arc length, and nodes at equal arc length.
//!
//! `p(t) = h00(t) P0 + h10(t) α v0 + h01(t) P1 + h11(t) α v1 + β n w(t)`, `t ∈ [0, 1]`, with the
//! unit guide tangents `v0`, `v1`, the tangent scale `α` (m), a unit bow direction `n`, the bow
//! height `β` (m) and the bow profile `w(t) = 16 t²(1 − t)²`. `w` and `w'` vanish at both ends,
//! so the bow keeps the end points and end tangents; `max w = w(½) = 1`, so `β` is the height
//! of the bow. Without a bow (`β = 0`) this is the plain Hermite curve of the paper.
//!
//! The curve is stored as monomial coefficients so that `p`, `p'` and the sensitivities
//! `∂p'/∂α`, `∂p'/∂β` cost a few multiply–adds each (Horner); the root finds evaluate them
//! thousands of times.
//!
//! - `arc_length`: the arc length (adaptive Gauss–Kronrod quadrature), its derivatives with
//!   respect to a shape parameter, and the continuous bending energy.
//! - `root_find`: the shape parameter that gives a prescribed arc length.
//! - `resample`: parameters of points at equal arc length.

use nalgebra::{Point3, Unit, Vector3};

use crate::pose::Pose;

mod arc_length;
mod resample;
mod root_find;

pub use arc_length::ArcLengthError;
pub(crate) use arc_length::arc_length_tolerance;
pub(crate) use root_find::ParameterSearch;

/// A shape parameter of [`HermiteCurve`] that the arc-length root find can adjust. The curve
/// is affine in both, so its arc length is convex in each (the integrand is the norm of an
/// affine function of the parameter).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveParameter {
    /// The tangent scale α (m).
    Alpha,
    /// The bow height β (m).
    Bow,
}

/// Cubic Hermite curve from `P0` with unit tangent `v0` to `P1` with unit tangent `v1`, tangent
/// magnitudes `α` (m) at both ends, plus an optional bow `β n w(t)` (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct HermiteCurve {
    start: Point3<f64>,
    end: Point3<f64>,
    start_tangent: Unit<Vector3<f64>>,
    end_tangent: Unit<Vector3<f64>>,
    /// Unit bow direction `n`, or zero for a curve that has never been given one.
    bow_direction: Vector3<f64>,
    alpha_m: f64,
    bow_m: f64,
    /// `p(t) = c[0] + c[1] t + c[2] t² + c[3] t³ + c[4] t⁴`.
    position: [Vector3<f64>; 5],
    /// `p'(t) = d[0] + d[1] t + d[2] t² + d[3] t³`.
    velocity: [Vector3<f64>; 4],
    /// `∂p'/∂α` as cubic coefficients; independent of α and β because p is affine in both.
    alpha_sensitivity: [Vector3<f64>; 4],
    /// `∂p'/∂β = n w'(t)`, `w' = 32 t − 96 t² + 64 t³`, as cubic coefficients.
    bow_sensitivity: [Vector3<f64>; 4],
}

impl HermiteCurve {
    /// Curve from `start` with direction `start_tangent` to `end` arriving along `end_tangent`,
    /// tangent scale `alpha_m` (m), no bow.
    pub fn new(
        start: Point3<f64>,
        start_tangent: Unit<Vector3<f64>>,
        end: Point3<f64>,
        end_tangent: Unit<Vector3<f64>>,
        alpha_m: f64,
    ) -> Self {
        let (v0, v1) = (start_tangent.into_inner(), end_tangent.into_inner());
        let zero = Vector3::zeros();
        let mut curve = Self {
            start,
            end,
            start_tangent,
            end_tangent,
            bow_direction: zero,
            alpha_m,
            bow_m: 0.0,
            position: [zero; 5],
            velocity: [zero; 4],
            alpha_sensitivity: [v0, -2.0 * (2.0 * v0 + v1), 3.0 * (v0 + v1), zero],
            bow_sensitivity: [zero; 4],
        };
        curve.update_coefficients();
        curve
    }

    /// Curve between two guide frames: positions are the guide origins, tangents their +z axes.
    pub fn between_guides(start: &Pose, end: &Pose, alpha_m: f64) -> Self {
        Self::new(
            Point3::from(start.translation.vector),
            Unit::new_normalize(start.rotation * Vector3::z()),
            Point3::from(end.translation.vector),
            Unit::new_normalize(end.rotation * Vector3::z()),
            alpha_m,
        )
    }

    /// The same curve bowed by `bow_m` metres towards `direction` at its middle.
    pub fn with_bow(&self, direction: Unit<Vector3<f64>>, bow_m: f64) -> Self {
        let n = direction.into_inner();
        let mut curve = self.clone();
        curve.bow_direction = n;
        curve.bow_sensitivity = [Vector3::zeros(), 32.0 * n, -96.0 * n, 64.0 * n];
        curve.bow_m = bow_m;
        curve.update_coefficients();
        curve
    }

    /// Changes the tangent scale (m) in place.
    pub fn set_alpha(&mut self, alpha_m: f64) {
        self.alpha_m = alpha_m;
        self.update_coefficients();
    }

    /// Changes the bow height (m) in place (no effect on the shape without a bow direction).
    pub fn set_bow(&mut self, bow_m: f64) {
        self.bow_m = bow_m;
        self.update_coefficients();
    }

    /// The same curve with another tangent scale (m).
    pub fn with_alpha(&self, alpha_m: f64) -> Self {
        let mut curve = self.clone();
        curve.set_alpha(alpha_m);
        curve
    }

    /// Sets one shape parameter (m).
    pub fn set_parameter(&mut self, parameter: CurveParameter, value_m: f64) {
        match parameter {
            CurveParameter::Alpha => self.set_alpha(value_m),
            CurveParameter::Bow => self.set_bow(value_m),
        }
    }

    fn update_coefficients(&mut self) {
        let (v0, v1) = (
            self.start_tangent.into_inner(),
            self.end_tangent.into_inner(),
        );
        let (alpha, bow) = (self.alpha_m, self.bow_m * self.bow_direction);
        let chord = self.end - self.start;
        let c1 = alpha * v0;
        let c2 = 3.0 * chord - alpha * (2.0 * v0 + v1) + 16.0 * bow;
        let c3 = -2.0 * chord + alpha * (v0 + v1) - 32.0 * bow;
        let c4 = 16.0 * bow;
        self.position = [self.start.coords, c1, c2, c3, c4];
        self.velocity = [c1, 2.0 * c2, 3.0 * c3, 4.0 * c4];
    }

    /// Tangent scale α (m).
    pub fn alpha_m(&self) -> f64 {
        self.alpha_m
    }

    /// Bow height β (m): how far the middle of the curve is pushed along the bow direction.
    pub fn bow_m(&self) -> f64 {
        self.bow_m
    }

    /// Unit bow direction `n`, or zero if the curve was never given one.
    pub fn bow_direction(&self) -> Vector3<f64> {
        self.bow_direction
    }

    /// Start point `P0 = p(0)` (m).
    pub fn start(&self) -> Point3<f64> {
        self.start
    }

    /// End point `P1 = p(1)` (m).
    pub fn end(&self) -> Point3<f64> {
        self.end
    }

    /// Unit tangent `v0` at the start.
    pub fn start_tangent(&self) -> Unit<Vector3<f64>> {
        self.start_tangent
    }

    /// Unit tangent `v1` at the end.
    pub fn end_tangent(&self) -> Unit<Vector3<f64>> {
        self.end_tangent
    }

    /// Straight distance `|P1 − P0|` (m): the least possible arc length, reached by the
    /// unbowed curve at α = 0.
    pub fn chord_length(&self) -> f64 {
        (self.end - self.start).norm()
    }

    /// Position `p(t)` (m).
    #[inline]
    pub fn point(&self, t: f64) -> Point3<f64> {
        let [c0, c1, c2, c3, c4] = &self.position;
        Point3::from(c0 + t * (c1 + t * (c2 + t * (c3 + t * c4))))
    }

    /// Parametric velocity `p'(t)` (m per unit parameter).
    #[inline]
    pub fn derivative(&self, t: f64) -> Vector3<f64> {
        let [d0, d1, d2, d3] = &self.velocity;
        d0 + t * (d1 + t * (d2 + t * d3))
    }

    /// Parametric acceleration `p''(t)` (m per unit parameter²).
    #[inline]
    pub fn second_derivative(&self, t: f64) -> Vector3<f64> {
        let [_, d1, d2, d3] = &self.velocity;
        d1 + t * (2.0 * d2 + t * (3.0 * d3))
    }

    /// `∂p'(t)/∂q` for a shape parameter `q` (per unit parameter): how the velocity changes
    /// with the tangent scale or the bow height.
    #[inline]
    pub fn velocity_sensitivity(&self, parameter: CurveParameter, t: f64) -> Vector3<f64> {
        let [e0, e1, e2, e3] = self.sensitivity(parameter);
        e0 + t * (e1 + t * (e2 + t * e3))
    }

    fn sensitivity(&self, parameter: CurveParameter) -> &[Vector3<f64>; 4] {
        match parameter {
            CurveParameter::Alpha => &self.alpha_sensitivity,
            CurveParameter::Bow => &self.bow_sensitivity,
        }
    }

    /// Unit tangent at `t`: exactly `v0` at `t = 0` and `v1` at `t = 1` (also when α = 0),
    /// `p'/|p'|` inside; `None` where the curve has a cusp (`p' = 0`).
    pub fn unit_tangent(&self, t: f64) -> Option<Unit<Vector3<f64>>> {
        if t == 0.0 {
            Some(self.start_tangent)
        } else if t == 1.0 {
            Some(self.end_tangent)
        } else {
            Unit::try_new(self.derivative(t), f64::MIN_POSITIVE)
        }
    }
}

/// Fixtures shared by the unit tests of the curve and of its submodules.
#[cfg(test)]
pub(crate) mod test_support {
    use super::HermiteCurve;
    use nalgebra::{Point3, Unit, Vector3};

    /// A unit vector from components.
    pub fn unit(x: f64, y: f64, z: f64) -> Unit<Vector3<f64>> {
        Unit::new_normalize(Vector3::new(x, y, z))
    }

    /// A generic skew curve: no symmetry that could hide a sign or index error.
    pub fn sample_curve() -> HermiteCurve {
        HermiteCurve::new(
            Point3::new(0.1, -0.2, 0.3),
            unit(1.0, 0.5, -0.2),
            Point3::new(0.4, 0.1, 0.0),
            unit(-0.3, 1.0, 0.4),
            0.37,
        )
    }

    /// `|Σ w_i x_i^d − ∫_{−1}^{1} x^d dx|` of a quadrature rule on [−1, 1].
    pub fn rule_error(nodes: &[f64], weights: &[f64], degree: i32) -> f64 {
        let exact = if degree % 2 == 0 {
            2.0 / (degree as f64 + 1.0)
        } else {
            0.0
        };
        let sum: f64 = nodes
            .iter()
            .zip(weights)
            .map(|(x, w)| w * x.powi(degree))
            .sum();
        (sum - exact).abs()
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::{sample_curve, unit};
    use super::*;

    /// The Hermite basis and bow profile written out, independent of the stored monomial
    /// coefficients.
    fn basis_point(c: &HermiteCurve, t: f64) -> Point3<f64> {
        let h00 = 2.0 * t.powi(3) - 3.0 * t * t + 1.0;
        let h10 = t.powi(3) - 2.0 * t * t + t;
        let h01 = -2.0 * t.powi(3) + 3.0 * t * t;
        let h11 = t.powi(3) - t * t;
        let w = 16.0 * t * t * (1.0 - t) * (1.0 - t);
        let a = c.alpha_m();
        Point3::from(
            h00 * c.start().coords
                + h10 * a * c.start_tangent().into_inner()
                + h01 * c.end().coords
                + h11 * a * c.end_tangent().into_inner()
                + w * c.bow_m() * c.bow_direction(),
        )
    }

    #[test]
    fn monomial_form_matches_the_hermite_basis() {
        let plain = sample_curve();
        let bowed = plain.with_bow(unit(0.2, -1.0, 0.5), 0.07);
        for curve in [&plain, &bowed] {
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                assert!((curve.point(t) - basis_point(curve, t)).norm() < 1e-15);
                let h = 1e-6;
                let fd = (basis_point(curve, t + h) - basis_point(curve, t - h)) / (2.0 * h);
                assert!((curve.derivative(t) - fd).norm() < 1e-8);
            }
            assert!((curve.point(1.0) - curve.end()).norm() < 1e-15);
            let v0 = curve.alpha_m() * curve.start_tangent().into_inner();
            let v1 = curve.alpha_m() * curve.end_tangent().into_inner();
            assert!((curve.derivative(0.0) - v0).norm() < 1e-15);
            assert!((curve.derivative(1.0) - v1).norm() < 1e-15);
        }
        // The bow height is the displacement at the middle.
        let lift = bowed.point(0.5) - plain.point(0.5);
        assert!((lift - 0.07 * bowed.bow_direction()).norm() < 1e-15);
    }

    #[test]
    fn parameter_sensitivities_match_finite_differences() {
        let base = sample_curve().with_bow(unit(0.2, -1.0, 0.5), 0.07);
        let h = 1e-6;
        for parameter in [CurveParameter::Alpha, CurveParameter::Bow] {
            let value = match parameter {
                CurveParameter::Alpha => base.alpha_m(),
                CurveParameter::Bow => base.bow_m(),
            };
            let (mut plus, mut minus) = (base.clone(), base.clone());
            plus.set_parameter(parameter, value + h);
            minus.set_parameter(parameter, value - h);
            for i in 0..=10 {
                let t = i as f64 / 10.0;
                let fd = (plus.derivative(t) - minus.derivative(t)) / (2.0 * h);
                let got = base.velocity_sensitivity(parameter, t);
                assert!((got - fd).norm() < 1e-8, "{parameter:?} at {t}");
            }
            let (_, slope) = base.arc_length_and_slope(parameter);
            let fd = (plus.arc_length() - minus.arc_length()) / (2.0 * h);
            assert!((slope - fd).abs() < 1e-8, "{parameter:?}: {slope} vs {fd}");
        }
    }
}
