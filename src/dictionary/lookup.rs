//! Solving with a dictionary: the question `solve --setup` answers exactly for an intra-link
//! piece — does it hold its three limits under every gravity direction the motion produces
//! in its link's frame ([`crate::attachment::IntraLinkCriterion::GravityDirections`]) — answered
//! from the stored margins.
//!
//! At each test pose of the segment (one per distinct direction), the margins are
//! interpolated from the [`NEIGHBOURS`](super::directions::NEIGHBOURS) nearest stored
//! directions and widened by the piece's measured interpolation error
//! ([`PvRecord::error_bound`]):
//!
//! - every widened margin non-negative at every pose: the piece **holds**;
//! - some margin negative even widened, at some pose: the piece **fails** there;
//! - otherwise the dictionary cannot decide, and the attachment test solves the piece at the
//!   undecided poses ([`LookupAnswer::Undecided`]).
//!
//! So the dictionary never rejects a piece the exact test keeps (as long as the error bound
//! holds, which `tests/dictionary_lookup.rs` checks over random directions), and the pieces
//! it cannot rule out cost one exact check each.

use super::directions::Neighbours;
use super::error::{DictionaryError, Problem};
use super::format::{MarginRecord, PvRecord};
use super::reader::Dictionary;
use crate::attachment::{
    LookupAnswer, Margins, Rejection, SegmentPoses, admissible_pvs, needed_pvs,
};
use crate::path::Pv;
use crate::setup::Setup;
use nalgebra::Vector3;

/// The dictionary's answers for one motion.
#[derive(Debug)]
pub struct MotionLookup<'d> {
    dictionary: &'d Dictionary,
    /// Per segment (`None` for inter-link ones): the interpolation neighbours of each test
    /// pose's gravity direction, and the error bound.
    segments: Vec<Option<SegmentLookup>>,
}

#[derive(Debug)]
struct SegmentLookup {
    neighbours: Vec<Neighbours>,
}

impl<'d> MotionLookup<'d> {
    /// The interpolation neighbours of every intra-link segment's test poses (`poses`, for
    /// `setup`, the dictionary's setup). Fails when the dictionary lacks a PV the setup
    /// needs.
    pub fn new(
        dictionary: &'d Dictionary,
        setup: &Setup,
        poses: &SegmentPoses,
    ) -> Result<MotionLookup<'d>, LookupError> {
        let mut segments = Vec::with_capacity(setup.segment_count());
        let gravity = setup.gravity_m_s2;
        for m in 0..setup.segment_count() {
            if !setup.is_intra_link(m) {
                segments.push(None);
                continue;
            }
            check_coverage(dictionary, setup, m)?;
            if dictionary.segment(m).is_none() {
                return Err(
                    mismatch(dictionary, format!("segment C{} is not stored", m + 1)).into(),
                );
            }
            let link = setup.guides[setup.segment_guides(m).0].link;
            let neighbours = poses.poses[m]
                .iter()
                .map(|pose| {
                    let down: Vector3<f64> = pose.gravity_in_link(link, &gravity);
                    Neighbours::of(dictionary.directions(), &down)
                })
                .collect();
            segments.push(Some(SegmentLookup { neighbours }));
        }
        Ok(MotionLookup {
            dictionary,
            segments,
        })
    }

    /// The dictionary answering.
    pub fn dictionary(&self) -> &'d Dictionary {
        self.dictionary
    }

    /// How many distinct gravity directions segment `m` is looked up at (0 for an
    /// inter-link segment).
    pub fn direction_count(&self, m: usize) -> usize {
        self.segment(m).map_or(0, |s| s.neighbours.len())
    }

    fn segment(&self, m: usize) -> Option<&SegmentLookup> {
        self.segments.get(m)?.as_ref()
    }

    /// The answer for `pv` of intra-link segment `m` over its test poses. A zero-length PV
    /// holds; a PV the dictionary does not store (never after [`MotionLookup::new`]'s
    /// coverage check) is undecided everywhere.
    pub fn answer(&self, m: usize, pv: &Pv) -> LookupAnswer {
        let Some(segment) = self.segment(m) else {
            return LookupAnswer::Holds;
        };
        if pv.sub_segments == 0 {
            return LookupAnswer::Holds;
        }
        let Some((record, rows)) = self.dictionary.lookup(m, pv) else {
            return LookupAnswer::Undecided((0..segment.neighbours.len()).collect());
        };
        let mut undecided = Vec::new();
        for (pose, neighbours) in segment.neighbours.iter().enumerate() {
            match at_direction(record, rows, neighbours) {
                DirectionAnswer::Holds => {}
                DirectionAnswer::Undecided => undecided.push(pose),
                DirectionAnswer::Fails { rejection, margins } => {
                    return LookupAnswer::Fails {
                        pose,
                        rejection,
                        margins,
                    };
                }
            }
        }
        if undecided.is_empty() {
            LookupAnswer::Holds
        } else {
            LookupAnswer::Undecided(undecided)
        }
    }
}

