//! The search for the answer: the chains of pieces in non-decreasing length (decided up front,
//! or lazily in rounds), each offered to the static sweep and the motion test until one passes.

use super::certify::{Certification, Certified};
use super::options::{SolveError, SolveOptions};
use crate::attachment::{
    ConnectMethod, Evaluator, LazyAttachment, MotionSweep, SegmentPoses, SweepFailure,
};
use crate::chain::ChainSearch;
use crate::dictionary::MotionLookup;
use crate::motion::Motion;
use crate::motion_test::{self, MotionTestOptions, MotionTestReport};
use crate::path::{CablePath, Pv};
use crate::setup::Setup;
use std::time::Instant;

/// The motion tests over `chains`; with a dictionary's lookup (and the exact test it is
/// checked against), each chain certified before it is offered ([`Certified`]).
pub(super) fn search_chains(
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

/// The chain search over the sets `d2`, one per segment (declared ones and spans).
pub(super) fn chain_search(setup: &Setup, d2: &[Vec<Pv>]) -> Result<ChainSearch, SolveError> {
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
pub(super) trait Chains {
    /// The shortest chain of robust pieces not dropped (ties broken as [`ChainSearch`]
    /// does); `None` when there is none.
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError>;
    /// Takes piece `pv` of segment `m` out of every later chain.
    fn drop_piece(&mut self, m: usize, pv: &Pv);
}

/// The chains of fully decided sets (the exhaustive attachment test).
pub(super) struct Decided<'s> {
    pub(super) setup: &'s Setup,
    pub(super) d2: Vec<Vec<Pv>>,
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
pub(super) struct LazyChains<'r, 'a> {
    pub(super) setup: &'a Setup,
    pub(super) attachment: LazyAttachment<'r, 'a>,
    /// The fewest new candidates a round takes on ([`MIN_ROUND`]; smaller in tests, which
    /// want many rounds).
    pub(super) min_round: usize,
}

/// The fewest new candidates a lazy search's round takes on: fewer would leave the threads
/// idle between rounds.
pub(super) const MIN_ROUND: usize = 1000;

/// A lazy search's round takes on at least 1/this of the candidates decided so far. Rounds
/// re-solve the shorter lengths of the pairs they extend (a length's shape is continued from
/// its block's start), so smaller rounds cost more per piece; larger ones overshoot the
/// answer further. Measured (whole `solve`, 2 cores; divisor 1, 2, 4, 8 with rounds of at
/// least 1000): bundled inspection 0.67, 0.86, 0.78, 0.78 s; machine tending 0.80, 0.79,
/// 0.79, 0.75 s; the UR5 robot-level setup 5.4, 5.0, 4.6, 5.1 s.
const ROUND_GROWTH_DIVISOR: usize = 4;

impl LazyChains<'_, '_> {
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

impl Chains for LazyChains<'_, '_> {
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
            let mut lazy = LazyChains {
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
