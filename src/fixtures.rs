//! Inputs shared by the crate's unit tests.

use crate::attachment::{Evaluator, SegmentPoses, attachment_test};
use crate::motion::Motion;
use crate::path::Pv;
use crate::setup::Setup;
use std::path::Path;

/// The bundled robot-level setup with narrow length windows (C1 and C3 220–400 mm, C2
/// 100–160 mm) and the bundled pick-and-place motion: small enough that the exhaustive
/// attachment test a lazy one is checked against takes a second.
pub(crate) fn narrow_pick_and_place() -> (Setup, Motion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("robots/viper_s850/pick_and_place.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let text = text
        .replace(
            "lengths = { min = 20, max = 80, step = 1, allow_zero = false }",
            "lengths = { min = 22, max = 40, step = 1, allow_zero = false }",
        )
        .replace(
            "lengths = { min = 10, max = 40, step = 1, allow_zero = true }",
            "lengths = { min = 10, max = 16, step = 1, allow_zero = true }",
        );
    assert!(
        text.matches("min = 22, max = 40").count() == 2
            && text.matches("min = 10, max = 16").count() == 1,
        "the bundled setup's length windows changed: narrow them again"
    );
    let setup = Setup::from_toml_str(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let csv = root.join("motions/viper_s850/pick_and_place.csv");
    let motion = Motion::from_csv_file(&setup.robot, &csv).unwrap_or_else(|e| panic!("{e}"));
    (setup, motion)
}

/// The robust pieces of every segment by the exhaustive attachment test: what a lazy one
/// is checked against.
pub(crate) fn exhaustive_robust(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> Vec<Vec<Pv>> {
    attachment_test(evaluator, poses)
        .into_iter()
        .map(|s| s.d2)
        .collect()
}
