//! The contact metric of the motion test: the exact signed clearance of each simulated
//! segment to the robot's links, clamp zones excluded ([`min_clearance`]).

use crate::pose::Pose;
use crate::stress::{ClampZone, Clearance, ContactError, Obstacles, min_clearance};
use nalgebra::Point3;

/// The robot's obstacles and each simulated segment's clamp zones, prepared once.
pub(super) struct ClearanceQuery {
    obstacles: Obstacles,
    radius_m: f64,
    zones: Vec<Vec<ClampZone>>,
}

impl ClearanceQuery {
    /// `zones[j]` are the clamp zones of simulated segment `j`; `radius_m` the cable radius.
    pub fn new(obstacles: Obstacles, radius_m: f64, zones: Vec<Vec<ClampZone>>) -> Self {
        Self {
            obstacles,
            radius_m,
            zones,
        }
    }

    /// Per simulated segment, the clamp zones the query leaves out.
    pub fn zones(&self) -> &[Vec<ClampZone>] {
        &self.zones
    }

    /// Lowest clearance of simulated segment `j` with `nodes`, the links at `link_poses`.
    pub fn segment(
        &self,
        link_poses: &[Pose],
        j: usize,
        nodes: &[Point3<f64>],
    ) -> Result<Option<Clearance>, ContactError> {
        let zones = self.zones.get(j).map(Vec::as_slice).unwrap_or_default();
        min_clearance(&self.obstacles, link_poses, nodes, self.radius_m, zones)
    }
}
