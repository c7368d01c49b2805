//! Answers no dictionary can bend. Before a chain is offered to the static sweep and the
//! motion test, every piece of it that a dictionary answered — the piece and its robustness
//! neighbours — is solved exactly at every test pose of its segment. A piece the exact test
//! fails is a disagreement with the file: it is reported, naming the record, and taken out
//! of the chains, so a forged or stale dictionary can hide a shorter path but never yield one
//! that breaks a limit (docs/architecture.md, "Certified answers").

use super::chains::Chains;
use super::options::SolveError;
use crate::attachment::{Evaluator, Miss, SegmentPoses, robust_neighbours};
use crate::dictionary::MotionLookup;
use crate::path::{CablePath, Pv};
use serde::Serialize;
use std::collections::BTreeMap;

/// A dictionary record that says a piece holds where the exact test finds it fails.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Disagreement {
    /// The segment (e.g. `C2`).
    pub segment: String,
    /// The link whose catalogue holds the record.
    pub link: String,
    /// The record's clamp places in the link's catalogue, start and end.
    pub places: (usize, usize),
    /// The record's cable length (mm).
    pub length_mm: f64,
    /// The chain's piece whose robustness the record vouched for (its length, mm).
    pub piece_length_mm: f64,
    /// The first limit the exact test finds violated.
    pub limit: &'static str,
    /// The test pose of the segment where it is violated (index among its test poses).
    pub test_pose: usize,
}

impl Disagreement {
    /// One line for people, naming the record and what to do about the file.
    pub fn describe(&self, dictionary: &str) -> String {
        format!(
            "{dictionary}: the record of {} clamp places {} → {} at {:.0} mm says the piece \
             holds; solved exactly, it fails ({}) at test pose {} of {} — the {:.0} mm piece \
             it vouched for is left out. The file is stale or forged: rebuild it, or check it \
             with `cable-dict verify --recompute all`",
            self.link,
            self.places.0,
            self.places.1,
            self.length_mm,
            self.limit,
            self.test_pose,
            self.segment,
            self.piece_length_mm
        )
    }
}

/// What certifying the answers of a solve with a dictionary did.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Certification {
    /// Pieces solved exactly to certify the chains offered (pieces and their robustness
    /// neighbours, each once).
    pub pieces_solved: usize,
    /// Records the exact test contradicted, in the order found.
    pub disagreements: Vec<Disagreement>,
}

/// The chains of another [`Chains`], each certified before it is offered.
pub(super) struct Certified<'c, 'e, 'a> {
    chains: &'c mut dyn Chains,
    evaluator: &'e Evaluator<'a>,
    poses: &'e SegmentPoses,
    lookup: &'e MotionLookup<'e>,
    /// Every piece solved so far, per (segment, piece): its first limit violated, if any.
    solved: BTreeMap<(usize, Pv), Option<Miss>>,
    /// What was found so far.
    pub certification: Certification,
}

impl<'c, 'e, 'a> Certified<'c, 'e, 'a> {
    /// Certifies the chains of `chains` against the exact test of `evaluator` at `poses`,
    /// for the segments `lookup` answers.
    pub(super) fn new(
        chains: &'c mut dyn Chains,
        evaluator: &'e Evaluator<'a>,
        poses: &'e SegmentPoses,
        lookup: &'e MotionLookup<'e>,
    ) -> Certified<'c, 'e, 'a> {
        Certified {
            chains,
            evaluator,
            poses,
            lookup,
            solved: BTreeMap::new(),
            certification: Certification::default(),
        }
    }

    /// The pieces of `path` that a dictionary record made robust and the exact test does
    /// not; each disagreement is recorded.
    fn refuted(&mut self, path: &CablePath) -> Vec<(usize, Pv)> {
        let setup = self.evaluator.setup();
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let robustness = setup.robustness;
        let mut refuted = Vec::new();
        for (m, pv) in path.pieces().filter(|(_, pv)| pv.sub_segments > 0) {
            if self.lookup.record_of(m, &pv).is_none() {
                continue;
            }
            let vouched: Vec<Pv> = std::iter::once(pv)
                .chain(
                    robust_neighbours(&pv, robustness.delta_s, robustness.range)
                        .unwrap_or_default(),
                )
                .collect();
            self.solve(m, &vouched);
            let failing = vouched.iter().find_map(|v| {
                let miss = self.solved.get(&(m, *v))?.as_ref()?;
                Some((*v, *miss))
            });
            let Some((failing, miss)) = failing else {
                continue;
            };
            let Some((link, record)) = self.lookup.record_of(m, &failing) else {
                continue;
            };
            let disagreement = Disagreement {
                segment: setup.segment_name(m),
                link: link.to_string(),
                places: (record.start, record.end),
                length_mm: failing.sub_segments as f64 * pitch_mm,
                piece_length_mm: pv.sub_segments as f64 * pitch_mm,
                limit: miss.rejection.name(),
                test_pose: miss.pose,
            };
            log::warn!(
                "{}",
                disagreement.describe(&self.lookup.dictionary().path().display().to_string())
            );
            self.certification.disagreements.push(disagreement);
            refuted.push((m, pv));
        }
        refuted
    }

    /// Solves the pieces of `pieces` (all of one clamp pair of segment `m`) not solved yet,
    /// at every test pose of the segment.
    fn solve(&mut self, m: usize, pieces: &[Pv]) {
        let Some(first) = pieces.first() else {
            return;
        };
        let pair = (first.start, first.end);
        let mut lengths: Vec<usize> = pieces
            .iter()
            .filter(|pv| !self.solved.contains_key(&(m, **pv)))
            .map(|pv| pv.sub_segments)
            .collect();
        lengths.sort_unstable();
        lengths.dedup();
        let verdicts = self
            .evaluator
            .first_rejections(m, pair, &lengths, &self.poses.poses[m]);
        self.certification.pieces_solved += lengths.len();
        for (&s, verdict) in lengths.iter().zip(verdicts) {
            self.solved.insert((m, Pv::new(s, pair.0, pair.1)), verdict);
        }
    }
}

impl Chains for Certified<'_, '_, '_> {
    fn shortest(&mut self) -> Result<Option<CablePath>, SolveError> {
        loop {
            let Some(path) = self.chains.shortest()? else {
                return Ok(None);
            };
            let refuted = self.refuted(&path);
            if refuted.is_empty() {
                return Ok(Some(path));
            }
            for (m, pv) in refuted {
                self.chains.drop_piece(m, &pv);
            }
        }
    }

    fn drop_piece(&mut self, m: usize, pv: &Pv) {
        self.chains.drop_piece(m, pv);
    }

    fn restore_piece(&mut self, m: usize, pv: &Pv) {
        self.chains.restore_piece(m, pv);
    }

    fn shortest_known(&mut self) -> Result<Option<CablePath>, SolveError> {
        self.chains.shortest_known()
    }
}
