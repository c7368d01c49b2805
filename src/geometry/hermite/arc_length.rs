//! Arc length of a [`HermiteCurve`], its derivatives with respect to a shape parameter, and
//! the continuous bending energy.
//!
//! The quadrature is adaptive Gauss–Kronrod (G10/K21). Its initial panels end at 0, ½, 1 and
//! at the sharp interior minima of the speed `|p'|`, where a cusp puts a kink into the
//! integrand. Besides `L` it integrates `dL/dq` for a shape parameter `q` (α or β) from the
//! same nodes (and `d²L/dq²` in the cheap rule), for the root find in `root_find`.

use nalgebra::Vector3;

use super::{CurveParameter, HermiteCurve};

/// Nodes of the 21-point Gauss–Kronrod rule on `[−1, 1]` (QUADPACK `qk21`, Piessens et al.
/// 1983): the 10 Gauss–Legendre nodes at odd indices, their Kronrod extension at even ones.
const KRONROD_NODES: [f64; 21] = [
    -0.9956571630258081,
    -0.9739065285171717,
    -0.9301574913557082,
    -0.8650633666889845,
    -0.7808177265864169,
    -0.6794095682990244,
    -0.5627571346686047,
    -0.4333953941292472,
    -0.2943928627014602,
    -0.14887433898163122,
    0.0,
    0.14887433898163122,
    0.2943928627014602,
    0.4333953941292472,
    0.5627571346686047,
    0.6794095682990244,
    0.7808177265864169,
    0.8650633666889845,
    0.9301574913557082,
    0.9739065285171717,
    0.9956571630258081,
];
/// Weights of the 21-point Kronrod rule (exact for polynomials up to degree 31).
const KRONROD_WEIGHTS: [f64; 21] = [
    0.011694638867371874,
    0.032558162307964725,
    0.054755896574351995,
    0.07503967481091996,
    0.0931254545836976,
    0.10938715880229764,
    0.12349197626206584,
    0.13470921731147334,
    0.14277593857706009,
    0.14773910490133849,
    0.1494455540029169,
    0.14773910490133849,
    0.14277593857706009,
    0.13470921731147334,
    0.12349197626206584,
    0.10938715880229764,
    0.0931254545836976,
    0.07503967481091996,
    0.054755896574351995,
    0.032558162307964725,
    0.011694638867371874,
];
/// Weights of the embedded 10-point Gauss–Legendre rule (zero at the Kronrod-only nodes).
const GAUSS_WEIGHTS: [f64; 21] = [
    0.0,
    0.06667134430868814,
    0.0,
    0.1494513491505806,
    0.0,
    0.21908636251598204,
    0.0,
    0.26926671930999635,
    0.0,
    0.29552422471475287,
    0.0,
    0.29552422471475287,
    0.0,
    0.26926671930999635,
    0.0,
    0.21908636251598204,
    0.0,
    0.1494513491505806,
    0.0,
    0.06667134430868814,
    0.0,
];

/// Nodes of the 10-point Gauss–Legendre rule: the odd-indexed Kronrod nodes.
const GAUSS_NODES: [f64; 10] = [
    KRONROD_NODES[1],
    KRONROD_NODES[3],
    KRONROD_NODES[5],
    KRONROD_NODES[7],
    KRONROD_NODES[9],
    KRONROD_NODES[11],
    KRONROD_NODES[13],
    KRONROD_NODES[15],
    KRONROD_NODES[17],
    KRONROD_NODES[19],
];
/// Most edges of the initial quadrature panels: 0, ½, 1 and up to five interior speed minima
/// (`|p'|²` is a polynomial of degree ≤ 6, its derivative has at most five roots).
const MAX_EDGES: usize = 8;
/// Samples of `d|p'|²/dt` that bracket the interior speed minima.
const MINIMUM_SEARCH_SAMPLES: usize = 16;
/// Iteration limit of the Newton/bisection refinement of one speed minimum.
const MAX_MINIMUM_ITERATIONS: usize = 60;
/// A speed minimum is refined until the Newton step is below this (parameter units).
const MINIMUM_STEP_TOL: f64 = 1e-12;
/// Speed dips narrower than this (parameter units, see `sharp_speed_minima`) get a panel edge:
/// a quarter of the minimum search's sample spacing.
const SHARP_DIP_WIDTH: f64 = 1.0 / 64.0;
/// Bisection depth limit of the adaptive quadrature (panel width ≥ 2⁻⁵⁰ / 2).
const MAX_PANEL_DEPTH: u32 = 50;
/// A panel is accepted when its 10-point Gauss and 21-point Kronrod values of the length
/// differ by less than this fraction of the curve length per unit parameter. On smooth
/// panels the accepted Kronrod value (degree 31) is many orders more accurate than that
/// difference, which mostly measures the Gauss error; at kinks (cusps, `p' = 0`) both err
/// alike and the panel is bisected down to this tolerance. Measured: ≤ 1e-14 relative error
/// on bends, loops, hairpins and α up to 10× the chord (see the tests).
const PANEL_REL_TOL: f64 = 1e-10;

