//! Derivatives of what happens at one joint of the discrete cable, as functions of the two
//! edge vectors `a` (incoming) and `b` (outgoing) that meet there.
//!
//! - **Bending**: the energy `2c (1 − u)/(1 + u) = ½ c |κb|²`, `u = cos φ` the cosine of
//!   the turning angle and `κb = 2 tan(φ/2)` the discrete curvature binormal of the discrete
//!   elastic rod (Bergou et al. 2008). It equals the spring energy `½ c φ²` to
//!   `1 + φ²/6`, is a rational function of `u` (smooth at `φ = 0`, where `φ` itself is not)
//!   and grows without bound as the joint folds back (`φ → π`).
//! - **Reference twist**: how the parallel-transported frame turns about the tangent when
//!   the edges move; its gradient is `κb / (2|a|)` and `κb / (2|b|)`.

use nalgebra::{Matrix3, Vector3};

/// Unit direction and length of one edge.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge {
    pub(crate) unit: Vector3<f64>,
    pub(crate) length: f64,
}

impl Edge {
    pub(crate) fn new(vector: Vector3<f64>) -> Self {
        let length = vector.norm();
        Self {
            unit: vector / length,
            length,
        }
    }
}

/// Gradient and Hessian blocks of a function of two edge vectors `a` and `b`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgePairDerivatives {
    pub(crate) value: f64,
    pub(crate) grad_a: Vector3<f64>,
    pub(crate) grad_b: Vector3<f64>,
    pub(crate) hess_aa: Matrix3<f64>,
    pub(crate) hess_ab: Matrix3<f64>,
    pub(crate) hess_ba: Matrix3<f64>,
    pub(crate) hess_bb: Matrix3<f64>,
}

impl EdgePairDerivatives {
    /// `self += scale · other`.
    pub(crate) fn add_scaled(&mut self, other: &Self, scale: f64) {
        self.value += scale * other.value;
        self.grad_a += scale * other.grad_a;
        self.grad_b += scale * other.grad_b;
        self.hess_aa += scale * other.hess_aa;
        self.hess_ab += scale * other.hess_ab;
        self.hess_ba += scale * other.hess_ba;
        self.hess_bb += scale * other.hess_bb;
    }
}

impl EdgePairDerivatives {
    /// Value and gradient only (Hessian blocks zero).
    fn first_order(value: f64, grad_a: Vector3<f64>, grad_b: Vector3<f64>) -> Self {
        Self {
            value,
            grad_a,
            grad_b,
            hess_aa: Matrix3::zeros(),
            hess_ab: Matrix3::zeros(),
            hess_ba: Matrix3::zeros(),
            hess_bb: Matrix3::zeros(),
        }
    }
}

/// Bending energy `2c (1 − u)/(1 + u)` of a joint with stiffness `c` (N·m/rad) and its
/// derivatives with respect to the edge vectors (the Hessian blocks only `with_hessian`,
/// else zero).
pub(crate) fn bending(
    a: &Edge,
    b: &Edge,
    stiffness: f64,
    with_hessian: bool,
) -> EdgePairDerivatives {
    let u = a.unit.dot(&b.unit);
    let chi = 1.0 + u;
    let value = 2.0 * stiffness * (1.0 - u) / chi;
    let slope = -4.0 * stiffness / (chi * chi);
    let curvature = 8.0 * stiffness / (chi * chi * chi);
    of_cosine(a, b, (value, slope, curvature), with_hessian)
}

/// The bending energy of a joint whose first side, a guide's axis, may turn freely within a
/// cone of half-angle `cone_rad` about it (a swivel clamp): none while the turning angle
/// `φ` is within the cone, else the energy of the part beyond it, `2c (1 − w)/(1 + w)` with
/// `w = cos(φ − cone)` — the guide held at the cone's edge. Continuous with its gradient at
/// the edge; `cone_rad ≥ π` is a pin (never any energy).
pub(crate) fn cone_bending(
    a: &Edge,
    b: &Edge,
    stiffness: f64,
    cone_rad: f64,
    with_hessian: bool,
) -> EdgePairDerivatives {
    let u = a.unit.dot(&b.unit).clamp(-1.0, 1.0);
    let (sine, cosine) = cone_rad.min(std::f64::consts::PI).sin_cos();
    let r2 = 1.0 - u * u;
    if u >= cosine || r2 <= 0.0 {
        return of_cosine(a, b, (0.0, 0.0, 0.0), with_hessian);
    }
    let r = r2.sqrt();
    let w = u * cosine + r * sine;
    let dw = cosine - u * sine / r;
    let d2w = -sine / (r2 * r);
    let chi = 1.0 + w;
    let (t, dt, d2t) = ((1.0 - w) / chi, -2.0 / (chi * chi), 4.0 / (chi * chi * chi));
    let c = 2.0 * stiffness;
    let value = c * t;
    let slope = c * dt * dw;
    let curvature = c * (d2t * dw * dw + dt * d2w);
    of_cosine(a, b, (value, slope, curvature), with_hessian)
}

