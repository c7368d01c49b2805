//! Parameters of points at equal arc length along a [`HermiteCurve`]: a table of cumulative
//! arc length by the 5-point Gauss–Legendre rule, a quintic Hermite guess of `t(s)` per node
//! and a Newton correction, all on the speed polynomial `|p'|²`.

use super::HermiteCurve;

/// Nodes of the 5-point Gauss–Legendre rule on `[−1, 1]`, `±⅓√(5 ± 2√(10/7))` and 0: the
/// reference rule of the tests.
#[cfg(test)]
const GAUSS5_NODES: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683,
    0.0,
    0.538_469_310_105_683,
    0.906_179_845_938_664,
];
/// Weights of the 5-point Gauss–Legendre rule, `(322 ∓ 13√70)/900` and `128/225`; exact for
/// polynomials up to degree 9.
#[cfg(test)]
const GAUSS5_WEIGHTS: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];
/// Interior nodes of the 6-point Gauss–Lobatto rule on `[−1, 1]`, `±√(⅓ ∓ 2√7/21)`; the
/// other two are the ends.
const LOBATTO_NODES: [f64; 4] = [
    -0.765_055_323_929_464_7,
    -0.285_231_516_480_645_1,
    0.285_231_516_480_645_1,
    0.765_055_323_929_464_7,
];
/// Weights of the interior nodes of the 6-point Gauss–Lobatto rule, `(14 ∓ √7)/30`.
const LOBATTO_WEIGHTS: [f64; 4] = [
    0.378_474_956_297_847,
    0.554_858_377_035_486_4,
    0.554_858_377_035_486_4,
    0.378_474_956_297_847,
];
/// Weight of each end of the 6-point Gauss–Lobatto rule, `1/15`. The rule is exact for
/// polynomials up to degree 9 like the 5-point Gauss rule, with an error constant only 1.2
/// times larger, and it shares its end values with the neighbouring panels and with the
/// Newton step: 4 new speeds per panel instead of 5.
const LOBATTO_END_WEIGHT: f64 = 1.0 / 15.0;

/// Fewest panels of the arc-length table of `equal_arc_length_parameters`.
const MIN_TABLE_PANELS: usize = 32;
/// Table panels integrated together (their 32 interior and 8 edge speeds in one vectorized
/// pass).
const TABLE_BATCH: usize = 8;
/// Nodes whose first Newton step is taken together (their 40 speeds in one pass).
const NODE_BATCH: usize = 8;
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
    /// usually after one step. The speed is evaluated as the square root of the polynomial
    /// `|p'|²` (degree 6), a third of the work of forming `p'`. `L` is the table's own total,
    /// so the spacing is consistent up to `t_S = 1`. Across a cusp (`v = 0`) the rule is less
    /// accurate locally (pieces off by ~1e-6 m), which shifts nodes along the curve but never
    /// breaks their order.
    pub fn equal_arc_length_parameters(&self, segments: usize) -> Vec<f64> {
        let mut params = Vec::with_capacity(segments + 1);
        params.push(0.0);
        if segments == 0 {
            return params;
        }
        let speed = SpeedPolynomial::new(self);
        let table = speed.table(segments.max(MIN_TABLE_PANELS));
        let total = table[table.len() - 1].length;
        let targets = (1..segments).map(|k| total * (k as f64 / segments as f64));
        let mut panel = 0;
        let mut batch = NodeBatch::default();
        for target in targets {
            // Targets ascend, so the panel search only moves forward.
            while panel + 2 < table.len() && table[panel + 1].length < target {
                panel += 1;
            }
            batch.push(panel, target, &table);
            if batch.count == NODE_BATCH {
                batch.solve(&speed, &table, &mut params);
            }
        }
        batch.solve(&speed, &table, &mut params);
        params.push(1.0);
        params
    }

    /// `∫ₐᵇ |p'| dt` by the 5-point Gauss–Legendre rule (m), from `p'` itself: the reference
    /// of the tests.
    #[cfg(test)]
    fn gauss_length(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut sum = 0.0;
        for i in 0..5 {
            sum += GAUSS5_WEIGHTS[i] * self.derivative(mid + half * GAUSS5_NODES[i]).norm();
        }
        sum * half
    }
}

/// The speed of a curve through polynomials: `|p'|² = Σ a_k t^k` (degree 6) and
/// `p'·p'' = Σ g_k t^k` (degree 5), so that `v = √|p'|²` and `v' = p'·p''/v`.
struct SpeedPolynomial {
    squared: [f64; 7],
    slope: [f64; 6],
}

impl SpeedPolynomial {
    fn new(curve: &HermiteCurve) -> Self {
        let d = &curve.velocity;
        let mut squared = [0.0; 7];
        for (i, d_i) in d.iter().enumerate() {
            for (j, d_j) in d.iter().enumerate() {
                squared[i + j] += d_i.dot(d_j);
            }
        }
        // d/dt |p'|² = 2 p'·p''.
        let slope = std::array::from_fn(|k| 0.5 * (k + 1) as f64 * squared[k + 1]);
        Self { squared, slope }
    }