/// Why no value of a shape parameter gives the requested arc length.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ArcLengthError {
    /// The target is shorter than the straight distance between the end points, which is
    /// the shortest curve there is.
    #[error(
        "arc length {target_m} m is shorter than the straight distance {chord_m} m between the ends"
    )]
    BelowChord {
        /// Straight distance `|P1 − P0|` (m).
        chord_m: f64,
        /// Requested arc length (m).
        target_m: f64,
    },
    /// The curve is already longer than the target with the parameter at zero; the root find
    /// only searches non-negative values.
    #[error(
        "arc length {target_m} m is shorter than {at_zero_m} m, the length with the {parameter:?} parameter at zero"
    )]
    BelowZeroParameter {
        /// Which parameter was searched.
        parameter: CurveParameter,
        /// Arc length with that parameter at zero (m).
        at_zero_m: f64,
        /// Requested arc length (m).
        target_m: f64,
    },
    /// The target or the curve's data are NaN or infinite, or the target is negative.
    #[error("invalid arc-length problem: {what}")]
    InvalidInput {
        /// What is wrong, for people.
        what: String,
    },
    /// The root find ran out of iterations or of parameter range.
    #[error(
        "no {parameter:?} parameter found for arc length {target_m} m (residual {residual_m:e} m)"
    )]
    NotConverged {
        /// Which parameter was searched.
        parameter: CurveParameter,
        /// Requested arc length (m).
        target_m: f64,
        /// Best `|L − target|` reached (m).
        residual_m: f64,
    },
}

impl HermiteCurve {
    /// Arc length `L = ∫₀¹ |p'(t)| dt` (m), adaptive Gauss–Kronrod quadrature.
    pub fn arc_length(&self) -> f64 {
        self.arc_length_and_slope(CurveParameter::Alpha).0
    }

    /// Arc length `L` (m) and its derivative `dL/dq = ∫ p'·∂p'/∂q / |p'| dt` (dimensionless)
    /// for a shape parameter `q`, both from the same quadrature nodes.
    ///
    /// Adaptive Gauss–Kronrod (G10/K21) quadrature: the initial panels end at 0, ½, 1 and at
    /// the sharp interior minima of the speed `|p'|`; panels whose two rules disagree are
    /// bisected. About 1e-14 relative accuracy or better, also across cusps (see the tests).
    pub fn arc_length_and_slope(&self, parameter: CurveParameter) -> (f64, f64) {
        let edges = self.initial_edges();
        let mut scratch = QuadratureScratch::default();
        let sums = self.adaptive_sums(parameter, edges.edges(), &mut scratch);
        (sums.length, sums.slope)
    }

    /// `L`, `dL/dq` and `d²L/dq²` by the 10-point Gauss rule on the panels between `edges`,
    /// without error control: the cheap first phase of the root find (~1e-6 relative on
    /// ordinary bends).
    pub(super) fn coarse_sums(&self, parameter: CurveParameter, edges: &[f64]) -> LengthSums {
        let sensitivity = self.sensitivity(parameter);
        let zero = LengthSums {
            slope_rate: Some(0.0),
            ..LengthSums::default()
        };
        edges.windows(2).fold(zero, |sum, pair| {
            sum + self.gauss_panel(pair[0], pair[1], sensitivity)
        })
    }

    /// `L` and `dL/dq` by adaptive Gauss–Kronrod quadrature from the panels between the
    /// ascending `edges` (from 0 to 1): a panel is accepted when its 10- and 21-point
    /// values of the length agree to [`PANEL_REL_TOL`] of the length per unit parameter, else
    /// bisected. The edges of the accepted panels are left in `scratch.accepted` (ascending, 0
    /// to 1), so that a later call at a nearby parameter value can start from them and usually
    /// just confirm them.
    pub(super) fn adaptive_sums(
        &self,
        parameter: CurveParameter,
        edges: &[f64],
        scratch: &mut QuadratureScratch,
    ) -> LengthSums {
        let sensitivity = self.sensitivity(parameter);
        let QuadratureScratch { accepted, stack } = scratch;
        accepted.clear();
        accepted.push(0.0);
        stack.clear();
        stack.reserve(edges.len() + MAX_PANEL_DEPTH as usize + 2);
        let mut coarse = LengthSums::default();
        // Pushed from t = 1 down, so that they are popped (and summed) from t = 0 upwards.
        for pair in edges.windows(2).rev() {
            let panel = Panel::new(pair[0], pair[1], 0);
            let sums = self.kronrod_panel(&panel, sensitivity);
            coarse = coarse + sums.sums();
            stack.push((panel, sums));
        }
        if !(coarse.length > 0.0 && coarse.length.is_finite()) {
            // Degenerate (a single point) or non-finite data: nothing to refine.
            accepted.push(1.0);
            return coarse;
        }
        let tolerance_per_parameter = PANEL_REL_TOL * coarse.length;
        let mut total = LengthSums::default();
        while let Some((panel, sums)) = stack.pop() {
            let converged = sums.gauss_gap <= tolerance_per_parameter * (panel.b - panel.a);
            if converged || panel.depth >= MAX_PANEL_DEPTH {
                total = total + sums.sums();
                accepted.push(panel.b);
            } else {
                let mid = 0.5 * (panel.a + panel.b);
                let right = Panel::new(mid, panel.b, panel.depth + 1);
                let left = Panel::new(panel.a, mid, panel.depth + 1);
                stack.push((right, self.kronrod_panel(&right, sensitivity)));
                stack.push((left, self.kronrod_panel(&left, sensitivity)));
            }
        }
        total
    }

