//! Rainflow counting (ASTM E1049-85, section 5.4.4): the cycles of a load history, each a
//! range and a count (1 for a closed cycle, ½ for a half).
//!
//! Two forms of one three-point rule (ranges X, the newest, and Y, the one before):
//!
//! - [`cycles`] counts a finite history as the standard does: a range that contains the
//!   history's first point counts ½ when it closes, and what is left at the end counts ½
//!   per range. Its reversals and its cycles, in order, are those of the PyPI package
//!   `rainflow` 3.2.0 (tests/data/rainflow).
//! - [`Counter`] counts a history point by point, keeping only the ranges not yet closed,
//!   as a repeating one: [`Counter::close_periodic`] counts what is left as the history
//!   repeated, starting at its largest peak, so that every cycle closes. A motion program
//!   runs over and over: one pass of it is one cycle of the history.

/// One counted range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// Peak-to-valley range (the history's unit).
    pub range: f64,
    /// Mean of its peak and valley.
    pub mean: f64,
    /// 1 for a closed cycle, 0.5 for a half cycle.
    pub count: f64,
    /// Index in the history of its first reversal.
    pub start: usize,
    /// Index of its second reversal.
    pub end: usize,
}

impl Cycle {
    fn between((i, x): (usize, f64), (j, y): (usize, f64), count: f64) -> Cycle {
        Cycle {
            range: (x - y).abs(),
            mean: 0.5 * (x + y),
            count,
            start: i,
            end: j,
        }
    }
}

/// The turning points of `values` with their indices: the first and the last value, and
/// every value where the history changes direction (of a run of equal values, the last one).
/// Empty for fewer than two values.
pub fn reversals(values: &[f64]) -> Vec<(usize, f64)> {
    let [first, second, rest @ ..] = values else {
        return Vec::new();
    };
    let mut out = vec![(0, *first)];
    let (mut x, mut slope) = (*second, second - first);
    let mut index = 1;
    for (k, &next) in rest.iter().enumerate() {
        index = k + 2;
        if next == x {
            continue;
        }
        let next_slope = next - x;
        if slope * next_slope < 0.0 {
            out.push((index - 1, x));
        }
        x = next;
        slope = next_slope;
    }
    out.push((index, x));
    out
}

/// The rainflow cycles of a finite history, in the order they are counted.
pub fn cycles(values: &[f64]) -> Vec<Cycle> {
    let mut out = Vec::new();
    let mut points: Vec<(usize, f64)> = Vec::new();
    for point in reversals(values) {
        points.push(point);
        while let [.., a, b, c] = points[..] {
            let (x, y) = ((c.1 - b.1).abs(), (b.1 - a.1).abs());
            if x < y {
                break;
            }
            if points.len() == 3 {
                // Y holds the history's first point: half a cycle, and that point goes.
                out.push(Cycle::between(a, b, 0.5));
                points.remove(0);
            } else {
                out.push(Cycle::between(a, b, 1.0));
                points.truncate(points.len() - 3);
                points.push(c);
            }
        }
    }
    out.extend(points.windows(2).map(|w| Cycle::between(w[0], w[1], 0.5)));
    out
}

/// Rainflow counting one point at a time, for a history that repeats: each closed cycle is
/// handed on as it closes; the ranges still open stay (at most one per reversal of the
/// history's envelope) until [`Counter::close_periodic`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Counter {
    /// Reversals not yet part of a closed cycle, then the newest value (which may still move
    /// on in its direction).
    open: Vec<f64>,
    /// Direction of the newest run: +1 rising, −1 falling, 0 before the first change.
    direction: f64,
}

impl Counter {
    /// Takes in the next value of the history; `closed(range)` for every cycle it closes.
    pub fn push(&mut self, value: f64, mut closed: impl FnMut(f64)) {
        let Some(&last) = self.open.last() else {
            self.open.push(value);
            return;
        };
        let step = value - last;
        if step == 0.0 {
            return;
        }
        let direction = step.signum();
        if direction == self.direction {
            // Still running the same way: the newest point moves on.
            *self.open.last_mut().expect("not empty") = value;
        } else {
            // The newest point was a reversal; the value starts a run the other way.
            self.open.push(value);
        }
        self.direction = direction;
        self.close_inner(&mut closed);
    }

    /// The four-point rule over the open reversals, the newest point included (it only
    /// moves away from the one before it, so a range it closes stays closed): the inner
    /// range of four consecutive points closes when both its neighbours reach past it.
    fn close_inner(&mut self, closed: &mut impl FnMut(f64)) {
        while let [.., a, b, c, d] = self.open[..] {
            let inner = (c - b).abs();
            if inner > (d - c).abs() || inner > (b - a).abs() {
                return;
            }
            closed(inner);
            let n = self.open.len();
            self.open.drain(n - 3..n - 1);
        }
    }

    /// The cycles left open, counted as the history repeated: the open reversals turned to
    /// start and end at their largest value, then counted; every range closes (half cycles
    /// come in pairs of one range). Consumes the counter.
    pub fn close_periodic(self, mut closed: impl FnMut(f64, f64)) {
        let Some(top) = (0..self.open.len()).max_by(|&i, &j| self.open[i].total_cmp(&self.open[j]))
        else {
            return;
        };
        let mut turned: Vec<f64> = self.open[top..].to_vec();
        turned.extend_from_slice(&self.open[..=top]);
        for cycle in cycles(&turned) {
            closed(cycle.range, cycle.count);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard's worked example (ASTM E1049-85, 5.4.4, Fig. 6): ranges 3, 4, 6, 8, 9
    /// counted 0.5, 1.5, 0.5, 1.0, 0.5.
    #[test]
    fn the_standards_example_counts_as_its_table() {
        let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
        let mut by_range: Vec<(f64, f64)> = Vec::new();
        for c in cycles(&history) {
            match by_range.iter_mut().find(|(r, _)| *r == c.range) {
                Some((_, count)) => *count += c.count,
                None => by_range.push((c.range, c.count)),
            }
        }
        by_range.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(
            by_range,
            vec![(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]
        );
    }

    /// A sine repeated n times closes n cycles of its full range, whatever its phase.
    #[test]
    fn a_repeated_sine_is_one_closed_cycle_per_period() {
        for phase in [0.0, 0.3, 1.7, 3.0] {
            let mut counter = Counter::default();
            let mut counted: Vec<(f64, f64)> = Vec::new();
            let period = 40;
            for k in 0..3 * period {
                let v = (phase + std::f64::consts::TAU * k as f64 / period as f64).sin();
                counter.push(v, |r| counted.push((r, 1.0)));
            }
            counter.close_periodic(|r, c| counted.push((r, c)));
            let total: f64 = counted.iter().map(|(_, c)| c).sum();
            let big: f64 = counted
                .iter()
                .filter(|(r, _)| *r > 1.9)
                .map(|(_, c)| c)
                .sum();
            assert!((big - 3.0).abs() < 1e-12, "phase {phase}: {counted:?}");
            assert!((total - 3.0).abs() < 1e-12, "phase {phase}: {counted:?}");
        }
    }
}
