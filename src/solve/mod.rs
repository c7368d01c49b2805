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
//!    ([`MotionSweep`]), and the whole cable checked at rest at the motion's first pose; a PV
//!    that fails there, or the PV of the segment that failed a
//!    dynamic motion test, is dropped before the next try (segments are independent between
//!    clamps). When none passes within `k` dynamic tries, or there is no chain, the result
//!    says so and why.

mod allowed;
mod box_check;
mod certify;
mod chains;
mod check;
mod diagnosis;
mod learn;
mod life;
mod options;
mod ranges;
mod report;
mod search;
mod shapes;
mod sweep;

pub use allowed::{
    ALLOWED_RANGE_RESOLUTION_DEG, CONTINUOUS_JOINT_SPAN_DEG, allowed_box, allowed_ranges,
};
pub use box_check::{
    BoxCheck, BoxFailure, GRAVITY_RESOLUTION_PER_STEP, MAX_BOX_CHECK_POSES, PieceOverBox, check_box,
};
pub use certify::{Certification, Disagreement};
use chains::{Decided, LazyChains, MIN_ROUND, chain_search};
pub use check::{Check, check_mounting, check_ranges};
pub use diagnosis::{
    DiagnosedPose, Diagnosis, NearestMiss, REJECTING_POSES, RejectingPose, SegmentDiagnosis,
};
pub use options::{LifeGoal, SearchKind, SolveError, SolveOptions};
pub use ranges::{DEFAULT_GRID_STEP_DEG, STRESS_MOTION_RATE_HZ, range_cell, solve_ranges};
use search::{MotionSearch, search_chains};
pub use shapes::{
    CriticalPose, PoseShape, ReportShapes, ShapeError, ShapeLine, critical_poses,
    first_nearest_miss, path_shape,
};

use report::Stages;
pub use report::{
    AllowedAxis, AllowedRanges, AxisFailures, AxisRange, BindingMotion, CandidateOutcome,
    ClosestMiss, DictionarySegmentUse, DictionaryUse, Inputs, LearnedSwing, Margin, MotionVerdict,
    NamedPath, PathGuide, PathSegment, PieceBinding, PoseSummary, RangeDesign, RangeEnd,
    RangeProbe, SegmentReport, SolveReport, Status, SweepRejection, SweepSummary, Timings,
    Unsolved, UnsolvedCase, UntriedChain, dropped_per_segment, guide_names, named_path,
    pose_summary, shown_index,
};

use crate::attachment::{
    ConnectMethod, CostEstimate, Evaluator, IntraLinkAnswer, LazyAttachment, LookupAnswer,
    SegmentPoses, SegmentSets, VerdictMemory, attachment_test_with, check_size,
};
use crate::dictionary::{Dictionary, MotionLookup};
use crate::motion::{Cell, Motion};
use crate::path::{CablePath, Pv};
use crate::setup::Setup;
use std::time::Instant;

/// Runs the whole pipeline on `setup` and `motion`.
pub fn solve(
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
) -> Result<SolveReport, SolveError> {
    solve_with(setup, motion, options, None).map(|solution| solution.report)
}

/// A solve's report with the setup it solved: the given one with the options applied
/// ([`SolveOptions::setup_for`]), which the report's mounting, pictures and sheet refer to.
#[derive(Debug, Clone)]
pub struct Solution {
    /// What was found, and why.
    pub report: SolveReport,
    /// The setup as solved.
    pub setup: Setup,
}

impl Solution {
    /// The path the solve answers with: the one that passed every motion test; `None` when
    /// none did (or none was run).
    pub fn answer(&self) -> Option<&CablePath> {
        let report = &self.report;
        (report.status == Status::Solved)
            .then(|| report.shown_candidate())
            .flatten()
            .filter(|c| c.passed == Some(true))
            .map(|c| &c.path)
    }
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
    solve_with(setup, motion, options, Some(dictionary)).map(|solution| solution.report)
}

