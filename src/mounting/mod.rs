//! The answer as the workshop mounts it: physical clamps (guides that coincide on a 0 mm
//! piece are one clamp; a clamp that coincides with a fixed guide is that fitting), numbered
//! 1…n from the base side, each with its place on the link measured from the link's features
//! ([`place`]), the mark on the cable where it grips (length from the cable's end at the
//! tool), the robot pose to lay the cable at, and the length tolerance the search tested.
//!
//! The plan is also where the fitter's names come from ([`MountingPlan::clamp_of_guide`],
//! [`MountingPlan::piece_name`]): clamp numbers and fitting names, pieces named by their two
//! ends. The search's names (guides G…, pieces C…) stay in `solve -v` and the JSON.

mod features;
pub mod measured;
pub mod place;
pub mod rows;

use crate::path::CablePath;
use crate::pose::Pose;
use crate::robot::{JointKind, Robot};
use crate::setup::{ConfigurationOrigin, GuideKind, Setup};
use crate::stress::contact::{Obstacles, min_clearance};
use crate::text_table::decimal;
pub use measured::{Matched, MeasuredError, MeasuredMounting};
use nalgebra::Point3;
pub use place::{
    AlongFrom, LinkFeatures, LinkKind, LinkPlace, Turn, ZeroSide, link_features, link_place,
};
use serde::Serialize;

/// A fitting whose cable axis is farther than this (mm) from every collision surface at the
/// installation pose has nothing modelled to be mounted on: the tool is missing from the
/// setup, and the cable near it may run where the real tool is.
pub const FREE_SPACE_MM: f64 = 25.0;

/// What a fitter needs to mount one answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MountingPlan {
    /// Physical clamps and fittings from the cable's start (base side) to its end (tool side).
    pub clamps: Vec<PhysicalClamp>,
    /// The cable between consecutive physical clamps, from the start.
    pub pieces: Vec<MountedPiece>,
    /// Cable length from the first clamp to the last (mm).
    pub length_mm: f64,
    /// Every piece also held its limits this much shorter and longer (mm): the robustness
    /// test's R·ΔS.
    pub piece_tolerance_mm: f64,
    /// The length to cut with the cable file's allowances at its ends; `None` when the file
    /// gives none.
    pub cut: Option<CutLength>,
    /// The robot pose at which the cable is laid untwisted; `None` when the setup gives none
    /// (the clamps' declared frames are then the twist references).
    pub installation_pose: Option<Vec<JointValue>>,
    /// The sliding guides and retraction outlets the cable runs through, from the base side:
    /// parts to mount that grip no mark.
    pub sliding_parts: Vec<SlidingPart>,
}

/// A sliding guide or a retraction's outlet on the robot: the cable runs through it, so it
/// has no mark; the piece through it is one piece between two clamps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlidingPart {
    /// The setup's guide.
    pub guide: String,
    /// `sliding` or `retraction`.
    pub kind: &'static str,
    /// The link it is screwed onto.
    pub link: String,
    /// The placement's name.
    pub placement: String,
    /// Position in the frame of `link` (mm).
    pub xyz_mm: [f64; 3],
    /// URDF roll, pitch, yaw in the frame of `link` (deg).
    pub rpy_deg: [f64; 3],
    /// The place measured from the link's features.
    pub place: Option<LinkPlace>,
    /// Index into [`MountingPlan::pieces`] of the piece through it.
    pub piece: usize,
    /// A sliding guide's friction coefficient.
    pub friction: Option<f64>,
    /// A retraction's spring: force at rest (N), rate (N/mm), travel (mm), and the cable
    /// stored in it at rest from its inlet clamp (mm).
    pub retraction: Option<RetractionSpring>,
}

/// A retraction's spring and stored cable, as the fitter sets it up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RetractionSpring {
    /// Spring force at zero travel (N).
    pub preload_n: f64,
    /// Growth per mm pulled out (N/mm).
    pub rate_n_per_mm: f64,
    /// Travel (mm).
    pub travel_mm: f64,
    /// Cable stored between the inlet clamp and the outlet at rest (mm).
    pub stored_mm: f64,
}

