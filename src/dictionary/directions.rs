//! Gravity directions sampled on the unit sphere, and the conservative neighbourhood of a
//! direction the motion produces.
//!
//! The sample is the golden-angle (Fibonacci) spiral: point k of N has height
//! `z = 1 − (2k + 1)/N` and azimuth `k·π(3 − √5)`. It is quasi-uniform (every point covers
//! about 4π/N sr), needs no random numbers and is the same on every machine.
//!
//! Its **covering radius** — the largest angle from any direction on the sphere to its
//! nearest sample — bounds how far a motion's direction can be from the stored ones. It is
//! estimated on a 64× denser spiral (at least 16384 points) and rounded up by that spiral's
//! own half spacing.

use nalgebra::Vector3;
use std::f64::consts::PI;

/// The default N: covering radius 10.3°. Between neighbouring directions a stored PV's bend
/// radius changes by 0.04 mm per degree (median), 0.46 mm per degree (99th percentile;
/// measured on the bundled pick-and-place setup, README "Dictionaries"), so inside 10° a
/// limit crossing is rarely hidden, and a build of a bundled setup takes minutes on two
/// cores (build time is linear in N).
pub const DEFAULT_DIRECTION_COUNT: usize = 256;

/// Fewest directions a build accepts (fewer would leave hemispheres unsampled).
pub const MIN_DIRECTION_COUNT: usize = 8;

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

/// Marks in `required` every direction within `radius_rad` of the unit vector `u`, and the
/// nearest one in any case (so a radius below the covering radius still marks one).
pub fn mark_neighbourhood(
    directions: &[[f64; 3]],
    u: &Vector3<f64>,
    radius_rad: f64,
    required: &mut [bool],
) {
    let cos_radius = radius_rad.cos();
    let mut nearest = (f64::NEG_INFINITY, 0);
    for (k, d) in directions.iter().enumerate() {
        let cos = d[0] * u.x + d[1] * u.y + d[2] * u.z;
        if cos >= cos_radius {
            required[k] = true;
        }
        if cos > nearest.0 {
            nearest = (cos, k);
        }
    }
    if let Some(slot) = required.get_mut(nearest.1) {
        *slot = true;
    }
}
