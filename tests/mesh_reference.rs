//! Checks of the brute-force mesh reference (`reference::mesh_solid`) against closed forms:
//! boxes (inside, distance to faces, edges and corners), two overlapping boxes as two shells,
//! the same solids with their triangles wound inwards or with one triangle flipped, an open box,
//! an icosphere (distance ≈ |r − |p|| within the tessellation error), the STL reader, and the
//! closest point on a triangle against a second, differently written formula.
//!
//! The reference is the judge of the crate's contact code, so it is itself judged here only by
//! closed forms, never by the crate.

use crate::reference;

use reference::mesh_solid::{ReferenceSolid, Triangle, closest_point_on_triangle};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Helpers

/// xorshift64*: a small deterministic generator for test points.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn in_box(&mut self, lo: f64, hi: f64) -> [f64; 3] {
        [0, 1, 2].map(|_| lo + (hi - lo) * self.next_f64())
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Signed volume enclosed by a triangle soup (divergence theorem): positive when the normals
/// `(b − a) × (c − a)` point outwards.
fn signed_volume(triangles: &[Triangle]) -> f64 {
    triangles
        .iter()
        .map(|[a, b, c]| dot(*a, cross(*b, *c)) / 6.0)
        .sum()
}

fn flipped(t: Triangle) -> Triangle {
    [t[0], t[2], t[1]]
}

/// The 12 triangles of the box `[lo, hi]`, wound outwards.
fn box_triangles(lo: [f64; 3], hi: [f64; 3]) -> Vec<Triangle> {
    // Corner i has x from bit 0, y from bit 1, z from bit 2 (0 = lo, 1 = hi).
    let corner = |i: usize| [0, 1, 2].map(|k| if i >> k & 1 == 1 { hi[k] } else { lo[k] });
    // Each face counter-clockwise seen from outside.
    let faces = [
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
    ];
    let mut triangles = Vec::new();
    for [a, b, c, d] in faces {
        triangles.push([corner(a), corner(b), corner(c)]);
        triangles.push([corner(a), corner(c), corner(d)]);
    }
    let volume = (0..3).map(|k| hi[k] - lo[k]).product::<f64>();
    assert!((signed_volume(&triangles) - volume).abs() < 1e-12 * volume.max(1.0));
    triangles
}

/// Closed form: is `p` strictly inside the box, and its unsigned distance to the box surface.
fn box_closed_form(lo: [f64; 3], hi: [f64; 3], p: [f64; 3]) -> (bool, f64) {
    let inside = (0..3).all(|k| lo[k] < p[k] && p[k] < hi[k]);
    let distance = if inside {
        (0..3)
            .map(|k| (p[k] - lo[k]).min(hi[k] - p[k]))
            .fold(f64::INFINITY, f64::min)
    } else {
        norm([0, 1, 2].map(|k| (lo[k] - p[k]).max(0.0).max(p[k] - hi[k])))
    };
    (inside, distance)
}

/// Distance from `p` to the surface of the box is at least `margin` (so the inside answer is
/// clear-cut).
fn clear_of_box(lo: [f64; 3], hi: [f64; 3], p: [f64; 3], margin: f64) -> bool {
    box_closed_form(lo, hi, p).1 > margin
}

fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} (tolerance {tol})"
    );
}

const UNIT_LO: [f64; 3] = [0.0, 0.0, 0.0];
const UNIT_HI: [f64; 3] = [1.0, 1.0, 1.0];

/// Compares a solid whose surface is the unit cube with the closed form at 2000 random points.
fn check_against_unit_cube(solid: &ReferenceSolid, seed: u64) {
    let mut rng = Rng(seed);
    let mut skipped = 0;
    for _ in 0..2000 {
        let p = rng.in_box(-0.5, 1.5);
        let (inside, distance) = box_closed_form(UNIT_LO, UNIT_HI, p);
        assert_close(
            solid.distance(p),
            distance,
            1e-12,
            &format!("distance {p:?}"),
        );
        if !clear_of_box(UNIT_LO, UNIT_HI, p, 1e-9) {
            continue;
        }
        match solid.inside(p) {
            Some(got) => assert_eq!(got, inside, "inside {p:?}"),
            None => skipped += 1,
        }
    }
    assert!(skipped <= 2, "{skipped} undecided points");
}

