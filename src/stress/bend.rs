//! How tightly a cable shape bends: the bend radius at every joint of the discrete cable.
//!
//! A joint's bend radius is the cable length it stands for divided by its turning angle:
//! `l_ss / θ` between two sub-segments. The guide axes count as clamped sub-segments before
//! the first and after the last node, but a guide joint stands for half a sub-segment: a
//! cable leaving a clamp tangentially along a circle of radius `R` meets its first chord at
//! half the chord angle, `l_ss / 2R`. So a guide joint's radius is `(l_ss / 2) / θ`, and a
//! polygon inscribed in a circle gets the circle's radius at every joint, guides included.

use nalgebra::{Point3, Rotation3, Vector3};

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
    bend_profile(nodes, start_tangent, end_tangent, pitch_m).0
}

/// The tightest joint ([`min_bend_radius`]) and the curvature at every joint
/// ([`curvatures_per_m`]), in one pass over the joints.
pub fn bend_profile(
    nodes: &[Point3<f64>],
    start_tangent: &Vector3<f64>,
    end_tangent: &Vector3<f64>,
    pitch_m: f64,
) -> (BendRadius, Vec<f64>) {
    let mut tightest = BendRadius {
        radius_m: f64::INFINITY,
        node: 0,
    };
    if nodes.len() < 2 {
        return (tightest, Vec::new());
    }
    let curvatures = joints(nodes, start_tangent, end_tangent, pitch_m)
        .map(|(node, arc, angle)| {
            // Below this a joint is straight to rounding (a radius beyond 10⁷ pitches).
            if angle <= STRAIGHT_RAD {
                return 0.0;
            }
            let radius = arc / angle;
            if radius < tightest.radius_m {
                tightest = BendRadius {
                    radius_m: radius,
                    node,
                };
            }
            angle / arc
        })
        .collect();
    (tightest, curvatures)
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
    bend_profile(nodes, start_tangent, end_tangent, pitch_m).1
}

/// The curvature vector at every joint in the cable's own cross-section frame (1/m, two
/// components): the bending a conductor at angle φ around the axis feels is
/// `κ₁ cos φ + κ₂ sin φ` times its distance from the axis (up to sign), so the history of
/// these components is what bends each conductor back and forth — a cable bent one way and
/// then the other reverses their sign, which the curvature's magnitude would not show.
///
/// The frame starts as the start clamp's (`start`, its +z the cable's direction) and is
/// carried along the shape without turning about the cable (parallel transport), then turned
/// by the piece's twist `twist_rad` in proportion to the length from the start clamp (the
/// twist is uniform along a piece). Joints are those of [`curvatures_per_m`], which gives
/// the vectors' lengths.
pub fn curvature_vectors_per_m(
    nodes: &[Point3<f64>],
    start: &Rotation3<f64>,
    end_tangent: &Vector3<f64>,
    twist_rad: f64,
    pitch_m: f64,
) -> Vec<[f64; 2]> {
    if nodes.len() < 2 {
        return Vec::new();
    }
    let tangent = start * Vector3::z();
    let mut across = start * Vector3::x();
    let chords = nodes.windows(2).map(|w| (w[1] - w[0]).normalize());
    let directions: Vec<Vector3<f64>> = std::iter::once(tangent)
        .chain(chords)
        .chain(std::iter::once(end_tangent.normalize()))
        .collect();
    let length_m = (nodes.len() - 1) as f64 * pitch_m;
    let last_joint = directions.len() - 2;
    let mut out = Vec::with_capacity(directions.len() - 1);
    for (node, d) in directions.windows(2).enumerate() {
        let (t, next) = (d[0], d[1]);
        let arc = if node == 0 || node == last_joint {
            0.5 * pitch_m
        } else {
            pitch_m
        };
        // The cross-section's frame at this joint: the carried one turned by the twist so far.
        let turn = twist_rad * node as f64 * pitch_m / length_m;
        let d1 = across * turn.cos() + t.cross(&across) * turn.sin();
        let d2 = t.cross(&d1);
        let axis = t.cross(&next);
        let angle = angle_between(&t, &next);
        let curvature = if angle > STRAIGHT_RAD && axis.norm() > 0.0 {
            axis.normalize() * (angle / arc)
        } else {
            Vector3::zeros()
        };
        out.push([curvature.dot(&d1), curvature.dot(&d2)]);
        across = transported(&across, &t, &next);
    }
    out
}

/// `v` (perpendicular to `from`) carried to be perpendicular to `to` by the least rotation
/// taking `from` to `to` (unit vectors).
fn transported(v: &Vector3<f64>, from: &Vector3<f64>, to: &Vector3<f64>) -> Vector3<f64> {
    let axis = from.cross(to);
    let (sin, cos) = (axis.norm(), from.dot(to));
    let turned = if sin > 1e-12 {
        let k = axis / sin;
        v * cos + k.cross(v) * sin + k * (k.dot(v) * (1.0 - cos))
    } else {
        *v
    };
    // Rounding: keep it a unit vector across the new direction.
    (turned - to * to.dot(&turned)).normalize()
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

    /// On a circular arc in a plane the curvature vector has the circle's curvature at every
    /// joint and points across the plane: in a cross-section frame that does not twist, all
    /// along the first axis; twisted by Ψ over the piece, it turns by Ψ·s/L.
    #[test]
    fn the_curvature_vector_turns_with_the_twist_and_keeps_its_length() {
        let (r, l, n) = (0.06, 0.01, 12);
        let nodes = circle_polyline(r, l, n);
        let turn = 2.0 * (l / (2.0 * r)).asin();
        // The start clamp along +x, its x axis along +y (toward the circle's centre).
        let start = Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from_columns(&[
            Vector3::y(),
            Vector3::z(),
            Vector3::x(),
        ]));
        let end = Vector3::new((n as f64 * turn).cos(), (n as f64 * turn).sin(), 0.0);
        let lengths = curvatures_per_m(&nodes, &Vector3::x(), &end, l);
        for twist in [0.0, 1.0, -2.5] {
            let vectors = curvature_vectors_per_m(&nodes, &start, &end, twist, l);
            assert_eq!(vectors.len(), lengths.len());
            for (k, ([a, b], length)) in vectors.iter().zip(&lengths).enumerate() {
                assert!(((a * a + b * b).sqrt() - length).abs() < 1e-9, "joint {k}");
                // The curvature points along +z (the plane's normal): the frame's second
                // axis when untwisted (d2 = t × d1 = +z for d1 = +y across the tangent).
                let phase = twist * k as f64 / n as f64;
                let expected = [length * phase.sin(), length * phase.cos()];
                assert!(
                    (a - expected[0]).abs() < 1e-9 && (b - expected[1]).abs() < 1e-9,
                    "twist {twist}, joint {k}: {a}, {b} against {expected:?}"
                );
            }
        }
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
