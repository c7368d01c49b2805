//! The attachment test driven by the chain search: only the pieces some chain shorter than a
//! bound could use are evaluated, and the bound is widened until the shortest chain of robust
//! pieces is no longer than it (docs/architecture.md, "Lazy attachment test").
//!
//! Every candidate pair of guide configurations `(a, b)` of segment `m` has a *floor*: a
//! length below which none of its pieces can be robust — below the shortest length that
//! reaches between the clamps at every test pose, plus the robustness range (a shorter
//! neighbour would be too short), or below what is already known to fail. From the floors,
//! a dynamic program over the guides gives every configuration the shortest a chain can be
//! from the first guide to it (`before`) and from it to the last (`after`). A piece
//! `(S, a, b)` can be on a chain no longer than `L` only if `before(a) + S + after(b) ≤ L`;
//! [`LazyAttachment::widen_to`] decides those, up to each pair's first robust piece (a
//! longer one makes a longer chain through the same clamps), one segment at a time. Every
//! shortest chain no longer than `L` is then known, so the shortest known chain is the
//! shortest of all as soon as it is no longer than `L`.
//!
//! Verdicts do not depend on which lengths are asked for together, nor in which batches
//! ([`Evaluator::first_rejections`]), so the pieces decided here get exactly the verdicts of
//! the exhaustive test ([`super::attachment_test`]). Nor do they depend on the order of the
//! poses (each pose's lengths start from the connected geometry), so each segment's poses
//! are tried in the order of how many pieces they rejected in the earlier batches
//! ([`PoseOrder`]): a piece that fails, fails at the first pose it is solved at, mostly —
//! what an axis-range grid of thousands of poses per piece needs (the order changes the
//! pose a miss names, never a verdict).

use super::evaluate::Evaluator;
use super::jobs::{PairJob, evaluate_jobs, pair_jobs};
use super::lookup::{IntraLinkAnswer, LookupCounts, looked_up};
use super::memory::{Known, Learnt, Recall, VerdictMemory};
use super::poses::{SegmentPoses, TestPose};
use super::sets::{SegmentSets, Verdicts, robust_neighbours};
use super::verdict::Miss;
use crate::geometry::reaches;
use crate::path::Pv;
use crate::pose::Pose;
use crate::setup::Setup;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

/// A pair of guide configurations of one segment and what is known of its candidates.
#[derive(Debug, Clone)]
struct Pair {
    start: usize,
    end: usize,
    /// The candidates are the segment's zero-length one (coincident clamps) rather than its
    /// lengths above zero.
    coincident: bool,
    /// Candidates decided: the first `decided` of the pair's candidate lengths.
    decided: usize,
    /// The shortest length (sub-segments) that reaches between the clamps at every test
    /// pose: anything shorter is too short at one of them.
    reach: usize,
    /// The shortest decided candidate that is robust and not dropped.
    shortest_robust: Option<usize>,
}

/// One segment's pairs, verdicts and decided robust pieces.
#[derive(Debug)]
struct Segment {
    pairs: Vec<Pair>,
    /// The candidate lengths above zero, ascending.
    lengths: Vec<usize>,
    /// Whether zero is a candidate length (coincident clamps).
    zero: bool,
    verdicts: Verdicts,
    /// Robust candidates decided.
    robust: BTreeSet<Pv>,
    /// Robust pieces a later test failed: no longer on any chain.
    dropped: BTreeSet<Pv>,
    /// Worker time spent on this segment's pieces (s).
    busy_s: f64,
    lookup_counts: Option<LookupCounts>,
    /// The order its test poses are tried in.
    order: PoseOrder,
}

/// The order a segment's test poses are tried in: the poses that rejected most pieces
/// first (ties in the poses' own order), learned batch by batch — so the order, and with it
/// the work, is the same at any thread count.
#[derive(Debug)]
struct PoseOrder {
    /// Pieces each test pose rejected first.
    rejected: Vec<usize>,
    /// Test pose indices, the next batch's order.
    order: Vec<usize>,
}

impl PoseOrder {
    fn new(poses: usize) -> PoseOrder {
        PoseOrder {
            rejected: vec![0; poses],
            order: (0..poses).collect(),
        }
    }

    /// `poses` in this order.
    fn arrange<'p>(&self, poses: &'p [TestPose]) -> Vec<&'p TestPose> {
        self.order.iter().map(|&p| &poses[p]).collect()
    }

    /// Misses found over the arranged poses, their poses renumbered as the test poses.
    fn renumber(&self, misses: &mut [Option<Miss>]) {
        for miss in misses.iter_mut().flatten() {
            miss.pose = self.order[miss.pose];
        }
    }

    /// Counts the (renumbered) misses of a batch and reorders.
    fn learn<'m>(&mut self, misses: impl Iterator<Item = &'m Option<Miss>>) {
        let mut changed = false;
        for miss in misses.flatten() {
            if let Some(count) = self.rejected.get_mut(miss.pose) {
                *count += 1;
                changed = true;
            }
        }
        if changed {
            let rejected = &self.rejected;
            self.order = (0..rejected.len()).collect();
            self.order.sort_by_key(|&p| std::cmp::Reverse(rejected[p]));
        }
    }
}

