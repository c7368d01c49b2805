//! Dictionaries against independent references: the direction sample against the sphere's
//! geometry (cap areas, the octahedron's known covering radius), the stored margins against
//! the attachment test run in the world frame at a robot pose with the same gravity in the
//! link, the interpolation against a brute-force neighbour search, the lookup against the
//! exact test at random directions (no false reject), `solve --dict` against `solve --setup`
//! on every bundled motion, and the bytes against the thread count.

use cable_dict::attachment::{
    ConnectMethod, Evaluator, GRAVITY_RESOLUTION_DEG, Margins, SegmentPoses, TestPose,
};
use cable_dict::dictionary::directions::{
    Neighbours, covering_radius, fibonacci_sphere, probe_directions,
};
use cable_dict::dictionary::format::{MARGIN_UNITS, MarginRecord, PvRecord};
use cable_dict::dictionary::{
    BuildOptions, Built, Dictionary, DirectionAnswer, MotionLookup, build,
};
use cable_dict::motion::Motion;
use cable_dict::path::Pv;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, solve, solve_with_dictionary};
use nalgebra::Vector3;
use rayon::prelude::*;
use std::path::Path;

const SETUP: &str = "tests/data/dict_setup.toml";
const HAND_WRITTEN_PICK_AND_PLACE: &str = "robots/viper_s850/hand_written/pick_and_place.toml";
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

/// The dictionary of a bundled setup at `directions`, built once per test binary (the
/// hand-written pick-and-place catalogue takes about 11 s at 64 directions).
fn shared(path: &'static str, directions: usize) -> &'static Dictionary {
    crate::common::built_dictionary(path, directions)
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

/// The stored margins of a PV and direction equal the attachment test of the same PV in the
/// world frame (clearance against link_4, as for an intra-link segment), at a robot pose
/// where gravity, seen from link_4, points along that direction — to the fixed-point unit.
#[test]
fn stored_margins_match_the_attachment_test_at_a_pose_with_that_gravity() {
    let setup = setup();
    let dir = tempfile::tempdir().expect("temp dir");
    let dictionary = opened(dir.path(), &built(&setup, 16));
    let joints = [0.3, -0.5, 1.9, 0.7, 0.4, 0.1];
    let link_poses = setup.robot.link_poses(&joints).expect("pose");
    let link_4 = setup.robot.link_index("link_4").expect("link_4");
    let pose = TestPose {
        motion: 0,
        sample: 0,
        time_s: 0.0,
        grid: false,
        joints: joints.to_vec(),
        reason: "test".into(),
        link_poses: link_poses.clone(),
        clearance_link: Some(link_4),
    };
    let g = setup.gravity_m_s2.norm();
    let (mut compared, mut unmeasured) = (0, 0);
    // The setup's own PVs, found in link_4's catalogue through their clamp poses.
    let stored_segment = dictionary.stored_segment(&setup, C2).expect("C2 stored");
    let pieces = admissible_pairs(&setup, C2)
        .into_iter()
        .flat_map(|((start, end), lengths)| {
            lengths.into_iter().map(move |s| Pv::new(s, start, end))
        });
    for pv in pieces {
        let piece = stored_segment.piece(&pv).expect("mapped");
        let (record, rows) = dictionary
            .lookup(stored_segment.slot, &piece)
            .expect("stored");
        assert!(record.has(PvRecord::ADMISSIBLE) && record.pv() == piece);
        for d in [0, 5, 11] {
            let stored = rows[d];
            let direction = Vector3::from(dictionary.directions()[d]);
            let mut world = setup.clone();
            world.gravity_m_s2 = link_poses[link_4].rotation * (direction * g);
            let evaluator = Evaluator::new(&world, ConnectMethod::Hermite).expect("evaluator");
            let check = evaluator.check(C2, &pv, &pose);
            let Some(metrics) = check.metrics else {
                assert_eq!(stored, MarginRecord::UNMEASURED, "{pv:?} direction {d}");
                unmeasured += 1;
                continue;
            };
            let expected = Margins::of(&metrics, &setup.thresholds).to_array();
            let values = stored.values().expect("measured");
            for c in 0..3 {
                let range = f64::from(i16::MAX) * MARGIN_UNITS[c];
                let expected = expected[c].clamp(-range, range);
                // Half a unit of rounding, and the solver's tolerance on the shape.
                let tolerance = MARGIN_UNITS[c] + 1e-4 * expected.abs();
                assert!(
                    (values[c] - expected).abs() <= tolerance,
                    "{pv:?} direction {d} margin {c}: stored {} vs {expected}",
                    values[c]
                );
            }
            compared += 1;
        }
    }
    assert!(
        compared >= 20,
        "only {compared} comparisons ({unmeasured} unmeasured)"
    );
}

/// The interpolation neighbours are the nearest stored directions by brute force; a query
/// on a stored direction returns its value, a constant is reproduced everywhere and every
/// interpolated value lies within its neighbours' range.
#[test]
fn interpolation_uses_the_nearest_directions_and_stays_in_their_range() {
    let directions = fibonacci_sphere(64);
    for probe in probe_directions(200) {
        let u = Vector3::from(probe);
        let neighbours = Neighbours::of(&directions, &u);
        let mut by_angle: Vec<usize> = (0..directions.len()).collect();
        by_angle.sort_by(|&a, &b| angle(&directions[a], &u).total_cmp(&angle(&directions[b], &u)));
        assert_eq!(neighbours.indices.to_vec(), by_angle[..4].to_vec());
        let total: f64 = neighbours.weights.iter().sum();
        assert!((total - 1.0).abs() < 1e-12);
        let constant = neighbours
            .interpolate(|_| Some([2.5, -1.0, 0.25, 30.0]))
            .expect("values");
        assert!(
            constant
                .mean
                .iter()
                .zip([2.5, -1.0, 0.25, 30.0])
                .all(|(a, b)| (a - b).abs() < 1e-12)
        );
        let value = |k: usize| {
            Some([
                k as f64,
                (k * k) as f64,
                -(k as f64),
                1.0 / (1.0 + k as f64),
            ])
        };
        let interpolated = neighbours.interpolate(value).expect("values");
        for c in 0..4 {
            let values: Vec<f64> = neighbours
                .indices
                .iter()
                .map(|&k| value(k).expect("v")[c])
                .collect();
            let (low, high) = values
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(*v), h.max(*v))
                });
            assert!(interpolated.mean[c] >= low - 1e-9 && interpolated.mean[c] <= high + 1e-9);
            assert!((interpolated.spread[c] - (high - low)).abs() < 1e-12);
        }
    }
    for (k, d) in directions.iter().enumerate() {
        let neighbours = Neighbours::of(&directions, &Vector3::from(*d));
        assert_eq!((neighbours.indices[0], neighbours.weights[0]), (k, 1.0));
    }
}

