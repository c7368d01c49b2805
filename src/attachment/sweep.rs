//! The static motion sweep: one PV solved at every distinct pose of the motion.
//!
//! The attachment test looks at an inter-link segment only at its critical poses — the
//! extremes of the joints it traverses. The rest of the arm still turns gravity in the
//! segment's frame and moves other links past it between them. Measured on the bundled
//! pick-and-place: a C1 PV that passes at both J4 extremes bends to 47.9 mm (limit 48) at
//! C3's J5 maximum. Before a chain goes to the dynamic motion test (seconds per chain), each
//! of its PVs is solved statically at every motion sample (about 0.4 ms per pose); a PV that
//! fails anywhere can only fail the motion test too and is dropped without one.

use super::{Evaluator, Rejection, TestPose, poses::sample_pose};
use crate::motion::{Motion, MotionError};
use crate::path::Pv;
use crate::progress;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Where a PV first fails the static sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepFailure {
    /// The limit violated first at that pose.
    pub rejection: Rejection,
    /// Motion sample of the pose.
    pub sample: usize,
    /// Time of the pose (s).
    pub time_s: f64,
    /// Why, for people.
    pub detail: String,
}

/// Sweeps PVs over the motion, remembering every verdict.
pub struct MotionSweep<'e, 'a> {
    evaluator: &'e Evaluator<'a>,
    poses: Vec<TestPose>,
    verdicts: BTreeMap<(usize, Pv), Option<SweepFailure>>,
}

impl<'e, 'a> MotionSweep<'e, 'a> {
    /// The sweep over `motion`'s samples; a sample equal to the one before it (a dwell) is
    /// skipped: its shapes are the same.
    pub fn new(evaluator: &'e Evaluator<'a>, motion: &Motion) -> Result<Self, MotionError> {
        let samples = motion.samples();
        let poses = (0..samples.len())
            .filter(|&k| k == 0 || samples[k] != samples[k - 1])
            .map(|k| sample_pose(evaluator.setup(), motion, k, "motion sample"))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            evaluator,
            poses,
            verdicts: BTreeMap::new(),
        })
    }

    /// Number of distinct poses a PV is solved at.
    pub fn pose_count(&self) -> usize {
        self.poses.len()
    }

    /// Number of PVs swept so far.
    pub fn swept(&self) -> usize {
        self.verdicts.len()
    }

    /// The first pose (in time) where PV `pv` of segment `m` violates a limit; `None` when it
    /// holds all three everywhere. Poses are solved in parallel; the verdict does not depend
    /// on the thread count.
    pub fn check(&mut self, m: usize, pv: &Pv) -> Option<SweepFailure> {
        let evaluator = self.evaluator;
        let poses = &self.poses;
        self.verdicts
            .entry((m, *pv))
            .or_insert_with(|| {
                progress::begin(&format!("static sweep C{}", m + 1), poses.len() as u64);
                let failure = poses.par_iter().find_map_first(|pose| {
                    let check = evaluator.check(m, pv, pose);
                    progress::advance(1);
                    Some(SweepFailure {
                        rejection: check.rejection?,
                        sample: pose.sample,
                        time_s: pose.time_s,
                        detail: check.detail.unwrap_or_default(),
                    })
                });
                progress::end();
                failure
            })
            .clone()
    }
}
