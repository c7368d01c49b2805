//! Names from inputs are shown, never obeyed. The bundled robot-level setup with a guide named
//! like an HTML script injection and a clamp named with Markdown and an ANSI escape sequence
//! is solved with `--report`: the terminal summary and `solve -v` carry no control character, `summary.md`
//! no raw HTML (rendered by a Markdown renderer that passes raw HTML through, it makes no
//! tag), `index.html` and the SVG pictures no tag from a name, and the result JSON gives the
//! names back exactly. With `$CABLE_DICT_HOSTILE_REPORT_OUT` set, the report folder is left
//! there for CI's browser check, which fails if a script from the page runs.

use crate::common;

use std::path::Path;

const INJECTION: &str = "<img src=x onerror=alert(document.title)>";
/// A clamp name with Markdown markup, a raw tag, an ANSI colour sequence and a bidi override
/// that would show the rest of a label backwards (TOML escapes).
const MARKUP_TOML: &str = r"*bold* [link](example.com) `tick` <b>raw \u001b[31mred \u202Eevil";
const MARKUP: &str = "*bold* [link](example.com) `tick` <b>raw \u{1b}[31mred \u{202e}evil";

/// The bundled setup with G1 renamed to [`INJECTION`] and G4's clamp to [`MARKUP`], its
/// relative paths made absolute, written to `dir`.
fn hostile_setup(dir: &Path) -> std::path::PathBuf {
    let root = crate::common::root();
    let text = std::fs::read_to_string(root.join("robots/viper_s850/pick_and_place.toml"))
        .expect("bundled setup");
    let robot = root.join("robots/viper_s850/viper_s850.urdf");
    let cable = root.join("cables/smc_le_cp_3.toml");
    let text = text
        .replace(
            "robot = \"viper_s850.urdf\"",
            &format!("robot = {:?}", robot.display().to_string()),
        )
        .replace(
            "cable = \"../../cables/smc_le_cp_3.toml\"",
            &format!("cable = {:?}", cable.display().to_string()),
        )
        .replace("\"G1\"", &format!("{INJECTION:?}"))
        .replace(
            "name = \"gripper connector\"",
            &format!("name = \"{MARKUP_TOML}\""),
        );
    assert!(text.contains(INJECTION) && text.contains(MARKUP_TOML));
    let path = dir.join("hostile.toml");
    std::fs::write(&path, text).expect("written");
    path
}

/// Tags a Markdown renderer that passes raw HTML through makes of `markdown` from the names'
/// markup.
fn rendered_tags(markdown: &str) -> Vec<String> {
    let mut html = String::new();
    pulldown_cmark::html::push_html(&mut html, pulldown_cmark::Parser::new(markdown));
    ["<img", "<b>", "<em>", "<code>tick", "href=\"example.com\""]
        .iter()
        .filter(|tag| html.contains(*tag))
        .map(|tag| tag.to_string())
        .collect()
}

#[test]
fn names_from_inputs_are_shown_and_never_obeyed() {
    let work = tempfile::tempdir().expect("temp dir");
    let setup = hostile_setup(work.path());
    let report = std::env::var_os("CABLE_DICT_HOSTILE_REPORT_OUT")
        .map_or_else(|| work.path().join("report"), std::path::PathBuf::from);
    let json = work.path().join("result.json");
    let output = common::run(&[
        "solve",
        "--setup",
        setup.to_str().expect("utf-8"),
        "motions/viper_s850/pick_and_place.csv",
        "--report",
        report.to_str().expect("utf-8"),
        "-o",
        json.to_str().expect("utf-8"),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");

    // The summary names clamps by number and fittings by name; the guides' names are the
    // search's, shown by `solve -v`.
    let verbose = common::run(&[
        "solve",
        "-v",
        "--no-motion-test",
        "--setup",
        setup.to_str().expect("utf-8"),
        "motions/viper_s850/pick_and_place.csv",
    ]);
    let details = String::from_utf8_lossy(&verbose.stdout);
    assert!(details.contains(INJECTION), "the name is shown: {details}");
    assert!(!details.contains('\u{1b}'), "{details}");
    assert!(!stdout.contains('\u{1b}'), "{stdout}");
    assert!(!stderr.contains('\u{1b}'), "{stderr}");
    assert!(stdout.contains("\\u{1b}[31mred"), "{stdout}");

    let summary = std::fs::read_to_string(report.join("summary.md")).expect("summary.md");
    assert!(!summary.contains(INJECTION), "{summary}");
    assert!(!summary.contains('\u{1b}'));
    assert_eq!(rendered_tags(&summary), Vec::<String>::new(), "{summary}");

    let page = std::fs::read_to_string(report.join("index.html")).expect("index.html");
    assert!(
        !page.contains("<img src=x"),
        "a tag from a name in index.html"
    );
    assert!(!page.contains("<b>raw"), "a tag from a name in index.html");
    assert!(page.contains("&lt;img src=x onerror=alert(document.title)&gt;"));
    // The 3D view's clamp labels are text on the page: what would reorder or hide it is
    // written out.
    let view = std::fs::read_to_string(report.join("view-data.js")).expect("view-data.js");
    assert!(
        !view.contains('\u{202e}') && !view.contains('\u{1b}'),
        "raw in a label"
    );
    let labels = view.rsplit("\"clamps\"").next().unwrap_or_default();
    assert!(view.contains(r"\\u{202e}evil"), "written out: {labels}");
    for entry in std::fs::read_dir(&report).expect("report folder") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "svg") {
            let svg = std::fs::read_to_string(&path).expect("svg");
            assert!(!svg.contains("<img") && !svg.contains("<b>"), "{path:?}");
            // XML forbids control characters: one from a name makes the picture unreadable.
            let control = svg
                .chars()
                .find(|&c| c.is_control() && c != '\n' && c != '\t');
            assert_eq!(control, None, "{path:?}");
        }
    }

    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("result.json"))
            .expect("valid JSON");
    let guides = &result["ecpv"]["guides"];
    assert_eq!(guides[0]["name"], INJECTION, "{guides}");
    let last = guides.as_array().and_then(|g| g.last()).expect("guides");
    assert_eq!(last["configuration"], MARKUP, "{guides}");
}