impl SlidingPart {
    /// `sliding guide S`, `retraction outlet R`.
    pub fn name(&self) -> String {
        match self.kind {
            "retraction" => format!("retraction outlet {}", self.guide),
            _ => format!("sliding guide {}", self.guide),
        }
    }

    /// What it does and how it is set up, in the fitter's words.
    pub fn note(&self) -> String {
        match (&self.retraction, self.friction) {
            (Some(r), _) => format!(
                "retraction: load {} mm of cable from the inlet at rest; spring {} N + {} N/mm, \
                 {} mm of travel",
                decimal(r.stored_mm, 0),
                decimal(r.preload_n, 1),
                decimal(r.rate_n_per_mm, 3),
                decimal(r.travel_mm, 0)
            ),
            (None, friction) => format!(
                "the cable slides through it (friction {}): do not clamp it",
                decimal(friction.unwrap_or(0.0), 2)
            ),
        }
    }
}

/// The cable to cut: the designed length and the cable file's allowances (mm).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutLength {
    /// Beyond the last clamp into the connector at the tool (0 when not given).
    pub tool_end_mm: f64,
    /// Before the first clamp, to the base or the controller (0 when not given).
    pub base_end_mm: f64,
    /// The sum with the length between the clamps.
    pub total_mm: f64,
}

/// Where a physical clamp is on the cable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// The first: the cable before it is outside this design.
    Start,
    /// Between the first and the last.
    #[serde(rename = "clamp")]
    Middle,
    /// The last: the cable beyond it is outside this design, unless it is the end's fitting.
    End,
}

/// One clamp (or fitting) on the robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhysicalClamp {
    /// The fitter's number, 1…n from the base side, for a clamp to mount; `None` for a
    /// fitting (a connector or bracket the setup fixes), which is named instead.
    pub number: Option<usize>,
    /// The setup's guides it stands for, e.g. `["G2", "G3"]` when G3 coincides with G2.
    pub guides: Vec<String>,
    /// The setup's 0 mm pieces that make those guides one clamp (`C2`).
    pub joined_by: Vec<String>,
    /// First, middle or last on the cable.
    pub role: Role,
    /// For a fitting (a fixed guide, or a clamp that coincides with one), its name as written,
    /// e.g. `gripper connector`; `None` for a clamp placed by the search.
    pub fitting: Option<String>,
    /// The link it is screwed onto (the fitting's link for a fitting).
    pub link: String,
    /// The placement's name (generated site or configuration).
    pub placement: String,
    /// Position in the frame of `link` (mm).
    pub xyz_mm: [f64; 3],
    /// URDF roll, pitch, yaw in the frame of `link` (deg); +z of that frame is the cable
    /// direction toward the tool.
    pub rpy_deg: [f64; 3],
    /// The place measured from the link's features; `None` where the link has no axis to
    /// measure about.
    pub place: Option<LinkPlace>,
    /// Height of the cable's axis above the link's surface (mm): the clamp height plus the
    /// cable's radius, for a generated site; `None` for a placement written by hand.
    pub surface_to_cable_axis_mm: Option<f64>,
    /// Where it grips the cable: cable length from the end at the tool (mm).
    pub mark_mm: f64,
    /// For a fitting with no collision surface within [`FREE_SPACE_MM`] of its cable axis at
    /// the installation pose: the distance to the nearest (mm). Nothing holds it there.
    pub free_space_mm: Option<f64>,
    /// The part: `rigid`, `rotating` (the cable turns in it) or `swivel` (its direction
    /// turns within `cone_deg`).
    pub kind: &'static str,
    /// A swivel's cone: the half-angle its direction may turn within (deg).
    pub cone_deg: Option<f64>,
}

