//! Every wording of a solve's answer in one place: the summary `solve` prints for the people
//! who mount the cable (`workshop`), the search's details `solve -v` prints (`details`), and
//! the rows both, the sheet, the page and the plots share (the worst values over the motion,
//! the loads per clamp and piece, the verdict).

mod catalogue;
mod check;
mod details;
mod ranges;
mod workshop;

pub use catalogue::catalogue_listing;
pub use workshop::{
    Limits, LoadRow, WorstRow, life_words, load_rows, motion_verdict_words, verdict_words,
    worst_rows, write_motions,
};

use crate::solve::SolveReport;
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
            workshop::write_summary(self, f)
        }
    }
}

/// The motion as the summaries name it: `motion motions/pick_and_place.csv, 8.05 s` (its
/// file when the report knows it, and its duration), or `4 motions: pick_and_place, …`.
fn motion_words(report: &SolveReport) -> String {
    if report.motions.len() > 1 {
        let names: Vec<&str> = report.motions.iter().map(|m| m.name.as_str()).collect();
        return format!("{} motions: {}", names.len(), names.join(", "));
    }
    let inputs = &report.inputs;
    let file = inputs
        .motion_file
        .as_deref()
        .map(|m| format!("{m}, "))
        .unwrap_or_default();
    format!("motion {file}{:.2} s", inputs.motion_duration_s)
}
