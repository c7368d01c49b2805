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
//! holds, which `tests/dictionary.rs` checks over random directions), and the pieces
//! it cannot rule out cost one exact check each.

use super::directions::Neighbours;
use super::error::{DictionaryError, Problem};
use super::format::{ClampEntry, MarginRecord, PvRecord};
use super::reader::Dictionary;
use crate::attachment::{
    LookupAnswer, MarginValues, Margins, Rejection, SegmentPoses, admissible_pvs, needed_pvs,
};
use crate::path::Pv;
use crate::pose::Pose;
use crate::setup::{Guide, PoseIndex, Setup};
use nalgebra::{Quaternion, Translation3, UnitQuaternion, Vector3};

/// The dictionary's answers for one motion.
#[derive(Debug)]
pub struct MotionLookup<'d> {
    dictionary: &'d Dictionary,
    /// Per segment (`None` for inter-link ones): where its pieces are stored and the
    /// interpolation neighbours of each test pose's gravity direction.
    segments: Vec<Option<SegmentLookup>>,
}

#[derive(Debug)]
struct SegmentLookup {
    stored: StoredSegment,
    neighbours: Vec<Neighbours>,
}

/// Where an intra-link segment's pieces are stored: its link's catalogue and the catalogue
/// index of each configuration of its guides.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StoredSegment {
    /// Position of the link's catalogue in [`Header::links`](super::format::Header::links).
    pub slot: usize,
    /// Catalogue index of each configuration of the start guide.
    pub start_clamps: Vec<usize>,
    /// Catalogue index of each configuration of the end guide.
    pub end_clamps: Vec<usize>,
}

impl StoredSegment {
    /// The stored piece (catalogue clamp indices) of the segment's PV `pv`; `None` for a
    /// configuration out of range.
    pub fn piece(&self, pv: &Pv) -> Option<Pv> {
        let start = *self.start_clamps.get(pv.start)?;
        let end = *self.end_clamps.get(pv.end)?;
        Some(Pv::new(pv.sub_segments, start, end))
    }
}

