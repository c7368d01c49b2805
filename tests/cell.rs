//! A cell: one mounting for several motions (`solve` with several motions), and `check`, an
//! installed cable against motions with no search.

use crate::common::{root, run};
use cable_dict::motion::{Cell, Motion};
use cable_dict::motion_test::{self, MotionTestOptions};
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve, solve_cell};
use serde_json::Value;

fn setup() -> Setup {
    Setup::from_file(root().join(SETUP)).unwrap_or_else(|e| panic!("{e}"))
}

fn motion(setup: &Setup, name: &str) -> Motion {
    let file = root().join(format!("motions/viper_s850/{name}.csv"));
    Motion::from_csv_file(&setup.robot, file).unwrap_or_else(|e| panic!("{e}"))
}

const SETUP: &str = "robots/viper_s850/pick_and_place.toml";
const PICK: &str = "motions/viper_s850/pick_and_place.csv";

/// The bundled pick and place solved into a fresh folder named for `what`: the folder, the
/// result JSON's path and its content.
fn solved_pick_and_place(what: &str) -> (std::path::PathBuf, String, Value) {
    let dir = std::env::temp_dir().join(format!("cable-dict-{what}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let result = dir.join("result.json");
    let result = result.to_str().expect("a UTF-8 path").to_string();
    let solved = run(&["solve", "--setup", SETUP, PICK, "-o", &result]);
    let stderr = String::from_utf8_lossy(&solved.stderr);
    assert!(solved.status.success(), "{stderr}");
    let text = std::fs::read(&result).unwrap_or_else(|e| panic!("{e}"));
    let json = serde_json::from_slice(&text).unwrap_or_else(|e| panic!("{e}"));
    (dir, result, json)
}

/// The bundled pick-and-place and machine-tending answers are mirror images of each other;
/// one mounting for both must hold each motion's test when simulated alone, and cannot be
/// shorter than the shortest path of either motion alone (every path that holds both holds
/// each).
#[test]
fn one_mounting_for_two_motions_holds_each_and_is_no_shorter_than_either_alone() {
    let setup = setup();
    let names = ["pick_and_place", "machine_tending"];
    // Strictly shortest first, so that each single answer is the shortest that passes.
    let strict = SolveOptions {
        learn: false,
        ..SolveOptions::default()
    };
    let mut shortest_alone_mm = Vec::new();
    for name in names {
        let single =
            solve(&setup, &motion(&setup, name), &strict).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(single.status, Status::Solved, "{name}");
        assert!(single.unsolved.is_none(), "{name}: budget spent?");
        shortest_alone_mm.push(single.optimal_length_mm.expect("a length"));
    }
    let files: Vec<_> = (names.iter())
        .map(|n| root().join(format!("motions/viper_s850/{n}.csv")))
        .collect();
    let cell = Cell::from_files(&setup.robot, &files).unwrap_or_else(|e| panic!("{e}"));
    let solution =
        solve_cell(&setup, &cell, &SolveOptions::default(), None).unwrap_or_else(|e| panic!("{e}"));
    let report = &solution.report;
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    let length_mm = report.optimal_length_mm.expect("a length");
    for (name, alone) in names.iter().zip(&shortest_alone_mm) {
        assert!(
            length_mm >= *alone,
            "{length_mm} mm < {name} alone, {alone} mm"
        );
    }
    // Each motion's verdict, and the same path simulated motion by motion on its own.
    let path = &report.candidates.last().expect("the answer").path;
    let options = MotionTestOptions::new(
        SolveOptions::default()
            .engine
            .with_defaults(setup.gravity_m_s2),
    );
    for (verdict, name) in report.motions.iter().zip(names) {
        assert_eq!(verdict.name, name);
        assert_eq!(verdict.verdict(), "holds", "{name}");
        let alone = motion_test::run(&setup, path, &motion(&setup, name), &options)
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(alone.passed, "{name}: {:?}", alone.failure);
    }
    // Each simulated piece names the motion that bends it most: one of the two.
    assert!(!report.binding.is_empty());
    for piece in &report.binding {
        let motion = piece.bend_radius.as_ref().map(|b| b.motion.as_str());
        assert!(motion.is_some_and(|m| names.contains(&m)), "{piece:?}");
    }
}

/// `check` is the motion test of the mounting a solve found: against the motion it was
/// solved for, the margins are the solve's to the last digit; against another motion it may
/// fail, and says which limit, where and when; exit codes gate a pipeline.
#[test]
fn check_gives_the_margins_the_solve_reported_and_gates_with_exit_codes() {
    let (dir, result, solve_json) = solved_pick_and_place("check");
    let result_arg = result.as_str();
    let pick = PICK;
    let tending = "motions/viper_s850/machine_tending.csv";
    let json =
        |bytes: &[u8]| -> Value { serde_json::from_slice(bytes).unwrap_or_else(|e| panic!("{e}")) };

    let same = run(&["check", result_arg, pick, "--json"]);
    assert_eq!(
        same.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&same.stderr)
    );
    let same = json(&same.stdout);
    assert_eq!(same["verdict"], "holds");
    let checked = &same["motions"][0];
    for key in [
        "min_clearance_mm",
        "min_bend_radius_mm",
        "max_stretch",
        "min_self_clearance_mm",
        "worst_clearance",
        "worst_bend_radius",
        "twists",
        "clamp_loads",
    ] {
        assert_eq!(checked[key], solve_json["motion_test"][key], "{key}");
    }
    assert_eq!(same["total_length_mm"], solve_json["total_length_mm"]);

    let other = run(&["check", result_arg, pick, tending, "--json"]);
    assert_eq!(
        other.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&other.stderr)
    );
    let other = json(&other.stdout);
    assert_eq!(other["verdict"], "fails");
    let tending_json = &other["motions"][1];
    assert_eq!(tending_json["verdict"], "fails");
    assert!(
        tending_json["failure"]
            .as_str()
            .is_some_and(|f| !f.is_empty())
    );
    let words = run(&["check", result_arg, pick, tending]);
    let words = String::from_utf8_lossy(&words.stdout);
    assert!(
        words.contains("\nfails — 1 of 2 motions fails: machine_tending"),
        "{words}"
    );
    assert!(
        words.contains(" at t = ") && words.contains("from clamp"),
        "{words}"
    );

    // Invalid input: a motion that does not exist, a setup the result was not solved with.
    let missing = run(&["check", result_arg, "motions/viper_s850/nothing.csv"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("nothing.csv"));
    let other_setup = "robots/viper_s850/inspection.toml";
    let wrong = run(&["check", result_arg, pick, "--setup", other_setup]);
    assert_eq!(wrong.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&wrong.stderr).contains("another setup"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The mounting file a fitter writes from the sheet — each clamp's link, place and mark, read
/// off a tape to the millimetre and degree — reads back into the path the solve found, and
/// `check` then gives the solve's margins; a clamp measured where the setup has no place, or
/// a clamp missing, is refused with what is wrong.
#[test]
fn a_mounting_measured_as_the_sheet_gives_it_is_the_path_the_solve_found() {
    let (dir, _, solve_json) = solved_pick_and_place("measured");
    let setup = root().join(SETUP);
    let setup_arg = setup.to_str().expect("a UTF-8 path");
    let pick = PICK;
    // The sheet's clamps (not the fitting at the tool end), as a fitter measures them.
    let clamps: Vec<&Value> = (solve_json["mounting"]["clamps"].as_array())
        .expect("clamps")
        .iter()
        .filter(|c| c["fitting"].is_null())
        .collect();
    assert!(clamps.len() >= 2);
    let file = |shift_along_mm: f64, leave_out: Option<usize>| -> String {
        let mut text = format!("setup = {setup_arg:?}\n");
        for (k, clamp) in clamps.iter().enumerate() {
            if leave_out == Some(k) {
                continue;
            }
            let place = &clamp["place"];
            let along = place["along_mm"].as_f64().expect("along")
                + if k == 0 { shift_along_mm } else { 0.0 };
            text += &format!(
                "\n[[clamps]]\nlink = {:?}\nalong_mm = {:.0}\naround_deg = {:.0}\n\
                 cable_to_axis_deg = {:.0}\nmark_mm = {:.0}\n",
                clamp["link"].as_str().expect("link"),
                along,
                place["around_deg"].as_f64().expect("around"),
                place["cable_to_axis_deg"].as_f64().expect("angle"),
                clamp["mark_mm"].as_f64().expect("mark"),
            );
            if let Some(turn) = place["cable_turn"].as_str() {
                text += &format!("cable_turn = {turn:?}\n");
            }
        }
        text
    };
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
        path.to_str().expect("a UTF-8 path").to_string()
    };
    let measured = write("measured.toml", file(0.0, None));
    let checked = check_holds(&measured, pick);
    assert_eq!(checked["ecpv"], solve_json["ecpv"]);
    for key in [
        "min_clearance_mm",
        "min_bend_radius_mm",
        "worst_bend_radius",
    ] {
        assert_eq!(
            checked["motions"][0][key], solve_json["motion_test"][key],
            "{key}"
        );
    }

    let far = write("far.toml", file(40.0, None));
    let refused = run(&["check", &far, pick]);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("far.toml:3:") && stderr.contains("the nearest"),
        "{stderr}"
    );
    let missing = write("missing.toml", file(0.0, Some(0)));
    let refused = run(&["check", &missing, pick]);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("G1") && stderr.contains("not optional"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The bundled dress pack's mounting as a fitter measures it — the retraction's inlet (a
/// fitting) and the one clamp; the retraction's outlet and the ring are not clamps and get no
/// mark — reads back into the path the solve found, through both sliding parts, and `check`
/// gives the solve's margins.
#[test]
fn a_measured_dress_pack_skips_the_guides_the_cable_slides_through() {
    let dir = tempfile::tempdir().unwrap();
    let (setup_arg, solve_json) = solved_on_pick("robots/viper_s850/dress_pack.toml");
    let mounting = &solve_json["mounting"];
    let kinds: Vec<&str> = (mounting["sliding_parts"].as_array().expect("sliding parts"))
        .iter()
        .map(|p| p["kind"].as_str().expect("kind"))
        .collect();
    assert_eq!(kinds, ["retraction", "sliding"]);
    let clamps = mounting["clamps"].as_array().expect("clamps");
    let inlet = &clamps[0];
    let text = format!(
        "setup = {setup_arg:?}\n\n{}{}",
        measured_fitting(inlet, inlet["mark_mm"].as_f64().expect("mark")),
        measured_clamp(&clamps[1]),
    );
    let path = dir.path().join("measured.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    let checked = reads_back(&path, &solve_json);
    // Both runs followed the outlet and the ring alike, and say so in the JSON.
    let guides = |slides: &Value| -> Vec<String> {
        (slides.as_array().expect("slides").iter())
            .map(|s| s["guide"].as_str().expect("guide").to_string())
            .collect()
    };
    let solved_slides = &solve_json["motion_test"]["slides"];
    assert_eq!(guides(solved_slides), ["R", "S"]);
    let checked_slides = &checked["motions"][0]["slides"];
    for key in ["least_m", "most_m", "first_m"] {
        for i in 0..2 {
            assert_eq!(checked_slides[i][key], solved_slides[i][key], "{key}");
        }
    }
}

/// The bundled setup `file`'s absolute path and its solve of pick and place, as JSON.
fn solved_on_pick(file: &str) -> (String, Value) {
    let setup = root().join(file);
    let setup_arg = setup.to_str().expect("a UTF-8 path").to_string();
    let solved = run(&["solve", "--setup", &setup_arg, PICK, "--json"]);
    let json = serde_json::from_slice(&solved.stdout).unwrap_or_else(|e| panic!("{e}"));
    (setup_arg, json)
}

/// A `[[clamps]]` entry of a measured mounting: the solve's `clamp` measured as the sheet
/// gives it.
fn measured_clamp(clamp: &Value) -> String {
    let place = &clamp["place"];
    format!(
        "[[clamps]]\nlink = {:?}\nalong_mm = {:.0}\naround_deg = {:.0}\ncable_to_axis_deg = \
         {:.0}\ncable_turn = {:?}\nmark_mm = {:.0}\n\n",
        clamp["link"].as_str().expect("link"),
        place["along_mm"].as_f64().expect("along"),
        place["around_deg"].as_f64().expect("around"),
        place["cable_to_axis_deg"].as_f64().expect("angle"),
        place["cable_turn"].as_str().expect("turn"),
        clamp["mark_mm"].as_f64().expect("mark"),
    )
}

/// A `[[clamps]]` entry of a measured mounting: the solve's fitting `clamp` at `mark_mm`.
fn measured_fitting(clamp: &Value, mark_mm: f64) -> String {
    let name = clamp["fitting"].as_str().expect("a fitting");
    format!("[[clamps]]\nfitting = {name:?}\nmark_mm = {mark_mm:.0}\n\n")
}

/// `check` of the measured mounting at `path` holds on pick and place with the margins of
/// the solve `solve_json`, on its path: its JSON.
fn reads_back(path: &std::path::Path, solve_json: &Value) -> Value {
    let checked = check_holds(path.to_str().expect("a UTF-8 path"), PICK);
    assert_eq!(checked["ecpv"], solve_json["ecpv"]);
    for key in ["min_clearance_mm", "min_bend_radius_mm"] {
        assert_eq!(
            checked["motions"][0][key], solve_json["motion_test"][key],
            "{key}"
        );
    }
    checked
}

/// The forearm swivel's mounting as a fitter measures it — the clamp on link_3 and the
/// swivel clamp at its mark — reads back into the path the solve found (one piece of the
/// search through the swivel) with the solve's margins; a swivel measured 30 mm off its mark
/// is refused with the mark the solve gave.
#[test]
fn a_measured_swivel_between_two_pieces_reads_back_at_its_mark() {
    let dir = tempfile::tempdir().unwrap();
    let (setup_arg, solve_json) = solved_on_pick("robots/viper_s850/swivel_forearm.toml");
    let clamps = solve_json["mounting"]["clamps"].as_array().expect("clamps");
    let (clamp, swivel) = (&clamps[0], &clamps[1]);
    assert_eq!(swivel["kind"], "swivel");
    let swivel_mark = swivel["mark_mm"].as_f64().expect("mark");
    let measured = |mark_mm: f64| {
        format!(
            "setup = {setup_arg:?}\n\n{}{}",
            measured_clamp(clamp),
            measured_fitting(swivel, mark_mm)
        )
    };
    let path = dir.path().join("measured.toml");
    std::fs::write(&path, measured(swivel_mark)).unwrap_or_else(|e| panic!("{e}"));
    reads_back(&path, &solve_json);
    std::fs::write(&path, measured(swivel_mark + 30.0)).unwrap_or_else(|e| panic!("{e}"));
    let refused = run(&["check", path.to_str().unwrap(), PICK]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    let says = format!("mount it at mark {swivel_mark} mm");
    assert!(
        stderr.contains(&says) && stderr.contains("measured.toml"),
        "{stderr}"
    );
}

/// `check MOUNTING MOTION --json`, which must hold (exit 0): its JSON.
fn check_holds(mounting: &str, motion: &str) -> Value {
    let checked = run(&["check", mounting, motion, "--json"]);
    assert_eq!(
        checked.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&checked.stderr)
    );
    serde_json::from_slice(&checked.stdout).unwrap_or_else(|e| panic!("{e}"))
}
