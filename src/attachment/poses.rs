//! The robot poses at which each segment's PVs are tested.
//!
//! - An **inter-link** segment: its critical poses ([`critical_poses`] of the joints between
//!   its two guides' links).
//! - An **intra-link** segment: its shape depends only on gravity's direction in its link's
//!   frame, so it is tested under every gravity direction the motion produces in that frame
//!   — one pose per direction, the first sample (in time) whose direction is more than
//!   [`GRAVITY_RESOLUTION_DEG`] from every direction already chosen — with clearance measured
//!   against its own link only: exactly the question a dictionary answers
//!   ([`IntraLinkCriterion::GravityDirections`]). The other links' places depend on the
//!   pose; the static sweep over every motion pose and the motion test see them. The paper's
//!   rule, one arbitrary pose (the first sample), stays available for comparison
//!   ([`IntraLinkCriterion::FirstPose`]).

use crate::motion::{
    Cell, CriticalPose, Motion, MotionError, RangeGrid, critical_poses, traversed_joints,
};
use crate::pose::Pose;
use crate::setup::Setup;
use nalgebra::Vector3;
use serde::Serialize;

/// Two gravity directions in a link's frame closer than this (degrees) count as one for an
/// intra-link segment's test: the stated resolution of "every direction the motion
/// produces". Between neighbouring directions a piece's bend radius changes by 0.04 mm per
/// degree (median) to 0.46 mm per degree (99th percentile; docs/dictionaries.md), so a
/// direction skipped within 3° moves a 99th-percentile piece by under 1.4 mm; the static
/// sweep then checks every motion pose of the candidates against every link. The bundled
/// motions produce 1–120 directions per link at 3° (2°: 1.5× as many, and as many solves).
pub const GRAVITY_RESOLUTION_DEG: f64 = 3.0;

/// Which poses an intra-link segment is tested at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntraLinkCriterion {
    /// Every gravity direction the motion produces in the link's frame, to
    /// [`GRAVITY_RESOLUTION_DEG`], clearance against the own link: what a dictionary answers.
    #[default]
    GravityDirections,
    /// The paper's rule: one arbitrary pose (the motion's first sample), clearance against
    /// the own link.
    FirstPose,
}
/// One robot pose of the motion at which PVs are tested.
#[derive(Debug, Clone, PartialEq)]
pub struct TestPose {
    /// Which motion of the cell it is a sample of (0 for a single motion).
    pub motion: usize,
    /// Index of the motion sample.
    pub sample: usize,
    /// Time of the sample (s).
    pub time_s: f64,
    /// A pose of an axis-range grid (a list of poses, its "time" the pose's number), not a
    /// moment of a motion.
    pub grid: bool,
    /// Joint vector (rad / m).
    pub joints: Vec<f64>,
    /// Why this pose, e.g. `joint_4 max` or `initial pose`.
    pub reason: String,
    /// World pose of every link (indexed like `robot.links`).
    pub link_poses: Vec<Pose>,
    /// `Some(link)`: clearance is measured against that link only (an intra-link segment's
    /// own link); `None`: against every link.
    pub clearance_link: Option<usize>,
}

impl TestPose {
    /// Gravity's direction (unit; zero without gravity) in the frame of `link` at this pose,
    /// for `gravity_m_s2` in the world frame.
    pub fn gravity_in_link(&self, link: usize, gravity_m_s2: &Vector3<f64>) -> Vector3<f64> {
        let down = gravity_m_s2
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::zeros);
        self.link_poses[link]
            .rotation
            .inverse_transform_vector(&down)
    }
}

/// The test poses of every segment, and the critical poses of the inter-link ones.
#[derive(Debug, Clone)]
pub struct SegmentPoses {
    /// Joint-vector indices traversed by each segment (empty for intra-link segments).
    pub traversed: Vec<Vec<usize>>,
    /// Test poses of each segment, sorted by sample.
    pub poses: Vec<Vec<TestPose>>,
}

impl SegmentPoses {
    /// Critical poses of the inter-link segments of `setup` over `motion`, and the
    /// intra-link segments' gravity directions ([`IntraLinkCriterion::GravityDirections`]).
    pub fn new(setup: &Setup, motion: &Motion) -> Result<SegmentPoses, MotionError> {
        SegmentPoses::with(setup, motion, IntraLinkCriterion::default())
    }

    /// [`SegmentPoses::new`] with the intra-link segments tested by `criterion`.
    pub fn with(
        setup: &Setup,
        motion: &Motion,
        criterion: IntraLinkCriterion,
    ) -> Result<SegmentPoses, MotionError> {
        SegmentPoses::for_cell(setup, &Cell::single(motion.clone(), None), criterion)
    }