impl Segment {
    /// Recomputes the shortest robust piece not dropped of the pair of `pv`.
    fn update_shortest_robust(&mut self, pv: &Pv) {
        let same_pair = |r: &&Pv| (r.start, r.end) == (pv.start, pv.end);
        let shortest = (self.robust.difference(&self.dropped))
            .filter(same_pair)
            .map(|r| r.sub_segments)
            .min();
        let pair = (self.pairs.iter_mut()).find(|p| (p.start, p.end) == (pv.start, pv.end));
        if let Some(pair) = pair {
            pair.shortest_robust = shortest;
        }
    }

    fn candidate_lengths(&self, pair: &Pair) -> &[usize] {
        match (pair.coincident, self.zero) {
            (true, true) => &[0],
            (true, false) => &[],
            (false, _) => &self.lengths,
        }
    }
}

/// The lazily evaluated attachment test of every segment of a setup over a motion's test
/// poses.
pub struct LazyAttachment<'r, 'a> {
    evaluator: &'r Evaluator<'a>,
    poses: &'r SegmentPoses,
    intra_link: Option<&'r IntraLinkAnswer<'r>>,
    /// What earlier solves learnt of each segment's pieces, read against these poses (empty:
    /// nothing remembered).
    recall: Vec<Option<Recall<'r>>>,
    segments: Vec<Segment>,
    /// Every candidate on a chain no longer than this (sub-segments) is decided.
    bound: Option<usize>,
    /// Wall time spent deciding so far, the bounds between batches included (s).
    wall_s: f64,
}

impl<'r, 'a> LazyAttachment<'r, 'a> {
    /// Nothing evaluated yet; the pairs' reach computed at every test pose. The intra-link
    /// segments' pieces are answered by `intra_link` (a dictionary's lookup) when given.
    pub fn new(
        evaluator: &'r Evaluator<'a>,
        poses: &'r SegmentPoses,
        intra_link: Option<&'r IntraLinkAnswer<'r>>,
    ) -> LazyAttachment<'r, 'a> {
        let setup = evaluator.setup();
        let segments = (0..setup.segment_count())
            .map(|m| {
                let lengths = &setup.segments[m].lengths;
                Segment {
                    pairs: pairs(evaluator, poses, m),
                    lengths: lengths.iter().copied().filter(|&s| s > 0).collect(),
                    zero: lengths.contains(&0),
                    verdicts: Verdicts::new(),
                    robust: BTreeSet::new(),
                    dropped: BTreeSet::new(),
                    busy_s: 0.0,
                    // A dictionary answers for rigid clamps only.
                    lookup_counts: (intra_link.is_some()
                        && setup.is_intra_link(m)
                        && setup.segment_is_rigid(m))
                    .then(LookupCounts::default),
                    order: PoseOrder::new(poses.poses[m].len()),
                }
            })
            .collect();
        LazyAttachment {
            evaluator,
            poses,
            intra_link,
            recall: Vec::new(),
            segments,
            bound: None,
            wall_s: 0.0,
        }
    }

    /// The same test, knowing what earlier solves of the setup learnt ([`VerdictMemory`]):
    /// a piece that held at their poses is tested only at the poses new to it, one that failed
    /// at a pose these have fails without a test. The segments a dictionary answers ignore
    /// it, and so do those held to the flexing radius over their poses
    /// ([`Evaluator::watches_flexing`]): whether a piece flexes depends on every pose of the
    /// list, not on one at a time.
    pub fn remembering(mut self, memory: &'r VerdictMemory) -> LazyAttachment<'r, 'a> {
        self.recall = memory.recall(self.poses);
        for (m, recall) in self.recall.iter_mut().enumerate() {
            if self.evaluator.watches_flexing(m) {
                *recall = None;
            }
        }
        self
    }

    /// What was decided, for the memory of the next solve ([`VerdictMemory::learn`]): the
    /// verdicts of the segments the evaluator tested (not those a dictionary answered).
    pub fn learnt(self) -> Learnt {
        Learnt(
            (self.segments.into_iter())
                .map(|s| s.lookup_counts.is_none().then_some(s.verdicts))
                .collect(),
        )
    }