impl PhysicalClamp {
    /// The fitter's name: `clamp 2`, or the fitting's name (`gripper connector`).
    pub fn name(&self) -> String {
        match (&self.fitting, self.number) {
            (Some(fitting), _) => fitting.clone(),
            (None, Some(n)) => format!("clamp {n}"),
            (None, None) => self.guides.join(" = "),
        }
    }

    /// The name in a sentence: `clamp 2`, `the gripper connector`.
    pub fn in_words(&self) -> String {
        match &self.fitting {
            Some(fitting) => format!("the {fitting}"),
            None => self.name(),
        }
    }

    /// The short name pictures and pieces use: `2`, or the fitting's name.
    pub fn short_name(&self) -> String {
        match (&self.fitting, self.number) {
            (None, Some(n)) => n.to_string(),
            _ => self.name(),
        }
    }

    /// The search's names of its guides: `G2 = G3`.
    pub fn guides_label(&self) -> String {
        self.guides.join(" = ")
    }

    /// What the ends of the design mean for this clamp, if anything: `the cable before it is
    /// outside this design`.
    pub fn role_note(&self) -> Option<&'static str> {
        match (self.role, self.fitting.is_some()) {
            (Role::Start, false) => Some("the cable before it is outside this design"),
            (Role::Start, true) => Some("the cable's start: a fitting, not a clamp to mount"),
            (Role::End, true) => Some("the cable's end: a fitting, not a clamp to mount"),
            (Role::End, false) => Some("the cable beyond it is outside this design"),
            (Role::Middle, true) => Some("a fitting, not a clamp to mount"),
            (Role::Middle, false) => None,
        }
    }

    /// What the part lets the cable do, for a part that is not a rigid clamp: `a rotating
    /// clamp: the cable turns freely about its axis in it`.
    pub fn part_note(&self) -> Option<String> {
        match (self.kind, self.cone_deg) {
            ("rotating", _) => {
                Some("a rotating clamp: the cable turns freely about its axis in it".into())
            }
            ("swivel", Some(cone)) => Some(format!(
                "a swivel clamp: the cable turns freely in it, its direction within {} deg of \
                 the placement's",
                decimal(cone, 0)
            )),
            _ => None,
        }
    }

    /// Every note on this clamp ([`PhysicalClamp::role_note`], [`PhysicalClamp::part_note`]),
    /// joined.
    pub fn notes(&self) -> Option<String> {
        let notes: Vec<String> = (self.role_note().map(str::to_owned).into_iter())
            .chain(self.part_note())
            .collect();
        (!notes.is_empty()).then(|| notes.join("; "))
    }

    /// `the gripper connector (G4) hangs in free space, 58 mm from the nearest collision
    /// surface: …` when nothing modelled holds it.
    pub fn free_space_warning(&self) -> Option<String> {
        let distance = self.free_space_mm?;
        Some(format!(
            "{} ({}) hangs in free space, {} mm from the nearest collision surface at the \
             installation pose: model the tool with [[bodies]] in the setup, or the cable near \
             it may run where the real tool is",
            self.in_words(),
            self.guides_label(),
            decimal(distance, 0)
        ))
    }
}

/// The cable between two physical clamps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MountedPiece {
    /// Index into [`MountingPlan::clamps`] of its start clamp; it ends at the next one.
    pub from_clamp: usize,
    /// Natural length (mm).
    pub length_mm: f64,
    /// The joints it crosses, base side first (empty when both clamps are on one link).
    pub across_joints: Vec<String>,
    /// The setup's cable piece (`C3`) it is: pieces of 0 mm are inside a physical clamp, so
    /// every mounted piece is one of the setup's — but for the two either side of a swivel
    /// clamp between them, which are one piece of the search (`C2–C3`) and bear its name.
    pub segment: String,
}

impl JointValue {
    /// `joint_2 -68.6 deg`, with the pendant's angle when known: `joint_2 -68.6 deg
    /// (pendant 158.6)`.
    pub fn words(&self) -> String {
        let pendant = self
            .pendant
            .map(|p| format!(" (pendant {})", decimal(p, 1)))
            .unwrap_or_default();
        format!(
            "{} {} {}{pendant}",
            self.joint,
            decimal(self.value, 1),
            self.unit
        )
    }
}