/// The lookup never rejects a piece that the exact test (the static solve in the link frame,
/// lengths continued as `solve --setup` does) keeps under that gravity direction, over
/// random directions, for the fixture and both hand-written bundled setups; the pieces it
/// lets through that the exact test rejects (false accepts) are counted and printed.
#[test]
fn the_lookup_never_rejects_a_piece_the_exact_test_keeps() {
    for (path, directions) in [
        (SETUP, 16),
        (HAND_WRITTEN_PICK_AND_PLACE, 64),
        ("robots/viper_s850/hand_written/inspection.toml", 64),
    ] {
        let setup = Setup::from_file(path).expect("setup");
        let dictionary = shared(path, directions);
        let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
        let queries = random_directions(200, 0x5eed);
        let mut counts = [0usize; 4]; // holds, fails, undecided, false accepts
        for m in (0..setup.segment_count()).filter(|&m| setup.is_intra_link(m)) {
            let pairs = admissible_pairs(&setup, m);
            let stored = dictionary.stored_segment(&setup, m).expect("stored");
            let tallies: Vec<[usize; 4]> = pairs
                .par_iter()
                .map(|((start, end), lengths)| {
                    let mut tally = [0usize; 4];
                    for down in &queries {
                        let exact = evaluator.link_frame_metrics(m, (*start, *end), lengths, down);
                        for (&s, exact) in lengths.iter().zip(exact) {
                            let keeps = exact.is_ok_and(|metrics| {
                                Margins::first_violation(Margins::of(&metrics, &setup.thresholds).to_array()).is_none()
                            });
                            let pv = Pv::new(s, *start, *end);
                            let piece = stored.piece(&pv).expect("mapped");
                            let answer = dictionary.answer_at(stored.slot, &piece, down).expect("stored");
                            match answer {
                                DirectionAnswer::Fails { rejection, margins } => {
                                    assert!(!keeps, "{path} C{} {pv:?} at {down:?}: the exact test keeps it, the lookup rejects it ({rejection:?}, {margins:?})", m + 1);
                                    tally[1] += 1;
                                }
                                DirectionAnswer::Holds => {
                                    tally[0] += 1;
                                    tally[3] += usize::from(!keeps);
                                }
                                DirectionAnswer::Undecided => tally[2] += 1,
                            }
                        }
                    }
                    tally
                })
                .collect();
            for tally in tallies {
                for (c, t) in counts.iter_mut().zip(tally) {
                    *c += t;
                }
            }
        }
        let total: usize = counts[..3].iter().sum();
        println!(
            "{path}: {total} piece-directions, {} hold, {} fail, {} undecided ({:.2} %), {} false accepts ({:.3} % of the accepted)",
            counts[0],
            counts[1],
            counts[2],
            100.0 * counts[2] as f64 / total as f64,
            counts[3],
            100.0 * counts[3] as f64 / counts[0].max(1) as f64
        );
        assert!(
            counts[1] > 0 && counts[0] + counts[2] > 0,
            "{path}: both answers occur"
        );
        // The bound decides most pieces by itself: otherwise the dictionary saves nothing.
        assert!(
            counts[2] * 5 < total,
            "{path}: {} of {total} undecided",
            counts[2]
        );
    }
}

