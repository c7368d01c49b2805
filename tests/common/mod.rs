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
