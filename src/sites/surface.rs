//! Points spread over a collision shape's surface, with the outward normal at each: the
//! candidates from which [`super::generate`] picks a link's sites.
//!
//! Analytic shapes are sampled on regular grids on which no two points of one facing (see
//! [`FACING_TOLERANCE_DEG`]) are closer than `spacing`: box faces and the rows along a
//! cylinder in cells of at least `spacing` (their count floored), disc rings and their points
//! at least `spacing` apart, and around a cylinder about one point per `spacing` of
//! circumference where neighbours are different facings, else chords of at least `spacing`;
//! spheres on a Fibonacci lattice of about one point per `spacing²` (thinned like meshes). Meshes are sampled shell by shell
//! with the winding the tool gives each shell ([`TriMesh::shells`]: a closed shell outward, a
//! loose one consistent with most of its triangles), per triangle on a barycentric grid
//! [`MESH_CANDIDATES_PER_SPACING`] times finer than `spacing`, keeping the first point of each
//! grid-sized cell and normal octant: dense candidates, thinned to the spacing later.

use super::FACING_TOLERANCE_DEG;
use crate::robot::{Shape, TriMesh};
use nalgebra::{Point3, Unit, Vector3};
use std::collections::HashSet;
use std::f64::consts::PI;

/// Mesh candidates are this many times denser (per length) than the site spacing.
pub const MESH_CANDIDATES_PER_SPACING: f64 = 3.0;

/// A point on a surface and its outward unit normal, in the shape's frame (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// The point on the surface.
    pub point: Point3<f64>,
    /// The outward unit normal there.
    pub normal: Unit<Vector3<f64>>,
}

/// About how many points [`sample`] returns for `shape` at `spacing_m`: the surface area over
/// `spacing²`, known before anything is allocated.
pub fn estimated_count(shape: &Shape, spacing_m: f64) -> f64 {
    area(shape) / (spacing_m * spacing_m)
}

/// How many points [`sample`] visits for `shape` at `spacing_m` before thinning: the
/// estimated count for analytic shapes, the barycentric grid points of every triangle for a
/// mesh at the candidates' pitch (a long thin triangle costs its longest edge's steps
/// squared). Known before anything is allocated.
pub fn sampling_work(shape: &Shape, spacing_m: f64) -> f64 {
    match shape {
        Shape::Mesh(mesh) => {
            let pitch = spacing_m / MESH_CANDIDATES_PER_SPACING;
            mesh_triangles(mesh)
                .map(|[a, b, c]| {
                    let steps = grid_steps(&a, &b, &c, pitch) as f64;
                    0.5 * steps * (steps + 1.0)
                })
                .sum()
        }
        other => estimated_count(other, spacing_m),
    }
}

/// Grid steps along a triangle's longest edge at `pitch`, at least one.
fn grid_steps(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>, pitch: f64) -> usize {
    let longest = [(b - a).norm(), (c - b).norm(), (a - c).norm()]
        .into_iter()
        .fold(0.0, f64::max);
    (longest / pitch).ceil().clamp(1.0, 1e9) as usize
}

/// Surface area of a shape (m²).
fn area(shape: &Shape) -> f64 {
    match shape {
        Shape::Box { half_extents_m: h } => 8.0 * (h.x * h.y + h.y * h.z + h.z * h.x),
        Shape::Cylinder { radius_m, length_m } => 2.0 * PI * radius_m * (length_m + radius_m),
        Shape::Sphere { radius_m } => 4.0 * PI * radius_m * radius_m,
        Shape::Capsule { radius_m, length_m } => {
            2.0 * PI * radius_m * length_m + 4.0 * PI * radius_m * radius_m
        }
        Shape::Mesh(mesh) => mesh_triangles(mesh)
            .map(|[a, b, c]| triangle_area(&a, &b, &c))
            .sum(),
    }
}

/// Candidate points over the whole surface of `shape` for sites `spacing_m` apart, in a
/// fixed order (see the module documentation).
pub fn sample(shape: &Shape, spacing_m: f64) -> Vec<SurfacePoint> {
    match shape {
        Shape::Box { half_extents_m } => box_faces(half_extents_m, spacing_m),
        Shape::Cylinder { radius_m, length_m } => {
            let mut points = cylinder_side(*radius_m, 0.5 * length_m, spacing_m);
            for side in [1.0, -1.0] {
                points.extend(disc(*radius_m, side * 0.5 * length_m, side, spacing_m));
            }
            points
        }
        Shape::Sphere { radius_m } => sphere_cap(*radius_m, 0.0, None, spacing_m),
        Shape::Capsule { radius_m, length_m } => {
            let half = 0.5 * length_m;
            let mut points = cylinder_side(*radius_m, half, spacing_m);
            points.extend(sphere_cap(*radius_m, half, Some(1.0), spacing_m));
            points.extend(sphere_cap(*radius_m, -half, Some(-1.0), spacing_m));
            points
        }
        Shape::Mesh(mesh) => mesh_surface(mesh, spacing_m),
    }
}