/// The dictionary's answer for one piece under one gravity direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DirectionAnswer {
    /// Every interpolated margin, widened by the error bound, is non-negative.
    Holds,
    /// A margin is negative even widened, or the cable is too short for its clamps: the
    /// first such limit and the interpolated margins (none for a cable too short).
    Fails {
        /// The limit.
        rejection: Rejection,
        /// Interpolated `[clearance mm, stretch, curvature 1/m]`.
        margins: Option<[f64; 3]>,
    },
    /// The error bound straddles zero, or a neighbour has no equilibrium.
    Undecided,
}

impl Dictionary {
    /// The answer for `pv` of intra-link segment `m` with gravity along `down` (unit vector
    /// in the link's frame); `None` when the piece is not stored. A zero-length piece holds;
    /// a cable too short for its clamps fails.
    pub fn answer_at(&self, m: usize, pv: &Pv, down: &Vector3<f64>) -> Option<DirectionAnswer> {
        self.segment(m)?;
        if pv.sub_segments == 0 {
            return Some(DirectionAnswer::Holds);
        }
        let (record, rows) = self.lookup(m, pv)?;
        let neighbours = Neighbours::of(self.directions(), down);
        Some(at_direction(record, rows, &neighbours))
    }
}

/// Classifies the margins of `rows` interpolated at `neighbours` against the error bound of
/// `record`.
fn at_direction(
    record: &PvRecord,
    rows: &[MarginRecord],
    neighbours: &Neighbours,
) -> DirectionAnswer {
    if record.has(PvRecord::TOO_SHORT) {
        return DirectionAnswer::Fails {
            rejection: Rejection::TooShort,
            margins: None,
        };
    }
    let Some(interpolated) = neighbours.interpolate(|k| rows.get(k)?.values()) else {
        return DirectionAnswer::Undecided;
    };
    let margins = interpolated.mean;
    let error = record.error_bound(interpolated.spread);
    let upper: [f64; 3] = std::array::from_fn(|k| margins[k] + error[k]);
    if let Some(rejection) = Margins::first_violation(upper) {
        return DirectionAnswer::Fails {
            rejection,
            margins: Some(margins),
        };
    }
    let lower: [f64; 3] = std::array::from_fn(|k| margins[k] - error[k]);
    match Margins::first_violation(lower) {
        None => DirectionAnswer::Holds,
        Some(_) => DirectionAnswer::Undecided,
    }
}

/// Why a dictionary cannot answer for a motion.
#[derive(Debug, thiserror::Error)]
pub enum LookupError {
    /// The dictionary does not hold what the setup needs.
    #[error("{0}")]
    Dictionary(#[from] DictionaryError),
}

fn mismatch(dictionary: &Dictionary, detail: String) -> DictionaryError {
    DictionaryError::new(dictionary.path(), Problem::Mismatch(detail))
}

/// Every PV the attachment test of segment `m` asks about ([`needed_pvs`]: candidates and
/// robustness neighbours) is stored.
fn check_coverage(dictionary: &Dictionary, setup: &Setup, m: usize) -> Result<(), DictionaryError> {
    let robustness = &setup.robustness;
    let candidates = admissible_pvs(setup, m);
    for needed in needed_pvs(&candidates, robustness.delta_s, robustness.range) {
        if needed.sub_segments > 0 && dictionary.lookup(m, &needed).is_none() {
            return Err(mismatch(
                dictionary,
                format!(
                    "segment C{} S = {} configurations ({}, {}) is not stored: the \
                     dictionary was built for another setup",
                    m + 1,
                    needed.sub_segments,
                    needed.start,
                    needed.end
                ),
            ));
        }
    }
    Ok(())
}