    /// The setup under test.
    fn setup(&self) -> &'a Setup {
        self.evaluator.setup()
    }

    /// What evaluates the pieces.
    pub fn evaluator(&self) -> &'r Evaluator<'a> {
        self.evaluator
    }

    /// The test poses of every segment.
    pub fn poses(&self) -> &'r SegmentPoses {
        self.poses
    }

    /// The shortest any chain of robust pieces can be (sub-segments), from what is known so
    /// far; `None` when no chain is possible at all.
    pub fn lower_bound(&self) -> Option<usize> {
        let (before, _) = self.bounds();
        before.last()?.iter().copied().flatten().min()
    }

    /// The bound every candidate on a shorter chain is decided for, if any.
    pub fn bound(&self) -> Option<usize> {
        self.bound
    }

    /// The robust pieces decided so far, minus those dropped, per segment (sorted).
    pub fn robust(&self) -> Vec<Vec<Pv>> {
        self.segments
            .iter()
            .map(|s| s.robust.difference(&s.dropped).copied().collect())
            .collect()
    }

    /// Takes piece `pv` of segment `m` out of the chains (it failed a later test): its
    /// pair's floor rises accordingly.
    pub fn drop_piece(&mut self, m: usize, pv: &Pv) {
        if self.segments[m].robust.contains(pv) && self.segments[m].dropped.insert(*pv) {
            self.segments[m].update_shortest_robust(pv);
        }
    }

    /// Puts piece `pv` of segment `m`, dropped before, back on the chains: its pair's floor
    /// falls back. The pieces decided stay decided, so the bound still holds.
    pub fn restore_piece(&mut self, m: usize, pv: &Pv) {
        if self.segments[m].dropped.remove(pv) {
            self.segments[m].update_shortest_robust(pv);
        }
    }

    /// Decides every candidate, chain or no chain (what the exhaustive test decides, without
    /// its adjacency pruning): for a diagnosis when no path exists.
    pub fn decide_all(&mut self) {
        let everything: Deciding = self
            .segments
            .iter()
            .enumerate()
            .flat_map(|(m, segment)| {
                segment
                    .pairs
                    .iter()
                    .enumerate()
                    .map(move |(k, pair)| (m, k, segment.candidate_lengths(pair).len()))
            })
            .collect();
        let clock = Instant::now();
        self.decide_up_to(&everything, usize::MAX, Evaluate::Every);
        self.wall_s += clock.elapsed().as_secs_f64();
    }

    /// How many undecided candidates that can be robust each bound would decide: per chain
    /// length `L` (sub-segments), the number of those whose shortest chain through them
    /// (by the floors) is `L` — what a search weighs its next bound by.
    pub fn pending_by_bound(&self) -> BTreeMap<usize, usize> {
        let robustness = &self.setup().robustness;
        let mut pending = BTreeMap::new();
        for (_, _, segment, pair, around) in self.open_pairs() {
            let undecided = &segment.candidate_lengths(pair)[pair.decided..];
            for &s in undecided
                .iter()
                .filter(|&&s| feasible(s, pair.reach, robustness))
            {
                *pending.entry(around + s).or_insert(0) += 1;
            }
        }
        pending
    }

    /// Candidates decided so far.
    pub fn decided(&self) -> usize {
        self.segments
            .iter()
            .map(|segment| segment.pairs.iter().map(|pair| pair.decided).sum::<usize>())
            .sum()
    }

    /// Decides, for every pair of guide configurations that a chain no longer than `bound`
    /// sub-segments could use, its candidates up to its shortest robust piece (a longer one
    /// makes a longer chain through the same clamps): evaluates them and their robustness
    /// neighbours, in parallel batches, one segment at a time — the segment with the fewest
    /// such candidates first, because when its pieces fail, the chains through them and the
    /// other segments' pieces on those chains need no evaluation at all.
    pub fn widen_to(&mut self, bound: usize) {
        let clock = Instant::now();
        while let Some(deciding) = self.fewest_undecided(bound) {
            self.decide_up_to(&deciding, bound, Evaluate::Feasible);
        }
        self.bound = Some(self.bound.map_or(bound, |b| b.max(bound)));
        self.wall_s += clock.elapsed().as_secs_f64();
    }

    /// The undecided candidates of one segment that a chain no longer than `bound` could
    /// use, as `(segment, pair index, decide up to)`: those of the segment that has the
    /// fewest; `None` when no segment has any.
    fn fewest_undecided(&self, bound: usize) -> Option<Deciding> {
        self.undecided_per_segment(bound)
            .into_iter()
            .filter(|(count, _)| *count > 0)
            .min_by_key(|(count, _)| *count)
            .map(|(_, deciding)| deciding)
    }

    /// Per segment, how many undecided candidates that can be robust a chain no longer than
    /// `bound` could use, and their pairs as `(segment, pair index, decide up to)`.
    fn undecided_per_segment(&self, bound: usize) -> Vec<(usize, Deciding)> {
        let robustness = &self.setup().robustness;
        let mut by_segment: Vec<(usize, Deciding)> = vec![(0, Vec::new()); self.segments.len()];
        for (m, k, segment, pair, around) in self.open_pairs() {
            let Some(floor) = floor(segment, pair, robustness) else {
                continue;
            };
            let Some(target) = bound.checked_sub(around).filter(|&t| t >= floor) else {
                continue;
            };
            let undecided = &segment.candidate_lengths(pair)[pair.decided..];
            let upto = undecided.partition_point(|&s| s <= target);
            let count = undecided[..upto]
                .iter()
                .filter(|&&s| feasible(s, pair.reach, robustness))
                .count();
            if count > 0 {
                by_segment[m].0 += count;
                by_segment[m].1.push((m, k, pair.decided + upto));
            }
        }
        by_segment
    }

    /// The pieces the first widening evaluates at most — every candidate on a chain as short
    /// as any chain can be ([`Self::lower_bound`]), with its robustness neighbours — as if
    /// none failed (a piece that fails only spares others): what a cost estimate samples
    /// before the search starts. Empty when no chain is possible.
    pub(crate) fn first_round(&self) -> Vec<PairJob> {
        let Some(bound) = self.lower_bound() else {
            return Vec::new();
        };
        let deciding: Deciding = (self.undecided_per_segment(bound).into_iter())
            .flat_map(|(_, deciding)| deciding)
            .collect();
        pair_jobs(self.wanted(&deciding, Evaluate::Feasible).into_iter())
    }

    /// The chained pairs ([`Self::chained_pairs`]) that may still need candidates decided:
    /// those without a robust piece (one not dropped) yet.
    fn open_pairs(&self) -> Vec<(usize, usize, &Segment, &Pair, usize)> {
        let mut open = self.chained_pairs();
        open.retain(|(_, _, _, pair, _)| pair.shortest_robust.is_none());
        open
    }

    /// Every pair that lies on some chain by the floors, as `(segment, pair index, segment,
    /// pair, before(start) + after(end))`: the shortest a chain through it can be, its own
    /// piece left out.
    fn chained_pairs(&self) -> Vec<(usize, usize, &Segment, &Pair, usize)> {
        let (before, after) = self.bounds();
        let setup = self.setup();
        let mut chained = Vec::new();
        for (m, segment) in self.segments.iter().enumerate() {
            let (a, b) = setup.segment_guides(m);
            for (k, pair) in segment.pairs.iter().enumerate() {
                if let (Some(Some(head)), Some(Some(tail))) =
                    (before[a].get(pair.start), after[b].get(pair.end))
                {
                    chained.push((m, k, segment, pair, head + tail));
                }
            }
        }
        chained
    }

    /// Decides the candidates of pair `k` of segment `m` up to index `upto`, for every
    /// `(m, k, upto)` of `deciding`: the candidates `which` names and their robustness
    /// neighbours evaluated in one parallel batch (the progress stage names `bound`).
    fn decide_up_to(&mut self, deciding: &[(usize, usize, usize)], bound: usize, which: Evaluate) {
        let clock = Instant::now();
        let jobs = pair_jobs(self.wanted(deciding, which).into_iter());
        let segments: BTreeSet<usize> = jobs.iter().map(|job| job.segment).collect();
        let solves_before: usize = (0..self.segments.len())
            .map(|m| self.evaluator.static_solves(m))
            .sum();
        let pitch_mm = self.setup().cable.sub_segment_pitch_m * 1e3;
        let reach = match bound {
            usize::MAX => "every candidate".to_string(),
            _ => format!("chains up to {:.0} mm", bound as f64 * pitch_mm),
        };
        self.evaluate(&jobs, &format!("attachment, {reach}"));
        for &(m, k, upto) in deciding {
            self.decide(m, k, upto);
        }
        let solves: usize = (0..self.segments.len())
            .map(|m| self.evaluator.static_solves(m))
            .sum::<usize>()
            - solves_before;
        if jobs.is_empty() {
            return;
        }
        let names: Vec<String> = segments
            .iter()
            .map(|&m| self.setup().segment_name(m))
            .collect();
        log::info!(
            "attachment round, {reach}, {}: {} cable pieces of {} clamp pairs, {solves} \
             static solves, {:.2} s",
            names.join(" "),
            jobs.iter().map(|j| j.lengths.len()).sum::<usize>(),
            jobs.len(),
            clock.elapsed().as_secs_f64()
        );
    }

    /// The pieces without a verdict that deciding `deciding` evaluates: the candidates
    /// `which` names and their robustness neighbours, as `(segment, piece)`.
    fn wanted(&self, deciding: &[(usize, usize, usize)], which: Evaluate) -> Vec<(usize, Pv)> {
        let robustness = self.setup().robustness;
        let mut wanted: Vec<(usize, Pv)> = Vec::new();
        for &(m, k, upto) in deciding {
            let segment = &self.segments[m];
            let pair = &segment.pairs[k];
            for &s in &segment.candidate_lengths(pair)[pair.decided..upto] {
                if which == Evaluate::Feasible && !feasible(s, pair.reach, &robustness) {
                    continue;
                }
                let pv = Pv::new(s, pair.start, pair.end);
                let neighbours = robust_neighbours(&pv, robustness.delta_s, robustness.range)
                    .unwrap_or_default();
                for piece in std::iter::once(pv).chain(neighbours) {
                    if segment.verdicts.get(&piece).is_none() {
                        wanted.push((m, piece));
                    }
                }
            }
        }
        wanted
    }

    /// Evaluates `jobs` in parallel and records their verdicts.
    fn evaluate(&mut self, jobs: &[PairJob], stage: &str) {
        let evaluator = self.evaluator;
        let poses = self.poses;
        let intra_link = self.intra_link;
        let recall = &self.recall;
        let segments = &self.segments;
        let arranged: Vec<Vec<&TestPose>> = (segments.iter().zip(&poses.poses))
            .map(|(segment, poses)| segment.order.arrange(poses))
            .collect();
        let timed = evaluate_jobs(stage, jobs, |job| {
            let clock = Instant::now();
            let m = job.segment;
            let verdicts = match (intra_link, &segments[m].lookup_counts) {
                (Some(lookup), Some(counts)) => looked_up(
                    evaluator,
                    &poses.poses[m],
                    lookup,
                    m,
                    job.pair,
                    &job.lengths,
                    counts,
                ),
                _ => {
                    let fresh = |lengths: &[usize]| {
                        let mut misses =
                            evaluator.first_rejections(m, job.pair, lengths, &arranged[m]);
                        segments[m].order.renumber(&mut misses);
                        misses
                    };
                    match recall.get(m).and_then(Option::as_ref) {
                        Some(recall) => recalled(evaluator, job, &poses.poses[m], recall, fresh),
                        None => fresh(&job.lengths),
                    }
                }
            };
            (verdicts, clock.elapsed().as_secs_f64())
        });
        let mut by_segment: Vec<(Vec<PairJob>, Vec<_>)> = (0..self.segments.len())
            .map(|_| Default::default())
            .collect();
        for (job, (verdicts, busy_s)) in jobs.iter().zip(timed) {
            self.segments[job.segment].busy_s += busy_s;
            by_segment[job.segment].0.push(job.clone());
            by_segment[job.segment].1.push(verdicts);
        }
        for (segment, (jobs, verdicts)) in self.segments.iter_mut().zip(by_segment) {
            if segment.lookup_counts.is_none() {
                segment.order.learn(verdicts.iter().flatten());
            }
            segment.verdicts.extend(&jobs, verdicts);
        }
    }

    /// Marks the candidates of pair `k` of segment `m` decided up to index `upto`, keeping
    /// the robust ones.
    fn decide(&mut self, m: usize, k: usize, upto: usize) {
        let robustness = self.setup().robustness;
        let segment = &mut self.segments[m];
        let pair = segment.pairs[k].clone();
        let lengths = segment.candidate_lengths(&pair)[pair.decided..upto].to_vec();
        for s in lengths {
            let pv = Pv::new(s, pair.start, pair.end);
            if feasible(s, pair.reach, &robustness) && segment.verdicts.robust(&pv, &robustness) {
                segment.robust.insert(pv);
                if segment.dropped.contains(&pv) {
                    continue;
                }
                let shortest = &mut segment.pairs[k].shortest_robust;
                *shortest = Some(shortest.map_or(s, |r| r.min(s)));
            }
        }
        segment.pairs[k].decided = upto;
    }

    /// For every guide and configuration, the shortest a chain can be from the first guide
    /// to it and from it to the last (`None`: no chain), with every pair's floor as its
    /// length.
    fn bounds(&self) -> (ChainBounds, ChainBounds) {
        let setup = self.setup();
        let robustness = &setup.robustness;
        let counts = setup.configuration_counts();
        let last = counts.len() - 1;
        let mut before: ChainBounds = counts.iter().map(|&n| vec![None; n]).collect();
        let mut after = before.clone();
        before[0].iter_mut().for_each(|b| *b = Some(0));
        after[last].iter_mut().for_each(|b| *b = Some(0));
        let ends = setup.segment_ends();
        let relax = |slot: &mut Option<usize>, value: usize| {
            *slot = Some(slot.map_or(value, |v| v.min(value)));
        };
        for g in 1..=last {
            for (m, segment) in self
                .segments
                .iter()
                .enumerate()
                .filter(|(m, _)| ends[*m].1 == g)
            {
                let a = ends[m].0;
                for pair in &segment.pairs {
                    if let (Some(floor), Some(head)) =
                        (floor(segment, pair, robustness), before[a][pair.start])
                    {
                        relax(&mut before[g][pair.end], head + floor);
                    }
                }
            }
        }
        for g in (0..last).rev() {
            for (m, segment) in self
                .segments
                .iter()
                .enumerate()
                .filter(|(m, _)| ends[*m].0 == g)
            {
                let b = ends[m].1;
                for pair in &segment.pairs {
                    if let (Some(floor), Some(tail)) =
                        (floor(segment, pair, robustness), after[b][pair.end])
                    {
                        relax(&mut after[g][pair.start], tail + floor);
                    }
                }
            }
        }
        (before, after)
    }

    /// The sets of every segment as far as they are decided: candidates decided by
    /// evaluation count as tested ("after pruning"); the others were pruned by the search's
    /// bounds.
    pub fn sets(&self) -> Vec<SegmentSets> {
        let setup = self.setup();
        let busy_total: f64 = self.segments.iter().map(|s| s.busy_s).sum();
        self.segments
            .iter()
            .enumerate()
            .map(|(m, segment)| {
                let tested: Vec<Pv> = segment
                    .pairs
                    .iter()
                    .flat_map(|pair| {
                        segment.candidate_lengths(pair)[..pair.decided]
                            .iter()
                            .map(|&s| Pv::new(s, pair.start, pair.end))
                            .filter(|pv| segment.verdicts.get(pv).is_some())
                    })
                    .collect();
                let mut sets = segment.verdicts.sets(setup, &tested);
                sets.d0 = setup.admissible_pv_count(m);
                sets.d2 = segment.robust.iter().copied().collect();
                sets.static_solves = self.evaluator.static_solves(m);
                sets.looked_up = segment.lookup_counts.as_ref().map(LookupCounts::snapshot);
                sets.time_s = if busy_total > 0.0 {
                    self.wall_s * segment.busy_s / busy_total
                } else {
                    0.0
                };
                sets
            })
            .collect()
    }

    /// Wall time spent deciding (s).
    pub fn time_s(&self) -> f64 {
        self.wall_s
    }
}

