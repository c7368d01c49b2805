//! What testing every candidate piece would cost, measured on a sample of pairs before a long
//! run, so that a user knows before waiting (`sites`, `solve --exhaustive`).

use super::evaluate::{ConnectMethod, Evaluator};
use super::jobs::{PairJob, pair_jobs};
use super::lazy::LazyAttachment;
use super::poses::{SegmentPoses, TestPose};
use super::sets::{admissible_pvs, needed_pvs};
use crate::motion::Motion;
use crate::setup::Setup;
use std::time::Instant;

/// Pairs of clamp configurations sampled per segment: enough to average over short and long
/// clamp distances, few enough to take a fraction of a second.
pub const SAMPLE_PAIRS: usize = 6;

/// Test poses a sampled piece is solved at, at most, spread over its segment's: an
/// axis-range grid gives a piece thousands.
pub const SAMPLE_POSES: usize = 64;

/// The measured cost of a setup's attachment test.
#[derive(Debug, Clone, PartialEq)]
pub struct CostEstimate {
    /// Pieces evaluated per segment (candidates and their robustness lengths): every one for
    /// the exhaustive test.
    pub evaluations: Vec<usize>,
    /// CPU seconds per evaluated piece per segment, over all its test poses, measured on
    /// [`SAMPLE_PAIRS`] pairs spread over the segment's pieces.
    pub cpu_s_per_evaluation: Vec<f64>,
}

impl CostEstimate {
    /// The cost of testing every candidate piece of `setup` at one pose, its
    /// [`Setup::reference_joints`] (what `sites` prints before a user starts a long run);
    /// `None` when that pose cannot be used (a clamp out of reach, a robot without it).
    pub fn at_reference_pose(setup: &Setup) -> Option<CostEstimate> {
        let joints = setup.reference_joints();
        let motion =
            Motion::new(&setup.robot, vec![0.0, 1.0], vec![joints.clone(), joints]).ok()?;
        let poses = SegmentPoses::new(setup, &motion).ok()?;
        let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).ok()?;
        Some(CostEstimate::measure(&evaluator, &poses))
    }

    /// Times the test of a sample of each segment's pairs at its test poses (on this thread):
    /// the cost of the exhaustive test, every candidate evaluated.
    pub fn measure(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> CostEstimate {
        let setup = evaluator.setup();
        let robustness = setup.robustness;
        let jobs = (0..setup.segment_count()).flat_map(|m| {
            let needed = needed_pvs(
                &admissible_pvs(setup, m),
                robustness.delta_s,
                robustness.range,
            );
            pair_jobs(needed.into_iter().map(|pv| (m, pv)))
        });
        CostEstimate::of_jobs(evaluator, poses, &jobs.collect::<Vec<_>>())
    }

    /// The cost of the lazy search's first widening ([`LazyAttachment::first_round`]): the
    /// least a search over these poses costs, when its shortest chain holds.
    pub fn first_round(lazy: &LazyAttachment<'_, '_>) -> CostEstimate {
        CostEstimate::of_jobs(lazy.evaluator(), lazy.poses(), &lazy.first_round())
    }

    /// The cost of evaluating `jobs`: per segment, its pieces, and the CPU time per piece
    /// over every test pose of the segment, measured on [`SAMPLE_PAIRS`] jobs spread over
    /// the segment's, each at up to [`SAMPLE_POSES`] of its poses spread over them (the time
    /// scaled to all of them: a piece that fails, fails about as far into the sample as into
    /// all; each pose is solved from the connected geometry, so a pose costs the same in any
    /// company).
    pub(crate) fn of_jobs(
        evaluator: &Evaluator<'_>,
        poses: &SegmentPoses,
        jobs: &[PairJob],
    ) -> CostEstimate {
        let segments = evaluator.setup().segment_count();
        let mut evaluations = Vec::with_capacity(segments);
        let mut cpu_s_per_evaluation = Vec::with_capacity(segments);
        for m in 0..segments {
            let mine: Vec<&PairJob> = jobs.iter().filter(|job| job.segment == m).collect();
            evaluations.push(mine.iter().map(|job| job.lengths.len()).sum());
            let stride = (mine.len() / SAMPLE_PAIRS).max(1);
            let sample: Vec<&PairJob> = mine
                .into_iter()
                .step_by(stride)
                .take(SAMPLE_PAIRS)
                .collect();
            let sampled: usize = sample.iter().map(|job| job.lengths.len()).sum();
            let all = &poses.poses[m];
            let pose_stride = all.len().div_ceil(SAMPLE_POSES).max(1);
            let some: Vec<&TestPose> = all.iter().step_by(pose_stride).collect();
            let clock = Instant::now();
            for job in &sample {
                evaluator.first_rejections(m, job.pair, &job.lengths, &some);
            }
            let cpu_s = clock.elapsed().as_secs_f64() * all.len() as f64 / some.len().max(1) as f64;
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

    /// "about N CPU-s here, M s on T threads (measured on …)": what a front end prints, for
    /// `threads` workers.
    pub fn describe(&self, threads: usize) -> String {
        format!(
            "about {:.0} CPU-s here, {:.0} s on {threads} threads (measured on \
             {SAMPLE_PAIRS} clamp pairs per segment)",
            self.cpu_s(),
            self.wall_s(threads)
        )
    }

    /// CPU seconds of every piece's evaluation.
    pub fn cpu_s(&self) -> f64 {
        self.evaluations
            .iter()
            .zip(&self.cpu_s_per_evaluation)
            .map(|(&n, &s)| n as f64 * s)
            .sum()
    }

    /// Seconds of every piece's evaluation on `threads` workers.
    pub fn wall_s(&self, threads: usize) -> f64 {
        self.cpu_s() / threads.max(1) as f64
    }

    /// Pieces evaluated, over every segment.
    pub fn pieces(&self) -> usize {
        self.evaluations.iter().sum()
    }
}
