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

use crate::motion::{CriticalPose, Motion, MotionError, critical_poses, traversed_joints};
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
        let mut poses = Vec::with_capacity(setup.segment_count());
        for (m, critical) in critical.into_iter().enumerate() {
            poses.push(if setup.is_intra_link(m) {
                intra_link_poses(setup, motion, m, criterion)?
            } else {
                let all = critical
                    .into_iter()
                    .map(|pose| test_pose(setup, pose, None));
                all.collect::<Result<Vec<_>, _>>()?
            });
        }
        Ok(SegmentPoses { traversed, poses })
    }
}

/// The test poses of intra-link segment `m` under `criterion`, in time order.
fn intra_link_poses(
    setup: &Setup,
    motion: &Motion,
    m: usize,
    criterion: IntraLinkCriterion,
) -> Result<Vec<TestPose>, MotionError> {
    let link = setup.guides[setup.segment_guides(m).0].body;
    let first = test_pose(setup, motion_sample(motion, 0, "first pose"), Some(link))?;
    let gravity = &setup.gravity_m_s2;
    if criterion == IntraLinkCriterion::FirstPose || gravity.norm() == 0.0 {
        return Ok(vec![first]);
    }
    let resolution = GRAVITY_RESOLUTION_DEG.to_radians().cos();
    let link_name = &setup.robot.links[link].name;
    let mut chosen: Vec<(Vector3<f64>, TestPose)> = Vec::new();
    for k in 0..motion.samples().len() {
        let mut pose = test_pose(setup, motion_sample(motion, k, ""), Some(link))?;
        let down = pose.gravity_in_link(link, gravity);
        if !chosen.iter().any(|(d, _)| d.dot(&down) >= resolution) {
            pose.reason = format!(
                "gravity ({:.2}, {:.2}, {:.2}) in {link_name}'s frame",
                down.x, down.y, down.z
            );
            chosen.push((down, pose));
        }
    }
    Ok(chosen.into_iter().map(|(_, pose)| pose).collect())
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
        sample: pose.sample,
        time_s: pose.time_s,
        joints: pose.joints,
        reason: pose.reason,
        link_poses,
        clearance_link,
    })
}