/// Per guide and configuration, the shortest a chain can be on one side of it (`None`: no
/// chain).
type ChainBounds = Vec<Vec<Option<usize>>>;

/// Pairs whose candidates a batch decides, as `(segment, pair index, decide up to)`.
type Deciding = Vec<(usize, usize, usize)>;

/// The verdicts of `job`'s lengths at `poses` (its segment's), from what `recall` knows: a
/// remembered failure at one of them as it is, a piece that held at an earlier list tested
/// at the poses new to it only, the others at every pose by `fresh`.
fn recalled(
    evaluator: &Evaluator<'_>,
    job: &PairJob,
    poses: &[TestPose],
    recall: &Recall<'_>,
    fresh: impl Fn(&[usize]) -> Vec<Option<Miss>>,
) -> Vec<Option<Miss>> {
    let mut verdicts: Vec<Option<Option<Miss>>> = vec![None; job.lengths.len()];
    let mut unknown: Vec<usize> = Vec::new();
    let mut held: BTreeMap<usize, (&[usize], Vec<usize>)> = BTreeMap::new();
    for (i, &s) in job.lengths.iter().enumerate() {
        match recall.known(&Pv::new(s, job.pair.0, job.pair.1)) {
            Known::Fails(miss) => verdicts[i] = Some(Some(miss)),
            Known::HeldExcept { poses: [], .. } => verdicts[i] = Some(None),
            Known::HeldExcept { list, poses } => {
                held.entry(list).or_insert((poses, vec![])).1.push(i)
            }
            Known::Nothing => unknown.push(i),
        }
    }
    let lengths =
        |which: &[usize]| -> Vec<usize> { which.iter().map(|&i| job.lengths[i]).collect() };
    if !unknown.is_empty() {
        for (&i, miss) in unknown.iter().zip(fresh(&lengths(&unknown))) {
            verdicts[i] = Some(miss);
        }
    }
    for (new, which) in held.into_values() {
        let some: Vec<&TestPose> = new.iter().map(|&p| &poses[p]).collect();
        let misses = evaluator.first_rejections(job.segment, job.pair, &lengths(&which), &some);
        for (&i, miss) in which.iter().zip(misses) {
            verdicts[i] = Some(miss.map(|miss| Miss {
                pose: new[miss.pose],
                ..miss
            }));
        }
    }
    verdicts.into_iter().map(Option::flatten).collect()
}

