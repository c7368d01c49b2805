//! The attachment test and the solve pipeline on small setups (tests/data/small_setup.toml and
//! a two-segment variant), each set checked against a direct re-evaluation of its definition.

use cable_dict::attachment::{
    ConnectMethod, Evaluator, SegmentPoses, SegmentSets, admissible_pvs, attachment_test,
    robust_neighbours,
};
use cable_dict::motion::Motion;
use cable_dict::path::{CablePath, Pv};
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve};
use std::path::Path;

const MOTION: &str = "motions/viper_s850/pick_and_place.csv";
const SMALL: &str = "tests/data/small_setup.toml";

/// The small setup plus an intra-link segment G2 → G3 (G3 near the wrist on link_4), with or
/// without S = 0.
fn two_segment_setup_with(allow_zero: bool) -> Setup {
    let text = std::fs::read_to_string(SMALL)
        .unwrap()
        .replace("max_guides_per_link = 1", "max_guides_per_link = 2")
        + r#"
[[guides]]
name = "G3"
link = "link_4"
configurations = [
  { name = "left z280", position_mm = [0.0, 72.0, 280.0], rpy_deg = [0.0, 0.0, 90.0] },
]

[[segments]]
from = "G2"
to = "G3"
lengths = { min = 3, max = 5, step = 1, allow_zero = ALLOW }
"#;
    let text = text.replace("ALLOW", &allow_zero.to_string());
    Setup::from_toml_str(&text, Path::new(SMALL)).unwrap()
}

fn two_segment_setup() -> Setup {
    two_segment_setup_with(true)
}

fn run(setup: &Setup, threads: usize) -> (SegmentPoses, Vec<SegmentSets>) {
    let motion = Motion::from_csv_file(&setup.robot, MOTION).unwrap();
    let poses = SegmentPoses::new(setup, &motion).unwrap();
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let sets = pool.install(|| attachment_test(&evaluator, &poses));
    (poses, sets)
}

/// A PV passes when every test pose passes, evaluated directly.
fn passes(evaluator: &Evaluator<'_>, poses: &SegmentPoses, m: usize, pv: &Pv) -> bool {
    poses.poses[m]
        .iter()
        .all(|pose| evaluator.check(m, pv, pose).passed())
}

#[test]
fn robust_sets_follow_their_definition() {
    let setup = Setup::from_file(SMALL).unwrap();
    let (poses, sets) = run(&setup, 2);
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).unwrap();
    let (delta, range) = (setup.robustness.delta_s, setup.robustness.range);
    let d0 = admissible_pvs(&setup, 0);
    let d1: Vec<Pv> = d0
        .iter()
        .copied()
        .filter(|pv| passes(&evaluator, &poses, 0, pv))
        .collect();
    let d2: Vec<Pv> = d1
        .iter()
        .copied()
        .filter(|pv| {
            robust_neighbours(pv, delta, range)
                .is_some_and(|n| n.iter().all(|pv| passes(&evaluator, &poses, 0, pv)))
        })
        .collect();
    assert_eq!(sets[0].d0, d0.len());
    assert_eq!(sets[0].d1, d1.len());
    assert_eq!(sets[0].d2, d2);
    // Not a degenerate case: some PVs are rejected, some are robust, some pass but are not.
    assert!(!d2.is_empty() && d2.len() < d1.len() && d1.len() < d0.len());
    let rejected: usize = sets[0].rejections.values().sum();
    assert_eq!(rejected, d0.len() - d1.len());
}

#[test]
fn robustness_neighbours_are_s_plus_minus_k_delta() {
    let pv = Pv {
        sub_segments: 10,
        start: 1,
        end: 2,
    };
    let lengths: Vec<usize> = robust_neighbours(&pv, 3, 2)
        .unwrap()
        .iter()
        .map(|n| n.sub_segments)
        .collect();
    assert_eq!(lengths, vec![7, 13, 4, 16]);
    assert_eq!(
        robust_neighbours(&pv, 5, 2),
        None,
        "S − 2·5 = 0 is no cable"
    );
    let zero = Pv {
        sub_segments: 0,
        ..pv
    };
    assert_eq!(robust_neighbours(&zero, 1, 2), Some(vec![]));
}

#[test]
fn sets_do_not_depend_on_the_thread_count() {
    let setup = two_segment_setup();
    let (_, one) = run(&setup, 1);
    let (_, two) = run(&setup, 2);
    for (a, b) in one.iter().zip(&two) {
        assert_eq!(
            (a.d0, a.d0_pruned, a.d1, &a.d2),
            (b.d0, b.d0_pruned, b.d1, &b.d2)
        );
        assert_eq!(a.rejections, b.rejections);
    }
}

