//! The search for a split's (or travel's) least energy: Brent's method on a bracket, and a
//! window around a previous split first.

use super::SPLIT_TOLERANCE_M;
use crate::statics::StaticsError;

/// Half the window around a previous split or travel searched first (m).
const NEAR_WINDOW_M: f64 = 0.02;

/// [`least_energy`] on the window of ±[`NEAR_WINDOW_M`] around `near` (within `[low, high]`)
/// first, then on the whole range when the least lies at an edge of the window inside it.
pub(super) fn least_near(
    (low, high): (f64, f64),
    near: Option<f64>,
    stops: &[f64],
    mut energy: impl FnMut(f64) -> Result<f64, StaticsError>,
) -> Result<(f64, usize), StaticsError> {
    let Some(near) = near.filter(|n| n.is_finite()) else {
        return least_energy((low, high), stops, energy);
    };
    let window = (
        (near - NEAR_WINDOW_M).max(low),
        (near + NEAR_WINDOW_M).min(high),
    );
    if window.0 >= window.1 {
        return least_energy((low, high), stops, energy);
    }
    let (at, evaluations) = least_energy(window, stops, &mut energy)?;
    let near_edge = |edge: f64| (at - edge).abs() <= 4.0 * SPLIT_TOLERANCE_M;
    if (window.0 > low && near_edge(window.0)) || (window.1 < high && near_edge(window.1)) {
        let (at, more) = least_energy((low, high), stops, energy)?;
        return Ok((at, evaluations + more));
    }
    Ok((at, evaluations))
}

/// The argument of least `energy` on `[low, high]` (Brent's method: parabolic steps through
/// the three best points, golden-section steps where those do not shrink the bracket, to
/// [`SPLIT_TOLERANCE_M`]), then compared with the `stops` (ends of the interval where a
/// stop holds the cable), and the evaluations it took. The energy of a split is smooth, so
/// the parabolic steps converge superlinearly: 10 to 15 evaluations where golden sections
/// alone take 35.
fn least_energy(
    (low, high): (f64, f64),
    stops: &[f64],
    mut energy: impl FnMut(f64) -> Result<f64, StaticsError>,
) -> Result<(f64, usize), StaticsError> {
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    const MAX_EVALUATIONS: usize = 100;
    let (mut a, mut b) = (low, high);
    let mut x = a + GOLDEN * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = energy(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let mut evaluations = 1;
    // The step before last, and the last one.
    let (mut e, mut d): (f64, f64) = (0.0, 0.0);
    while evaluations < MAX_EVALUATIONS {
        let middle = 0.5 * (a + b);
        let tol = 0.5 * SPLIT_TOLERANCE_M;
        if (x - middle).abs() <= 2.0 * tol - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // The parabola through x, w and v.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let previous = e;
            if p.abs() < (0.5 * q * previous).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = tol.copysign(middle - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= middle { a - x } else { b - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = energy(u)?;
        evaluations += 1;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    // A least at a stop: the search closes in on it from inside; the stop itself is exact.
    let mut best = (fx, x);
    for &stop in stops {
        if (stop - x).abs() <= 4.0 * SPLIT_TOLERANCE_M {
            best = (energy(stop)?, stop);
            evaluations += 1;
        }
    }
    Ok((best.1, evaluations))
}