/// Which candidates a round evaluates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Evaluate {
    /// Those that can be robust (their shortest robustness neighbour reaches).
    Feasible,
    /// Every one: what a diagnosis ranks its nearest misses from.
    Every,
}

/// Whether candidate length `s` of a pair that reaches from `reach` sub-segments on can be
/// robust at all: its shortest robustness neighbour must reach too.
fn feasible(s: usize, reach: usize, robustness: &crate::setup::Robustness) -> bool {
    let below = robustness.range * robustness.delta_s;
    s == 0 || (s > below && s - below >= reach)
}

/// The shortest length a robust piece of `pair` can have from what is known: its shortest
/// known robust piece, or its first undecided candidate that can be robust; `None` when
/// there is neither.
fn floor(segment: &Segment, pair: &Pair, robustness: &crate::setup::Robustness) -> Option<usize> {
    let undecided = segment.candidate_lengths(pair)[pair.decided..]
        .iter()
        .copied()
        .find(|&s| feasible(s, pair.reach, robustness));
    match (pair.shortest_robust, undecided) {
        (Some(r), Some(u)) => Some(r.min(u)),
        (r, u) => r.or(u),
    }
}

/// The candidate pairs of segment `m` (those with at least one admissible length), with
/// the shortest length that reaches at every test pose.
fn pairs(evaluator: &Evaluator<'_>, poses: &SegmentPoses, m: usize) -> Vec<Pair> {
    let setup = evaluator.setup();
    let (a, b) = setup.segment_guides(m);
    let (na, nb) = (
        setup.guides[a].configurations.len(),
        setup.guides[b].configurations.len(),
    );
    let pitch = setup.cable.sub_segment_pitch_m;
    let mut pairs = Vec::new();
    for start in 0..na {
        for end in 0..nb {
            let coincident = setup.coincident(a, start, b, end);
            let distance = poses.poses[m]
                .iter()
                .map(|pose| evaluator.clamp_distance_m(m, (start, end), pose))
                .fold(0.0, f64::max);
            pairs.push(Pair {
                start,
                end,
                coincident,
                decided: 0,
                reach: shortest_reaching(distance, pitch),
                shortest_robust: None,
            });
        }
    }
    pairs
}