/// Cells of `extent` split into pieces at least `spacing` long (one when `extent` is
/// shorter): their centres' offsets from the start.
fn cell_centres(extent: f64, spacing: f64) -> impl Iterator<Item = f64> {
    let count = (extent / spacing).floor().max(1.0) as usize;
    let cell = extent / count as f64;
    (0..count).map(move |k| (k as f64 + 0.5) * cell)
}

/// The most points evenly around a circle of `radius` whose neighbours are at least
/// `spacing` apart (chord), at least one.
fn chord_limited_count(radius: f64, spacing: f64) -> usize {
    if spacing < 2.0 * radius {
        ((PI / (0.5 * spacing / radius).asin()).floor() as usize).max(1)
    } else {
        1
    }
}

/// Points around a cylinder: about one per `spacing` of circumference, as long as
/// neighbours are different facings (normals more than [`FACING_TOLERANCE_DEG`] apart) or at
/// least `spacing` apart; never fewer than the four sides (90° apart).
fn around_cylinder(radius: f64, spacing: f64) -> usize {
    let by_length = (2.0 * PI * radius / spacing).round() as usize;
    let distinct_facings = (360.0 / FACING_TOLERANCE_DEG).ceil() as usize - 1;
    chord_limited_count(radius, spacing)
        .max(by_length.min(distinct_facings))
        .max(4)
}

/// The six faces of a box, each in cells of at least `spacing`.
fn box_faces(half: &Vector3<f64>, spacing: f64) -> Vec<SurfacePoint> {
    let mut points = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for sign in [1.0, -1.0] {
            let mut normal = Vector3::zeros();
            normal[axis] = sign;
            for a in cell_centres(2.0 * half[u], spacing) {
                for b in cell_centres(2.0 * half[v], spacing) {
                    let mut point = Point3::origin();
                    point[axis] = sign * half[axis];
                    point[u] = a - half[u];
                    point[v] = b - half[v];
                    points.push(SurfacePoint {
                        point,
                        normal: Unit::new_unchecked(normal),
                    });
                }
            }
        }
    }
    points
}

/// The lateral surface of a cylinder about z from `−half` to `half`.
fn cylinder_side(radius: f64, half: f64, spacing: f64) -> Vec<SurfacePoint> {
    let around = around_cylinder(radius, spacing);
    let mut points = Vec::new();
    for z in cell_centres(2.0 * half, spacing) {
        for k in 0..around {
            let angle = 2.0 * PI * k as f64 / around as f64;
            let normal = Vector3::new(angle.cos(), angle.sin(), 0.0);
            points.push(SurfacePoint {
                point: Point3::from(radius * normal + Vector3::new(0.0, 0.0, z - half)),
                normal: Unit::new_unchecked(normal),
            });
        }
    }
    points
}

/// A disc of `radius` at height `z` facing `side` (±1 along z): its centre and rings at
/// least `spacing` apart, the outermost half a ring's pitch inside the rim.
fn disc(radius: f64, z: f64, side: f64, spacing: f64) -> Vec<SurfacePoint> {
    let normal = Unit::new_unchecked(Vector3::new(0.0, 0.0, side));
    let mut points = vec![SurfacePoint {
        point: Point3::new(0.0, 0.0, z),
        normal,
    }];
    let rings = (radius / spacing - 0.5).floor().max(0.0) as usize;
    for ring in 1..=rings {
        let rho = radius * ring as f64 / (rings as f64 + 0.5);
        let around = chord_limited_count(rho, spacing);
        for k in 0..around {
            let angle = 2.0 * PI * k as f64 / around as f64;
            points.push(SurfacePoint {
                point: Point3::new(rho * angle.cos(), rho * angle.sin(), z),
                normal,
            });
        }
    }
    points
}

/// A Fibonacci lattice of about one point per `spacing²` on the sphere of `radius` centred at
/// height `z`; with `half = Some(±1)` only the hemisphere on that side of the centre (a
/// capsule's end cap).
fn sphere_cap(radius: f64, z: f64, half: Option<f64>, spacing: f64) -> Vec<SurfacePoint> {
    let count = ((4.0 * PI * radius * radius / (spacing * spacing)).floor() as usize).max(4);
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..count)
        .filter_map(|k| {
            let height = 1.0 - (2.0 * k as f64 + 1.0) / count as f64;
            let ring = (1.0 - height * height).sqrt();
            let angle = golden * k as f64;
            let normal = Vector3::new(ring * angle.cos(), ring * angle.sin(), height);
            if half.is_some_and(|side| side * height < 0.0) {
                return None;
            }
            Some(SurfacePoint {
                point: Point3::from(radius * normal + Vector3::new(0.0, 0.0, z)),
                normal: Unit::new_unchecked(normal),
            })
        })
        .collect()
}

