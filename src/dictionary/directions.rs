//! Gravity directions sampled on the unit sphere, and the interpolation between them.
//!
//! The sample is the golden-angle (Fibonacci) spiral: point k of N has height
//! `z = 1 − (2k + 1)/N` and azimuth `k·π(3 − √5)`. It is quasi-uniform (every point covers
//! about 4π/N sr), needs no random numbers and is the same on every machine.
//!
//! Its **covering radius** — the largest angle from any direction on the sphere to its
//! nearest sample — bounds how far a motion's direction can be from the stored ones. It is
//! estimated on a 64× denser spiral (at least 16384 points) and rounded up by that spiral's
//! own half spacing.

use crate::attachment::{MARGIN_COUNT, MarginValues};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The default N: covering radius 28.1°. Build time grows linearly with N, while the share of
/// lookups left to an exact check shrinks slowly: measured on the hand-written pick-and-place
/// catalogue (2 cores), N = 16, 32, 64, 128, 256 took 2.8, 4.75, 9.4, 19.4, 38.3 s to build
/// and left 9.6, 8.3, 7.5, 7.2, 6.6 % of link_4's lookups undecided (`info`); a solve of the
/// bundled pick and place with them solved 31, 16, 16, 13, 12 of its C2 pieces exactly, in
/// the same attachment time (0.32–0.40 s). Most undecided pieces change branch somewhere on
/// the sphere and stay undecided at any N (docs/dictionaries.md, "Direction count").
pub const DEFAULT_DIRECTION_COUNT: usize = 32;

/// Fewest directions a build accepts (fewer would leave hemispheres unsampled).
pub const MIN_DIRECTION_COUNT: usize = 8;

/// Most directions a build accepts (a covering radius of about 2°, 16 times the default's
/// build time): `verify` recomputes the covering radius, whose cost grows with N².
pub const MAX_DIRECTION_COUNT: usize = 4096;

/// Densification of the spiral the covering radius is estimated on, and its least size.
const DENSE_FACTOR: usize = 64;
const DENSE_MIN: usize = 16_384;

/// `n` unit vectors of the golden-angle spiral.
pub fn fibonacci_sphere(n: usize) -> Vec<[f64; 3]> {
    let golden_angle = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden_angle * k as f64;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect()
}

/// An upper estimate of the covering radius (rad) of `directions` (unit vectors).
pub fn covering_radius(directions: &[[f64; 3]]) -> f64 {
    let dense = fibonacci_sphere((DENSE_FACTOR * directions.len()).max(DENSE_MIN));
    let widest = dense
        .iter()
        .map(|p| nearest_angle(directions, p))
        .fold(0.0, f64::max);
    let dense_spacing = (4.0 * PI / dense.len() as f64).sqrt();
    widest + 0.5 * dense_spacing
}

/// Angle (rad) from `p` to the nearest of `directions`.
fn nearest_angle(directions: &[[f64; 3]], p: &[f64; 3]) -> f64 {
    let best = directions
        .iter()
        .map(|d| d[0] * p[0] + d[1] * p[1] + d[2] * p[2])
        .fold(-1.0, f64::max);
    best.clamp(-1.0, 1.0).acos()
}

/// Stored directions an interpolation weighs.
pub const NEIGHBOURS: usize = 4;

/// The [`NEIGHBOURS`] stored directions nearest to a query direction and their weights
/// (summing to 1): inverse squared angle, so that a query on a stored direction returns its
/// value exactly and the weights change smoothly between.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbours {
    /// Indices into the stored directions, nearest first.
    pub indices: [usize; NEIGHBOURS],
    /// Weight of each.
    pub weights: [f64; NEIGHBOURS],
}

impl Neighbours {
    /// The neighbours of the unit vector `u` among `directions` (at least [`NEIGHBOURS`] of
    /// them, as every build has).
    pub fn of(directions: &[[f64; 3]], u: &Vector3<f64>) -> Neighbours {
        Neighbours::excluding(directions, u, None)
    }

    /// [`Neighbours::of`] without the stored direction `left_out` (for leave-one-out
    /// estimates of the interpolation error at a stored direction).
    pub fn excluding(
        directions: &[[f64; 3]],
        u: &Vector3<f64>,
        left_out: Option<usize>,
    ) -> Neighbours {
        let mut nearest = [(f64::NEG_INFINITY, 0usize); NEIGHBOURS];
        for (k, d) in directions.iter().enumerate() {
            if Some(k) == left_out {
                continue;
            }
            let cos = d[0] * u.x + d[1] * u.y + d[2] * u.z;
            if cos > nearest[NEIGHBOURS - 1].0 {
                nearest[NEIGHBOURS - 1] = (cos, k);
                // Insertion into the sorted list, strict so that ties keep the lower index.
                let mut i = NEIGHBOURS - 1;
                while i > 0 && nearest[i].0 > nearest[i - 1].0 {
                    nearest.swap(i, i - 1);
                    i -= 1;
                }
            }
        }
        // atan2(|d × u|, d · u): exact 0 on a stored direction, accurate near it (acos is not).
        let angles = nearest.map(|(_, k)| {
            let d = Vector3::from(directions[k]);
            d.cross(u).norm().atan2(d.dot(u))
        });
        let weights = if angles[0] == 0.0 {
            std::array::from_fn(|i| if i == 0 { 1.0 } else { 0.0 })
        } else {
            let raw = angles.map(|a| 1.0 / (a * a));
            let total: f64 = raw.iter().sum();
            raw.map(|w| w / total)
        };
        Neighbours {
            indices: nearest.map(|(_, k)| k),
            weights,
        }
    }

    /// The weighted mean of `value(index)` over the neighbours and the spread (largest −
    /// smallest) of their values, per component; `None` when any value is `None`.
    pub fn interpolate(
        &self,
        value: impl Fn(usize) -> Option<MarginValues>,
    ) -> Option<Interpolated> {
        let mut mean = [0.0; MARGIN_COUNT];
        let mut low = [f64::INFINITY; MARGIN_COUNT];
        let mut high = [f64::NEG_INFINITY; MARGIN_COUNT];
        for (&k, &w) in self.indices.iter().zip(&self.weights) {
            let v = value(k)?;
            for c in 0..MARGIN_COUNT {
                mean[c] += w * v[c];
                low[c] = low[c].min(v[c]);
                high[c] = high[c].max(v[c]);
            }
        }
        Some(Interpolated {
            mean,
            spread: std::array::from_fn(|c| high[c] - low[c]),
        })
    }
}

/// Interpolated values and how much the neighbours they come from differ: the local
/// variation the interpolation error is measured against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interpolated {
    /// The weighted mean.
    pub mean: MarginValues,
    /// Largest − smallest neighbour value.
    pub spread: MarginValues,
}

/// `n` probe directions for measuring the interpolation error: the golden-angle spiral of
/// `n` points turned by a fixed rotation (1 rad about (1, 2, 3)/√14), so that they fall
/// between the stored directions of any count rather than on them.
pub fn probe_directions(n: usize) -> Vec<[f64; 3]> {
    let axis = nalgebra::Unit::new_normalize(Vector3::new(1.0, 2.0, 3.0));
    let turn = nalgebra::UnitQuaternion::from_axis_angle(&axis, 1.0);
    fibonacci_sphere(n)
        .into_iter()
        .map(|d| (turn * Vector3::from(d)).into())
        .collect()
}
