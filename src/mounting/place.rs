//! Where a clamp sits on its link, in words a fitter can follow with a tape: how far along the
//! link's measuring line from a feature on the arm ([`super::features`]), how far the cable's
//! axis is off that line, at which angle around it, and which way the cable leaves.
//!
//! Angles around the line are counted clockwise as seen from the line's base-side end
//! (looking toward the tool; for the base, from above), from the side that faces up with the
//! robot at its installation pose — or, when the line is near vertical there, from the side
//! facing the robot's front (+x of the world). Why these features: docs/architecture.md,
//! "Mounting".

pub use super::features::{AlongFrom, LinkFeatures, LinkKind, link_features};
use crate::pose::Pose;
use crate::robot::Robot;
use crate::text_table::decimal;
use nalgebra::{Point3, Unit, Vector3};
use serde::Serialize;

/// Smallest share of the up direction left once its part along the line is removed, for
/// "up" to name a side of the link.
const MIN_SIDEWAYS_SHARE: f64 = 0.3;

/// A cable within this angle (deg) of the line runs along the link.
const ALONG_WITHIN_DEG: f64 = 20.0;

/// A cable within this angle (deg) of square to the line runs square across it.
const SQUARE_WITHIN_DEG: f64 = 10.0;

/// A line within this angle (deg) of vertical at the installation pose is seen from above or
/// below, which the words then say.
const VERTICAL_WITHIN_DEG: f64 = 25.0;

/// The side 0° faces at the installation pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ZeroSide {
    /// The side facing up.
    Top,
    /// The side facing the robot's front (world +x), for a near-vertical line.
    Front,
}

impl ZeroSide {
    /// `top` or `front`.
    pub fn word(self) -> &'static str {
        match self {
            ZeroSide::Top => "top",
            ZeroSide::Front => "robot's front",
        }
    }
}

/// Which way the cable leans around the line, as the angle is seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Turn {
    /// Clockwise.
    Clockwise,
    /// Anticlockwise.
    Anticlockwise,
    /// Straight away from the line.
    Outward,
    /// Straight toward the line.
    Inward,
}

/// A clamp's place on its link, from the link's features.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinkPlace {
    /// How the link is measured.
    pub kind: LinkKind,
    /// The joint whose axis the place is measured about (base, roll, flange) or from (arm).
    pub joint: String,
    /// The link before `joint`, whose end the seam is; `None` on the base.
    pub parent_link: Option<String>,
    /// The next joint toward the tool; `None` on a flange.
    pub next_joint: Option<String>,
    /// On an arm link: the line is the next joint's own axis, not the link's centre line.
    pub line_is_next_axis: bool,
    /// The feature the distance along the line starts from.
    pub along_from: AlongFrom,
    /// Distance along the line from `along_from` to the clamp (mm), toward the tool; `None`
    /// when nothing on the link can be measured from ([`AlongFrom::Unmeasured`]).
    pub along_mm: Option<f64>,
    /// Where the next joint lies along the line, from the same feature (mm): its origin on an
    /// arm link, its axis on a roll link; `None` without one.
    pub next_joint_mm: Option<f64>,
    /// Distance of the cable's axis (not the clamp's foot) from the line (mm).
    pub off_axis_mm: f64,
    /// Angle around the line (deg, 0–360), clockwise as seen from `seen_from_above` or the
    /// line's base-side end, from `zero_side`.
    pub around_deg: f64,
    /// The side 0° faces at the installation pose.
    pub zero_side: ZeroSide,
    /// The angle is seen from above (the base), not from the line's base-side end.
    pub seen_from_above: bool,
    /// The line is near vertical at the installation pose: its base-side end is below
    /// (`Some(true)`) or above (`Some(false)`) the rest.
    pub base_side_below: Option<bool>,
    /// Angle between the cable (leaving toward the tool) and the line (deg): 0 along it
    /// toward the tool, 180 back.
    pub cable_to_axis_deg: f64,
    /// Which way the cable leans around the line; `None` when it runs along the line.
    pub cable_turn: Option<Turn>,
}

/// The place of a clamp at `clamp_in_body` (its frame, +z the cable direction) on `body`, a
/// link of `robot`; `link_poses` are the links at the installation pose. `None` where the link
/// has no axis to measure about (see [`link_features`]).
pub fn link_place(
    robot: &Robot,
    body: usize,
    clamp_in_body: &Pose,
    link_poses: &[Pose],
) -> Option<LinkPlace> {
    let features = link_features(robot, body, link_poses)?;
    Some(place_on(&features, clamp_in_body, link_poses.get(body)?))
}