/// One joint of the installation pose, in display units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointValue {
    /// The joint's name.
    pub joint: String,
    /// Its value (deg for rotary joints, mm for prismatic ones).
    pub value: f64,
    /// Degrees or millimetres.
    pub unit: crate::robot::DisplayUnit,
    /// The angle the robot's pendant shows (deg), where the setup gives the conversion
    /// (`[pendant_angles]`).
    pub pendant: Option<f64>,
}

impl MountingPlan {
    /// `each piece also held every limit 20 mm shorter and longer: put each mark within
    /// ±10 mm` (a mark off by half the tolerance keeps both neighbouring pieces inside it).
    pub fn tolerance_words(&self) -> String {
        format!(
            "each piece also held every limit {} mm shorter and longer: put each mark within \
             ±{} mm",
            decimal(self.piece_tolerance_mm, 0),
            decimal(self.piece_tolerance_mm / 2.0, 0)
        )
    }

    /// `lay the cable untwisted along its route with the robot at its installation pose:
    /// joint_1 0.0 deg, …`, or what stands in for a pose the setup does not give.
    pub fn installation_words(&self) -> String {
        match &self.installation_pose {
            Some(pose) => {
                let joints: Vec<String> = pose.iter().map(JointValue::words).collect();
                let pendant = if pose.iter().any(|j| j.pendant.is_some()) {
                    "; angles of the robot description (URDF), the pendant's in brackets"
                } else {
                    "; angles of the robot description (URDF): a pendant may count them from \
                     another zero or the other way (give [pendant_angles] in the setup)"
                };
                format!(
                    "lay the cable untwisted along its route with the robot at its installation \
                     pose: {}{pendant}",
                    joints.join(", ")
                )
            }
            None => "the setup gives no installation pose: each clamp's twist reference is its \
                     frame's +x axis as written"
                .into(),
        }
    }

    /// The clamps to mount (fittings are not).
    pub fn clamps_to_mount(&self) -> usize {
        self.clamps.iter().filter(|c| c.fitting.is_none()).count()
    }

    /// The physical clamp guide `guide` (a setup guide name) is part of.
    pub fn clamp_of_guide(&self, guide: &str) -> Option<&PhysicalClamp> {
        self.clamps
            .iter()
            .find(|c| c.guides.iter().any(|g| g == guide))
    }

    /// The fitter's name of the piece starting at clamp `from_clamp`: `1 → 2`,
    /// `2 → gripper connector`.
    pub fn piece_name(&self, from_clamp: usize) -> String {
        let name = |i: usize| self.clamps.get(i).map(PhysicalClamp::short_name);
        format!(
            "{} → {}",
            name(from_clamp).unwrap_or_default(),
            name(from_clamp + 1).unwrap_or_default()
        )
    }

    /// The mounted piece that is the setup's piece `segment` (`C3`); `None` for a 0 mm piece
    /// (inside a clamp) or one not on this path.
    pub fn piece_of_segment(&self, segment: &str) -> Option<&MountedPiece> {
        self.pieces.iter().find(|piece| piece.segment == segment)
    }

    /// [`MountingPlan::piece_words`] of `plan`, or `segment` itself without a plan.
    pub fn piece_words_in(plan: Option<&MountingPlan>, segment: &str) -> String {
        plan.map_or_else(|| segment.to_string(), |plan| plan.piece_words(segment))
    }