    /// Edges of the initial quadrature panels, ascending: 0, ½, 1 and the sharp interior
    /// speed minima. A cusp (`p' = 0`) puts a kink into `|p'|`; inside a panel it would take
    /// dozens of bisections to integrate, on a panel edge it costs nothing. Near-cusps (tight
    /// turns) gain in the same way.
    pub(super) fn initial_edges(&self) -> InitialEdges {
        let (minima, found) = self.sharp_speed_minima();
        let mut edges = [0.0; MAX_EDGES];
        let mut count = 1;
        let mut push = |t: f64| {
            // Skip repeats (a minimum at ½) that would make empty panels.
            if t > edges[count - 1] {
                edges[count] = t;
                count += 1;
            }
        };
        let split = minima[..found].partition_point(|&t| t < 0.5);
        minima[..split].iter().for_each(|&t| push(t));
        push(0.5);
        minima[split..found].iter().for_each(|&t| push(t));
        push(1.0);
        InitialEdges {
            edges,
            count,
            minima,
            found,
        }
    }

    /// Interior parameters where the speed `|p'|` has a sharp local minimum, ascending, and
    /// how many. The minima are the sign changes from − to + of `g = p'·p''` (half of
    /// `d|p'|²/dt`, a polynomial of degree ≤ 5) between [`MINIMUM_SEARCH_SAMPLES`] samples.
    /// A minimum is sharp when the dip is narrower than [`SHARP_DIP_WIDTH`]: `|p'| < w |p''|`
    /// there (`|p'|² ≈ m² + |p''|²(t − t_c)²` has width `m/|p''|`); a cusp (`m = 0`) is the
    /// sharpest. Only those are refined (Newton on `g`): a wide dip is smooth for the
    /// quadrature. Minima closer together than a sample spacing may be missed; that only costs
    /// quadrature panels.
    fn sharp_speed_minima(&self) -> ([f64; MAX_EDGES - 3], usize) {
        let g = self.speed_slope_polynomial();
        let mut minima = [0.0; MAX_EDGES - 3];
        let mut found = 0;
        let step = 1.0 / MINIMUM_SEARCH_SAMPLES as f64;
        // All samples first, branch-free, so that the Horner chains overlap.
        let samples: [f64; MINIMUM_SEARCH_SAMPLES + 1] =
            std::array::from_fn(|i| horner(&g, i as f64 * step));
        for (i, pair) in samples.windows(2).enumerate() {
            if !(pair[0] < 0.0 && pair[1] >= 0.0) || found == minima.len() {
                continue;
            }
            let (lo, hi) = (i as f64 * step, (i + 1) as f64 * step);
            // Regula falsi: close enough to judge the width of the dip.
            let estimate = lo + step * pair[0] / (pair[0] - pair[1]);
            let (velocity, acceleration) =
                (self.derivative(estimate), self.second_derivative(estimate));
            if velocity.norm() < SHARP_DIP_WIDTH * acceleration.norm() {
                let minimum = refine_polynomial_root(&g, lo, hi, estimate);
                if minimum > 0.0 && minimum < 1.0 {
                    minima[found] = minimum;
                    found += 1;
                }
            }
        }
        (minima, found)
    }

    /// Coefficients of `g(t) = p'(t)·p''(t) = Σ g_k t^k`: with `p' = Σ d_i t^i` and
    /// `p'' = Σ (j+1) d_{j+1} t^j`, `g_k = Σ_{i+j=k} (j+1) d_i·d_{j+1}`.
    fn speed_slope_polynomial(&self) -> [f64; 6] {
        let d = &self.velocity;
        let mut g = [0.0; 6];
        for (i, d_i) in d.iter().enumerate() {
            for j in 0..3 {
                g[i + j] += (j + 1) as f64 * d_i.dot(&d[j + 1]);
            }
        }
        g
    }

