//! The main job: from a setup and a motion to the optimal cable path d*.
//!
//! 1. Critical poses of every inter-link segment, test poses of the intra-link ones
//!    ([`SegmentPoses`]).
//! 2. The attachment test: D0 → D'0 → D1 → D2 per segment. By default it is lazy
//!    ([`LazyAttachment`], [`SearchKind::Lazy`]): steps 2 and 3 interleave, and only the
//!    pieces a shortest chain can use are decided; [`SearchKind::Exhaustive`]
//!    decides every candidate first ([`crate::attachment::attachment_test`]). Both give the
//!    same chains. With a dictionary ([`solve_with_dictionary`]) the intra-link segments'
//!    pieces are answered from its margins at the motion's gravity directions, the undecided
//!    ones solved ([`MotionLookup`]): the same sets either way.
//! 3. The chain search over D2: |D3| and the shortest chain d̂ ([`ChainSearch`]).
//! 4. The motion test of the chains in non-decreasing length: the first that passes is d*.
//!    With a dictionary, the pieces a chain takes from it are first solved exactly
//!    ([`Certification`]): a piece the file got wrong is dropped, never reported. Each PV of a
//!    chain is then swept statically over every pose of the motion
//!    ([`MotionSweep`]); a PV that fails there, or the PV of the segment that failed a
//!    dynamic motion test, is dropped before the next try (segments are independent between
//!    clamps). When none passes within `k` dynamic tries, or there is no chain, the result
//!    says so and why.

mod certify;
mod diagnosis;
mod report;

use certify::Certified;
pub use certify::{Certification, Disagreement};
pub use diagnosis::{Diagnosis, NearestMiss, SegmentDiagnosis};

pub use report::{
    CandidateOutcome, DictionarySegmentUse, DictionaryUse, Inputs, LoadRow, Margin, NamedPath,
    PathGuide, PathSegment, PoseSummary, SegmentReport, SolveReport, Status, SweepRejection,
    SweepSummary, Timings, WorstRow, guide_names, load_rows, named_path, pose_summary, shown_index,
    verdict_words, worst_rows,
};

use crate::attachment::{
    ConnectMethod, CostEstimate, Evaluator, IntraLinkAnswer, IntraLinkCriterion, LazyAttachment,
    LookupAnswer, MotionSweep, SegmentPoses, SegmentSets, SweepFailure, attachment_test_with,
    check_size,
};
use crate::chain::{ChainError, ChainSearch};
use crate::dictionary::{Dictionary, LookupError, MotionLookup};
use crate::motion::{Motion, MotionError};
use crate::motion_test::{self, EngineKind, MotionTestError, MotionTestOptions, MotionTestReport};
use crate::path::{CablePath, Pv};
use crate::setup::{Setup, SetupError};
use crate::stress::contact::ContactError;
use std::time::Instant;

/// What `solve` does besides the defaults of the setup.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOptions {
    /// Connected geometry and static solver of the attachment test.
    pub method: ConnectMethod,
    /// `Some(1)`: the paper's method 1 (one guide per link: intra-link segments only at
    /// S = 0); `Some(2)` or `None`: as the setup declares.
    pub max_guides_per_link: Option<usize>,
    /// Chains tried in the motion test, at most (≥ 1): the budget of motion tests.
    pub k_best: usize,
    /// Run the motion test; without it the shortest chain d̂ is the answer.
    pub motion_test: bool,
    /// Before each dynamic motion test, sweep the chain's PVs statically over every pose of
    /// the motion ([`MotionSweep`]) and drop those that fail. Off: the paper's pipeline,
    /// where only the dynamic test follows the critical poses.
    pub static_sweep: bool,
    /// Keep the cable's shape every this many seconds in each motion test's report
    /// ([`MotionTestOptions::shape_interval_s`]), e.g. for the report's animation.
    pub shape_interval_s: Option<f64>,
    /// What simulates the cable in the motion test, at its default settings.
    pub engine: EngineKind,
    /// Which poses the intra-link segments are tested at (the dictionary's criterion, or
    /// the paper's one pose).
    pub intra_link: IntraLinkCriterion,
    /// How much of the attachment test runs: only the pieces a chain shorter than the
    /// answer could use (the default), or every candidate first (the reference the lazy
    /// search is tested against; same path, slower).
    pub search: SearchKind,
}

