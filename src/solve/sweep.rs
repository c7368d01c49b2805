//! The static sweep as the search uses it: each piece of a chain over every pose of the
//! motion ([`MotionSweep`]), then the whole cable at rest at the motion's first pose; for a
//! cell, motion by motion ([`CellSweep`]).

use super::options::SolveError;
use crate::attachment::{Evaluator, MotionSweep, Rejection, SweepFailure, SweptLeast};
use crate::motion::{Cell, Motion};
use crate::motion_test::{self, Constraint, FailureCause, MotionTestOptions};
use crate::path::{CablePath, Pv};
use crate::setup::Setup;

/// A PV the static sweep dropped: segment, PV, where it failed.
pub(crate) type Dropped = (usize, Pv, SweepFailure);

/// The static sweep of a chain: each piece over every pose of the motion, then the whole
/// cable at rest at the motion's first pose, its pieces joined at their clamps as the motion
/// test's first step measures them. Two pieces hanging into each other fail there, which no
/// check of one piece sees; such a failure is the motion test's own at its first step (it
/// starts from that rest shape), so it drops the piece the motion test would drop and spends
/// no motion test.
pub(super) struct SweepAtRest<'a, 'e, 'v> {
    pieces: MotionSweep<'e, 'v>,
    setup: &'a Setup,
    motion: &'a Motion,
    /// The motion test's options, first pose only.
    options: MotionTestOptions,
}

impl<'a, 'e, 'v> SweepAtRest<'a, 'e, 'v> {
    /// The sweep `pieces`, then the whole cable checked as the motion test with `test`
    /// options checks it at its first step.
    pub(super) fn new(
        pieces: MotionSweep<'e, 'v>,
        setup: &'a Setup,
        motion: &'a Motion,
        test: &MotionTestOptions,
    ) -> Self {
        SweepAtRest {
            pieces,
            setup,
            motion,
            options: MotionTestOptions {
                first_pose_only: true,
                record_series: false,
                ..test.clone()
            },
        }
    }
}

impl ChainSweep for SweepAtRest<'_, '_, '_> {
    fn failing(
        &mut self,
        path: &CablePath,
        stops: &[Option<SweptLeast>],
    ) -> Result<Vec<Dropped>, SolveError> {
        let failed = self.pieces.failing(path, stops)?;
        if !failed.is_empty() {
            return Ok(failed);
        }
        let report = motion_test::run(self.setup, path, self.motion, &self.options)?;
        let Some(failure) = report.failure else {
            return Ok(Vec::new());
        };
        // A failure of no single segment is left to the motion test to report.
        let Some(m) = failure.segment else {
            return Ok(Vec::new());
        };
        let rejection = match (failure.cause, &report.first_violation) {
            (FailureCause::TooShort, _) => Rejection::TooShort,
            (FailureCause::Violation, Some(violation)) => match violation.constraint {
                Constraint::Contact | Constraint::ContactForce => Rejection::Contact,
                // Out of travel: the piece is too short for the pose.
                Constraint::Stretch => Rejection::Stretch,
                Constraint::Travel => Rejection::TooShort,
                Constraint::BendRadius | Constraint::FlexingBendRadius => Rejection::Bend,
                Constraint::Twist => Rejection::Twist,
                Constraint::SelfContact => Rejection::SelfContact,
            },
            _ => Rejection::Diverged,
        };
        let at_rest = SweepFailure {
            motion: 0,
            rejection,
            sample: 0,
            time_s: self.motion.times_s()[0],
            detail: format!(
                "the whole cable at rest at the first pose: {}",
                failure.reason
            ),
        };
        let piece = path.pieces().find(|&(segment, _)| segment == m);
        Ok(piece.map(|(m, pv)| (m, pv, at_rest)).into_iter().collect())
    }

    fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast> {
        self.pieces.least(m, pv)
    }

    fn swept(&self) -> usize {
        self.pieces.swept()
    }
}

/// The static sweep of every motion of a cell, one after the other: a piece that fails one
/// motion's is dropped (its failure names the motion); a piece's least values are the least
/// over the motions. The motion that dropped a piece last is swept first: the likeliest to
/// drop the next chain's too, before the others' whole sweeps are spent on it.
pub(super) struct CellSweep<'a, 'e, 'v> {
    motions: Vec<SweepAtRest<'a, 'e, 'v>>,
    /// The cell's index of each motion swept (an axis-range grid is not).
    swept: Vec<usize>,
    order: Vec<usize>,
}

