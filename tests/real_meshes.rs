//! The contact test on real robots' collision meshes (tests/data/robots: UR5, Franka Panda,
//! KUKA KR6 R900 sixx, ABB IRB 2400 — STL files as their vendors' ROS packages ship them,
//! several shells per link, overlapping or touching, some wound inward), judged by an
//! independent brute-force reference (tests/reference/mesh_solid.rs: its own STL reader,
//! shells by shared vertices, inside by ray parity over five directions, distances to every
//! triangle). The reference's definition of the clearance is the library's: outside the union
//! of the shells, the distance to the nearest triangle; inside, minus the depth below the
//! surface of the shell the point is deepest in.

use crate::reference;

use cable_dict::pose::Pose;
use cable_dict::robot::{Robot, Shape, TriMesh};
use cable_dict::stress::{Obstacles, min_clearance, min_clearance_to_links};
use nalgebra::{Point3, Vector3};
use reference::mesh_solid::ReferenceSolid;
use std::path::PathBuf;

fn robots() -> PathBuf {
    crate::common::root().join("tests/data/robots")
}

const ROBOTS: [&str; 4] = [
    "ur_description/urdf/ur5.urdf",
    "franka_description/urdf/panda.urdf",
    "kuka_kr6_support/urdf/kr6r900sixx.urdf",
    "abb_irb2400_support/urdf/irb2400.urdf",
];

/// xorshift64*: reproducible points without a dependency.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn in_box(&mut self, lo: [f64; 3], hi: [f64; 3], margin: f64) -> [f64; 3] {
        [0, 1, 2].map(|k| lo[k] - margin + (hi[k] - lo[k] + 2.0 * margin) * self.unit())
    }
}

/// The reference's signed clearance of a point (mesh frame), `None` where its rays disagree or
/// the point is within a micrometre of a surface. `exact_depth`: the reference's shells are the
/// library's (no shells touching), so the depth below the deepest shell is comparable.
fn reference_sd(solid: &ReferenceSolid, p: [f64; 3]) -> Option<f64> {
    let inside = solid.inside(p)?;
    let nearest = solid.distance(p);
    if nearest < 1e-6 {
        return None;
    }
    if !inside {
        return Some(nearest);
    }
    let mut deepest = 0.0f64;
    for shell in 0..solid.shell_count() {
        if solid.inside_shell(p, shell)? {
            deepest = deepest.max(solid.distance_to_shell(p, shell));
        }
    }
    Some(-deepest)
}

/// The library's signed clearance of a point (mesh frame of collider `c` of link `l`) to that
/// link, through the public clearance query with a zero-length cable of radius 0.
fn library_sd(obstacles: &Obstacles, poses: &[Pose], l: usize, origin: &Pose, p: [f64; 3]) -> f64 {
    let world = poses[l] * origin * Point3::from(p);
    min_clearance_to_links(obstacles, poses, &[world, world], 0.0, &[], &[l])
        .expect("valid query")
        .expect("the link is checked")
        .clearance_m
}

struct MeshCase<'a> {
    link: usize,
    origin: Pose,
    mesh: &'a TriMesh,
}

fn mesh_colliders(robot: &Robot) -> Vec<MeshCase<'_>> {
    robot
        .links
        .iter()
        .enumerate()
        .flat_map(|(l, link)| {
            link.colliders.iter().filter_map(move |c| match &c.shape {
                Shape::Mesh(mesh) => Some(MeshCase {
                    link: l,
                    origin: c.origin,
                    mesh,
                }),
                _ => None,
            })
        })
        .collect()
}

/// Points around every mesh of every robot: the sign of the clearance always agrees with the
/// reference's inside test; outside the value is the reference's distance; inside it is the
/// reference's depth where the reference's shells are the library's (none of them touch), and
/// no less deep than the nearest surface where shells touch (the reference then merges them).
#[test]
fn points_inside_and_outside_every_link_agree_with_the_reference() {
    let mut rng = Rng(0x5eed_cafe);
    for file in ROBOTS {
        let robot = Robot::from_urdf_file(robots().join(file)).unwrap_or_else(|e| panic!("{e}"));
        let obstacles = Obstacles::from_robot(&robot).unwrap_or_else(|e| panic!("{e}"));
        let poses = robot.link_poses(&vec![0.0; robot.dof()]).unwrap();
        for case in mesh_colliders(&robot) {
            let solid = ReferenceSolid::from_stl(&case.mesh.file, 1.0);
            let (lo, hi) = solid.bounds();
            let library_box = case.mesh.vertices.iter().fold(
                (
                    Vector3::repeat(f64::INFINITY),
                    Vector3::repeat(f64::NEG_INFINITY),
                ),
                |(a, b), v| (a.inf(&v.coords), b.sup(&v.coords)),
            );
            assert!(
                (library_box.0 - Vector3::from(lo)).norm() < 1e-9
                    && (library_box.1 - Vector3::from(hi)).norm() < 1e-9,
                "{}: the reference reads the mesh at the URDF's scale",
                case.mesh.file.display()
            );
            let library_shells = case.mesh.shells().shells.len();
            let exact_depth = solid.shell_count() == library_shells;
            let (mut inside, mut outside) = (0, 0);
            // A margin of a tenth of the mesh's smallest extent, so thin parts (a flange) are
            // hit inside as often as large ones.
            let smallest = (0..3).map(|k| hi[k] - lo[k]).fold(f64::INFINITY, f64::min);
            let margin = 0.1 * smallest;
            for _ in 0..600 {
                if inside >= 20 && outside >= 20 {
                    break;
                }
                let p = rng.in_box(lo, hi, margin);
                let Some(want) = reference_sd(&solid, p) else {
                    continue;
                };
                let got = library_sd(&obstacles, &poses, case.link, &case.origin, p);
                let what = format!(
                    "{} at {p:?}: library {got}, reference {want}",
                    case.mesh.file.display()
                );
                assert_eq!(got < 0.0, want < 0.0, "sign: {what}");
                if want > 0.0 || exact_depth {
                    assert!((got - want).abs() < 1e-9, "{what}");
                } else {
                    assert!(got <= -solid.distance(p) + 1e-9, "depth bound: {what}");
                }
                if want < 0.0 {
                    inside += 1;
                } else {
                    outside += 1;
                }
            }
            assert!(
                inside >= 20 && outside >= 20,
                "{}: {inside} points inside, {outside} outside",
                case.mesh.file.display()
            );
        }
    }
}

