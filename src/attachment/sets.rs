//! What the attachment test decides for a segment: its sets (D0 … D2 and the nearest misses), the verdicts of its evaluated pieces, the robustness neighbours a piece needs, and the size limit of a whole test.

use super::jobs::PairJob;
use super::verdict::{Miss, Rejection};
use crate::path::Pv;
use crate::setup::Setup;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// The sets of one segment after the attachment test.
#[derive(Debug, Clone, Serialize)]
pub struct SegmentSets {
    /// |D0|: admissible PVs.
    pub d0: usize,
    /// |D'0|: PVs left after adjacency pruning.
    pub d0_pruned: usize,
    /// |D1|: PVs that pass at every test pose.
    pub d1: usize,
    /// D2: robust PVs, sorted.
    pub d2: Vec<Pv>,
    /// PVs of D'0 rejected, by the first limit they violated (at the first pose that failed).
    pub rejections: BTreeMap<Rejection, usize>,
    /// The rejected PVs of D'0 that came closest to holding every limit, least severe first:
    /// the closest of each limit that rejected any, then the next closest, at most
    /// [`NEAREST_MISSES`], measured ones only — what a diagnosis shows.
    pub nearest_misses: Vec<(Pv, Miss)>,
    /// Per test pose (index), how many PVs of D'0 were rejected there (the first pose that
    /// failed them, in the order tried): where the segment's pieces fail.
    pub rejected_at: BTreeMap<usize, usize>,
    /// (guides, length) combinations evaluated, robustness lengths included.
    pub evaluations: usize,
    /// Static solves (Newton's) started for them, at every test pose.
    pub static_solves: usize,
    /// How a lookup answered them (intra-link segments solved with a dictionary).
    pub looked_up: Option<LookedUp>,
    /// Wall time of this segment's test (s).
    pub time_s: f64,
}

/// Nearest misses kept per segment.
pub const NEAREST_MISSES: usize = 3;

/// How the pieces of an intra-link segment were answered by a lookup.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct LookedUp {
    /// Pieces (robustness lengths included) that hold by the lookup alone.
    pub holds: usize,
    /// Pieces that fail by the lookup alone (none with `solve --dict`, which solves every
    /// piece a file rejects; a lookup that does decide failures counts them here).
    pub fails: usize,
    /// Pieces the lookup could not decide, solved exactly.
    pub solved: usize,
    /// Of those, the ones the exact check rejected: the lookup's false accepts.
    pub solved_failed: usize,
}

/// Most candidate pieces (PVs of D0, over all segments) one attachment test takes on: about
/// 150 bytes each while it runs (the candidate, robustness and verdict lists), so 1.5 GB,
/// and 5–80 µs each on one core. The robot-level bundled setups have about 1 million.
pub const MAX_CANDIDATE_PIECES: u128 = 10_000_000;

/// `Err` naming the count when `setup` has more candidate pieces than
/// [`MAX_CANDIDATE_PIECES`], with the largest segments and what to change.
pub fn check_size(setup: &Setup) -> Result<(), String> {
    let per_segment: Vec<u128> = (0..setup.segment_count())
        .map(|m| setup.pv_count(m) as u128)
        .collect();
    let total: u128 = per_segment.iter().sum();
    if total <= MAX_CANDIDATE_PIECES {
        return Ok(());
    }
    let listed: Vec<String> = per_segment
        .iter()
        .enumerate()
        .map(|(m, n)| format!("{} {n}", setup.segment_name(m)))
        .collect();
    Err(format!(
        "{total} candidate pieces ({}), at most {MAX_CANDIDATE_PIECES} (about 150 bytes and \
         up to 80 µs each): raise spacing_mm, use fewer directions_deg or a region, or narrow \
         the length windows (`cable-dict sites` counts them)",
        listed.join(", ")
    ))
}

/// D0 of segment `m`: every admissible PV, sorted.
pub fn admissible_pvs(setup: &Setup, m: usize) -> Vec<Pv> {
    let (a, b) = setup.segment_guides(m);
    let (na, nb) = (
        setup.guides[a].configurations.len(),
        setup.guides[b].configurations.len(),
    );
    let mut pvs = Vec::new();
    for &s in &setup.segments[m].lengths {
        for i in 0..na {
            for j in 0..nb {
                if setup.is_admissible(m, s, i, j) {
                    pvs.push(Pv {
                        sub_segments: s,
                        start: i,
                        end: j,
                    });
                }
            }
        }
    }
    pvs
}

/// The verdicts of one segment's evaluated pieces (`None`: the piece holds every limit at
/// every test pose).
#[derive(Debug, Clone, Default)]
pub(crate) struct Verdicts(BTreeMap<Pv, Option<Miss>>);

impl Verdicts {
    pub(crate) fn new() -> Verdicts {
        Verdicts::default()
    }

    /// Records the results of `jobs` (all of one segment).
    pub(crate) fn extend(&mut self, jobs: &[PairJob], results: Vec<Vec<Option<Miss>>>) {
        for (job, result) in jobs.iter().zip(results) {
            for (&sub_segments, verdict) in job.lengths.iter().zip(result) {
                self.0
                    .insert(Pv::new(sub_segments, job.pair.0, job.pair.1), verdict);
            }
        }
    }

