//! The attachment test: which PVs of each segment hold all three stress limits
//! at every pose that matters, and which of those are robust to a length error.
//!
//! Per segment `C_m`, in the paper's notation:
//!
//! - **D0**: the admissible PVs (S, P_m, P_(m+1)) of the setup ([`Setup::is_admissible`]).
//! - **D'0** (adjacency): for an inter-link segment, the PVs of D0 whose guide shared with an
//!   intra-link neighbour is used by some PV in that neighbour's D2. Intra-link segments are
//!   tested first, so their D'0 is their D0.
//! - **D1**: the PVs of D'0 whose static equilibrium keeps the clearance, stretch and bend
//!   radius limits at every test pose ([`SegmentPoses`]). A zero-length PV (one clamp) has no
//!   cable and passes.
//! - **D2** (robustness): the PVs of D1 whose guides, with every length `S ± k·ΔS`,
//!   `k = 1…R`, pass the same test. Lengths beyond the candidate range are evaluated for this
//!   purpose (they are not candidates themselves), so a PV at the end of its range is judged
//!   by physics, not by the range. A length below one sub-segment cannot be built: a PV that
//!   would need one is not robust. Zero-length PVs are robust (there is no cable to cut
//!   wrong).
//!
//! Every (guides, length) pair is evaluated once, in parallel with rayon; results are
//! collected in a fixed order, so the sets do not depend on the thread count. A failed
//! solve rejects that PV (counted as "solver failed") and the run goes on.
//!
//! Two drivers share the evaluation: [`attachment_test`] decides every candidate (the
//! paper's order, `solve --exhaustive`), [`LazyAttachment`] only those a chain shorter than
//! a bound can use (`solve`'s default; docs/architecture.md, "Lazy attachment test"). The
//! modules: verdicts and margins (`verdict`), one piece at one pose (`evaluate`), warm starts
//! and continuation over lengths (`continuation`), the rapier baseline (`baseline`), test
//! poses (`poses`), the static sweep (`sweep`), cost estimates (`estimate`).

mod baseline;
mod continuation;
mod estimate;
mod evaluate;
mod lazy;
mod poses;
mod sweep;
mod verdict;

pub use continuation::CONTINUATION_BLOCK;
pub use estimate::{CostEstimate, SAMPLE_PAIRS};
pub use evaluate::{ConnectMethod, Evaluator};
pub use lazy::LazyAttachment;
pub use poses::{GRAVITY_RESOLUTION_DEG, IntraLinkCriterion, SegmentPoses, TestPose};
pub use sweep::{MotionSweep, SweepFailure};
pub use verdict::{Check, Margins, Metrics, Miss, Rejection};

use crate::path::Pv;
use crate::progress;
use crate::setup::Setup;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

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

