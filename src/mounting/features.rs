//! What a fitter can find on a link of the real arm, and which of it a place is measured from.
//!
//! A link frame's origin is wherever the robot description's author put it, usually inside a
//! casting. What the arm shows are its joints — the centre of a motor housing is a joint's
//! axis — and the ends of its housings: the seam where a link turns against the one before
//! it, the flange face, the base's mounting face. Each link is one of four kinds:
//!
//! - **base** (the robot's root): about the first joint's axis, from the base's mounting face;
//! - **roll**: the link turns about its own long axis (a turret, a forearm or wrist roll): the
//!   next joint's axis lies on the moving joint's axis or crosses it away from the joint, or
//!   the link reaches along its axis at least twice as far as the next joint lies off it. It
//!   is measured about the moving joint's axis, from the seam at its base-side end, with the
//!   next joint's axis as a second feature;
//! - **flange** (no rotary joint after it): about the moving joint's axis, from the flange
//!   face at its tool-side end;
//! - **arm** (every other link: an upper arm, an elbow, an offset wrist): from the moving
//!   joint's axis along the line toward the next joint (along the next joint's own axis when
//!   that axis passes through the moving one at the joint).
//!
//! Ends of housings come from the link's own collision shapes (bodies a setup attaches, such
//! as a tool, are not the robot's features); a link without shapes has no end to measure from,
//! which the place then says.

use crate::pose::Pose;
use crate::robot::Robot;
use nalgebra::{Point3, Unit, Vector3};
use serde::Serialize;

/// Shortest distance (m) that separates two features: joints closer than this are one, a
/// crossing closer to the joint than this is at the joint.
pub const MIN_FEATURE_DISTANCE_M: f64 = 0.02;

/// Two joint axes closer than this (m) meet: one crosses the other, or they are one line.
const AXES_MEET_WITHIN_M: f64 = 0.005;

/// A roll link reaches along its axis at least this many times as far as the next joint lies
/// off the axis (a turret: the Viper's 220 mm against 75 mm, KUKA's 400 mm against 25 mm).
const ROLL_REACH_RATIO: f64 = 2.0;

/// Sines below this are parallel axes.
const PARALLEL_SINE: f64 = 1e-6;

/// How a link is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LinkKind {
    /// The robot's root: about the first joint's axis, from the base's mounting face.
    Base,
    /// From the moving joint's axis along the line toward the next joint.
    Arm,
    /// About the moving joint's axis, which runs along the link, from its base-side seam.
    Roll,
    /// The last link: about the moving joint's axis, from the flange face.
    Flange,
}

/// The feature a place's distance along the measuring line starts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AlongFrom {
    /// The axis of the joint that moves the link (an arm link).
    JointAxis,
    /// The seam at the link's base-side end, where it turns against the link before it.
    Seam,
    /// The flange face at the link's tool-side end.
    FlangeFace,
    /// The base's mounting face (its end away from the arm).
    MountingFace,
    /// The next joint's axis where it crosses the measuring line (a link without shapes).
    NextAxis,
    /// Nothing on the link to measure along the line from (no shapes, no crossing axis).
    Unmeasured,
}

/// The features of one link (a body: the link and those fixed to it), in its frame.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkFeatures {
    /// How the link is measured.
    pub kind: LinkKind,
    /// The joint whose axis the place is measured about or from: the one that moves the link
    /// (the first joint for the base).
    pub joint: String,
    /// The link on the base side of `joint`, whose end the seam is (`None` for the base).
    pub parent_link: Option<String>,
    /// The next rotary joint toward the tool, if any.
    pub next_joint: Option<String>,
    /// Where the measuring line starts (on `joint`'s axis), link frame (m).
    pub origin_m: Point3<f64>,
    /// The measuring line's direction, toward the tool (unit, link frame).
    pub line: Unit<Vector3<f64>>,
    /// On an arm link: the line is the next joint's own axis (which passes through the
    /// moving joint's axis at the joint), not the link's centre line.
    pub line_is_next_axis: bool,
    /// What distances along the line start from, and its coordinate along the line (m).
    pub along_from: (AlongFrom, f64),
    /// Coordinate along the line (m) of the next joint: its axis where it crosses or comes
    /// closest to the line (roll), or its origin (arm); `None` without one.
    pub next_at_m: Option<f64>,
}