    /// The fitter's name of the setup's piece `segment` (`C3`): `piece 2 → gripper
    /// connector` (`pieces 1 → 2 → gripper connector` for the two either side of a swivel
    /// clamp between them); `segment` itself for a piece not mounted (0 mm, or not on this
    /// path).
    pub fn piece_words(&self, segment: &str) -> String {
        let through = self.pieces.iter().filter(|p| p.segment == segment).count();
        match self.piece_of_segment(segment) {
            // Through a swivel clamp: both pieces, `pieces 1 → swivel → gripper connector`.
            Some(piece) if through > 1 => {
                let names: Vec<String> = (piece.from_clamp..=piece.from_clamp + through)
                    .filter_map(|i| self.clamps.get(i).map(PhysicalClamp::short_name))
                    .collect();
                format!("pieces {}", names.join(" → "))
            }
            Some(piece) => format!("piece {}", self.piece_name(piece.from_clamp)),
            None => segment.to_string(),
        }
    }

    /// Where on the mounted cable the setup's piece `segment` is, `along_mm` from its start
    /// (when known): `on piece 2 → gripper connector, 25 mm from clamp 2`, or `at clamp 2`
    /// for a 0 mm piece inside a clamp; `None` for a piece not on this path.
    pub fn place_on_cable(&self, segment: &str, along_mm: Option<f64>) -> Option<String> {
        if let Some(mut piece) = self.piece_of_segment(segment) {
            // Through a swivel clamp the search's piece is two mounted ones: a place is on
            // the one it falls on, measured from that one's start; no place, on both.
            let pieces = self.pieces.iter().filter(|p| p.segment == segment).count();
            if along_mm.is_none() && pieces > 1 {
                return Some(format!("on {}", self.piece_words(segment)));
            }
            let mut along_mm = along_mm;
            for next in self.pieces.iter().filter(|p| p.segment == segment).skip(1) {
                match along_mm {
                    Some(along) if along > piece.length_mm => {
                        along_mm = Some(along - piece.length_mm);
                        piece = next;
                    }
                    _ => break,
                }
            }
            let mut words = format!("on piece {}", self.piece_name(piece.from_clamp));
            // A retraction's free piece is measured from its outlet (the cable behind it is
            // stored in the unit).
            let index = self.pieces.iter().position(|p| std::ptr::eq(p, piece));
            let outlet = (self.sliding_parts.iter())
                .find(|part| Some(part.piece) == index && part.retraction.is_some());
            if let Some(along) = along_mm {
                let from = match outlet {
                    Some(outlet) => format!("out of the {}", outlet.name()),
                    None => format!("from {}", self.clamps[piece.from_clamp].in_words()),
                };
                words += &format!(", {} mm {from}", decimal(along, 0));
            }
            return Some(words);
        }
        self.clamps
            .iter()
            .find(|c| c.joined_by.iter().any(|s| s == segment))
            .map(|clamp| format!("at {}", clamp.in_words()))
    }

    /// The warnings a fitter must read before mounting: fittings that hang in free space.
    pub fn warnings(&self) -> Vec<String> {
        self.clamps
            .iter()
            .filter_map(PhysicalClamp::free_space_warning)
            .collect()
    }
}

impl CutLength {
    /// `cut 2160 mm: 620 mm between the clamps, 40 mm into the connector at the tool,
    /// 1500 mm from the first clamp to the base (the cable file's allowances)`.
    pub fn describe(&self) -> String {
        let between = self.total_mm - self.tool_end_mm - self.base_end_mm;
        format!(
            "cut {} mm: {} mm between the clamps, {} mm into the connector at the tool, {} mm \
             from the first clamp to the base (the cable file's allowances)",
            decimal(self.total_mm, 0),
            decimal(between, 0),
            decimal(self.tool_end_mm, 0),
            decimal(self.base_end_mm, 0)
        )
    }
}

/// The words for the cut length: the rule with the file's allowances, or which allowances
/// would give it.
pub fn cut_words(plan: &MountingPlan) -> String {
    match &plan.cut {
        Some(cut) => cut.describe(),
        None => format!(
            "cut {} mm plus what the cable needs beyond the last clamp and before the first \
             (tool_end_allowance_mm and base_end_allowance_mm in the cable file give the cut \
             length)",
            decimal(plan.length_mm, 0)
        ),
    }
}

