//! The result of [`solve`](super::solve), one job per file: the data (`data`), its assembly
//! from the stages' results (`assemble`), the margins re-solved for the answer (`margins`),
//! the result JSON (`json`), and the printed summaries: for the workshop (`workshop_text`)
//! and with the search's details (`text`, `solve -v`).

mod assemble;
mod data;
mod json;
mod margins;
mod text;
mod workshop_text;

pub use assemble::{guide_names, named_path, pose_summary};
pub use data::*;
pub use workshop_text::{LoadRow, WorstRow, load_rows, verdict_words, worst_rows};

use std::fmt;

impl fmt::Display for SolveReport {
    /// The summary for the people who mount the cable (`{}`): the clamps, their places and
    /// cable marks, the installation pose, the tolerance and the worst values over the
    /// motion; with `{:#}` (`solve -v`) the search's details: every candidate count, the
    /// margins at the test poses, the static sweep and the timings.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.alternate() {
            self.write_details(f)
        } else {
            workshop_text::write_summary(self, f)
        }
    }
}