    /// `|p'|`, `∂|p'|/∂q = p'·w / |p'|` and, if `RATE`, `∂²|p'|/∂q² = (|w|² − (p'·w)²/|p'|²) / |p'|`
    /// (else zeros) at the points `mid + half·x` of a panel, `w = ∂p'/∂q` (independent of
    /// `q`, the curve being affine in it). Written over fixed arrays of scalars so that the
    /// compiler vectorizes the square roots and divisions.
    #[inline]
    fn speed_samples<const N: usize, const RATE: bool>(
        &self,
        mid: f64,
        half: f64,
        abscissae: &[f64; N],
        sensitivity: &[Vector3<f64>; 4],
    ) -> [[f64; N]; 3] {
        let [d0, d1, d2, d3] = &self.velocity;
        let [e0, e1, e2, e3] = sensitivity;
        let mut speed = [0.0; N];
        let mut speed_slope = [0.0; N];
        let mut speed_rate = [0.0; N];
        for i in 0..N {
            let t = mid + half * abscissae[i];
            let vx = d0.x + t * (d1.x + t * (d2.x + t * d3.x));
            let vy = d0.y + t * (d1.y + t * (d2.y + t * d3.y));
            let vz = d0.z + t * (d1.z + t * (d2.z + t * d3.z));
            let wx = e0.x + t * (e1.x + t * (e2.x + t * e3.x));
            let wy = e0.y + t * (e1.y + t * (e2.y + t * e3.y));
            let wz = e0.z + t * (e1.z + t * (e2.z + t * e3.z));
            let norm = (vx * vx + vy * vy + vz * vz).sqrt();
            let along = vx * wx + vy * wy + vz * wz;
            speed[i] = norm;
            // The derivatives are undefined at a cusp (p' = 0), a set of measure zero: take 0.
            if RATE {
                // One division and one select per point keep the loop vectorized.
                let inverse = if norm > 0.0 { 1.0 / norm } else { 0.0 };
                let slope = along * inverse;
                speed_slope[i] = slope;
                speed_rate[i] = (wx * wx + wy * wy + wz * wz - slope * slope) * inverse;
            } else {
                speed_slope[i] = if norm > 0.0 { along / norm } else { 0.0 };
            }
        }
        [speed, speed_slope, speed_rate]
    }

    /// Gauss–Legendre (10-point) sums of `|p'|` and its first two `q`-derivatives over a
    /// panel: the cheap rule of the first phase of the root find.
    #[inline]
    fn gauss_panel(&self, a: f64, b: f64, sensitivity: &[Vector3<f64>; 4]) -> LengthSums {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let [speed, slope, rate] =
            self.speed_samples::<10, true>(mid, half, &GAUSS_NODES, sensitivity);
        LengthSums {
            length: gauss10_sum(&speed) * half,
            slope: gauss10_sum(&slope) * half,
            slope_rate: Some(gauss10_sum(&rate) * half),
        }
    }

    /// Kronrod sums of `|p'|` and `p'·∂p'/∂q / |p'|` over a panel, and the gap between the
    /// Kronrod and Gauss values of the former.
    #[inline]
    fn kronrod_panel(&self, panel: &Panel, sensitivity: &[Vector3<f64>; 4]) -> PanelSums {
        let mid = 0.5 * (panel.a + panel.b);
        let half = 0.5 * (panel.b - panel.a);
        let [speed, speed_slope, _] =
            self.speed_samples::<21, false>(mid, half, &KRONROD_NODES, sensitivity);
        let (mut kronrod, mut gauss, mut kronrod_slope) = (0.0, 0.0, 0.0);
        for i in 0..21 {
            kronrod += KRONROD_WEIGHTS[i] * speed[i];
            gauss += GAUSS_WEIGHTS[i] * speed[i];
            kronrod_slope += KRONROD_WEIGHTS[i] * speed_slope[i];
        }
        PanelSums {
            length: kronrod * half,
            slope: kronrod_slope * half,
            gauss_gap: ((kronrod - gauss) * half).abs(),
        }
    }

    /// `K = ∫ |∂p'/∂q| dt` (dimensionless) by the 10-point Gauss rule on `[0, ½]` and `[½, 1]`:
    /// the asymptotic slope of `L(q)`, `|L(q) − q K| ≤ L(0)` (triangle inequality).
    pub(super) fn sensitivity_length(&self, parameter: CurveParameter) -> f64 {
        let [e0, e1, e2, e3] = self.sensitivity(parameter);
        let mut length = 0.0;
        for mid in [0.25, 0.75] {
            let mut samples = [0.0; 10];
            for (sample, x) in samples.iter_mut().zip(GAUSS_NODES) {
                let t = mid + 0.25 * x;
                *sample = (e0 + t * (e1 + t * (e2 + t * e3))).norm();
            }
            length += gauss10_sum(&samples) * 0.25;
        }
        length
    }

