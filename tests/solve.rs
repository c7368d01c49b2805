//! `cable-dict solve` and `critical-poses` end to end: the result JSON's documented fields
//! against the setup file, exit codes, and the motion-test search (no failed PV is tried
//! twice) against the attachment test's own sets; the report's pictures against the
//! physics' own cable shapes.

use crate::common;
use crate::svg_pictures;

use crate::common::write_report;
use cable_dict::attachment::{ConnectMethod, Evaluator, SegmentPoses, attachment_test};
use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve};
use common::run;
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::Path;

const MOTION: &str = "motions/viper_s850/pick_and_place.csv";
const SMALL: &str = "tests/data/small_setup.toml";

/// Exit code, parsed standard output (JSON) and standard error of a run.
fn json_run(args: &[&str]) -> (i32, Value, String) {
    let output = run(args);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    let value = serde_json::from_slice(&output.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {stderr}"));
    (output.status.code().unwrap_or(-1), value, stderr)
}

fn number(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("not a number: {value}"))
}

/// The small setup with other length candidates for its one segment, in a temporary folder
/// (paths inside stay valid: they are made absolute).
fn small_setup_with_lengths(dir: &Path, lengths: &str) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read_to_string(Path::new(root).join(SMALL))
        .expect("small setup")
        .replace("../../robots", &format!("{root}/robots"))
        .replace("../../cables", &format!("{root}/cables"))
        .replace(
            "lengths = { min = 24, max = 36, step = 1, allow_zero = false }",
            lengths,
        );
    let path = dir.join("setup.toml");
    std::fs::write(&path, text).expect("written");
    path.to_str().expect("utf-8").to_string()
}