    /// The test poses of every motion of `cell`: each inter-link segment's critical poses of
    /// every motion (a pose another motion already has is tested once), each intra-link
    /// segment's gravity directions over all of them (to [`GRAVITY_RESOLUTION_DEG`]). A piece
    /// that holds at these poses holds at every motion's. An axis-range grid of the cell
    /// ([`CellMotion::grid`](crate::motion::CellMotion::grid)) adds each segment's own grid
    /// poses (an intra-link segment's, the directions not met yet).
    pub fn for_cell(
        setup: &Setup,
        cell: &Cell,
        criterion: IntraLinkCriterion,
    ) -> Result<SegmentPoses, MotionError> {
        let robot = &setup.robot;
        let mut traversed = Vec::with_capacity(setup.segment_count());
        let mut poses = Vec::with_capacity(setup.segment_count());
        for m in 0..setup.segment_count() {
            let (a, b) = setup.segment_guides(m);
            let link_a = &robot.links[setup.guides[a].link].name;
            let link_b = &robot.links[setup.guides[b].link].name;
            let joints = traversed_joints(robot, link_a, link_b)?;
            let mut union: Vec<TestPose> = Vec::new();
            for (i, tested) in cell.motions.iter().enumerate() {
                let before = union.len();
                match (&tested.grid, setup.is_intra_link(m)) {
                    (Some(grid), _) => grid_poses(setup, &tested.motion, grid, m, &mut union)?,
                    (None, true) => {
                        intra_link_poses(setup, &tested.motion, m, criterion, &mut union)?
                    }
                    (None, false) => {
                        for pose in critical_poses(&tested.motion, &joints)? {
                            if union.iter().all(|p| p.joints != pose.joints) {
                                union.push(test_pose(setup, pose, None)?);
                            }
                        }
                    }
                }
                for pose in &mut union[before..] {
                    pose.motion = i;
                    pose.reason = cell.label(i, &pose.reason);
                }
            }
            poses.push(union);
            traversed.push(joints);
        }
        Ok(SegmentPoses { traversed, poses })
    }
}

/// Adds to `chosen` segment `m`'s poses of the axis-range grid `grid` (samples of `motion`)
/// that are not there yet: an inter-link segment's every pose (clearance against every
/// link), an intra-link segment's directions not within the grid's gravity resolution of one
/// chosen (clearance against its own link).
fn grid_poses(
    setup: &Setup,
    motion: &Motion,
    grid: &RangeGrid,
    m: usize,
    chosen: &mut Vec<TestPose>,
) -> Result<(), MotionError> {
    let robot = &setup.robot;
    let intra_link = setup.is_intra_link(m);
    let link = setup.guides[setup.segment_guides(m).0].body;
    let gravity = &setup.gravity_m_s2;
    let resolution = grid.gravity_resolution_deg.to_radians().cos();
    let mut directions: Vec<Vector3<f64>> = match intra_link {
        true => chosen
            .iter()
            .map(|p| p.gravity_in_link(link, gravity))
            .collect(),
        false => Vec::new(),
    };
    let own = grid.per_segment.get(m).map_or(&[][..], Vec::as_slice);
    let gridded = grid.gridded.get(m).map_or(&[][..], Vec::as_slice);
    for &k in own {
        let joints = &motion.samples()[k];
        if !intra_link && chosen.iter().any(|p| &p.joints == joints) {
            continue;
        }
        let places: Vec<String> = (gridded.iter())
            .map(|&j| {
                let joint = robot.actuated_joint(j);
                let (per_si, unit) = joint.kind.display_unit();
                format!("{} {:.1} {unit}", joint.name, joints[j] * per_si)
            })
            .collect();
        let reason = format!("pose {k} ({})", places.join(", "));
        let mut pose = test_pose(
            setup,
            motion_sample(motion, k, &reason),
            intra_link.then_some(link),
        )?;
        pose.grid = true;
        if intra_link {
            let down = pose.gravity_in_link(link, gravity);
            if directions.iter().any(|d| d.dot(&down) >= resolution) {
                continue;
            }
            directions.push(down);
            pose.reason = format!(
                "{reason} (gravity ({:.2}, {:.2}, {:.2}) in {}'s frame)",
                down.x, down.y, down.z, robot.links[link].name
            );
        }
        chosen.push(pose);
    }
    Ok(())
}

