//! The shortest chain of PVs through the guides' configurations (an element of the paper's
//! D3), the next-shortest ones in order, and the number of chains.
//!
//! Guides `G_0 … G_M` are joined by segments `C_0 … C_(M-1)`; segment `m` has a set of
//! admissible PVs (D2,m). A *chain* takes one PV per segment such that consecutive PVs agree
//! on their shared guide. Seen as a layered graph — layer `g` holds the configurations of
//! guide `g`, every PV of segment `m` is an edge from layer `m` to layer `m + 1` weighing its
//! `sub_segments` — a chain is a path from layer 0 to layer M, so the shortest chain and the
//! count come from dynamic programming instead of enumerating the (astronomically many)
//! chains.
//!
//! **Determinism.** Chains are totally ordered by total length, then lexicographically by
//! their PV sequence (segment 0 first) under [`Pv`]'s derived order. The shortest chain is the
//! minimum of that order and [`ChainSearch::k_best`] follows it exactly, so results depend
//! neither on the order of the input PV lists nor on duplicates in them.
//!
//! **Complexity** (E PVs in all, C configurations in all, M segments):
//! - [`ChainSearch::new`]: O(E log E + C) time, O(E + C) memory;
//! - [`ChainSearch::shortest`]: O(M); [`ChainSearch::chain_count`]: O(1) (counted in `new`);
//! - the first k chains of [`ChainSearch::k_best`]: O(k·M²·log(k·M)) time and O(k·M²)
//!   memory, independent of how many chains there are.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::fmt;
use std::iter::FusedIterator;

use crate::path::{CablePath, Pv};

/// Which configuration of a PV is at fault in [`ChainError::OutOfRange`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PvSide {
    /// `Pv::start`, a configuration of the segment's first guide.
    Start,
    /// `Pv::end`, a configuration of the segment's second guide.
    End,
}

impl fmt::Display for PvSide {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PvSide::Start => "start",
            PvSide::End => "end",
        })
    }
}

/// Inputs that do not describe a layered graph of guides and segments.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ChainError {
    /// A cable path has at least one segment.
    #[error("no segments: a chain needs at least one segment")]
    NoSegments,
    /// `config_counts` must have one entry per guide, one more than there are segments.
    #[error(
        "{guides} guide configuration counts for {segments} segments: expected {}",
        .segments + 1
    )]
    LengthMismatch {
        /// `config_counts.len()`.
        guides: usize,
        /// `segments.len()`.
        segments: usize,
    },
    /// A PV names a configuration its guide does not have.
    #[error(
        "segment {segment}, PV {pv_index} ({pv:?}): {side} configuration {configuration} is out \
         of range for guide {guide}, which has {config_count} configurations"
    )]
    OutOfRange {
        /// The segment whose PV list holds the PV.
        segment: usize,
        /// Position of the PV in that list, as given.
        pv_index: usize,
        /// The PV itself.
        pv: Pv,
        /// Which of its two configurations is out of range.
        side: PvSide,
        /// The guide that configuration belongs to.
        guide: usize,
        /// The offending configuration index.
        configuration: usize,
        /// The number of configurations of that guide (the exclusive bound).
        config_count: usize,
    },
}

/// A live PV (part of at least one complete chain) with its rank key.
#[derive(Debug, Clone, Copy)]
struct Edge {
    pv: Pv,
    /// `sub_segments` plus the shortest suffix from `pv.end`: the length of the shortest
    /// chain remainder that starts with this PV. u128 so that summing M lengths cannot
    /// overflow.
    through: u128,
}

/// The layered graph of one problem, reduced to its live PVs; built once, queried many times.
#[derive(Debug, Clone)]
pub struct ChainSearch {
    segment_count: usize,
    /// The live PVs of segment 0 ranked by (`through`, PV): every chain starts with one.
    roots: Vec<Edge>,
    /// `out[m][c]` for m ≥ 1: live PVs of segment m leaving configuration c, ranked by
    /// (`through`, PV). `out[0]` is empty, [`Self::roots`] stands for it.
    out: Vec<Vec<Vec<Edge>>>,
    /// Per guide, the configurations some complete chain passes through, ascending.
    used: Vec<Vec<usize>>,
    /// |D3|, saturated at `u128::MAX`.
    count: u128,
}