#[test]
fn the_result_json_has_the_documented_fields_with_the_setups_values() {
    let (code, result, stderr) = json_run(&[
        "solve",
        "--setup",
        SMALL,
        MOTION,
        "--json",
        "--no-motion-test",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(result["status"], "untested");
    assert_eq!(result["outcome"], "untested");
    // The small setup allows one clamp per link (`max_guides_per_link = 1`).
    assert_eq!(result["method"], "one clamp per link");
    assert!(result["motion_test"].is_null());
    assert!(result["reason"].is_string());

    // The path: one segment, G1 on link_3 → G2 on link_4, lengths in the setup's range.
    let segments = result["ecpv"]["segments"].as_array().expect("segments");
    assert_eq!(segments.len(), 1);
    let c1 = &segments[0];
    assert_eq!(c1["name"], "C1");
    assert_eq!(c1["from_guide"], "G1");
    assert_eq!(c1["to_guide"], "G2");
    assert_eq!(c1["kind"], "inter-link");
    let s = number(&c1["sub_segments"]);
    assert!((24.0..=36.0).contains(&s), "{s}");
    assert_eq!(number(&c1["length_mm"]), 10.0 * s);
    assert_eq!(number(&result["total_length_mm"]), 10.0 * s);

    // The guides carry the positions and angles written in tests/data/small_setup.toml.
    let written = [
        ("left", [-90.0, 82.0, 100.0], [0.0, 0.0, 90.0]),
        ("right", [-90.0, -82.0, 100.0], [0.0, 0.0, -90.0]),
        ("left z250", [0.0, 80.0, 250.0], [0.0, 0.0, 90.0]),
        ("right z250", [0.0, -80.0, 250.0], [0.0, 0.0, -90.0]),
    ];
    let guides = result["ecpv"]["guides"].as_array().expect("guides");
    assert_eq!(guides.len(), 2);
    for (guide, (name, link)) in guides.iter().zip([("G1", "link_3"), ("G2", "link_4")]) {
        assert_eq!(guide["name"], name);
        assert_eq!(guide["link"], link);
        let configuration = guide["configuration"].as_str().expect("name");
        let (_, xyz, rpy) = written
            .iter()
            .find(|(n, _, _)| *n == configuration)
            .unwrap_or_else(|| panic!("{configuration} is not in the setup"));
        let values =
            |v: &Value| -> Vec<f64> { v.as_array().expect("array").iter().map(number).collect() };
        assert_eq!(values(&guide["xyz_mm"]), xyz.to_vec());
        assert_eq!(values(&guide["rpy_deg"]), rpy.to_vec());
    }

    // Set sizes: |D0| = 13 lengths × 2 × 2 configurations, and D0 ⊇ D'0 ⊇ D1 ⊇ D2.
    let sets = result["sets"].as_array().expect("sets");
    assert_eq!(sets[0]["segment"], "C1");
    let sizes: Vec<f64> = ["d0", "d0_pruned", "d1", "d2"]
        .iter()
        .map(|k| number(&sets[0][k]))
        .collect();
    assert_eq!(sizes[0], 13.0 * 2.0 * 2.0);
    assert!(sizes.windows(2).all(|w| w[0] >= w[1]), "{sizes:?}");
    let timings = &result["timings_s"];
    for stage in [
        "critical_poses",
        "attachment",
        "chain_search",
        "static_sweep",
        "motion_test",
        "total",
    ] {
        assert!(number(&timings[stage]) >= 0.0, "{stage}");
    }
    assert!(number(&timings["total"]) >= number(&timings["attachment"]));
}

#[test]
fn no_cable_path_is_an_answer_with_exit_code_zero() {
    let dir = tempfile::tempdir().expect("temp dir");
    // 10–30 mm of cable between guides ~170 mm apart: every PV is too short.
    let setup = small_setup_with_lengths(
        dir.path(),
        "lengths = { min = 1, max = 3, step = 1, allow_zero = false }",
    );
    let (code, result, stderr) = json_run(&["solve", "--setup", &setup, MOTION, "--json"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(result["status"], "unsolved");
    assert_eq!(result["outcome"], "no_chain");
    assert!(result["ecpv"].is_null());
    assert!(result["total_length_mm"].is_null());
    assert_eq!(number(&result["sets"][0]["d1"]), 0.0);
    let reason = result["reason"].as_str().expect("reason");
    assert!(
        reason.contains("C1") && reason.contains("too short"),
        "{reason}"
    );
    assert_eq!(number(&result["motion_test"]["candidates_tried"]), 0.0);
}

#[test]
fn bad_input_exits_with_two_and_names_the_file_and_place() {
    let dir = tempfile::tempdir().expect("temp dir");
    let csv = dir.path().join("bad.csv");
    std::fs::write(
        &csv,
        "time_s,joint_1_deg,joint_2_deg,joint_3_deg,joint_4_deg,joint_5_deg,joint_6_deg\n\
         0,0,-68.6,216.4,0,32.2,0\n\
         0.1,0,-68.6,NaN,0,32.2,0\n",
    )
    .expect("written");
    let csv = csv.to_str().expect("utf-8");
    let missing = dir.path().join("missing.toml");
    let missing = missing.to_str().expect("utf-8");
    let cases: [(Vec<&str>, Vec<&str>); 5] = [
        (
            vec!["solve", "--setup", SMALL, csv],
            vec!["bad.csv:3", "joint_3_deg", "NaN"],
        ),
        (
            vec!["solve", "--setup", missing, MOTION],
            vec!["missing.toml", "cannot read"],
        ),
        (
            vec!["solve", "--setup", SMALL, MOTION, "--k-best", "0"],
            vec!["--k-best"],
        ),
        (
            vec![
                "solve",
                "--setup",
                SMALL,
                MOTION,
                "--max-guides-per-link",
                "3",
            ],
            vec!["max-guides-per-link"],
        ),
        (vec!["critical-poses", SMALL, csv], vec!["bad.csv:3", "NaN"]),
    ];
    for (args, expected) in cases {
        let output = run(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        for text in expected {
            assert!(stderr.contains(text), "{args:?}: {stderr}");
        }
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

#[test]
fn critical_poses_json_lists_the_extremes_of_the_traversed_joint() {
    let (code, segments, stderr) = json_run(&["critical-poses", SMALL, MOTION, "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let c1 = &segments[0];
    assert_eq!(c1["traversed_joints"][0], "joint_4");
    // Reference: the extremes of joint 4 read from the CSV column itself.
    let text = std::fs::read_to_string(crate::common::root().join(MOTION)).expect("motion");
    let joint_4: Vec<f64> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("time_s"))
        .map(|l| {
            l.split(',')
                .nth(4)
                .expect("column")
                .parse()
                .expect("number")
        })
        .collect();
    let (lo, hi) = joint_4
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let poses = c1["poses"].as_array().expect("poses");
    assert_eq!(poses.len(), 2);
    let mut found: Vec<f64> = poses.iter().map(|p| number(&p["joints"][3])).collect();
    found.sort_by(f64::total_cmp);
    assert!((found[0] - lo).abs() < 1e-9 && (found[1] - hi).abs() < 1e-9);
}

/// Every robust PV of the small setup fails the motion test (its G2 clamp zone lies in the
/// wrist box, and the cable touches the forearm between critical poses). The search must
/// try each PV exactly once — shortest first when it learns nothing from the failures
/// (`learn: false`); with learning, the pieces it set aside come back when no chain is left
/// without them, so every one is still tried — and then say that no chain is left.
#[test]
fn the_motion_test_search_tries_every_robust_pv_once_in_length_order() {
    let setup = Setup::from_file(SMALL).expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, MOTION).expect("motion");
    // Reference: D2 from the attachment test run directly.
    let poses = SegmentPoses::new(&setup, &motion).expect("poses");
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    let d2: BTreeSet<_> = attachment_test(&evaluator, &poses)[0]
        .d2
        .iter()
        .map(|pv| (pv.sub_segments, pv.start, pv.end))
        .collect();
    for learn in [false, true] {
        let options = SolveOptions {
            k_best: 1000,
            learn,
            ..SolveOptions::default()
        };
        let report = solve(&setup, &motion, &options).expect("solve");
        let tried: Vec<_> = report
            .candidates
            .iter()
            .map(|c| {
                let pv = c.path.pv(0);
                (pv.sub_segments, pv.start, pv.end)
            })
            .collect();
        let unique: BTreeSet<_> = tried.iter().collect();
        assert_eq!(unique.len(), tried.len(), "learning {learn}: {tried:?}");
        if report.status != Status::Solved {
            // Every robust PV was either dropped by the static sweep or failed the motion
            // test.
            assert_eq!(report.status, Status::NonePassedMotionTest);
            let swept_out = &report.static_sweep.rejected;
            assert!(tried.iter().all(|pv| d2.contains(pv)));
            assert_eq!(tried.len() + swept_out.len(), d2.len(), "learning {learn}");
            assert!(report.explanation.contains("no chain is left"));
        }
        assert_eq!(report.static_sweep.poses, distinct_samples(&motion));
        assert!(report.static_sweep.pvs_swept >= report.candidates.len());
        if !learn {
            assert!(tried.windows(2).all(|w| w[0].0 <= w[1].0), "{tried:?}");
        }
        for c in &report.candidates {
            assert_eq!(c.passed, Some(c.failure.is_none()));
        }
    }
}

/// Samples that differ from the one before them (the first counts).
fn distinct_samples(motion: &Motion) -> usize {
    1 + motion.samples().windows(2).filter(|w| w[0] != w[1]).count()
}

#[test]
fn a_budget_of_one_motion_test_tries_the_shortest_chain_only() {
    let setup = Setup::from_file(SMALL).expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, MOTION).expect("motion");
    let untested = solve(
        &setup,
        &motion,
        &SolveOptions {
            motion_test: false,
            ..SolveOptions::default()
        },
    )
    .expect("solve");
    let tested = solve(
        &setup,
        &motion,
        &SolveOptions {
            k_best: 1,
            // Without the sweep, nothing stands between d̂ and its motion test.
            static_sweep: false,
            ..SolveOptions::default()
        },
    )
    .expect("solve");
    assert_eq!(tested.candidates.len(), 1);
    assert_eq!(tested.candidates[0].path, untested.candidates[0].path);
    if tested.status != Status::Solved {
        assert!(tested.explanation.contains("budget of 1 motion tests"));
    }
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let setup = Setup::from_file(SMALL).expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, MOTION).expect("motion");
    let options = SolveOptions {
        k_best: 3,
        ..SolveOptions::default()
    };
    let result = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let report = pool.install(|| solve(&setup, &motion, &options).expect("solve"));
        let mut value = serde_json::to_value(&report).expect("JSON");
        // Wall-clock times are the only values allowed to differ.
        value["timings_s"] = Value::Null;
        value["motion_test"]["wall_time_s"] = Value::Null;
        for motion in value["motions"].as_array_mut().expect("motions") {
            motion["wall_time_s"] = Value::Null;
        }
        value
    };
    assert_eq!(result(1), result(2));
}

/// The README's main job: the bundled pick-and-place is solved, and d* keeps the cable
/// datasheet's limits (read from the cable file here, not through the setup) over the whole
/// dynamic run, and the cable never touches itself; every chain tried before it failed.
#[test]
fn the_bundled_pick_and_place_is_solved_within_the_datasheet_limits() {
    let root = crate::common::root();
    let setup =
        Setup::from_file(root.join("robots/viper_s850/pick_and_place.toml")).expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, root.join(MOTION)).expect("motion");
    let options = SolveOptions {
        shape_interval_s: Some(FRAME_S),
        ..SolveOptions::default()
    };
    let report = solve(&setup, &motion, &options).expect("solve");
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    check_report_folder(&setup, &motion, &report);

    let cable: toml::Table = std::fs::read_to_string(root.join("cables/smc_le_cp_3.toml"))
        .expect("cable file")
        .parse()
        .expect("cable TOML");
    let datasheet_bend_mm = cable["min_bend_radius_mm"].as_float().expect("number");
    let dynamics = report.motion_test.as_ref().expect("motion test");
    assert!(dynamics.passed);
    let worst = |w: &Option<cable_dict::motion_test::Worst>| w.as_ref().expect("worst").value;
    assert!(worst(&dynamics.worst_bend) * 1e3 >= datasheet_bend_mm);
    assert!(worst(&dynamics.worst_clearance) >= 0.0);
    assert!(worst(&dynamics.worst_stretch) <= 1.02);
    // The answer never comes back toward itself closer than it may (or not at all).
    assert!(
        dynamics
            .worst_self_clearance
            .as_ref()
            .is_none_or(|w| w.value >= 0.0)
    );

    let ecpv = report.optimal.as_ref().expect("d*");
    let total_mm: f64 = ecpv
        .segments
        .iter()
        .map(|s| s.sub_segments as f64 * 10.0)
        .sum();
    assert_eq!(report.optimal_length_mm, Some(total_mm));
    let (winner, failed) = report.candidates.split_last().expect("candidates");
    assert_eq!(winner.passed, Some(true));
    assert!(failed.iter().all(|c| c.passed == Some(false)));
    assert!(
        failed
            .iter()
            .all(|c| c.total_length_mm <= winner.total_length_mm)
    );
}

/// Keyframe interval of the report scene (s).
const FRAME_S: f64 = 1.0 / 30.0;

/// The report of the bundled pick-and-place: the stress plot says d* passed, the scene
/// animates the whole motion test at 30 frames/s and has one snapshot per critical pose.
/// Written to `$CABLE_DICT_REPORT_OUT` when set (CI validates its scene.glb with the Khronos
/// validator), else to a temporary folder.
fn check_report_folder(setup: &Setup, motion: &Motion, report: &cable_dict::solve::SolveReport) {
    let temporary = tempfile::tempdir().expect("temporary folder");
    let dir = std::env::var_os("CABLE_DICT_REPORT_OUT")
        .map_or_else(|| temporary.path().to_path_buf(), std::path::PathBuf::from);
    write_report(&dir, setup, motion, report).expect("report written");

    let stress = std::fs::read_to_string(dir.join("stress.svg")).expect("stress.svg");
    assert!(stress.contains("motion test passed"));
    let bytes = std::fs::read(dir.join("scene.glb")).expect("scene.glb");
    let scene = gltf::Gltf::from_slice(&bytes).expect("valid glTF");
    let animation = scene.animations().next().expect("an animation");
    let times: Vec<f32> = animation
        .channels()
        .next()
        .and_then(|c| c.reader(|_| scene.blob.as_deref()).read_inputs())
        .expect("keyframe times")
        .collect();
    let simulated = report
        .motion_test
        .as_ref()
        .expect("motion test")
        .simulated_s;
    let step = 1.0 / 240.0;
    assert_eq!(times[0], 0.0);
    assert!((f64::from(times[times.len() - 1]) - simulated).abs() < 1e-4);
    for pair in times[..times.len() - 1].windows(2) {
        assert!(
            (f64::from(pair[1] - pair[0]) - FRAME_S).abs() < step,
            "{pair:?}"
        );
    }
    let named = |prefix: &str| {
        scene
            .nodes()
            .filter(|n| n.name().is_some_and(|name| name.starts_with(prefix)))
            .count()
    };
    let critical: BTreeSet<usize> = report
        .segments
        .iter()
        .filter(|s| s.kind == "inter-link")
        .flat_map(|s| s.test_poses.iter().map(|p| p.sample))
        .collect();
    assert_eq!(named("critical pose "), critical.len());
    let c1 = &report.optimal.as_ref().expect("d*").segments[0];
    assert_eq!(named("C1 sub-segment "), c1.sub_segments);
    check_pictures_against_the_physics(setup, motion, report, &critical, &dir);
}

/// Each critical pose's picture draws d*'s static equilibrium there — computed here by the
/// attachment test's evaluator, projected here — and its clamps where the setup puts them:
/// every cable node and clamp at its world coordinates (mm, vertical axis negated, rounded to
/// 0.1 mm) in each view.
fn check_pictures_against_the_physics(
    setup: &Setup,
    motion: &Motion,
    report: &cable_dict::solve::SolveReport,
    critical: &BTreeSet<usize>,
    dir: &Path,
) {
    let path = &report
        .candidates
        .iter()
        .find(|c| c.passed == Some(true))
        .expect("d*")
        .path;
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).expect("evaluator");
    // Front (x, −z), side (y, −z), top (x, −y), in mm.
    let project = |view: &str, p: [f64; 3]| {
        let (right, up) = match view {
            "front" => (0, 2),
            "side" => (1, 2),
            _ => (0, 1),
        };
        [p[right] * 1e3, -p[up] * 1e3]
    };
    let near = |drawn: [f64; 2], expected: [f64; 2]| {
        (drawn[0] - expected[0]).abs() <= 0.051 && (drawn[1] - expected[1]).abs() <= 0.051
    };
    for (k, &sample) in critical.iter().enumerate() {
        let file = format!("pose-{}.svg", k + 1);
        let svg = std::fs::read_to_string(dir.join(&file)).expect("picture");
        let elements = svg_pictures::elements(&svg);
        let link_poses = setup
            .robot
            .link_poses(&motion.samples()[sample])
            .expect("poses");
        for view in svg_pictures::VIEWS {
            // A 0 mm piece (two clamps at one place) has no cable to draw.
            for m in (0..path.segment_count()).filter(|&m| path.pv(m).sub_segments > 0) {
                let nodes = evaluator
                    .equilibrium_nodes(m, &path.pv(m), &link_poses)
                    .expect("an equilibrium");
                let piece = format!("C{}", m + 1);
                let line = elements
                    .iter()
                    .find(|e| e.is("polyline", view, "cable") && e.attribute("data-piece") == piece)
                    .unwrap_or_else(|| panic!("{file} {view}: no {piece}"));
                let drawn = svg_pictures::points(line.attribute("points"));
                assert_eq!(drawn.len(), nodes.len(), "{file} {view} {piece}");
                for (d, node) in drawn.iter().zip(&nodes) {
                    let expected = project(view, [node.x, node.y, node.z]);
                    assert!(
                        near(*d, expected),
                        "{file} {view} {piece}: {d:?} ≠ {expected:?}"
                    );
                }
            }
            let clamps: Vec<[f64; 2]> = elements
                .iter()
                .filter(|e| e.is("circle", view, "clamps"))
                .map(|e| [e.attribute("cx"), e.attribute("cy")].map(|v| v.parse().expect("number")))
                .collect();
            // One dot per physical clamp: a guide after a 0 mm piece is the previous one's.
            let mounted: Vec<usize> = (0..setup.guides.len())
                .filter(|&g| g == 0 || path.pv(g - 1).sub_segments > 0)
                .collect();
            assert_eq!(clamps.len(), mounted.len());
            for (dot, &g) in clamps.iter().zip(&mounted) {
                let guide = &setup.guides[g];
                let at = link_poses[guide.link] * guide.configurations[path.configurations[g]].pose;
                let v = at.translation.vector;
                let expected = project(view, [v.x, v.y, v.z]);
                assert!(near(*dot, expected), "{file} {view} G{}", g + 1);
            }
        }
    }
}

/// `-v` logs each stage with its set sizes and time on standard error and leaves standard
/// output as it was; `-q`, and a plain run on a pipe (no progress bars there), leave standard
/// error empty; `-q` and `-v` together are refused.
#[test]
fn verbosity_changes_standard_error_only() {
    let args = [
        "solve",
        "--setup",
        SMALL,
        MOTION,
        "--no-motion-test",
        "--json",
    ];
    let with = |flag: &str| run(&[&[flag][..], &args[..]].concat());
    let (verbose, quiet) = (with("-v"), with("-q"));
    assert!(verbose.status.success() && quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
    let result: Value = serde_json::from_slice(&quiet.stdout).expect("JSON");
    let without_timings = |output: &[u8]| {
        let mut value: Value = serde_json::from_slice(output).expect("JSON");
        value["timings_s"] = Value::Null;
        value
    };
    assert_eq!(
        without_timings(&verbose.stdout),
        without_timings(&quiet.stdout)
    );
    let log = String::from_utf8_lossy(&verbose.stderr);
    let d1 = &result["sets"][0]["d1"];
    assert!(log.contains(&format!(", {d1} hold the limits, ")), "{log}");
    for stage in ["critical poses:", "attachment test:", "chain search: "] {
        assert!(log.contains(stage), "{stage} missing: {log}");
    }
    assert_eq!(
        run(&[&["-q", "-v"][..], &args[..]].concat()).status.code(),
        Some(2)
    );
}

/// Learning from failed motion tests against the motion test of every chain: on a small
/// real case (the hand-written inspection catalogue over the pick-and-place motion, which
/// strictly shortest first passes after 18 failed tests), every chain of robust pieces in
/// non-decreasing length is swept, checked at rest and simulated until one passes — no piece
/// dropped, no swing learned. The learning search finds that chain, or one no shorter whose
/// answer names an untried chain no longer than it; the strict search finds it exactly.
#[test]
fn learning_against_the_motion_test_of_every_chain_in_order() {
    use cable_dict::attachment::{IntraLinkCriterion, MotionSweep};
    use cable_dict::chain::ChainSearch;
    use cable_dict::motion_test::{self, MotionTestOptions};
    let setup = Setup::from_file("robots/viper_s850/hand_written/inspection.toml").expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, MOTION).expect("motion");
    let learning = solve(&setup, &motion, &SolveOptions::default()).expect("solves");
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;

    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    let poses =
        SegmentPoses::with(&setup, &motion, IntraLinkCriterion::GravityDirections).expect("poses");
    let d2: Vec<_> = attachment_test(&evaluator, &poses)
        .into_iter()
        .map(|s| s.d2)
        .collect();
    let (counts, ends) = (setup.configuration_counts(), setup.segment_ends());
    let chains = ChainSearch::over(&counts, &ends, &d2).expect("chains");
    let mut sweep = MotionSweep::new(&evaluator, &motion).expect("sweep");
    let test = MotionTestOptions {
        stop_at_first_violation: true,
        record_series: false,
        ..MotionTestOptions::default()
    };
    let mut simulated = 0;
    let reference = chains.k_best().find(|path| {
        let pieces: Vec<_> = path.pieces().map(|(m, pv)| (m, pv, None)).collect();
        if sweep.check_until(&pieces).iter().any(Option::is_some) {
            return false;
        }
        simulated += 1;
        let report = motion_test::run(&setup, path, &motion, &test).expect("runs");
        report.passed
    });
    let reference = reference.expect("a chain passes");
    let reference_mm = reference.total_sub_segments() as f64 * pitch_mm;
    println!(
        "reference: {reference_mm} mm after simulating {simulated} chains; learning: {:?} mm \
         after {} motion tests, shortest untried {:?} mm",
        learning.optimal_length_mm,
        learning.candidates.len(),
        learning.static_sweep.shortest_untried_mm
    );
    let strict = SolveOptions {
        learn: false,
        ..SolveOptions::default()
    };
    let strict = solve(&setup, &motion, &strict).expect("solves");
    assert_eq!(strict.optimal_length_mm, Some(reference_mm));
    let answer_mm = learning.optimal_length_mm.expect("learning answers");
    assert!(
        answer_mm >= reference_mm - 1e-9,
        "{answer_mm} < {reference_mm}"
    );
    if answer_mm > reference_mm + 1e-9 {
        let untried = learning.static_sweep.shortest_untried_mm;
        assert!(
            untried.is_some_and(|u| u <= reference_mm + 1e-9),
            "learning answered {answer_mm} mm without naming a chain of {reference_mm} mm: {untried:?}"
        );
    }
}