    /// `|p' × p''|² / |p'|⁵` at the points `mid + half·x` (0 where `p' = 0`). Scalar arrays, so
    /// that the square roots and divisions vectorize.
    #[inline]
    fn energy_samples<const N: usize>(
        &self,
        mid: f64,
        half: f64,
        abscissae: &[f64; N],
    ) -> [f64; N] {
        let [d0, d1, d2, d3] = &self.velocity;
        let mut samples = [0.0; N];
        for (sample, x) in samples.iter_mut().zip(abscissae) {
            let t = mid + half * x;
            let vx = d0.x + t * (d1.x + t * (d2.x + t * d3.x));
            let vy = d0.y + t * (d1.y + t * (d2.y + t * d3.y));
            let vz = d0.z + t * (d1.z + t * (d2.z + t * d3.z));
            let ax = d1.x + t * (2.0 * d2.x + t * (3.0 * d3.x));
            let ay = d1.y + t * (2.0 * d2.y + t * (3.0 * d3.y));
            let az = d1.z + t * (2.0 * d2.z + t * (3.0 * d3.z));
            let (cx, cy, cz) = (vy * az - vz * ay, vz * ax - vx * az, vx * ay - vy * ax);
            let bend = cx * cx + cy * cy + cz * cz;
            let speed_squared = vx * vx + vy * vy + vz * vz;
            *sample = if speed_squared > 0.0 {
                bend / (speed_squared * speed_squared * speed_squared.sqrt())
            } else {
                0.0
            };
        }
        samples
    }
}

/// Sub-panels of each half of an initial panel that borders no sharp speed minimum.
const SMOOTH_ENERGY_PIECES: usize = 2;
/// Ratio of successive sub-panels of the geometric grading towards a sharp speed minimum.
const ENERGY_GRADING: f64 = 0.25;
/// A speed minimum whose dip is narrower than this (parameter units) is a cusp: the curve
/// turns by a finite angle in no length, and its bending energy is infinite.
const CUSP_DIP_WIDTH: f64 = 1e-9;

impl HermiteCurve {
    /// Continuous bending energy `∫ κ² ds = ∫ |p' × p''|² / |p'|⁵ dt` (1/m); infinite if the
    /// curve has a cusp (a speed minimum narrower than [`CUSP_DIP_WIDTH`]).
    ///
    /// 10-point Gauss–Legendre on the initial arc-length panels (edges 0, ½, 1 and the sharp
    /// speed minima), each split at its middle; a half is graded geometrically (ratio ¼)
    /// towards an edge at a sharp minimum until the pieces are narrower than the dip there,
    /// else split into [`SMOOTH_ENERGY_PIECES`] equal pieces.
    pub(crate) fn bending_energy_integral(&self) -> f64 {
        let initial = self.initial_edges();
        let minima = initial.minima();
        let mut widths = [0.0; MAX_EDGES - 3];
        for (width, &t) in widths.iter_mut().zip(minima) {
            *width = self.derivative(t).norm() / self.second_derivative(t).norm();
            if width.is_nan() || *width < CUSP_DIP_WIDTH {
                return f64::INFINITY;
            }
        }
        let dip_at = |t: f64| minima.iter().position(|&m| m == t).map(|i| widths[i]);
        initial
            .edges()
            .windows(2)
            .map(|pair| {
                let mid = 0.5 * (pair[0] + pair[1]);
                self.energy_half(pair[0], mid, dip_at(pair[0]))
                    + self.energy_half(pair[1], mid, dip_at(pair[1]))
            })
            .sum()
    }

    /// Bending energy between `edge` and `inner` (either order), graded towards `edge` if a
    /// dip of the given width sits there.
    fn energy_half(&self, edge: f64, inner: f64, dip: Option<f64>) -> f64 {
        let span = inner - edge;
        match dip {
            None => (0..SMOOTH_ENERGY_PIECES)
                .map(|i| {
                    let piece = span / SMOOTH_ENERGY_PIECES as f64;
                    let a = edge + piece * i as f64;
                    self.energy_panel(a, a + piece)
                })
                .sum(),
            Some(width) => {
                let (mut outer, mut energy) = (span, 0.0);
                while outer.abs() > 0.25 * width {
                    let next = outer * ENERGY_GRADING;
                    energy += self.energy_panel(edge + next, edge + outer);
                    outer = next;
                }
                energy + self.energy_panel(edge, edge + outer)
            }
        }
    }

    /// `∫ₐᵇ |p' × p''|² / |p'|⁵ dt` by the 10-point Gauss–Legendre rule (absolute value, so
    /// that `a > b` is fine); 0 where the speed vanishes at a node.
    fn energy_panel(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a).abs());
        gauss10_sum(&self.energy_samples(mid, half, &GAUSS_NODES)) * half
    }
}

/// `Σ w_i f_i` of the 10-point Gauss–Legendre rule on `[−1, 1]`.
#[inline]
fn gauss10_sum(values: &[f64; 10]) -> f64 {
    let mut sum = 0.0;
    for (i, value) in values.iter().enumerate() {
        sum += GAUSS_WEIGHTS[2 * i + 1] * value;
    }
    sum
}

