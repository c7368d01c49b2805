//! Where the search takes its chains from, shortest first: the fully decided sets of the exhaustive attachment test (`Decided`), or the lazy test widened in rounds until no undecided piece can make a shorter chain (`LazyChains`). The certification of a dictionary's pieces is a layer over either (`certify`).

use super::options::SolveError;
use crate::attachment::LazyAttachment;
use crate::chain::ChainSearch;
use crate::path::{CablePath, Pv};
use crate::setup::Setup;
use std::collections::BTreeSet;

/// The chain search over the sets `d2`, one per segment (declared ones and spans).
pub(super) fn chain_search(setup: &Setup, d2: &[Vec<Pv>]) -> Result<ChainSearch, SolveError> {
    let (counts, ends) = (setup.configuration_counts(), setup.segment_ends());
    Ok(ChainSearch::over(&counts, &ends, d2)?)
}

/// Where the search for d* takes its chains from.
pub(super) trait Chains {
    /// The shortest chain of robust pieces not dropped (ties broken as [`ChainSearch`]
    /// does); `None` when there is none.
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError>;
    /// Takes piece `pv` of segment `m` out of every later chain.
    fn drop_piece(&mut self, m: usize, pv: &Pv);
    /// The shortest chain of the robust pieces decided so far, not dropped, deciding nothing
    /// more: a chain as long as [`Chains::shortest`]'s or longer.
    fn shortest_known(&mut self) -> Result<Option<CablePath>, SolveError> {
        self.shortest()
    }
    /// Puts piece `pv` of segment `m`, dropped before, back into the later chains (a piece
    /// set aside on a guess, [`super::learn`]).
    fn restore_piece(&mut self, m: usize, pv: &Pv);
}

/// The chains of fully decided sets (the exhaustive attachment test).
pub(super) struct Decided<'s> {
    pub(super) setup: &'s Setup,
    pub(super) d2: Vec<Vec<Pv>>,
    /// Pieces taken out of the chains: `(segment, piece)`.
    pub(super) dropped: BTreeSet<(usize, Pv)>,
}

impl<'s> Decided<'s> {
    /// The chains of the sets `d2`, one per segment, nothing dropped yet.
    pub(super) fn new(setup: &'s Setup, d2: Vec<Vec<Pv>>) -> Self {
        Decided {
            setup,
            d2,
            dropped: BTreeSet::new(),
        }
    }
}

impl Chains for Decided<'_> {
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError> {
        let dropped = &self.dropped;
        let kept: Vec<Vec<Pv>> = (self.d2.iter().enumerate())
            .map(|(m, d2)| {
                let kept = d2.iter().filter(|pv| !dropped.contains(&(m, **pv)));
                kept.copied().collect()
            })
            .collect();
        Ok(chain_search(self.setup, &kept)?.shortest())
    }

    fn drop_piece(&mut self, m: usize, pv: &Pv) {
        self.dropped.insert((m, *pv));
    }

    fn restore_piece(&mut self, m: usize, pv: &Pv) {
        self.dropped.remove(&(m, *pv));
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

    fn restore_piece(&mut self, m: usize, pv: &Pv) {
        self.attachment.restore_piece(m, pv);
    }

    fn shortest_known(&mut self) -> Result<Option<CablePath>, SolveError> {
        Ok(chain_search(self.setup, &self.attachment.robust())?.shortest())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attachment::{ConnectMethod, Evaluator, SegmentPoses};
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
            let mut decided = Decided::new(&setup, d2.clone());
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