    /// `|p'(t)|`; round-off near a cusp cannot make it NaN.
    #[inline]
    fn speed(&self, t: f64) -> f64 {
        let [a0, a1, a2, a3, a4, a5, a6] = self.squared;
        let squared = a0 + t * (a1 + t * (a2 + t * (a3 + t * (a4 + t * (a5 + t * a6)))));
        squared.max(0.0).sqrt()
    }

    /// `∫ₐᵇ |p'| dt` by the 6-point Gauss–Lobatto rule (m), given the speeds at the ends.
    #[inline]
    fn partial_length(&self, a: f64, b: f64, speed_a: f64, speed_b: f64) -> f64 {
        let interior = self.speeds(&lobatto_points(a, b));
        lobatto_integral(a, b, speed_a, speed_b, &interior)
    }

    /// `|p'|` at each of `points`: one flat loop, so that the compiler vectorizes the square
    /// roots and the independent evaluations overlap.
    #[inline]
    fn speeds<const N: usize>(&self, points: &[f64; N]) -> [f64; N] {
        let mut speeds = [0.0; N];
        for (speed, &t) in speeds.iter_mut().zip(points) {
            *speed = self.speed(t);
        }
        speeds
    }

    /// Cumulative arc length on `panels` equal parameter panels: `panels + 1` entries. The
    /// panels are integrated [`TABLE_BATCH`] at a time, their interior Lobatto points and
    /// right edges in one vectorized pass (independent, so they overlap).
    fn table(&self, panels: usize) -> Vec<TableEntry> {
        let edge = |i: usize| i as f64 / panels as f64;
        let mut table = Vec::with_capacity(panels + 1);
        table.push(self.table_entries(&[0.0])[0]);
        for first in (0..panels).step_by(TABLE_BATCH) {
            let count = TABLE_BATCH.min(panels - first);
            let mut points = [0.0; TABLE_BATCH * 4];
            let mut edges = [1.0; TABLE_BATCH];
            for (b, chunk) in points.chunks_exact_mut(4).enumerate().take(count) {
                let i = first + b;
                chunk.copy_from_slice(&lobatto_points(edge(i), edge(i + 1)));
                edges[b] = edge(i + 1);
            }
            let speeds = self.speeds(&points);
            let mut entries = self.table_entries(&edges);
            let mut left = table[table.len() - 1];
            for (entry, interior) in entries.iter_mut().zip(speeds.chunks_exact(4)).take(count) {
                let piece = lobatto_integral(left.t, entry.t, left.speed, entry.speed, interior);
                entry.length = left.length + piece;
                left = *entry;
            }
            table.extend_from_slice(&entries[..count]);
        }
        table
    }

    /// Table entries at parameters `ts` (lengths left 0): the speed, its slope and the
    /// derivatives of `t(s)` for the quintic guess, in one vectorized pass.
    #[inline]
    fn table_entries<const N: usize>(&self, ts: &[f64; N]) -> [TableEntry; N] {
        let speeds = self.speeds(ts);
        std::array::from_fn(|i| {
            let (t, speed) = (ts[i], speeds[i]);
            let inverse_speed = 1.0 / speed;
            let speed_slope = horner(&self.slope, t) * inverse_speed;
            TableEntry {
                t,
                length: 0.0,
                speed,
                speed_slope,
                inverse_speed,
                bend: -speed_slope * inverse_speed * inverse_speed * inverse_speed,
            }
        })
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
            let speed = self.speed(t);
            let residual =
                start.length + self.partial_length(start.t, t, start.speed, speed) - target;
            if residual < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - residual / speed;
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
}

/// `∫ₐᵇ f` by the 6-point Gauss–Lobatto rule from the end values `f(a)`, `f(b)` and the
/// `interior` values at [`LOBATTO_NODES`].
#[inline]
fn lobatto_integral(a: f64, b: f64, f_a: f64, f_b: f64, interior: &[f64]) -> f64 {
    let mut sum = LOBATTO_END_WEIGHT * (f_a + f_b);
    for (w, f) in LOBATTO_WEIGHTS.iter().zip(interior) {
        sum += w * f;
    }
    sum * (0.5 * (b - a))
}

/// The interior points of the 6-point Gauss–Lobatto rule on `[a, b]`.
#[inline]
fn lobatto_points(a: f64, b: f64) -> [f64; 4] {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    LOBATTO_NODES.map(|x| mid + half * x)
}

/// Up to [`NODE_BATCH`] nodes awaiting their parameter: table panel, target arc length and
/// quintic guess each.
#[derive(Debug, Default)]
struct NodeBatch {
    count: usize,
    panels: [usize; NODE_BATCH],
    targets: [f64; NODE_BATCH],
    guesses: [f64; NODE_BATCH],
}

impl NodeBatch {
    fn push(&mut self, panel: usize, target: f64, table: &[TableEntry]) {
        let i = self.count;
        self.panels[i] = panel;
        self.targets[i] = target;
        self.guesses[i] = quintic_inverse(&table[panel], &table[panel + 1], target);
        self.count += 1;
    }

