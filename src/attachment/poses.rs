//! The robot poses at which each segment's PVs are tested.
//!
//! - An **inter-link** segment: its critical poses ([`critical_poses`] of the joints between
//!   its two guides' links).
//! - An **intra-link** segment: its shape depends only on gravity's direction in its link's
//!   frame, so it is tested at the motion's first sample and at the critical poses of the
//!   nearest inter-link segment on each side (the poses where the arm around it is at its
//!   extremes). Duplicated samples are tested once.

use crate::motion::{CriticalPose, Motion, MotionError, critical_poses, traversed_joints};
use crate::pose::Pose;
use crate::setup::Setup;

/// One robot pose of the motion at which PVs are tested.
#[derive(Debug, Clone, PartialEq)]
pub struct TestPose {
    /// Index of the motion sample.
    pub sample: usize,
    /// Time of the sample (s).
    pub time_s: f64,
    /// Joint vector (rad / m).
    pub joints: Vec<f64>,
    /// Why this pose, e.g. `joint_4 max` or `initial pose`.
    pub reason: String,
    /// World pose of every link (indexed like `robot.links`).
    pub link_poses: Vec<Pose>,
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
    /// Critical poses of the inter-link segments of `setup` over `motion`, and the test poses
    /// of every segment derived from them.
    pub fn new(setup: &Setup, motion: &Motion) -> Result<SegmentPoses, MotionError> {
        let robot = &setup.robot;
        let mut traversed = Vec::with_capacity(setup.segment_count());
        let mut critical = Vec::with_capacity(setup.segment_count());
        for m in 0..setup.segment_count() {
            let (a, b) = setup.segment_guides(m);
            let link_a = &robot.links[setup.guides[a].link].name;
            let link_b = &robot.links[setup.guides[b].link].name;
            let joints = traversed_joints(robot, link_a, link_b)?;
            critical.push(critical_poses(motion, &joints)?);
            traversed.push(joints);
        }
        let poses = (0..setup.segment_count())
            .map(|m| {
                let chosen = if setup.is_intra_link(m) {
                    intra_link_poses(setup, motion, &critical, m)
                } else {
                    critical[m].clone()
                };
                chosen
                    .into_iter()
                    .map(|pose| test_pose(setup, pose))
                    .collect::<Result<Vec<_>, _>>()
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SegmentPoses { traversed, poses })
    }
}

/// The first sample plus the critical poses of the nearest inter-link segment on each side.
fn intra_link_poses(
    setup: &Setup,
    motion: &Motion,
    critical: &[Vec<CriticalPose>],
    m: usize,
) -> Vec<CriticalPose> {
    let initial = motion_sample(motion, 0, "initial pose");
    let before = (0..m).rev().find(|&n| !setup.is_intra_link(n));
    let after = (m + 1..setup.segment_count()).find(|&n| !setup.is_intra_link(n));
    let mut poses = vec![initial];
    for n in [before, after].into_iter().flatten() {
        poses.extend(critical[n].iter().map(|pose| CriticalPose {
            reason: format!("C{}: {}", n + 1, pose.reason),
            ..pose.clone()
        }));
    }
    poses.sort_by_key(|pose| pose.sample);
    poses.dedup_by_key(|pose| pose.sample);
    poses
}

/// Motion sample `k` as a test pose, for `reason`.
pub(super) fn sample_pose(
    setup: &Setup,
    motion: &Motion,
    k: usize,
    reason: &str,
) -> Result<TestPose, MotionError> {
    test_pose(setup, motion_sample(motion, k, reason))
}

fn motion_sample(motion: &Motion, k: usize, reason: &str) -> CriticalPose {
    CriticalPose {
        sample: k,
        time_s: motion.times_s()[k],
        joints: motion.samples()[k].clone(),
        reason: reason.to_string(),
    }
}

fn test_pose(setup: &Setup, pose: CriticalPose) -> Result<TestPose, MotionError> {
    let link_poses = setup
        .robot
        .link_poses(&pose.joints)
        .map_err(|e| MotionError::data(format!("sample {}: {e}", pose.sample)))?;
    Ok(TestPose {
        sample: pose.sample,
        time_s: pose.time_s,
        joints: pose.joints,
        reason: pose.reason,
        link_poses,
    })
}
