//! The search for the answer: the chains of pieces in non-decreasing length (decided up front,
//! or lazily in rounds), each offered to the static sweep and the motion test until one passes.

use super::certify::{Certification, Certified};
use super::chains::Chains;
use super::options::{SolveError, SolveOptions};
use crate::attachment::{ConnectMethod, Evaluator, MotionSweep, SegmentPoses, SweepFailure};
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
