//! The mounting plan as rows of words, built once for every place that shows it: the printed
//! summary, the report's summary page and the installation sheet render these rows, each in
//! its own format, and say nothing of their own about a clamp or a piece.

use super::{MountingPlan, PhysicalClamp};
use crate::text_table::{decimal, decimals};

/// One physical clamp or fitting, in the fitter's words.
#[derive(Debug, Clone, PartialEq)]
pub struct ClampRow {
    /// `clamp 1`, `gripper connector`.
    pub name: String,
    /// The short name pictures and piece names use: `1`, `gripper connector`.
    pub short_name: String,
    /// The link it goes on.
    pub link: String,
    /// The mark, mm from the cable's end at the tool: `620`.
    pub mark_mm: String,
    /// What the design's ends mean here and what the part lets the cable do, if anything.
    pub note: Option<String>,
    /// Where along the link: `173 mm along the joint_4 axis from the seam with link_3 …`.
    pub along: String,
    /// Off the line and around it: `the cable's axis 72 mm from the joint_4 axis, at …`.
    pub around: String,
    /// How the cable leaves it: `across the link, 90° from its axis …`.
    pub cable: String,
    /// How high the cable's axis stands off the surface: `the cable's axis 12 mm off the
    /// surface (clamp and cable radius)`, or that the placement was written by hand.
    pub height: String,
    /// The same height alone, `12` (mm), for a generated site.
    pub height_mm: Option<String>,
    /// The search's names of its guides and placement, for `-v` and the JSON's readers.
    pub search_names: String,
    /// Position and orientation in the link frame, for CAD: `x, y, z mm; r, p, y deg`.
    pub link_frame: String,
    /// A sliding guide or retraction outlet: the cable slides through it (no mark).
    pub slides: bool,
}

/// One piece of cable between two physical clamps.
#[derive(Debug, Clone, PartialEq)]
pub struct PieceRow {
    /// `1 → 2`.
    pub name: String,
    /// `280`.
    pub length_mm: String,
    /// `across joint_4`, or `on one link`.
    pub across: String,
    /// The setup's piece it is (`C1`), for `-v`.
    pub segment: String,
}

/// The plan's clamps as rows, from the base side.
pub fn clamp_rows(plan: &MountingPlan) -> Vec<ClampRow> {
    plan.clamps.iter().map(clamp_row).collect()
}

fn clamp_row(clamp: &PhysicalClamp) -> ClampRow {
    let (along, around, cable) = match &clamp.place {
        Some(place) => (
            place.along_words(),
            place.around_words(),
            place.cable_direction(),
        ),
        None => (
            format!(
                "on {}, which no joint turns: the model gives no feature to measure from (place \
                 it as the 3D view shows; its place in the link's frame is in result.json)",
                clamp.link
            ),
            String::new(),
            String::new(),
        ),
    };
    let height = match clamp.surface_to_cable_axis_mm {
        Some(h) => format!(
            "the cable's axis {} mm off the surface (the clamp's height and the cable's radius)",
            decimal(h, 0)
        ),
        None if clamp.fitting.is_some() => "where the fitting holds the cable".into(),
        None => "placement written by hand: the cable's axis as given".into(),
    };
    ClampRow {
        name: clamp.name(),
        short_name: clamp.short_name(),
        link: clamp.link.clone(),
        mark_mm: decimal(clamp.mark_mm, 0),
        note: clamp.notes(),
        along,
        around,
        cable,
        height,
        height_mm: clamp.surface_to_cable_axis_mm.map(|h| decimal(h, 0)),
        search_names: format!("{} ({})", clamp.guides_label(), clamp.placement),
        link_frame: format!(
            "{} mm; {} deg",
            decimals(&clamp.xyz_mm, 1),
            decimals(&clamp.rpy_deg, 1)
        ),
        slides: false,
    }
}

/// The plan's sliding guides and retraction outlets as rows, from the base side: `slides`
/// where a clamp's mark would be.
pub fn sliding_rows(plan: &MountingPlan) -> Vec<ClampRow> {
    plan.sliding_parts
        .iter()
        .map(|part| {
            let (along, around, cable) = match &part.place {
                Some(place) => (
                    place.along_words(),
                    place.around_words(),
                    place.cable_direction(),
                ),
                None => (
                    format!("on {}, which no joint turns", part.link),
                    String::new(),
                    String::new(),
                ),
            };
            ClampRow {
                name: part.name(),
                short_name: part.guide.clone(),
                link: part.link.clone(),
                mark_mm: "slides".into(),
                note: Some(part.note()),
                along,
                around,
                cable,
                height: "placement written by hand: the cable's axis as given".into(),
                height_mm: None,
                search_names: format!("{} ({})", part.guide, part.placement),
                link_frame: format!(
                    "{} mm; {} deg",
                    decimals(&part.xyz_mm, 1),
                    decimals(&part.rpy_deg, 1)
                ),
                slides: true,
            }
        })
        .collect()
}

/// The plan's pieces as rows, from the base side.
pub fn piece_rows(plan: &MountingPlan) -> Vec<PieceRow> {
    plan.pieces
        .iter()
        .enumerate()
        .map(|(k, piece)| {
            let mut across = if piece.across_joints.is_empty() {
                "on one link".to_string()
            } else {
                format!("across {}", piece.across_joints.join(", "))
            };
            // What it runs through: a sliding guide, or a retraction holding part of it.
            for part in plan.sliding_parts.iter().filter(|p| p.piece == k) {
                across += &match &part.retraction {
                    Some(r) => format!(
                        "; {} mm of it stored in the retraction at rest",
                        decimal(r.stored_mm, 0)
                    ),
                    None => format!("; through {}", part.name()),
                };
            }
            PieceRow {
                name: plan.piece_name(piece.from_clamp),
                length_mm: decimal(piece.length_mm, 0),
                across,
                segment: piece.segment.clone(),
            }
        })
        .collect()
}

/// `2 clamps to mount; marks are cable lengths from its end at the gripper connector`.
pub fn count_words(plan: &MountingPlan) -> String {
    let n = plan.clamps_to_mount();
    let end = plan
        .clamps
        .last()
        .map(PhysicalClamp::in_words)
        .unwrap_or_default();
    let sliding = match plan.sliding_parts.len() {
        0 => String::new(),
        1 => " and a guide the cable slides through".to_string(),
        k => format!(" and {k} guides the cable slides through"),
    };
    format!(
        "{n} clamp{}{sliding} to mount; marks are cable lengths from its end at {end}",
        if n == 1 { "" } else { "s" }
    )
}

/// `620 mm of cable between the first clamp and the last`.
pub fn length_words(plan: &MountingPlan) -> String {
    let ends = |c: Option<&PhysicalClamp>| c.map(PhysicalClamp::in_words).unwrap_or_default();
    format!(
        "{} mm of cable from {} to {}",
        decimal(plan.length_mm, 0),
        ends(plan.clamps.first()),
        ends(plan.clamps.last())
    )
}
