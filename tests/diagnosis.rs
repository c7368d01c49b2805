//! "Unsolved" as a diagnosis, on setups with a known, constructed cause: a length window too
//! short for the clamps' distance, a bend-radius limit no piece can keep, and a robust length
//! window wider than the lengths that pass. The report of an unsolved search pictures its
//! nearest miss.

use crate::svg_pictures;

use crate::common::write_report;
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
/// asks for a longer window reaching that distance.
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
        .link_poses(&motion.joints_at(nearest.at.time_s))
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
    // It must reach before it can hold: the clamps' distance in whole 10 mm sub-segments
    // (not that distance over the allowed stretch, which is shorter than the distance).
    let needed = format!(
        "needs at least {:.0} mm to reach between its clamps",
        (distance_mm / 10.0).ceil() * 10.0
    );
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
        .link_poses(&motion.joints_at(nearest.at.time_s))
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
    check_nearest_miss_picture(&setup, &motion, &report, &evaluator);
}

/// Without a candidate path the report pictures the first nearest miss: its piece's static
/// shape at the miss's time (re-solved here, projected here) in every view, and a red ring at
/// its node nearest to the failing place.
fn check_nearest_miss_picture(
    setup: &Setup,
    motion: &Motion,
    report: &SolveReport,
    evaluator: &Evaluator<'_>,
) {
    let dir = tempfile::tempdir().expect("temporary folder");
    write_report(dir.path(), setup, motion, report).expect("report written");
    let miss = &diagnosis(report).segments[0].nearest_misses[0];
    let pv = cable_dict::path::Pv {
        sub_segments: (miss.length_mm / 10.0).round() as usize,
        start: configuration(setup, 0, &miss.from_configuration),
        end: configuration(setup, 1, &miss.to_configuration),
    };
    let links = setup
        .robot
        .link_poses(&motion.joints_at(miss.at.time_s))
        .unwrap_or_else(|e| panic!("{e}"));
    let nodes = evaluator
        .equilibrium_nodes(0, &pv, &links)
        .unwrap_or_else(|e| panic!("{e}"));
    let place = miss.from_start_clamp_mm.expect("a place on the cable");
    let ringed = nodes[(place / 10.0).round() as usize];
    let svg = std::fs::read_to_string(dir.path().join("nearest-miss.svg")).expect("picture");
    let elements = svg_pictures::elements(&svg);
    // Front (x, −z), side (y, −z), top (x, −y), in mm to 0.1 mm.
    let axes = [(0, 2), (1, 2), (0, 1)];
    for (view, (right, up)) in svg_pictures::VIEWS.into_iter().zip(axes) {
        let project = |p: &nalgebra::Point3<f64>| [p[right] * 1e3, -p[up] * 1e3];
        let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) <= 0.051;
        let line = elements
            .iter()
            .find(|e| e.is("polyline", view, "cable"))
            .unwrap_or_else(|| panic!("{view}: no cable"));
        assert_eq!(line.attribute("data-piece"), "C1 nearest miss");
        let drawn = svg_pictures::points(line.attribute("points"));
        assert_eq!(drawn.len(), nodes.len(), "{view}");
        for (d, node) in drawn.iter().zip(&nodes) {
            assert!(near(*d, project(node)), "{view}: {d:?} vs {node:?}");
        }
        let ring = elements
            .iter()
            .find(|e| e.view.as_deref() == Some(view) && e.attribute("class") == "worst")
            .unwrap_or_else(|| panic!("{view}: no ring"));
        let centre =
            [ring.attribute("cx"), ring.attribute("cy")].map(|v| v.parse().expect("number"));
        assert!(near(centre, project(&ringed)), "{view}: ring at {centre:?}");
    }
    let page = std::fs::read_to_string(dir.path().join("index.html")).expect("page");
    assert!(page.contains("nearest-miss.svg") && page.contains("No cable path was found."));
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