impl ChainSearch {
    /// Builds the search; `segments[m]` lists the admissible PVs of segment `m` in any order,
    /// duplicates allowed.
    ///
    /// `config_counts.len()` must be `segments.len() + 1`, and every PV of segment `m` must
    /// have `start < config_counts[m]` and `end < config_counts[m + 1]`. A segment without
    /// PVs is not an error: there is simply no chain.
    pub fn new(config_counts: &[usize], segments: &[Vec<Pv>]) -> Result<ChainSearch, ChainError> {
        validate(config_counts, segments)?;
        let segments: Vec<Vec<Pv>> = segments.iter().map(|pvs| sorted_unique(pvs)).collect();
        let suffix = best_suffixes(config_counts, &segments);
        let reach = reachable(config_counts, &segments);
        let roots = ranked(segments[0].iter(), &suffix[1]);
        let mut out = vec![Vec::new()];
        for m in 1..segments.len() {
            out.push(ranked_by_start(&segments[m], &reach[m], &suffix[m + 1]));
        }
        let used = reach
            .iter()
            .zip(&suffix)
            .map(|(reached, best)| {
                (0..reached.len())
                    .filter(|&c| reached[c] && best[c].is_some())
                    .collect()
            })
            .collect();
        Ok(ChainSearch {
            segment_count: segments.len(),
            roots,
            out,
            used,
            count: count_chains(config_counts, &segments),
        })
    }

    /// The minimum chain of the total order (shortest, then lexicographically smallest PV
    /// sequence), or `None` when no chain exists.
    pub fn shortest(&self) -> Option<CablePath> {
        // Lists are ranked by (exact remaining length, PV), so following first entries is
        // both shortest and, among equally short chains, lexicographically smallest.
        let mut edge = self.roots.first()?;
        let mut pvs = vec![edge.pv];
        for m in 1..self.segment_count {
            edge = self.siblings(m, edge.pv.end).first()?;
            pvs.push(edge.pv);
        }
        CablePath::from_pvs(&pvs)
    }

    /// The number of chains |D3| (distinct PVs only), saturated at `u128::MAX`.
    pub fn chain_count(&self) -> u128 {
        self.count
    }

    /// All chains in increasing total order (non-decreasing length, ties lexicographic by PV
    /// sequence), produced lazily: for a fallback when the shortest fails a later test.
    pub fn k_best(&self) -> KBest<'_> {
        let mut heap = BinaryHeap::new();
        if let Some(first) = self.roots.first() {
            heap.push(Reverse(Prefix {
                bound: first.through,
                pvs: vec![first.pv],
                length: first.pv.sub_segments as u128,
                rank: 0,
            }));
        }
        KBest { search: self, heap }
    }

    /// Configurations of guide `g` used by at least one complete chain, ascending (for
    /// adjacency reporting); empty when there is no chain or no guide `g`.
    pub fn used_configurations(&self, g: usize) -> Vec<usize> {
        self.used.get(g).cloned().unwrap_or_default()
    }

    /// The ranked live PVs of segment `m` leaving configuration `start` (all of segment 0's
    /// for m = 0, where every configuration starts a chain).
    fn siblings(&self, m: usize, start: usize) -> &[Edge] {
        if m == 0 {
            &self.roots
        } else {
            &self.out[m][start]
        }
    }
}

/// Refuses inputs that are not a layered graph, naming the first offending PV.
fn validate(config_counts: &[usize], segments: &[Vec<Pv>]) -> Result<(), ChainError> {
    if segments.is_empty() {
        return Err(ChainError::NoSegments);
    }
    if config_counts.len() != segments.len() + 1 {
        return Err(ChainError::LengthMismatch {
            guides: config_counts.len(),
            segments: segments.len(),
        });
    }
    for (segment, pvs) in segments.iter().enumerate() {
        for (pv_index, &pv) in pvs.iter().enumerate() {
            let sides = [
                (PvSide::Start, segment, pv.start),
                (PvSide::End, segment + 1, pv.end),
            ];
            for (side, guide, configuration) in sides {
                if configuration >= config_counts[guide] {
                    return Err(ChainError::OutOfRange {
                        segment,
                        pv_index,
                        pv,
                        side,
                        guide,
                        configuration,
                        config_count: config_counts[guide],
                    });
                }
            }
        }
    }
    Ok(())
}

/// The PVs sorted and deduplicated, so that nothing downstream depends on input order.
fn sorted_unique(pvs: &[Pv]) -> Vec<Pv> {
    let mut pvs = pvs.to_vec();
    pvs.sort_unstable();
    pvs.dedup();
    pvs
}