/// The mounting plan of `path` in `setup`.
pub fn mounting_plan(setup: &Setup, path: &CablePath) -> MountingPlan {
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    // The clamps and the pieces between them; a swivel clamp between two pieces is a clamp
    // of its own with its mark, the two pieces either side bearing the span's name.
    let mut mounted: Vec<(usize, usize)> = Vec::new();
    let mut segments: Vec<(String, f64)> = Vec::new();
    let mut pieces_of_path = path.pieces();
    for guide in path.guides(setup).zip(path.configurations.iter().copied()) {
        mounted.push(guide);
        let Some((m, pv)) = pieces_of_path.next() else {
            continue;
        };
        let name = setup.segment_name(m);
        let length = |sub_segments: usize| sub_segments as f64 * pitch_mm;
        match setup.swivel_of(m, pv.sub_segments) {
            Some(split) if pv.sub_segments > 0 => {
                segments.push((name.clone(), length(split.before)));
                mounted.push((split.guide, 0));
                segments.push((name, length(pv.sub_segments - split.before)));
            }
            _ => segments.push((name, length(pv.sub_segments))),
        }
    }
    let length_mm: f64 = segments.iter().map(|(_, l)| l).sum();
    let link_poses = installation_link_poses(setup);
    // Per physical clamp, the (guide, configuration) pairs it stands for.
    let mut groups: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut pieces: Vec<MountedPiece> = Vec::new();
    let mut marks: Vec<f64> = Vec::new();
    let mut joined: Vec<Vec<String>> = Vec::new();
    let mut from_start_mm = 0.0;
    for (i, &(g, c)) in mounted.iter().enumerate() {
        let before = i.checked_sub(1).map(|p| &segments[p]);
        from_start_mm += before.map_or(0.0, |(_, l)| *l);
        if let (Some((name, length)), Some(group)) = (before, groups.last_mut()) {
            if *length == 0.0 {
                // A 0 mm piece: the two guides are one clamp.
                group.push((g, c));
                if let Some(joined_by) = joined.last_mut() {
                    joined_by.push(name.clone());
                }
                continue;
            }
            let start_body = setup.guides[group[0].0].body;
            pieces.push(MountedPiece {
                from_clamp: groups.len() - 1,
                length_mm: *length,
                across_joints: joints_between(&setup.robot, start_body, setup.guides[g].body),
                segment: name.clone(),
            });
        }
        groups.push(vec![(g, c)]);
        joined.push(Vec::new());
        marks.push(length_mm - from_start_mm);
    }
    let sliding_parts = path
        .pieces()
        .filter_map(|(m, _)| {
            let slide = setup.slide_of(m)?;
            let name = setup.segment_name(m);
            let piece = pieces.iter().position(|p| p.segment == name)?;
            Some(sliding_part(setup, slide, piece, &link_poses))
        })
        .collect();
    let count = groups.len();
    let mut number = 0;
    let clamps = groups
        .iter()
        .zip(&marks)
        .zip(joined)
        .enumerate()
        .map(|(i, ((group, &mark_mm), joined_by))| {
            let role = match i {
                0 => Role::Start,
                i if i + 1 == count => Role::End,
                _ => Role::Middle,
            };
            let mut clamp = physical_clamp(setup, group, &link_poses, mark_mm, role);
            clamp.joined_by = joined_by;
            if clamp.fitting.is_none() {
                number += 1;
                clamp.number = Some(number);
            }
            clamp
        })
        .collect();
    MountingPlan {
        clamps,
        pieces,
        length_mm,
        piece_tolerance_mm: (setup.robustness.range * setup.robustness.delta_s) as f64 * pitch_mm,
        cut: cut_length(setup, length_mm),
        installation_pose: setup
            .installation
            .as_ref()
            .map(|i| joint_values(setup, &i.joints)),
        sliding_parts,
    }
}