    /// The nodes' parameters, appended to `params` (never below the previous one): the first
    /// Newton step of all nodes at once — their speeds in one vectorized pass — and the
    /// safeguarded iteration of [`SpeedPolynomial::invert_partial_length`] for any node that
    /// step does not settle.
    fn solve(&mut self, speed: &SpeedPolynomial, table: &[TableEntry], params: &mut Vec<f64>) {
        // Per node: the interior Lobatto points of [panel start, guess], then the guess itself.
        // Unused slots evaluate harmless copies of the first node.
        let mut points = [0.0; NODE_BATCH * 5];
        for (i, chunk) in points.chunks_exact_mut(5).enumerate() {
            let node = if i < self.count { i } else { 0 };
            let start = &table[self.panels[node]];
            let t = self.guesses[node].clamp(start.t, table[self.panels[node] + 1].t);
            chunk[..4].copy_from_slice(&lobatto_points(start.t, t));
            chunk[4] = t;
        }
        let speeds = speed.speeds(&points);
        for i in 0..self.count {
            let (start, end) = (&table[self.panels[i]], &table[self.panels[i] + 1]);
            let chunk = &speeds[5 * i..5 * i + 5];
            let t = points[5 * i + 4];
            let partial = lobatto_integral(start.t, t, start.speed, chunk[4], &chunk[..4]);
            let residual = start.length + partial - self.targets[i];
            let settled = settled_newton_step(start, end, t, residual, chunk[4]);
            let t = settled.unwrap_or_else(|| {
                speed.invert_partial_length(start, end, self.guesses[i], self.targets[i])
            });
            let previous = params.last().copied().unwrap_or(0.0);
            params.push(t.max(previous));
        }
        self.count = 0;
    }
}

/// The first step of [`SpeedPolynomial::invert_partial_length`] from `t` (arc-length
/// `residual`, speed `v`), if it ends that iteration: a Newton step inside the bracket whose
/// left error `|v'|δ²/2` is below [`PIECE_TOLERANCE`].
fn settled_newton_step(
    start: &TableEntry,
    end: &TableEntry,
    t: f64,
    residual: f64,
    speed: f64,
) -> Option<f64> {
    let (lo, hi) = if residual < 0.0 {
        (t, end.t)
    } else {
        (start.t, t)
    };
    let newton = t - residual / speed;
    let curvature = 0.5 * start.speed_slope.abs().max(end.speed_slope.abs());
    let step = newton - t;
    (newton >= lo && newton <= hi && curvature * step * step <= PIECE_TOLERANCE).then_some(newton)
}

/// `Σ c_k t^k` by Horner's rule.
#[inline]
fn horner(coefficients: &[f64], t: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |sum, c| sum * t + c)
}

/// One edge of the arc-length table of [`HermiteCurve::equal_arc_length_parameters`].
#[derive(Debug, Clone, Copy, Default)]
struct TableEntry {
    t: f64,
    /// Arc length from `t = 0` (m).
    length: f64,
    /// `v = |p'(t)|` (m per unit parameter).
    speed: f64,
    /// `v' = p'·p''/v` (m per unit parameter²).
    speed_slope: f64,
    /// `dt/ds = 1/v`.
    inverse_speed: f64,
    /// `d²t/ds² = −v'/v³`.
    bend: f64,
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
    let slope = |e: &TableEntry| span * e.inverse_speed;
    let bend = |e: &TableEntry| span * span * e.bend;
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

#[cfg(test)]
mod probe_rules {
    use super::super::test_support::{sample_curve, unit};
    use super::*;
    #[test]
    fn probe_rule_errors() {
        let bowed = sample_curve()
            .with_alpha(0.5)
            .with_bow(unit(0.0, 0.0, 1.0), 0.1);
        let speed = SpeedPolynomial::new(&bowed);
        for panels in [32usize, 40, 64] {
            let (mut worst_g, mut worst_l, mut worst_gp) = (0.0f64, 0.0f64, 0.0f64);
            for i in 0..panels {
                let (a, b) = (i as f64 / panels as f64, (i + 1) as f64 / panels as f64);
                let reference: f64 = (0..200)
                    .map(|j| {
                        let h = (b - a) / 200.0;
                        bowed.gauss_length(a + j as f64 * h, a + (j + 1) as f64 * h)
                    })
                    .sum();
                let g = bowed.gauss_length(a, b);
                let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
                let gp: f64 = (0..5)
                    .map(|k| GAUSS5_WEIGHTS[k] * speed.speed(mid + half * GAUSS5_NODES[k]))
                    .sum::<f64>()
                    * half;
                let l = speed.partial_length(a, b, speed.speed(a), speed.speed(b));
                worst_g = worst_g.max((g - reference).abs());
                worst_gp = worst_gp.max((gp - reference).abs());
                worst_l = worst_l.max((l - reference).abs());
            }
            println!(
                "panels {panels}: gauss(vector) {worst_g:.2e} gauss(poly) {worst_gp:.2e} lobatto(poly) {worst_l:.2e}"
            );
        }
    }
}
