//! "Unsolved" as a diagnosis, on setups with a known, constructed cause: a length window too
//! short for the clamps' distance, a bend-radius limit no piece can keep, and a robust length
//! window wider than the lengths that pass.

use cable_dict::attachment::{ConnectMethod, Evaluator, Rejection};
use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{Diagnosis, SolveOptions, SolveReport, Status, solve};
use std::path::Path;

const MOTION: &str = "motions/viper_s850/pick_and_place.csv";
const SMALL: &str = "tests/data/small_setup.toml";

fn solve_text(text: &str) -> (Setup, Motion, SolveReport) {
    let setup = Setup::from_toml_str(text, Path::new(SMALL)).unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(&setup.robot, MOTION).unwrap_or_else(|e| panic!("{e}"));
    let report = solve(&setup, &motion, &SolveOptions::default()).expect("solve");
    (setup, motion, report)
}

fn small_with(from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(SMALL).unwrap_or_else(|e| panic!("{e}"));
    assert!(text.contains(from), "{from}");
    text.replace(from, to)
}

/// Index of guide `g`'s configuration called `name`.
fn configuration(setup: &Setup, g: usize, name: &str) -> usize {
    setup.guides[g]
        .configuration_index(name)
        .unwrap_or_else(|| panic!("no {name}"))
}

fn diagnosis(report: &SolveReport) -> &Diagnosis {
    assert_eq!(report.status, Status::NoChain, "{}", report.explanation);
    report.diagnosis.as_ref().expect("a diagnosis")
}

/// Lengths 100–140 mm between clamps about 265 mm apart: every piece is too short. The
/// diagnosis names the segment, its nearest miss is a 140 mm piece whose needed stretch is
/// the clamps' distance (recomputed here from the robot's kinematics) over 140 mm, and it
/// asks for a longer window reaching that distance over the allowed stretch.
#[test]
fn a_window_too_short_for_the_clamps_asks_for_longer_lengths() {
    let text = small_with(
        "lengths = { min = 24, max = 36,",
        "lengths = { min = 10, max = 14,",
    );
    let (setup, motion, report) = solve_text(&text);
    let diagnosis = diagnosis(&report);
    let c1 = &diagnosis.segments[0];
    assert_eq!(c1.segment, "C1");
    assert!(c1.problem.contains("none of its"), "{}", c1.problem);
    let nearest = c1.nearest_misses.first().expect("a nearest miss");
    assert_eq!(nearest.limit, Rejection::TooShort);
    assert_eq!(nearest.length_mm, 140.0);
    let links = setup
        .robot
        .link_poses(&motion.joints_at(nearest.time_s))
        .unwrap_or_else(|e| panic!("{e}"));
    let a = setup.guide_world_pose(
        &links,
        0,
        configuration(&setup, 0, &nearest.from_configuration),
    );
    let b = setup.guide_world_pose(
        &links,
        1,
        configuration(&setup, 1, &nearest.to_configuration),
    );
    let distance_mm = (b.translation.vector - a.translation.vector).norm() * 1e3;
    assert!(
        (nearest.value - distance_mm / 140.0).abs() < 1e-6,
        "{nearest:?}"
    );
    let needed = format!("needs about {:.0} mm", distance_mm / 1.02);
    assert!(
        c1.suggestions
            .iter()
            .any(|s| s.contains("longer length window") && s.contains(&needed)),
        "{:?} ({needed})",
        c1.suggestions
    );
    // The summary and the JSON carry it.
    let summary = report.to_string();
    assert!(summary.contains("why there is no path") && summary.contains("nearest miss"));
    let json = serde_json::to_value(&report).expect("JSON");
    assert_eq!(json["diagnosis"]["segments"][0]["segment"], "C1");
}

/// A 500 mm minimum bend radius, lengths 340–460 mm (never too short for clamps at most
/// about 310 mm apart): every piece that does not touch the robot bends below it. The
/// nearest misses are sorted from the smallest relative shortfall and include the closest
/// bend failure, with its place on the piece; the re-evaluated equilibrium at the reported
/// pose has the reported radius.
#[test]
fn an_impossible_bend_limit_reports_the_radius_the_pieces_reach() {
    let text = small_with("min_bend_radius_mm = 25.0", "min_bend_radius_mm = 500.0").replace(
        "lengths = { min = 24, max = 36,",
        "lengths = { min = 34, max = 46,",
    );
    let (setup, motion, report) = solve_text(&text);
    let c1 = &diagnosis(&report).segments[0];
    let severities: Vec<f64> = c1
        .nearest_misses
        .iter()
        .map(|m| match m.limit {
            Rejection::Bend => (m.limit_value - m.value) / m.limit_value,
            Rejection::Contact => (m.limit_value - m.value) / 8.0,
            other => panic!("{other:?}: {m:?}"),
        })
        .collect();
    assert!(
        severities.windows(2).all(|w| w[0] <= w[1]),
        "{severities:?}"
    );
    let nearest = c1
        .nearest_misses
        .iter()
        .find(|m| m.limit == Rejection::Bend)
        .expect("the closest piece failing by its bend radius is listed");
    assert_eq!(nearest.limit_value, 500.0);
    let at = nearest.from_start_clamp_mm.expect("a place on the cable");
    assert!((0.0..=nearest.length_mm).contains(&at));
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    let pv = cable_dict::path::Pv {
        sub_segments: (nearest.length_mm / 10.0).round() as usize,
        start: configuration(&setup, 0, &nearest.from_configuration),
        end: configuration(&setup, 1, &nearest.to_configuration),
    };
    let links = setup
        .robot
        .link_poses(&motion.joints_at(nearest.time_s))
        .unwrap_or_else(|e| panic!("{e}"));
    let check = evaluator.check_at(0, &pv, &links);
    let radius_mm = check.metrics.expect("metrics").min_bend_radius_m * 1e3;
    assert!(
        (radius_mm - nearest.value).abs() < 1e-3,
        "{radius_mm} vs {}",
        nearest.value
    );
    assert!(
        c1.suggestions
            .iter()
            .any(|s| s.contains("other clamp sites"))
    );
}

/// ±20 mm robustness around lengths of which only a 20 mm band passes: pieces pass, none is
/// robust, and the diagnosis says so and points at the robustness window.
#[test]
fn a_robust_window_wider_than_the_passing_band_is_named() {
    let text = small_with("range = 2", "range = 12");
    let (_, _, report) = solve_text(&text);
    let c1 = &diagnosis(&report).segments[0];
    assert!(
        c1.problem.contains("robust length window"),
        "{}",
        c1.problem
    );
    assert!(
        c1.suggestions
            .iter()
            .any(|s| s.contains("[robustness] range = 12")),
        "{:?}",
        c1.suggestions
    );
}
