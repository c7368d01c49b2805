//! What testing every candidate piece would cost, measured on a sample of pairs before a long
//! run, so that a user knows before waiting (`sites`, `solve --exhaustive`).

use super::evaluate::{ConnectMethod, Evaluator};
use super::jobs::{PairJob, pair_jobs};
use super::poses::SegmentPoses;
use super::sets::{admissible_pvs, needed_pvs};
use crate::motion::Motion;
use crate::setup::Setup;
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
            let pairs = pair_jobs(needed.iter().map(|pv| (m, *pv)));
            evaluations.push(needed.len());
            let stride = (pairs.len() / SAMPLE_PAIRS).max(1);
            let sample: Vec<&PairJob> = pairs.iter().step_by(stride).take(SAMPLE_PAIRS).collect();
            let sampled: usize = sample.iter().map(|job| job.lengths.len()).sum();
            let clock = Instant::now();
            for job in &sample {
                evaluator.first_rejections(m, job.pair, &job.lengths, &poses.poses[m]);
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

    /// "about N CPU-s here, M s on T threads (measured on …)": what a front end prints, for
    /// `threads` workers.
    pub fn describe(&self, threads: usize) -> String {
        let cpu_s = self.exhaustive_cpu_s();
        format!(
            "about {cpu_s:.0} CPU-s here, {:.0} s on {threads} threads (measured on \
             {SAMPLE_PAIRS} clamp pairs per segment)",
            cpu_s / threads.max(1) as f64
        )
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
