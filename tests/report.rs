//! `solve --report` and `export-scene` end to end: the folder holds every file, the page
//! needs nothing outside it, the result file is what `--json` prints, the summary's hashes
//! are the input files' own, the scene has the path's cable, the critical poses and the
//! motion test's frames, and the pictures show robot and cable in every view.

use crate::common;
use crate::svg_pictures;

use base64::Engine as _;
use common::run;
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::Path;
use std::process::Output;

const MOTION: &str = "motions/viper_s850/pick_and_place.csv";
const SMALL: &str = "tests/data/small_setup.toml";

/// Every attribute value of `name` in `html` (`src="…"` and `href="…"`).
fn attribute_values<'a>(html: &'a str, name: &str) -> Vec<&'a str> {
    let marker = format!("{name}=\"");
    html.match_indices(&marker)
        .filter_map(|(i, _)| {
            let rest = &html[i + marker.len()..];
            rest.find('"').map(|end| &rest[..end])
        })
        .collect()
}

/// The scene's document, parsed and validated by the gltf crate's importer.
fn scene(path: &Path) -> gltf::Gltf {
    let bytes = std::fs::read(path).expect("scene file");
    gltf::Gltf::from_slice(&bytes).expect("a valid glTF binary")
}

/// Names of the scene's nodes that start with `prefix`.
fn nodes_named(scene: &gltf::Gltf, prefix: &str) -> Vec<String> {
    scene
        .nodes()
        .filter_map(|n| n.name().map(str::to_string))
        .filter(|name| name.starts_with(prefix))
        .collect()
}

/// Distinct motion samples of the inter-link segments' critical poses in a result JSON.
fn critical_samples(result: &Value) -> BTreeSet<u64> {
    result["sets"]
        .as_array()
        .expect("sets")
        .iter()
        .filter(|s| s["kind"] == "inter-link")
        .flat_map(|s| s["test_poses"].as_array().expect("poses").iter())
        .map(|p| p["sample"].as_u64().expect("sample"))
        .collect()
}

