//! The `cable-dict` binary end to end: JSON shapes, values against closed forms, exit codes.

use crate::common;

use common::run;
use serde_json::Value;

const URDF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/robots/viper_s850/viper_s850.urdf"
);
const CABLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/cables/smc_le_cp_3_paper.toml");

fn json(args: &[&str]) -> Value {
    let output = run(args);
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("valid JSON")
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .expect("array")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect()
}

/// Arguments of a `segment` run.
fn segment<'a>(cable: &'a str, length_mm: &'a str, start: &'a str, end: &'a str) -> Vec<&'a str> {
    vec![
        "segment",
        "--cable",
        cable,
        "--length-mm",
        length_mm,
        "--start",
        start,
        "--end",
        end,
    ]
}

/// A JSON array of number arrays (a row-major matrix, or a list of points).
fn matrix(value: &Value) -> Vec<Vec<f64>> {
    value
        .as_array()
        .expect("array of arrays")
        .iter()
        .map(numbers)
        .collect()
}

fn failure(args: &[&str]) -> (i32, String) {
    let output = run(args);
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn fk_json_gives_the_flange_of_the_dh_table_at_zero() {
    let report = json(&["fk", URDF, "--joints-deg", "0,0,0,0,0,0", "--json"]);
    let links = report["links"].as_array().expect("links");
    assert_eq!(links.len(), 8);
    let tool0 = links.iter().find(|l| l["name"] == "tool0").expect("tool0");
    // x = a1 + a2 + a3, z = d1 + d4 + d6.
    let expected = [0.075 + 0.365 - 0.090, 0.0, 0.335 + 0.405 + 0.080];
    for (got, want) in numbers(&tool0["position_m"]).iter().zip(expected) {
        assert!((got - want).abs() < 1e-12);
    }
    for (r, row) in matrix(&tool0["rotation"]).iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            assert!((v - if r == c { 1.0 } else { 0.0 }).abs() < 1e-12);
        }
    }
}

#[test]
fn fk_rotation_is_row_major_link_to_base() {
    // Joint 1 at +90°: every link's x axis maps to base +y, so row 1 column 0 is 1.
    let report = json(&["fk", URDF, "--joints-deg", "90,0,0,0,0,0", "--json"]);
    let link_1 = &report["links"][1];
    assert_eq!(link_1["name"], "link_1");
    let rows = matrix(&link_1["rotation"]);
    assert!(
        (rows[1][0] - 1.0).abs() < 1e-12 && (rows[0][1] + 1.0).abs() < 1e-12,
        "{rows:?}"
    );
}

#[test]
fn robot_info_lists_the_actuated_joints() {
    let report = json(&["robot-info", URDF, "--json"]);
    assert_eq!(report["dof"], 6);
    let names: Vec<&str> = report["joints"]
        .as_array()
        .expect("joints")
        .iter()
        .filter(|j| !j["joint_vector_index"].is_null())
        .map(|j| j["name"].as_str().expect("name"))
        .collect();
    assert_eq!(
        names,
        [
            "joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6"
        ]
    );
}

