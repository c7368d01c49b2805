//! Where a clamp sits on its link, measured from features a fitter can find on the real arm:
//! the axis of the joint that moves the link, and the direction to the next joint.
//!
//! The link's *long axis* starts where the joint moving the link crosses its own frame and
//! runs toward the next joint's origin; when the next joint is on that axis or there is none
//! (a wrist), it runs along the moving joint's axis. A clamp is then given in cylindrical
//! coordinates about the long axis: how far along it, how far off it, and at which angle
//! around it, counted clockwise when looking along the long axis, from the side that faces up
//! with the robot at its installation pose (from the front, +x of the base, when the long
//! axis is vertical there). Why these features: docs/architecture.md, "Mounting".

use crate::pose::Pose;
use crate::robot::Robot;
use crate::text_table::decimal;
use nalgebra::{Unit, Vector3};
use serde::Serialize;

/// Shortest distance (m) between the moving and the next joint origin for the link's long
/// axis to point at the next joint; closer, they are one wrist centre.
const MIN_LINK_LENGTH_M: f64 = 0.02;

/// Smallest share of the up direction left once its part along the long axis is removed, for
/// "up" to name a side of the link.
const MIN_SIDEWAYS_SHARE: f64 = 0.3;

/// A cable within this angle (deg) of the long axis runs along the link.
const ALONG_WITHIN_DEG: f64 = 20.0;

/// A clamp's place on its link, from the link's features.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinkPlace {
    /// The joint whose axis the distances start from (the joint that moves the link).
    pub from_joint: String,
    /// The next joint, which the long axis points at; `None` when the long axis is
    /// `from_joint`'s own axis (no next joint off it, as at a flange).
    pub toward: Option<String>,
    /// Distance from `from_joint`'s axis to the next joint along the long axis (mm); `None`
    /// with no next joint off the axis.
    pub next_joint_mm: Option<f64>,
    /// Distance along the long axis from `from_joint` (mm); negative behind it.
    pub along_mm: f64,
    /// Distance of the clamp's cable axis from the long axis (mm).
    pub off_axis_mm: f64,
    /// Angle around the long axis (deg, 0–360), clockwise looking along it, from `zero_side`.
    pub around_deg: f64,
    /// The side 0° faces at the installation pose: `top` or `front`.
    pub zero_side: &'static str,
    /// Angle between the cable (leaving toward the tool) and the long axis (deg).
    pub cable_to_axis_deg: f64,
}

impl LinkPlace {
    /// The place in words, e.g. `173 mm from the joint_4 axis toward joint_5, 72 mm off the
    /// arm's axis at 30° clockwise from the top; cable along the link, toward the tool`.
    pub fn describe(&self) -> String {
        let (along, off) = (decimal(self.along_mm, 0), decimal(self.off_axis_mm, 0));
        let from = &self.from_joint;
        let line = match &self.toward {
            Some(next) => format!(
                "{along} mm from the {from} axis toward {next}, {off} mm off the line between them"
            ),
            None => format!(
                "{along} mm along the {from} axis from the link's frame origin, {off} mm off that axis"
            ),
        };
        format!(
            "{line} at {}° clockwise from the {}; cable {}",
            decimal(self.around_deg, 0),
            self.zero_side,
            self.cable_direction()
        )
    }

    /// How the cable leaves the clamp relative to the link: along it (either way) or across.
    pub fn cable_direction(&self) -> String {
        let angle = self.cable_to_axis_deg;
        let target = match &self.toward {
            Some(next) => next.clone(),
            None => format!("the end of the {} axis", self.from_joint),
        };
        if angle <= ALONG_WITHIN_DEG {
            format!("along the link, toward {target}")
        } else if angle >= 180.0 - ALONG_WITHIN_DEG {
            format!("along the link, away from {target}")
        } else {
            format!("across the link, {}° from its axis", decimal(angle, 0))
        }
    }
}

/// The place of a clamp at `clamp_in_body` (its frame, +z the cable direction) on `body`, a
/// link of `robot` moved by a joint; `link_poses` is the robot at its installation pose.
/// `None` for the root link, which no joint moves (its own frame is the only feature).
pub fn link_place(
    robot: &Robot,
    body: usize,
    clamp_in_body: &Pose,
    link_poses: &[Pose],
) -> Option<LinkPlace> {
    let moving = &robot.joints[robot.links[body].parent_joint?];
    let next = robot
        .joints
        .iter()
        .find(|j| j.parent_link == body && j.origin.translation.vector.norm() > MIN_LINK_LENGTH_M);
    let (axis, toward, next_joint_mm) = match next {
        Some(joint) => (
            Unit::new_normalize(joint.origin.translation.vector),
            Some(joint.name.clone()),
            Some(joint.origin.translation.vector.norm() * 1e3),
        ),
        None => (moving.axis, None, None),
    };
    let body_pose = &link_poses[body];
    let zero = zero_direction(body_pose, &axis);
    let position = clamp_in_body.translation.vector;
    let along = position.dot(&axis);
    let radial = position - axis.into_inner() * along;
    let clockwise = axis.cross(&zero.0);
    let around = radial
        .dot(&clockwise)
        .atan2(radial.dot(&zero.0))
        .to_degrees();
    let cable = clamp_in_body.rotation * Vector3::z();
    Some(LinkPlace {
        from_joint: moving.name.clone(),
        toward,
        next_joint_mm,
        along_mm: along * 1e3,
        off_axis_mm: radial.norm() * 1e3,
        around_deg: around.rem_euclid(360.0),
        zero_side: zero.1,
        cable_to_axis_deg: cable.angle(&axis).to_degrees(),
    })
}

/// The body-frame direction, square to `axis`, that faces up in the world at `body_pose`
/// (the front, world +x, when `axis` is near vertical), with its name.
fn zero_direction(body_pose: &Pose, axis: &Unit<Vector3<f64>>) -> (Vector3<f64>, &'static str) {
    let to_body = body_pose.rotation.inverse();
    let square = |world: Vector3<f64>| {
        let v = to_body * world;
        v - axis.into_inner() * v.dot(axis)
    };
    let up = square(Vector3::z());
    if up.norm() >= MIN_SIDEWAYS_SHARE {
        return (up.normalize(), "top");
    }
    let front = square(Vector3::x());
    let side = if front.norm() >= MIN_SIDEWAYS_SHARE {
        front
    } else {
        square(Vector3::y())
    };
    (side.normalize(), "front")
}