#[test]
fn adjacency_keeps_exactly_the_pvs_whose_shared_guide_the_neighbour_uses() {
    // Without S = 0 only G2's left configuration reaches G3 (the right one is 144 mm away).
    let setup = two_segment_setup_with(false);
    let (_, sets) = run(&setup, 2);
    let used: Vec<usize> = sets[1].d2.iter().map(|pv| pv.start).collect();
    let expected = admissible_pvs(&setup, 0)
        .iter()
        .filter(|pv| used.contains(&pv.end))
        .count();
    assert_eq!(sets[0].d0_pruned, expected);
    assert!(expected < sets[0].d0, "the neighbour prunes something");
}

#[test]
fn the_untested_answer_is_the_shortest_chain_of_robust_pvs() {
    let setup = two_segment_setup();
    let motion = Motion::from_csv_file(&setup.robot, MOTION).unwrap();
    let options = SolveOptions {
        motion_test: false,
        ..SolveOptions::default()
    };
    let report = solve(&setup, &motion, &options).unwrap();
    let (_, sets) = run(&setup, 2);
    // Brute force over D2 × D2.
    let mut chains: Vec<CablePath> = Vec::new();
    for a in &sets[0].d2 {
        for b in &sets[1].d2 {
            chains.extend(CablePath::from_pvs(&[*a, *b]));
        }
    }
    chains.sort_by_key(|c| (c.total_sub_segments(), c.clone()));
    assert_eq!(report.status, Status::Untested);
    assert_eq!(report.chains, chains.len().to_string());
    let best = &chains[0];
    let optimal = report.optimal.unwrap();
    let lengths: Vec<usize> = optimal.segments.iter().map(|s| s.sub_segments).collect();
    assert_eq!(lengths, best.lengths);
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    assert_eq!(
        report.optimal_length_mm,
        Some(best.total_sub_segments() as f64 * pitch_mm)
    );
    // Every margin of the answer holds at its binding pose.
    assert!(report.margins.iter().all(|m| m.margin >= 0.0));
}

#[test]
fn method_one_leaves_intra_link_segments_at_zero_length() {
    let setup = two_segment_setup();
    let motion = Motion::from_csv_file(&setup.robot, MOTION).unwrap();
    let options = SolveOptions {
        motion_test: false,
        max_guides_per_link: Some(1),
        ..SolveOptions::default()
    };
    let report = solve(&setup, &motion, &options).unwrap();
    assert_eq!(report.inputs.method, "one clamp per link");
    match report.optimal {
        Some(path) => assert_eq!(path.segments[1].sub_segments, 0),
        None => assert_eq!(report.status, Status::NoChain),
    }
    let bad = SolveOptions {
        max_guides_per_link: Some(3),
        ..options
    };
    assert!(solve(&setup, &motion, &bad).is_err());
}

#[test]
fn a_static_bend_margin_rejects_exactly_the_pvs_that_keep_less_than_the_limit_plus_margin() {
    const MARGIN_MM: f64 = 3.0;
    let text = std::fs::read_to_string(SMALL).unwrap();
    let plain = Setup::from_file(SMALL).unwrap();
    let margined = Setup::from_toml_str(
        &text.replacen(
            "clamp_zone_mm = 20.0",
            &format!("clamp_zone_mm = 20.0\nstatic_bend_margin_mm = {MARGIN_MM}"),
            1,
        ),
        Path::new(SMALL),
    )
    .unwrap();
    let motion = Motion::from_csv_file(&plain.robot, MOTION).unwrap();
    let poses = SegmentPoses::new(&plain, &motion).unwrap();
    let without = Evaluator::new(&plain, ConnectMethod::Hermite).unwrap();
    let with = Evaluator::new(&margined, ConnectMethod::Hermite).unwrap();
    let limit_m = plain.thresholds.min_bend_radius_m + MARGIN_MM * 1e-3;
    let mut flipped = 0;
    for pv in admissible_pvs(&plain, 0) {
        // Expected from the plain verdicts and the plain metrics alone.
        let checks: Vec<_> = poses.poses[0]
            .iter()
            .map(|pose| without.check(0, &pv, pose))
            .collect();
        let keeps_margin = checks
            .iter()
            .all(|c| c.metrics.is_some_and(|m| m.min_bend_radius_m >= limit_m));
        let expected = checks.iter().all(|c| c.passed()) && keeps_margin;
        assert_eq!(passes(&with, &poses, 0, &pv), expected, "{pv:?}");
        flipped += usize::from(passes(&without, &poses, 0, &pv) && !expected);
    }
    assert!(
        flipped > 0,
        "no PV between the limit and the limit + margin"
    );
}
