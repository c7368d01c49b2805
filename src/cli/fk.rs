//! `cable-dict fk`: link poses for a joint vector.

use super::args;
use super::output::{Failure, emit, print_json, tidy};
use cable_dict::pose::{Pose, rotation_rows};
use cable_dict::robot::Robot;
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The robot's URDF file.
    urdf: PathBuf,
    /// One value per actuated joint, in the order `robot-info` lists them: degrees for rotary
    /// joints, millimetres for prismatic ones (e.g. `0,-90,180,0,0,0`).
    #[arg(long, value_name = "A,B,C,…", allow_hyphen_values = true, value_parser = args::number_list_arg)]
    joints_deg: args::NumberList,
    /// Compute poses even for values beyond the joint limits.
    #[arg(long)]
    allow_beyond_limits: bool,
    /// Print JSON: {"links":[{"name", "position_m", "rotation"}]} (rotation row-major, link to base).
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct LinkPose {
    name: String,
    position_m: [f64; 3],
    rotation: [[f64; 3]; 3],
}

#[derive(Serialize)]
struct FkReport {
    links: Vec<LinkPose>,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let robot = Robot::from_urdf_file(&args.urdf).map_err(Failure::input)?;
    let joints = joint_vector_si(&robot, &args.joints_deg.0);
    if !args.allow_beyond_limits {
        robot
            .check_limits(&joints)
            .map_err(|e| Failure::input(anyhow::anyhow!("--joints-deg: {e}")))?;
    }
    let poses = robot
        .link_poses(&joints)
        .map_err(|e| Failure::input(anyhow::anyhow!("--joints-deg: {e}")))?;
    let report = FkReport {
        links: robot
            .links
            .iter()
            .zip(&poses)
            .map(|(link, pose)| LinkPose {
                name: link.name.clone(),
                position_m: pose.translation.vector.into(),
                rotation: rotation_rows(pose),
            })
            .collect(),
    };
    if args.json {
        print_json(&report)
    } else {
        emit(
            &PoseTable {
                robot: &robot,
                poses: &poses,
            }
            .to_string(),
        )
    }
}

/// Converts command-line units (deg, mm) to SI (rad, m) joint by joint.
pub(super) fn joint_vector_si(robot: &Robot, values: &[f64]) -> Vec<f64> {
    values
        .iter()
        .enumerate()
        .map(
            |(i, &v)| match i < robot.dof() && !robot.actuated_joint(i).kind.is_rotary() {
                true => v * 1e-3,
                false => v.to_radians(),
            },
        )
        .collect()
}

/// The link poses as a table in mm and degrees.
struct PoseTable<'a> {
    robot: &'a Robot,
    poses: &'a [Pose],
}

impl fmt::Display for PoseTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<16} {:>9} {:>9} {:>9}   {:>8} {:>8} {:>8}",
            "link", "x mm", "y mm", "z mm", "roll°", "pitch°", "yaw°"
        )?;
        for (link, pose) in self.robot.links.iter().zip(self.poses) {
            let p = pose.translation.vector.map(|v| tidy(v * 1e3));
            let (roll, pitch, yaw) = pose.rotation.euler_angles();
            let [roll, pitch, yaw] = [roll, pitch, yaw].map(|a| tidy(a.to_degrees()));
            writeln!(
                f,
                "{:<16} {:>9.3} {:>9.3} {:>9.3}   {:>8.3} {:>8.3} {:>8.3}",
                link.name, p.x, p.y, p.z, roll, pitch, yaw
            )?;
        }
        Ok(())
    }
}
