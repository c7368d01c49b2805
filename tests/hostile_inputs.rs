//! Careless or hostile input files, end to end: each is refused with exit code 2 and a short
//! message naming the file, the place and what is wrong — no panic, no runaway memory, no
//! echo of the whole input. (The dictionary cases are in
//! `dictionary_files.rs`.)

use crate::common;

use common::run;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const SETUP: &str = "robots/viper_s850/hand_written/pick_and_place.toml";
const MOTION: &str = "motions/viper_s850/pick_and_place.csv";

/// Exit code and standard error of a run that must fail.
fn refusal(args: &[&str]) -> (i32, String) {
    code_and_stderr(run(args))
}

/// The exit code of `output` (-1 when killed) and its standard error.
fn code_and_stderr(output: std::process::Output) -> (i32, String) {
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// The bundled pick-and-place setup with its robot and cable paths made absolute and
/// `edit` applied, written into `dir`.
fn setup_with(dir: &Path, edit: impl Fn(String) -> String) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(ROOT).join(SETUP)).unwrap();
    let text = text
        .replace(
            "robot = \"../viper_s850.urdf\"",
            &format!("robot = \"{ROOT}/robots/viper_s850/viper_s850.urdf\""),
        )
        .replace(
            "cable = \"../../../cables/",
            &format!("cable = \"{ROOT}/cables/"),
        );
    let path = dir.join("setup.toml");
    std::fs::write(&path, edit(text)).unwrap();
    path
}

fn solve_refusal(setup: &Path) -> (i32, String) {
    refusal(&["solve", "--setup", setup.to_str().unwrap(), MOTION])
}

#[test]
fn a_device_as_the_robot_is_refused_before_reading_it() {
    let dir = tempfile::tempdir().unwrap();
    let setup = setup_with(dir.path(), |t| {
        t.replace(
            &format!("robot = \"{ROOT}/robots/viper_s850/viper_s850.urdf\""),
            "robot = \"/dev/zero\"",
        )
    });
    let (code, message) = solve_refusal(&setup);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("setup.toml:17: robot: /dev/zero: the URDF file is not a regular file"),
        "{message}"
    );
}

#[test]
fn a_urdf_nested_100_000_deep_is_refused_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("deep.urdf");
    let depth = 100_000;
    let text = format!(
        "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n{}{}</robot>\n",
        "<link>".repeat(depth),
        "</link>".repeat(depth)
    );
    std::fs::write(&path, text).unwrap();
    let (code, message) = refusal(&["robot-info", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("deep.urdf:3: elements nested more than 64 deep"),
        "{message}"
    );
}

#[test]
fn lengths_near_the_integer_limits_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    for max in ["9223372036854775807", "1000000000"] {
        let setup = setup_with(dir.path(), |t| {
            t.replace("max = 75", &format!("max = {max}"))
        });
        let (code, message) = solve_refusal(&setup);
        assert_eq!(code, 2, "{message}");
        assert!(
            message.contains(&format!(
                "segments[0].lengths.max: max = {max} sub-segments, more than the 10000"
            )),
            "{message}"
        );
    }
    let setup = setup_with(dir.path(), |t| {
        t.replace("range = 2 ", "range = 9223372036854775807 ")
    });
    let (code, message) = solve_refusal(&setup);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("robustness.range: range × delta_s"),
        "{message}"
    );
}

#[test]
fn a_catalogue_of_100_000_clamp_places_is_refused_with_the_count() {
    let dir = tempfile::tempdir().unwrap();
    let places: Vec<String> = (0..100_000)
        .map(|k| {
            format!(
                "  {{ name = \"c{k}\", position_mm = [{:.3}, 107.0, 330.0], rpy_deg = [153.4, -5.7, -111.3] }}",
                -65.0 - 0.001 * k as f64
            )
        })
        .collect();
    let setup = setup_with(dir.path(), |t| {
        let g2 = t.find("name = \"G2\"").unwrap();
        let start = g2 + t[g2..].find("configurations = [").unwrap();
        let end = start + t[start..].find("]\n").unwrap();
        format!(
            "{}configurations = [\n{}\n{}",
            &t[..start],
            places.join(",\n"),
            &t[end..]
        )
    });
    let (code, message) = solve_refusal(&setup);
    assert_eq!(code, 2, "{message}");
    // C2 (G2 → G3, S = 0 allowed) pairs the 100 000 places with themselves: 10¹⁰ per length.
    assert!(message.contains("setup.toml: "), "{message}");
    assert!(
        message.contains("candidate pieces (C1 21700000, C2 2200"),
        "{message}"
    );
}

