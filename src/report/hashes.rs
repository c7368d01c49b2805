//! The inputs of a run, each with the hash of its bytes: what a report is traced back to.

use crate::setup::Setup;
use crate::solve::SolveReport;
use std::path::Path;

/// An input file of the run, with the xxh3-64 of its bytes, so that a report can be traced to
/// the exact files that made it.
#[derive(Debug, Clone, PartialEq)]
pub struct Hashed {
    /// `setup`, `robot`, `cable`, `motion` or `dictionary`.
    pub role: &'static str,
    /// The file as given.
    pub file: String,
    /// 16 hexadecimal digits, or why the file could not be read.
    pub hash: String,
}

impl Hashed {
    /// The hash of `bytes`.
    pub fn of_bytes(role: &'static str, file: impl Into<String>, bytes: &[u8]) -> Hashed {
        Hashed {
            role,
            file: file.into(),
            hash: format!("{:016x}", xxhash_rust::xxh3::xxh3_64(bytes)),
        }
    }

    /// The hash of the file at `path` as it is now.
    pub fn of_file(role: &'static str, path: &Path) -> Hashed {
        match std::fs::read(path) {
            Ok(bytes) => Hashed::of_bytes(role, path.display().to_string(), &bytes),
            Err(e) => Hashed {
                role,
                file: path.display().to_string(),
                hash: format!("unreadable: {e}"),
            },
        }
    }
}

/// The hashes of a solve's inputs: the setup, URDF and cable texts as loaded, the motion
/// and dictionary files as they are now.
pub fn input_hashes(setup: &Setup, report: &SolveReport) -> Vec<Hashed> {
    let mut inputs = vec![
        Hashed::of_bytes(
            "setup",
            setup.source.display().to_string(),
            setup.text.as_bytes(),
        ),
        Hashed::of_bytes(
            "robot",
            setup.robot_path.display().to_string(),
            setup.robot_text.as_bytes(),
        ),
        Hashed::of_bytes(
            "cable",
            setup.cable_path.display().to_string(),
            setup.cable_text.as_bytes(),
        ),
    ];
    // Every motion of a cell (its first is `inputs.motion_file`), then the dictionary.
    let motions = (report.motions.iter()).filter_map(|m| m.file.as_deref());
    let motions = motions.map(|file| ("motion", Some(file)));
    let dictionary = report.inputs.dictionary.as_ref().map(|d| d.file.as_str());
    for (role, file) in motions.chain([("dictionary", dictionary)]) {
        if let Some(file) = file {
            inputs.push(Hashed::of_file(role, Path::new(file)));
        }
    }
    inputs
}