/// Runs the attachment test on every segment: intra-link segments first, then the inter-link
/// ones pruned by their intra-link neighbours' D2.
pub fn attachment_test(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> Vec<SegmentSets> {
    attachment_test_with(evaluator, poses, None)
}

/// [`attachment_test`], with the intra-link segments' pieces answered by `intra_link` (a
/// dictionary's lookup over the same test poses) when it is `Some`: the pieces it cannot
/// decide are solved exactly at the undecided poses, so the sets equal the exact test's.
pub fn attachment_test_with(
    evaluator: &Evaluator<'_>,
    poses: &SegmentPoses,
    intra_link: Option<&IntraLinkAnswer<'_>>,
) -> Vec<SegmentSets> {
    let setup = evaluator.setup();
    let count = setup.segment_count();
    let at_poses = |m: usize, guides: (usize, usize), lengths: &[usize]| {
        evaluator.first_rejections(m, guides, lengths, &poses.poses[m])
    };
    let mut sets: Vec<Option<SegmentSets>> = vec![None; count];
    for m in (0..count).filter(|&m| setup.is_intra_link(m)) {
        let candidates = admissible_pvs(setup, m);
        sets[m] = Some(match intra_link {
            Some(lookup) => {
                let counts = LookupCounts::default();
                let mut tested = test_segment(setup, m, candidates, |guides, lengths| {
                    looked_up(
                        evaluator,
                        &poses.poses[m],
                        lookup,
                        m,
                        guides,
                        lengths,
                        &counts,
                    )
                });
                tested.looked_up = Some(counts.snapshot());
                tested
            }
            None => test_segment(setup, m, candidates, |guides, lengths| {
                at_poses(m, guides, lengths)
            }),
        });
    }
    for m in (0..count).filter(|&m| !setup.is_intra_link(m)) {
        let (a, b) = setup.segment_guides(m);
        let allowed_start = neighbour_configurations(&sets, setup.segments_into(a), |pv| pv.end);
        let allowed_end = neighbour_configurations(&sets, setup.segments_from(b), |pv| pv.start);
        let d0 = admissible_pvs(setup, m);
        let d0_count = d0.len();
        let candidates: Vec<Pv> = d0
            .into_iter()
            .filter(|pv| allowed_start.as_ref().is_none_or(|a| a.contains(&pv.start)))
            .filter(|pv| allowed_end.as_ref().is_none_or(|a| a.contains(&pv.end)))
            .collect();
        let mut tested = test_segment(setup, m, candidates, |guides, lengths| {
            at_poses(m, guides, lengths)
        });
        tested.d0 = d0_count;
        sets[m] = Some(tested);
    }
    let mut sets: Vec<SegmentSets> = sets.into_iter().flatten().collect();
    for (m, s) in sets.iter_mut().enumerate() {
        s.static_solves = evaluator.static_solves(m);
    }
    sets
}

/// A lookup's answer for one piece of an intra-link segment over the segment's test poses
/// (e.g. a dictionary's, [`crate::dictionary::MotionLookup`]).
#[derive(Debug, Clone, PartialEq)]
pub enum LookupAnswer {
    /// Every limit holds at every test pose, by more than the lookup's error.
    Holds,
    /// A limit fails at test pose `pose` (index) by more than the lookup's error;
    /// `margins`, the looked-up `[clearance mm, stretch, curvature 1/m]` there.
    Fails {
        /// Index of the test pose.
        pose: usize,
        /// The limit.
        rejection: Rejection,
        /// The looked-up margins, when there are any (not for a cable too short).
        margins: Option<[f64; 3]>,
    },
    /// The lookup cannot decide at these test poses (indices, ascending): solve them.
    Undecided(Vec<usize>),
}

/// The answer for piece `pv` of segment `m`.
pub type IntraLinkAnswer<'v> = dyn Fn(usize, &Pv) -> LookupAnswer + Sync + 'v;

/// How the pieces of an intra-link segment were answered by a lookup.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct LookedUp {
    /// Pieces (robustness lengths included) that hold by the lookup alone.
    pub holds: usize,
    /// Pieces that fail by the lookup alone.
    pub fails: usize,
    /// Pieces the lookup could not decide, solved exactly.
    pub solved: usize,
    /// Of those, the ones the exact check rejected: the lookup's false accepts.
    pub solved_failed: usize,
}

/// [`LookedUp`] counted from parallel workers.
#[derive(Default, Debug)]
struct LookupCounts([AtomicUsize; 4]);

impl LookupCounts {
    fn add(&self, k: usize) {
        self.0[k].fetch_add(1, Ordering::Relaxed);
    }

    /// The counts so far.
    fn snapshot(&self) -> LookedUp {
        let [holds, fails, solved, solved_failed] =
            std::array::from_fn(|k| self.0[k].load(Ordering::Relaxed));
        LookedUp {
            holds,
            fails,
            solved,
            solved_failed,
        }
    }
}