/// Cable pieces of 10–40 mm near the UR5's and the KUKA's links, clear of them by the
/// reference at 400 points along each: the library's exact minimum is at most the sampled
/// minimum and at least it minus half the sample spacing (the clearance is 1-Lipschitz).
#[test]
fn clearances_of_pieces_near_the_meshes_match_a_sampled_brute_force() {
    let mut rng = Rng(0xfeed_beef);
    for file in [ROBOTS[0], ROBOTS[2]] {
        let robot = Robot::from_urdf_file(robots().join(file)).unwrap_or_else(|e| panic!("{e}"));
        let obstacles = Obstacles::from_robot(&robot).unwrap();
        let poses = robot.link_poses(&vec![0.0; robot.dof()]).unwrap();
        for case in mesh_colliders(&robot) {
            let solid = ReferenceSolid::from_stl(&case.mesh.file, 1.0);
            let (lo, hi) = solid.bounds();
            let mut checked = 0;
            for _ in 0..40 {
                let a = rng.in_box(lo, hi, 0.04);
                let dir =
                    Vector3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5).normalize();
                let length = 0.01 + 0.03 * rng.unit();
                let b = (Vector3::from(a) + dir * length).into();
                const SAMPLES: usize = 400;
                let sampled: Option<Vec<f64>> = (0..=SAMPLES)
                    .map(|i| {
                        let t = i as f64 / SAMPLES as f64;
                        let p: [f64; 3] =
                            (Vector3::from(a) * (1.0 - t) + Vector3::from(b) * t).into();
                        reference_sd(&solid, p).filter(|&sd| sd > 0.0)
                    })
                    .collect();
                let Some(sampled) = sampled else {
                    continue; // touches or enters the solid somewhere: not this test's case
                };
                let want = sampled.iter().copied().fold(f64::INFINITY, f64::min);
                let to_world = |p: [f64; 3]| poses[case.link] * case.origin * Point3::from(p);
                let got = min_clearance_to_links(
                    &obstacles,
                    &poses,
                    &[to_world(a), to_world(b)],
                    0.0,
                    &[],
                    &[case.link],
                )
                .unwrap()
                .unwrap()
                .clearance_m;
                let slack = 0.5 * length / SAMPLES as f64;
                assert!(
                    got <= want + 1e-9 && got >= want - slack - 1e-9,
                    "{}: piece {a:?} → {b:?}: library {got}, sampled {want}",
                    case.mesh.file.display()
                );
                checked += 1;
            }
            assert!(
                checked >= 5,
                "{}: only {checked} pieces clear",
                case.mesh.file.display()
            );
        }
    }
}

/// Issue 25's case: at joints (0, −90, 90, −90, −90, 0) deg a 20 mm piece at x = 86 mm lies
/// inside the UR5's forearm, where two shells meet inside the link; it was reported clear by
/// 8.0 mm. Its clearance is now the reference's: the deepest of 2001 points along its axis,
/// less the cable radius.
#[test]
fn the_piece_inside_the_ur5_forearm_is_in_contact() {
    let robot = Robot::from_urdf_file(robots().join(ROBOTS[0])).unwrap();
    let obstacles = Obstacles::from_robot(&robot).unwrap();
    let q: Vec<f64> = [0.0f64, -90.0, 90.0, -90.0, -90.0, 0.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let poses = robot.link_poses(&q).unwrap();
    let radius = 0.004;
    let forearm = robot.link_index("forearm_link").unwrap();
    let case = mesh_colliders(&robot)
        .into_iter()
        .find(|c| c.link == forearm)
        .unwrap();
    let solid = ReferenceSolid::from_stl(&case.mesh.file, 1.0);
    for x_mm in [86.0, 334.9] {
        let a = Point3::new(x_mm, 5.95, 517.159) * 1e-3;
        let b = Point3::new(x_mm, 5.95, 497.159) * 1e-3;
        let found = min_clearance(&obstacles, &poses, &[a, b], radius, &[])
            .unwrap()
            .unwrap();
        assert_eq!(found.link, forearm);
        let to_mesh = (poses[forearm] * case.origin).inverse();
        let deepest = (0..=2000)
            .filter_map(|i| {
                let p = a + (b - a) * (i as f64 / 2000.0);
                reference_sd(&solid, (to_mesh * p).coords.into())
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            deepest < -0.01,
            "x = {x_mm}: the reference puts the piece inside ({deepest})"
        );
        let want = deepest - radius;
        assert!(
            found.clearance_m <= want + 1e-9 && found.clearance_m >= want - 1e-5,
            "x = {x_mm} mm: {:.4} mm, reference {:.4} mm",
            found.clearance_m * 1e3,
            want * 1e3
        );
    }
}
