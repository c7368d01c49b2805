//! The closed-form segment minima against a brute-force oracle on random segments, and the
//! mesh solid against the equivalent box.

use super::mesh::{MeshSolid, SolidMesh, solids_of};
use super::primitives::*;
use nalgebra::{Point3, Vector3};

/// xorshift64*: reproducible pseudo-random numbers without a dependency.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A point in ±`extent`, sometimes with a coordinate snapped to a special value so that
    /// axis-parallel and face-aligned segments are covered.
    fn point(&mut self, extent: &Vector3<f64>, snaps: &[f64]) -> Point3<f64> {
        Point3::from(Vector3::from_fn(|i, _| {
            if self.unit() < 0.15 {
                snaps[(self.unit() * snaps.len() as f64) as usize % snaps.len()] * extent[i] * 0.5
            } else {
                self.range(-extent[i], extent[i])
            }
        }))
    }
}

/// Minimum over t ∈ [0, 1] of a convex function: dense samples, then golden section.
fn oracle(f: impl Fn(f64) -> f64) -> f64 {
    const N: usize = 400;
    let (mut bi, mut bv) = (0, f(0.0));
    for i in 1..=N {
        let v = f(i as f64 / N as f64);
        if v < bv {
            (bi, bv) = (i, v);
        }
    }
    let mut lo = bi.saturating_sub(1) as f64 / N as f64;
    let mut hi = (bi + 1).min(N) as f64 / N as f64;
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (x1, x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
        if f(x1) <= f(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    bv.min(f(0.5 * (lo + hi)))
}

fn check_shape(
    name: &str,
    extent: Vector3<f64>,
    sd: impl Fn(&Point3<f64>) -> f64,
    segment: impl Fn(&Point3<f64>, &Point3<f64>) -> SegmentMin,
    project: impl Fn(&Point3<f64>) -> Projection,
) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let snaps = [-2.0, -1.0, 0.0, 1.0, 2.0];
    for case in 0..4000 {
        let a = rng.point(&extent, &snaps);
        let b = if case % 5 == 0 {
            // Short sub-segment-like pieces.
            a + Vector3::from_fn(|_, _| rng.range(-0.02, 0.02))
        } else {
            rng.point(&extent, &snaps)
        };
        let e = b - a;
        let found = segment(&a, &b);
        let want = oracle(|t| sd(&(a + e * t)));
        assert!(
            (0.0..=1.0).contains(&found.t),
            "{name} case {case}: t {}",
            found.t
        );
        let at_t = sd(&(a + e * found.t));
        assert!(
            (at_t - found.sd).abs() < 1e-13,
            "{name} case {case}: reported {} but sd there {at_t}",
            found.sd
        );
        assert!(
            found.sd <= want + 1e-13,
            "{name} case {case}: a {a:?} b {b:?}: found {} above oracle {want}",
            found.sd
        );
        assert!(
            found.sd >= want - 1e-9,
            "{name} case {case}: found {} below oracle {want}?",
            found.sd
        );
        // Projection: p = q + sd·n, q on the surface, n a unit vector.
        let p = a + e * found.t;
        let pr = project(&p);
        assert!((pr.sd - sd(&p)).abs() < 1e-14, "{name} case {case}");
        assert!((pr.n.norm() - 1.0).abs() < 1e-12, "{name} case {case}");
        assert!(
            (pr.q + pr.n * pr.sd - p).norm() < 1e-12,
            "{name} case {case}"
        );
        assert!(sd(&pr.q).abs() < 1e-12, "{name} case {case}");
    }
}

#[test]
fn box_minimum_matches_the_oracle() {
    let h = Vector3::new(0.25, 0.08, 0.075);
    check_shape(
        "box",
        2.0 * h,
        |p| box_sd(&h, p),
        |a, b| box_segment(&h, a, b),
        |p| box_project(&h, p),
    );
}

#[test]
fn cylinder_minimum_matches_the_oracle() {
    let (r, hl) = (0.06, 0.115);
    check_shape(
        "cylinder",
        Vector3::new(2.0 * r, 2.0 * r, 2.0 * hl),
        |p| cylinder_sd(r, hl, p),
        |a, b| cylinder_segment(r, hl, a, b),
        |p| cylinder_project(r, hl, p),
    );
    // A flat disc and a long thin rod stress the rim and the inside crossings.
    for (r, hl) in [(0.1, 0.005), (0.01, 0.3)] {
        check_shape(
            "cylinder",
            Vector3::new(2.0 * r, 2.0 * r, 2.0 * hl),
            |p| cylinder_sd(r, hl, p),
            |a, b| cylinder_segment(r, hl, a, b),
            |p| cylinder_project(r, hl, p),
        );
    }
}

#[test]
fn sphere_and_capsule_minima_match_the_oracle() {
    let r = 0.07;
    check_shape(
        "sphere",
        Vector3::repeat(2.0 * r),
        |p| p.coords.norm() - r,
        |a, b| sphere_segment(r, a, b),
        |p| sphere_project(r, p),
    );
    let hl = 0.1;
    let capsule_sd = |p: &Point3<f64>| (p - Point3::new(0.0, 0.0, p.z.clamp(-hl, hl))).norm() - r;
    check_shape(
        "capsule",
        Vector3::new(2.0 * r, 2.0 * r, 2.0 * (hl + r)),
        capsule_sd,
        |a, b| capsule_segment(r, hl, a, b),
        |p| capsule_project(r, hl, p),
    );
}

/// Vertices and the 12 triangles of the box ±h centred at `c`, outward (or inward) wound.
fn cube(h: &Vector3<f64>, c: Vector3<f64>, inward: bool) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
    let vertices: Vec<Point3<f64>> = (0..8)
        .map(|i| {
            let s = |bit: usize| if i & bit != 0 { 1.0 } else { -1.0 };
            Point3::from(c + Vector3::new(s(1) * h.x, s(2) * h.y, s(4) * h.z))
        })
        .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    if inward {
        triangles.iter_mut().for_each(|t| t.swap(1, 2));
    }
    (vertices, triangles)
}