/// The sliding guide or retraction outlet `g` (its one configuration) of `kind`, storing
/// `stored` sub-segments at rest, on the plan's piece `piece`.
fn sliding_part(
    setup: &Setup,
    (g, kind, stored): (usize, GuideKind, usize),
    piece: usize,
    link_poses: &[Pose],
) -> SlidingPart {
    let guide = &setup.guides[g];
    let configuration = &guide.configurations[0];
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let in_body = guide.link_in_body * configuration.pose;
    let (friction, retraction) = match kind {
        GuideKind::Sliding { friction } => (Some(friction), None),
        GuideKind::Retraction {
            preload_n,
            rate_n_per_m,
            travel_max_m,
        } => (
            None,
            Some(RetractionSpring {
                preload_n,
                rate_n_per_mm: rate_n_per_m * 1e-3,
                travel_mm: travel_max_m * 1e3,
                stored_mm: stored as f64 * pitch_mm,
            }),
        ),
        _ => (None, None),
    };
    SlidingPart {
        guide: guide.name.clone(),
        kind: kind.word(),
        link: setup.robot.links[guide.link].name.clone(),
        placement: configuration.name.clone(),
        xyz_mm: configuration.position_mm,
        rpy_deg: configuration.rpy_deg,
        place: link_place(&setup.robot, guide.body, &in_body, link_poses),
        piece,
        friction,
        retraction,
    }
}

/// One physical clamp from the guides of `group` (one, or several joined by 0 mm pieces): a
/// fixed guide among them makes it that fitting, placed as the fitting is declared.
fn physical_clamp(
    setup: &Setup,
    group: &[(usize, usize)],
    link_poses: &[Pose],
    mark_mm: f64,
    role: Role,
) -> PhysicalClamp {
    let &(g, c) = group
        .iter()
        .find(|&&(g, _)| setup.guides[g].fixed)
        .unwrap_or(&group[0]);
    let guide = &setup.guides[g];
    let configuration = &guide.configurations[c];
    // Guides joined by a 0 mm piece are one part: the one that lets the cable do most.
    let kind = (group.iter())
        .map(|&(g, c)| setup.guides[g].configurations[c].kind)
        .max_by_key(GuideKind::rank)
        .unwrap_or(configuration.kind);
    let clamp_in_body = guide.link_in_body * configuration.pose;
    let free_space_mm = guide
        .fixed
        .then(|| fitting_free_space_mm(setup, g, c, link_poses))
        .flatten();
    PhysicalClamp {
        number: None,
        joined_by: Vec::new(),
        guides: group
            .iter()
            .map(|&(g, _)| setup.guides[g].name.clone())
            .collect(),
        role,
        fitting: guide.fixed.then(|| configuration.name.clone()),
        link: setup.robot.links[guide.link].name.clone(),
        placement: configuration.name.clone(),
        xyz_mm: configuration.position_mm,
        rpy_deg: configuration.rpy_deg,
        place: link_place(&setup.robot, guide.body, &clamp_in_body, link_poses),
        surface_to_cable_axis_mm: surface_to_cable_axis_mm(setup, g, c),
        mark_mm,
        free_space_mm,
        kind: kind.word(),
        cone_deg: match kind {
            GuideKind::Swivel { cone_rad } => Some(cone_rad.to_degrees()),
            _ => None,
        },
    }
}

/// Height of the cable axis above the surface for a generated site (or a copy of one).
fn surface_to_cable_axis_mm(setup: &Setup, g: usize, c: usize) -> Option<f64> {
    let (g, _) = match setup.guides[g].configurations[c].origin {
        ConfigurationOrigin::Generated { .. } => (g, c),
        ConfigurationOrigin::Coincident {
            guide,
            configuration,
        } => match setup.guides[guide]
            .configurations
            .get(configuration)?
            .origin
        {
            ConfigurationOrigin::Generated { .. } => (guide, configuration),
            _ => return None,
        },
        ConfigurationOrigin::Declared { .. } => return None,
    };
    let spec = &setup.guides[g].generated.as_ref()?.spec;
    Some((spec.clamp_height_m + 0.5 * setup.cable.diameter_m) * 1e3)
}

