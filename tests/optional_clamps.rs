//! Optional clamps (`optional = true`): the search may leave a clamp out, and the cable then
//! runs in one piece from the previous clamp to the next. Checked on a real robot (the UR5 of
//! tests/data/robots, STL meshes) against a second computation: the best path that mounts
//! the clamp and the best path without it, each solved as its own setup (the clamp declared
//! mandatory; the clamp removed and its two segments joined into one) — the optional setup's
//! answer must be the shorter of the two, and here that is the one without the wrist clamp.

use cable_dict::motion::{Motion, WaypointFile};
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, SolveReport, Status, solve};
use std::path::PathBuf;

fn data(file: &str) -> PathBuf {
    crate::common::root().join("tests/data/ur5").join(file)
}

fn ur5_motion(setup: &Setup) -> Motion {
    let waypoints =
        WaypointFile::from_file(data("pick_and_place.toml")).unwrap_or_else(|e| panic!("{e}"));
    waypoints
        .generate(&setup.robot)
        .unwrap_or_else(|e| panic!("{e}"))
        .motion
}

fn solved(text: &str, name: &str) -> (Setup, SolveReport) {
    let setup = Setup::from_toml_str(text, &data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let motion = ur5_motion(&setup);
    let report = solve(&setup, &motion, &SolveOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        report.status,
        Status::Solved,
        "{name}: {}",
        report.explanation
    );
    (setup, report)
}

fn total_mm(report: &SolveReport) -> f64 {
    report
        .optimal
        .as_ref()
        .map(|path| path.segments.iter().map(|s| s.length_mm).sum())
        .unwrap_or(f64::NAN)
}

#[test]
fn leaving_the_wrist_clamp_out_is_shorter_and_the_search_does_it() {
    let optional_text = std::fs::read_to_string(data("optional_wrist_clamp.toml")).unwrap();
    let (setup, optional) = solved(&optional_text, "optional_wrist_clamp.toml");
    // One span from the forearm clamp to the connector besides the two declared segments.
    assert_eq!(setup.segment_count(), 3);
    assert_eq!(setup.segment_guides(2), (0, 2));
    assert_eq!(setup.segment_name(2), "C1–C2");

    // Second computation 1: the wrist clamp mandatory.
    let mandatory_text = optional_text.replace("optional = true\n", "");
    let (_, mandatory) = solved(&mandatory_text, "mandatory.toml");
    // Second computation 2: no wrist clamp at all, one segment whose window is the two
    // segments' windows added (10 + 10 … 50 + 40 sub-segments).
    let g2_start = optional_text.find("[[guides]]\nname = \"G2\"").unwrap();
    let g3_start = optional_text.find("[[guides]]\nname = \"G3\"").unwrap();
    let segments_start = optional_text.find("[[segments]]").unwrap();
    let without_text = format!(
        "{}{}[[segments]]\nfrom = \"G1\"\nto = \"G3\"\nlengths = {{ min = 20, max = 90, step = 1, allow_zero = false }}\n",
        &optional_text[..g2_start],
        &optional_text[g3_start..segments_start]
    );
    let (_, without) = solved(&without_text, "without.toml");

    let best = total_mm(&mandatory).min(total_mm(&without));
    assert!(
        total_mm(&without) < total_mm(&mandatory),
        "the fixture must make the wrist clamp a detour: {} mm without, {} mm with",
        total_mm(&without),
        total_mm(&mandatory)
    );
    assert_eq!(total_mm(&optional), best);
    let path = optional.optimal.as_ref().unwrap();
    assert_eq!(path.left_out, vec!["G2".to_string()]);
    assert_eq!(path.segments.len(), 1);
    assert_eq!(path.segments[0].name, "C1–C2");
    let skipped = without.optimal.as_ref().unwrap();
    assert_eq!(
        path.guides, skipped.guides,
        "the same clamps as the setup without G2"
    );
    let dynamics = optional.motion_test.as_ref().unwrap();
    assert!(dynamics.passed);

    // The report's pictures draw the clamps the path mounts (G1 and G3), not G2, under the
    // fitter's names of its mounting plan.
    let folder = tempfile::tempdir().unwrap();
    let dir = folder.path().join("report");
    crate::common::write_report(&dir, &setup, &ur5_motion(&setup), &optional)
        .unwrap_or_else(|e| panic!("{e}"));
    let plan = optional.mounting.as_ref().expect("a mounting plan");
    let guides: Vec<&str> = plan
        .clamps
        .iter()
        .flat_map(|c| c.guides.iter().map(String::as_str))
        .collect();
    assert_eq!(guides, ["G1", "G3"]);
    let picture = std::fs::read_to_string(dir.join("pose-1.svg")).unwrap();
    let clamps = &picture[picture.find("class=\"clamps\"").expect("clamps drawn")..];
    let clamps = &clamps[..clamps.find("</g>").expect("the group ends")];
    assert_eq!(
        clamps.matches("<circle").count(),
        plan.clamps.len(),
        "{clamps}"
    );
    for clamp in &plan.clamps {
        let label = format!(">{}<", clamp.short_name());
        assert!(clamps.contains(&label), "{label} in {clamps}");
    }
}

#[test]
fn the_first_and_last_guide_and_a_clamp_within_one_link_cannot_be_optional() {
    let text = std::fs::read_to_string(data("optional_wrist_clamp.toml")).unwrap();
    let first = text.replace(
        "link = \"forearm_link\"\n",
        "link = \"forearm_link\"\noptional = true\n",
    );
    let err = Setup::from_toml_str(&first, &data("first.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("guides[0].optional") && err.contains("first guide"),
        "{err}"
    );
    let last = text.replace("link = \"tool0\"\n", "link = \"tool0\"\noptional = true\n");
    let err = Setup::from_toml_str(&last, &data("last.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("guides[2].optional") && err.contains("last guide"),
        "{err}"
    );
    // A clamp between two clamps of one link: that is S = 0 of an intra-link segment.
    let within = text
        .replace("max_guides_per_link = 1", "max_guides_per_link = 3")
        .replace("link = \"forearm_link\"", "link = \"wrist_2_link\"")
        .replace("link = \"tool0\"", "link = \"wrist_2_link\"");
    let err = Setup::from_toml_str(&within, &data("within.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("guides[1].optional") && err.contains("allow_zero"),
        "{err}"
    );
}
