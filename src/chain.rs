//! The shortest chain of PVs through the guides' configurations (an element of the paper's
//! D3), the next-shortest ones in order, and the number of chains.
//!
//! Guides `G_0 … G_M` are joined by *pieces*: the declared segments `C_m` from guide `m` to
//! `m + 1`, and, where guides are optional, spans that jump over them (from guide `a` to guide
//! `b > a + 1`). Piece `p` has a set of admissible PVs (D2,p). A *chain* is a sequence of
//! pieces from guide 0 to guide M, each starting where the previous one ends, with one PV
//! each that agrees with its neighbours on their shared guide. Seen as a graph — a node per
//! configuration of a guide, every PV of piece `p` an edge from its start guide's
//! configuration to its end guide's, weighing its `sub_segments` — a chain is a path from
//! guide 0 to guide M. Edges only run towards the tool end, so the graph has no cycle and the
//! shortest chain and the count come from dynamic programming over the guides instead of
//! enumerating the (astronomically many) chains.
//!
//! **Determinism.** Chains are totally ordered by total length, then lexicographically by
//! their sequence of (PV, piece) pairs (first piece first) under [`Pv`]'s derived order. The
//! shortest chain is the minimum of that order and [`ChainSearch::k_best`] follows it
//! exactly, so results depend neither on the order of the input PV lists nor on duplicates in
//! them.
//!
//! **Complexity** (E PVs in all, C configurations in all, M + 1 guides):
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
    /// A piece must run from a guide to a later one among the guides counted.
    #[error("piece {piece} runs from guide {start} to guide {end}, of {guides} guides")]
    PieceEnds {
        /// The piece.
        piece: usize,
        /// Its start guide.
        start: usize,
        /// Its end guide.
        end: usize,
        /// Number of guides.
        guides: usize,
    },
    /// One list of PVs per piece.
    #[error("{ends} piece ends for {pieces} lists of PVs")]
    PieceCount {
        /// Number of `(start, end)` guide pairs.
        ends: usize,
        /// Number of PV lists.
        pieces: usize,
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
    /// The piece it belongs to.
    piece: usize,
    /// `sub_segments` plus the shortest suffix from `pv.end`: the length of the shortest
    /// chain remainder that starts with this PV. u128 so that summing lengths cannot
    /// overflow.
    through: u128,
}

/// The graph of one problem, reduced to its live PVs; built once, queried many times.
#[derive(Debug, Clone)]
pub struct ChainSearch {
    /// Start and end guide of every piece.
    ends: Vec<(usize, usize)>,
    /// Index of the last guide.
    last: usize,
    /// The live PVs leaving guide 0, ranked by (`through`, PV, piece): every chain starts
    /// with one.
    roots: Vec<Edge>,
    /// `out[g][c]` for g ≥ 1: live PVs leaving configuration c of guide g, ranked by
    /// (`through`, PV, piece). `out[0]` is empty, [`Self::roots`] stands for it.
    out: Vec<Vec<Vec<Edge>>>,
    /// Per guide, the configurations some complete chain passes through, ascending.
    used: Vec<Vec<usize>>,
    /// |D3|, saturated at `u128::MAX`.
    count: u128,
}

impl ChainSearch {
    /// Builds the search over consecutive segments: `segments[m]` lists the admissible PVs
    /// of the segment from guide `m` to guide `m + 1`, in any order, duplicates allowed.
    ///
    /// `config_counts.len()` must be `segments.len() + 1`, and every PV of segment `m` must
    /// have `start < config_counts[m]` and `end < config_counts[m + 1]`. A segment without
    /// PVs is not an error: there is simply no chain.
    pub fn new(config_counts: &[usize], segments: &[Vec<Pv>]) -> Result<ChainSearch, ChainError> {
        if segments.is_empty() {
            return Err(ChainError::NoSegments);
        }
        if config_counts.len() != segments.len() + 1 {
            return Err(ChainError::LengthMismatch {
                guides: config_counts.len(),
                segments: segments.len(),
            });
        }
        let ends: Vec<(usize, usize)> = (0..segments.len()).map(|m| (m, m + 1)).collect();
        ChainSearch::over(config_counts, &ends, segments)
    }