/// The shortest whole number of sub-segments of `pitch_m` that reaches `distance_m`
/// ([`reaches`]' rule).
fn shortest_reaching(distance_m: f64, pitch_m: f64) -> usize {
    let mut s = ((distance_m / pitch_m).floor() as usize)
        .saturating_sub(1)
        .max(1);
    let origin = Pose::identity();
    let at = Pose::translation(distance_m, 0.0, 0.0);
    while reaches(&origin, &at, s, pitch_m).is_err() {
        s += 1;
    }
    s
}

#[cfg(test)]
mod tests {
    //! The invariant of the lazy test, checked against the exhaustive sets with a dynamic
    //! program of the test's own: after widening to a bound, the lazy test knows, for every
    //! pair of clamp placements on a chain of robust pieces no longer than the bound, the
    //! shortest robust piece between them — so it knows every shortest chain.

    use super::*;
    use crate::attachment::ConnectMethod;
    use crate::attachment::sets::{admissible_pvs, needed_pvs};
    use crate::fixtures::{exhaustive_robust, narrow_pick_and_place};

    /// The pieces of `d2` (per segment, segment `m` from guide `m` to `m + 1`) that lie on a
    /// chain of `d2` no longer than `bound`: a shortest prefix and suffix per configuration by
    /// relaxation over the guides, written here independently of the library's chain search.
    fn on_chains_up_to(setup: &Setup, d2: &[Vec<Pv>], bound: usize) -> Vec<BTreeSet<Pv>> {
        let counts: Vec<usize> = setup
            .guides
            .iter()
            .map(|g| g.configurations.len())
            .collect();
        let guides = counts.len();
        let mut before: Vec<Vec<usize>> = counts.iter().map(|&n| vec![usize::MAX; n]).collect();
        let mut after = before.clone();
        before[0].fill(0);
        after[guides - 1].fill(0);
        for (m, pieces) in d2.iter().enumerate() {
            for pv in pieces {
                let head = before[m][pv.start];
                if head != usize::MAX {
                    let slot = &mut before[m + 1][pv.end];
                    *slot = (*slot).min(head + pv.sub_segments);
                }
            }
        }
        for (m, pieces) in d2.iter().enumerate().rev() {
            for pv in pieces {
                let tail = after[m + 1][pv.end];
                if tail != usize::MAX {
                    let slot = &mut after[m][pv.start];
                    *slot = (*slot).min(tail + pv.sub_segments);
                }
            }
        }
        d2.iter()
            .enumerate()
            .map(|(m, pieces)| {
                pieces
                    .iter()
                    .filter(|pv| {
                        let (head, tail) = (before[m][pv.start], after[m + 1][pv.end]);
                        head != usize::MAX
                            && tail != usize::MAX
                            && head + pv.sub_segments + tail <= bound
                    })
                    .copied()
                    .collect()
            })
            .collect()
    }