/// The place of `clamp_in_body` on a link with `features`, the link at `body_pose` at the
/// installation pose.
pub fn place_on(features: &LinkFeatures, clamp_in_body: &Pose, body_pose: &Pose) -> LinkPlace {
    let line = features.line;
    let from_start = Point3::from(clamp_in_body.translation.vector) - features.origin_m;
    let along = from_start.dot(&line);
    let radial = from_start - line.into_inner() * along;
    let seen_from_above = features.kind == LinkKind::Base;
    let view = if seen_from_above { -line } else { line };
    let (zero, zero_side) = zero_direction(body_pose, &line);
    let clockwise = view.cross(&zero);
    let around = radial.dot(&clockwise).atan2(radial.dot(&zero)).to_degrees();
    let (from, reference) = features.along_from;
    let cable = clamp_in_body.rotation * Vector3::z();
    let to_axis = cable.angle(&line).to_degrees();
    let up_along_line = (body_pose.rotation * line.into_inner()).z;
    let vertical = up_along_line.abs() >= VERTICAL_WITHIN_DEG.to_radians().cos();
    LinkPlace {
        kind: features.kind,
        joint: features.joint.clone(),
        parent_link: features.parent_link.clone(),
        next_joint: features.next_joint.clone(),
        line_is_next_axis: features.line_is_next_axis,
        along_from: from,
        along_mm: (from != AlongFrom::Unmeasured).then_some((along - reference) * 1e3),
        next_joint_mm: features.next_at_m.map(|at| (at - reference) * 1e3),
        off_axis_mm: radial.norm() * 1e3,
        around_deg: around.rem_euclid(360.0),
        zero_side,
        seen_from_above,
        base_side_below: vertical.then_some(up_along_line > 0.0),
        cable_to_axis_deg: to_axis,
        cable_turn: (to_axis > ALONG_WITHIN_DEG && to_axis < 180.0 - ALONG_WITHIN_DEG)
            .then(|| turn(&cable, &radial, &view)),
    }
}

/// Which way `cable` leans around the line `view` looks along, at the radial offset
/// `radial`: the larger of its part around the line and its part away from it.
fn turn(cable: &Vector3<f64>, radial: &Vector3<f64>, view: &Unit<Vector3<f64>>) -> Turn {
    let Some(out) = radial.try_normalize(1e-9) else {
        return Turn::Outward;
    };
    let around = cable.dot(&view.cross(&out));
    let away = cable.dot(&out);
    if around.abs() >= away.abs() {
        if around >= 0.0 {
            Turn::Clockwise
        } else {
            Turn::Anticlockwise
        }
    } else if away >= 0.0 {
        Turn::Outward
    } else {
        Turn::Inward
    }
}

/// The body-frame direction, square to `line`, that faces up in the world at `body_pose`
/// (the front, world +x, when `line` is near vertical), with its name.
fn zero_direction(body_pose: &Pose, line: &Unit<Vector3<f64>>) -> (Vector3<f64>, ZeroSide) {
    let to_body = body_pose.rotation.inverse();
    let square = |world: Vector3<f64>| {
        let v = to_body * world;
        v - line.into_inner() * v.dot(line)
    };
    let up = square(Vector3::z());
    if up.norm() >= MIN_SIDEWAYS_SHARE {
        return (up.normalize(), ZeroSide::Top);
    }
    let front = square(Vector3::x());
    let side = if front.norm() >= MIN_SIDEWAYS_SHARE {
        front
    } else {
        square(Vector3::y())
    };
    (side.normalize(), ZeroSide::Front)
}

impl LinkPlace {
    /// Where the clamp is along the link, e.g. `173 mm along the joint_4 axis from the seam
    /// with link_3 (117 mm before the joint_5 axis)`.
    pub fn along_words(&self) -> String {
        let joint = &self.joint;
        let Some(along) = self.along_mm else {
            return format!(
                "along the {joint} axis: the model has no shape of this link to measure from \
                 (place it as the 3D view shows)"
            );
        };
        let mm = decimal(along, 0);
        let next_gap = match (&self.next_joint, self.next_joint_mm) {
            (Some(next), Some(at)) if self.kind == LinkKind::Roll => {
                let gap = at - along;
                let side = if gap >= 0.0 { "before" } else { "past" };
                format!(" ({} mm {side} the {next} axis)", decimal(gap.abs(), 0))
            }
            _ => String::new(),
        };
        match (self.kind, self.along_from) {
            (LinkKind::Arm, _) => {
                let next = self.next_joint.as_deref().unwrap_or("the next joint");
                let distance = decimal(along.abs(), 0);
                match (self.line_is_next_axis, along >= 0.0) {
                    (true, true) => {
                        format!("{distance} mm along the {next} axis from the {joint} axis")
                    }
                    (true, false) => format!(
                        "{distance} mm along the {next} axis from the {joint} axis, on the far \
                         side from {next}"
                    ),
                    (false, true) => format!("{distance} mm from the {joint} axis toward {next}"),
                    (false, false) => {
                        format!("{distance} mm from the {joint} axis, away from {next}")
                    }
                }
            }
            (_, AlongFrom::Seam) => {
                let parent = self.parent_link.as_deref().unwrap_or("the link before it");
                format!("{mm} mm along the {joint} axis from the seam with {parent}{next_gap}")
            }
            (_, AlongFrom::FlangeFace) => {
                let side = if along >= 0.0 { "beyond" } else { "behind" };
                format!(
                    "{} mm {side} the flange face, along the {joint} axis",
                    decimal(along.abs(), 0)
                )
            }
            (_, AlongFrom::MountingFace) => {
                format!("{mm} mm from the base's mounting face along the {joint} axis")
            }
            (_, AlongFrom::NextAxis) => {
                let next = self.next_joint.as_deref().unwrap_or("next joint's");
                format!("{mm} mm along the {joint} axis from the {next} axis")
            }
            (_, AlongFrom::JointAxis | AlongFrom::Unmeasured) => {
                format!("{mm} mm along the {joint} axis")
            }
        }
    }