#[test]
fn a_twin_place_in_a_large_catalogue_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let setup = setup_with(dir.path(), |t| {
        t.replace(
            "position_mm = [-75.0, 107.0, 340.0], rpy_deg = [153.2, -5.0, -109.8]",
            "position_mm = [-65.0, 107.0, 330.0], rpy_deg = [153.4, -5.7, -111.3]",
        )
    });
    let (code, message) = solve_refusal(&setup);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains(
            "configuration \"fork bracket x-75 y107 z340\" has the same pose as \"fork bracket \
             x-65 y107 z330\""
        ),
        "{message}"
    );
}

#[test]
fn a_motion_line_of_10_mb_is_refused_without_echoing_it() {
    let dir = tempfile::tempdir().unwrap();
    let header = "time_s,joint_1_deg,joint_2_deg,joint_3_deg,joint_4_deg,joint_5_deg,joint_6_deg";
    let cases = [
        (
            "long.csv",
            format!("{header}\n0,{}", "1".repeat(10_000_000)),
            "2 values, but the header has 7 columns".to_string(),
        ),
        (
            "fields.csv",
            format!("{header}\n0{}\n", ",1".repeat(5_000_000)),
            "more than 7 values, but the header has 7 columns".to_string(),
        ),
        (
            "number.csv",
            format!("{header}\n0,{},0,0,0,0,0\n", "9".repeat(10_000_000) + "x"),
            format!("`{}… (10000001 bytes)` is not a number", "9".repeat(40)),
        ),
    ];
    for (name, text, expected) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let (code, message) = refusal(&["critical-poses", SETUP, path.to_str().unwrap()]);
        assert_eq!(code, 2, "{name}");
        assert!(
            message.len() < 500,
            "{name}: {} bytes of message",
            message.len()
        );
        assert!(message.contains(&format!("{name}:2: ")), "{message}");
        assert!(message.contains(&expected), "{message}");
    }
}

#[test]
fn a_report_folder_holding_other_files_is_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    let precious = dir.path().join("thesis.tex");
    std::fs::write(&precious, "years of work").unwrap();
    let (code, message) = refusal(&[
        "solve",
        "--setup",
        SETUP,
        MOTION,
        "--report",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("holds `thesis.tex`, which a report does not write"),
        "{message}"
    );
    assert_eq!(std::fs::read_to_string(&precious).unwrap(), "years of work");
}

#[test]
fn a_collision_mesh_the_tool_does_not_read_is_refused_naming_link_file_and_stl() {
    let dir = tempfile::tempdir().unwrap();
    let meshes = dir.path().join("meshes");
    std::fs::create_dir(&meshes).unwrap();
    let collada = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<COLLADA \
                   xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n\
                   </COLLADA>\n";
    std::fs::write(meshes.join("arm.dae"), collada).unwrap();
    std::fs::write(meshes.join("arm"), "no extension").unwrap();
    // COLLADA under an STL name.
    std::fs::write(meshes.join("arm.stl"), collada).unwrap();
    let cases: [(&str, &[&str]); 4] = [
        (
            "meshes/arm.dae",
            &["is a COLLADA (.dae) file", "only STL meshes are supported"],
        ),
        (
            "meshes/arm",
            &["has no file extension", "only STL meshes are supported"],
        ),
        (
            "meshes/missing.obj",
            &["Wavefront OBJ", "does not exist", "STL"],
        ),
        (
            "meshes/arm.stl",
            &[
                "is not a readable STL file",
                "COLLADA",
                "binary or ASCII STL",
            ],
        ),
    ];
    for (filename, expected) in cases {
        let urdf = dir.path().join("robot.urdf");
        let text = format!(
            "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\">\n    \
             <collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>\n    \
             <collision><geometry><mesh filename=\"{filename}\"/></geometry></collision>\n  \
             </link>\n  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/>\
             <child link=\"arm\"/><axis xyz=\"0 0 1\"/>\
             <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n</robot>\n"
        );
        std::fs::write(&urdf, text).unwrap();
        let (code, message) = refusal(&["robot-info", urdf.to_str().unwrap()]);
        assert_eq!(code, 2, "{filename}: {message}");
        let place = format!(
            "{}:3: <link name=\"arm\">: <collision> #2: mesh '{filename}'",
            urdf.display()
        );
        assert!(message.contains(&place), "{filename}: {message}");
        if !filename.contains("missing") {
            // The file the URI resolves to.
            let resolved = dir.path().join(filename);
            assert!(
                message.contains(&resolved.display().to_string()),
                "{filename}: {message}"
            );
        }
        for expected in expected {
            assert!(
                message.contains(expected),
                "{filename}: {expected}: {message}"
            );
        }
    }
}