// ---------------------------------------------------------------------------------------------
// Unit cube

#[test]
fn unit_cube_inside_and_distances_to_faces_edges_and_corners() {
    let cube = ReferenceSolid::from_triangles(box_triangles(UNIT_LO, UNIT_HI));
    assert_eq!(cube.shell_count(), 1);
    assert_eq!(cube.bounds(), (UNIT_LO, UNIT_HI));

    for p in [
        [0.5, 0.5, 0.5],
        [0.01, 0.02, 0.03],
        [0.99, 0.98, 0.97],
        [0.5, 0.999, 0.001],
    ] {
        assert_eq!(cube.inside(p), Some(true), "{p:?}");
    }
    for p in [
        [1.5, 0.5, 0.5],
        [-0.1, 0.5, 0.5],
        [0.5, 0.5, 1.001],
        [2.0, 2.0, 2.0],
        [-3.0, 0.2, 0.7],
        [0.5, -1e-6, 0.5],
    ] {
        assert_eq!(cube.inside(p), Some(false), "{p:?}");
    }

    // Faces: from outside and from inside.
    assert_close(cube.distance([0.5, 0.5, 1.3]), 0.3, 1e-15, "above +z");
    assert_close(cube.distance([0.5, 0.5, 0.9]), 0.1, 1e-15, "below +z");
    assert_close(cube.distance([-0.25, 0.3, 0.6]), 0.25, 1e-15, "beyond −x");
    assert_close(
        cube.distance([0.2, 0.3, 0.6]),
        0.2,
        1e-15,
        "inside, nearest −x",
    );
    assert_close(cube.distance([0.5, 0.5, 0.5]), 0.5, 1e-15, "centre");
    // Edges: (1.3, 0.5, 1.4) is nearest to the edge x = 1, z = 1.
    assert_close(cube.distance([1.3, 0.5, 1.4]), 0.5, 1e-15, "edge x=1,z=1");
    assert_close(
        cube.distance([0.7, -0.2, -0.1]),
        (0.05f64).sqrt(),
        1e-15,
        "edge y=0,z=0",
    );
    // Corners.
    assert_close(
        cube.distance([1.3, 1.4, -1.2]),
        1.3,
        1e-15,
        "corner (1,1,0)",
    );
    assert_close(
        cube.distance([-1.0, -1.0, -1.0]),
        3f64.sqrt(),
        1e-15,
        "corner (0,0,0)",
    );
    // On the surface.
    assert_eq!(cube.distance([1.0, 0.25, 0.75]), 0.0);
    assert_eq!(cube.distance([1.0, 1.0, 1.0]), 0.0);

    check_against_unit_cube(&cube, 0x9e37_79b9_7f4a_7c15);
}