/// [`solve`], or [`solve_with_dictionary`] when `dictionary` is given, keeping the setup as
/// solved.
pub fn solve_with(
    setup: &Setup,
    motion: &Motion,
    options: &SolveOptions,
    dictionary: Option<&Dictionary>,
) -> Result<Solution, SolveError> {
    solve_cell(
        setup,
        &Cell::single(motion.clone(), None),
        options,
        dictionary,
    )
}

/// The shortest path that holds every limit over every motion of `cell`: the pieces tested
/// at the union of the motions' test poses ([`SegmentPoses::for_cell`]), each chain swept
/// and motion-tested motion by motion ([`search`]); `dictionary` as in
/// [`solve_with_dictionary`].
pub fn solve_cell(
    setup: &Setup,
    cell: &Cell,
    options: &SolveOptions,
    dictionary: Option<&Dictionary>,
) -> Result<Solution, SolveError> {
    solve_cell_remembering(setup, cell, options, dictionary, None)
}

/// [`solve_cell`], the lazy attachment test knowing what earlier solves of `setup` with
/// the same options learnt (`memory`, [`VerdictMemory`]) and adding what this one learns:
/// the same answer for less work when the cells share test poses, as the boxes of a range
/// design do. The pieces a dictionary answers are not remembered (it answers them again).
pub fn solve_cell_remembering(
    setup: &Setup,
    cell: &Cell,
    options: &SolveOptions,
    dictionary: Option<&Dictionary>,
    memory: Option<&mut VerdictMemory>,
) -> Result<Solution, SolveError> {
    let total = Instant::now();
    if let Some(dictionary) = dictionary
        && options.method != ConnectMethod::Hermite
    {
        // A dictionary's verdicts are of one connected geometry; the other segments would be
        // tested another way, and the answer would be neither method's.
        return Err(SolveError::Options(format!(
            "{} was built with the {} connected geometry: solve with it (drop --connect), or \
             with --setup alone",
            dictionary.path().display(),
            dictionary.header().solver.connect
        )));
    }
    let solved = options.setup_for(setup)?;
    let setup = &solved;
    check_size(setup)
        .map_err(|e| SolveError::Options(format!("{}: {e}", setup.source.display())))?;
    let clock = Instant::now();
    let poses = SegmentPoses::for_cell(setup, cell, options.intra_link)?;
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
            let mut chains = Decided::new(setup, d2);
            let searched = search_chains(setup, cell, options, &mut chains, certify)?;
            (sets, searched, attachment_s)
        }
        SearchKind::Lazy => {
            let attachment = LazyAttachment::new(&evaluator, &poses, intra_link);
            let attachment = match memory.as_deref() {
                Some(memory) => attachment.remembering(memory),
                None => attachment,
            };
            let mut chains = LazyChains {
                setup,
                attachment,
                min_round: MIN_ROUND,
            };
            let (outcome, certification) =
                search_chains(setup, cell, options, &mut chains, certify)?;
            if outcome.tried.is_empty() && options.diagnose {
                // No chain: the diagnosis wants every piece's verdict, as without the search.
                chains.attachment.decide_all();
            }
            let attachment = chains.attachment;
            let attachment_s = attachment.time_s();
            let outcome = MotionSearch {
                chain_s: (outcome.chain_s - attachment_s).max(0.0),
                ..outcome
            };
            let sets = attachment.sets();
            let learnt = attachment.learnt();
            if let Some(memory) = memory {
                memory.learn(&poses, learnt);
            }
            (sets, (outcome, certification), attachment_s)
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
    let mut report = SolveReport::new(Stages {
        setup,
        cell,
        options,
        evaluator: &evaluator,
        poses: &poses,
        sets: &sets,
        search: &search,
        outcome,
        timings,
    });
    if let Some(lookup) = &lookup {
        report.inputs.dictionary = Some(dictionary_use(setup, lookup, &sets, certification));
    }
    Ok(Solution {
        report,
        setup: solved,
    })
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
                ", from the dictionary ({} directions: {} hold, {} solved)",
                l.direction_count(m),
                p.holds,
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
