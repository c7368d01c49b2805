//! Dictionaries against independent references: the direction sample against the sphere's
//! geometry (cap areas, the octahedron's known covering radius), the stored results against
//! the attachment test run in the world frame at a robot pose with the same gravity in the
//! link, the lookup's required directions against gravity computed from the joint angles by
//! hand, `solve --dict` against a direct recomputation, and the bytes against the thread count.

use cable_dict::attachment::{ConnectMethod, Evaluator, TestPose};
use cable_dict::dictionary::directions::{covering_radius, fibonacci_sphere};
use cable_dict::dictionary::format::{PvRecord, Verdict};
use cable_dict::dictionary::{BuildOptions, Built, Dictionary, MotionLookup, build};
use cable_dict::motion::Motion;
use cable_dict::path::Pv;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, solve_with_dictionary};
use nalgebra::Vector3;
use std::path::Path;

const SETUP: &str = "tests/data/dict_setup.toml";
/// The intra-link segment of the fixture (C2, on link_4).
const C2: usize = 1;

fn setup() -> Setup {
    Setup::from_file(SETUP).expect("fixture setup")
}

fn built(setup: &Setup, directions: usize) -> Built {
    let options = BuildOptions {
        directions,
        shard: None,
    };
    build(setup, &options).expect("builds")
}

fn opened(dir: &Path, built: &Built) -> Dictionary {
    let path = dir.join("fixture.cdict");
    cable_dict::dictionary::write_dictionary(&path, built).expect("written");
    Dictionary::open(&path).expect("opens")
}

fn angle(a: &[f64; 3], b: &Vector3<f64>) -> f64 {
    (a[0] * b.x + a[1] * b.y + a[2] * b.z)
        .clamp(-1.0, 1.0)
        .acos()
}

#[test]
fn the_spiral_is_unit_and_area_uniform() {
    let n = 400;
    let points = fibonacci_sphere(n);
    assert!(
        points
            .iter()
            .all(|p| (Vector3::from(*p).norm() - 1.0).abs() < 1e-12)
    );
    // A cap z > h has area 2π(1 − h): it must hold its share (1 − h)/2 of the points, ± 1.
    for h in [-0.6, 0.0, 0.5, 0.9] {
        let inside = points.iter().filter(|p| p[2] > h).count() as f64;
        let expected = n as f64 * (1.0 - h) / 2.0;
        assert!(
            (inside - expected).abs() <= 1.0,
            "cap z > {h}: {inside} vs {expected}"
        );
    }
}

#[test]
fn the_covering_radius_of_the_octahedron_is_its_face_centre_angle() {
    let octahedron = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let exact = (1.0 / 3f64.sqrt()).acos();
    let estimate = covering_radius(&octahedron);
    assert!(estimate >= exact, "{estimate} < {exact}");
    assert!(estimate < exact + 0.02, "{estimate} vs {exact}");
}

#[test]
fn the_covering_radius_bounds_the_gap_of_every_probe_direction() {
    let directions = fibonacci_sphere(64);
    let radius = covering_radius(&directions);
    // Probe directions from a fixed pseudo-random sequence, independent of the spiral.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut uniform = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20_000 {
        let z = 2.0 * uniform() - 1.0;
        let phi = 2.0 * std::f64::consts::PI * uniform();
        let r = (1.0 - z * z).sqrt();
        let probe = Vector3::new(r * phi.cos(), r * phi.sin(), z);
        let nearest = directions
            .iter()
            .map(|d| angle(d, &probe))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest <= radius, "{nearest} > {radius}");
    }
}

/// The stored result of a PV and direction equals the attachment test of the same PV in the
/// world frame, at a robot pose where gravity, seen from link_4, points along that direction.
#[test]
fn stored_results_match_the_attachment_test_at_a_pose_with_that_gravity() {
    let setup = setup();
    let dir = tempfile::tempdir().expect("temp dir");
    let dictionary = opened(dir.path(), &built(&setup, 16));
    let joints = [0.3, -0.5, 1.9, 0.7, 0.4, 0.1];
    let link_poses = setup.robot.link_poses(&joints).expect("pose");
    let link_4 = setup.robot.link_index("link_4").expect("link_4");
    let pose = TestPose {
        sample: 0,
        time_s: 0.0,
        joints: joints.to_vec(),
        reason: "test".into(),
        link_poses: link_poses.clone(),
    };
    let g = setup.gravity_m_s2.norm();
    let mut compared = 0;
    for (k, record) in dictionary.pv_records().iter().enumerate() {
        if !record.has(PvRecord::ADMISSIBLE) || record.sub_segments == 0 {
            continue;
        }
        let pv = Pv {
            sub_segments: record.sub_segments as usize,
            start: record.start as usize,
            end: record.end as usize,
        };
        for d in [0, 5, 11] {
            let stored = dictionary.results()[k * 16 + d];
            let direction = Vector3::from(dictionary.directions()[d]);
            let mut world = setup.clone();
            world.gravity_m_s2 = link_poses[link_4].rotation * (direction * g);
            let evaluator = Evaluator::new(&world, ConnectMethod::Hermite).expect("evaluator");
            let check = evaluator.check(C2, &pv, &pose);
            let Some(metrics) = check.metrics else {
                assert_eq!(
                    Verdict::from_rejection(check.rejection) as u8,
                    stored.verdict,
                    "{pv:?} direction {d}"
                );
                continue;
            };
            let close = |a: f32, b: f64| (f64::from(a) - b).abs() <= 1e-4 * b.abs().max(1.0);
            assert!(close(stored.stretch, metrics.stretch), "{pv:?} {d}");
            assert!(
                close(stored.min_bend_radius_mm, metrics.min_bend_radius_m * 1e3),
                "{pv:?} {d}: {} vs {}",
                stored.min_bend_radius_mm,
                metrics.min_bend_radius_m * 1e3
            );
            // The world test sees every link; the dictionary only link_4, so it can only be
            // farther from an obstacle, and equal when the nearest link is link_4.
            // NaN: no sub-segment outside the clamp zones faces link_4.
            if let Some(world_mm) = metrics.clearance_m.map(|c| c * 1e3)
                && !stored.clearance_mm.is_nan()
            {
                assert!(
                    f64::from(stored.clearance_mm) >= world_mm - 1e-3,
                    "{pv:?} {d}: {} vs {world_mm} ({:?})",
                    stored.clearance_mm,
                    metrics.clearance_link
                );
                if metrics.clearance_link == Some(link_4) {
                    assert!(close(stored.clearance_mm, world_mm), "{pv:?} {d}");
                    assert_eq!(
                        Verdict::from_rejection(check.rejection) as u8,
                        stored.verdict
                    );
                }
            }
            compared += 1;
        }
    }
    assert!(compared >= 20, "only {compared} comparisons");
}

