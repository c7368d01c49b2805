//! Parameters of points at equal arc length along a [`HermiteCurve`]: a table of cumulative
//! arc length by the 5-point Gauss–Legendre rule, a quintic Hermite guess of `t(s)` per node
//! and a Newton correction.

use super::HermiteCurve;

/// Nodes of the 5-point Gauss–Legendre rule on `[−1, 1]`, `±⅓√(5 ± 2√(10/7))` and 0.
const GAUSS5_NODES: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683,
    0.0,
    0.538_469_310_105_683,
    0.906_179_845_938_664,
];
/// Weights of the 5-point Gauss–Legendre rule, `(322 ∓ 13√70)/900` and `128/225`; exact for
/// polynomials up to degree 9.
const GAUSS5_WEIGHTS: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];

/// Fewest panels of the arc-length table of `equal_arc_length_parameters`.
const MIN_TABLE_PANELS: usize = 32;
/// Iteration limit of the Newton/bisection inversion of `s(t)` for one node.
const MAX_INVERSION_ITERATIONS: usize = 100;
/// Arc-length error (m) at which the Newton iteration for one node stops.
const PIECE_TOLERANCE: f64 = 1e-12;

impl HermiteCurve {
    /// Parameters `t_0 = 0 < t_1 < … < t_S = 1` of `S + 1` points at equal arc length `L/S`
    /// (`segments = S`; `[0]` for `S = 0`).
    ///
    /// The cumulative arc length is tabulated on `max(S, 32)` equal parameter panels with the
    /// 5-point Gauss–Legendre rule (a panel spans one node spacing on average, over which a degree-9
    /// rule is accurate to ~1e-16 relative on smooth curves), together with the speed
    /// `v = |p'|` and its slope `v' = p'·p''/v` at the panel edges. Each interior `t_k` starts
    /// from the quintic Hermite interpolant of `t(s)` in its panel (`dt/ds = 1/v`,
    /// `d²t/ds² = −v'/v³`) and is corrected by Newton's method on `s(t) = k L/S`, the partial
    /// panel integrated by the same rule, safeguarded by bisection. A Newton step `δ` leaves an
    /// arc-length error of about `|v'|δ²/2`; the iteration stops once that is below 1e-12 m,
    /// usually after one step. The nodes do not depend on each other, so their iterations
    /// overlap in the processor. `L` is the table's own total, so the spacing is consistent up
    /// to `t_S = 1`. Across a cusp (`v = 0`) the rule is less accurate locally (pieces off by
    /// ~1e-6 m), which shifts nodes along the curve but never breaks their order.
    pub fn equal_arc_length_parameters(&self, segments: usize) -> Vec<f64> {
        let mut params = Vec::with_capacity(segments + 1);
        params.push(0.0);
        if segments == 0 {
            return params;
        }
        let panels = segments.max(MIN_TABLE_PANELS);
        let edge = |i: usize| i as f64 / panels as f64;
        let mut table = Vec::with_capacity(panels + 1);
        table.push(self.table_entry(0.0, 0.0));
        let mut total = 0.0;
        for i in 0..panels {
            total += self.gauss_length(edge(i), edge(i + 1));
            table.push(self.table_entry(edge(i + 1), total));
        }
        let mut panel = 0;
        for k in 1..segments {
            let target = total * (k as f64 / segments as f64);
            while panel + 1 < panels && table[panel + 1].length < target {
                panel += 1;
            }
            let (start, end) = (&table[panel], &table[panel + 1]);
            let guess = quintic_inverse(start, end, target);
            let t = self.invert_partial_length(start, end, guess, target);
            let previous = params.last().copied().unwrap_or(0.0);
            params.push(t.max(previous));
        }
        params.push(1.0);
        params
    }

    /// Parameter, cumulative arc length, speed and speed slope at one table edge.
    fn table_entry(&self, t: f64, length: f64) -> TableEntry {
        let (velocity, acceleration) = (self.derivative(t), self.second_derivative(t));
        let speed = velocity.norm();
        TableEntry {
            t,
            length,
            speed,
            speed_slope: velocity.dot(&acceleration) / speed,
        }
    }

    /// The parameter in the panel `[start.t, end.t]` where the arc length reaches `target`,
    /// from `guess`: Newton with slope `|p'|`, bisection when a step leaves the panel. Stops
    /// once the error the last step leaves (`|v'|δ²/2`) is below [`PIECE_TOLERANCE`].
    fn invert_partial_length(
        &self,
        start: &TableEntry,
        end: &TableEntry,
        guess: f64,
        target: f64,
    ) -> f64 {
        let (mut lo, mut hi) = (start.t, end.t);
        let mut t = guess.clamp(lo, hi);
        let curvature = 0.5 * start.speed_slope.abs().max(end.speed_slope.abs());
        for _ in 0..MAX_INVERSION_ITERATIONS {
            let residual = start.length + self.gauss_length(start.t, t) - target;
            if residual < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - residual / self.derivative(t).norm();
            let inside = newton >= lo && newton <= hi;
            let next = if inside { newton } else { 0.5 * (lo + hi) };
            let step = next - t;
            // NaN (a non-finite curve) ends the loop through the iteration limit.
            let done = (inside && curvature * step * step <= PIECE_TOLERANCE)
                || hi - lo <= 4.0 * f64::EPSILON;
            t = next;
            if done {
                break;
            }
        }
        t
    }

