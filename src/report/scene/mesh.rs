//! Tessellation of the collision shapes, the cable pieces and the guide markers into
//! triangle meshes with outward normals and counter-clockwise winding seen from outside
//! (glTF front faces).
//!
//! Round shapes are surfaces of revolution about z ([`lathe`]): a profile in the
//! (radius, z) half-plane, walked so that the solid lies on its right (top → outside →
//! bottom), is swept around the axis.

use crate::robot::{Shape, TriMesh};
use nalgebra::{Point3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Segments around the axis of collider cylinders, spheres and capsules.
pub(super) const COLLIDER_SEGMENTS: usize = 24;
/// Latitude bands of a collider sphere (half of them per capsule cap).
const COLLIDER_STACKS: usize = 12;
/// Segments around the cable (unit cylinder, joint spheres, tubes, guide collars).
pub(super) const CABLE_SEGMENTS: usize = 16;
/// Latitude bands of a cable joint sphere.
const JOINT_STACKS: usize = 8;

/// An indexed triangle list with one normal per vertex.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vector3<f64>>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

impl TriangleMesh {
    /// Appends a vertex and returns its index.
    pub fn vertex(&mut self, position: Point3<f64>, normal: Vector3<f64>) -> u32 {
        self.positions.push(position);
        self.normals.push(normal);
        (self.positions.len() - 1) as u32
    }

    /// Appends a triangle.
    pub fn triangle(&mut self, a: u32, b: u32, c: u32) {
        self.indices.extend([a, b, c]);
    }
}

/// The mesh of a collider shape in its own frame.
pub(super) fn shape_mesh(shape: &Shape) -> TriangleMesh {
    match shape {
        Shape::Box { half_extents_m } => box_mesh(half_extents_m),
        Shape::Cylinder { radius_m, length_m } => cylinder(*radius_m, *length_m, COLLIDER_SEGMENTS),
        Shape::Sphere { radius_m } => sphere(*radius_m, COLLIDER_STACKS, COLLIDER_SEGMENTS),
        Shape::Capsule { radius_m, length_m } => capsule(*radius_m, *length_m),
        Shape::Mesh(mesh) => flat_trimesh(mesh),
    }
}

/// Box centred on the origin: 24 vertices, flat faces.
pub(super) fn box_mesh(half: &Vector3<f64>) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let normal = Vector3::ith(axis, sign);
            // (u, v, normal) right-handed, so u → v turns counter-clockwise seen from outside.
            let u = Vector3::ith((axis + 1) % 3, sign);
            let v = normal.cross(&u);
            let centre = normal.component_mul(half);
            let (u, v) = (u.component_mul(half), v.component_mul(half));
            let first = mesh.vertex(Point3::from(centre - u - v), normal);
            mesh.vertex(Point3::from(centre + u - v), normal);
            mesh.vertex(Point3::from(centre + u + v), normal);
            mesh.vertex(Point3::from(centre - u + v), normal);
            mesh.triangle(first, first + 1, first + 2);
            mesh.triangle(first, first + 2, first + 3);
        }
    }
    mesh
}

/// One point of a lathe profile.
#[derive(Debug, Clone, Copy)]
pub(super) struct ProfilePoint {
    /// Distance from the axis (0: a pole, drawn as one vertex).
    pub radius: f64,
    /// Height along the axis.
    pub z: f64,
    /// Unit normal in the (radial, z) half-plane.
    pub normal: [f64; 2],
}

fn point(radius: f64, z: f64, normal: [f64; 2]) -> ProfilePoint {
    ProfilePoint { radius, z, normal }
}

/// Sweeps each profile strip around the z axis with `segments` segments. Consecutive points
/// of a strip are joined; separate strips meet at a crease (flat caps).
pub(super) fn lathe(strips: &[Vec<ProfilePoint>], segments: usize) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for strip in strips {
        let rings: Vec<Ring> = strip.iter().map(|p| ring(&mut mesh, p, segments)).collect();
        for pair in rings.windows(2) {
            join_rings(&mut mesh, &pair[0], &pair[1]);
        }
    }
    mesh
}

/// The vertices of one profile point swept around the axis.
enum Ring {
    Pole(u32),
    Circle { first: u32, count: u32 },
}

impl Ring {
    fn at(&self, i: u32) -> u32 {
        match *self {
            Ring::Pole(v) => v,
            Ring::Circle { first, count } => first + i % count,
        }
    }
}