#[test]
fn box_of_other_size_and_place() {
    let (lo, hi) = ([-0.2, 0.1, -0.05], [0.3, 0.15, 0.4]);
    let solid = ReferenceSolid::from_triangles(box_triangles(lo, hi));
    assert_eq!(solid.bounds(), (lo, hi));
    let mut rng = Rng(7);
    for _ in 0..1000 {
        let p = rng.in_box(-0.4, 0.6);
        let (inside, distance) = box_closed_form(lo, hi, p);
        assert_close(solid.distance(p), distance, 1e-12, "distance");
        if clear_of_box(lo, hi, p, 1e-9) {
            assert_eq!(solid.inside(p), Some(inside), "{p:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Winding does not matter

#[test]
fn cube_wound_inwards_gives_the_same_answers() {
    let inward: Vec<Triangle> = box_triangles(UNIT_LO, UNIT_HI)
        .into_iter()
        .map(flipped)
        .collect();
    assert!(signed_volume(&inward) < 0.0);
    let cube = ReferenceSolid::from_triangles(inward);
    assert_eq!(cube.shell_count(), 1);
    assert_eq!(cube.inside([0.5, 0.5, 0.5]), Some(true));
    assert_eq!(cube.inside([0.5, 0.5, 1.5]), Some(false));
    check_against_unit_cube(&cube, 11);
}

#[test]
fn cube_with_one_triangle_flipped_gives_the_same_answers() {
    for which in [0, 5, 11] {
        let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
        triangles[which] = flipped(triangles[which]);
        let cube = ReferenceSolid::from_triangles(triangles);
        assert_eq!(cube.shell_count(), 1);
        check_against_unit_cube(&cube, 100 + which as u64);
    }
}

// ---------------------------------------------------------------------------------------------
// Two overlapping boxes: two shells, the union is the solid

const B_LO: [f64; 3] = [0.5, 0.25, 0.3];
const B_HI: [f64; 3] = [1.5, 1.25, 1.3];

fn check_two_boxes(solid: &ReferenceSolid) {
    assert_eq!(solid.shell_count(), 2);
    assert_eq!(solid.bounds(), (UNIT_LO, B_HI));

    // In the overlap.
    assert_eq!(solid.inside([0.75, 0.6, 0.65]), Some(true));
    // In A only, but the nearest triangle is B's face x = 0.5, which lies inside A: a test by the
    // nearest face's normal would call this point outside.
    let p = [0.45, 0.6, 0.65];
    assert_eq!(solid.inside(p), Some(true));
    assert_close(solid.distance(p), 0.05, 1e-15, "to B's face x = 0.5");
    // In B only.
    assert_eq!(solid.inside([1.3, 1.1, 1.2]), Some(true));
    // Outside both, nearest to B's face y = 0.25.
    let q = [1.3, 0.1, 0.5];
    assert_eq!(solid.inside(q), Some(false));
    assert_close(solid.distance(q), 0.15, 1e-15, "to B's face y = 0.25");

    let mut rng = Rng(0x1234_5678);
    let mut skipped = 0;
    for _ in 0..2000 {
        let p = rng.in_box(-0.3, 1.8);
        let (in_a, d_a) = box_closed_form(UNIT_LO, UNIT_HI, p);
        let (in_b, d_b) = box_closed_form(B_LO, B_HI, p);
        assert_close(solid.distance(p), d_a.min(d_b), 1e-12, "distance");
        if d_a.min(d_b) <= 1e-9 {
            continue;
        }
        match solid.inside(p) {
            Some(got) => assert_eq!(got, in_a || in_b, "inside {p:?}"),
            None => skipped += 1,
        }
    }
    assert!(skipped <= 2, "{skipped} undecided points");
}

#[test]
fn two_overlapping_boxes_are_two_shells_and_their_union_is_inside() {
    let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
    triangles.extend(box_triangles(B_LO, B_HI));
    check_two_boxes(&ReferenceSolid::from_triangles(triangles));
}

#[test]
fn two_overlapping_boxes_one_wound_inwards() {
    let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
    triangles.extend(box_triangles(B_LO, B_HI).into_iter().map(flipped));
    check_two_boxes(&ReferenceSolid::from_triangles(triangles));
    // And the triangles of the two shells interleaved: shells do not depend on the order.
    let a = box_triangles(UNIT_LO, UNIT_HI);
    let b: Vec<Triangle> = box_triangles(B_LO, B_HI).into_iter().map(flipped).collect();
    let mixed: Vec<Triangle> = a.into_iter().zip(b).flat_map(|(x, y)| [y, x]).collect();
    check_two_boxes(&ReferenceSolid::from_triangles(mixed));
}

#[test]
fn boxes_touching_at_one_vertex_are_one_shell() {
    let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
    triangles.extend(box_triangles([1.0, 1.0, 1.0], [2.0, 2.5, 3.0]));
    assert_eq!(ReferenceSolid::from_triangles(triangles).shell_count(), 1);
    // −0.0 and 0.0 are the same position.
    let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
    triangles.extend(box_triangles([-1.0, -1.0, -1.0], [-0.0, -0.0, -0.0]));
    assert_eq!(ReferenceSolid::from_triangles(triangles).shell_count(), 1);
}

#[test]
fn open_box_is_undecided_where_rays_leave_through_the_hole() {
    // The unit cube without its +z face (the last two triangles).
    let mut triangles = box_triangles(UNIT_LO, UNIT_HI);
    triangles.truncate(10);
    let open = ReferenceSolid::from_triangles(triangles);
    // Some of the five rays from here leave through the missing top, the others cross a wall.
    assert_eq!(open.inside([0.5, 0.5, 0.9]), None);
    // The distance needs no closed surface.
    assert_close(
        open.distance([0.5, 0.5, 0.9]),
        0.5,
        1e-15,
        "to the side walls",
    );
    assert_close(
        open.distance([0.5, 0.5, 1.2]),
        0.29f64.sqrt(),
        1e-15,
        "to the rim",
    );
}

// ---------------------------------------------------------------------------------------------
// Icosphere

/// Unit icosphere: the icosahedron with each triangle split into four `levels` times, new
/// vertices pushed onto the sphere. Shared edges give bit-identical midpoints.
fn icosphere(levels: usize) -> Vec<Triangle> {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let unit = |v: [f64; 3]| {
        let n = norm(v);
        v.map(|x| x / n)
    };
    let v: Vec<[f64; 3]> = [
        [-1.0, phi, 0.0],
        [1.0, phi, 0.0],
        [-1.0, -phi, 0.0],
        [1.0, -phi, 0.0],
        [0.0, -1.0, phi],
        [0.0, 1.0, phi],
        [0.0, -1.0, -phi],
        [0.0, 1.0, -phi],
        [phi, 0.0, -1.0],
        [phi, 0.0, 1.0],
        [-phi, 0.0, -1.0],
        [-phi, 0.0, 1.0],
    ]
    .into_iter()
    .map(unit)
    .collect();
    let faces = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut triangles: Vec<Triangle> = faces.iter().map(|f| f.map(|i| v[i])).collect();
    for _ in 0..levels {
        // (a + b) / 2 is the same for (b, a): floating-point addition commutes.
        let mid = |a: [f64; 3], b: [f64; 3]| unit([0, 1, 2].map(|k| (a[k] + b[k]) / 2.0));
        triangles = triangles
            .into_iter()
            .flat_map(|[a, b, c]| {
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    triangles
}

#[test]
fn icosphere_distance_is_r_minus_norm_within_the_tessellation_error() {
    let triangles = icosphere(3);
    assert_eq!(triangles.len(), 1280);
    assert!(signed_volume(&triangles) > 4.0, "wound outwards");
    // Every point of the mesh lies between the radius of the nearest face plane and 1, and
    // every point of the sphere has a mesh point straight below it no deeper than that: the
    // mesh and the sphere are within `tessellation` of each other (Hausdorff), so their
    // distance functions differ by at most that.
    let inner_radius = triangles
        .iter()
        .map(|[a, b, c]| {
            let n = cross(sub(*b, *a), sub(*c, *a));
            dot(n, *a).abs() / norm(n)
        })
        .fold(f64::INFINITY, f64::min);
    let tessellation = 1.0 - inner_radius;
    assert!(tessellation > 0.0 && tessellation < 0.02, "{tessellation}");

    // Every other triangle wound the other way: the answers must not change.
    let mixed: Vec<Triangle> = triangles
        .iter()
        .enumerate()
        .map(|(i, t)| if i % 2 == 0 { *t } else { flipped(*t) })
        .collect();
    for solid in [
        ReferenceSolid::from_triangles(triangles),
        ReferenceSolid::from_triangles(mixed),
    ] {
        assert_eq!(solid.shell_count(), 1);
        // The centre's nearest points are the feet on the nearest face planes.
        assert_close(solid.distance([0.0; 3]), inner_radius, 1e-12, "centre");
        assert_eq!(solid.inside([0.0; 3]), Some(true));
        let mut rng = Rng(42);
        let mut decided = 0;
        for _ in 0..400 {
            let p = rng.in_box(-1.6, 1.6);
            let r = norm(p);
            let want = (1.0 - r).abs();
            let got = solid.distance(p);
            assert!(
                (got - want).abs() <= tessellation + 1e-12,
                "{p:?}: distance {got}, sphere {want}"
            );
            if r < inner_radius - 1e-9 {
                assert_eq!(solid.inside(p), Some(true), "{p:?}");
                decided += 1;
            } else if r > 1.0 + 1e-9 {
                assert_eq!(solid.inside(p), Some(false), "{p:?}");
                decided += 1;
            }
        }
        assert!(decided > 350, "{decided}");
    }
}

// ---------------------------------------------------------------------------------------------
// Closest point on a triangle: against a second formula

/// The nearest point of a triangle written differently: the projection onto the plane when it
/// falls inside (all three edge tests agree in sign), otherwise the nearest of the three edges.
fn closest_by_projection_or_edges(p: [f64; 3], t: &Triangle) -> [f64; 3] {
    let segment = |a: [f64; 3], b: [f64; 3]| {
        let ab = sub(b, a);
        let len2 = dot(ab, ab);
        let s = if len2 == 0.0 {
            0.0
        } else {
            (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
        };
        [0, 1, 2].map(|k| a[k] + s * ab[k])
    };
    let mut best = [t[0], t[1], t[2]]
        .iter()
        .zip([t[1], t[2], t[0]])
        .map(|(a, b)| segment(*a, b))
        .min_by(|x, y| norm(sub(p, *x)).total_cmp(&norm(sub(p, *y))))
        .unwrap();
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let n2 = dot(n, n);
    if n2 > 0.0 {
        let foot_offset = dot(sub(p, t[0]), n) / n2;
        let foot = [0, 1, 2].map(|k| p[k] - foot_offset * n[k]);
        let inside = (0..3).all(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            dot(cross(sub(b, a), sub(foot, a)), n) >= 0.0
        });
        if inside && norm(sub(p, foot)) < norm(sub(p, best)) {
            best = foot;
        }
    }
    best
}

#[test]
fn closest_point_on_triangle_agrees_with_projection_or_edges() {
    let mut rng = Rng(2024);
    for i in 0..20_000 {
        let mut t: Triangle = [
            rng.in_box(-1.0, 1.0),
            rng.in_box(-1.0, 1.0),
            rng.in_box(-1.0, 1.0),
        ];
        match i % 10 {
            // A sliver: c almost on the line ab.
            0 => {
                t[2] = [0, 1, 2].map(|k| 0.3 * t[0][k] + 0.7 * t[1][k] + 1e-7 * t[2][k]);
            }
            // Collinear.
            1 => t[2] = [0, 1, 2].map(|k| 2.0 * t[1][k] - t[0][k]),
            // Two vertices at one point, and all three.
            2 => t[1] = t[0],
            3 => {
                t[1] = t[0];
                t[2] = t[0];
            }
            _ => {}
        }
        let p = rng.in_box(-2.0, 2.0);
        let a = norm(sub(p, closest_point_on_triangle(p, &t)));
        let b = norm(sub(p, closest_by_projection_or_edges(p, &t)));
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + b),
            "case {i}: {t:?}, p {p:?}: {a} vs {b}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// STL reader

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("mesh_reference_{}_{name}", std::process::id()))
}

fn write_binary_stl(path: &Path, header: &[u8], triangles: &[Triangle]) {
    let mut bytes = vec![0u8; 80];
    bytes[..header.len()].copy_from_slice(header);
    bytes.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        bytes.extend([0f32; 3].iter().flat_map(|x| x.to_le_bytes()));
        for v in t {
            bytes.extend(v.iter().flat_map(|x| (*x as f32).to_le_bytes()));
        }
        bytes.extend([0u8; 2]);
    }
    std::fs::write(path, bytes).unwrap();
}

fn write_ascii_stl(path: &Path, triangles: &[Triangle]) {
    let mut text = String::from("solid cube\n");
    for t in triangles {
        text.push_str("  facet normal 0 0 0\n    outer loop\n");
        for v in t {
            text.push_str(&format!("      vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        text.push_str("    endloop\n  endfacet\n");
    }
    text.push_str("endsolid cube\n");
    std::fs::write(path, text).unwrap();
}

#[test]
fn stl_binary_and_ascii_read_back_with_scale() {
    // A box in millimetres, with coordinates exact in f32.
    let mm = box_triangles([-20.0, 0.0, 12.5], [30.0, 40.0, 62.5]);
    let want: Vec<Triangle> = mm.iter().map(|t| t.map(|v| v.map(|x| x * 0.001))).collect();
    let files = [
        ("binary.stl", Some(&b"binary header"[..])),
        // Binary files whose header begins with "solid" exist; the length decides.
        ("binary_solid.stl", Some(&b"solid but binary"[..])),
        ("ascii.stl", None),
    ];
    for (name, header) in files {
        let path = temp_path(name);
        match header {
            Some(h) => write_binary_stl(&path, h, &mm),
            None => write_ascii_stl(&path, &mm),
        }
        let solid = ReferenceSolid::from_stl(&path, 0.001);
        std::fs::remove_file(&path).ok();
        assert_eq!(solid.triangles().len(), 12, "{name}");
        for (got, want) in solid.triangles().iter().zip(&want) {
            for (g, w) in got.iter().flatten().zip(want.iter().flatten()) {
                assert_close(*g, *w, 1e-15, name);
            }
        }
        assert_eq!(solid.shell_count(), 1);
        assert_eq!(solid.inside([0.0, 0.02, 0.03]), Some(true), "{name}");
        assert_close(solid.distance([0.0, 0.02, 0.07]), 0.0075, 1e-15, name);
    }
}

#[test]
fn robot_collision_meshes_parse() {
    // (file under tests/data/robots, triangles): the binary STL headers' counts.
    let meshes = [
        ("ur_description/meshes/ur5/collision/base.stl", 578),
        ("ur_description/meshes/ur5/collision/wrist3.stl", 446),
        ("franka_description/meshes/collision/link0.stl", 200),
        (
            "kuka_kr6_support/meshes/kr6r900sixx/collision/link_4.stl",
            786,
        ),
        (
            "abb_irb2400_support/meshes/irb2400/collision/link_5.stl",
            84,
        ),
    ];
    let root = crate::common::root().join("tests/data/robots");
    for (file, count) in meshes {
        let solid = ReferenceSolid::from_stl(&root.join(file), 1.0);
        assert_eq!(solid.triangles().len(), count, "{file}");
        let (lo, hi) = solid.bounds();
        // Metres, robot-sized.
        assert!(
            (0..3).all(|k| lo[k] < hi[k] && hi[k] - lo[k] < 1.0),
            "{file}"
        );
        let far = [hi[0] + 1.0, hi[1] + 1.0, hi[2] + 1.0];
        assert_eq!(solid.inside(far), Some(false), "{file}");
        assert!(solid.distance(far) >= 3f64.sqrt() - 1e-12, "{file}");
    }
}