/// The features of `body`, a moving link of `robot` or its root; `link_poses` are the links
/// at the installation pose (they orient a line whose direction the joints alone leave open).
/// `None` for a root without a rotary joint, or a link moved by a prismatic joint: no axis to
/// measure about.
pub fn link_features(robot: &Robot, body: usize, link_poses: &[Pose]) -> Option<LinkFeatures> {
    let Some(moving) = robot.links[body].parent_joint.map(|j| &robot.joints[j]) else {
        return base_features(robot, body);
    };
    if !moving.kind.is_rotary() {
        return None;
    }
    let axis = moving.axis;
    let own = Extent::of_body(robot, body);
    let parent_link = robot.links[moving.parent_link].name.clone();
    let away_from_parent = away_from_parent(robot, body, moving.parent_link, &axis, link_poses);
    let features = |kind, line, along_from, next_at_m, next_joint| LinkFeatures {
        kind,
        joint: moving.name.clone(),
        parent_link: Some(parent_link.clone()),
        next_joint,
        origin_m: Point3::origin(),
        line,
        line_is_next_axis: false,
        along_from,
        next_at_m,
    };
    let Some(next) = next_joint(robot, body) else {
        let line = oriented(axis, away_from_parent);
        let face = own
            .map(|e| (AlongFrom::FlangeFace, e.high(&line)))
            .unwrap_or((AlongFrom::Unmeasured, 0.0));
        return Some(features(LinkKind::Flange, line, face, None, None));
    };
    let relation = Relation::of(&axis, &next.point_m, &next.axis);
    let roll_line = |toward: Option<f64>| oriented(axis, toward.or(away_from_parent));
    let roll = |line: Unit<Vector3<f64>>, next_at: Option<f64>| {
        let along_from = match (own, next_at) {
            (Some(e), _) => (AlongFrom::Seam, e.low(&line)),
            (None, Some(at)) => (AlongFrom::NextAxis, at),
            (None, None) => (AlongFrom::Unmeasured, 0.0),
        };
        features(
            LinkKind::Roll,
            line,
            along_from,
            next_at,
            Some(next.name.clone()),
        )
    };
    // An arm link reaches square to its moving axis: its line runs through the middle of its
    // shapes along that axis (where a fitter sees the arm's centre line), square to it.
    let centre_line = || {
        let h = next.point_m.coords.dot(&axis);
        let middle = own.map_or(0.0, |e| 0.5 * (e.high(&axis) + e.low(&axis)));
        let origin = Point3::from(axis.into_inner() * middle);
        (origin, next.point_m - axis.into_inner() * (h - middle))
    };
    let arm = |origin: Point3<f64>, next_point: Point3<f64>| {
        let to_next = next_point - origin;
        let mut f = features(
            LinkKind::Arm,
            Unit::new_normalize(to_next),
            (AlongFrom::JointAxis, 0.0),
            Some(to_next.norm()),
            Some(next.name.clone()),
        );
        f.origin_m = origin;
        f
    };
    Some(match relation {
        Relation::Crossing { at_m } if at_m.abs() >= MIN_FEATURE_DISTANCE_M => {
            let line = roll_line(Some(at_m));
            roll(line, Some(at_m * line.dot(&axis)))
        }
        Relation::Crossing { at_m } => {
            let crossing = Point3::from(axis.into_inner() * at_m);
            if (next.point_m - crossing).norm() >= MIN_FEATURE_DISTANCE_M {
                let mut f = arm(crossing, next.point_m);
                f.line_is_next_axis = true;
                f
            } else {
                roll(roll_line(None), None)
            }
        }
        Relation::Coaxial => {
            let h = next.point_m.coords.dot(&axis);
            let line = roll_line((h.abs() >= MIN_FEATURE_DISTANCE_M).then_some(h));
            let at = line.dot(&axis) * h;
            roll(line, (at.abs() >= MIN_FEATURE_DISTANCE_M).then_some(at))
        }
        Relation::Parallel => {
            let (origin, next_point) = centre_line();
            arm(origin, next_point)
        }
        Relation::Skew { closest_m } => {
            let off =
                (next.point_m.coords - axis.into_inner() * next.point_m.coords.dot(&axis)).norm();
            let reach = own.map_or(0.0, |e| e.length(&axis));
            if reach >= ROLL_REACH_RATIO * off {
                let h = next.point_m.coords.dot(&axis);
                let line = roll_line((h.abs() >= MIN_FEATURE_DISTANCE_M).then_some(h));
                roll(line, Some(closest_m * line.dot(&axis)))
            } else {
                let (origin, next_point) = centre_line();
                arm(origin, next_point)
            }
        }
    })
}