    /// Per pair of clamp placements of each segment, the shortest of `pieces`.
    fn shortest_per_pair(pieces: &[BTreeSet<Pv>]) -> Vec<BTreeSet<Pv>> {
        pieces
            .iter()
            .map(|segment| {
                let mut shortest: BTreeMap<(usize, usize), Pv> = BTreeMap::new();
                for pv in segment {
                    shortest
                        .entry((pv.start, pv.end))
                        .and_modify(|kept| {
                            if pv.sub_segments < kept.sub_segments {
                                *kept = *pv;
                            }
                        })
                        .or_insert(*pv);
                }
                shortest.into_values().collect()
            })
            .collect()
    }

    #[test]
    fn after_widening_the_lazy_test_knows_the_shortest_piece_of_every_pair_on_a_chain() {
        let (setup, motion) = narrow_pick_and_place();
        assert!(setup.segment_count() == 3 && setup.guides.len() == 4);
        let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let exhaustive = exhaustive_robust(&evaluator, &poses);
        let mut lazy = LazyAttachment::new(&evaluator, &poses, None);
        let first = lazy.lower_bound().expect("a chain can exist");
        let on_any_chain = on_chains_up_to(&setup, &exhaustive, usize::MAX);
        assert!(
            on_any_chain.iter().all(|pieces| !pieces.is_empty()),
            "the narrow setup has chains"
        );
        let mut longer_pieces_left_out = false;
        for bound in [first, first + 3, first + 8, first + 16] {
            lazy.widen_to(bound);
            let known = lazy.robust();
            let expected = on_chains_up_to(&setup, &exhaustive, bound);
            let found = on_chains_up_to(&setup, &known, bound);
            assert_eq!(
                shortest_per_pair(&found),
                shortest_per_pair(&expected),
                "bound {bound}"
            );
            longer_pieces_left_out |= found != expected;
            for (m, pieces) in known.iter().enumerate() {
                for pv in pieces {
                    assert!(
                        exhaustive[m].contains(pv),
                        "bound {bound}: C{} {pv:?} robust only in the lazy test",
                        m + 1
                    );
                }
            }
            // In one round from nothing, the same shortest pieces: verdicts do not depend on
            // batches.
            let mut fresh = LazyAttachment::new(&evaluator, &poses, None);
            fresh.widen_to(bound);
            assert_eq!(
                shortest_per_pair(&on_chains_up_to(&setup, &fresh.robust(), bound)),
                shortest_per_pair(&expected)
            );
        }
        assert!(
            longer_pieces_left_out,
            "the lazy test skips the longer pieces of pairs with a shorter robust one"
        );
        // A dropped piece (the motion test failed it) reopens its pair: widening to the same
        // bound again decides what the bound now needs of it.
        let bound = lazy.bound().expect("widened");
        let mut remaining = exhaustive.clone();
        let shortest = shortest_per_pair(&on_chains_up_to(&setup, &exhaustive, bound));
        for (m, pieces) in shortest.iter().enumerate() {
            for pv in pieces.iter().take(3) {
                lazy.drop_piece(m, pv);
                remaining[m].retain(|kept| kept != pv);
            }
        }
        lazy.widen_to(bound);
        assert_eq!(
            shortest_per_pair(&on_chains_up_to(&setup, &lazy.robust(), bound)),
            shortest_per_pair(&on_chains_up_to(&setup, &remaining, bound)),
            "after drops"
        );
    }