/// For fixed guide `g`'s configuration `c`: the distance (mm) from its cable axis to the
/// nearest collision surface at the installation pose when that is more than
/// [`FREE_SPACE_MM`]; `None` when something is near (or the geometry cannot be measured).
fn fitting_free_space_mm(setup: &Setup, g: usize, c: usize, link_poses: &[Pose]) -> Option<f64> {
    let guide = &setup.guides[g];
    let at = link_poses.get(guide.link)? * guide.configurations[c].pose * Point3::origin();
    let obstacles = Obstacles::from_robot(&setup.robot).ok()?;
    let nearest = min_clearance(&obstacles, link_poses, &[at, at], 0.0, &[]).ok()??;
    let distance_mm = nearest.clearance_m * 1e3;
    (distance_mm > FREE_SPACE_MM).then_some(distance_mm)
}

/// The cut length when the cable file gives an allowance.
fn cut_length(setup: &Setup, length_mm: f64) -> Option<CutLength> {
    let cable = &setup.cable;
    if cable.tool_end_allowance_m.is_none() && cable.base_end_allowance_m.is_none() {
        return None;
    }
    let tool_end_mm = cable.tool_end_allowance_m.unwrap_or(0.0) * 1e3;
    let base_end_mm = cable.base_end_allowance_m.unwrap_or(0.0) * 1e3;
    Some(CutLength {
        tool_end_mm,
        base_end_mm,
        total_mm: length_mm + tool_end_mm + base_end_mm,
    })
}

/// The link poses at the installation pose, or with every joint at 0 when the setup has
/// none (the "top" of a link is then its top at the zero pose).
pub fn installation_link_poses(setup: &Setup) -> Vec<Pose> {
    match &setup.installation {
        Some(installation) => installation.link_poses.clone(),
        None => setup
            .robot
            .link_poses(&vec![0.0; setup.robot.dof()])
            .unwrap_or_else(|_| vec![Pose::identity(); setup.robot.links.len()]),
    }
}

/// The joints on the way from link `a` to link `b` that move (fixed joints left out), in the
/// order the cable crosses them from `a`.
pub fn joints_between(robot: &Robot, a: usize, b: usize) -> Vec<String> {
    let up_a = ancestors(robot, a);
    let up_b = ancestors(robot, b);
    let common = up_a.iter().find(|link| up_b.contains(link)).copied();
    let climb = |chain: &[usize]| -> Vec<usize> {
        chain
            .iter()
            .take_while(|&&link| Some(link) != common)
            .filter_map(|&link| robot.links[link].parent_joint)
            .collect()
    };
    let mut joints = climb(&up_a);
    joints.extend(climb(&up_b).into_iter().rev());
    joints
        .into_iter()
        .filter(|&j| robot.joints[j].kind != JointKind::Fixed)
        .map(|j| robot.joints[j].name.clone())
        .collect()
}

/// `link` and its ancestors up to the root.
fn ancestors(robot: &Robot, mut link: usize) -> Vec<usize> {
    let mut chain = vec![link];
    while let Some(joint) = robot.links[link].parent_joint {
        link = robot.joints[joint].parent_link;
        if chain.contains(&link) || chain.len() > robot.links.len() {
            break;
        }
        chain.push(link);
    }
    chain
}

/// The joint vector in display units, with the names of the actuated joints.
fn joint_values(setup: &Setup, joints: &[f64]) -> Vec<JointValue> {
    joints
        .iter()
        .enumerate()
        .map(|(i, &value)| {
            let joint = setup.robot.actuated_joint(i);
            let (scale, unit) = joint.kind.display_unit();
            let pendant = setup.pendant_angles.iter().find(|p| p.joint == i);
            JointValue {
                joint: joint.name.clone(),
                value: value * scale,
                unit,
                pendant: pendant.map(|p| p.of(value * scale)),
            }
        })
        .collect()
}