/// The derivatives with respect to the edge vectors of an energy `E(u)` of the cosine `u`
/// of the joint's turning angle, given `(E, dE/du, d²E/du²)` at `u`.
fn of_cosine(
    a: &Edge,
    b: &Edge,
    (value, slope, curvature): (f64, f64, f64),
    with_hessian: bool,
) -> EdgePairDerivatives {
    let u = a.unit.dot(&b.unit);
    let du_da = (b.unit - u * a.unit) / a.length;
    let du_db = (a.unit - u * b.unit) / b.length;
    if !with_hessian {
        return EdgePairDerivatives::first_order(value, slope * du_da, slope * du_db);
    }
    let cross_term = |x: &Edge, y: &Edge| {
        // ∂²u/∂x² = −(y xᵀ + x yᵀ + u I − 3u x xᵀ)/|x|² in unit directions.
        -(y.unit * x.unit.transpose()
            + x.unit * y.unit.transpose()
            + Matrix3::from_diagonal_element(u)
            - 3.0 * u * x.unit * x.unit.transpose())
            / (x.length * x.length)
    };
    let d2u_ab = (Matrix3::identity() - a.unit * a.unit.transpose() - b.unit * b.unit.transpose()
        + u * a.unit * b.unit.transpose())
        / (a.length * b.length);
    let hess_ab = curvature * du_da * du_db.transpose() + slope * d2u_ab;
    EdgePairDerivatives {
        value,
        grad_a: slope * du_da,
        grad_b: slope * du_db,
        hess_aa: curvature * du_da * du_da.transpose() + slope * cross_term(a, b),
        hess_ab,
        hess_ba: hess_ab.transpose(),
        hess_bb: curvature * du_db * du_db.transpose() + slope * cross_term(b, a),
    }
}