    #[test]
    fn the_first_round_foreseen_holds_every_piece_the_first_widening_evaluates() {
        let (setup, motion) = narrow_pick_and_place();
        let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let mut lazy = LazyAttachment::new(&evaluator, &poses, None);
        let foreseen: BTreeSet<(usize, Pv)> = (lazy.first_round().iter())
            .flat_map(|job| {
                (job.lengths.iter()).map(|&s| (job.segment, Pv::new(s, job.pair.0, job.pair.1)))
            })
            .collect();
        let bound = lazy.lower_bound().expect("a chain can exist");
        lazy.widen_to(bound);
        let evaluated: usize = lazy.segments.iter().map(|s| s.verdicts.len()).sum();
        let foreseen_evaluated = (foreseen.iter())
            .filter(|(m, pv)| lazy.segments[*m].verdicts.get(pv).is_some())
            .count();
        assert!(evaluated > 0, "the first widening evaluates pieces");
        assert_eq!(
            foreseen_evaluated, evaluated,
            "every piece the widening evaluated was foreseen"
        );
        // Foreseen as if none failed: more than the widening needed here, far fewer than
        // every candidate.
        let every: usize = (0..setup.segment_count())
            .map(|m| {
                let r = setup.robustness;
                needed_pvs(&admissible_pvs(&setup, m), r.delta_s, r.range).len()
            })
            .sum();
        assert!(
            evaluated <= foreseen.len() && 4 * foreseen.len() < every,
            "evaluated {evaluated}, foreseen {}, every candidate {every}",
            foreseen.len()
        );
    }
}