/// How the attachment test and the chain search work together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SearchKind {
    /// Pieces are evaluated as the search for the shortest chain needs them
    /// ([`LazyAttachment`]).
    #[default]
    Lazy,
    /// Every candidate piece is evaluated, then the chains are searched (the paper's order).
    Exhaustive,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: ConnectMethod::Hermite,
            max_guides_per_link: None,
            k_best: 50,
            motion_test: true,
            static_sweep: true,
            shape_interval_s: None,
            engine: EngineKind::Implicit,
            intra_link: IntraLinkCriterion::GravityDirections,
            search: SearchKind::Lazy,
        }
    }
}

impl SolveOptions {
    /// The setup as these options solve it: restricted to one guide per link for method 1.
    /// The indices of a [`SolveReport`]'s paths refer to this setup.
    pub fn setup_for(&self, setup: &Setup) -> Result<Setup, SolveError> {
        if self.k_best == 0 {
            return Err(SolveError::Options("--k-best must be at least 1".into()));
        }
        match self.max_guides_per_link {
            Some(1) => Ok(setup.inter_link_only()?),
            Some(2) | None => Ok(setup.clone()),
            Some(n) => Err(SolveError::Options(format!(
                "max guides per link must be 1 or 2, got {n}"
            ))),
        }
    }
}