fn ring(mesh: &mut TriangleMesh, p: &ProfilePoint, segments: usize) -> Ring {
    if p.radius == 0.0 {
        let normal = Vector3::new(0.0, 0.0, p.normal[1].signum());
        return Ring::Pole(mesh.vertex(Point3::new(0.0, 0.0, p.z), normal));
    }
    let first = mesh.positions.len() as u32;
    for i in 0..segments {
        let (sin, cos) = (TAU * i as f64 / segments as f64).sin_cos();
        mesh.vertex(
            Point3::new(p.radius * cos, p.radius * sin, p.z),
            Vector3::new(p.normal[0] * cos, p.normal[0] * sin, p.normal[1]),
        );
    }
    Ring::Circle {
        first,
        count: segments as u32,
    }
}

fn join_rings(mesh: &mut TriangleMesh, a: &Ring, b: &Ring) {
    let count = match (a, b) {
        (Ring::Pole(_), Ring::Pole(_)) => return,
        (Ring::Circle { count, .. }, _) | (_, Ring::Circle { count, .. }) => *count,
    };
    for i in 0..count {
        let j = i + 1;
        match (a, b) {
            (Ring::Pole(pole), _) => mesh.triangle(*pole, b.at(i), b.at(j)),
            (_, Ring::Pole(pole)) => mesh.triangle(a.at(i), *pole, a.at(j)),
            _ => {
                mesh.triangle(a.at(i), b.at(i), b.at(j));
                mesh.triangle(a.at(i), b.at(j), a.at(j));
            }
        }
    }
}

/// Closed cylinder centred on the origin, axis z, flat caps.
pub(super) fn cylinder(radius: f64, length: f64, segments: usize) -> TriangleMesh {
    let h = 0.5 * length;
    let (up, out, down) = ([0.0, 1.0], [1.0, 0.0], [0.0, -1.0]);
    let strips = [
        vec![point(0.0, h, up), point(radius, h, up)],
        vec![point(radius, h, out), point(radius, -h, out)],
        vec![point(radius, -h, down), point(0.0, -h, down)],
    ];
    lathe(&strips, segments)
}

/// Open cylinder of `radius` from z = 0 to z = 1: the cable sub-segment, scaled along z.
pub(super) fn unit_cable_cylinder(radius: f64) -> TriangleMesh {
    let out = [1.0, 0.0];
    lathe(
        &[vec![point(radius, 1.0, out), point(radius, 0.0, out)]],
        CABLE_SEGMENTS,
    )
}

/// Sphere centred on the origin with `stacks` latitude bands.
pub(super) fn sphere(radius: f64, stacks: usize, segments: usize) -> TriangleMesh {
    lathe(&[arc(radius, 0.0, 0.0, PI, stacks)], segments)
}

/// Sphere of the cable radius drawn at every cable node.
pub(super) fn cable_joint_sphere(radius: f64) -> TriangleMesh {
    sphere(radius, JOINT_STACKS, CABLE_SEGMENTS)
}

/// Capsule centred on the origin, axis z: a cylinder of `length` with hemispherical ends.
pub(super) fn capsule(radius: f64, length: f64) -> TriangleMesh {
    let h = 0.5 * length;
    let half_stacks = COLLIDER_STACKS / 2;
    let mut profile = arc(radius, h, 0.0, FRAC_PI_2, half_stacks);
    let bottom = arc(radius, -h, FRAC_PI_2, PI, half_stacks);
    // Without a cylindrical part both arcs share the equator: keep it once.
    let skip = usize::from(length == 0.0);
    profile.extend(bottom.into_iter().skip(skip));
    lathe(&[profile], COLLIDER_SEGMENTS)
}

/// Points of a circular arc of `radius` centred at height `z`, from polar angle `from` to
/// `to` (0 = +z pole) in `steps` steps; polar angles 0 and π are exact poles.
fn arc(radius: f64, z: f64, from: f64, to: f64, steps: usize) -> Vec<ProfilePoint> {
    (0..=steps)
        .map(|i| {
            let theta = match i {
                0 => from,
                i if i == steps => to,
                i => from + (to - from) * i as f64 / steps as f64,
            };
            let (sin, cos) = theta.sin_cos();
            let sin = if theta == 0.0 || theta == PI {
                0.0
            } else {
                sin
            };
            point(radius * sin, z + radius * cos, [sin, cos])
        })
        .collect()
}

/// A guide marker: a collar (hollow cylinder) around the cable along z, centred on the
/// guide's origin.
pub(super) fn collar(inner_radius: f64, outer_radius: f64, length: f64) -> TriangleMesh {
    let h = 0.5 * length;
    let (ri, ro) = (inner_radius, outer_radius);
    let strips = [
        vec![point(ri, h, [0.0, 1.0]), point(ro, h, [0.0, 1.0])],
        vec![point(ro, h, [1.0, 0.0]), point(ro, -h, [1.0, 0.0])],
        vec![point(ro, -h, [0.0, -1.0]), point(ri, -h, [0.0, -1.0])],
        vec![point(ri, -h, [-1.0, 0.0]), point(ri, h, [-1.0, 0.0])],
    ];
    lathe(&strips, CABLE_SEGMENTS)
}