/// The root's features: about its first rotary joint's axis, pointing from the root's shapes
/// toward those of the first link it turns, from the root's own end away from the arm.
fn base_features(robot: &Robot, root: usize) -> Option<LinkFeatures> {
    let next = next_joint(robot, root)?;
    let origin = next.point_m;
    // The first moving link's frame is the joint's, so its axis there is the joint's own.
    let turret = robot.joints[next.index].child_link;
    let axis_in_turret = robot.joints[next.index].axis;
    let turret_middle = Extent::of_body(robot, turret).map(|e| {
        origin.coords.dot(&next.axis) + 0.5 * (e.high(&axis_in_turret) + e.low(&axis_in_turret))
    });
    let base_middle =
        Extent::of_body(robot, root).map(|e| 0.5 * (e.high(&next.axis) + e.low(&next.axis)));
    let arm_middle = match (turret_middle, base_middle) {
        (Some(turret), Some(base)) => Some(turret - base),
        (Some(turret), None) => Some(turret - origin.coords.dot(&next.axis)),
        _ => None,
    };
    let line = oriented(next.axis, arm_middle);
    let own = Extent::of_body(robot, root);
    let along_from = own
        .map(|e| {
            (
                AlongFrom::MountingFace,
                e.low(&line) - origin.coords.dot(&line),
            )
        })
        .unwrap_or((AlongFrom::Unmeasured, 0.0));
    Some(LinkFeatures {
        kind: LinkKind::Base,
        joint: robot.joints[next.index].name.clone(),
        parent_link: None,
        next_joint: Some(robot.joints[next.index].name.clone()),
        origin_m: origin,
        line,
        line_is_next_axis: false,
        along_from,
        next_at_m: None,
    })
}

/// `axis` turned to point along `toward` (a signed coordinate along `axis`), or as it is.
fn oriented(axis: Unit<Vector3<f64>>, toward: Option<f64>) -> Unit<Vector3<f64>> {
    match toward {
        Some(t) if t < 0.0 => -axis,
        _ => axis,
    }
}

/// The next rotary joint after a body, in the body's frame.
struct NextJoint {
    index: usize,
    name: String,
    /// Its origin, a point on its axis (m).
    point_m: Point3<f64>,
    /// Its axis (unit).
    axis: Unit<Vector3<f64>>,
}

/// The first rotary joint (in the robot's order) whose parent moves with `body`. Prismatic
/// joints after a body (gripper fingers) are not joints of the arm.
fn next_joint(robot: &Robot, body: usize) -> Option<NextJoint> {
    robot.joints.iter().enumerate().find_map(|(index, joint)| {
        if !joint.kind.is_rotary() {
            return None;
        }
        let (parent_body, parent_in_body) = robot.moving_body(joint.parent_link);
        if parent_body != body {
            return None;
        }
        let frame = parent_in_body * joint.origin;
        Some(NextJoint {
            index,
            name: joint.name.clone(),
            point_m: Point3::from(frame.translation.vector),
            axis: Unit::new_normalize(frame.rotation * joint.axis.into_inner()),
        })
    })
}