impl<'d> MotionLookup<'d> {
    /// Checks that `setup` can use `dictionary` — the same robot (URDF and meshes), cable,
    /// gravity, limits and installation pose as the setup it was built from, every
    /// configuration of an intra-link segment's guides among the clamp places of its link's
    /// catalogue, every length the attachment test asks for stored — and finds the
    /// interpolation neighbours of every intra-link segment's test poses (`poses`). The
    /// error names the first thing that does not fit.
    pub fn new(
        dictionary: &'d Dictionary,
        setup: &Setup,
        poses: &SegmentPoses,
    ) -> Result<MotionLookup<'d>, LookupError> {
        let built_for = dictionary.setup()?;
        same_physics(&built_for, setup).map_err(|detail| mismatch(dictionary, detail))?;
        let mut segments = Vec::with_capacity(setup.segment_count());
        for m in 0..setup.segment_count() {
            if !setup.is_intra_link(m) {
                segments.push(None);
                continue;
            }
            let stored = dictionary.stored_segment(setup, m)?;
            let body = setup.guides[setup.segment_guides(m).0].body;
            let neighbours = poses.poses[m]
                .iter()
                .map(|pose| {
                    let down: Vector3<f64> = pose.gravity_in_link(body, &setup.gravity_m_s2);
                    Neighbours::of(dictionary.directions(), &down)
                })
                .collect();
            segments.push(Some(SegmentLookup { stored, neighbours }));
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

    /// The record that answers piece `pv` of intra-link segment `m`: its link and the piece
    /// in the link's catalogue (clamp places); `None` for an inter-link segment.
    pub fn record_of(&self, m: usize, pv: &Pv) -> Option<(&'d str, Pv)> {
        let stored = &self.segment(m)?.stored;
        let link = &self.dictionary.header().links.get(stored.slot)?.link;
        Some((link.as_str(), stored.piece(pv)?))
    }

    fn segment(&self, m: usize) -> Option<&SegmentLookup> {
        self.segments.get(m)?.as_ref()
    }

    /// The answer for `pv` of intra-link segment `m` over its test poses. A zero-length PV
    /// holds; a PV the dictionary does not store (never after [`MotionLookup::new`]'s
    /// coverage check) is undecided everywhere — and so is one the file says fails at some
    /// pose: a record forged (or stale) to fail would otherwise keep its piece out of every
    /// chain and the answer longer than the truth, silently. The search decides only pieces
    /// a chain within its bound could use, so these are the file's rejections a shorter chain
    /// would need; what the file says holds is certified on every chain that takes it. So a
    /// dictionary's answer is `solve --setup`'s whatever the file says.
    pub fn answer(&self, m: usize, pv: &Pv) -> LookupAnswer {
        let Some(segment) = self.segment(m) else {
            return LookupAnswer::Holds;
        };
        if pv.sub_segments == 0 {
            return LookupAnswer::Holds;
        }
        let stored = &segment.stored;
        let stored = stored
            .piece(pv)
            .and_then(|piece| self.dictionary.lookup(stored.slot, &piece));
        let Some((record, rows)) = stored else {
            return LookupAnswer::Undecided((0..segment.neighbours.len()).collect());
        };
        let mut undecided = Vec::new();
        for (pose, neighbours) in segment.neighbours.iter().enumerate() {
            match at_direction(record, rows, neighbours) {
                DirectionAnswer::Holds => {}
                DirectionAnswer::Undecided => undecided.push(pose),
                DirectionAnswer::Fails { .. } => {
                    return LookupAnswer::Undecided((0..segment.neighbours.len()).collect());
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
        /// Interpolated `[clearance mm, stretch, curvature 1/m, twist deg/m]`.
        margins: Option<MarginValues>,
    },
    /// The error bound straddles zero, or a neighbour has no equilibrium.
    Undecided,
}

impl Dictionary {
    /// The answer for piece `pv` (catalogue clamp indices) of the link at `slot` with
    /// gravity along `down` (unit vector in the link's frame); `None` when the piece is not
    /// stored. A zero-length piece holds; a cable too short for its clamps fails.
    pub fn answer_at(&self, slot: usize, pv: &Pv, down: &Vector3<f64>) -> Option<DirectionAnswer> {
        self.link(slot)?;
        if pv.sub_segments == 0 {
            return Some(DirectionAnswer::Holds);
        }
        let (record, rows) = self.lookup(slot, pv)?;
        let neighbours = Neighbours::of(self.directions(), down);
        Some(at_direction(record, rows, &neighbours))
    }
}

/// Gravity directions [`Dictionary::undecided_share`] samples: the probe spiral's
/// ([`super::directions::probe_directions`]), at a count no build uses for its probes.
pub const UNDECIDED_SAMPLE_DIRECTIONS: usize = 97;

impl Dictionary {
    /// How often the lookup of a candidate piece of the link at `slot` cannot decide and
    /// leaves the piece to an exact solve: the share of (piece, direction) lookups that are
    /// undecided over [`UNDECIDED_SAMPLE_DIRECTIONS`] gravity directions spread over the
    /// sphere; `None` without candidate pieces.
    pub fn undecided_share(&self, slot: usize) -> Option<f64> {
        let neighbours: Vec<Neighbours> =
            super::directions::probe_directions(UNDECIDED_SAMPLE_DIRECTIONS)
                .iter()
                .map(|d| Neighbours::of(self.directions(), &Vector3::from(*d)))
                .collect();
        let (mut undecided, mut lookups) = (0usize, 0usize);
        let candidates = self.pv_records().iter().filter(|r| {
            usize::from(r.link) == slot && r.has(PvRecord::CANDIDATE) && r.sub_segments > 0
        });
        for candidate in candidates {
            let pv = Pv::new(
                candidate.sub_segments as usize,
                candidate.start.into(),
                candidate.end.into(),
            );
            let Some((record, rows)) = self.lookup(slot, &pv) else {
                continue;
            };
            for around in &neighbours {
                lookups += 1;
                if at_direction(record, rows, around) == DirectionAnswer::Undecided {
                    undecided += 1;
                }
            }
        }
        (lookups > 0).then(|| undecided as f64 / lookups as f64)
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
    let upper: MarginValues = std::array::from_fn(|k| margins[k] + error[k]);
    if let Some(rejection) = Margins::first_violation(upper) {
        return DirectionAnswer::Fails {
            rejection,
            margins: Some(margins),
        };
    }
    let lower: MarginValues = std::array::from_fn(|k| margins[k] - error[k]);
    match Margins::first_violation(lower) {
        None => DirectionAnswer::Holds,
        Some(_) => DirectionAnswer::Undecided,
    }
}

/// Why a dictionary cannot answer for a motion.
#[derive(Debug, thiserror::Error)]
pub enum LookupError {
    /// The dictionary does not hold what the setup needs.
    #[error(transparent)]
    Dictionary(#[from] DictionaryError),
}

fn mismatch(dictionary: &Dictionary, detail: String) -> DictionaryError {
    DictionaryError::new(dictionary.path(), Problem::Mismatch(detail))
}

/// What differs between the physics of `built_for` (a dictionary's setup) and `setup`, for
/// people; `Ok` when a piece evaluates the same under both.
fn same_physics(built_for: &Setup, setup: &Setup) -> Result<(), String> {
    let install = |s: &Setup| s.installation.as_ref().map(|i| i.joints.clone());
    // What the margins are measured against (not where the bend limit was written).
    let limits = |s: &Setup| {
        let t = &s.thresholds;
        [
            t.contact_clearance_m,
            t.stretch,
            t.static_min_bend_radius_m(),
            t.clamp_zone_m,
        ]
    };
    let difference = if built_for.robot_text != setup.robot_text {
        "another robot (the URDF texts differ)".to_string()
    } else if built_for.robot.mesh_files != setup.robot.mesh_files {
        "another robot (its mesh files differ)".to_string()
    } else if built_for.cable_text != setup.cable_text {
        "another cable (the cable files differ)".to_string()
    } else if built_for.gravity_m_s2 != setup.gravity_m_s2 {
        format!(
            "gravity {:?} m/s², the setup has {:?}",
            built_for.gravity_m_s2.as_slice(),
            setup.gravity_m_s2.as_slice()
        )
    } else if limits(built_for) != limits(setup) {
        "other limits ([thresholds] differ)".to_string()
    } else if install(built_for) != install(setup) {
        "another installation pose (install_joints_deg differs)".to_string()
    } else {
        return Ok(());
    };
    Err(format!(
        "built for {} with {difference}: build a dictionary from this setup (cable-dict \
         build) or use solve --setup",
        built_for.source.display()
    ))
}

impl Dictionary {
    /// Where the pieces of intra-link segment `m` of `setup` are stored; an error naming the
    /// first configuration of its guides that is not among the clamp places of its link's
    /// catalogue, or the first length the attachment test asks for that is not stored.
    /// (Whether `setup` has the dictionary's physics is [`MotionLookup::new`]'s check.)
    pub fn stored_segment(
        &self,
        setup: &Setup,
        m: usize,
    ) -> Result<StoredSegment, DictionaryError> {
        let (a, b) = setup.segment_guides(m);
        let link = &setup.robot.links[setup.guides[a].body].name;
        let fail =
            |detail: String| mismatch(self, format!("segment {}: {detail}", setup.segment_name(m)));
        let slot = self
            .link_slot(link)
            .ok_or_else(|| fail(format!("{link} has no clamp catalogue in the dictionary")))?;
        let entry = &self.header().links[slot];
        let places: Vec<Pose> = entry.clamps.iter().map(clamp_pose).collect();
        let places = PoseIndex::of(&places);
        let start_clamps =
            place_indices(&places, entry.clamps.len(), &setup.guides[a], link).map_err(&fail)?;
        let end_clamps =
            place_indices(&places, entry.clamps.len(), &setup.guides[b], link).map_err(&fail)?;
        let robustness = &setup.robustness;
        let candidates = admissible_pvs(setup, m);
        for needed in needed_pvs(&candidates, robustness.delta_s, robustness.range) {
            let length = u32::try_from(needed.sub_segments).unwrap_or(u32::MAX);
            if needed.sub_segments > 0 && entry.lengths.binary_search(&length).is_err() {
                return Err(fail(format!(
                    "S = {} is not stored (the dictionary holds S = {} to {} on {link})",
                    needed.sub_segments,
                    entry.lengths.first().copied().unwrap_or(0),
                    entry.lengths.last().copied().unwrap_or(0)
                )));
            }
        }
        Ok(StoredSegment {
            slot,
            start_clamps,
            end_clamps,
        })
    }
}

/// The index among `places` (the catalogue's poses in the link's frame) of each
/// configuration of `guide`; `Err` naming the first that is not one of them, with its
/// position.
fn place_indices(
    places: &PoseIndex,
    place_count: usize,
    guide: &Guide,
    link: &str,
) -> Result<Vec<usize>, String> {
    (0..guide.configurations.len())
        .map(|c| {
            let pose = guide.pose_in_body(c);
            places.find(&pose).ok_or_else(|| {
                let mm = pose.translation.vector * 1e3;
                format!(
                    "{} '{}' at ({:.1}, {:.1}, {:.1}) mm is not among the dictionary's {} clamp \
                     places on {link}",
                    guide.name, guide.configurations[c].name, mm.x, mm.y, mm.z, place_count
                )
            })
        })
        .collect()
}

/// The pose of a stored clamp place (a header [`parse`](super::format::parse) accepted has
/// unit quaternions).
fn clamp_pose(clamp: &ClampEntry) -> Pose {
    let [x, y, z, w] = clamp.rotation_xyzw;
    Pose::from_parts(
        Translation3::from(Vector3::from(clamp.position_m)),
        UnitQuaternion::new_unchecked(Quaternion::new(w, x, y, z)),
    )
}