/// The triangles of a mesh as corner points, as the file has them (indices beyond the
/// vertices skipped).
pub(super) fn mesh_triangles(mesh: &TriMesh) -> impl Iterator<Item = [Point3<f64>; 3]> + '_ {
    mesh.triangles.iter().filter_map(|t| corners(mesh, t))
}

fn corners(mesh: &TriMesh, t: &[u32; 3]) -> Option<[Point3<f64>; 3]> {
    let corner = |i: u32| mesh.vertices.get(i as usize).copied();
    Some([corner(t[0])?, corner(t[1])?, corner(t[2])?])
}

fn triangle_area(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>) -> f64 {
    0.5 * (b - a).cross(&(c - a)).norm()
}

/// Candidates on a mesh: every shell's triangles wound as [`TriMesh::shells`] winds them
/// (normal `(b − a) × (c − a)`), each on a barycentric grid at the candidates' pitch; the
/// first point of each pitch-sized cell and normal octant is kept.
fn mesh_surface(mesh: &TriMesh, spacing: f64) -> Vec<SurfacePoint> {
    let pitch = spacing / MESH_CANDIDATES_PER_SPACING;
    let mut seen: HashSet<([i64; 3], u8)> = HashSet::new();
    let mut points = Vec::new();
    let shells = mesh.shells();
    let triangles = shells.shells.iter().flat_map(|s| s.triangles.iter());
    for [a, b, c] in triangles.filter_map(|t| corners(mesh, t)) {
        let Some(normal) = Unit::try_new((b - a).cross(&(c - a)), 1e-18) else {
            continue;
        };
        for point in triangle_grid(&a, &b, &c, pitch) {
            let cell = [point.x, point.y, point.z].map(|x| (x / pitch).floor() as i64);
            if seen.insert((cell, octant(&normal))) {
                points.push(SurfacePoint { point, normal });
            }
        }
    }
    points
}

/// Which octant a direction points into (a bit per positive component).
fn octant(v: &Vector3<f64>) -> u8 {
    (0..3).fold(0u8, |o, k| o | (u8::from(v[k] >= 0.0) << k))
}

