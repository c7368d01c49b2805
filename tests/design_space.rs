//! The robot-level bundled setups — clamp sites generated on link_3, link_4 and link_6, no
//! motion-specific direction, twist references derived by the tool — solve every bundled
//! motion of their tool, and the answer keeps the cable datasheet's limits (read from the
//! cable file here, not through the setup) over the whole dynamic run. About 20–35 s each
//! in release on 2 cores.

use cable_dict::motion::Motion;
use cable_dict::setup::{ConfigurationOrigin, Setup};
use cable_dict::solve::{SolveOptions, SolveReport, Status, solve};

fn solved(setup_file: &str, motion_file: &str, options: &SolveOptions) -> (Setup, SolveReport) {
    let root = crate::common::root();
    let setup = Setup::from_file(root.join("robots/viper_s850").join(setup_file))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(
        &setup.robot,
        root.join("motions/viper_s850").join(motion_file),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let report = solve(&setup, &motion, options).expect("solve");
    assert_eq!(
        report.status,
        Status::Solved,
        "{motion_file}: {}",
        report.explanation
    );
    check_datasheet(&setup, &report, motion_file);
    (setup, report)
}

/// The motion test passed and its worst values keep the limits of the cable file's
/// datasheet values; every clamp of the answer is a generated site or the tool's connector.
fn check_datasheet(setup: &Setup, report: &SolveReport, motion_file: &str) {
    let cable_text = std::fs::read_to_string(&setup.cable_path).unwrap_or_else(|e| panic!("{e}"));
    let cable: toml::Table = cable_text.parse().unwrap_or_else(|e| panic!("{e}"));
    let bend_mm = cable["min_bend_radius_mm"].as_float().expect("number");
    let dynamics = report.motion_test.as_ref().expect("motion test");
    assert!(dynamics.passed, "{motion_file}");
    let worst = |w: &Option<cable_dict::motion_test::Worst>| w.as_ref().expect("worst").value;
    assert!(
        worst(&dynamics.worst_bend) * 1e3 >= bend_mm,
        "{motion_file}"
    );
    assert!(worst(&dynamics.worst_clearance) >= 0.0, "{motion_file}");
    assert!(worst(&dynamics.worst_stretch) <= 1.02, "{motion_file}");
    let path = &report.candidates.last().expect("d*").path;
    for (g, &c) in path.configurations.iter().enumerate() {
        let (root_guide, root_origin) = match setup.guides[g].configurations[c].origin {
            ConfigurationOrigin::Coincident {
                guide,
                configuration,
            } => (
                guide,
                setup.guides[guide].configurations[configuration].origin,
            ),
            other => (g, other),
        };
        assert!(
            matches!(root_origin, ConfigurationOrigin::Generated { .. })
                || setup.guides[root_guide].fixed,
            "{motion_file}: G{} uses a hand-written configuration",
            g + 1
        );
    }
}

#[test]
fn pick_and_place_is_solved_with_generated_sites() {
    solved(
        "pick_and_place.toml",
        "pick_and_place.csv",
        &SolveOptions::default(),
    );
}

#[test]
fn palletizing_is_solved_with_the_same_setup() {
    solved(
        "pick_and_place.toml",
        "palletizing.csv",
        &SolveOptions::default(),
    );
}

#[test]
fn machine_tending_is_solved_with_the_same_setup() {
    solved(
        "pick_and_place.toml",
        "machine_tending.csv",
        &SolveOptions::default(),
    );
}

#[test]
fn screw_driving_is_solved_with_the_same_setup() {
    solved(
        "pick_and_place.toml",
        "screw_driving.csv",
        &SolveOptions::default(),
    );
}

/// The inspection motion with its wrist flip, by method 2; the answer has one clamp per link,
/// so method 1 finds the same length (checked too).
#[test]
fn inspection_is_solved_by_both_methods() {
    let (_, method_2) = solved(
        "inspection.toml",
        "inspection.csv",
        &SolveOptions::default(),
    );
    let one_per_link = SolveOptions {
        max_guides_per_link: Some(1),
        ..SolveOptions::default()
    };
    let (_, method_1) = solved("inspection.toml", "inspection.csv", &one_per_link);
    assert!(method_2.optimal_length_mm <= method_1.optimal_length_mm);
}