#[test]
fn the_motion_requires_the_directions_around_gravity_in_the_link_frame() {
    let setup = setup();
    let dir = tempfile::tempdir().expect("temp dir");
    let dictionary = opened(dir.path(), &built(&setup, 64));
    // Two samples: the zero pose (forearm up: gravity along −z of link_4) and joint 2 at
    // 45° (link_4 turned by 45° about y: gravity (sin 45°, 0, −cos 45°) in link_4).
    let header = "time_s,joint_1_deg,joint_2_deg,joint_3_deg,joint_4_deg,joint_5_deg,joint_6_deg";
    let csv = format!("{header}\n0,0,0,0,0,0,0\n1,0,45,0,0,0,0\n");
    let motion = Motion::from_csv_str(&setup.robot, &csv, Path::new("two.csv")).expect("motion");
    let lookup = MotionLookup::new(&dictionary, &setup, &motion).expect("lookup");
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let gravity_in_link = [Vector3::new(0.0, 0.0, -1.0), Vector3::new(s, 0.0, -s)];
    let radius = dictionary.header().directions.covering_radius_rad;
    let directions = dictionary.directions();
    let nearest = |u: &Vector3<f64>| {
        (0..directions.len())
            .min_by(|&a, &b| angle(&directions[a], u).total_cmp(&angle(&directions[b], u)))
            .expect("directions")
    };
    let expected: Vec<bool> = (0..directions.len())
        .map(|k| {
            gravity_in_link
                .iter()
                .any(|u| angle(&directions[k], u) <= radius + 1e-9 || nearest(u) == k)
        })
        .collect();
    assert_eq!(lookup.required(C2).expect("intra-link"), &expected[..]);
    assert!(lookup.required(0).is_none(), "C1 is inter-link");
}

/// `solve --dict`'s intra-link D1 is exactly the candidates that pass the static test at
/// every direction the motion requires, recomputed here PV by PV.
#[test]
fn solve_with_a_dictionary_keeps_the_pvs_that_pass_every_required_direction() {
    let setup = setup();
    let dir = tempfile::tempdir().expect("temp dir");
    let dictionary = opened(dir.path(), &built(&setup, 16));
    let motion = Motion::from_csv_file(&setup.robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let options = SolveOptions {
        motion_test: false,
        ..SolveOptions::default()
    };
    let report = solve_with_dictionary(&dictionary, &setup, &motion, &options).expect("solves");
    let lookup = MotionLookup::new(&dictionary, &setup, &motion).expect("lookup");
    let required = lookup.required(C2).expect("intra-link");
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    let g = setup.gravity_m_s2.norm();
    let d1 = cable_dict::attachment::admissible_pvs(&setup, C2)
        .into_iter()
        .filter(|pv| {
            dictionary
                .directions()
                .iter()
                .zip(required)
                .filter(|(_, needed)| **needed)
                .all(|(d, _)| {
                    evaluator
                        .check_in_link_frame(C2, pv, &(Vector3::from(*d) * g))
                        .passed()
                })
        })
        .count();
    assert_eq!(report.segments[C2].d1, d1);
    assert!(d1 > 0, "the fixture keeps some PVs");
    let used = report.inputs.dictionary.as_ref().expect("dictionary named");
    assert_eq!(
        used.required_directions,
        vec![("C2".to_string(), lookup.required_count(C2))]
    );
}

#[test]
fn the_bytes_do_not_depend_on_the_thread_count() {
    let setup = setup();
    let bytes = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| built(&setup, 12).to_bytes().expect("encodes"))
    };
    assert_eq!(bytes(1), bytes(2));
}
