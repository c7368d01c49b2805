//! Verdicts kept from one solve of a setup to the next over other test poses — the boxes a
//! range design tries share most of their poses (a gentler ramp: every grid pose; a box
//! narrowed from one end: every grid value on the kept side).
//!
//! A piece's verdict at a pose does not depend on the other poses (each pose's lengths start
//! from the connected geometry, [`super::lazy`]), so what an earlier solve learnt carries
//! over: a piece that held at every pose of an earlier list needs testing only at the poses
//! new to it, and one that failed at a pose the new list has fails again — the same verdict
//! as a fresh test, for less. (The miss a remembered failure names is where it failed
//! before, which a fresh test, trying the poses in another order, might not name first.)

use super::poses::{SegmentPoses, TestPose};
use super::sets::Verdicts;
use super::verdict::Miss;
use crate::path::Pv;
use std::collections::{BTreeMap, HashMap, HashSet};

/// A test pose as far as a verdict is concerned: the joints (exact) and which links the
/// clearance is measured against.
type PoseKey = (Vec<u64>, Option<usize>);

fn key(pose: &TestPose) -> PoseKey {
    let joints = pose.joints.iter().map(|v| v.to_bits()).collect();
    (joints, pose.clearance_link)
}

/// What earlier solves of one setup (with one connected-geometry method) learnt of its
/// pieces, per segment. Give it to each solve of the same setup and options
/// ([`super::LazyAttachment::remembering`]); never across setups.
#[derive(Debug, Default)]
pub struct VerdictMemory {
    segments: Vec<SegmentMemory>,
}

/// The verdicts one solve decided, per segment (`None`: answered by a dictionary, not
/// remembered), on their way into a [`VerdictMemory`].
#[derive(Debug)]
pub struct Learnt(pub(crate) Vec<Option<Verdicts>>);

/// One segment's memory.
#[derive(Debug, Default)]
struct SegmentMemory {
    /// Every test pose seen, numbered.
    numbers: HashMap<PoseKey, usize>,
    /// The lists of poses pieces were tested over, as pose numbers.
    lists: Vec<HashSet<usize>>,
    /// Pieces that held at every pose of a list (its index in `lists`).
    held: BTreeMap<Pv, usize>,
    /// Pieces that failed: at which pose (its number), how.
    failed: BTreeMap<Pv, (usize, Miss)>,
}

/// What the memory knows of a piece at a new list of test poses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Known<'a> {
    /// Nothing: test it at every pose.
    Nothing,
    /// It fails (the miss's pose an index into the new list).
    Fails(Miss),
    /// It held at every pose of the new list but `poses` (indices into it; an earlier list,
    /// `list`, held the others): test it there.
    HeldExcept { list: usize, poses: &'a [usize] },
}

/// The memory of one segment read against a new list of its test poses.
#[derive(Debug)]
pub(crate) struct Recall<'m> {
    memory: &'m SegmentMemory,
    /// Per remembered pose number that the new list has, its index there.
    index: HashMap<usize, usize>,
    /// Per remembered list, the new list's poses not in it (indices).
    new_poses: Vec<Vec<usize>>,
}

impl VerdictMemory {
    /// Nothing remembered yet.
    pub fn new() -> VerdictMemory {
        VerdictMemory::default()
    }

    /// Pieces remembered, over every segment.
    pub fn pieces(&self) -> usize {
        (self.segments.iter())
            .map(|s| s.held.len() + s.failed.len())
            .sum()
    }

