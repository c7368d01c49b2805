//! Intra-link pieces answered by a dictionary's lookup instead of solved: what a lookup says of a piece, and how often it decided.

use super::evaluate::Evaluator;
use super::poses::TestPose;
use super::sets::LookedUp;
use super::verdict::{Miss, Rejection};
use crate::path::Pv;
use std::collections::BTreeSet;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A lookup's answer for one piece of an intra-link segment over the segment's test poses
/// (e.g. a dictionary's, [`crate::dictionary::MotionLookup`]).
#[derive(Debug, Clone, PartialEq)]
pub enum LookupAnswer {
    /// Every limit holds at every test pose, by more than the lookup's error.
    Holds,
    /// A limit fails at test pose `pose` (index) by more than the lookup's error;
    /// `margins`, the looked-up `[clearance mm, stretch, curvature 1/m]` there.
    Fails {
        /// Index of the test pose.
        pose: usize,
        /// The limit.
        rejection: Rejection,
        /// The looked-up margins, when there are any (not for a cable too short).
        margins: Option<super::MarginValues>,
    },
    /// The lookup cannot decide at these test poses (indices, ascending): solve them.
    Undecided(Vec<usize>),
}

/// The answer for piece `pv` of segment `m`.
pub type IntraLinkAnswer<'v> = dyn Fn(usize, &Pv) -> LookupAnswer + Sync + 'v;

/// [`LookedUp`] counted from parallel workers.
#[derive(Default, Debug)]
pub(super) struct LookupCounts([AtomicUsize; 4]);

impl LookupCounts {
    pub(super) fn add(&self, k: usize) {
        self.0[k].fetch_add(1, Ordering::Relaxed);
    }

    /// The counts so far.
    pub(super) fn snapshot(&self) -> LookedUp {
        let [holds, fails, solved, solved_failed] =
            std::array::from_fn(|k| self.0[k].load(Ordering::Relaxed));
        LookedUp {
            holds,
            fails,
            solved,
            solved_failed,
        }
    }
}

/// The verdicts of the lengths of one pair of configurations from `lookup`; the undecided
/// ones solved at the poses where any length of the pair is undecided, the whole chain of
/// lengths together, as the exact test solves them.
pub(super) fn looked_up(
    evaluator: &Evaluator<'_>,
    poses: &[TestPose],
    lookup: &IntraLinkAnswer<'_>,
    m: usize,
    (start, end): (usize, usize),
    lengths: &[usize],
    counts: &LookupCounts,
) -> Vec<Option<Miss>> {
    let setup = evaluator.setup();
    let answers: Vec<LookupAnswer> = lengths
        .iter()
        .map(|&s| lookup(m, &Pv::new(s, start, end)))
        .collect();
    let undecided: BTreeSet<usize> = answers
        .iter()
        .filter_map(|a| match a {
            LookupAnswer::Undecided(at) => Some(at.iter().copied()),
            _ => None,
        })
        .flatten()
        .collect();
    let at: Vec<usize> = undecided.into_iter().collect();
    let wanted: Vec<bool> = answers
        .iter()
        .map(|a| matches!(a, LookupAnswer::Undecided(_)))
        .collect();
    let exact = if at.is_empty() {
        vec![None; lengths.len()]
    } else {
        let chosen: Vec<&TestPose> = at.iter().map(|&p| &poses[p]).collect();
        evaluator.first_rejections_of(m, (start, end), lengths, &chosen, &wanted)
    };
    answers
        .into_iter()
        .enumerate()
        .map(|(i, answer)| match answer {
            LookupAnswer::Holds => {
                counts.add(0);
                None
            }
            LookupAnswer::Fails {
                pose,
                rejection,
                margins,
            } => {
                counts.add(1);
                Some(Miss::looked_up(setup, rejection, margins, pose))
            }
            LookupAnswer::Undecided(_) => {
                counts.add(2);
                let miss = exact[i].map(|miss| Miss {
                    pose: at[miss.pose],
                    ..miss
                });
                if miss.is_some() {
                    counts.add(3);
                }
                miss
            }
        })
        .collect()
}
