//! What testing every candidate piece would cost, measured on a sample of pairs before a long
//! run, so that a user knows before waiting (`sites`, `solve --exhaustive`).

use super::{Evaluator, SegmentPoses, admissible_pvs, needed_pvs};
use crate::path::Pv;
use std::collections::BTreeMap;
use std::time::Instant;

/// Pairs of clamp configurations sampled per segment: enough to average over short and long
/// clamp distances, few enough to take a fraction of a second.
pub const SAMPLE_PAIRS: usize = 6;

/// The measured cost of a setup's attachment test.
#[derive(Debug, Clone, PartialEq)]
pub struct CostEstimate {
    /// Pieces the exhaustive test evaluates per segment (candidates and their robustness
    /// lengths).
    pub evaluations: Vec<usize>,
    /// CPU seconds per evaluated piece per segment, over all its test poses, measured on
    /// [`SAMPLE_PAIRS`] pairs spread over the segment's candidates.
    pub cpu_s_per_evaluation: Vec<f64>,
}

impl CostEstimate {
    /// Times the test of a sample of each segment's pairs at its test poses (on this thread).
    pub fn measure(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> CostEstimate {
        let setup = evaluator.setup();
        let robustness = setup.robustness;
        let mut evaluations = Vec::with_capacity(setup.segment_count());
        let mut cpu_s_per_evaluation = Vec::with_capacity(setup.segment_count());
        for m in 0..setup.segment_count() {
            let needed = needed_pvs(
                &admissible_pvs(setup, m),
                robustness.delta_s,
                robustness.range,
            );
            let pairs = lengths_by_pair(&needed);
            evaluations.push(needed.len());
            let stride = (pairs.len() / SAMPLE_PAIRS).max(1);
            let sample: Vec<(&(usize, usize), &Vec<usize>)> =
                pairs.iter().step_by(stride).take(SAMPLE_PAIRS).collect();
            let sampled: usize = sample.iter().map(|(_, lengths)| lengths.len()).sum();
            let clock = Instant::now();
            for (pair, lengths) in &sample {
                evaluator.first_rejections(m, **pair, lengths, &poses.poses[m]);
            }
            let cpu_s = clock.elapsed().as_secs_f64();
            cpu_s_per_evaluation.push(if sampled > 0 {
                cpu_s / sampled as f64
            } else {
                0.0
            });
        }
        CostEstimate {
            evaluations,
            cpu_s_per_evaluation,
        }
    }

    /// CPU seconds of the whole exhaustive test.
    pub fn exhaustive_cpu_s(&self) -> f64 {
        self.evaluations
            .iter()
            .zip(&self.cpu_s_per_evaluation)
            .map(|(&n, &s)| n as f64 * s)
            .sum()
    }
}

/// The lengths (> 0) of `pieces` grouped by pair of clamp configurations.
fn lengths_by_pair(pieces: &[Pv]) -> BTreeMap<(usize, usize), Vec<usize>> {
    let mut pairs: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for pv in pieces.iter().filter(|pv| pv.sub_segments > 0) {
        pairs
            .entry((pv.start, pv.end))
            .or_default()
            .push(pv.sub_segments);
    }
    pairs
}
