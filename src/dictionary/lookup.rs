//! Solving with a dictionary: which stored directions a motion needs for each intra-link
//! segment, and the verdict of a PV over exactly those.
//!
//! For every sample of the motion, gravity is expressed in the segment's link frame and every
//! stored direction within the covering radius of it is required, the nearest one always
//! (conservative: a PV passes only if it passes all of them). A PV's verdict is the first
//! failure among the required directions, in stored order.

use super::directions::mark_neighbourhood;
use super::error::{DictionaryError, Problem};
use super::format::{ResultRecord, Verdict};
use super::reader::Dictionary;
use crate::attachment::{Rejection, admissible_pvs, needed_pvs};
use crate::motion::{Motion, MotionError};
use crate::path::Pv;
use crate::pose::Pose;
use crate::setup::Setup;

/// The dictionary's answer for one motion.
#[derive(Debug)]
pub struct MotionLookup<'d> {
    dictionary: &'d Dictionary,
    /// Per segment: the required directions (`None` for inter-link segments).
    required: Vec<Option<Vec<bool>>>,
}

impl<'d> MotionLookup<'d> {
    /// The required directions of every intra-link segment of `setup` over `motion`. Fails
    /// when the dictionary lacks a PV the setup needs.
    pub fn new(
        dictionary: &'d Dictionary,
        setup: &Setup,
        motion: &Motion,
    ) -> Result<MotionLookup<'d>, LookupError> {
        let mut required = vec![None; setup.segment_count()];
        let samples = sample_link_poses(setup, motion)?;
        for m in (0..setup.segment_count()).filter(|&m| setup.is_intra_link(m)) {
            check_coverage(dictionary, setup, m)?;
            required[m] = Some(required_directions(dictionary, setup, &samples, m));
        }
        Ok(MotionLookup {
            dictionary,
            required,
        })
    }

    /// The dictionary answering.
    pub fn dictionary(&self) -> &'d Dictionary {
        self.dictionary
    }

    /// Which stored directions segment `m` needs, `None` for an inter-link segment.
    pub fn required(&self, m: usize) -> Option<&[bool]> {
        self.required.get(m)?.as_deref()
    }

    /// How many stored directions segment `m` needs (0 for an inter-link segment).
    pub fn required_count(&self, m: usize) -> usize {
        self.required(m)
            .map_or(0, |r| r.iter().filter(|&&x| x).count())
    }

    /// The first failure of `pv` of intra-link segment `m` over the required directions;
    /// `None` when it passes them all. A zero-length PV passes.
    pub fn verdict(&self, m: usize, pv: &Pv) -> Option<Rejection> {
        if pv.sub_segments == 0 {
            return None;
        }
        let Some(rows) = self.dictionary.lookup(m, pv) else {
            return Some(Rejection::Diverged);
        };
        first_failure(rows, self.required(m).unwrap_or_default())
    }
}

/// Why a dictionary cannot answer for a motion.
#[derive(Debug, thiserror::Error)]
pub enum LookupError {
    /// The dictionary does not hold what the setup needs.
    #[error("{0}")]
    Dictionary(#[from] DictionaryError),
    /// The motion does not fit the robot.
    #[error("{0}")]
    Motion(#[from] MotionError),
}

fn first_failure(rows: &[ResultRecord], required: &[bool]) -> Option<Rejection> {
    rows.iter()
        .zip(required)
        .filter(|(_, needed)| **needed)
        .find_map(|(row, _)| {
            Verdict::from_byte(row.verdict).map_or(Some(Rejection::Diverged), Verdict::rejection)
        })
}

/// Every PV the attachment test of segment `m` asks about ([`needed_pvs`]: candidates and
/// robustness neighbours) is stored.
fn check_coverage(dictionary: &Dictionary, setup: &Setup, m: usize) -> Result<(), DictionaryError> {
    let robustness = &setup.robustness;
    let candidates = admissible_pvs(setup, m);
    for needed in needed_pvs(&candidates, robustness.delta_s, robustness.range) {
        if needed.sub_segments > 0 && dictionary.lookup(m, &needed).is_none() {
            return Err(DictionaryError::new(
                dictionary.path(),
                Problem::Mismatch(format!(
                    "segment C{} S = {} configurations ({}, {}) is not stored: the \
                     dictionary was built for another setup",
                    m + 1,
                    needed.sub_segments,
                    needed.start,
                    needed.end
                )),
            ));
        }
    }
    Ok(())
}

/// The link poses at every sample of `motion`, computed once for all segments.
fn sample_link_poses(setup: &Setup, motion: &Motion) -> Result<Vec<Vec<Pose>>, MotionError> {
    motion
        .samples()
        .iter()
        .enumerate()
        .map(|(k, joints)| {
            setup
                .robot
                .link_poses(joints)
                .map_err(|e| MotionError::data(format!("sample {k}: {e}")))
        })
        .collect()
}

/// The stored directions within the covering radius of gravity in segment `m`'s link frame
/// at some sample (`samples`: the link poses of every sample).
fn required_directions(
    dictionary: &Dictionary,
    setup: &Setup,
    samples: &[Vec<Pose>],
    m: usize,
) -> Vec<bool> {
    let directions = dictionary.directions();
    let radius = dictionary.header().directions.covering_radius_rad;
    let link = setup.guides[setup.segment_guides(m).0].link;
    let down = setup.gravity_m_s2.normalize();
    let mut required = vec![false; directions.len()];
    for poses in samples {
        let in_link = poses[link].rotation.inverse_transform_vector(&down);
        mark_neighbourhood(directions, &in_link, radius, &mut required);
    }
    required
}