/// Gradient and (`with_hessian`) Hessian of the reference twist of the joint (value 0: only
/// its change matters; the total twist is measured separately by transport).
pub(crate) fn reference_twist(a: &Edge, b: &Edge, with_hessian: bool) -> EdgePairDerivatives {
    let chi = 1.0 + a.unit.dot(&b.unit);
    let kb = 2.0 * a.unit.cross(&b.unit) / chi;
    if !with_hessian {
        return EdgePairDerivatives::first_order(0.0, 0.5 / a.length * kb, 0.5 / b.length * kb);
    }
    let tilde = (a.unit + b.unit) / chi;
    // ∂κb/∂a and ∂κb/∂b.
    let dkb_da = -((2.0 / chi) * b.unit.cross_matrix() + kb * tilde.transpose()) / a.length;
    let dkb_db = ((2.0 / chi) * a.unit.cross_matrix() - kb * tilde.transpose()) / b.length;
    let half_a = 0.5 / a.length;
    let half_b = 0.5 / b.length;
    EdgePairDerivatives {
        value: 0.0,
        grad_a: half_a * kb,
        grad_b: half_b * kb,
        hess_aa: half_a * dkb_da - half_a / a.length * kb * a.unit.transpose(),
        hess_ab: half_a * dkb_db,
        hess_ba: half_b * dkb_da,
        hess_bb: half_b * dkb_db - half_b / b.length * kb * b.unit.transpose(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edges() -> (Vector3<f64>, Vector3<f64>) {
        (
            Vector3::new(0.01, 0.002, -0.001),
            Vector3::new(0.008, 0.005, 0.003),
        )
    }

    /// Central finite differences of `f` over the six edge coordinates.
    fn numeric_gradient(f: impl Fn(&Vector3<f64>, &Vector3<f64>) -> f64) -> [f64; 6] {
        let (a, b) = edges();
        let h = 1e-7;
        let mut g = [0.0; 6];
        for (k, slot) in g.iter_mut().enumerate() {
            let (mut ap, mut bp, mut am, mut bm) = (a, b, a, b);
            if k < 3 {
                ap[k] += h;
                am[k] -= h;
            } else {
                bp[k - 3] += h;
                bm[k - 3] -= h;
            }
            *slot = (f(&ap, &bp) - f(&am, &bm)) / (2.0 * h);
        }
        g
    }

    #[test]
    fn bending_energy_is_half_stiffness_times_curvature_binormal_squared() {
        let (a, b) = edges();
        let (ea, eb) = (Edge::new(a), Edge::new(b));
        let phi = a.angle(&b);
        let d = bending(&ea, &eb, 0.3, true);
        assert!((d.value - 0.5 * 0.3 * (2.0 * (phi / 2.0).tan()).powi(2)).abs() < 1e-15);
    }

    /// The analytic Hessian of `function` against central differences of its gradient.
    fn assert_hessian_is_the_gradient_derivative(
        function: fn(&Edge, &Edge) -> EdgePairDerivatives,
    ) {
        let (a, b) = edges();
        let d = function(&Edge::new(a), &Edge::new(b));
        let scale = d.hess_aa.norm() + d.hess_bb.norm();
        for row in 0..6 {
            let component = |a: &Vector3<f64>, b: &Vector3<f64>| {
                let d = function(&Edge::new(*a), &Edge::new(*b));
                if row < 3 {
                    d.grad_a[row]
                } else {
                    d.grad_b[row - 3]
                }
            };
            for (col, numeric) in numeric_gradient(component).into_iter().enumerate() {
                let analytic = match (row < 3, col < 3) {
                    (true, true) => d.hess_aa[(row, col)],
                    (true, false) => d.hess_ab[(row, col - 3)],
                    (false, true) => d.hess_ba[(row - 3, col)],
                    (false, false) => d.hess_bb[(row - 3, col - 3)],
                };
                assert!(
                    (analytic - numeric).abs() < 1e-6 * scale,
                    "({row},{col}): {analytic} vs {numeric}"
                );
            }
        }
    }

    fn bending_of_stiffness_0_3(a: &Edge, b: &Edge) -> EdgePairDerivatives {
        bending(a, b, 0.3, true)
    }

    fn reference_twist_with_hessian(a: &Edge, b: &Edge) -> EdgePairDerivatives {
        reference_twist(a, b, true)
    }

    #[test]
    fn first_order_derivatives_equal_the_full_ones() {
        let (a, b) = edges();
        let (a, b) = (Edge::new(a), Edge::new(b));
        for (full, first) in [
            (bending(&a, &b, 0.3, true), bending(&a, &b, 0.3, false)),
            (
                reference_twist(&a, &b, true),
                reference_twist(&a, &b, false),
            ),
        ] {
            assert_eq!(
                (full.value, full.grad_a, full.grad_b),
                (first.value, first.grad_a, first.grad_b)
            );
        }
    }

    #[test]
    fn bending_derivatives_match_finite_differences() {
        let energy = |a: &Vector3<f64>, b: &Vector3<f64>| {
            bending(&Edge::new(*a), &Edge::new(*b), 0.3, true).value
        };
        let (a, b) = edges();
        let d = bending(&Edge::new(a), &Edge::new(b), 0.3, true);
        let g = numeric_gradient(energy);
        for k in 0..3 {
            assert!((d.grad_a[k] - g[k]).abs() < 1e-6 * d.grad_a.norm());
            assert!((d.grad_b[k] - g[k + 3]).abs() < 1e-6 * d.grad_b.norm());
        }
        assert_hessian_is_the_gradient_derivative(bending_of_stiffness_0_3);
    }

    #[test]
    fn reference_twist_hessian_is_the_derivative_of_its_gradient() {
        assert_hessian_is_the_gradient_derivative(reference_twist_with_hessian);
    }

    /// Half the test edges' turning angle: the cone a swivel test leaves the joint beyond.
    fn half_angle() -> f64 {
        let (a, b) = edges();
        0.5 * a.angle(&b)
    }

    fn cone_bending_beyond_half(a: &Edge, b: &Edge) -> EdgePairDerivatives {
        cone_bending(a, b, 0.3, half_angle(), true)
    }

    #[test]
    fn a_swivel_bends_only_beyond_its_cone_as_a_clamp_at_the_cone_edge_would() {
        let (a, b) = edges();
        let (ea, eb) = (Edge::new(a), Edge::new(b));
        let phi = a.angle(&b);
        // Beyond the cone: the energy of the turning angle past the cone's edge (closed form).
        let beyond = cone_bending(&ea, &eb, 0.3, 0.5 * phi, true);
        let expected = 0.5 * 0.3 * (2.0 * (0.25 * phi).tan()).powi(2);
        assert!(
            (beyond.value - expected).abs() < 1e-15 * expected.max(1.0),
            "{}",
            beyond.value
        );
        // Within the cone, and for a pin: nothing, no force.
        for cone in [1.01 * phi, std::f64::consts::PI] {
            let within = cone_bending(&ea, &eb, 0.3, cone, true);
            assert_eq!(
                (within.value, within.grad_a.norm(), within.grad_b.norm()),
                (0.0, 0.0, 0.0)
            );
        }
        // A zero cone is the rigid clamp.
        let rigid = cone_bending(&ea, &eb, 0.3, 0.0, true);
        let clamp = bending(&ea, &eb, 0.3, true);
        assert!((rigid.value - clamp.value).abs() < 1e-12 * clamp.value);
        assert!((rigid.grad_b - clamp.grad_b).norm() < 1e-9 * clamp.grad_b.norm());
        // Derivatives against finite differences.
        let energy = |a: &Vector3<f64>, b: &Vector3<f64>| {
            cone_bending(&Edge::new(*a), &Edge::new(*b), 0.3, half_angle(), false).value
        };
        let g = numeric_gradient(energy);
        for k in 0..3 {
            assert!((beyond.grad_a[k] - g[k]).abs() < 1e-6 * beyond.grad_a.norm());
            assert!((beyond.grad_b[k] - g[k + 3]).abs() < 1e-6 * beyond.grad_b.norm());
        }
        assert_hessian_is_the_gradient_derivative(cone_bending_beyond_half);
    }
}