    /// The verdict of `pv`: `Some(None)` it holds (zero-length pieces always do),
    /// `Some(Some(miss))` it fails, `None` not evaluated.
    pub(crate) fn get(&self, pv: &Pv) -> Option<Option<Miss>> {
        if pv.sub_segments == 0 {
            return Some(None);
        }
        self.0.get(pv).copied()
    }

    /// Whether `pv` was evaluated and holds.
    pub(crate) fn holds(&self, pv: &Pv) -> bool {
        matches!(self.get(pv), Some(None))
    }

    /// Whether candidate `pv` is robust: it and every robustness neighbour hold.
    pub(crate) fn robust(&self, pv: &Pv, robustness: &crate::setup::Robustness) -> bool {
        self.holds(pv)
            && robust_neighbours(pv, robustness.delta_s, robustness.range)
                .is_some_and(|neighbours| neighbours.iter().all(|n| self.holds(n)))
    }

    /// Every piece evaluated and its verdict, in order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (&Pv, &Option<Miss>)> {
        self.0.iter()
    }

    /// Pieces evaluated (zero-length ones not counted).
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    /// The sets of a segment whose `candidates` were all decided with these verdicts.
    pub(crate) fn sets(&self, setup: &Setup, candidates: &[Pv]) -> SegmentSets {
        let mut rejections = BTreeMap::new();
        let mut rejected_at = BTreeMap::new();
        let mut misses: Vec<(Pv, Miss)> = Vec::new();
        for pv in candidates {
            if let Some(Some(miss)) = self.get(pv) {
                *rejections.entry(miss.rejection).or_insert(0) += 1;
                *rejected_at.entry(miss.pose).or_insert(0) += 1;
                if miss.severity.is_finite() {
                    misses.push((*pv, miss));
                }
            }
        }
        let d1 = candidates.iter().filter(|pv| self.holds(pv)).count();
        let mut d2: Vec<Pv> = candidates
            .iter()
            .filter(|pv| self.robust(pv, &setup.robustness))
            .copied()
            .collect();
        d2.sort();
        SegmentSets {
            d0: candidates.len(),
            d0_pruned: candidates.len(),
            d1,
            d2,
            rejections,
            nearest_misses: nearest_misses(misses),
            rejected_at,
            evaluations: self.len() + candidates.iter().filter(|pv| pv.sub_segments == 0).count(),
            static_solves: 0,
            looked_up: None,
            time_s: 0.0,
        }
    }
}

/// The least severe miss of every limit that rejected something, then the next least severe
/// ones, up to [`NEAREST_MISSES`], least severe first; ties in PV order (the sorts are
/// stable), so the choice is deterministic.
pub(super) fn nearest_misses(mut misses: Vec<(Pv, Miss)>) -> Vec<(Pv, Miss)> {
    misses.sort_by(|a, b| a.1.severity.total_cmp(&b.1.severity));
    let mut chosen: Vec<(Pv, Miss)> = Vec::with_capacity(NEAREST_MISSES);
    for miss in &misses {
        if chosen.len() < NEAREST_MISSES
            && !chosen.iter().any(|c| c.1.rejection == miss.1.rejection)
        {
            chosen.push(*miss);
        }
    }
    for miss in &misses {
        // By piece: a miss holds NaN where nothing was measured, and NaN ≠ NaN.
        if chosen.len() < NEAREST_MISSES && !chosen.iter().any(|c| c.0 == miss.0) {
            chosen.push(*miss);
        }
    }
    chosen.sort_by(|a, b| a.1.severity.total_cmp(&b.1.severity));
    chosen
}

/// The PVs `S ± k·ΔS`, `k = 1…R`, with the same guides; `None` when one of them would be
/// shorter than one sub-segment. Empty for a zero-length PV.
pub fn robust_neighbours(pv: &Pv, delta_s: usize, range: usize) -> Option<Vec<Pv>> {
    if pv.sub_segments == 0 {
        return Some(Vec::new());
    }
    let mut neighbours = Vec::with_capacity(2 * range);
    for k in 1..=range {
        let step = k * delta_s;
        if pv.sub_segments <= step {
            return None;
        }
        for s in [pv.sub_segments - step, pv.sub_segments + step] {
            neighbours.push(Pv {
                sub_segments: s,
                ..*pv
            });
        }
    }
    Some(neighbours)
}

/// Every PV to evaluate: the candidates and their robustness neighbours, each once, sorted.
pub fn needed_pvs(candidates: &[Pv], delta_s: usize, range: usize) -> Vec<Pv> {
    let mut needed: BTreeSet<Pv> = candidates.iter().copied().collect();
    for pv in candidates {
        if let Some(neighbours) = robust_neighbours(pv, delta_s, range) {
            needed.extend(neighbours);
        }
    }
    needed.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn miss(rejection: Rejection, severity: f64) -> Miss {
        Miss {
            rejection,
            severity,
            value: f64::NAN,
            pose: 0,
            at_m: f64::NAN,
        }
    }

    #[test]
    fn a_nearest_miss_is_listed_once_though_it_holds_unmeasured_values() {
        let misses = vec![
            (Pv::new(30, 0, 0), miss(Rejection::TooShort, 0.5)),
            (Pv::new(31, 0, 0), miss(Rejection::TooShort, 0.6)),
        ];
        let chosen = nearest_misses(misses);
        let pieces: Vec<Pv> = chosen.iter().map(|(pv, _)| *pv).collect();
        assert_eq!(pieces, [Pv::new(30, 0, 0), Pv::new(31, 0, 0)]);
    }
}