impl<'a, 'e, 'v> CellSweep<'a, 'e, 'v> {
    /// The sweep of every motion of `cell` with `evaluator`, each motion's whole cable
    /// checked at rest as the motion test with `test` options checks it.
    pub(super) fn new(
        evaluator: &'e Evaluator<'v>,
        setup: &'a Setup,
        cell: &'a Cell,
        test: &MotionTestOptions,
    ) -> Result<Self, SolveError> {
        let sweep = |motion: &'a Motion| -> Result<SweepAtRest<'a, 'e, 'v>, SolveError> {
            let pieces = MotionSweep::new(evaluator, motion)?;
            Ok(SweepAtRest::new(pieces, setup, motion, test))
        };
        // An axis-range grid's poses are each piece's own, tested by the attachment test.
        let swept: Vec<usize> = (0..cell.len())
            .filter(|&i| cell.motions[i].grid.is_none())
            .collect();
        let motions = (swept.iter())
            .map(|&i| sweep(&cell.motions[i].motion))
            .collect::<Result<_, _>>()?;
        let order = (0..swept.len()).collect();
        Ok(CellSweep {
            motions,
            swept,
            order,
        })
    }

    /// Distinct poses a piece is solved at, over every motion.
    pub(super) fn pose_count(&self) -> usize {
        self.motions.iter().map(|s| s.pieces.pose_count()).sum()
    }
}

impl ChainSweep for CellSweep<'_, '_, '_> {
    fn failing(
        &mut self,
        path: &CablePath,
        stops: &[Option<SweptLeast>],
    ) -> Result<Vec<Dropped>, SolveError> {
        for k in 0..self.order.len() {
            let i = self.order[k];
            let mut failed = self.motions[i].failing(path, stops)?;
            if !failed.is_empty() {
                for (_, _, failure) in &mut failed {
                    failure.motion = self.swept[i];
                }
                self.order[..=k].rotate_right(1);
                return Ok(failed);
            }
        }
        Ok(Vec::new())
    }

    fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast> {
        let each = self.motions.iter().filter_map(|s| s.least(m, pv));
        each.reduce(SweptLeast::least_with)
    }

    fn least_in(&self, motion: usize, m: usize, pv: &Pv) -> Option<SweptLeast> {
        let i = self.swept.iter().position(|&k| k == motion)?;
        self.motions[i].least(m, pv)
    }

    fn swept(&self) -> usize {
        self.motions
            .iter()
            .map(ChainSweep::swept)
            .max()
            .unwrap_or(0)
    }
}

/// The static sweep as the search uses it: the pieces of a chain that fail it, and the least
/// values each piece swept met.
pub(super) trait ChainSweep {
    /// The pieces of `path` that fail the sweep, piece by piece; a piece's sweep may stop as
    /// soon as a least value falls below its entry in `stops` (one per piece, in order).
    fn failing(
        &mut self,
        path: &CablePath,
        stops: &[Option<SweptLeast>],
    ) -> Result<Vec<Dropped>, SolveError>;
    /// The least bend radius and clearance of a swept piece.
    fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast>;
    /// The same over motion `motion` of a cell alone.
    fn least_in(&self, motion: usize, m: usize, pv: &Pv) -> Option<SweptLeast> {
        let _ = motion;
        self.least(m, pv)
    }
    /// Pieces swept so far.
    fn swept(&self) -> usize;
}

impl ChainSweep for MotionSweep<'_, '_> {
    fn failing(
        &mut self,
        path: &CablePath,
        stops: &[Option<SweptLeast>],
    ) -> Result<Vec<Dropped>, SolveError> {
        let pvs: Vec<(usize, Pv, Option<SweptLeast>)> = (path.pieces().zip(stops))
            .map(|((m, pv), stop)| (m, pv, *stop))
            .collect();
        let failures = self.check_until(&pvs);
        let failed = pvs.iter().zip(failures);
        Ok(failed
            .filter_map(|(&(m, pv, _), failure)| Some((m, pv, failure?)))
            .collect())
    }

    fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast> {
        MotionSweep::least(self, m, pv)
    }

    fn swept(&self) -> usize {
        MotionSweep::swept(self)
    }
}
