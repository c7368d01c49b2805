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
    if nodes.len() < 2 {
        return BendRadius {
            radius_m: f64::INFINITY,
            node: 0,
        };
    }
    let (node, radius_m) = joints(nodes, start_tangent, end_tangent, pitch_m)
        .map(|(node, arc, angle)| {
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
    BendRadius { radius_m, node }
}

/// Every joint of a shape: its node, the cable length it stands for (m) and its turning
/// angle (rad), guide joints included (see the module documentation).
fn joints(
    nodes: &[Point3<f64>],
    start_tangent: &Vector3<f64>,
    end_tangent: &Vector3<f64>,
    pitch_m: f64,
) -> impl Iterator<Item = (usize, f64, f64)> {
    let chords = nodes.windows(2).map(|w| w[1] - w[0]);
    let directions: Vec<Vector3<f64>> = std::iter::once(*start_tangent)
        .chain(chords)
        .chain(std::iter::once(*end_tangent))
        .collect();
    let last_joint = directions.len().saturating_sub(2);
    (0..directions.len().saturating_sub(1)).map(move |node| {
        let arc = if node == 0 || node == last_joint {
            0.5 * pitch_m
        } else {
            pitch_m
        };
        (
            node,
            arc,
            angle_between(&directions[node], &directions[node + 1]),
        )
    })
}

/// The curvature at every joint (1/m): joint `k` at node `k`, the guide joints at 0 and `S`
/// — the reciprocal of the bend radius [`min_bend_radius`] takes the least of, 0 where
/// straight. Empty for fewer than two nodes.
pub fn curvatures_per_m(
    nodes: &[Point3<f64>],
    start_tangent: &Vector3<f64>,
    end_tangent: &Vector3<f64>,
    pitch_m: f64,
) -> Vec<f64> {
    if nodes.len() < 2 {
        return Vec::new();
    }
    joints(nodes, start_tangent, end_tangent, pitch_m)
        .map(|(_, arc, angle)| {
            if angle > STRAIGHT_RAD {
                angle / arc
            } else {
                0.0
            }
        })
        .collect()
}

/// How much the curvature at each joint of a piece changes over a motion: the least and
/// largest curvature seen at every joint, and the tightest bend. A piece flexes when some
/// joint's change exceeds a stated amount; it must then keep the flexing bend radius.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CurvatureRange {
    low: Vec<f64>,
    high: Vec<f64>,
}

impl CurvatureRange {
    /// Takes in the curvatures of one more shape ([`curvatures_per_m`]); a shape with another
    /// number of joints than the first is ignored (it is not the same piece).
    pub fn take(&mut self, curvatures_per_m: &[f64]) {
        if self.low.is_empty() {
            self.low = curvatures_per_m.to_vec();
            self.high = curvatures_per_m.to_vec();
            return;
        }
        if curvatures_per_m.len() != self.low.len() {
            return;
        }
        for ((low, high), &k) in self
            .low
            .iter_mut()
            .zip(&mut self.high)
            .zip(curvatures_per_m)
        {
            *low = low.min(k);
            *high = high.max(k);
        }
    }

    /// The largest change of curvature at one joint (1/m) and that joint (node index); 0
    /// before two shapes.
    pub fn largest_change(&self) -> (f64, usize) {
        self.low
            .iter()
            .zip(&self.high)
            .map(|(low, high)| high - low)
            .enumerate()
            .fold((0.0, 0), |best, (node, change)| {
                if change > best.0 {
                    (change, node)
                } else {
                    best
                }
            })
    }

    /// Whether the curvature changed by more than `change_per_m` somewhere.
    pub fn flexes(&self, change_per_m: f64) -> bool {
        self.largest_change().0 > change_per_m
    }
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

    /// A piece that keeps its shape does not flex, whatever its bend; one whose bend at one
    /// joint goes from 1/0.2 to 1/0.1 changes by 5 1/m there.
    #[test]
    fn a_piece_flexes_where_its_curvature_changes() {
        let mut still = CurvatureRange::default();
        for _ in 0..3 {
            still.take(&[0.0, 20.0, 5.0]);
        }
        assert_eq!(still.largest_change(), (0.0, 0));
        assert!(!still.flexes(0.0));
        let mut moving = CurvatureRange::default();
        moving.take(&[0.0, 5.0, 1.0]);
        moving.take(&[0.0, 10.0, 1.5]);
        moving.take(&[0.0, 7.0, 1.0]);
        assert_eq!(moving.largest_change(), (5.0, 1));
        assert!(moving.flexes(4.9) && !moving.flexes(5.0));
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
