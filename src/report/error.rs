//! Why a report folder could not be written.

use super::plots;
use std::path::PathBuf;

/// Why the report folder could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file or the folder cannot be written.
    #[error("cannot write {path}: {error}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// Why (in the message, not a separate cause, so that it is printed once).
        error: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error("{file}: {source}")]
    Plot {
        /// The plot's file name.
        file: &'static str,
        /// Why.
        source: plots::PlotError,
    },
    /// The scene could not be assembled or encoded.
    #[error("scene.glb: {0}")]
    Scene(String),
    /// The result could not be encoded as JSON.
    #[error("result.json: {0}")]
    Json(#[from] serde_json::Error),
}
