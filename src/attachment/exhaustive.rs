//! The exhaustive driver: every candidate of every segment decided, intra-link segments first, then the inter-link ones pruned by their neighbours' D2 (the paper's order, `solve --exhaustive`).

use super::evaluate::Evaluator;
use super::jobs::{evaluate_jobs, pair_jobs};
use super::lookup::{IntraLinkAnswer, LookupCounts, looked_up};
use super::poses::SegmentPoses;
use super::sets::{SegmentSets, Verdicts, admissible_pvs, needed_pvs};
use super::verdict::Miss;
use crate::path::Pv;
use crate::setup::Setup;
use std::collections::BTreeSet;
use std::time::Instant;

/// Runs the attachment test on every segment: intra-link segments first, then the inter-link
/// ones pruned by their intra-link neighbours' D2.
pub fn attachment_test(evaluator: &Evaluator<'_>, poses: &SegmentPoses) -> Vec<SegmentSets> {
    attachment_test_with(evaluator, poses, None)
}

/// [`attachment_test`], with the intra-link segments' pieces answered by `intra_link` (a
/// dictionary's lookup over the same test poses) when it is `Some`: the pieces it cannot
/// decide are solved exactly at the undecided poses, so the sets equal the exact test's.
pub fn attachment_test_with(
    evaluator: &Evaluator<'_>,
    poses: &SegmentPoses,
    intra_link: Option<&IntraLinkAnswer<'_>>,
) -> Vec<SegmentSets> {
    let setup = evaluator.setup();
    let count = setup.segment_count();
    let at_poses = |m: usize, guides: (usize, usize), lengths: &[usize]| {
        evaluator.first_rejections(m, guides, lengths, &poses.poses[m])
    };
    let mut sets: Vec<Option<SegmentSets>> = vec![None; count];
    for m in (0..count).filter(|&m| setup.is_intra_link(m)) {
        let candidates = admissible_pvs(setup, m);
        // A dictionary answers for rigid clamps only.
        sets[m] = Some(match intra_link.filter(|_| setup.segment_is_rigid(m)) {
            Some(lookup) => {
                let counts = LookupCounts::default();
                let mut tested = test_segment(setup, m, candidates, |guides, lengths| {
                    looked_up(
                        evaluator,
                        &poses.poses[m],
                        lookup,
                        m,
                        guides,
                        lengths,
                        &counts,
                    )
                });
                tested.looked_up = Some(counts.snapshot());
                tested
            }
            None => test_segment(setup, m, candidates, |guides, lengths| {
                at_poses(m, guides, lengths)
            }),
        });
    }
    for m in (0..count).filter(|&m| !setup.is_intra_link(m)) {
        let (a, b) = setup.segment_guides(m);
        let allowed_start = neighbour_configurations(&sets, setup.segments_into(a), |pv| pv.end);
        let allowed_end = neighbour_configurations(&sets, setup.segments_from(b), |pv| pv.start);
        let d0 = admissible_pvs(setup, m);
        let d0_count = d0.len();
        let candidates: Vec<Pv> = d0
            .into_iter()
            .filter(|pv| allowed_start.as_ref().is_none_or(|a| a.contains(&pv.start)))
            .filter(|pv| allowed_end.as_ref().is_none_or(|a| a.contains(&pv.end)))
            .collect();
        let mut tested = test_segment(setup, m, candidates, |guides, lengths| {
            at_poses(m, guides, lengths)
        });
        tested.d0 = d0_count;
        sets[m] = Some(tested);
    }
    let mut sets: Vec<SegmentSets> = sets.into_iter().flatten().collect();
    for (m, s) in sets.iter_mut().enumerate() {
        s.static_solves = evaluator.static_solves(m);
    }
    sets
}

/// The configurations of the shared guide used by the D2 of its neighbours (the segments
/// that end, or start, there), when every neighbour has been tested already; `None` (no
/// pruning) when one has not, or there is none.
fn neighbour_configurations(
    sets: &[Option<SegmentSets>],
    neighbours: impl Iterator<Item = usize>,
    shared: impl Fn(&Pv) -> usize,
) -> Option<BTreeSet<usize>> {
    let mut used = BTreeSet::new();
    let mut any = false;
    for n in neighbours {
        let tested = sets.get(n)?.as_ref()?;
        used.extend(tested.d2.iter().map(&shared));
        any = true;
    }
    any.then_some(used)
}

/// D1 and D2 of segment `m` from its candidates (D'0), given the verdicts of the lengths
/// (sorted, > 0) of one pair of guide configurations: the pairs are evaluated in parallel,
/// each pair's lengths together (so that they can share their solves' start shapes).
pub(super) fn test_segment(
    setup: &Setup,
    m: usize,
    candidates: Vec<Pv>,
    verdicts_of: impl Fn((usize, usize), &[usize]) -> Vec<Option<Miss>> + Sync,
) -> SegmentSets {
    let timer = Instant::now();
    let robustness = &setup.robustness;
    let needed = needed_pvs(&candidates, robustness.delta_s, robustness.range);
    let jobs = pair_jobs(needed.iter().map(|pv| (m, *pv)));
    let mut verdicts = Verdicts::new();
    verdicts.extend(
        &jobs,
        evaluate_jobs(
            &format!("attachment {}", setup.segment_name(m)),
            &jobs,
            |job| verdicts_of(job.pair, &job.lengths),
        ),
    );
    let mut sets = verdicts.sets(setup, &candidates);
    sets.time_s = timer.elapsed().as_secs_f64();
    sets
}