/// Why `solve` could not run (not: "no path found", which is a [`Status`]).
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The options do not fit the setup.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The motion does not fit the robot.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// The robot's collision geometry cannot be used for clearance queries.
    #[error(transparent)]
    Obstacles(#[from] ContactError),
    /// The chain search refused the sets (a bug if it happens: the sets come from the setup).
    #[error("chain search: {0}")]
    Chain(#[from] ChainError),
    /// The motion test refused its input.
    #[error("motion test: {0}")]
    MotionTest(#[from] MotionTestError),
    /// Invalid options.
    #[error("{0}")]
    Options(String),
    /// The dictionary cannot answer for this setup and motion.
    #[error(transparent)]
    Dictionary(#[from] LookupError),
}

/// Runs the whole pipeline on `setup` and `motion`.
pub fn solve(
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
) -> Result<SolveReport, SolveError> {
    solve_with(setup, motion, options, None)
}

/// Runs the whole pipeline with the intra-link segments' pieces answered by `dictionary`:
/// built from `setup`, or from any setup of the same robot, cable, gravity, limits and
/// installation pose whose clamp catalogues hold every configuration of `setup`'s intra-link
/// guides ([`MotionLookup::new`] checks it); the inter-link segments are tested at their
/// critical poses as in [`solve`].
pub fn solve_with_dictionary(
    dictionary: &Dictionary,
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
) -> Result<SolveReport, SolveError> {
    solve_with(setup, motion, options, Some(dictionary))
}

fn solve_with(
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
    dictionary: Option<&Dictionary>,
) -> Result<SolveReport, SolveError> {
    let total = Instant::now();
    let setup = &options.setup_for(setup)?;
    check_size(setup)
        .map_err(|e| SolveError::Options(format!("{}: {e}", setup.source.display())))?;
    let clock = Instant::now();
    let poses = SegmentPoses::with(setup, motion, options.intra_link)?;
    let critical_poses_s = clock.elapsed().as_secs_f64();
    log::info!("critical poses: {critical_poses_s:.3} s");

    let evaluator = Evaluator::new(setup, options.method)?;
    let lookup = dictionary
        .map(|d| MotionLookup::new(d, setup, &poses))
        .transpose()?;
    let answer = |m: usize, pv: &Pv| match &lookup {
        Some(lookup) => lookup.answer(m, pv),
        None => LookupAnswer::Undecided(Vec::new()),
    };
    let intra_link: Option<&IntraLinkAnswer<'_>> = lookup.is_some().then_some(&answer);
    log_candidates(setup, options.search);
    let certify = lookup.as_ref().map(|lookup| (&evaluator, &poses, lookup));
    let (sets, (outcome, certification), attachment_s) = match options.search {
        SearchKind::Exhaustive => {
            if log::log_enabled!(log::Level::Info) {
                let sampler = Evaluator::new(setup, options.method)?;
                log_estimate(&CostEstimate::measure(&sampler, &poses));
            }
            let clock = Instant::now();
            let sets = attachment_test_with(&evaluator, &poses, intra_link);
            let attachment_s = clock.elapsed().as_secs_f64();
            let d2: Vec<Vec<Pv>> = sets.iter().map(|s| s.d2.clone()).collect();
            let mut chains = Decided { setup, d2 };
            let searched = search_chains(setup, motion, options, &mut chains, certify)?;
            (sets, searched, attachment_s)
        }
        SearchKind::Lazy => {
            let mut chains = Lazy {
                setup,
                attachment: LazyAttachment::new(&evaluator, &poses, intra_link),
                min_round: MIN_ROUND,
            };
            let (outcome, certification) =
                search_chains(setup, motion, options, &mut chains, certify)?;
            if outcome.tried.is_empty() {
                // No chain: the diagnosis wants every piece's verdict, as without the search.
                chains.attachment.decide_all();
            }
            let attachment = chains.attachment;
            let attachment_s = attachment.time_s();
            let outcome = MotionSearch {
                chain_s: (outcome.chain_s - attachment_s).max(0.0),
                ..outcome
            };
            (attachment.sets(), (outcome, certification), attachment_s)
        }
    };
    log_sets(setup, &sets, lookup.as_ref(), attachment_s);

    let clock = Instant::now();
    let d2: Vec<Vec<Pv>> = sets.iter().map(|s| s.d2.clone()).collect();
    let search = chain_search(setup, &d2)?;
    let chain_s = clock.elapsed().as_secs_f64() + outcome.chain_s;
    log::info!(
        "chain search: {} chains of robust pieces, {chain_s:.3} s",
        search.chain_count()
    );
    let motion_test_s = outcome.motion_test_s;
    log::info!(
        "static sweep: {} cable pieces dropped, {:.2} s; motion test: {} runs, {motion_test_s:.2} s",
        outcome.dropped.len(),
        outcome.sweep_s,
        outcome.tried.len()
    );

    let timings = Timings {
        critical_poses_s,
        attachment_s,
        attachment_intra_link_s: (0..setup.segment_count())
            .filter(|&m| setup.is_intra_link(m))
            .map(|m| sets[m].time_s)
            .sum(),
        chain_s,
        static_sweep_s: outcome.sweep_s,
        motion_test_s,
        total_s: total.elapsed().as_secs_f64(),
    };
    let mut report = SolveReport::new(
        setup, motion, options, &evaluator, &poses, &sets, &search, outcome, timings,
    );
    if let Some(lookup) = &lookup {
        report.inputs.dictionary = Some(dictionary_use(setup, lookup, &sets, certification));
    }
    Ok(report)
}

/// What the report says of the dictionary a solve used.
fn dictionary_use(
    setup: &Setup,
    lookup: &MotionLookup<'_>,
    sets: &[SegmentSets],
    certification: Certification,
) -> DictionaryUse {
    let dictionary = lookup.dictionary();
    let header = dictionary.header();
    DictionaryUse {
        file: dictionary.path().display().to_string(),
        directions: header.directions.count,
        covering_radius_deg: header.directions.covering_radius_rad.to_degrees(),
        segments: sets
            .iter()
            .enumerate()
            .filter_map(|(m, s)| {
                Some(DictionarySegmentUse {
                    segment: setup.segment_name(m),
                    gravity_directions: lookup.direction_count(m),
                    pieces: s.looked_up?,
                })
            })
            .collect(),
        certification,
        provenance: None,
    }
}

/// The motion tests over `chains`; with a dictionary's lookup (and the exact test it is
/// checked against), each chain certified before it is offered ([`Certified`]).
fn search_chains(
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
    chains: &mut dyn Chains,
    certify: Option<(&Evaluator<'_>, &SegmentPoses, &MotionLookup<'_>)>,
) -> Result<(MotionSearch, Certification), SolveError> {
    let Some((evaluator, poses, lookup)) = certify else {
        let outcome = motion_tests(setup, motion, chains, options)?;
        return Ok((outcome, Certification::default()));
    };
    let mut certified = Certified::new(chains, evaluator, poses, lookup);
    let outcome = motion_tests(setup, motion, &mut certified, options)?;
    let certification = certified.certification;
    log::info!(
        "certified: {} stored pieces solved exactly, {} records contradicted",
        certification.pieces_solved,
        certification.disagreements.len()
    );
    Ok((outcome, certification))
}

/// The number of candidate pieces, before the attachment test starts.
fn log_candidates(setup: &Setup, search: SearchKind) {
    let counts: Vec<usize> = (0..setup.segment_count())
        .map(|m| setup.admissible_pv_count(m))
        .collect();
    let listed: Vec<String> = counts
        .iter()
        .enumerate()
        .map(|(m, n)| format!("{} {n}", setup.segment_name(m)))
        .collect();
    let what = match search {
        SearchKind::Lazy => "testing those a chain shorter than the answer can use, in rounds",
        SearchKind::Exhaustive => "testing every one",
    };
    log::info!(
        "attachment test: {} candidate pieces ({}); {what}",
        counts.iter().sum::<usize>(),
        listed.join(", ")
    );
}

/// What the exhaustive test is about to cost, measured on a sample.
fn log_estimate(estimate: &CostEstimate) {
    let threads = rayon::current_num_threads();
    log::info!("attachment test: {}", estimate.describe(threads));
}

/// One `info` line per segment: its set sizes, and where intra-link verdicts came from.
fn log_sets(
    setup: &Setup,
    sets: &[SegmentSets],
    lookup: Option<&MotionLookup<'_>>,
    attachment_s: f64,
) {
    for (m, s) in sets.iter().enumerate() {
        let source = match (lookup, s.looked_up) {
            (Some(l), Some(p)) => format!(
                ", from the dictionary ({} directions: {} hold, {} fail, {} solved)",
                l.direction_count(m),
                p.holds,
                p.fails,
                p.solved
            ),
            _ => String::new(),
        };
        log::info!(
            "attachment {}: {} candidates, {} after pruning, {} hold the limits, {} robust, \
             {} evaluations, {} static solves, {:.2} s{source}",
            setup.segment_name(m),
            s.d0,
            s.d0_pruned,
            s.d1,
            s.d2.len(),
            s.evaluations,
            s.static_solves,
            s.time_s
        );
    }
    log::info!("attachment test: {attachment_s:.2} s");
}

/// The chain search over the sets `d2`, one per segment (declared ones and spans).
fn chain_search(setup: &Setup, d2: &[Vec<Pv>]) -> Result<ChainSearch, SolveError> {
    let counts: Vec<usize> = setup
        .guides
        .iter()
        .map(|g| g.configurations.len())
        .collect();
    let ends: Vec<(usize, usize)> = (0..setup.segment_count())
        .map(|m| setup.segment_guides(m))
        .collect();
    Ok(ChainSearch::over(&counts, &ends, d2)?)
}

/// Where the search for d* takes its chains from.
trait Chains {
    /// The shortest chain of robust pieces not dropped (ties broken as [`ChainSearch`]
    /// does); `None` when there is none.
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError>;
    /// Takes piece `pv` of segment `m` out of every later chain.
    fn drop_piece(&mut self, m: usize, pv: &Pv);
}

/// The chains of fully decided sets (the exhaustive attachment test).
struct Decided<'s> {
    setup: &'s Setup,
    d2: Vec<Vec<Pv>>,
}

impl Chains for Decided<'_> {
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError> {
        Ok(chain_search(self.setup, &self.d2)?.shortest())
    }

    fn drop_piece(&mut self, m: usize, pv: &Pv) {
        self.d2[m].retain(|kept| kept != pv);
    }
}

/// The chains of a lazy attachment test: its bound widened until the shortest chain of the
/// pieces it decided is no longer than the bound (then no undecided piece can make a shorter
/// one). Each widening takes at least a fixed share of the candidates decided before
/// ([`ROUND_GROWTH_DIVISOR`], and at least [`MIN_ROUND`]), so the rounds grow geometrically
/// in work, not in length: the work past the answer's bound stays a bounded fraction of the
/// work up to it.
struct Lazy<'r, 'a> {
    setup: &'a Setup,
    attachment: LazyAttachment<'r, 'a>,
    /// The fewest new candidates a round takes on ([`MIN_ROUND`]; smaller in tests, which
    /// want many rounds).
    min_round: usize,
}

/// The fewest new candidates a lazy search's round takes on: fewer would leave the threads
/// idle between rounds.
const MIN_ROUND: usize = 1000;

/// A lazy search's round takes on at least 1/this of the candidates decided so far. Rounds
/// re-solve the shorter lengths of the pairs they extend (a length's shape is continued from
/// its block's start), so smaller rounds cost more per piece; larger ones overshoot the
/// answer further. Measured (whole `solve`, 2 cores; divisor 1, 2, 4, 8 with rounds of at
/// least 1000): bundled inspection 0.67, 0.86, 0.78, 0.78 s; machine tending 0.80, 0.79,
/// 0.79, 0.75 s; the UR5 robot-level setup 5.4, 5.0, 4.6, 5.1 s.
const ROUND_GROWTH_DIVISOR: usize = 4;

impl Lazy<'_, '_> {
    /// The next bound after `bound`: the first that decides [`MIN_ROUND`] candidates, or the
    /// share [`ROUND_GROWTH_DIVISOR`] of those decided already, no more than `cap` (a known
    /// chain's length).
    fn next_bound(&self, bound: usize, cap: Option<usize>) -> usize {
        let wanted = (self.attachment.decided() / ROUND_GROWTH_DIVISOR).max(self.min_round);
        let mut taken = 0;
        let mut next = bound + 1;
        for (&key, &count) in self.attachment.pending_by_bound().range(bound + 1..) {
            next = key;
            taken += count;
            if taken >= wanted {
                break;
            }
        }
        cap.map_or(next, |cap| next.min(cap)).max(bound + 1)
    }
}

impl Chains for Lazy<'_, '_> {
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError> {
        // A piece dropped since the last call reopens its pair: decide what the bound now
        // needs of it before trusting the bound.
        if let Some(bound) = self.attachment.bound() {
            self.attachment.widen_to(bound);
        }
        loop {
            let Some(bound) = self.attachment.bound() else {
                let Some(first) = self.attachment.lower_bound() else {
                    return Ok(None);
                };
                let next = self.next_bound(first.saturating_sub(1), None);
                self.attachment.widen_to(next);
                continue;
            };
            let path = chain_search(self.setup, &self.attachment.robust())?.shortest();
            if let Some(path) = &path
                && path.total_sub_segments() <= bound
            {
                return Ok(Some(path.clone()));
            }
            if self.attachment.lower_bound().is_none() {
                return Ok(path);
            }
            let next = self.next_bound(bound, path.as_ref().map(CablePath::total_sub_segments));
            log::debug!("lazy search: no chain up to {bound} sub-segments, widening to {next}");
            self.attachment.widen_to(next);
        }
    }

    fn drop_piece(&mut self, m: usize, pv: &Pv) {
        self.attachment.drop_piece(m, pv);
    }
}

/// One chain put to the motion test (`None`: not tested).
pub(crate) type Tried = (CablePath, Option<MotionTestReport>);

/// A PV the static sweep dropped: segment, PV, where it failed.
pub(crate) type Dropped = (usize, Pv, SweepFailure);

/// What the search for d* did.
pub(crate) struct MotionSearch {
    /// The chains put to the dynamic test, in order.
    pub tried: Vec<Tried>,
    /// Index of the one that passed.
    pub winner: Option<usize>,
    /// Why the search stopped without one (empty otherwise).
    pub stop: String,
    /// Distinct motion poses of the static sweep (0 when it did not run).
    pub sweep_poses: usize,
    /// PVs swept.
    pub swept: usize,
    /// PVs the sweep dropped, in the order found.
    pub dropped: Vec<Dropped>,
    /// Wall time spent sweeping (s).
    pub sweep_s: f64,
    /// Wall time of the chain searches between motion tests (s), attachment tests a lazy
    /// search ran for them not included.
    pub chain_s: f64,
    /// Wall time of the dynamic motion tests (s).
    pub motion_test_s: f64,
}

impl MotionSearch {
    fn stopped(mut self, stop: impl Into<String>) -> Self {
        self.stop = stop.into();
        self
    }
}

/// The search for d*: the shortest chain of what is left of D2 is swept statically (its
/// failing PVs dropped, then the next chain) and put to the dynamic motion test; after a
/// failure that belongs to a segment, that segment's PV is dropped and the search goes on,
/// for at most `k_best` dynamic tests. Segments are independent between clamps, so every
/// chain with a failed PV fails too: this tries, in non-decreasing length, exactly the chains
/// of the k-best enumeration that contain no PV already seen failing.
fn motion_tests(
    setup: &Setup,
    motion: &Motion,
    chains: &mut dyn Chains,
    options: &SolveOptions,
) -> Result<MotionSearch, SolveError> {
    let mut outcome = MotionSearch {
        tried: Vec::new(),
        winner: None,
        stop: String::new(),
        sweep_poses: 0,
        swept: 0,
        dropped: Vec::new(),
        sweep_s: 0.0,
        chain_s: 0.0,
        motion_test_s: 0.0,
    };
    let shortest = |outcome: &mut MotionSearch, chains: &mut dyn Chains| {
        let clock = Instant::now();
        let path = chains.shortest();
        outcome.chain_s += clock.elapsed().as_secs_f64();
        path
    };
    if !options.motion_test {
        let path = shortest(&mut outcome, chains)?;
        outcome.tried.extend(path.map(|path| (path, None)));
        outcome.winner = (!outcome.tried.is_empty()).then_some(0);
        return Ok(outcome);
    }
    // The sweep is a cheap static filter in front of the dynamic test: always the
    // quasi-static solver, whatever the attachment test used.
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
    let mut sweep = options
        .static_sweep
        .then(|| MotionSweep::new(&evaluator, motion))
        .transpose()?;
    outcome.sweep_poses = sweep.as_ref().map_or(0, MotionSweep::pose_count);
    // Stopping at the first violation only shortens failing runs: a passing candidate is
    // simulated through the whole motion either way, series included.
    let test_options = MotionTestOptions {
        stop_at_first_violation: true,
        shape_interval_s: options.shape_interval_s,
        ..MotionTestOptions::new(options.engine.with_defaults(setup.gravity_m_s2))
    };
    while outcome.tried.len() < options.k_best {
        let Some(path) = shortest(&mut outcome, chains)? else {
            return Ok(
                outcome.stopped("no chain is left of the robust pieces that did not fail it")
            );
        };
        if let Some(sweep) = sweep.as_mut() {
            let clock = Instant::now();
            let failed = sweep_chain(sweep, &path);
            outcome.sweep_s += clock.elapsed().as_secs_f64();
            outcome.swept = sweep.swept();
            if !failed.is_empty() {
                for (m, pv, failure) in &failed {
                    log::debug!(
                        "static sweep drops {} {pv:?}: {}",
                        setup.segment_name(*m),
                        failure.detail
                    );
                    chains.drop_piece(*m, pv);
                }
                outcome.dropped.extend(failed);
                continue;
            }
        }
        let clock = Instant::now();
        let report = motion_test::run(setup, &path, motion, &test_options)?;
        outcome.motion_test_s += clock.elapsed().as_secs_f64();
        log::info!(
            "motion test {}: {:.0} mm, {}",
            outcome.tried.len() + 1,
            path.total_sub_segments() as f64 * setup.cable.sub_segment_pitch_m * 1e3,
            report
                .failure
                .as_ref()
                .map_or("passed".to_string(), |f| f.reason.clone())
        );
        let failed_segment = report.failure.as_ref().and_then(|f| f.segment);
        let passed = report.passed;
        outcome.tried.push((path.clone(), Some(report)));
        if passed {
            outcome.winner = Some(outcome.tried.len() - 1);
            return Ok(outcome);
        }
        let Some(m) = failed_segment else {
            return Ok(outcome.stopped("the last failure belongs to no single segment"));
        };
        for (_, failed) in path.pieces().filter(|&(segment, _)| segment == m) {
            chains.drop_piece(m, &failed);
        }
    }
    let budget = options.k_best;
    Ok(outcome.stopped(format!(
        "the budget of {budget} motion tests (--k-best) is spent"
    )))
}

/// The PVs of `path` that fail the static sweep, piece by piece.
fn sweep_chain(sweep: &mut MotionSweep<'_, '_>, path: &CablePath) -> Vec<Dropped> {
    let pvs: Vec<(usize, Pv)> = path.pieces().collect();
    pvs.iter()
        .zip(sweep.check_all(&pvs))
        .filter_map(|(&(m, pv), failure)| Some((m, pv, failure?)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{exhaustive_robust, narrow_pick_and_place};

    /// Drops the pieces of `path`'s segment `m`, as a motion test that failed there does.
    fn fail_segment(chains: &mut dyn Chains, path: &CablePath, m: usize) {
        for (m, pv) in path.pieces().filter(|&(segment, _)| segment == m) {
            chains.drop_piece(m, &pv);
        }
    }

    #[test]
    fn the_lazy_chains_follow_the_exhaustive_ones_through_failed_motion_tests() {
        let (setup, motion) = narrow_pick_and_place();
        let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let d2 = exhaustive_robust(&evaluator, &poses);
        // Small rounds and large ones: in the large ones, a drop reopens its pair far
        // inside the bound.
        for min_round in [1, 30, 300] {
            let mut decided = Decided {
                setup: &setup,
                d2: d2.clone(),
            };
            let mut lazy = Lazy {
                setup: &setup,
                attachment: LazyAttachment::new(&evaluator, &poses, None),
                min_round,
            };
            for step in 0..12 {
                let expected = decided.shortest().unwrap_or_else(|e| panic!("{e}"));
                let found = lazy.shortest().unwrap_or_else(|e| panic!("{e}"));
                assert_eq!(found, expected, "rounds of {min_round}, chain {step}");
                let Some(path) = expected else { break };
                fail_segment(&mut decided, &path, step % 3);
                fail_segment(&mut lazy, &path, step % 3);
            }
        }
    }
}