/// The small setup's solve with a budget of one motion test fails its only candidate (a
/// 0.03 mm contact mid-motion): the report shows it, where it fails.
#[test]
fn a_report_folder_holds_every_file_and_the_page_needs_nothing_else() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let report = dir.path().join("out");
    let report_arg = report.to_str().expect("utf-8");
    let output = run(&[
        "solve", "--setup", SMALL, MOTION, "--json", "--report", report_arg, "--k-best", "1",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );

    let files: BTreeSet<String> = std::fs::read_dir(&report)
        .expect("report folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    // result.json is what --json printed.
    let written = std::fs::read(report.join("result.json")).expect("result.json");
    assert_eq!(written, output.stdout);
    let result: Value = serde_json::from_slice(&written).expect("JSON");
    assert_eq!(result["status"], "unsolved");

    // One picture per critical pose and one where the motion test failed.
    let mut pictures: Vec<String> = (1..=critical_samples(&result).len())
        .map(|k| format!("pose-{k}.svg"))
        .collect();
    pictures.push("worst-moment.svg".into());
    // No installation sheet: nothing passed. The 3D view's files are there.
    let mut expected: BTreeSet<String> = [
        "index.html",
        "joints.svg",
        "model-viewer-licenses.txt",
        "model-viewer.min.js",
        "result.json",
        "scene.glb",
        "sets.svg",
        "stress.svg",
        "summary.md",
        "view-data.js",
        "view.js",
    ]
    .iter()
    .map(|f| f.to_string())
    .collect();
    expected.extend(pictures.iter().cloned());
    assert_eq!(files, expected);

    // The page refers only to files of the folder, and to each plot.
    let html = std::fs::read_to_string(report.join("index.html")).expect("index.html");
    let references: Vec<&str> = ["src", "href"]
        .iter()
        .flat_map(|a| attribute_values(&html, a))
        .collect();
    assert!(!references.is_empty());
    for reference in &references {
        assert!(
            !reference.contains('/') && !reference.contains(':') && files.contains(*reference),
            "index.html refers to {reference}, which is not a file of the folder"
        );
    }
    for plot in ["joints.svg", "stress.svg", "sets.svg"]
        .into_iter()
        .chain(pictures.iter().map(String::as_str))
    {
        assert!(
            references.contains(&plot),
            "index.html does not show {plot}"
        );
    }
    check_pictures(&report, &pictures, &html);
    // The only scripts are the view's own files, in this order; nothing is fetched.
    let scripts: Vec<&str> = html
        .match_indices("<script")
        .map(|(i, _)| &html[i..])
        .collect();
    let sources = ["model-viewer.min.js", "view-data.js", "view.js"];
    assert_eq!(scripts.len(), sources.len(), "{html}");
    for (script, source) in scripts.iter().zip(sources) {
        assert!(script.starts_with(&format!("<script src=\"{source}\"></script>")));
    }
    for outside in ["http", "@import", "url("] {
        assert!(!html.contains(outside), "index.html contains {outside}");
    }

    // The summary names the inputs with the hashes of the files' bytes.
    let summary = std::fs::read_to_string(report.join("summary.md")).expect("summary.md");
    for file in [
        SMALL,
        "robots/viper_s850/viper_s850.urdf",
        "cables/smc_le_cp_3_paper.toml",
        MOTION,
    ] {
        let bytes = std::fs::read(file).expect("input file");
        let hash = format!("{:016x}", xxhash_rust::xxh3::xxh3_64(&bytes));
        assert!(
            summary.contains(&hash),
            "summary.md lacks the hash of {file}"
        );
    }
    assert!(summary.contains("unsolved"));

    // The failed candidate's motion test: where it fails, on the plot.
    let last = result["candidates"]
        .as_array()
        .expect("candidates")
        .last()
        .cloned();
    let failure = last.and_then(|c| c["failure"].as_str().map(str::to_string));
    let failure = failure.expect("the last candidate failed");
    let stress = std::fs::read_to_string(report.join("stress.svg")).expect("stress.svg");
    assert!(
        stress.contains("FAILED"),
        "stress.svg does not say it failed"
    );
    let t_fail = failure
        .split("t = ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .expect("failure time");
    assert!(
        stress.contains(t_fail),
        "stress.svg lacks the failure time {t_fail}"
    );

    // The scene: one snapshot per critical pose, the candidate's cable, an animation of its
    // motion test up to the failure.
    let glb = scene(&report.join("scene.glb"));
    assert_eq!(
        nodes_named(&glb, "critical pose ").len(),
        critical_samples(&result).len()
    );
    assert!(!nodes_named(&glb, "C1 sub-segment").is_empty());
    assert_eq!(glb.animations().count(), 1);
}

/// Each picture is well-formed XML showing, in each of the three views, the robot (filled
/// outlines), the cable (the candidate's one piece) and its two clamps; the page
/// says that the candidate drawn failed the motion test, and where.
fn check_pictures(report: &Path, pictures: &[String], html: &str) {
    for file in pictures {
        let svg = std::fs::read_to_string(report.join(file)).expect("picture");
        let elements = svg_pictures::elements(&svg);
        for view in svg_pictures::VIEWS {
            let count = |name: &str, group: &str| {
                elements.iter().filter(|e| e.is(name, view, group)).count()
            };
            assert!(count("polygon", "robot") >= 5, "{file} {view}: no robot");
            assert_eq!(count("polyline", "cable"), 1, "{file} {view}: not 1 piece");
            assert_eq!(count("circle", "clamps"), 2, "{file} {view}: not 2 clamps");
        }
        // Not degenerate: outlines have an area, the cable runs through its nodes.
        for e in &elements {
            let corners = svg_pictures::points(e.attribute("points")).len();
            match (e.name.as_str(), e.group.as_deref()) {
                ("polygon", Some("robot")) => assert!(corners >= 3, "{file}: {e:?}"),
                ("polyline", Some("cable")) => assert!(corners >= 10, "{file}: {e:?}"),
                _ => {}
            }
        }
    }
    assert!(html.contains("failed the motion test: this is the nearest miss"));
    assert!(html.contains("The motion test failed at t = "));
}

/// `export-scene path` draws the candidate of a result file at a pose and says whether each
/// segment holds the limits there; wrong input is refused with exit code 2.
#[test]
fn export_scene_draws_a_candidate_at_a_pose() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let result = dir.path().join("result.json");
    let solved = run(&[
        "solve",
        "--setup",
        SMALL,
        MOTION,
        "--no-motion-test",
        "-o",
        result.to_str().expect("utf-8"),
    ]);
    assert!(solved.status.success());
    let json: Value =
        serde_json::from_slice(&std::fs::read(&result).expect("result")).expect("JSON");
    let sub_segments = json["ecpv"]["segments"][0]["sub_segments"]
        .as_u64()
        .expect("S");

    let glb = dir.path().join("candidate.glb");
    let (result_arg, glb_arg) = (
        result.to_str().expect("utf-8"),
        glb.to_str().expect("utf-8"),
    );
    // `export-scene path` of the candidate in `result_file`, with `rest` (the pose, a rank).
    let export = |result_file: &str, rest: &[&str]| {
        let mut args = vec![
            "export-scene",
            "path",
            "--setup",
            SMALL,
            "--result",
            result_file,
        ];
        args.extend_from_slice(rest);
        args.extend(["-o", glb_arg]);
        run(&args)
    };
    let exported = export(result_arg, &["--motion", MOTION, "--time-s", "0"]);
    let stdout = String::from_utf8_lossy(&exported.stdout);
    assert!(
        exported.status.success(),
        "{}",
        String::from_utf8_lossy(&exported.stderr)
    );
    // d̂ is robust at the first pose (an intra-link test pose of every segment); the first
    // line says the motion test did not judge it.
    assert!(
        stdout.starts_with("candidate 1 (")
            && stdout
                .lines()
                .next()
                .is_some_and(|l| l.ends_with("was not motion-tested"))
            && stdout.contains("\nC1 ")
            && stdout.contains("holds the limits at this pose"),
        "{stdout}"
    );
    let scene = scene(&glb);
    assert_eq!(
        nodes_named(&scene, "C1 sub-segment").len() as u64,
        sub_segments
    );
    assert_eq!(scene.animations().count(), 0);

    // A candidate the motion test failed says so first, with the failure, whatever the
    // static check at this pose finds.
    let mut failed = json.clone();
    failed["candidates"][0]["passed"] = Value::Bool(false);
    failed["candidates"][0]["failure"] = Value::from("contact at t = 1.20 s, segment C1");
    let failed_file = dir.path().join("failed.json");
    std::fs::write(&failed_file, failed.to_string()).expect("written");
    let failed_arg = failed_file.to_str().expect("utf-8");
    let exported = export(failed_arg, &["--joints-deg", "0,0,0,0,0,0"]);
    let stdout = String::from_utf8_lossy(&exported.stdout);
    assert!(
        stdout.lines().next().is_some_and(
            |l| l.ends_with("FAILED the motion test: contact at t = 1.20 s, segment C1")
        ),
        "{stdout}"
    );

    for (args, message) in [
        (
            vec!["--candidate", "7", "--joints-deg", "0,0,0,0,0,0"],
            "no candidate of rank 7",
        ),
        (vec!["--joints-deg", "0,0"], "joint"),
    ] {
        let refused = export(result_arg, &args);
        let stderr = String::from_utf8_lossy(&refused.stderr);
        assert_eq!(refused.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}

/// `export-scene segment` writes the shape `segment` computes: one tube piece per
/// sub-segment, the two guides.
#[test]
fn export_scene_draws_a_segment() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let glb = dir.path().join("segment.glb");
    let output = run(&[
        "export-scene",
        "segment",
        "--cable",
        "cables/smc_le_cp_3_paper.toml",
        "--length-mm",
        "400",
        "--start",
        "0,0,0,0,90,0",
        "--end",
        "250,0,-150,0,150,0",
        "-o",
        glb.to_str().expect("utf-8"),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let scene = scene(&glb);
    assert_eq!(nodes_named(&scene, "segment sub-segment").len(), 40);
    assert_eq!(nodes_named(&scene, "start guide").len(), 1);
    assert_eq!(nodes_named(&scene, "end guide").len(), 1);
}

/// A report folder that cannot be made is a bad argument: exit code 2, the path named.
#[test]
fn an_unwritable_report_folder_is_refused() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, "not a folder").expect("written");
    let inside = blocker.join("report");
    let output = run(&[
        "solve",
        "--setup",
        SMALL,
        MOTION,
        "--no-motion-test",
        "--report",
        inside.to_str().expect("utf-8"),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("report"), "{stderr}");
}

const ROBOT_LEVEL: &str = "robots/viper_s850/pick_and_place.toml";

/// The robot-level setup's report of `motion`, in a temporary folder (kept as long as the
/// first value lives), with the command's output.
fn robot_level_report(motion: &str) -> (tempfile::TempDir, std::path::PathBuf, Output) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let report = dir.path().join("out");
    let output = run(&[
        "solve",
        "--setup",
        ROBOT_LEVEL,
        motion,
        "--report",
        report.to_str().expect("utf-8"),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    (dir, report, output)
}

/// The bundled pick-and-place answer's C2 has no length (G2 and G3 are one clamp): the
/// summary lists one clamp for both and no 0 mm piece, the JSON's mounting plan joins them,
/// and the pictures do not call the piece one without a static shape (it read as a failure).
#[test]
fn a_piece_of_no_length_is_said_to_join_its_clamps() {
    let (_dir, report, output) = robot_level_report(MOTION);
    let result: Value =
        serde_json::from_slice(&std::fs::read(report.join("result.json")).expect("result"))
            .expect("JSON");
    let clamps = result["mounting"]["clamps"].as_array().expect("clamps");
    let joined = clamps
        .iter()
        .find(|c| c["guides"] == serde_json::json!(["G2", "G3"]))
        .expect("G2 and G3 are one clamp");
    assert_eq!(joined["joined_by"], serde_json::json!(["C2"]));
    let name = format!("clamp {}", joined["number"]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let listed = stdout
        .lines()
        .filter(|line| {
            line.trim_start().starts_with(&format!("{name} ")) && line.contains(" mark ")
        })
        .count();
    assert_eq!(listed, 1, "{stdout}");
    assert!(
        !stdout
            .lines()
            .any(|line| line.contains('→') && line.contains(" 0 mm")),
        "{stdout}"
    );
    let html = std::fs::read_to_string(report.join("index.html")).expect("index.html");
    assert!(!html.contains("No static shape found"), "{html}");
}

/// The rows of `install.html`'s clamp table: (name, link, mark) of each.
fn sheet_rows(html: &str) -> Vec<(String, String, f64)> {
    let table = &html[html
        .find("<table class=\"clamps\">")
        .expect("the clamp table")..];
    let table = &table[..table.find("</table>").expect("its end")];
    table
        .split("<tr><td>")
        .skip(1)
        .map(|row| {
            let name = row
                .split_once("<span class=\"name\">")
                .and_then(|(_, rest)| rest.split_once("</span>"))
                .expect("a name")
                .0;
            let cells: Vec<&str> = row
                .split("</td><td")
                .map(|cell| cell.split_once('>').map_or(cell, |(_, text)| text))
                .collect();
            let mark = cells[2].parse().expect("a mark in mm");
            (name.to_string(), cells[1].to_string(), mark)
        })
        .collect()
}

/// The boxes of the clamp labels of every view panel of an SVG picture (`data-box`: x, y,
/// width, height in the panel's units) with the panel's view box.
fn label_boxes(svg: &str) -> Vec<([f64; 4], Vec<[f64; 4]>)> {
    let numbers = |text: &str| -> [f64; 4] {
        let v: Vec<f64> = text
            .split_whitespace()
            .map(|n| n.parse().expect("a number"))
            .collect();
        [v[0], v[1], v[2], v[3]]
    };
    svg.split("<svg class=\"view ")
        .skip(1)
        .map(|panel| {
            let view_box = panel
                .split_once("viewBox=\"")
                .and_then(|(_, rest)| rest.split_once('"'))
                .expect("a view box")
                .0;
            let clamps = panel
                .split_once("class=\"clamps\"")
                .map_or("", |(_, rest)| {
                    rest.split_once("</g>").map_or(rest, |(group, _)| group)
                });
            let boxes = clamps
                .split("data-box=\"")
                .skip(1)
                .map(|rest| numbers(rest.split_once('"').expect("closed").0))
                .collect();
            (numbers(view_box), boxes)
        })
        .collect()
}

/// The installation sheet of a bundled answer against its result JSON: one row per physical
/// clamp (guides joined by a 0 mm piece are one), on the JSON's link, at the mark the JSON's
/// piece lengths give summed from the tool end; the picture carries every label and mark.
/// The 3D view labels the same clamps, at the world positions the robot's kinematics give
/// for the motion's first pose and for the installation pose (in glTF's y-up frame), and the
/// piece the motion test found within one cable diameter of the robot wears the tight colour.
#[test]
fn the_installation_sheet_and_the_view_agree_with_the_result() {
    let motion_file = "motions/viper_s850/machine_tending.csv";
    let (_dir, report, _) = robot_level_report(motion_file);
    let result: Value =
        serde_json::from_slice(&std::fs::read(report.join("result.json")).expect("result"))
            .expect("JSON");
    assert_eq!(result["status"], "solved");
    let pieces = result["ecpv"]["segments"].as_array().expect("pieces");
    let guides = result["ecpv"]["guides"].as_array().expect("guides");
    // (guides, link, mark) from the JSON alone.
    let total: f64 = pieces
        .iter()
        .map(|p| p["length_mm"].as_f64().expect("mm"))
        .sum();
    // (guides, the fitter's name, link, mark) from the JSON's path and the setup alone: a
    // fixed guide is a fitting named as the setup names it, the others are numbered.
    let setup = cable_dict::setup::Setup::from_file(ROBOT_LEVEL).expect("setup");
    let mut expected: Vec<(Vec<String>, String, String, f64)> = Vec::new();
    let mut from_start = 0.0;
    for (i, guide) in guides.iter().enumerate() {
        let name = guide["name"].as_str().expect("name").to_string();
        let before = i
            .checked_sub(1)
            .map(|p| pieces[p]["length_mm"].as_f64().expect("mm"));
        from_start += before.unwrap_or(0.0);
        let link = guide["link"].as_str().expect("link").to_string();
        let fitting = setup
            .guides
            .iter()
            .find(|g| g.name == name && g.fixed)
            .map(|g| g.configurations[0].name.clone());
        if before == Some(0.0) {
            let last = expected.last_mut().expect("a clamp");
            last.0.push(name);
            if let Some(fitting) = fitting {
                (last.1, last.2) = (fitting, link);
            }
        } else {
            expected.push((
                vec![name],
                fitting.unwrap_or_default(),
                link,
                total - from_start,
            ));
        }
    }
    let mut number = 0;
    for clamp in &mut expected {
        if clamp.1.is_empty() {
            number += 1;
            clamp.1 = format!("clamp {number}");
        }
    }
    let html = std::fs::read_to_string(report.join("install.html")).expect("install.html");
    let rows = sheet_rows(&html);
    assert_eq!(rows.len(), expected.len(), "{html}");
    let svg = std::fs::read_to_string(report.join("install.svg")).expect("install.svg");
    for ((name, link, mark), (_, json_name, json_link, json_mark)) in rows.iter().zip(&expected) {
        assert_eq!(name, json_name);
        assert_eq!(link, json_link);
        assert!(
            (mark - json_mark.round()).abs() < 0.5,
            "{name}: {mark} against {json_mark}"
        );
        assert!(
            svg.contains(&format!(">{mark:.0} mm<")) && svg.contains(&format!(">{name}<")),
            "{name}: no mark in the strip"
        );
    }
    // The title block ties the sheet to the job: the setup's hash as the result gives it.
    let hash = result["inputs"]["setup_hash"].as_str().expect("hash");
    assert!(html.contains(&format!("<td>{hash}</td>")), "{html}");
    // Each clamp's largest force and each piece's largest twist, as the JSON gives them.
    for load in result["motion_test"]["clamp_loads"]
        .as_array()
        .expect("loads")
    {
        let force = load["max_force_n"].as_f64().expect("force");
        assert!(
            html.contains(&format!("{force:.2} N (t = ")),
            "{force} in {html}"
        );
    }
    for twist in result["motion_test"]["twists"].as_array().expect("twists") {
        let degrees = twist["twist_deg"].as_f64().expect("twist");
        let per_m = twist["twist_deg_per_m"].as_f64().expect("twist");
        let said = format!("largest twist {}° ({}°/m)", degrees.round(), per_m.round());
        assert!(
            html.contains(&said.replace("-0°", "0°")),
            "{said} in {html}"
        );
    }
    // Every picture's clamp labels: inside their panel, no two overlapping.
    for entry in std::fs::read_dir(&report).expect("report") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "svg") {
            continue;
        }
        let svg = std::fs::read_to_string(&path).expect("svg");
        for ([vx, vy, vw, vh], boxes) in label_boxes(&svg) {
            for (i, [x, y, w, h]) in boxes.iter().enumerate() {
                let inside = *x >= vx - 0.05
                    && *y >= vy - 0.05
                    && x + w <= vx + vw + 0.05
                    && y + h <= vy + vh + 0.05;
                assert!(inside, "{path:?}: label {i} leaves its panel");
                for [a, b, c, d] in &boxes[i + 1..] {
                    let apart = x + w <= a + 0.05
                        || a + c <= x + 0.05
                        || y + h <= b + 0.05
                        || b + d <= y + 0.05;
                    assert!(apart, "{path:?}: labels overlap");
                }
            }
        }
    }

    // The view's labels: the same clamps, at their places at the motion's first pose.
    let view = view_data(&report);
    // The piece that came within one cable diameter (8 mm) of the robot is drawn as tight.
    let worst = &result["motion_test"]["worst_clearance"];
    let clearance = worst["value"].as_f64().expect("clearance");
    assert!(
        (0.0..0.008).contains(&clearance),
        "{clearance}: not a tight case"
    );
    let glb = base64::engine::general_purpose::STANDARD
        .decode(view["glb_base64"].as_str().expect("scene"))
        .expect("base64");
    let line = worst["segment_name"].as_str().expect("piece");
    let scene = gltf::Gltf::from_slice(&glb).expect("the view's scene");
    let tight = scene
        .nodes()
        .find(|n| n.name() == Some(&format!("{line} sub-segment 0")))
        .and_then(|n| n.mesh())
        .and_then(|m| m.primitives().next())
        .and_then(|p| p.material().name().map(str::to_string));
    assert_eq!(tight.as_deref(), Some("cable, tight margin"));
    let clamps = view["clamps"].as_array().expect("clamps");
    assert_eq!(clamps.len(), rows.len());
    let motion =
        cable_dict::motion::Motion::from_csv_file(&setup.robot, motion_file).expect("motion");
    let poses = setup.robot.link_poses(&motion.samples()[0]).expect("poses");
    // The one motion's clip: per clamp, its positions over the keyframes.
    let tracks = view["clips"][0]["positions_m"].as_array().expect("tracks");
    assert_eq!(view["clips"].as_array().map(Vec::len), Some(1));
    assert_eq!(tracks.len(), clamps.len());
    for ((clamp, track), ((label, _, _), (names, _, _, _))) in
        clamps.iter().zip(tracks).zip(rows.iter().zip(&expected))
    {
        assert_eq!(clamp["label"].as_str(), Some(label.as_str()));
        let first = names[0].as_str();
        let guide = setup
            .guides
            .iter()
            .find(|g| g.name == first)
            .expect("guide");
        let placement = guides
            .iter()
            .find(|g| g["name"] == first)
            .expect("placement")["configuration"]
            .clone();
        let configuration = guide
            .configurations
            .iter()
            .find(|c| c.name == placement)
            .expect("configuration");
        let installed = &setup
            .installation
            .as_ref()
            .expect("installation")
            .link_poses;
        for (poses, shown) in [(&poses, &track[0]), (installed, &clamp["installation_m"])] {
            let world = poses[guide.link] * configuration.pose * nalgebra::Point3::origin();
            for (axis, value) in [world.x, world.z, -world.y].into_iter().enumerate() {
                assert!(
                    (shown[axis].as_f64().expect("coordinate") - value).abs() < 1e-9,
                    "{label}"
                );
            }
        }
    }
}

/// The 3D view's data a report folder holds (`view-data.js`, its one assignment).
fn view_data(report: &Path) -> Value {
    let data = std::fs::read_to_string(report.join("view-data.js")).expect("view-data.js");
    let json = data
        .split_once("window.cableDictView = ")
        .and_then(|(_, rest)| rest.trim_end().strip_suffix(';'))
        .expect("the data assignment");
    serde_json::from_str(json).expect("view data JSON")
}

/// The 3D view of the bundled dress pack labels the retraction's outlet and the sliding ring
/// after the clamps, by the names the answer gives them, at their places at the installation
/// pose (the setup's fixed placements carried by the robot's forward kinematics).
#[test]
fn the_view_labels_the_guides_the_cable_slides_through() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let report = dir.path().join("report");
    let output = run(&[
        "solve",
        "--setup",
        "robots/viper_s850/dress_pack.toml",
        MOTION,
        "--report",
        report.to_str().expect("a UTF-8 path"),
        "--quiet",
    ]);
    assert!(output.status.success(), "{output:?}");
    let view = view_data(&report);
    let labels: Vec<&str> = (view["clamps"].as_array().expect("clamps").iter())
        .map(|c| c["label"].as_str().expect("label"))
        .collect();
    assert_eq!(
        labels[labels.len() - 2..],
        ["retraction outlet R", "sliding guide S"],
        "{labels:?}"
    );
    let setup = cable_dict::setup::Setup::from_file("robots/viper_s850/dress_pack.toml")
        .expect("the dress pack");
    let installed = &setup
        .installation
        .as_ref()
        .expect("installation")
        .link_poses;
    let clamps = view["clamps"].as_array().expect("clamps");
    for (name, clamp) in ["R", "S"].iter().zip(&clamps[clamps.len() - 2..]) {
        let g = (setup.guides.iter())
            .position(|g| g.name == *name)
            .expect("guide");
        let world = setup.guide_world_pose(installed, g, 0) * nalgebra::Point3::origin();
        let shown = clamp["installation_m"].as_array().expect("installed place");
        for (axis, value) in [world.x, world.z, -world.y].into_iter().enumerate() {
            assert!(
                (shown[axis].as_f64().expect("coordinate") - value).abs() < 1e-9,
                "{name}"
            );
        }
    }
}