    /// `∫ₐᵇ |p'| dt` by the 5-point Gauss–Legendre rule (m).
    #[inline]
    fn gauss_length(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut sum = 0.0;
        for i in 0..5 {
            sum += GAUSS5_WEIGHTS[i] * self.derivative(mid + half * GAUSS5_NODES[i]).norm();
        }
        sum * half
    }
}

/// One edge of the arc-length table of [`HermiteCurve::equal_arc_length_parameters`].
#[derive(Debug, Clone, Copy)]
struct TableEntry {
    t: f64,
    /// Arc length from `t = 0` (m).
    length: f64,
    /// `v = |p'(t)|` (m per unit parameter).
    speed: f64,
    /// `v' = p'·p''/v` (m per unit parameter²).
    speed_slope: f64,
}

/// Quintic Hermite interpolation of `t(s)` on one table panel, from the values and first
/// two derivatives at its ends (`dt/ds = 1/v`, `d²t/ds² = −v'/v³`); linear where a speed
/// vanishes (a cusp).
fn quintic_inverse(start: &TableEntry, end: &TableEntry, target: f64) -> f64 {
    let span = end.length - start.length;
    let width = end.t - start.t;
    if span.is_nan() || span <= 0.0 {
        return start.t + 0.5 * width;
    }
    let u = ((target - start.length) / span).clamp(0.0, 1.0);
    if !(start.speed > 0.0 && end.speed > 0.0) {
        return start.t + u * width;
    }
    // Derivatives with respect to u = (s − s_a)/span.
    let slope = |e: &TableEntry| span / e.speed;
    let bend = |e: &TableEntry| -span * span * e.speed_slope / e.speed.powi(3);
    let (u2, u3) = (u * u, u * u * u);
    let (u4, u5) = (u3 * u, u3 * u2);
    let rise = 10.0 * u3 - 15.0 * u4 + 6.0 * u5;
    start.t
        + width * rise
        + slope(start) * (u - 6.0 * u3 + 8.0 * u4 - 3.0 * u5)
        + slope(end) * (-4.0 * u3 + 7.0 * u4 - 3.0 * u5)
        + bend(start) * 0.5 * (u2 - 3.0 * u3 + 3.0 * u4 - u5)
        + bend(end) * 0.5 * (u3 - 2.0 * u4 + u5)
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{rule_error, sample_curve, unit};
    use super::*;
    use nalgebra::Point3;

    #[test]
    fn the_five_point_rule_integrates_polynomials_exactly() {
        for degree in 0..=9 {
            let error = rule_error(&GAUSS5_NODES, &GAUSS5_WEIGHTS, degree);
            assert!(error < 1e-15, "degree {degree}");
        }
    }

    /// Equal arc-length parameters: every piece has length `L/S` by the adaptive quadrature of
    /// the sub-curve (re-parametrized onto `[t_k, t_{k+1}]`), also across the cusps of a
    /// folded curve.
    #[test]
    fn resampled_parameters_split_the_arc_length_evenly() {
        let bend = sample_curve().with_alpha(0.5);
        let folded = HermiteCurve::new(
            Point3::origin(),
            unit(0.0, 0.0, 1.0),
            Point3::new(0.0, 0.0, 0.1),
            unit(0.0, 0.0, 1.0),
            0.6,
        );
        let bowed = bend.with_bow(unit(0.0, 0.0, 1.0), 0.1);
        for (label, curve, tolerance) in [
            ("bend", &bend, 1e-13),
            ("bowed", &bowed, 1e-13),
            ("folded", &folded, 1e-5),
        ] {
            for segments in [1, 7, 40] {
                let params = curve.equal_arc_length_parameters(segments);
                assert_eq!(params.len(), segments + 1);
                assert_eq!((params[0], params[segments]), (0.0, 1.0));
                let total = curve.arc_length();
                let worst = params
                    .windows(2)
                    .map(|w| (piece_length(curve, w[0], w[1]) - total / segments as f64).abs())
                    .fold(0.0, f64::max);
                println!("{label}, {segments} pieces: worst piece error {worst:.2e} m");
                assert!(worst < tolerance, "{label}: {worst:e}");
            }
        }
    }

    /// Arc length of `p` over `[a, b]`: 2000 panels of the 5-point rule.
    fn piece_length(curve: &HermiteCurve, a: f64, b: f64) -> f64 {
        let panels = 2000;
        (0..panels)
            .map(|i| {
                let lo = a + (b - a) * i as f64 / panels as f64;
                let hi = a + (b - a) * (i + 1) as f64 / panels as f64;
                curve.gauss_length(lo, hi)
            })
            .sum()
    }
}
