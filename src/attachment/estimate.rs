//! What testing every candidate piece would cost, measured on a sample of pairs before a long
//! run, so that a user knows before waiting (`sites`, `solve --exhaustive`).

use super::evaluate::{ConnectMethod, Evaluator};
use super::jobs::PairJob;
use super::lazy::LazyAttachment;
use super::poses::{SegmentPoses, TestPose};
use super::sets::needed_pvs;
use crate::motion::Motion;
use crate::path::Pv;
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
    /// the cost of the exhaustive test, every candidate evaluated. The pieces are counted,
    /// not listed (a setup may have millions): every pair of clamp configurations that are
    /// not the same place has the same lengths to evaluate — the segment's lengths above zero
    /// and their robustness neighbours — and a pair that is, its zero-length piece.
    pub fn measure(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> CostEstimate {
        let setup = evaluator.setup();
        let robustness = setup.robustness;
        let mut evaluations = Vec::with_capacity(setup.segment_count());
        let mut sample = Vec::new();
        for m in 0..setup.segment_count() {
            let (a, b) = setup.segment_guides(m);
            let lengths = &setup.segments[m].lengths;
            let above_zero: Vec<Pv> = (lengths.iter())
                .filter(|&&s| s > 0)
                .map(|&s| Pv::new(s, 0, 0))
                .collect();
            let per_pair: Vec<usize> =
                needed_pvs(&above_zero, robustness.delta_s, robustness.range)
                    .iter()
                    .map(|pv| pv.sub_segments)
                    .collect();
            let nb = setup.guides[b].configurations.len();
            let pairs = setup.guides[a].configurations.len().saturating_mul(nb);
            let coincident = setup.coincident_pair_count(m);
            evaluations.push(
                (pairs - coincident).saturating_mul(per_pair.len())
                    + if lengths.contains(&0) { coincident } else { 0 },
            );
            if per_pair.is_empty() {
                continue;
            }
            // Pairs spread over the segment's, the same places left out (nothing to solve).
            let stride = (pairs / SAMPLE_PAIRS).max(1);
            let spread = (0..pairs).step_by(stride).map(|k| (k / nb, k % nb));
            let apart = spread.filter(|&(i, j)| !setup.coincident(a, i, b, j));
            sample.extend(apart.take(SAMPLE_PAIRS).map(|pair| PairJob {
                segment: m,
                pair,
                lengths: per_pair.clone(),
            }));
        }
        CostEstimate {
            cpu_s_per_evaluation: per_evaluation(evaluator, poses, &sample),
            evaluations,
        }
    }

    /// The cost of the lazy search's first widening ([`LazyAttachment::first_round`]): the
    /// least a search over these poses costs, when its shortest chain holds.
    pub fn first_round(lazy: &LazyAttachment<'_, '_>) -> CostEstimate {
        CostEstimate::of_jobs(lazy.evaluator(), lazy.poses(), &lazy.first_round())
    }

    /// The cost of evaluating `jobs`: per segment, its pieces, and the CPU time per piece
    /// over every test pose of the segment ([`per_evaluation`], on [`SAMPLE_PAIRS`] jobs
    /// spread over the segment's).
    fn of_jobs(evaluator: &Evaluator<'_>, poses: &SegmentPoses, jobs: &[PairJob]) -> CostEstimate {
        let segments = evaluator.setup().segment_count();
        let mut evaluations = Vec::with_capacity(segments);
        let mut sample = Vec::new();
        for m in 0..segments {
            let mine: Vec<&PairJob> = jobs.iter().filter(|job| job.segment == m).collect();
            evaluations.push(mine.iter().map(|job| job.lengths.len()).sum());
            let stride = (mine.len() / SAMPLE_PAIRS).max(1);
            sample.extend(mine.into_iter().step_by(stride).take(SAMPLE_PAIRS).cloned());
        }
        CostEstimate {
            cpu_s_per_evaluation: per_evaluation(evaluator, poses, &sample),
            evaluations,
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

/// Per segment, the CPU time per evaluated piece over all its test poses, measured on the
/// jobs of `sample` (on this thread), each at up to [`SAMPLE_POSES`] of the segment's poses
/// spread over them and the time scaled to all of them: a piece that fails, fails about as
/// far into the sample as into all; each pose is solved from the connected geometry, so a
/// pose costs the same in any company. 0 for a segment without a sampled job.
fn per_evaluation(evaluator: &Evaluator<'_>, poses: &SegmentPoses, sample: &[PairJob]) -> Vec<f64> {
    (0..evaluator.setup().segment_count())
        .map(|m| {
            let mine: Vec<&PairJob> = sample.iter().filter(|job| job.segment == m).collect();
            let sampled: usize = mine.iter().map(|job| job.lengths.len()).sum();
            let all = &poses.poses[m];
            let stride = all.len().div_ceil(SAMPLE_POSES).max(1);
            let some: Vec<&TestPose> = all.iter().step_by(stride).collect();
            if sampled == 0 || some.is_empty() {
                return 0.0;
            }
            let clock = Instant::now();
            for job in &mine {
                evaluator.first_rejections(m, job.pair, &job.lengths, &some);
            }
            clock.elapsed().as_secs_f64() * all.len() as f64 / some.len() as f64 / sampled as f64
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attachment::sets::admissible_pvs;
    use crate::attachment::{ConnectMethod, LazyAttachment};
    use crate::fixtures::narrow_pick_and_place;

    /// The pieces the exhaustive test evaluates, counted without listing them, are the
    /// candidates and robustness neighbours listed one by one (`needed_pvs` of
    /// `admissible_pvs`, what the exhaustive test evaluates); the first round's are fewer.
    #[test]
    fn pieces_counted_without_listing_them_are_the_pieces_listed() {
        let (setup, motion) = narrow_pick_and_place();
        let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let estimate = CostEstimate::measure(&evaluator, &poses);
        let r = setup.robustness;
        let listed: Vec<usize> = (0..setup.segment_count())
            .map(|m| needed_pvs(&admissible_pvs(&setup, m), r.delta_s, r.range).len())
            .collect();
        assert_eq!(estimate.evaluations, listed);
        assert!(
            (0..setup.segment_count()).any(|m| setup.coincident_pair_count(m) > 0),
            "the fixture has clamp places shared between guides"
        );
        assert!(estimate.cpu_s() > 0.0);
        let first = CostEstimate::first_round(&LazyAttachment::new(&evaluator, &poses, None));
        assert!(0 < first.pieces() && first.pieces() < estimate.pieces());
    }
}
