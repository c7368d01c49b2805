//! `cable-dict robot-info`: what a URDF describes, as the tool understood it.

use super::{Failure, emit, print_json, tidy};
use cable_dict::pose::Pose;
use cable_dict::robot::{Collider, Joint, JointDrive, Robot, Shape};
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The robot's URDF file.
    urdf: PathBuf,
    /// Print JSON instead of tables (SI units: metres, radians).
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let robot = Robot::from_urdf_file(&args.urdf).map_err(Failure::input)?;
    if args.json {
        print_json(&RobotReport::of(&robot))
    } else {
        emit(&RobotTables(&robot).to_string())
    }
}

#[derive(Serialize)]
struct RobotReport {
    name: String,
    source: String,
    dof: usize,
    joints: Vec<JointReport>,
    links: Vec<LinkReport>,
}

#[derive(Serialize)]
struct JointReport {
    name: String,
    #[serde(rename = "type")]
    kind: &'static str,
    parent: String,
    child: String,
    origin: PoseReport,
    axis: [f64; 3],
    /// Index in the joint vector, for actuated joints.
    joint_vector_index: Option<usize>,
    /// `[joint, multiplier, offset]` for mimic joints.
    mimic: Option<(String, f64, f64)>,
    lower: Option<f64>,
    upper: Option<f64>,
    velocity: Option<f64>,
}

#[derive(Serialize)]
struct PoseReport {
    xyz_m: [f64; 3],
    rpy_rad: [f64; 3],
}

#[derive(Serialize)]
struct LinkReport {
    name: String,
    colliders: Vec<ColliderReport>,
}

#[derive(Serialize)]
struct ColliderReport {
    origin: PoseReport,
    shape: &'static str,
    /// Shape dimensions in metres: box size, radius (+ length), or mesh triangle count.
    description: String,
}

impl RobotReport {
    fn of(robot: &Robot) -> Self {
        RobotReport {
            name: robot.name.clone(),
            source: robot.source.display().to_string(),
            dof: robot.dof(),
            joints: robot
                .joints
                .iter()
                .map(|j| JointReport::of(robot, j))
                .collect(),
            links: robot
                .links
                .iter()
                .map(|l| LinkReport {
                    name: l.name.clone(),
                    colliders: l.colliders.iter().map(ColliderReport::of).collect(),
                })
                .collect(),
        }
    }
}

impl JointReport {
    fn of(robot: &Robot, joint: &Joint) -> Self {
        let limits = joint.limits;
        JointReport {
            name: joint.name.clone(),
            kind: joint.kind.urdf_name(),
            parent: robot.links[joint.parent_link].name.clone(),
            child: robot.links[joint.child_link].name.clone(),
            origin: PoseReport::of(&joint.origin),
            axis: joint.axis.into_inner().into(),
            joint_vector_index: match joint.drive {
                JointDrive::Actuated { index } => Some(index),
                _ => None,
            },
            mimic: match joint.drive {
                JointDrive::Mimic {
                    index,
                    multiplier,
                    offset,
                } => Some((robot.actuated_joint(index).name.clone(), multiplier, offset)),
                _ => None,
            },
            lower: limits.map(|l| l.lower),
            upper: limits.map(|l| l.upper),
            velocity: limits.and_then(|l| l.velocity),
        }
    }
}

impl PoseReport {
    fn of(pose: &Pose) -> Self {
        let (roll, pitch, yaw) = pose.rotation.euler_angles();
        PoseReport {
            xyz_m: pose.translation.vector.into(),
            rpy_rad: [roll, pitch, yaw],
        }
    }
}

impl ColliderReport {
    fn of(collider: &Collider) -> Self {
        let shape = match collider.shape {
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Capsule { .. } => "capsule",
            Shape::Mesh(_) => "mesh",
        };
        ColliderReport {
            origin: PoseReport::of(&collider.origin),
            shape,
            description: collider.shape.describe(),
        }
    }
}

/// The robot as human-readable tables (mm, degrees).
struct RobotTables<'a>(&'a Robot);

impl fmt::Display for RobotTables<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let robot = self.0;
        writeln!(
            f,
            "robot '{}' from {}: {} actuated joints",
            robot.name,
            robot.source.display(),
            robot.dof()
        )?;
        writeln!(f)?;
        writeln!(
            f,
            "{:<3} {:<14} {:<11} {:<24} {:<14} {:>18} {:>10}",
            "#", "joint", "type", "parent → child", "axis", "limits", "max speed"
        )?;
        for joint in &robot.joints {
            let index = match joint.drive {
                JointDrive::Actuated { index } => index.to_string(),
                JointDrive::Mimic { index, .. } => format!("={index}"),
                JointDrive::None => "-".into(),
            };
            let (scale, unit) = joint.kind.display_unit();
            let limits = joint.limits.map_or("-".into(), |l| {
                format!(
                    "{:.1} … {:.1} {unit}",
                    tidy(l.lower * scale),
                    tidy(l.upper * scale)
                )
            });
            let speed = joint
                .limits
                .and_then(|l| l.velocity)
                .map_or("-".into(), |v| format!("{:.0} {unit}/s", v * scale));
            let a = joint.axis;
            writeln!(
                f,
                "{:<3} {:<14} {:<11} {:<24} {:<14} {:>18} {:>10}",
                index,
                joint.name,
                joint.kind.urdf_name(),
                format!(
                    "{} → {}",
                    robot.links[joint.parent_link].name, robot.links[joint.child_link].name
                ),
                format!("({:.2},{:.2},{:.2})", a.x, a.y, a.z),
                limits,
                speed
            )?;
        }
        writeln!(f)?;
        writeln!(
            f,
            "links and collision shapes (positions in the link frame, mm):"
        )?;
        for link in &robot.links {
            writeln!(f, "  {}", link.name)?;
            for collider in &link.colliders {
                let p = collider.origin.translation.vector * 1e3;
                writeln!(
                    f,
                    "      at ({:.1}, {:.1}, {:.1}): {}",
                    p.x,
                    p.y,
                    p.z,
                    collider.shape.describe()
                )?;
            }
        }
        Ok(())
    }
}
