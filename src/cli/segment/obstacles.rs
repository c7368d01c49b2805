//! The robot around a segment (`--robot`): its posed links as obstacles for the contact
//! metric.

use super::super::fk::joint_vector_si;
use super::super::output::Failure;
use super::Args;
use cable_dict::cable::CableSpec;
use cable_dict::pose::Pose;
use cable_dict::robot::Robot;
use cable_dict::stress::{ClampZone, GuideEnd, Obstacles, min_clearance};
use nalgebra::Point3;
use serde::Serialize;

/// The posed robot and what the contact metric needs.
pub struct Scene {
    robot: Robot,
    obstacles: Obstacles,
    link_poses: Vec<Pose>,
    clamp_zones: Vec<ClampZone>,
    cable_radius_m: f64,
    threshold_m: f64,
}

/// The closest approach of a shape to the robot.
#[derive(Serialize)]
pub struct ContactMetric {
    /// Signed clearance (mm): < 0 is a penetration depth.
    pub min_clearance_mm: f64,
    /// The link it is closest to.
    pub link: String,
    /// The sub-segment k (node k → node k + 1).
    pub sub_segment: usize,
    /// The threshold it is compared with (mm).
    pub threshold_mm: f64,
    /// `min_clearance_mm < threshold_mm`.
    pub violation: bool,
}

impl Scene {
    /// The scene of `--robot` / `--joints-deg`, or `None` without a robot.
    pub fn from_args(args: &Args, cable: &CableSpec) -> Result<Option<Scene>, Failure> {
        let (Some(path), Some(joints)) = (&args.robot, &args.joints_deg) else {
            return Ok(None);
        };
        let robot = Robot::from_urdf_file(path).map_err(Failure::input)?;
        let joints = joint_vector_si(&robot, &joints.0);
        robot
            .check_limits(&joints)
            .map_err(|e| Failure::input(anyhow::anyhow!("--joints-deg: {e}")))?;
        let link_poses = robot
            .link_poses(&joints)
            .map_err(|e| Failure::input(anyhow::anyhow!("--joints-deg: {e}")))?;
        let obstacles = Obstacles::from_robot(&robot).map_err(Failure::input)?;
        if !(args.clamp_zone_mm.is_finite() && args.clamp_zone_mm >= 0.0) {
            return Err(Failure::input(anyhow::anyhow!(
                "--clamp-zone-mm {}: must be a finite length ≥ 0",
                args.clamp_zone_mm
            )));
        }
        let mut clamp_zones = Vec::new();
        for (end, link) in [
            (GuideEnd::Start, &args.start_link),
            (GuideEnd::End, &args.end_link),
        ] {
            if let Some(name) = link {
                let link = robot.link_index(name).ok_or_else(|| {
                    Failure::input(anyhow::anyhow!(
                        "link '{name}' is not in {}",
                        robot.source.display()
                    ))
                })?;
                clamp_zones.push(ClampZone::of_length(
                    end,
                    link,
                    args.clamp_zone_mm * 1e-3,
                    cable.sub_segment_pitch_m,
                ));
            }
        }
        Ok(Some(Scene {
            robot,
            obstacles,
            link_poses,
            clamp_zones,
            cable_radius_m: 0.5 * cable.diameter_m,
            threshold_m: args.contact_threshold_mm * 1e-3,
        }))
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// Its links' world poses at --joints-deg.
    pub fn link_poses(&self) -> &[Pose] {
        &self.link_poses
    }

    /// The contact metric of `nodes`; `None` if no link has a collider.
    pub fn contact(&self, nodes: &[Point3<f64>]) -> Result<Option<ContactMetric>, Failure> {
        let clearance = min_clearance(
            &self.obstacles,
            &self.link_poses,
            nodes,
            self.cable_radius_m,
            &self.clamp_zones,
        )
        .map_err(Failure::input)?;
        Ok(clearance.map(|c| ContactMetric {
            min_clearance_mm: c.clearance_m * 1e3,
            link: self.robot.links[c.link].name.clone(),
            sub_segment: c.sub_segment,
            threshold_mm: self.threshold_m * 1e3,
            violation: c.clearance_m < self.threshold_m,
        }))
    }
}