/// Unit vectors from a fixed linear congruential sequence (reproducible, no dependency).
fn random_directions(n: usize, seed: u64) -> Vec<Vector3<f64>> {
    let mut state = seed;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let z = 2.0 * uniform() - 1.0;
            let phi = 2.0 * std::f64::consts::PI * uniform();
            let r = (1.0 - z * z).sqrt();
            Vector3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// The admissible cable lengths (> 0) of segment `m` per pair of configurations, the
/// robustness neighbours included, as the attachment test asks for them.
fn admissible_pairs(setup: &Setup, m: usize) -> Vec<((usize, usize), Vec<usize>)> {
    let candidates = cable_dict::attachment::admissible_pvs(setup, m);
    let r = &setup.robustness;
    let mut pairs: std::collections::BTreeMap<(usize, usize), Vec<usize>> = Default::default();
    for pv in cable_dict::attachment::needed_pvs(&candidates, r.delta_s, r.range) {
        if pv.sub_segments > 0 {
            pairs
                .entry((pv.start, pv.end))
                .or_default()
                .push(pv.sub_segments);
        }
    }
    pairs.into_iter().collect()
}

/// `solve --dict` and `solve --setup` give the same intra-link D1 and D2 and the same path
/// on every bundled motion with the hand-written bundled setups, and on two with a coarser
/// copy of the robot-level one (generated sites, installed twist), each with its own
/// dictionary (the full robot-level catalogue: docs/dictionaries.md); and with a setup
/// drawn from the hand-written pick-and-place catalogue (subsets of its places, other
/// lengths, two clamps on a link the build setup has one on) and the dictionary of that
/// catalogue.
#[test]
fn solve_with_a_dictionary_equals_solve_on_the_fly_on_every_bundled_motion() {
    // The hand-written catalogue has no path for any of them: screw driving, first, runs out
    // of chains in a few seconds where the others spend the whole motion-test budget.
    let gripper = [
        "screw_driving",
        "pick_and_place",
        "palletizing",
        "machine_tending",
    ];
    // (setup, dictionary built from, directions, motions)
    let cases = [
        // Generated sites: the motions with the most gravity directions on link_4.
        (
            "tests/data/dict_sites_setup.toml",
            "tests/data/dict_sites_setup.toml",
            16,
            &["machine_tending", "screw_driving"][..],
        ),
        (
            HAND_WRITTEN_PICK_AND_PLACE,
            HAND_WRITTEN_PICK_AND_PLACE,
            64,
            gripper.as_slice(),
        ),
        (
            "tests/data/dict_subset_setup.toml",
            HAND_WRITTEN_PICK_AND_PLACE,
            64,
            ["pick_and_place", "machine_tending"].as_slice(),
        ),
        (
            "robots/viper_s850/hand_written/inspection.toml",
            "robots/viper_s850/hand_written/inspection.toml",
            64,
            ["inspection"].as_slice(),
        ),
    ];
    for (path, built_from, directions, motions) in cases {
        let setup = Setup::from_file(path).expect("setup");
        let dictionary = shared(built_from, directions);
        for (k, name) in motions.iter().enumerate() {
            let motion = format!("motions/viper_s850/{name}.csv");
            let motion = Motion::from_csv_file(&setup.robot, motion).expect("motion");
            // The static sweep and the motion test are a deterministic function of the D2
            // sets, so equal sets give an equal d*: each case runs them on its first motion
            // (end to end), the others compare every set and the shortest chain.
            let options = SolveOptions {
                motion_test: k == 0,
                static_sweep: k == 0,
                ..SolveOptions::default()
            };
            let exact = solve(&setup, &motion, &options).expect("solves");
            let looked_up =
                solve_with_dictionary(dictionary, &setup, &motion, &options).expect("solves");
            for m in 0..setup.segment_count() {
                let (a, b) = (&exact.segments[m], &looked_up.segments[m]);
                assert_eq!((a.d1, a.d2), (b.d1, b.d2), "{path} {name} C{}", m + 1);
            }
            assert_eq!(exact.status, looked_up.status, "{path} {name}");
            assert_eq!(exact.optimal, looked_up.optimal, "{path} {name}");
            let used = looked_up.inputs.dictionary.as_ref().expect("named");
            assert!(used.segments.iter().all(|s| s.gravity_directions > 0));
        }
    }
}

/// The intra-link test poses are the motion's gravity directions in the link frame to the stated
/// resolution: the first sample among them, no two closer, and every sample's direction
/// within it of one of them — gravity in the link computed from the link's world rotation.
#[test]
fn intra_link_poses_are_the_motions_gravity_directions_to_the_resolution() {
    let setup = setup();
    let motion = Motion::from_csv_file(&setup.robot, "motions/viper_s850/machine_tending.csv")
        .expect("motion");
    let poses = SegmentPoses::new(&setup, &motion).expect("poses");
    let link_4 = setup.robot.link_index("link_4").expect("link_4");
    let down = setup.gravity_m_s2.normalize();
    let in_link = |joints: &[f64]| {
        let link_poses = setup.robot.link_poses(joints).expect("pose");
        link_poses[link_4].rotation.inverse() * down
    };
    let chosen: Vec<Vector3<f64>> = poses.poses[C2].iter().map(|p| in_link(&p.joints)).collect();
    assert_eq!(poses.poses[C2][0].sample, 0);
    assert!(
        poses.poses[C2]
            .iter()
            .all(|p| p.clearance_link == Some(link_4))
    );
    let resolution = GRAVITY_RESOLUTION_DEG.to_radians();
    for (i, a) in chosen.iter().enumerate() {
        for b in &chosen[..i] {
            assert!(
                a.angle(b) > resolution,
                "two test poses within the resolution"
            );
        }
    }
    for joints in motion.samples() {
        let u = in_link(joints);
        let nearest = chosen
            .iter()
            .map(|c| c.angle(&u))
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest <= resolution + 1e-12,
            "a sample {nearest} rad from every test pose"
        );
    }
    assert!(
        chosen.len() > 5,
        "link_4 turns: {} directions",
        chosen.len()
    );
    assert!(
        poses.poses[0].iter().all(|p| p.clearance_link.is_none()),
        "C1 sees every link"
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

/// Without gravity an intra-link segment has one test pose, and its pieces' verdicts there
/// (solved in the link's frame) are the world-frame check's at that pose.
#[test]
fn without_gravity_the_intra_link_test_is_one_pose_and_finite() {
    let mut setup = setup();
    setup.gravity_m_s2 = Vector3::zeros();
    let motion = Motion::from_csv_file(&setup.robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let poses = SegmentPoses::new(&setup, &motion).expect("poses");
    assert_eq!(poses.poses[C2].len(), 1);
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    let pose = &poses.poses[C2][0];
    for ((start, end), lengths) in admissible_pairs(&setup, C2) {
        let verdicts = evaluator.first_rejections(C2, (start, end), &lengths, &poses.poses[C2]);
        for (&s, verdict) in lengths.iter().zip(verdicts) {
            let check = evaluator.check(C2, &Pv::new(s, start, end), pose);
            assert_eq!(
                verdict.map(|m| m.rejection),
                check.rejection,
                "S = {s} ({start}, {end})"
            );
            if let Some(metrics) = check.metrics {
                assert!(metrics.stretch.is_finite() && metrics.min_bend_radius_m > 0.0);
            }
        }
    }
}

/// A setup the dictionary cannot serve is refused, naming the first thing that differs: a
/// clamp place that is not in the link's catalogue (with its position), other limits, a
/// length that is not stored. The unchanged text is served (the control).
#[test]
fn a_setup_outside_the_catalogue_is_refused_naming_what_differs() {
    let dictionary = shared(SETUP, 16);
    let text = std::fs::read_to_string(SETUP).expect("fixture");
    let motion = Motion::from_csv_file(&setup().robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let refusal = |edited: &str| -> Option<String> {
        let setup = Setup::from_toml_str(edited, Path::new(SETUP)).expect("edited setup loads");
        let poses = SegmentPoses::new(&setup, &motion).expect("poses");
        MotionLookup::new(dictionary, &setup, &poses)
            .err()
            .map(|e| e.to_string())
    };
    assert_eq!(refusal(&text), None);
    let cases = [
        (
            "[-72.0, 0.0, 280.0]",
            "[-72.0, 0.0, 281.0]",
            "G3 'back z280' at (-72.0, 0.0, 281.0) mm is not among the dictionary's",
        ),
        ("stretch = 1.02", "stretch = 1.03", "other limits"),
        (
            "min = 4, max = 8",
            "min = 4, max = 12",
            "S = 11 is not stored",
        ),
    ];
    for (from, to, expected) in cases {
        assert!(text.contains(from), "{from}");
        let message = refusal(&text.replace(from, to)).expect("refused");
        assert!(
            message.contains(expected) && message.contains(".cdict"),
            "{message}"
        );
    }
}

/// `info`'s undecided share of a link equals the share counted one lookup at a time through
/// [`Dictionary::answer_at`] (each call finding its own neighbours) over the same directions,
/// and it falls as the directions get denser (the hand-written pick-and-place catalogue at 16
/// and 64 directions; docs/dictionaries.md, "Direction count").
#[test]
fn the_undecided_share_counts_single_lookups() {
    use cable_dict::dictionary::UNDECIDED_SAMPLE_DIRECTIONS;
    use cable_dict::dictionary::directions::probe_directions;
    use cable_dict::dictionary::format::PvRecord;
    let downs: Vec<Vector3<f64>> = probe_directions(UNDECIDED_SAMPLE_DIRECTIONS)
        .into_iter()
        .map(Vector3::from)
        .collect();
    let mut shares = Vec::new();
    for directions in [16, 64] {
        let dictionary = shared(HAND_WRITTEN_PICK_AND_PLACE, directions);
        let slot = dictionary.link_slot("link_4").expect("link_4 stored");
        let (mut undecided, mut lookups) = (0usize, 0usize);
        for record in dictionary.pv_records().iter().filter(|r| {
            usize::from(r.link) == slot && r.has(PvRecord::CANDIDATE) && r.sub_segments > 0
        }) {
            let pv = Pv::new(
                record.sub_segments as usize,
                record.start.into(),
                record.end.into(),
            );
            for down in &downs {
                let answer = dictionary.answer_at(slot, &pv, down).expect("stored");
                lookups += 1;
                undecided += usize::from(answer == DirectionAnswer::Undecided);
            }
        }
        let share = dictionary.undecided_share(slot).expect("candidates");
        assert!(lookups > 0);
        assert_eq!(share, undecided as f64 / lookups as f64, "{directions}");
        shares.push(share);
    }
    assert!(shares[1] < shares[0], "{shares:?}");
}