/// `suffix[g][c]`: length of the shortest chain remainder from configuration `c` of guide `g`
/// to the last guide (0 at the last guide, `None` when there is none).
fn best_suffixes(config_counts: &[usize], segments: &[Vec<Pv>]) -> Vec<Vec<Option<u128>>> {
    let last = segments.len();
    let mut suffix = vec![Vec::new(); last + 1];
    suffix[last] = vec![Some(0); config_counts[last]];
    for m in (0..last).rev() {
        let mut best: Vec<Option<u128>> = vec![None; config_counts[m]];
        for pv in &segments[m] {
            if let Some(rest) = suffix[m + 1][pv.end] {
                let through = pv.sub_segments as u128 + rest;
                let slot = &mut best[pv.start];
                *slot = Some(slot.map_or(through, |b| b.min(through)));
            }
        }
        suffix[m] = best;
    }
    suffix
}

/// `reach[g][c]`: some chain prefix runs from guide 0 to configuration `c` of guide `g`
/// (every configuration of guide 0 trivially).
fn reachable(config_counts: &[usize], segments: &[Vec<Pv>]) -> Vec<Vec<bool>> {
    let mut reach: Vec<Vec<bool>> = config_counts.iter().map(|&n| vec![false; n]).collect();
    reach[0].fill(true);
    for (m, pvs) in segments.iter().enumerate() {
        for pv in pvs {
            if reach[m][pv.start] {
                reach[m + 1][pv.end] = true;
            }
        }
    }
    reach
}

/// The PVs that can be completed to the last guide, ranked by (`through`, PV): the order in
/// which [`KBest`] tries siblings and [`ChainSearch::shortest`] picks the first.
fn ranked<'a>(pvs: impl Iterator<Item = &'a Pv>, suffix_next: &[Option<u128>]) -> Vec<Edge> {
    let mut edges: Vec<Edge> = pvs
        .filter_map(|&pv| {
            let rest = suffix_next[pv.end]?;
            Some(Edge {
                pv,
                through: pv.sub_segments as u128 + rest,
            })
        })
        .collect();
    edges.sort_unstable_by_key(|edge| (edge.through, edge.pv));
    edges
}

/// One segment's live PVs grouped by start configuration and ranked; PVs leaving a
/// configuration no prefix reaches are dropped (dead ends backwards).
fn ranked_by_start(pvs: &[Pv], reached: &[bool], suffix_next: &[Option<u128>]) -> Vec<Vec<Edge>> {
    let mut by_start: Vec<Vec<Pv>> = vec![Vec::new(); reached.len()];
    for &pv in pvs.iter().filter(|pv| reached[pv.start]) {
        by_start[pv.start].push(pv);
    }
    by_start
        .iter()
        .map(|pvs| ranked(pvs.iter(), suffix_next))
        .collect()
}

/// |D3| by backward DP: `ways[c]` counts the chain remainders from configuration `c`; PVs
/// from unreachable configurations only feed counts that never reach guide 0.
fn count_chains(config_counts: &[usize], segments: &[Vec<Pv>]) -> u128 {
    let mut ways = vec![1u128; config_counts[segments.len()]];
    for (m, pvs) in segments.iter().enumerate().rev() {
        let mut here = vec![0u128; config_counts[m]];
        for pv in pvs {
            here[pv.start] = here[pv.start].saturating_add(ways[pv.end]);
        }
        ways = here;
    }
    ways.into_iter().fold(0, u128::saturating_add)
}

/// A chain prefix in the best-first search of [`KBest`].
///
/// Ordered by (`bound`, `pvs`) — the derived order's later fields never decide because no two
/// prefixes share their PVs. `bound` is exact (the shortest completion), so this key never
/// decreases from a prefix to its first child or its next sibling, and complete chains are
/// popped in exactly the total order.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Prefix {
    /// Length of the shortest complete chain starting with `pvs`.
    bound: u128,
    /// PVs of segments `0..pvs.len()`, never empty.
    pvs: Vec<Pv>,
    /// Total `sub_segments` of `pvs`.
    length: u128,
    /// Position of the last PV in its ranked sibling list.
    rank: usize,
}

/// Iterator over all chains in increasing total order, see [`ChainSearch::k_best`].
///
/// Best-first search over prefixes. Each prefix has one generator: its previous sibling in
/// the ranked list, or (first siblings) its parent prefix. A pop therefore pushes at most two
/// prefixes — the next sibling and the first child — so the heap grows with the number of
/// chains taken, not with the degree of the graph or the number of chains.
#[derive(Debug, Clone)]
pub struct KBest<'a> {
    search: &'a ChainSearch,
    heap: BinaryHeap<Reverse<Prefix>>,
}

