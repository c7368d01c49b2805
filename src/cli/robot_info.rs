//! `cable-dict robot-info`: what a URDF describes, as the tool understood it.

use super::output::{Failure, emit, print_json, tidy};
use cable_dict::robot::info::RobotInfo;
use cable_dict::robot::{JointDrive, Robot};
use cable_dict::text_table::{Align, TextTable};
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
    let report = RobotInfo::of(&robot);
    if args.json {
        print_json(&report)
    } else {
        emit(&RobotTables(&robot, &report).to_string())
    }
}

/// The robot as human-readable tables (mm, degrees), with its meshes as reported.
struct RobotTables<'a>(&'a Robot, &'a RobotInfo);

impl fmt::Display for RobotTables<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (robot, report) = (self.0, self.1);
        writeln!(
            f,
            "robot '{}' from {}: {} actuated joints",
            robot.name,
            robot.source.display(),
            robot.dof()
        )?;
        writeln!(f)?;
        let mut joints = TextTable::new(
            0,
            &[
                ("#", Align::Left),
                ("joint", Align::Left),
                ("type", Align::Left),
                ("parent → child", Align::Left),
                ("axis", Align::Left),
                ("limits", Align::Right),
                ("max speed", Align::Right),
            ],
        );
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
            joints.row(vec![
                index,
                joint.name.clone(),
                joint.kind.urdf_name().to_string(),
                format!(
                    "{} → {}",
                    robot.links[joint.parent_link].name, robot.links[joint.child_link].name
                ),
                format!("({:.2},{:.2},{:.2})", a.x, a.y, a.z),
                limits,
                speed,
            ]);
        }
        write!(f, "{joints}")?;
        writeln!(f)?;
        writeln!(
            f,
            "links and collision shapes (positions in the link frame, mm):"
        )?;
        for (link, link_report) in robot.links.iter().zip(&report.links) {
            writeln!(f, "  {}", link.name)?;
            for (collider, collider_report) in link.colliders.iter().zip(&link_report.colliders) {
                let p = collider.origin.translation.vector * 1e3;
                let shape = match &collider_report.mesh {
                    Some(mesh) => mesh.text("          "),
                    None => collider.shape.describe(),
                };
                writeln!(f, "      at ({:.1}, {:.1}, {:.1}): {shape}", p.x, p.y, p.z)?;
            }
        }
        if !report.warnings.is_empty() {
            writeln!(f)?;
        }
        for warning in &report.warnings {
            writeln!(f, "warning: {}", warning.message)?;
        }
        Ok(())
    }
}