/// A triangle mesh as given, with flat normals (three own vertices per triangle);
/// degenerate triangles are left out. Indices are assumed checked.
pub(super) fn flat_trimesh(trimesh: &TriMesh) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for triangle in &trimesh.triangles {
        let corners = triangle.map(|i| trimesh.vertices.get(i as usize).copied());
        let [Some(a), Some(b), Some(c)] = corners else {
            continue;
        };
        let Some(normal) = (b - a).cross(&(c - a)).try_normalize(0.0) else {
            continue;
        };
        if !normal.iter().all(|v| v.is_finite()) {
            continue;
        }
        let first = mesh.vertex(a, normal);
        mesh.vertex(b, normal);
        mesh.vertex(c, normal);
        mesh.triangle(first, first + 1, first + 2);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle's geometric normal agrees with its vertex normals and points away
    /// from the (convex) shape's centre.
    fn assert_outward(mesh: &TriangleMesh, centre: Point3<f64>, what: &str) {
        assert!(!mesh.indices.is_empty(), "{what}: no triangles");
        for t in mesh.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
            let face = (b - a).cross(&(c - a));
            assert!(face.norm() > 1e-12, "{what}: degenerate triangle {t:?}");
            let mid = Point3::from((a.coords + b.coords + c.coords) / 3.0);
            assert!(
                face.dot(&(mid - centre)) > 0.0,
                "{what}: inward triangle {t:?}"
            );
            for &i in t {
                let n = mesh.normals[i as usize];
                assert!((n.norm() - 1.0).abs() < 1e-12, "{what}: normal {n:?}");
                assert!(
                    n.dot(&face) > 0.0,
                    "{what}: vertex normal against face {t:?}"
                );
            }
        }
    }

    #[test]
    fn primitive_shapes_face_outward() {
        let o = Point3::origin();
        assert_outward(&box_mesh(&Vector3::new(0.1, 0.2, 0.3)), o, "box");
        assert_outward(&cylinder(0.1, 0.4, 24), o, "cylinder");
        assert_outward(&sphere(0.2, 12, 24), o, "sphere");
        assert_outward(&capsule(0.1, 0.3), o, "capsule");
        assert_outward(&capsule(0.1, 0.0), o, "capsule without a cylinder");
        assert_outward(&cable_joint_sphere(0.005), o, "joint sphere");
        assert_outward(
            &unit_cable_cylinder(0.005),
            Point3::new(0.0, 0.0, 0.5),
            "unit cylinder",
        );
    }

    #[test]
    fn collar_walls_face_away_from_the_material() {
        let mesh = collar(0.01, 0.02, 0.012);
        for t in mesh.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize]);
            let face = (b - a).cross(&(c - a)).normalize();
            let mid = (a.coords + b.coords + c.coords) / 3.0;
            let radial = Vector3::new(mid.x, mid.y, 0.0).normalize();
            let r = Vector3::new(mid.x, mid.y, 0.0).norm();
            // Material occupies r ∈ [0.01, 0.02], |z| ≤ 0.006: a small step along the
            // face normal must leave it.
            let step = mid + face * 2e-3;
            let r_step = Vector3::new(step.x, step.y, 0.0).norm();
            let inside = (0.01..=0.02).contains(&r_step) && step.z.abs() <= 0.006;
            assert!(
                !inside,
                "face {t:?} at r {r}, normal {face:?}, radial {radial:?}"
            );
        }
    }

    #[test]
    fn box_has_24_vertices_at_the_half_extents() {
        let half = Vector3::new(0.1, 0.2, 0.3);
        let mesh = box_mesh(&half);
        assert_eq!((mesh.positions.len(), mesh.indices.len()), (24, 36));
        for p in &mesh.positions {
            assert!((p.coords.abs() - half).norm() < 1e-15, "{p:?}");
        }
    }

    #[test]
    fn trimesh_gets_flat_normals_and_loses_degenerate_triangles() {
        let trimesh = TriMesh {
            file: "t.stl".into(),
            vertices: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(2.0, 0.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 1, 3], [0, 1, 9]],
        };
        let mesh = flat_trimesh(&trimesh);
        assert_eq!(mesh.indices, vec![0, 1, 2]);
        assert!(mesh.normals.iter().all(|n| *n == Vector3::z()));
    }
}