/// `Σ c_k t^k` by Horner's rule.
#[inline]
fn horner(coefficients: &[f64], t: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |sum, c| sum * t + c)
}

/// The root of the polynomial `g` in `[lo, hi]`, where `g(lo) < 0 ≤ g(hi)`: Newton from
/// `start`, with bisection whenever a step leaves the bracket.
fn refine_polynomial_root(g: &[f64; 6], mut lo: f64, mut hi: f64, start: f64) -> f64 {
    let slope: [f64; 5] = std::array::from_fn(|k| (k + 1) as f64 * g[k + 1]);
    let mut t = start.clamp(lo, hi);
    for _ in 0..MAX_MINIMUM_ITERATIONS {
        let value = horner(g, t);
        if value < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - value / horner(&slope, t);
        let next = if newton >= lo && newton <= hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        // A kink δ off a panel edge costs the quadrature O(δ²): 1e-12 is plenty, and tighter
        // would chase the round-off of g near its root.
        let done = (next - t).abs() <= MINIMUM_STEP_TOL || hi - lo <= MINIMUM_STEP_TOL;
        t = next;
        if done {
            break;
        }
    }
    t
}

/// Convergence tolerance of the arc-length root (m).
pub(crate) fn arc_length_tolerance(target_m: f64) -> f64 {
    1e-12_f64.max(64.0 * f64::EPSILON * target_m)
}

/// A quadrature panel awaiting evaluation: its parameter interval and bisection depth.
#[derive(Debug, Clone, Copy, Default)]
struct Panel {
    a: f64,
    b: f64,
    depth: u32,
}

impl Panel {
    fn new(a: f64, b: f64, depth: u32) -> Self {
        Self { a, b, depth }
    }
}

/// Quadrature results on one panel.
#[derive(Debug, Clone, Copy, Default)]
struct PanelSums {
    /// Kronrod value of `∫ |p'|` (m).
    length: f64,
    /// Kronrod value of `∫ ∂|p'|/∂q`.
    slope: f64,
    /// `|Kronrod − Gauss|` for the length: the refinement criterion (m).
    gauss_gap: f64,
}

impl PanelSums {
    fn sums(&self) -> LengthSums {
        LengthSums {
            length: self.length,
            slope: self.slope,
            slope_rate: None,
        }
    }
}

/// Edges of the initial quadrature panels of a curve (see [`HermiteCurve::initial_edges`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct InitialEdges {
    edges: [f64; MAX_EDGES],
    count: usize,
    minima: [f64; MAX_EDGES - 3],
    found: usize,
}

impl InitialEdges {
    /// The edges, ascending from 0 to 1.
    pub(super) fn edges(&self) -> &[f64] {
        &self.edges[..self.count]
    }

    /// The sharp speed minima among the edges, ascending.
    fn minima(&self) -> &[f64] {
        &self.minima[..self.found]
    }

    /// No sharp speed minimum: `|p'|` and its `q`-derivatives are smooth, so `d²L/dq²` from
    /// the quadrature is reliable.
    pub(super) fn is_smooth(&self) -> bool {
        self.found == 0
    }
}

/// Quadrature values of the arc length and its derivatives with respect to one shape
/// parameter `q`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LengthSums {
    /// `L = ∫ |p'| dt` (m).
    pub(super) length: f64,
    /// `dL/dq` (dimensionless).
    pub(super) slope: f64,
    /// `d²L/dq² = ∫ (|w|² − (p'·w)²/|p'|²) / |p'| dt` (1/m), `w = ∂p'/∂q`: by the cheap rule
    /// only (the adaptive one leaves it out), as a scale for the Taylor term of a Newton step.
    pub(super) slope_rate: Option<f64>,
}

impl std::ops::Add for LengthSums {
    type Output = Self;

    fn add(self, other: Self) -> Self {
        Self {
            length: self.length + other.length,
            slope: self.slope + other.slope,
            slope_rate: self.slope_rate.zip(other.slope_rate).map(|(a, b)| a + b),
        }
    }
}

/// Buffers of the adaptive quadrature, reusable across evaluations.
#[derive(Debug, Clone, Default)]
pub(super) struct QuadratureScratch {
    /// Edges of the panels the last evaluation accepted.
    pub(super) accepted: Vec<f64>,
    /// Panels awaiting acceptance or bisection.
    stack: Vec<(Panel, PanelSums)>,
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{rule_error, sample_curve, unit};
    use super::*;
    use nalgebra::Point3;

    #[test]
    fn quadrature_rules_integrate_polynomials_exactly() {
        for degree in 0..=31 {
            let kronrod = rule_error(&KRONROD_NODES, &KRONROD_WEIGHTS, degree);
            assert!(kronrod < 1e-15, "Kronrod, degree {degree}");
            if degree <= 19 {
                let gauss = rule_error(&KRONROD_NODES, &GAUSS_WEIGHTS, degree);
                assert!(gauss < 1e-15, "Gauss 10, degree {degree}");
            }
        }
    }