/// The verdicts of the lengths of one pair of configurations from `lookup`; the undecided
/// ones solved at the poses where any length of the pair is undecided, the whole chain of
/// lengths together, as the exact test solves them.
fn looked_up(
    evaluator: &Evaluator<'_>,
    poses: &[TestPose],
    lookup: &IntraLinkAnswer<'_>,
    m: usize,
    (start, end): (usize, usize),
    lengths: &[usize],
    counts: &LookupCounts,
) -> Vec<Option<Miss>> {
    let setup = evaluator.setup();
    let answers: Vec<LookupAnswer> = lengths
        .iter()
        .map(|&s| lookup(m, &Pv::new(s, start, end)))
        .collect();
    let undecided: BTreeSet<usize> = answers
        .iter()
        .filter_map(|a| match a {
            LookupAnswer::Undecided(at) => Some(at.iter().copied()),
            _ => None,
        })
        .flatten()
        .collect();
    let at: Vec<usize> = undecided.into_iter().collect();
    let wanted: Vec<bool> = answers
        .iter()
        .map(|a| matches!(a, LookupAnswer::Undecided(_)))
        .collect();
    let exact = if at.is_empty() {
        vec![None; lengths.len()]
    } else {
        let chosen: Vec<&TestPose> = at.iter().map(|&p| &poses[p]).collect();
        evaluator.first_rejections_of(m, (start, end), lengths, &chosen, &wanted)
    };
    answers
        .into_iter()
        .enumerate()
        .map(|(i, answer)| match answer {
            LookupAnswer::Holds => {
                counts.add(0);
                None
            }
            LookupAnswer::Fails {
                pose,
                rejection,
                margins,
            } => {
                counts.add(1);
                Some(Miss::looked_up(setup, rejection, margins, pose))
            }
            LookupAnswer::Undecided(_) => {
                counts.add(2);
                let miss = exact[i].map(|miss| Miss {
                    pose: at[miss.pose],
                    ..miss
                });
                if miss.is_some() {
                    counts.add(3);
                }
                miss
            }
        })
        .collect()
}

/// The configurations of the shared guide used by the D2 of its neighbours (the segments
/// that end, or start, there), when every neighbour has been tested already; `None` (no
/// pruning) when one has not, or there is none.
fn neighbour_configurations(
    sets: &[Option<SegmentSets>],
    neighbours: impl Iterator<Item = usize>,
    shared: impl Fn(&Pv) -> usize,
) -> Option<BTreeSet<usize>> {
    let mut used = BTreeSet::new();
    let mut any = false;
    for n in neighbours {
        let tested = sets.get(n)?.as_ref()?;
        used.extend(tested.d2.iter().map(&shared));
        any = true;
    }
    any.then_some(used)
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

/// D1 and D2 of segment `m` from its candidates (D'0), given the verdicts of the lengths
/// (sorted, > 0) of one pair of guide configurations: the pairs are evaluated in parallel,
/// each pair's lengths together (so that they can share their solves' start shapes).
fn test_segment(
    setup: &Setup,
    m: usize,
    candidates: Vec<Pv>,
    verdicts_of: impl Fn((usize, usize), &[usize]) -> Vec<Option<Miss>> + Sync,
) -> SegmentSets {
    let timer = Instant::now();
    let robustness = &setup.robustness;
    let needed = needed_pvs(&candidates, robustness.delta_s, robustness.range);
    let jobs = pair_jobs(needed.iter().map(|pv| (m, *pv)));
    let mut verdicts = Verdicts::new();
    verdicts.extend(
        &jobs,
        evaluate_jobs(
            &format!("attachment {}", setup.segment_name(m)),
            &jobs,
            |job| verdicts_of(job.pair, &job.lengths),
        ),
    );
    let mut sets = verdicts.sets(setup, &candidates);
    sets.time_s = timer.elapsed().as_secs_f64();
    sets
}

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

    /// Pieces evaluated (zero-length ones not counted).
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    /// The sets of a segment whose `candidates` were all decided with these verdicts.
    pub(crate) fn sets(&self, setup: &Setup, candidates: &[Pv]) -> SegmentSets {
        let mut rejections = BTreeMap::new();
        let mut misses: Vec<(Pv, Miss)> = Vec::new();
        for pv in candidates {
            if let Some(Some(miss)) = self.get(pv) {
                *rejections.entry(miss.rejection).or_insert(0) += 1;
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
fn nearest_misses(mut misses: Vec<(Pv, Miss)>) -> Vec<(Pv, Miss)> {
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