/// Points of a triangle on a barycentric grid of about `pitch`: the centres of the grid's
/// upright sub-triangles (one point for a triangle smaller than `pitch`).
fn triangle_grid<'a>(
    a: &'a Point3<f64>,
    b: &'a Point3<f64>,
    c: &'a Point3<f64>,
    pitch: f64,
) -> impl Iterator<Item = Point3<f64>> + 'a {
    let steps = grid_steps(a, b, c, pitch);
    let n = steps as f64;
    (0..steps).flat_map(move |i| {
        (0..steps - i).map(move |j| {
            let (u, v) = ((i as f64 + 1.0 / 3.0) / n, (j as f64 + 1.0 / 3.0) / n);
            a + u * (b - a) + v * (c - a)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_surface_box(p: &SurfacePoint, half: &Vector3<f64>) -> bool {
        let axis = (0..3).find(|&k| p.normal[k].abs() == 1.0);
        axis.is_some_and(|k| (p.point[k].abs() - half[k]).abs() < 1e-12)
            && (0..3).all(|k| p.point[k].abs() <= half[k] + 1e-12)
    }

    #[test]
    fn box_points_lie_on_their_faces_at_the_spacing_density() {
        let half = Vector3::new(0.05, 0.075, 0.0575);
        let shape = Shape::Box {
            half_extents_m: half,
        };
        let points = sample(&shape, 0.02);
        assert!(points.iter().all(|p| on_surface_box(p, &half)));
        let expected = estimated_count(&shape, 0.02);
        let ratio = points.len() as f64 / expected;
        assert!(
            (0.6..1.6).contains(&ratio),
            "{} points for {expected:.1}",
            points.len()
        );
    }

    #[test]
    fn cylinder_and_sphere_points_have_radial_normals() {
        let cylinder = Shape::Cylinder {
            radius_m: 0.07,
            length_m: 0.175,
        };
        for p in sample(&cylinder, 0.025) {
            let radial = Vector3::new(p.point.x, p.point.y, 0.0);
            if p.normal.z == 0.0 {
                assert!((radial.norm() - 0.07).abs() < 1e-12);
                assert!((radial.normalize() - p.normal.into_inner()).norm() < 1e-12);
            } else {
                assert!((p.point.z.abs() - 0.0875).abs() < 1e-12);
                assert!(radial.norm() < 0.07);
            }
        }
        for p in sample(&Shape::Sphere { radius_m: 0.05 }, 0.02) {
            assert!((p.point.coords.norm() - 0.05).abs() < 1e-12);
            assert!((p.point.coords / 0.05 - p.normal.into_inner()).norm() < 1e-12);
        }
    }

    /// A cube of 10 cm as 12 triangles.
    fn cube(inward: bool) -> TriMesh {
        let v = |x: f64, y: f64, z: f64| Point3::new(x, y, z) * 0.1;
        let vertices = vec![
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(1., 1., 0.),
            v(0., 1., 0.),
            v(0., 0., 1.),
            v(1., 0., 1.),
            v(1., 1., 1.),
            v(0., 1., 1.),
        ];
        let outward: Vec<[u32; 3]> = vec![
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 6],
            [4, 6, 7],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        let triangles = if inward {
            outward.iter().map(|t| [t[0], t[2], t[1]]).collect()
        } else {
            outward
        };
        TriMesh {
            file: "cube.stl".into(),
            vertices,
            triangles,
        }
    }

    /// A cube as 12 triangles, wound outward or inward: the mesh sampler puts its points on
    /// the faces with the outward normals of the analytic box (the shells are wound outward
    /// whatever the file says), denser than the sites will be.
    #[test]
    fn mesh_cube_candidates_face_outward_however_the_file_winds_it() {
        for inward in [false, true] {
            let shape = Shape::Mesh(cube(inward));
            let points = sample(&shape, 0.025);
            let centre = Vector3::new(0.05, 0.05, 0.05);
            let half = Vector3::new(0.05, 0.05, 0.05);
            for p in &points {
                let local = SurfacePoint {
                    point: p.point - centre,
                    normal: p.normal,
                };
                assert!(on_surface_box(&local, &half), "{p:?}");
                let outward = (p.point - Point3::from(centre)).dot(&p.normal);
                assert!(outward > 0.0, "inward {inward}: {p:?}");
            }
            assert!(points.len() as f64 >= 4.0 * estimated_count(&shape, 0.025));
        }
    }

    /// On the grids of boxes and cylinders no two points of one facing are closer than the
    /// spacing, whatever the sizes (extents just below and above multiples of the spacing,
    /// radii from a quarter of the spacing to many spacings).
    #[test]
    fn analytic_grids_keep_the_spacing_within_a_facing() {
        let spacing = 0.02;
        let facing = FACING_TOLERANCE_DEG.to_radians().cos();
        let mut shapes = vec![Shape::Box {
            half_extents_m: Vector3::new(0.0199, 0.0201, 0.0599),
        }];
        for radius in [0.005, 0.012, 0.019, 0.021, 0.03, 0.06, 0.2] {
            shapes.push(Shape::Cylinder {
                radius_m: radius,
                length_m: 0.061,
            });
            shapes.push(Shape::Capsule {
                radius_m: radius,
                length_m: 0.039,
            });
        }
        for shape in &shapes {
            // Capsule caps are a Fibonacci lattice, thinned with the meshes: only their sides.
            let side = |p: &SurfacePoint| match shape {
                Shape::Capsule { length_m, .. } => p.point.z.abs() < 0.5 * length_m - 1e-12,
                _ => true,
            };
            let points: Vec<_> = sample(shape, spacing).into_iter().filter(side).collect();
            for (i, a) in points.iter().enumerate() {
                for b in &points[i + 1..] {
                    let close = (a.point - b.point).norm() < spacing * (1.0 - 1e-9);
                    assert!(
                        !(close && a.normal.dot(&b.normal) >= facing),
                        "{}: {a:?} {b:?}",
                        shape.describe()
                    );
                }
            }
        }
    }

    /// A sliver 10 m long and 1 mm wide has the area of 5000 sites at 1 mm spacing but a
    /// barycentric grid of 3·10⁴ steps along its long edge at the candidates' pitch (a third
    /// of the spacing): 4.5·10⁸ points to visit, which the generator refuses before sampling.
    #[test]
    fn a_sliver_triangle_counts_its_grid_not_its_area() {
        let vertices = vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(10.0, 0.0, 0.0),
            Point3::new(0.0, 0.001, 0.0),
        ];
        let mesh = TriMesh {
            file: "sliver.stl".into(),
            vertices,
            triangles: vec![[0, 1, 2]],
        };
        let shape = Shape::Mesh(mesh);
        let area_points = estimated_count(&shape, 0.001);
        assert!((area_points - 5000.0).abs() < 1e-6, "{area_points}");
        let work = sampling_work(&shape, 0.001);
        // 3·10⁴ steps, give or take the rounding of 10 / (0.001 / 3).
        assert!((work - 4.5e8).abs() < 1e5, "{work}");
        assert!(work > crate::sites::MAX_SAMPLING_WORK as f64);
    }
}