#[test]
fn segment_json_runs_from_guide_to_guide_in_pitch_steps() {
    let start = [0.0, 0.0, 0.0];
    let end = [250.0, 100.0, 50.0];
    let mut args = segment(CABLE, "400", "0,0,0,0,90,0", "250,100,50,0,90,0");
    args.extend(["--stage", "connected", "--json"]);
    let report = json(&args);
    assert_eq!(report["stage"], "connected");
    assert!(report.get("converged").is_none());
    assert_eq!(report["length_mm"], 400.0);
    let nodes = matrix(&report["nodes_mm"]);
    assert_eq!(nodes.len(), 41);
    let distance = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    assert!(distance(&nodes[0], &start) < 1e-6 && distance(&nodes[40], &end) < 1e-6);
    for pair in nodes.windows(2) {
        assert!(
            (distance(&pair[0], &pair[1]) - 10.0).abs() < 1e-6,
            "spacing in mm"
        );
    }
    // Both guides have pitch 90°: their +z (third column) is world +x.
    let frames = report["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 41);
    for frame in [&frames[0], &frames[40]] {
        let rows = matrix(frame);
        assert!(
            (rows[0][2] - 1.0).abs() < 1e-9 && rows[1][2].abs() < 1e-9 && rows[2][2].abs() < 1e-9
        );
    }
    let stretch = report["metrics"]["stretch"].as_f64().expect("stretch");
    assert!((stretch - 1.0).abs() < 1e-9, "nodes 10 mm apart: stretch 1");
    assert!(
        report["metrics"]["min_bend_radius_mm"]
            .as_f64()
            .expect("bent")
            > 0.0
    );
}

/// The default stage solves the equilibrium: it keeps its length, reports how the solve went,
/// and hangs lower than the same cable without gravity (which buckles into the elastica
/// between the coaxial guides).
#[test]
fn segment_converged_stage_hangs_under_gravity() {
    let mut args = segment(CABLE, "400", "0,0,0,0,90,0", "300,0,0,0,90,0");
    args.push("--json");
    let report = json(&args);
    assert_eq!(report["stage"], "converged");
    let converged = &report["converged"];
    assert_eq!(converged["solver"], "quasi-static");
    let nodes = matrix(&converged["nodes_mm"]);
    assert_eq!(nodes.len(), 41);
    assert!(nodes[0].iter().all(|c| c.abs() < 1e-9));
    assert!((nodes[40][0] - 300.0).abs() < 1e-9);
    let lowest = |nodes: &[Vec<f64>]| nodes.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    let stretch = converged["metrics"]["stretch"].as_f64().expect("stretch");
    assert!(stretch > 1.0 && stretch < 1.001, "{stretch}");
    assert!(converged["residual"].as_f64().expect("residual") <= 1e-8);
    assert!(converged["iterations"].as_u64().expect("iterations") >= 1);
    assert!(converged["solve_time_us"].as_f64().expect("time") > 0.0);
    // Without gravity the cable rises (by ~2 mm: over 400 mm its weight bends it little).
    args.extend(["--gravity", "0,0,0"]);
    let weightless = json(&args);
    let nodes = matrix(&weightless["converged"]["nodes_mm"]);
    assert!(lowest(&nodes) > lowest(&matrix(&converged["nodes_mm"])) + 1.0);
}

/// With `--robot` the links are obstacles: a cable straight through the Viper's upper arm at
/// q = 0 (the box spans z 0.335 ± 0.075 m around the arm's axis) is in contact with
/// `link_2`; the same cable 265 mm higher is clear of it.
#[test]
fn segment_with_a_robot_reports_contact() {
    let through = |z: &str| {
        let start = format!("250,-150,{z},-90,0,0");
        let end = format!("250,150,{z},-90,0,0");
        let mut args: Vec<String> = segment(CABLE, "300", &start, &end)
            .into_iter()
            .map(String::from)
            .collect();
        args.extend(["--robot", URDF, "--joints-deg", "0,0,0,0,0,0", "--json"].map(String::from));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        json(&args)
    };
    let inside = through("335");
    for stage in [&inside["metrics"], &inside["converged"]["metrics"]] {
        let contact = &stage["contact"];
        assert_eq!(contact["link"], "link_2");
        assert_eq!(contact["violation"], true);
        assert!(contact["min_clearance_mm"].as_f64().expect("clearance") < -50.0);
    }
    let above = through("600");
    let contact = &above["converged"]["metrics"]["contact"];
    assert_eq!(contact["violation"], false);
    assert!(contact["min_clearance_mm"].as_f64().expect("clearance") > 0.0);
}

#[test]
fn exit_codes_separate_no_answer_from_bad_input() {
    let too_short = failure(&segment(CABLE, "200", "0,0,0,0,0,0", "0,0,300,0,0,0"));
    assert_eq!(too_short.0, 1, "{}", too_short.1);
    assert!(
        too_short.1.contains("too short") && too_short.1.contains("1.500"),
        "{}",
        too_short.1
    );

    let cases: [(&[&str], &str); 5] = [
        (
            &segment(CABLE, "405", "0,0,0,0,0,0", "0,0,300,0,0,0"),
            "whole number of 10 mm",
        ),
        (
            &segment("missing.toml", "400", "0,0,0,0,0,0", "0,0,300,0,0,0"),
            "missing.toml",
        ),
        (
            &segment(CABLE, "400", "0,0,0,0,0", "0,0,300,0,0,0"),
            "expected 6 comma-separated numbers",
        ),
        (
            &["fk", URDF, "--joints-deg", "0,0,0,0,130,0"],
            "joint 'joint_5': 130 deg is outside its limits [-120, 120] deg",
        ),
        (
            &["fk", URDF, "--joints-deg", "0,0,0"],
            "expected 6 joint values",
        ),
    ];
    for (args, expected) in cases {
        let (code, stderr) = failure(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

#[test]
fn help_explains_every_subcommand() {
    let output = run(&["--help"]);
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    for command in ["robot-info", "fk", "segment"] {
        assert!(help.contains(command), "{help}");
    }
}

/// Every subcommand's help agrees with the documentation it cites: each section it sends
/// the reader to (`README, "Title"`, `README.md, "Title"` or `docs/page.md, "Title"`, several
/// titles possible) exists in that file (a heading or a bold paragraph title), and each time
/// range it quotes is in a file it cites, or in the README or a docs page when it cites none
/// (once `build --help` cited an explanation that did not exist, `segment --help`
/// quoted other solver timings).
#[test]
fn every_help_points_to_readme_sections_that_exist_and_quotes_its_timings() {
    let root = crate::common::root();
    let read = |relative: &str| {
        std::fs::read_to_string(root.join(relative)).unwrap_or_else(|e| panic!("{relative}: {e}"))
    };
    // The whole user documentation: the README and every page under docs/.
    let mut documentation = vec![("README.md".to_string(), read("README.md"))];
    for entry in std::fs::read_dir(root.join("docs")).expect("docs/") {
        let name = entry
            .expect("docs/ entry")
            .file_name()
            .into_string()
            .expect("UTF-8");
        if name.ends_with(".md") {
            let relative = format!("docs/{name}");
            let text = read(&relative);
            documentation.push((relative, text));
        }
    }
    let top = String::from_utf8_lossy(&run(&["--help"]).stdout).into_owned();
    let commands: Vec<&str> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() >= 15, "{commands:?}");
    let (mut references, mut timings) = (0, 0);
    for command in commands {
        let help = String::from_utf8_lossy(&run(&[command, "--help"]).stdout).into_owned();
        let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
        // `(docs/dictionaries.md, "Direction count": why 32)` → the file and each quoted title
        // up to the first ':' or ')'.
        let mut cited_files = Vec::new();
        let citations = help
            .match_indices(".md, \"")
            .map(|(at, _)| {
                let file_start = help[..at].rfind([' ', '(']).map_or(0, |i| i + 1);
                (format!("{}.md", &help[file_start..at]), at)
            })
            .chain(
                help.match_indices("README, \"")
                    .map(|(at, _)| ("README.md".to_string(), at)),
            );
        for (file, at) in citations {
            let (_, text) = documentation
                .iter()
                .find(|(name, _)| *name == file)
                .unwrap_or_else(|| panic!("`{command} --help` cites {file}, which does not exist"));
            let rest = &help[help[at..].find('"').expect("a title") + at..];
            let titles = &rest[..rest.find([':', ')']).unwrap_or(rest.len())];
            for title in titles.split('"').skip(1).step_by(2) {
                let heading = text
                    .lines()
                    .any(|l| l.starts_with('#') && l.contains(title));
                let bold = text.contains(&format!("**{title}.**"));
                assert!(
                    heading || bold,
                    "`{command} --help` cites {file}, \"{title}\", which is no heading there"
                );
                references += 1;
            }
            cited_files.push(text.as_str());
        }
        if cited_files.is_empty() {
            cited_files = documentation
                .iter()
                .map(|(_, text)| text.as_str())
                .collect();
        }
        let words: Vec<&str> = help.split(' ').collect();
        for pair in words
            .windows(2)
            .filter(|w| w[0].contains('–') && w[1] == "ms")
        {
            let range = format!("{} ms", pair[0].trim_start_matches('('));
            assert!(
                cited_files.iter().any(|text| text.contains(&range)),
                "`{command} --help` quotes {range}, which the pages it cites do not"
            );
            timings += 1;
        }
    }
    assert!(
        references >= 2,
        "the help cites the documentation {references} times"
    );
    assert!(timings >= 2, "the help quotes {timings} timings");
}

/// The documentation's own segment example (docs/commands.md, under `export-scene`) is a
/// cable that holds its limits: its static equilibrium is judged ok, and the start shape
/// (not a cable at rest) is not judged (the example once printed "TOO TIGHT").
#[test]
fn the_readme_segment_example_holds_its_limits() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/commands.md"))
        .expect("docs/commands.md");
    let start = readme
        .find("cable-dict export-scene segment --cable")
        .expect("the example");
    let example = readme[start..].split(" -o ").next().expect("its options");
    let words: Vec<&str> = example
        .split_whitespace()
        .filter(|w| *w != "\\")
        .skip(3)
        .collect();
    let mut args = vec!["segment"];
    args.extend(words);
    let output = run(&args);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{args:?}: {stdout}");
    let (start_shape, equilibrium) = stdout
        .split_once("static equilibrium")
        .expect("both stages");
    assert!(
        !start_shape.contains(": ok") && !start_shape.contains("below"),
        "{stdout}"
    );
    assert!(
        equilibrium.contains("(cable minimum 48.0 mm: ok)"),
        "{stdout}"
    );
}

/// The setup is taken the same way by every command that reads one: as `--setup` or as the
/// first file; `critical-poses` answers the same either way, and a `solve` without a setup
/// says how to give one.
#[test]
fn every_command_takes_the_setup_as_an_option_or_as_the_first_file() {
    let setup = "robots/viper_s850/pick_and_place.toml";
    let motion = "motions/viper_s850/pick_and_place.csv";
    let positional = json(&["critical-poses", setup, motion, "--json"]);
    let option = json(&["critical-poses", "--setup", setup, motion, "--json"]);
    assert_eq!(positional, option);
    assert!(positional.as_array().is_some_and(|a| !a.is_empty()));
    let sites = |args: &[&str]| {
        let output = run(args);
        assert!(output.status.success(), "{args:?}");
        output.stdout
    };
    assert_eq!(
        sites(&["sites", setup, "--json"]),
        sites(&["sites", "--setup", setup, "--json"])
    );
    let (code, stderr) = failure(&["solve", motion]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("no setup for the motion") && stderr.contains("--setup SETUP.toml"),
        "{stderr}"
    );
    let (code, stderr) = failure(&["solve", "--setup", setup, setup, motion]);
    assert_eq!(code, 2);
    assert!(stderr.contains("give the setup once"), "{stderr}");
}