    /// Each segment's memory read against its poses in `poses`.
    pub(crate) fn recall(&self, poses: &SegmentPoses) -> Vec<Option<Recall<'_>>> {
        (0..poses.poses.len())
            .map(|m| {
                let memory = self.segments.get(m)?;
                let numbers: Vec<Option<usize>> = (poses.poses[m].iter())
                    .map(|pose| memory.numbers.get(&key(pose)).copied())
                    .collect();
                let index = (numbers.iter().enumerate())
                    .filter_map(|(i, n)| n.map(|n| (n, i)))
                    .collect();
                let new_poses = (memory.lists.iter())
                    .map(|list| {
                        (numbers.iter().enumerate())
                            .filter(|(_, n)| !n.is_some_and(|n| list.contains(&n)))
                            .map(|(i, _)| i)
                            .collect()
                    })
                    .collect();
                Some(Recall {
                    memory,
                    index,
                    new_poses,
                })
            })
            .collect()
    }

    /// Remembers what a solve at `poses` learnt ([`super::LazyAttachment::learnt`]).
    pub fn learn(&mut self, poses: &SegmentPoses, learnt: Learnt) {
        for (m, verdicts) in learnt.0.iter().enumerate() {
            if let Some(verdicts) = verdicts {
                self.remember(poses, m, verdicts);
            }
        }
    }

    /// Remembers the verdicts of segment `m`'s pieces tested at its poses in `poses` (each
    /// tested at all of them: `None` held at every one, a miss's pose an index into them).
    fn remember(&mut self, poses: &SegmentPoses, m: usize, verdicts: &Verdicts) {
        if self.segments.len() <= m {
            self.segments.resize_with(m + 1, SegmentMemory::default);
        }
        let memory = &mut self.segments[m];
        let mut list = HashSet::with_capacity(poses.poses[m].len());
        let mut numbers = Vec::with_capacity(poses.poses[m].len());
        for pose in &poses.poses[m] {
            let next = memory.numbers.len();
            let number = *memory.numbers.entry(key(pose)).or_insert(next);
            list.insert(number);
            numbers.push(number);
        }
        let list_index = memory.lists.len();
        memory.lists.push(list);
        for (pv, verdict) in verdicts.iter() {
            match verdict {
                None => {
                    memory.failed.remove(pv);
                    memory.held.insert(*pv, list_index);
                }
                Some(miss) => {
                    let Some(&number) = numbers.get(miss.pose) else {
                        continue;
                    };
                    memory.held.remove(pv);
                    memory.failed.insert(*pv, (number, *miss));
                }
            }
        }
        // Lists no piece refers to any more are emptied, not removed (indices stay valid).
        let used: HashSet<usize> = memory.held.values().copied().collect();
        for (i, list) in memory.lists.iter_mut().enumerate() {
            if !used.contains(&i) {
                *list = HashSet::new();
            }
        }
    }
}

impl Recall<'_> {
    /// What is known of piece `pv` at the new list of poses.
    pub(crate) fn known(&self, pv: &Pv) -> Known<'_> {
        if let Some(&(number, miss)) = self.memory.failed.get(pv)
            && let Some(&pose) = self.index.get(&number)
        {
            return Known::Fails(Miss { pose, ..miss });
        }
        match self.memory.held.get(pv) {
            Some(&list) => Known::HeldExcept {
                list,
                poses: &self.new_poses[list],
            },
            None => Known::Nothing,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The reference is the lazy test itself, fresh at the new poses: remembering must decide
    //! the same pieces with the same verdicts, for fewer static solves.

    use super::*;
    use crate::attachment::{ConnectMethod, Evaluator, LazyAttachment};
    use crate::fixtures::narrow_pick_and_place;

    /// Every piece decided and whether it holds, per segment.
    fn decided(learnt: &Learnt) -> Vec<Vec<(Pv, bool)>> {
        (learnt.0.iter())
            .map(|v| {
                (v.iter())
                    .flat_map(|v| v.iter().map(|(pv, miss)| (*pv, miss.is_none())))
                    .collect()
            })
            .collect()
    }

    #[test]
    fn a_test_remembering_an_earlier_one_at_other_poses_decides_what_a_fresh_one_decides() {
        let (setup, motion) = narrow_pick_and_place();
        let all = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let mut half = all.clone();
        for poses in &mut half.poses {
            let kept: Vec<TestPose> = poses.iter().step_by(2).cloned().collect();
            *poses = kept;
        }
        assert!(
            (all.poses.iter().zip(&half.poses)).any(|(a, h)| a.len() > h.len()),
            "the half lists leave poses out"
        );
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let solves = || -> usize {
            (0..setup.segment_count())
                .map(|m| evaluator.static_solves(m))
                .sum()
        };
        // Fewer poses remembered than asked (held pieces tested at the others), then more
        // (failures at poses the new list lacks tested again).
        for (earlier, later) in [(&half, &all), (&all, &half)] {
            let mut memory = VerdictMemory::new();
            let mut first = LazyAttachment::new(&evaluator, earlier, None);
            let bound = first.lower_bound().expect("a chain") + 8;
            first.widen_to(bound);
            memory.learn(earlier, first.learnt());
            assert!(memory.pieces() > 0);

            let before = solves();
            let mut fresh = LazyAttachment::new(&evaluator, later, None);
            fresh.widen_to(bound);
            let fresh_solves = solves() - before;
            let fresh_robust = fresh.robust();
            let fresh = decided(&fresh.learnt());

            let before = solves();
            let mut remembering = LazyAttachment::new(&evaluator, later, None).remembering(&memory);
            remembering.widen_to(bound);
            let remembering_solves = solves() - before;
            assert_eq!(remembering.robust(), fresh_robust);
            assert_eq!(
                decided(&remembering.learnt()),
                fresh,
                "the same pieces, the same verdicts"
            );
            assert!(
                remembering_solves < fresh_solves,
                "{remembering_solves} static solves remembering, {fresh_solves} fresh"
            );
        }
    }
}
