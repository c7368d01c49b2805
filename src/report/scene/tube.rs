//! The cable as one swept tube around its centreline polyline.
//!
//! A ring of vertices surrounds every node, in the plane normal to the node's tangent (the
//! bisector of the adjacent segments), oriented by parallel-transported (rotation-minimizing)
//! frames so that the tube does not twist. On the outer side of a bend the ring lies at the
//! radius from the node; on the inner side it is stretched to where the two adjacent
//! segments' cylinders meet (a mitre). Every ring vertex is therefore at exactly the radius
//! from the polyline: the rings sample the surface of the set of points within the radius
//! of the centreline. Normals are the rings' radial directions; flat caps close both ends.

use super::mesh::{CABLE_SEGMENTS, TriangleMesh};
use nalgebra::{Point3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::TAU;

/// Largest sine of half a bend angle that is mitred in full (sharper bends are drawn thinner
/// on their inner side rather than with long spikes).
const MAX_HALF_BEND_SINE: f64 = 0.95;

/// The swept tube of `radius` around `nodes` (at least two), caps included.
pub(super) fn swept_tube(nodes: &[Point3<f64>], radius: f64) -> TriangleMesh {
    let directions = segment_directions(nodes);
    let frames = node_frames(&directions);
    let mut mesh = TriangleMesh::default();
    for (k, (node, frame)) in nodes.iter().zip(&frames).enumerate() {
        let bend = Bend::at(&directions, k);
        for i in 0..CABLE_SEGMENTS {
            let (sin, cos) = (TAU * i as f64 / CABLE_SEGMENTS as f64).sin_cos();
            let radial = frame.normal * cos + frame.binormal * sin;
            mesh.vertex(node + radial * bend.ring_radius(radius, &radial), radial);
        }
    }
    join_rings(&mut mesh, nodes.len());
    add_caps(&mut mesh, &frames, nodes.len());
    mesh
}

/// Unit direction of every segment; a zero-length segment borrows the direction of the
/// nearest segment before it (or after it), and a line without length points along +z.
fn segment_directions(nodes: &[Point3<f64>]) -> Vec<Unit<Vector3<f64>>> {
    let raw: Vec<Option<Unit<Vector3<f64>>>> = nodes
        .windows(2)
        .map(|pair| Unit::try_new(pair[1] - pair[0], 0.0))
        .collect();
    let fallback = raw
        .iter()
        .flatten()
        .next()
        .copied()
        .unwrap_or(Vector3::z_axis());
    let mut last = fallback;
    raw.iter()
        .map(|d| {
            last = d.unwrap_or(last);
            last
        })
        .collect()
}

/// A node's ring frame: tangent, and the normal and binormal spanning the ring plane with
/// `normal × binormal = tangent`.
#[derive(Debug, Clone, Copy)]
struct Frame {
    tangent: Unit<Vector3<f64>>,
    normal: Vector3<f64>,
    binormal: Vector3<f64>,
}

/// Tangent of node `k`: the bisector of its adjacent segments (or the one segment at an end).
fn tangent(directions: &[Unit<Vector3<f64>>], k: usize) -> Unit<Vector3<f64>> {
    let after = directions[k.min(directions.len() - 1)];
    match k.checked_sub(1).map(|i| directions[i]) {
        Some(before) if k < directions.len() => {
            Unit::try_new(before.into_inner() + after.into_inner(), 1e-12).unwrap_or(after)
        }
        Some(before) => before,
        None => after,
    }
}

/// Frames at every node, the normal parallel-transported from node to node.
fn node_frames(directions: &[Unit<Vector3<f64>>]) -> Vec<Frame> {
    let mut frames: Vec<Frame> = Vec::with_capacity(directions.len() + 1);
    for k in 0..=directions.len() {
        let tangent = tangent(directions, k);
        let carried = match frames.last() {
            Some(previous) => transport(previous, &tangent),
            None => any_perpendicular(&tangent),
        };
        frames.push(frame(tangent, carried));
    }
    frames
}

/// The previous frame's normal rotated by the smallest rotation taking its tangent to `tangent`.
fn transport(previous: &Frame, tangent: &Unit<Vector3<f64>>) -> Vector3<f64> {
    match UnitQuaternion::rotation_between_axis(&previous.tangent, tangent) {
        Some(rotation) => rotation * previous.normal,
        None => previous.normal,
    }
}

fn any_perpendicular(tangent: &Unit<Vector3<f64>>) -> Vector3<f64> {
    let t = tangent.into_inner();
    let axis = if t.x.abs() < 0.6 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    axis.cross(&t)
}

/// A right-handed frame from a tangent and a normal guess (made perpendicular).
fn frame(tangent: Unit<Vector3<f64>>, guess: Vector3<f64>) -> Frame {
    let t = tangent.into_inner();
    let normal = Unit::try_new(guess - t * guess.dot(&t), 1e-9)
        .map(Unit::into_inner)
        .unwrap_or_else(|| any_perpendicular(&tangent).normalize());
    Frame {
        tangent,
        normal,
        binormal: t.cross(&normal),
    }
}

/// The bend at a node: towards `inside` (unit, in the ring plane) by twice `half_sine`'s angle.
struct Bend {
    inside: Vector3<f64>,
    half_sine: f64,
}

impl Bend {
    /// The bend between the segments before and after node `k` (none at the ends).
    fn at(directions: &[Unit<Vector3<f64>>], k: usize) -> Bend {
        let straight = Bend {
            inside: Vector3::zeros(),
            half_sine: 0.0,
        };
        let (Some(before), Some(after)) =
            (k.checked_sub(1).map(|i| directions[i]), directions.get(k))
        else {
            return straight;
        };
        let turn = after.into_inner() - before.into_inner();
        match Unit::try_new(turn, 1e-12) {
            Some(inside) => Bend {
                inside: inside.into_inner(),
                half_sine: (0.5 * turn.norm()).min(MAX_HALF_BEND_SINE),
            },
            None => straight,
        }
    }

    /// Distance from the node of the ring vertex in direction `radial`: the radius on the
    /// outer side, the mitre (distance `radius` from both adjacent segments) on the inner side.
    fn ring_radius(&self, radius: f64, radial: &Vector3<f64>) -> f64 {
        let inward = radial.dot(&self.inside).max(0.0);
        let s = self.half_sine * inward;
        radius / (1.0 - s * s).sqrt()
    }
}

/// Two triangles per ring segment between consecutive rings.
fn join_rings(mesh: &mut TriangleMesh, rings: usize) {
    let n = CABLE_SEGMENTS as u32;
    for k in 0..rings.saturating_sub(1) as u32 {
        let (a, b) = (k * n, (k + 1) * n);
        for i in 0..n {
            let j = (i + 1) % n;
            mesh.triangle(a + i, a + j, b + j);
            mesh.triangle(a + i, b + j, b + i);
        }
    }
}

/// Flat caps: the end rings again with the end tangents as normals, fanned.
fn add_caps(mesh: &mut TriangleMesh, frames: &[Frame], rings: usize) {
    let n = CABLE_SEGMENTS as u32;
    let ends = [(0, -1.0), (rings - 1, 1.0)];
    for (ring, sign) in ends {
        let normal = frames[ring].tangent.into_inner() * sign;
        let first = mesh.positions.len() as u32;
        for i in 0..n {
            let position = mesh.positions[ring * CABLE_SEGMENTS + i as usize];
            mesh.vertex(position, normal);
        }
        for i in 1..n - 1 {
            if sign > 0.0 {
                mesh.triangle(first, first + i, first + i + 1);
            } else {
                mesh.triangle(first, first + i + 1, first + i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance_to_segment(p: &Point3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
        let ab = b - a;
        let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
        (p - (a + ab * t)).norm()
    }

    #[test]
    fn ring_vertices_lie_at_the_radius_from_a_bent_polyline() {
        let nodes: Vec<Point3<f64>> = (0..12)
            .map(|k| {
                let s = k as f64 * 0.4;
                Point3::new(0.3 * s.cos(), 0.3 * s.sin(), 0.05 * s)
            })
            .collect();
        let radius = 0.01;
        let mesh = swept_tube(&nodes, radius);
        for p in &mesh.positions {
            let d = nodes
                .windows(2)
                .map(|w| distance_to_segment(p, &w[0], &w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!((d - radius).abs() < 1e-12, "{p:?}: {d}");
        }
    }

    #[test]
    fn tube_faces_outward_and_frames_do_not_twist_on_a_straight_line() {
        let nodes: Vec<Point3<f64>> = (0..4)
            .map(|k| Point3::new(0.0, 0.0, k as f64 * 0.1))
            .collect();
        let mesh = swept_tube(&nodes, 0.02);
        let n = CABLE_SEGMENTS;
        for k in 1..4 {
            let (p0, pk) = (mesh.positions[0], mesh.positions[k * n]);
            assert!(((pk - p0) - Vector3::new(0.0, 0.0, k as f64 * 0.1)).norm() < 1e-12);
        }
        for t in mesh.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
            let face = (b - a).cross(&(c - a));
            let normal = mesh.normals[t[0] as usize];
            assert!(face.dot(&normal) > 0.0, "triangle {t:?}");
        }
    }
}
