//! The lazy search (the default) against the exhaustive one (`--exhaustive`, every candidate
//! piece tested before the chains are searched): the same path, the same candidates tried in
//! the same order, on bundled motions of both kinds (answered at the first chain, and after
//! failed motion tests) and on a site-generated setup of a second robot
//! (the UR5's STL meshes). The invariant behind it is tested beside the lazy test
//! (`attachment::lazy`), and its chains through failed motion tests beside the search
//! (`solve`).

use cable_dict::motion::{Motion, WaypointFile};
use cable_dict::setup::Setup;
use cable_dict::solve::{SearchKind, SolveOptions, SolveReport, solve};
use std::path::PathBuf;

fn root(path: &str) -> PathBuf {
    crate::common::root().join(path)
}

fn setup(path: &str) -> Setup {
    Setup::from_file(root(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn motion(setup: &Setup, csv: &str) -> Motion {
    Motion::from_csv_file(&setup.robot, root(csv)).unwrap_or_else(|e| panic!("{csv}: {e}"))
}

fn solved(setup: &Setup, motion: &Motion, search: SearchKind) -> SolveReport {
    let options = SolveOptions {
        search,
        ..SolveOptions::default()
    };
    solve(setup, motion, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// Both searches on one setup and motion: same status, path and candidates tried; the lazy
/// one tests fewer pieces.
fn same_answer(setup: &Setup, motion: &Motion, name: &str) {
    let lazy = solved(setup, motion, SearchKind::Lazy);
    let exhaustive = solved(setup, motion, SearchKind::Exhaustive);
    assert_eq!(lazy.status, exhaustive.status, "{name}");
    assert_eq!(lazy.optimal, exhaustive.optimal, "{name}");
    let tried = |r: &SolveReport| -> Vec<_> {
        r.candidates
            .iter()
            .map(|c| (c.path.clone(), c.passed, c.failure.clone()))
            .collect()
    };
    assert_eq!(tried(&lazy), tried(&exhaustive), "{name}");
    let evaluated = |r: &SolveReport| r.segments.iter().map(|s| s.evaluations).sum::<usize>();
    assert!(
        evaluated(&lazy) < evaluated(&exhaustive),
        "{name}: {} vs {}",
        evaluated(&lazy),
        evaluated(&exhaustive)
    );
}

#[test]
fn both_searches_find_the_same_path_on_the_bundled_motions() {
    // Pick-and-place passes its first chain; machine tending goes through failed motion
    // tests before its answer. Palletizing, screw driving and the robot-level inspection
    // pass their first chain as pick-and-place does (the same path through the search), so
    // their exhaustive runs (80–115 CPU-s each) are left out of the suite (docs/commands.md
    // says how to compare them).
    let robot_level = setup("robots/viper_s850/pick_and_place.toml");
    for name in ["pick_and_place", "machine_tending"] {
        let csv = format!("motions/viper_s850/{name}.csv");
        same_answer(&robot_level, &motion(&robot_level, &csv), name);
    }
}

#[test]
fn both_searches_find_the_same_path_on_a_second_robot() {
    let ur5 = setup("tests/data/ur5/sites_setup.toml");
    let waypoints = WaypointFile::from_file(root("tests/data/ur5/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion = waypoints
        .generate(&ur5.robot)
        .unwrap_or_else(|e| panic!("{e}"))
        .motion;
    same_answer(&ur5, &motion, "UR5");
}

/// The makers' rule for the cable (a flexing radius twice the fixed one,
/// [`crate::common::ten_mm_setup_text`]): the attachment test holds inter-link pieces that
/// flex between its poses to the flexing radius, a verdict over all of a piece's poses; both
/// searches still find the same path after the same failed motion tests.
#[test]
fn both_searches_find_the_same_path_under_a_flexing_radius() {
    let source = root("robots/viper_s850/pick_and_place.toml");
    let text = crate::common::ten_mm_setup_text(true);
    let rule = Setup::from_toml_str(&text, &source).unwrap_or_else(|e| panic!("{e}"));
    let csv = "motions/viper_s850/pick_and_place.csv";
    same_answer(&rule, &motion(&rule, csv), "pick and place, makers' rule");
}

/// The bundled dress pack (a retraction on the upper arm, a sliding ring on the forearm, a
/// connector that may be rotating or a swivel: every kind; its one searched clamp's sites
/// 120 mm apart instead of 80 to keep the exhaustive run short): the pieces through the outlet and the ring are spans solved at their
/// split of least energy, and both searches find the same path through the same candidates.
#[test]
fn both_searches_find_the_same_path_through_sliding_guides() {
    let source = root("robots/viper_s850/dress_pack.toml");
    let text = std::fs::read_to_string(&source).unwrap();
    let coarse = text.replacen(
        "sites = { spacing_mm = 80.0",
        "sites = { spacing_mm = 120.0",
        1,
    );
    assert_ne!(coarse, text);
    let dress_pack = Setup::from_toml_str(&coarse, &source).unwrap_or_else(|e| panic!("{e}"));
    let motion = motion(&dress_pack, "motions/viper_s850/pick_and_place.csv");
    same_answer(&dress_pack, &motion, "dress pack");
    let report = solved(&dress_pack, &motion, SearchKind::Lazy);
    let test = report.motion_test.as_ref().expect("a path was tested");
    assert!(test.passed);
    // Both sliding parts were followed over the motion: the ring's split moved, the
    // retraction's travel stayed within its stops.
    let slides: Vec<(&str, &str)> = (test.slides.iter())
        .map(|s| (s.guide.as_str(), s.kind))
        .collect();
    assert_eq!(slides, [("R", "retraction"), ("S", "sliding")]);
    let ring = &test.slides[1];
    assert!(ring.most_m > ring.least_m && ring.series.len() > 100);
    let outlet = &test.slides[0];
    assert!(outlet.least_m >= 0.0 && outlet.most_m <= 0.15);
}

/// The forearm swivel (a swivel clamp between two pieces: one piece of the search, held at
/// the mark the length windows give): both searches find the same path through the same
/// candidates, after failed motion tests.
#[test]
fn both_searches_find_the_same_path_through_a_swivel_clamp() {
    let swivel = setup("robots/viper_s850/swivel_forearm.toml");
    let motion = motion(&swivel, "motions/viper_s850/pick_and_place.csv");
    same_answer(&swivel, &motion, "forearm swivel");
}
