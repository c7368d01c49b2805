//! The static motion sweep: one PV solved at every distinct pose of the motion.
//!
//! The attachment test looks at an inter-link segment only at its critical poses — the
//! extremes of the joints it traverses. The rest of the arm still turns gravity in the
//! segment's frame and moves other links past it between them. Measured on the bundled
//! pick-and-place with the paper's floppy cable: dozens of C1 PVs pass both J4 extremes and
//! bend to 47.9 mm (limit 48) between them (with the realistic preset, two C1 PVs of the
//! catalogue touch the forearm there by less than 0.05 mm). Before a chain goes to the
//! dynamic motion test, each of its PVs is solved statically at every motion sample: a PV
//! that fails anywhere would fail if the robot stopped there (a pause, an emergency stop),
//! and the motion test too when the motion is slow; it is dropped without a motion test.
//!
//! The poses are solved in the motion's order, each from the previous pose's equilibrium
//! carried along by the guides ([`Evaluator::sweep`]): a few Newton steps per pose instead
//! of a solve from the connected geometry, and the branch of equilibria a cable moved slowly
//! through the motion follows — the quasi-static limit of the motion test.

use super::evaluate::{Evaluator, SweptLeast};
use super::poses::{TestPose, sample_pose};
use super::verdict::Rejection;
use crate::motion::{Motion, MotionError};
use crate::path::Pv;
use crate::progress;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Where a PV first fails the static sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepFailure {
    /// Which motion of a cell (0 for a single motion).
    pub motion: usize,
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
    verdicts: BTreeMap<(usize, Pv), Verdict>,
}

/// What the sweep knows of one PV.
#[derive(Debug, Clone)]
struct Verdict {
    failure: Option<SweepFailure>,
    least: SweptLeast,
    /// Every pose was solved (or it failed at one): not stopped early by a least value.
    complete: bool,
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
    /// holds all three everywhere.
    pub fn check(&mut self, m: usize, pv: &Pv) -> Option<SweepFailure> {
        self.check_all(&[(m, *pv)]).pop().flatten()
    }

    /// [`MotionSweep::check`] of several PVs (segment, PV), swept in parallel; one result
    /// each, in order, independent of the thread count.
    pub fn check_all(&mut self, pvs: &[(usize, Pv)]) -> Vec<Option<SweepFailure>> {
        let asked: Vec<(usize, Pv, Option<SweptLeast>)> =
            pvs.iter().map(|&(m, pv)| (m, pv, None)).collect();
        self.check_until(&asked)
    }

    /// [`MotionSweep::check_all`], each PV's sweep stopped as soon as one of its least values
    /// falls below the one given with it ([`SweptLeast::below`]): then its result is `None`
    /// and [`MotionSweep::least`] says the least values so far; a later check without a stop
    /// sweeps it again, whole.
    pub fn check_until(
        &mut self,
        pvs: &[(usize, Pv, Option<SweptLeast>)],
    ) -> Vec<Option<SweepFailure>> {
        let evaluator = self.evaluator;
        let poses = &self.poses;
        // A sweep stopped early answers only a question it already answered: least values
        // below the stop asked for now.
        let known = |key: &(usize, Pv), stop: &Option<SweptLeast>| match self.verdicts.get(key) {
            None => false,
            Some(verdict) => {
                verdict.complete || stop.as_ref().is_some_and(|s| verdict.least.below(s))
            }
        };
        let new: Vec<(usize, Pv, Option<SweptLeast>)> = pvs
            .iter()
            .filter(|(m, pv, stop)| !known(&(*m, *pv), stop))
            .copied()
            .collect();
        progress::begin("static sweep", (new.len() * poses.len()) as u64);
        let swept: Vec<Verdict> = new
            .par_iter()
            .map(|(m, pv, stop)| {
                let swept = evaluator.sweep(*m, pv, poses, stop.as_ref());
                let failure = swept.failure.map(|(pose, check)| SweepFailure {
                    motion: 0,
                    rejection: check.rejection.unwrap_or(Rejection::Diverged),
                    sample: pose.sample,
                    time_s: pose.time_s,
                    detail: check.detail.unwrap_or_default(),
                });
                progress::advance(poses.len() as u64);
                Verdict {
                    failure,
                    least: swept.least,
                    complete: !swept.stopped_below,
                }
            })
            .collect();
        progress::end();
        let keys = new.into_iter().map(|(m, pv, _)| (m, pv));
        self.verdicts.extend(keys.zip(swept));
        pvs.iter()
            .map(|(m, pv, _)| (self.verdicts.get(&(*m, *pv))).and_then(|v| v.failure.clone()))
            .collect()
    }

    /// The least bend radius and clearance of PV `pv` of segment `m` over the poses it was
    /// swept at (up to its first failure); `None` when it was not swept.
    pub fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast> {
        self.verdicts.get(&(m, *pv)).map(|verdict| verdict.least)
    }
}
