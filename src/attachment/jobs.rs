//! Pieces grouped into jobs (one pair of clamp configurations, its lengths together, so that they share their start shapes) and evaluated in parallel in a fixed order.

use crate::path::Pv;
use crate::progress;
use rayon::prelude::*;
use std::collections::{BTreeMap, BTreeSet};

/// The lengths of one pair of guide configurations of one segment to evaluate together.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct PairJob {
    /// The segment.
    pub segment: usize,
    /// Its start and end guide configurations.
    pub pair: (usize, usize),
    /// The lengths (sorted, > 0).
    pub lengths: Vec<usize>,
}

/// The pieces `(segment, PV)` grouped by segment and pair, lengths ascending; zero-length
/// pieces (nothing to evaluate) left out.
pub(crate) fn pair_jobs(pieces: impl Iterator<Item = (usize, Pv)>) -> Vec<PairJob> {
    let mut pairs: BTreeMap<(usize, (usize, usize)), BTreeSet<usize>> = BTreeMap::new();
    for (m, pv) in pieces.filter(|(_, pv)| pv.sub_segments > 0) {
        pairs
            .entry((m, (pv.start, pv.end)))
            .or_default()
            .insert(pv.sub_segments);
    }
    pairs
        .into_iter()
        .map(|((segment, pair), lengths)| PairJob {
            segment,
            pair,
            lengths: lengths.into_iter().collect(),
        })
        .collect()
}

/// Every job's verdicts, evaluated in parallel (one job per worker at a time), in the
/// order of `jobs`, with a progress stage named `stage`.
pub(crate) fn evaluate_jobs<T: Send>(
    stage: &str,
    jobs: &[PairJob],
    verdicts_of: impl Fn(&PairJob) -> T + Sync,
) -> Vec<T> {
    let total: usize = jobs.iter().map(|job| job.lengths.len()).sum();
    progress::begin(stage, total as u64);
    let results = jobs
        .par_iter()
        .map(|job| {
            let result = verdicts_of(job);
            progress::advance(job.lengths.len() as u64);
            result
        })
        .collect();
    progress::end();
    results
}