/// Adds to `chosen` the test poses of intra-link segment `m` under `criterion` over
/// `motion`, in time order, that no pose chosen already stands for.
fn intra_link_poses(
    setup: &Setup,
    motion: &Motion,
    m: usize,
    criterion: IntraLinkCriterion,
    chosen: &mut Vec<TestPose>,
) -> Result<(), MotionError> {
    let link = setup.guides[setup.segment_guides(m).0].body;
    let gravity = &setup.gravity_m_s2;
    let new =
        |k: usize, reason: &str| test_pose(setup, motion_sample(motion, k, reason), Some(link));
    if criterion == IntraLinkCriterion::FirstPose || gravity.norm() == 0.0 {
        if chosen.is_empty() {
            chosen.push(new(0, "first pose")?);
        }
        return Ok(());
    }
    let resolution = GRAVITY_RESOLUTION_DEG.to_radians().cos();
    let link_name = &setup.robot.links[link].name;
    let mut directions: Vec<Vector3<f64>> = chosen
        .iter()
        .map(|p| p.gravity_in_link(link, gravity))
        .collect();
    for k in 0..motion.samples().len() {
        let mut pose = new(k, "")?;
        let down = pose.gravity_in_link(link, gravity);
        if !directions.iter().any(|d| d.dot(&down) >= resolution) {
            pose.reason = format!(
                "gravity ({:.2}, {:.2}, {:.2}) in {link_name}'s frame",
                down.x, down.y, down.z
            );
            directions.push(down);
            chosen.push(pose);
        }
    }
    Ok(())
}

/// Motion sample `k` as a test pose, for `reason`.
pub(super) fn sample_pose(
    setup: &Setup,
    motion: &Motion,
    k: usize,
    reason: &str,
) -> Result<TestPose, MotionError> {
    test_pose(setup, motion_sample(motion, k, reason), None)
}

fn motion_sample(motion: &Motion, k: usize, reason: &str) -> CriticalPose {
    CriticalPose {
        sample: k,
        time_s: motion.times_s()[k],
        joints: motion.samples()[k].clone(),
        reason: reason.to_string(),
    }
}

fn test_pose(
    setup: &Setup,
    pose: CriticalPose,
    clearance_link: Option<usize>,
) -> Result<TestPose, MotionError> {
    let link_poses = setup
        .robot
        .link_poses(&pose.joints)
        .map_err(|e| MotionError::data(format!("sample {}: {e}", pose.sample)))?;
    Ok(TestPose {
        motion: 0,
        sample: pose.sample,
        time_s: pose.time_s,
        grid: false,
        joints: pose.joints,
        reason: pose.reason,
        link_poses,
        clearance_link,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::narrow_pick_and_place;

    /// The cell's poses against each motion's own: every inter-link pose of each motion is
    /// one of the cell's (same joints), none twice; every gravity direction an intra-link
    /// segment meets in any motion is within the resolution of one the cell tests.
    #[test]
    fn a_cell_tests_every_pose_of_each_of_its_motions_once() {
        let (setup, motion) = narrow_pick_and_place();
        // A second motion: the first played backwards from another start, the joints moved.
        let mut samples: Vec<Vec<f64>> = motion.samples().iter().rev().cloned().collect();
        for (k, joints) in samples.iter_mut().enumerate() {
            joints[3] = (joints[3] * 0.5 + 0.3 * (k as f64 * 0.01).sin()).clamp(-2.0, 2.0);
        }
        let other = Motion::new(&setup.robot, motion.times_s().to_vec(), samples)
            .unwrap_or_else(|e| panic!("{e}"));
        let cell = Cell {
            source: None,
            description: None,
            motions: [("a", &motion), ("b", &other)]
                .into_iter()
                .map(|(name, m)| crate::motion::CellMotion {
                    name: name.into(),
                    file: None,
                    cycles_per_hour: None,
                    motion: m.clone(),
                    grid: None,
                })
                .collect(),
        };
        let criterion = IntraLinkCriterion::GravityDirections;
        let union =
            SegmentPoses::for_cell(&setup, &cell, criterion).unwrap_or_else(|e| panic!("{e}"));
        let resolution = GRAVITY_RESOLUTION_DEG.to_radians().cos();
        for (i, m) in [&motion, &other].into_iter().enumerate() {
            let alone = SegmentPoses::with(&setup, m, criterion).unwrap_or_else(|e| panic!("{e}"));
            for s in 0..setup.segment_count() {
                let cell_poses = &union.poses[s];
                if setup.is_intra_link(s) {
                    let link = setup.guides[setup.segment_guides(s).0].body;
                    let g = &setup.gravity_m_s2;
                    for pose in &alone.poses[s] {
                        let down = pose.gravity_in_link(link, g);
                        let near = cell_poses
                            .iter()
                            .any(|p| p.gravity_in_link(link, g).dot(&down) >= resolution);
                        assert!(near, "motion {i}, segment {s}: direction {down:?}");
                    }
                } else {
                    for pose in &alone.poses[s] {
                        assert!(
                            cell_poses.iter().any(|p| p.joints == pose.joints),
                            "motion {i}, segment {s}: {}",
                            pose.reason
                        );
                    }
                }
            }
        }
        for poses in &union.poses {
            for (k, a) in poses.iter().enumerate() {
                assert!(
                    poses[..k].iter().all(|b| b.joints != a.joints),
                    "{}",
                    a.reason
                );
                assert!(
                    a.reason.starts_with("a: ") || a.reason.starts_with("b: "),
                    "{}",
                    a.reason
                );
            }
        }
    }
}