impl KBest<'_> {
    /// Pushes the prefix that differs from `prefix` only by the next-ranked last PV.
    fn push_sibling(&mut self, prefix: &Prefix) {
        let Some(&last) = prefix.pvs.last() else {
            return;
        };
        let m = prefix.pvs.len() - 1;
        let Some(next) = self.search.siblings(m, last.start).get(prefix.rank + 1) else {
            return;
        };
        let base = prefix.length - last.sub_segments as u128;
        let mut pvs = prefix.pvs.clone();
        pvs[m] = next.pv;
        self.heap.push(Reverse(Prefix {
            bound: base + next.through,
            pvs,
            length: base + next.pv.sub_segments as u128,
            rank: prefix.rank + 1,
        }));
    }

    /// Pushes `prefix` extended by the first-ranked PV of the next segment (same bound).
    fn push_first_child(&mut self, mut prefix: Prefix) {
        let Some(&last) = prefix.pvs.last() else {
            return;
        };
        // Every live PV ends at a configuration with a live continuation, so this list is
        // not empty; `else` only guards the invariant.
        let Some(first) = self.search.siblings(prefix.pvs.len(), last.end).first() else {
            return;
        };
        prefix.pvs.push(first.pv);
        prefix.bound = prefix.length + first.through;
        prefix.length += first.pv.sub_segments as u128;
        prefix.rank = 0;
        self.heap.push(Reverse(prefix));
    }
}

impl Iterator for KBest<'_> {
    type Item = CablePath;

    fn next(&mut self) -> Option<CablePath> {
        while let Some(Reverse(prefix)) = self.heap.pop() {
            self.push_sibling(&prefix);
            if prefix.pvs.len() == self.search.segment_count {
                // Consecutive PVs agree by construction (each is taken from the list of
                // its predecessor's end), so this is always `Some`.
                return CablePath::from_pvs(&prefix.pvs);
            }
            self.push_first_child(prefix);
        }
        None
    }
}

impl FusedIterator for KBest<'_> {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dead_ends_are_pruned_from_both_sides() {
        // Guide 1 has configurations 0, 1, 2. Configuration 1 is entered but has no way on;
        // configuration 2 leaves but is never entered. Only configuration 0 carries chains.
        let search = ChainSearch::new(
            &[1, 3, 1],
            &[
                vec![Pv::new(1, 0, 0), Pv::new(1, 0, 1)],
                vec![Pv::new(2, 0, 0), Pv::new(9, 0, 0), Pv::new(1, 2, 0)],
            ],
        )
        .expect("valid");
        assert_eq!(search.used_configurations(1), vec![0]);
        assert_eq!(search.roots.len(), 1, "the PV into configuration 1 is dead");
        assert!(
            search.out[1][2].is_empty(),
            "the PV out of configuration 2 is dead"
        );
        assert_eq!(search.chain_count(), 2);
        let lengths: Vec<usize> = search.k_best().map(|p| p.total_sub_segments()).collect();
        assert_eq!(lengths, vec![3, 10]);
    }

    #[test]
    fn count_saturates_instead_of_overflowing() {
        // 130 segments with two parallel PVs each: 2^130 chains > u128::MAX.
        let segments = vec![vec![Pv::new(1, 0, 0), Pv::new(2, 0, 0)]; 130];
        let search = ChainSearch::new(&[1; 131], &segments).expect("valid");
        assert_eq!(search.chain_count(), u128::MAX);
        let shortest = search.shortest().expect("a chain");
        assert_eq!(shortest.total_sub_segments(), 130);
        // The second chain differs in the last segment only: lexicographically next.
        let second = search.k_best().nth(1).expect("a second chain");
        assert_eq!(second.total_sub_segments(), 131);
        assert_eq!(second.lengths[129], 2);
    }

    #[test]
    fn a_guide_without_configurations_has_no_chain() {
        let search = ChainSearch::new(&[1, 0, 1], &[vec![], vec![]]).expect("valid");
        assert_eq!(search.chain_count(), 0);
        assert_eq!(search.shortest(), None);
        assert_eq!(search.k_best().next(), None);
        assert!(search.used_configurations(0).is_empty());
        assert!(search.used_configurations(7).is_empty());
    }
}