    /// Builds the search over pieces that may jump over guides: piece `p` runs from guide
    /// `ends[p].0` to guide `ends[p].1` (later), with the admissible PVs `pieces[p]` in any
    /// order, duplicates allowed. Chains run from guide 0 to the last guide
    /// (`config_counts.len() − 1`).
    pub fn over(
        config_counts: &[usize],
        ends: &[(usize, usize)],
        pieces: &[Vec<Pv>],
    ) -> Result<ChainSearch, ChainError> {
        validate(config_counts, ends, pieces)?;
        let pieces: Vec<Vec<Pv>> = pieces.iter().map(|pvs| sorted_unique(pvs)).collect();
        let graph = Graph {
            config_counts,
            ends,
            pieces: &pieces,
            last: config_counts.len() - 1,
        };
        let suffix = graph.best_suffixes();
        let reach = graph.reachable();
        let mut roots = Vec::new();
        let mut out: Vec<Vec<Vec<Edge>>> =
            config_counts.iter().map(|&n| vec![Vec::new(); n]).collect();
        for (p, pvs) in pieces.iter().enumerate() {
            let (start, end) = ends[p];
            for &pv in pvs.iter().filter(|pv| reach[start][pv.start]) {
                let Some(rest) = suffix[end][pv.end] else {
                    continue;
                };
                let edge = Edge {
                    pv,
                    piece: p,
                    through: pv.sub_segments as u128 + rest,
                };
                if start == 0 {
                    roots.push(edge);
                } else {
                    out[start][pv.start].push(edge);
                }
            }
        }
        rank(&mut roots);
        out.iter_mut().flatten().for_each(|edges| rank(edges));
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
            ends: ends.to_vec(),
            last: graph.last,
            roots,
            out,
            used,
            count: graph.count_chains(),
        })
    }

    /// The minimum chain of the total order (shortest, then lexicographically smallest
    /// sequence), or `None` when no chain exists.
    pub fn shortest(&self) -> Option<CablePath> {
        // Lists are ranked by (exact remaining length, PV, piece), so following first
        // entries is both shortest and, among equally short chains, lexicographically
        // smallest.
        let mut edge = self.roots.first()?;
        let mut chain = vec![*edge];
        while self.ends[edge.piece].1 != self.last {
            edge = self.out[self.ends[edge.piece].1][edge.pv.end].first()?;
            chain.push(*edge);
        }
        self.path(&chain)
    }

    /// The number of chains |D3| (distinct PVs only), saturated at `u128::MAX`.
    pub fn chain_count(&self) -> u128 {
        self.count
    }

    /// All chains in increasing total order (non-decreasing length, ties lexicographic by
    /// sequence), produced lazily: for a fallback when the shortest fails a later test.
    pub fn k_best(&self) -> KBest<'_> {
        let mut heap = BinaryHeap::new();
        if let Some(first) = self.roots.first() {
            heap.push(Reverse(Prefix {
                bound: first.through,
                steps: vec![(first.pv, first.piece)],
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

    /// The ranked live PVs leaving configuration `config` of guide `guide` (all of guide 0's
    /// for guide 0, where every configuration starts a chain).
    fn siblings(&self, guide: usize, config: usize) -> &[Edge] {
        if guide == 0 {
            &self.roots
        } else {
            &self.out[guide][config]
        }
    }

    /// The path of consecutive edges (they agree on shared guides by construction).
    fn path(&self, chain: &[Edge]) -> Option<CablePath> {
        let pieces: Vec<(usize, Pv)> = chain.iter().map(|e| (e.piece, e.pv)).collect();
        CablePath::from_pieces(&pieces)
    }
}

/// Ranks edges by (`through`, PV, piece): the order in which [`KBest`] tries siblings and
/// [`ChainSearch::shortest`] picks the first.
fn rank(edges: &mut [Edge]) {
    edges.sort_unstable_by_key(|edge| (edge.through, edge.pv, edge.piece));
}

/// Refuses inputs that are not a graph of guides and pieces, naming the first offending
/// piece or PV.
fn validate(
    config_counts: &[usize],
    ends: &[(usize, usize)],
    pieces: &[Vec<Pv>],
) -> Result<(), ChainError> {
    if pieces.is_empty() {
        return Err(ChainError::NoSegments);
    }
    if ends.len() != pieces.len() {
        return Err(ChainError::PieceCount {
            ends: ends.len(),
            pieces: pieces.len(),
        });
    }
    let guides = config_counts.len();
    for (piece, (&(start, end), pvs)) in ends.iter().zip(pieces).enumerate() {
        if !(start < end && end < guides) {
            return Err(ChainError::PieceEnds {
                piece,
                start,
                end,
                guides,
            });
        }
        for (pv_index, &pv) in pvs.iter().enumerate() {
            let sides = [(PvSide::Start, start, pv.start), (PvSide::End, end, pv.end)];
            for (side, guide, configuration) in sides {
                if configuration >= config_counts[guide] {
                    return Err(ChainError::OutOfRange {
                        segment: piece,
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

/// The validated graph, for the dynamic programs over it.
struct Graph<'a> {
    config_counts: &'a [usize],
    ends: &'a [(usize, usize)],
    pieces: &'a [Vec<Pv>],
    last: usize,
}

impl Graph<'_> {
    /// The pieces leaving guide `g` with their PVs.
    fn leaving(&self, g: usize) -> impl Iterator<Item = (usize, &[Pv])> + '_ {
        self.ends
            .iter()
            .zip(self.pieces)
            .filter(move |((start, _), _)| *start == g)
            .map(|(&(_, end), pvs)| (end, pvs.as_slice()))
    }

    /// `suffix[g][c]`: length of the shortest chain remainder from configuration `c` of
    /// guide `g` to the last guide (0 at the last guide, `None` when there is none).
    fn best_suffixes(&self) -> Vec<Vec<Option<u128>>> {
        let mut suffix: Vec<Vec<Option<u128>>> =
            self.config_counts.iter().map(|&n| vec![None; n]).collect();
        suffix[self.last].fill(Some(0));
        // Pieces run towards later guides: every suffix a guide needs is final by then.
        for g in (0..self.last).rev() {
            for (end, pvs) in self.leaving(g) {
                for pv in pvs {
                    if let Some(rest) = suffix[end][pv.end] {
                        let through = pv.sub_segments as u128 + rest;
                        let slot = &mut suffix[g][pv.start];
                        *slot = Some(slot.map_or(through, |b| b.min(through)));
                    }
                }
            }
        }
        suffix
    }

    /// `reach[g][c]`: some chain prefix runs from guide 0 to configuration `c` of guide `g`
    /// (every configuration of guide 0 trivially).
    fn reachable(&self) -> Vec<Vec<bool>> {
        let mut reach: Vec<Vec<bool>> =
            self.config_counts.iter().map(|&n| vec![false; n]).collect();
        reach[0].fill(true);
        for g in 0..self.last {
            for (end, pvs) in self.leaving(g) {
                for pv in pvs {
                    if reach[g][pv.start] {
                        reach[end][pv.end] = true;
                    }
                }
            }
        }
        reach
    }

    /// |D3| by backward DP: `ways[g][c]` counts the chain remainders from configuration `c`
    /// of guide `g`; PVs from unreachable configurations only feed counts that never reach
    /// guide 0.
    fn count_chains(&self) -> u128 {
        let mut ways: Vec<Vec<u128>> = self.config_counts.iter().map(|&n| vec![0; n]).collect();
        ways[self.last].fill(1);
        for g in (0..self.last).rev() {
            for (end, pvs) in self.leaving(g) {
                for pv in pvs {
                    ways[g][pv.start] = ways[g][pv.start].saturating_add(ways[end][pv.end]);
                }
            }
        }
        ways[0].iter().copied().fold(0, u128::saturating_add)
    }
}

/// A chain prefix in the best-first search of [`KBest`].
///
/// Ordered by (`bound`, `steps`) — the derived order's later fields never decide because no
/// two prefixes share their steps. `bound` is exact (the shortest completion), so this key
/// never decreases from a prefix to its first child or its next sibling, and complete chains
/// are popped in exactly the total order.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Prefix {
    /// Length of the shortest complete chain starting with `steps`.
    bound: u128,
    /// (PV, piece) of the chain's first pieces, never empty.
    steps: Vec<(Pv, usize)>,
    /// Total `sub_segments` of `steps`.
    length: u128,
    /// Position of the last step in its ranked sibling list.
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
    /// Pushes the prefix that differs from `prefix` only by the next-ranked last step.
    fn push_sibling(&mut self, prefix: &Prefix) {
        let Some(&(last, piece)) = prefix.steps.last() else {
            return;
        };
        let start = self.search.ends[piece].0;
        let Some(next) = self.search.siblings(start, last.start).get(prefix.rank + 1) else {
            return;
        };
        let base = prefix.length - last.sub_segments as u128;
        let mut steps = prefix.steps.clone();
        if let Some(step) = steps.last_mut() {
            *step = (next.pv, next.piece);
        }
        self.heap.push(Reverse(Prefix {
            bound: base + next.through,
            steps,
            length: base + next.pv.sub_segments as u128,
            rank: prefix.rank + 1,
        }));
    }

    /// Pushes `prefix` extended by the first-ranked PV leaving its end (same bound).
    fn push_first_child(&mut self, mut prefix: Prefix) {
        let Some(&(last, piece)) = prefix.steps.last() else {
            return;
        };
        // Every live PV ends at a configuration with a live continuation, so this list is
        // not empty; `else` only guards the invariant.
        let end = self.search.ends[piece].1;
        let Some(first) = self.search.siblings(end, last.end).first() else {
            return;
        };
        prefix.steps.push((first.pv, first.piece));
        prefix.bound = prefix.length + first.through;
        prefix.length += first.pv.sub_segments as u128;
        prefix.rank = 0;
        self.heap.push(Reverse(prefix));
    }

    /// Whether the prefix reaches the last guide.
    fn complete(&self, prefix: &Prefix) -> bool {
        prefix
            .steps
            .last()
            .is_some_and(|&(_, piece)| self.search.ends[piece].1 == self.search.last)
    }
}

impl Iterator for KBest<'_> {
    type Item = CablePath;

    fn next(&mut self) -> Option<CablePath> {
        while let Some(Reverse(prefix)) = self.heap.pop() {
            self.push_sibling(&prefix);
            if self.complete(&prefix) {
                // Consecutive steps agree by construction (each is taken from the list of
                // its predecessor's end), so this is always `Some`.
                let pieces: Vec<(usize, Pv)> = prefix
                    .steps
                    .iter()
                    .map(|&(pv, piece)| (piece, pv))
                    .collect();
                return CablePath::from_pieces(&pieces);
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
