//! Helpers the test modules share: the package root, the binary runner, the bundled setup and
//! the limits of the small setups written inline.

pub mod spindle;

use std::path::Path;
use std::process::{Command, Output};

/// Runs the binary with `args` from the package root (where the bundled files' relative paths
/// start).
pub fn run(args: &[&str]) -> Output {
    run_in(root(), args)
}

/// The text of the bundled robot-level setup `robots/viper_s850/pick_and_place.toml` with its
/// robot and cable paths made absolute, so that it loads from any folder a test writes it to.
pub fn bundled_setup_text() -> String {
    viper_setup_text("pick_and_place.toml")
}

/// [`bundled_setup_text`] of the bundled Viper setup `file` (in `robots/viper_s850/`).
pub fn viper_setup_text(file: &str) -> String {
    let root = root();
    std::fs::read_to_string(root.join("robots/viper_s850").join(file))
        .expect("the bundled setup")
        .replace(
            "robot = \"viper_s850.urdf\"",
            &format!(
                "robot = {:?}",
                root.join("robots/viper_s850/viper_s850.urdf")
            ),
        )
        .replace(
            "cable = \"../../cables/smc_le_cp_3.toml\"",
            &format!("cable = {:?}", root.join("cables/smc_le_cp_3.toml")),
        )
}

/// The bundled pick-and-place setup ([`bundled_setup_text`]) with length errors of ±10 mm
/// (robustness R = 1 instead of 2), and with the makers' rule for its cable when `rule`
/// (tests/data/datasheet: fixed 5 × d, flexing 10 × d, ±360°/m, a rated life). Under the
/// rule with the bundled ±20 mm every chain has a piece whose 20 mm longer or shorter
/// neighbour flexes below 80 mm, and the motion has no path.
pub fn ten_mm_setup_text(rule: bool) -> String {
    let root = root();
    let text = bundled_setup_text().replacen("range = 2 ", "range = 1 ", 1);
    assert!(
        text.contains("range = 1 "),
        "the bundled setup's robustness range"
    );
    match rule {
        false => text,
        true => text.replace(
            &format!("cable = {:?}", root.join("cables/smc_le_cp_3.toml")),
            &format!(
                "cable = {:?}",
                root.join("tests/data/datasheet/smc_le_cp_3_maker_rule.toml")
            ),
        ),
    }
}

/// The package root, where the bundled files' relative paths start.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs the binary with `args` in the folder `dir`.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    binary()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// The binary as a command still to be given its arguments and folder.
pub fn binary() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cable-dict"))
}

/// The thresholds and robustness tables of the small setups the tests write inline: touching
/// allowed down to 0 mm, 2 % stretch, the bend radius `min_bend` (a TOML value: `"\"cable\""`
/// for the cable file's, or millimetres), a 20 mm clamp zone, the robustness window δs 1,
/// range 2.
pub fn limits(min_bend: &str) -> String {
    format!(
        r#"[thresholds]
contact_clearance_mm = 0.0
stretch = 1.02
min_bend_radius_mm = {min_bend}
clamp_zone_mm = 20.0

[robustness]
delta_s = 1
range = 2
"#
    )
}

/// Writes the report folder `dir` of `report` as `solve --report` does: the shapes solved
/// for it, then the folder.
pub fn write_report(
    dir: &Path,
    setup: &cable_dict::setup::Setup,
    motion: &cable_dict::motion::Motion,
    report: &cable_dict::solve::SolveReport,
) -> Result<Vec<std::path::PathBuf>, String> {
    let shapes =
        cable_dict::solve::ReportShapes::of(setup, &[motion], report).map_err(|e| e.to_string())?;
    cable_dict::report::write_report(dir, setup, &[motion], report, &shapes)
        .map_err(|e| e.to_string())
}

/// The dictionary `cable-dict build` makes of the setup at `path` (from the package root)
/// with `directions` gravity directions, built once per test run and shared by every test
/// that asks for it (a build of a bundled setup costs tens of CPU-seconds).
pub fn built_dictionary(
    path: &'static str,
    directions: usize,
) -> &'static cable_dict::dictionary::Dictionary {
    use cable_dict::dictionary::{BuildOptions, Dictionary, build, write_dictionary};
    use std::collections::BTreeMap;
    use std::sync::{Mutex, OnceLock};
    type Cache = Mutex<BTreeMap<(&'static str, usize), &'static Dictionary>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    let dir = DIR.get_or_init(|| tempfile::tempdir().expect("temp dir"));
    let mut cache = CACHE.get_or_init(Cache::default).lock().expect("cache");
    cache.entry((path, directions)).or_insert_with(|| {
        let setup = cable_dict::setup::Setup::from_file(root().join(path)).expect("setup");
        let options = BuildOptions {
            directions,
            shard: None,
        };
        let built = build(&setup, &options).expect("builds");
        let file = dir.path().join(format!(
            "{}-{directions}.cdict",
            path.replace(['/', '.'], "_")
        ));
        write_dictionary(&file, &built).expect("written");
        Box::leak(Box::new(Dictionary::open(&file).expect("opens")))
    })
}
