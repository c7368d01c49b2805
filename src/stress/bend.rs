//! How tightly a cable shape bends: the bend radius at every joint of the discrete cable.
//!
//! A joint's bend radius is the cable length it stands for divided by its turning angle:
//! `l_ss / θ` between two sub-segments. The guide axes count as clamped sub-segments before
//! the first and after the last node, but a guide joint stands for half a sub-segment: a
//! cable leaving a clamp tangentially along a circle of radius `R` meets its first chord at
//! half the chord angle, `l_ss / 2R`. So a guide joint's radius is `(l_ss / 2) / θ`, and a
//! polygon inscribed in a circle gets the circle's radius at every joint, guides included.

use nalgebra::{Point3, Vector3};

/// Joint angles below this (rad) are rounding noise on a straight cable.
const STRAIGHT_RAD: f64 = 1e-9;

/// The tightest bend of a shape and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendRadius {
    /// Radius at the sharpest joint (m): `l_ss / angle`, `(l_ss / 2) / angle` at a guide;
    /// `f64::INFINITY` for a straight cable.
    pub radius_m: f64,
    /// Node index of that joint: 0 at the start guide, `S` at the end guide.
    pub node: usize,
}

/// Smallest bend radius over all joints (see the module documentation), θ the angle between
/// adjacent sub-segments, including the joints between the guide axes and the first/last
/// sub-segment.
///
/// `nodes` runs from the start guide origin to the end guide origin; the tangents are the
/// guides' +z axes. Fewer than two nodes is a cable without joints: radius infinite.
pub fn min_bend_radius(
    nodes: &[Point3<f64>],
    start_tangent: &Vector3<f64>,
    end_tangent: &Vector3<f64>,
    pitch_m: f64,
) -> BendRadius {
    let chords = nodes.windows(2).map(|w| w[1] - w[0]);
    let directions: Vec<Vector3<f64>> = std::iter::once(*start_tangent)
        .chain(chords)
        .chain(std::iter::once(*end_tangent))
        .collect();
    let last_joint = directions.len().saturating_sub(2);
    let sharpest = directions
        .windows(2)
        .enumerate()
        .map(|(node, d)| {
            let arc = if node == 0 || node == last_joint {
                0.5 * pitch_m
            } else {
                pitch_m
            };
            let angle = angle_between(&d[0], &d[1]);
            // Below this a joint is straight to rounding (a radius beyond 10⁷ pitches).
            let radius = if angle > STRAIGHT_RAD {
                arc / angle
            } else {
                f64::INFINITY
            };
            (node, radius)
        })
        .fold((0, f64::INFINITY), |best, (node, radius)| {
            if radius < best.1 {
                (node, radius)
            } else {
                best
            }
        });
    let (node, radius_m) = if nodes.len() < 2 {
        (0, f64::INFINITY)
    } else {
        sharpest
    };
    BendRadius { radius_m, node }
}

/// Angle between two vectors in [0, π], accurate for small and near-π angles.
fn angle_between(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nodes on a circle of radius `r` with chord `l`, starting at the origin heading +x.
    fn circle_polyline(r: f64, l: f64, n: usize) -> Vec<Point3<f64>> {
        let step = 2.0 * (l / (2.0 * r)).asin();
        (0..=n)
            .map(|k| {
                let phi = k as f64 * step;
                Point3::new(r * phi.sin(), r * (1.0 - phi.cos()), 0.0)
            })
            .collect()
    }

    #[test]
    fn bend_radius_of_a_polygon_on_a_circle_is_chord_over_turning_angle() {
        let (r, l) = (0.06, 0.01);
        let nodes = circle_polyline(r, l, 12);
        // Guide tangents along the circle's tangents: a guide joint turns through half the
        // chord angle and stands for half a sub-segment, so it has the same radius.
        let turn = 2.0 * (l / (2.0 * r)).asin();
        let start = Vector3::x();
        let end = Vector3::new((12.0 * turn).cos(), (12.0 * turn).sin(), 0.0);
        let bend = min_bend_radius(&nodes, &start, &end, l);
        assert!(
            (bend.radius_m - l / turn).abs() < 1e-12,
            "{}",
            bend.radius_m
        );
        // l/θ approaches the circle radius as (l/R)² → 0.
        assert!((bend.radius_m - r).abs() / r < (l / r).powi(2) / 20.0);
    }

    #[test]
    fn a_straight_cable_has_infinite_radius() {
        let nodes: Vec<_> = (0..=5)
            .map(|k| Point3::new(0.0, 0.0, 0.01 * k as f64))
            .collect();
        let z = Vector3::z();
        assert_eq!(
            min_bend_radius(&nodes, &z, &z, 0.01).radius_m,
            f64::INFINITY
        );
    }

    #[test]
    fn the_guide_joint_is_located() {
        let nodes: Vec<_> = (0..=3)
            .map(|k| Point3::new(0.01 * k as f64, 0.0, 0.0))
            .collect();
        // The end guide points 90° away from the cable: the kink is at the last node, a guide
        // joint standing for half a sub-segment.
        let bend = min_bend_radius(&nodes, &Vector3::x(), &Vector3::y(), 0.01);
        assert_eq!(bend.node, 3);
        assert!((bend.radius_m - 0.005 / std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        // The same angle at an interior joint is a radius twice as large.
        let kinked = [nodes[0], nodes[1], Point3::new(0.01, 0.01, 0.0)];
        let bend = min_bend_radius(&kinked, &Vector3::x(), &Vector3::y(), 0.01);
        assert_eq!(bend.node, 1);
        assert!((bend.radius_m - 0.01 / std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }
}