    /// With `α(v0 + v1) = 2(P1 − P0)` the cubic term vanishes: a parabola, whose arc length
    /// has the closed form `∫ |a + b t| dt`.
    #[test]
    fn parabola_arc_length_matches_closed_form() {
        let width = 0.3;
        let alpha = 2.0_f64.sqrt() * width;
        let curve = HermiteCurve::new(
            Point3::origin(),
            unit(1.0, 0.0, 1.0),
            Point3::new(width, 0.0, 0.0),
            unit(1.0, 0.0, -1.0),
            alpha,
        );
        // p'(t) = a + b t with a = α v0, b = 2 c2.
        let a = alpha * Vector3::new(1.0, 0.0, 1.0) / 2.0_f64.sqrt();
        let b = curve.derivative(1.0) - curve.derivative(0.0);
        let antiderivative = |t: f64| {
            // ∫ sqrt(A t² + B t + C) dt for the quadratic |a + b t|².
            let (qa, qb, qc) = (b.dot(&b), 2.0 * a.dot(&b), a.dot(&a));
            let u = t + qb / (2.0 * qa);
            let k = qc / qa - (qb / (2.0 * qa)).powi(2);
            let r = (u * u + k).sqrt();
            qa.sqrt() * 0.5 * (u * r + k * (u + r).ln())
        };
        let exact = antiderivative(1.0) - antiderivative(0.0);
        let length = curve.arc_length();
        assert!(
            ((length - exact) / exact).abs() < 1e-14,
            "{length} vs {exact}"
        );
    }

    #[test]
    fn straight_aligned_curve_has_chord_length_on_its_flat_stretch() {
        let curve = HermiteCurve::new(
            Point3::origin(),
            unit(0.0, 0.0, 1.0),
            Point3::new(0.0, 0.0, 0.2),
            unit(0.0, 0.0, 1.0),
            0.5,
        );
        assert!((curve.arc_length() - 0.2).abs() < 1e-15);
    }

    #[test]
    fn alpha_root_reproduces_the_target_length() {
        let curve = sample_curve();
        for target in [0.53, 0.6, 1.0, 3.0] {
            let alpha = curve.alpha_for_arc_length(target).unwrap();
            let length = curve.with_alpha(alpha).arc_length();
            assert!((length - target).abs() < 1e-12, "{target}: {length}");
        }
    }

    /// The bow root on the increasing branch, also when the unbowed curve bulges against the
    /// bow direction (then `L(β)` first decreases).
    #[test]
    fn bow_root_reproduces_the_target_length_on_the_increasing_branch() {
        let chord = Point3::new(0.3, 0.0, 0.0);
        let tilted = HermiteCurve::new(
            Point3::origin(),
            unit(1.0, 0.0, 0.6),
            chord,
            unit(1.0, 0.0, -0.6),
            0.3,
        );
        for (curve, n) in [
            (tilted.clone(), unit(0.0, 0.0, -1.0)),
            (tilted, unit(0.0, 0.0, 1.0)),
            (
                HermiteCurve::new(
                    Point3::origin(),
                    unit(1.0, 0.0, 0.0),
                    chord,
                    unit(1.0, 0.0, 0.0),
                    0.3,
                ),
                unit(0.0, 1.0, 0.0),
            ),
        ] {
            let bowed = curve.with_bow(n, 0.0);
            for target in [0.35, 0.4, 0.6] {
                let bow = bowed.bow_for_arc_length(target).unwrap();
                let mut solved = bowed.clone();
                solved.set_bow(bow);
                let (length, slope) = solved.arc_length_and_slope(CurveParameter::Bow);
                assert!((length - target).abs() < 1e-12, "{target}: {length}");
                assert!(bow > 0.0 && slope > 0.0, "β {bow}, dL/dβ {slope}");
            }
        }
    }

    #[test]
    fn alpha_root_handles_coincident_ends_and_cusps() {
        // P0 = P1 with equal tangents: p' vanishes twice (a folded straight line).
        let curve = HermiteCurve::new(
            Point3::origin(),
            unit(0.0, 0.0, 1.0),
            Point3::origin(),
            unit(0.0, 0.0, 1.0),
            0.0,
        );
        let alpha = curve.alpha_for_arc_length(0.3).unwrap();
        // |p'| = α |1 − 6t + 6t²|, and ∫₀¹ |1 − 6t + 6t²| dt = 2/(3√3) (roots at (3 ± √3)/6).
        let exact_alpha = 0.3 / (2.0 / (3.0 * 3.0_f64.sqrt()));
        assert!(
            (alpha - exact_alpha).abs() < 1e-11,
            "{alpha} vs {exact_alpha}"
        );
    }