/// A mesh's parts, and the mesh solid that combines them for the contact search.
struct Union(Vec<SolidMesh>, MeshSolid);

impl Union {
    fn new(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Union {
        match (
            solids_of(vertices, triangles),
            MeshSolid::new(vertices, triangles),
        ) {
            (Ok(parts), Ok(solid)) => Union(parts, solid),
            (Err(e), _) | (_, Err(e)) => panic!("mesh refused: {e}"),
        }
    }

    fn closed_parts(&self) -> usize {
        self.0.iter().filter(|p| p.is_closed_shell()).count()
    }

    fn segment_min(&self, a: &Point3<f64>, b: &Point3<f64>, cutoff: f64) -> SegmentMin {
        self.1.segment_min(a, b, cutoff)
    }

    fn signed_distance(&self, p: &Point3<f64>) -> f64 {
        self.0
            .iter()
            .map(|part| {
                let nearest = part.nearest(p);
                if part.is_inside(p, &nearest) {
                    -nearest.distance
                } else {
                    nearest.distance
                }
            })
            .fold(f64::INFINITY, f64::min)
    }
}

#[test]
fn a_closed_cube_mesh_is_the_box() {
    let h = Vector3::new(0.1, 0.06, 0.04);
    for inward in [false, true] {
        let (vertices, triangles) = cube(&h, Vector3::zeros(), inward);
        let mesh = Union::new(&vertices, &triangles);
        assert_eq!((mesh.0.len(), mesh.closed_parts()), (1, 1));
        // From a point of the top face down to the centre (no crossing, touching at t = 0),
        // and lying in the top face.
        let top = Point3::new(0.01, 0.0, h.z);
        assert_eq!(
            mesh.segment_min(&top, &Point3::origin(), f64::INFINITY).sd,
            -h.z
        );
        let in_face = mesh
            .segment_min(&top, &Point3::new(-0.05, 0.02, h.z), f64::INFINITY)
            .sd;
        assert!(in_face.abs() < 1e-15, "{in_face}");
        let mut rng = Rng(12345);
        for case in 0..3000 {
            let a = rng.point(&(2.0 * h), &[-2.0, -1.0, 0.0, 1.0, 2.0]);
            let b = if case % 3 == 0 {
                a + Vector3::from_fn(|_, _| rng.range(-0.02, 0.02))
            } else {
                rng.point(&(2.0 * h), &[-2.0, -1.0, 0.0, 1.0, 2.0])
            };
            let want = box_segment(&h, &a, &b).sd;
            let got = mesh.segment_min(&a, &b, f64::INFINITY);
            assert!(
                (got.sd - want).abs() < 1e-12,
                "inward {inward} case {case}: a {a:?} b {b:?}: mesh {} box {want}",
                got.sd
            );
            assert!(
                (mesh.signed_distance(&a) - box_sd(&h, &a)).abs() < 1e-12,
                "case {case}"
            );
        }
    }
}

/// Two boxes that overlap, in one mesh, the second wound inward as some vendor shells are:
/// points inside the first box whose nearest face belongs to the second (inside the first)
/// are inside, and the segment minimum is the lower of the two boxes' — the union.
#[test]
fn a_mesh_of_two_overlapping_cubes_is_their_union() {
    let (ha, hb) = (
        Vector3::new(0.05, 0.04, 0.03),
        Vector3::new(0.02, 0.06, 0.05),
    );
    let cb = Vector3::new(0.04, 0.01, -0.02);
    let (mut vertices, mut triangles) = cube(&ha, Vector3::zeros(), false);
    let (vb, tb) = cube(&hb, cb, true);
    triangles.extend(tb.iter().map(|t| t.map(|v| v + 8)));
    vertices.extend(vb);
    let mesh = Union::new(&vertices, &triangles);
    assert_eq!((mesh.0.len(), mesh.closed_parts()), (2, 2));
    // Inside the first box, 5 mm from the second box's face x = 0.02 and 20 mm from the
    // first box's nearest face.
    let p = Point3::new(0.015, 0.0, 0.01);
    assert!((mesh.signed_distance(&p) + 0.02).abs() < 1e-15);
    let mut rng = Rng(777);
    let extent = Vector3::new(0.1, 0.1, 0.1);
    for case in 0..2000 {
        let a = rng.point(&extent, &[0.0]);
        let b = rng.point(&extent, &[0.0]);
        let want = box_segment(&ha, &a, &b)
            .sd
            .min(box_segment(&hb, &(a - cb), &(b - cb)).sd);
        let got = mesh.segment_min(&a, &b, f64::INFINITY).sd;
        assert!(
            (got - want).abs() < 1e-12,
            "case {case}: a {a:?} b {b:?}: mesh {got} union {want}"
        );
        // With a cutoff: exact at or below it, only "above" above it.
        let cutoff = want + rng.range(-0.01, 0.01);
        let got = mesh.segment_min(&a, &b, cutoff).sd;
        if want <= cutoff {
            assert!((got - want).abs() < 1e-12, "case {case}: cutoff {cutoff}");
        } else {
            assert!(got > cutoff, "case {case}: {got} not above cutoff {cutoff}");
        }
    }
}

/// A box with one triangle missing on its +x face: a loose shell, its inside decided by the
/// winding number — the box's away from the hole.
#[test]
fn a_cube_with_a_hole_is_still_a_solid_away_from_the_hole() {
    let h = Vector3::new(0.1, 0.06, 0.04);
    let (vertices, mut triangles) = cube(&h, Vector3::zeros(), false);
    triangles.retain(|t| *t != [1, 3, 5]);
    let mesh = Union::new(&vertices, &triangles);
    assert_eq!((mesh.0.len(), mesh.closed_parts()), (1, 0));
    let mut rng = Rng(4242);
    for case in 0..2000 {
        let p = rng.point(&(2.0 * h), &[0.0]);
        if p.x > 0.0 && p.x.abs() > 0.5 * h.x {
            continue; // near the hole
        }
        let (got, want) = (mesh.signed_distance(&p), box_sd(&h, &p));
        assert!(
            (got - want).abs() < 1e-12,
            "case {case}: {p:?}: {got} vs box {want}"
        );
    }
}

#[test]
fn an_open_mesh_is_a_bare_surface() {
    // One square, z = 0, |x|, |y| ≤ 1.
    let vertices = [
        Point3::new(-1.0, -1.0, 0.0),
        Point3::new(1.0, -1.0, 0.0),
        Point3::new(1.0, 1.0, 0.0),
        Point3::new(-1.0, 1.0, 0.0),
    ];
    let mesh = Union::new(&vertices, &[[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.closed_parts(), 0);
    let crossing = mesh.segment_min(
        &Point3::new(0.2, 0.1, -0.5),
        &Point3::new(0.2, 0.1, 0.5),
        1.0,
    );
    assert_eq!(crossing.sd, 0.0);
    assert!((crossing.t - 0.5).abs() < 1e-15);
    let beside = mesh.segment_min(
        &Point3::new(1.5, 0.0, -0.5),
        &Point3::new(1.5, 0.0, 0.5),
        1.0,
    );
    assert!((beside.sd - 0.5).abs() < 1e-15);
    assert!((mesh.signed_distance(&Point3::new(0.0, 0.0, -0.01)) - 0.01).abs() < 1e-15);
}

#[test]
fn degenerate_meshes_are_refused() {
    let line = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(2.0, 0.0, 0.0),
    ];
    let err = solids_of(&line, &[[0, 1, 2]]).expect_err("zero area");
    assert!(err.contains("zero area"), "{err}");
    let err = solids_of(&line, &[[0, 1, 3]]).expect_err("bad index");
    assert!(err.contains("vertex"), "{err}");
}
