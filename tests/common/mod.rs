//! Helpers shared by the tests that run the `cable-dict` binary.

use std::process::{Command, Output};

/// Runs the binary with `args` from the package root (where the bundled files' relative paths
/// start).
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cable-dict"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// The text of the bundled robot-level setup `robots/viper_s850/pick_and_place.toml` with its
/// robot and cable paths made absolute, so that it loads from any folder a test writes it to.
#[allow(dead_code)] // not every test binary uses every helper
pub fn bundled_setup_text() -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(root.join("robots/viper_s850/pick_and_place.toml"))
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