/// Site generators each within their own limits but together far beyond a catalogue's
/// memory (the 4 KB setup: 2–3 mm spacing, 36 directions on every generated guide)
/// are refused before any site is made, with the estimated total, the limit and the largest
/// generators — by `critical-poses` as by `solve`, at once.
#[test]
fn site_generators_too_many_together_are_refused_before_any_runs() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text =
        std::fs::read_to_string(Path::new(ROOT).join("robots/viper_s850/pick_and_place.toml"))
            .expect("bundled setup");
    let directions: Vec<String> = (0..36).map(|k| format!("{}.0", k * 10)).collect();
    let text = text
        .replace(
            "robot = \"viper_s850.urdf\"",
            &format!("robot = \"{ROOT}/robots/viper_s850/viper_s850.urdf\""),
        )
        .replace(
            "cable = \"../../cables/",
            &format!("cable = \"{ROOT}/cables/"),
        )
        .replace(
            "spacing_mm = 80.0, clamp_height_mm = 8.0, directions_deg = [0.0, 90.0, 180.0, 270.0]",
            &format!(
                "spacing_mm = 3.0, clamp_height_mm = 8.0, directions_deg = [{}]",
                directions.join(", ")
            ),
        );
    assert_eq!(text.matches("spacing_mm = 3.0").count(), 3);
    let setup = dir.path().join("setup.toml");
    std::fs::write(&setup, &text).expect("written");
    let setup = setup.to_str().expect("utf-8");
    for args in [
        vec!["critical-poses", setup, MOTION],
        vec!["solve", "--setup", setup, MOTION],
    ] {
        let (code, stderr) = refusal(&args);
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains("setup.toml:"), "{stderr}");
        assert!(stderr.contains("clamp configurations together"), "{stderr}");
        assert!(stderr.contains("at most 1000000"), "{stderr}");
        assert!(stderr.contains("guides[1] on link_4"), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
}

/// A few bytes that would buy hours: a motion whose second row is an hour after its first
/// (every chain's motion test integrates the whole motion: 91 CPU-s before the limit), and a
/// waypoint file whose dwell of a day would be sampled into a motion file of gigabytes. Each
/// is refused at once with exit code 2, naming the file and the limit, in an address space
/// of 4 GB.
#[test]
fn a_motion_an_hour_long_or_a_dwell_of_a_day_is_refused_naming_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let bounded = |args: &[&str]| code_and_stderr(bounded(args));
    let csv = dir.path().join("hour.csv");
    std::fs::write(
        &csv,
        "time_s,joint_1_deg,joint_2_deg,joint_3_deg,joint_4_deg,joint_5_deg,joint_6_deg\n\
         0,0,-60,210,0,20,0\n3600,10,-60,210,0,20,0\n",
    )
    .unwrap();
    let (code, message) = bounded(&["solve", "--setup", SETUP, csv.to_str().unwrap()]);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("hour.csv") && message.contains("1800 s"),
        "{message}"
    );

    let waypoints =
        std::fs::read_to_string(Path::new(ROOT).join("motions/viper_s850/pick_and_place.toml"))
            .unwrap()
            .replace(
                "robot = \"../../robots/",
                &format!("robot = \"{ROOT}/robots/"),
            )
            .replacen("dwell_s = 0.2", "dwell_s = 86400.0", 1);
    let toml = dir.path().join("day.toml");
    std::fs::write(&toml, waypoints).unwrap();
    let out = dir.path().join("day.csv");
    let (code, message) = bounded(&[
        "motion",
        toml.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{message}");
    assert!(
        message.contains("day.toml") && message.contains("1800 s"),
        "{message}"
    );
    assert!(!out.exists(), "nothing written");
}

/// The binary run with `args` from the package root in an address space of 4 GB: what a
/// small hostile file may make it allocate.
fn bounded(args: &[&str]) -> std::process::Output {
    std::process::Command::new("bash")
        .arg("-c")
        .arg("ulimit -v 4000000 && exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_cable-dict"))
        .args(args)
        .current_dir(ROOT)
        .output()
        .unwrap()
}

/// `sites` is what `solve`'s refusal sends a user to, so it must count what `solve`
/// refuses without making it: the bundled robot-level setup at 20 mm spacing (127 million
/// candidate pieces; listing them for the cost estimate took 117 CPU-s and 6.15 GB) is
/// listed with its counts per segment and the same refusal as `solve`'s, in 4 GB of address
/// space — no estimate is timed for a setup no solve would take.
#[test]
fn sites_counts_a_setup_too_large_to_solve_without_making_its_pieces() {
    let dir = tempfile::tempdir().unwrap();
    let text = common::bundled_setup_text().replace("spacing_mm = 80.0", "spacing_mm = 20.0");
    let setup = dir.path().join("fine.toml");
    std::fs::write(&setup, text).unwrap();
    let output = bounded(&["sites", setup.to_str().unwrap()]);
    let listing = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        listing.contains("too many for solve and build: 126861480 candidate pieces"),
        "{listing}"
    );
    assert!(!listing.contains("CPU-s"), "no estimate: {listing}");
    let (code, message) = solve_refusal(&setup);
    assert_eq!(code, 2);
    assert!(message.contains("126861480 candidate pieces"), "{message}");
}