    #[test]
    fn root_find_reports_unreachable_and_invalid_targets() {
        let curve = sample_curve();
        let chord = curve.chord_length();
        assert!(matches!(
            curve.alpha_for_arc_length(0.5 * chord),
            Err(ArcLengthError::BelowChord { .. })
        ));
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            assert!(matches!(
                curve.alpha_for_arc_length(bad),
                Err(ArcLengthError::InvalidInput { .. })
            ));
        }
        assert_eq!(curve.alpha_for_arc_length(chord).unwrap(), 0.0);
        // At α = 0.37 the curve is longer than 1.01 × chord already.
        let bowed = curve.with_bow(unit(0.0, 0.0, 1.0), 0.0);
        assert!(matches!(
            bowed.bow_for_arc_length(1.01 * chord),
            Err(ArcLengthError::BelowZeroParameter { .. })
        ));
    }

    /// The adaptive rule against a 20 000-panel composite Kronrod rule on bends, loops,
    /// hairpins, coincident ends, coaxial folds, bows and α from 1/10 to 100 times the chord.
    #[test]
    fn adaptive_arc_length_matches_a_fine_composite_rule() {
        let cases = [
            (
                Point3::new(0.3, 0.1, 0.05),
                unit(1.0, 0.0, 0.0),
                unit(0.866, 0.0, 0.5),
            ),
            (
                Point3::new(0.1, 0.0, 0.0),
                unit(0.0, 0.0, 1.0),
                unit(0.0, 0.0, 1.0),
            ),
            (
                Point3::new(0.1, 0.0, 0.0),
                unit(0.0, 0.0, 1.0),
                unit(0.0, 0.0, -1.0),
            ),
            (Point3::origin(), unit(0.0, 0.0, 1.0), unit(1.0, 0.0, 0.0)),
            (
                Point3::new(0.2, 0.0, 0.1),
                unit(0.0, 0.0, 1.0),
                unit(1.0, 0.0, 0.0),
            ),
        ];
        let mut worst: f64 = 0.0;
        for (end, v0, v1) in cases {
            for alpha in [0.01, 0.1, 0.3, 1.0, 3.0, 10.0] {
                let plain = HermiteCurve::new(Point3::origin(), v0, end, v1, alpha);
                for curve in [plain.clone(), plain.with_bow(unit(0.0, 1.0, 0.0), 0.05)] {
                    let panels = 20_000;
                    let alpha_slope = &curve.alpha_sensitivity;
                    let reference: f64 = (0..panels)
                        .map(|i| {
                            let (a, b) = (i as f64 / panels as f64, (i + 1) as f64 / panels as f64);
                            curve
                                .kronrod_panel(&Panel::new(a, b, 0), alpha_slope)
                                .length
                        })
                        .sum();
                    let error = ((curve.arc_length() - reference) / reference).abs();
                    worst = worst.max(error);
                }
            }
        }
        println!("adaptive arc length: worst relative error {worst:.2e}");
        assert!(worst < 1e-13);
    }

    /// Coaxial guides: on the axis `|p'| = |f(t)|` with the quadratic
    /// `f = 6d(t − t²) + α(1 − 6t + 6t²)`, whose integral is exact piecewise between its roots.
    /// For α > 3d the curve folds back (two cusps, kinks of `|p'|` on panel edges).
    #[test]
    fn adaptive_arc_length_is_exact_across_the_cusps_of_a_coaxial_fold() {
        let d = 0.1;
        let mut worst: f64 = 0.0;
        for alpha in [0.05, 0.1, 0.3, 0.31, 1.0, 3.0, 10.0] {
            let axis = unit(0.0, 0.0, 1.0);
            let curve = HermiteCurve::new(
                Point3::origin(),
                axis,
                Point3::new(0.0, 0.0, d),
                axis,
                alpha,
            );
            let (a, b, c) = (6.0 * (alpha - d), 6.0 * (d - alpha), alpha);
            let antiderivative = |t: f64| a * t * t * t / 3.0 + b * t * t / 2.0 + c * t;
            let discriminant = b * b - 4.0 * a * c;
            let mut edges = vec![0.0];
            if discriminant > 0.0 && a != 0.0 {
                let root = discriminant.sqrt();
                let mut roots = [(-b - root) / (2.0 * a), (-b + root) / (2.0 * a)];
                roots.sort_by(f64::total_cmp);
                edges.extend(roots.iter().filter(|r| **r > 0.0 && **r < 1.0));
            }
            edges.push(1.0);
            let exact: f64 = edges
                .windows(2)
                .map(|w| (antiderivative(w[1]) - antiderivative(w[0])).abs())
                .sum();
            let error = ((curve.arc_length() - exact) / exact).abs();
            println!(
                "coaxial, α = {alpha}: {} cusps, relative error {error:.2e}",
                edges.len() - 2
            );
            worst = worst.max(error);
        }
        assert!(worst < 1e-13, "{worst:e}");
    }
}