/// How the next joint's axis lies against the moving joint's axis (through the body origin).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Relation {
    /// It crosses the moving axis `at_m` along it.
    Crossing { at_m: f64 },
    /// Both axes are one line.
    Coaxial,
    /// Parallel and apart.
    Parallel,
    /// Neither: its closest approach to the moving axis is `closest_m` along it.
    Skew { closest_m: f64 },
}

impl Relation {
    fn of(axis: &Unit<Vector3<f64>>, point: &Point3<f64>, next: &Unit<Vector3<f64>>) -> Relation {
        let normal = axis.cross(next);
        let sine = normal.norm();
        if sine < PARALLEL_SINE {
            let off = point.coords - axis.into_inner() * point.coords.dot(axis);
            return if off.norm() < AXES_MEET_WITHIN_M {
                Relation::Coaxial
            } else {
                Relation::Parallel
            };
        }
        // Closest points of the lines t·a and p + u·b: (t·a − p − u·b) ⊥ a and ⊥ b.
        let (a, b, p) = (axis.into_inner(), next.into_inner(), point.coords);
        let ab = a.dot(&b);
        let (pa, pb) = (p.dot(&a), p.dot(&b));
        let t = (pa - ab * pb) / (1.0 - ab * ab);
        let distance = (p.dot(&normal) / sine).abs();
        if distance < AXES_MEET_WITHIN_M {
            Relation::Crossing { at_m: t }
        } else {
            Relation::Skew { closest_m: t }
        }
    }
}

/// The sign, along `axis`, that points away from the parent link at the installation pose:
/// the parent's origin lies behind it. `None` when the parent's origin lies square to the
/// axis (then a fixed frame after the body decides, else nothing does).
fn away_from_parent(
    robot: &Robot,
    body: usize,
    parent: usize,
    axis: &Unit<Vector3<f64>>,
    link_poses: &[Pose],
) -> Option<f64> {
    let (Some(body_pose), Some(parent_pose)) = (link_poses.get(body), link_poses.get(parent))
    else {
        return None;
    };
    let parent_in_body = body_pose.inverse() * parent_pose * Point3::origin();
    let behind = parent_in_body.coords.dot(axis);
    if behind.abs() >= MIN_FEATURE_DISTANCE_M {
        return Some(-behind);
    }
    // A frame fixed after the body (a flange or tool frame) on the axis points to the tool.
    robot.rigidly_attached(body).into_iter().find_map(|link| {
        let (_, link_in_body) = robot.moving_body(link);
        let along = link_in_body.translation.vector.dot(axis);
        (along.abs() >= 1e-3).then_some(along)
    })
}

/// The reach of a body's own collision shapes (those of the links moving with it, without
/// the bodies a setup attaches), in the body frame.
#[derive(Debug, Clone, Copy)]
struct Extent<'r> {
    robot: &'r Robot,
    body: usize,
}

impl<'r> Extent<'r> {
    /// `None` when the body has no shapes of its own.
    fn of_body(robot: &'r Robot, body: usize) -> Option<Extent<'r>> {
        let has = robot.rigidly_attached(body).iter().any(|&l| {
            robot.links[l]
                .colliders
                .iter()
                .any(|c| c.attached.is_none())
        });
        has.then_some(Extent { robot, body })
    }

    /// How far the shapes reach along `d` (m, body frame).
    fn high(&self, d: &Unit<Vector3<f64>>) -> f64 {
        let mut reach = f64::NEG_INFINITY;
        for link in self.robot.rigidly_attached(self.body) {
            let (_, link_in_body) = self.robot.moving_body(link);
            for collider in &self.robot.links[link].colliders {
                if collider.attached.is_none() {
                    let pose = link_in_body * collider.origin;
                    reach = reach.max(collider.shape.support_m(&pose, d));
                }
            }
        }
        reach
    }

    /// Where the shapes begin along `d` (m): the lowest `d·x` over them.
    fn low(&self, d: &Unit<Vector3<f64>>) -> f64 {
        -self.high(&-*d)
    }

    /// Their length along `d` (m).
    fn length(&self, d: &Unit<Vector3<f64>>) -> f64 {
        self.high(d) - self.low(d)
    }
}