    /// How far off the line the cable's axis is and at which angle, e.g. `the cable's axis
    /// 72 mm from the joint_4 axis, at 252° clockwise from the top seen from the link_3 end`.
    pub fn around_words(&self) -> String {
        let off = decimal(self.off_axis_mm, 0);
        let line = match (self.kind, &self.next_joint) {
            (LinkKind::Arm, Some(next)) if self.line_is_next_axis => format!("the {next} axis"),
            (LinkKind::Arm, _) => "the link's centre line".to_string(),
            _ => format!("the {} axis", self.joint),
        };
        format!(
            "the cable's axis {off} mm from {line}, at {}° clockwise from the {} {}",
            decimal(self.around_deg, 0),
            self.zero_side.word(),
            self.seen_from()
        )
    }

    /// `seen from the link_3 end (from below)`, or `seen from above` on the base.
    pub fn seen_from(&self) -> String {
        if self.seen_from_above {
            return "seen from above".into();
        }
        let end = match (self.kind, &self.parent_link) {
            (LinkKind::Arm, _) | (_, None) => format!("the {} end", self.joint),
            (_, Some(parent)) => format!("the {parent} end"),
        };
        let vertical = match self.base_side_below {
            Some(true) => " (from below)",
            Some(false) => " (from above)",
            None => "",
        };
        format!("seen from {end}{vertical}")
    }

    /// Where the line points, toward the tool: the next joint, or the tool on a flange.
    fn ahead(&self) -> String {
        match (self.kind, &self.next_joint) {
            (LinkKind::Base, _) => "the arm".into(),
            (LinkKind::Flange, _) | (_, None) => "the tool".into(),
            (_, Some(next)) => next.clone(),
        }
    }

    /// Where the line comes from: the moving joint, or the link before it.
    fn behind(&self) -> String {
        match (self.kind, &self.parent_link) {
            (LinkKind::Base, _) => "the floor".into(),
            (LinkKind::Arm, _) | (_, None) => self.joint.clone(),
            (_, Some(parent)) => parent.clone(),
        }
    }

    /// How the cable leaves the clamp toward the tool, with its side: `along the link,
    /// toward joint_5`, or `across the link, 68° from its axis toward joint_4, turned
    /// clockwise seen from that end` (the end [`LinkPlace::around_words`] sees it from).
    pub fn cable_direction(&self) -> String {
        let angle = self.cable_to_axis_deg;
        if angle <= ALONG_WITHIN_DEG {
            return format!("along the link, toward {}", self.ahead());
        }
        if angle >= 180.0 - ALONG_WITHIN_DEG {
            return format!("along the link, back toward {}", self.behind());
        }
        let lean = if (angle - 90.0).abs() <= SQUARE_WITHIN_DEG {
            "square to its axis".to_string()
        } else if angle < 90.0 {
            format!(
                "{}° from its axis toward {}",
                decimal(angle, 0),
                self.ahead()
            )
        } else {
            format!(
                "{}° from its axis, back toward {}",
                decimal(angle, 0),
                self.behind()
            )
        };
        let side = match self.cable_turn {
            // Seen from the end the angle around the line is seen from (`around_words`).
            Some(Turn::Clockwise) => ", turned clockwise seen from that end",
            Some(Turn::Anticlockwise) => ", turned anticlockwise seen from that end",
            Some(Turn::Outward) => ", pointing away from the axis",
            Some(Turn::Inward) => ", pointing toward the axis",
            None => "",
        };
        format!("across the link, {lean}{side}")
    }

    /// The place in one line: along, around, and the cable's direction.
    pub fn describe(&self) -> String {
        format!(
            "{}; {}; cable {}",
            self.along_words(),
            self.around_words(),
            self.cable_direction()
        )
    }
}
