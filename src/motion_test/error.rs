//! Why a motion test could not be run at all (invalid input), as opposed to a candidate that
//! failed it (a [`MotionTestReport`](super::MotionTestReport) with `passed == false`).

use crate::geometry::ConnectError;
use crate::rigid_chain::DynamicsError;
use crate::robot::JointVectorError;
use crate::statics::StaticsError;
use crate::stress::ContactError;

/// Invalid input to [`run`](super::run): the path, motion or options do not fit the setup.
#[derive(Debug, thiserror::Error)]
pub enum MotionTestError {
    /// `path.lengths` does not have one entry per segment of the setup.
    #[error("the cable path has {got} segment lengths, but the setup has {expected} segments")]
    SegmentCount {
        /// Segments in the setup.
        expected: usize,
        /// Lengths in the path.
        got: usize,
    },
    /// `path.configurations` does not have one entry per guide of the setup.
    #[error("the cable path has {got} guide configurations, but the setup has {expected} guides")]
    GuideCount {
        /// Guides in the setup.
        expected: usize,
        /// Configurations in the path.
        got: usize,
    },
    /// A configuration index beyond the guide's candidate list.
    #[error(
        "guide {name} (path.configurations[{guide}]): configuration index {index} is out of range, the guide has {count} configurations"
    )]
    ConfigurationIndex {
        /// Index of the guide in the setup.
        guide: usize,
        /// The guide's name.
        name: String,
        /// The index given.
        index: usize,
        /// Number of configurations of the guide.
        count: usize,
    },
    /// S = 0 between guides that do not coincide, or S > 0 between guides that do.
    #[error(
        "segment C{} (path.lengths[{segment}] = {sub_segments}): {problem}",
        .segment + 1
    )]
    Inadmissible {
        /// Index of the segment in the setup.
        segment: usize,
        /// Its length in sub-segments.
        sub_segments: usize,
        /// What is wrong.
        problem: String,
    },
    /// Every segment has S = 0: there is no cable to simulate.
    #[error("the cable path has no cable: every segment has length 0")]
    NoCable,
    /// The motion's joints are not the setup robot's.
    #[error("the motion's joints [{motion}] are not the robot's [{robot}]")]
    MotionJoints {
        /// The motion's joint names.
        motion: String,
        /// The robot's actuated joint names.
        robot: String,
    },
    /// Options out of range or inconsistent with the setup.
    #[error("invalid motion-test options: {what}")]
    Options {
        /// What is wrong.
        what: String,
    },
    /// Forward kinematics refused a joint vector of the motion.
    #[error("forward kinematics at t = {time_s} s: {source}")]
    Kinematics {
        /// Time of the joint vector (s).
        time_s: f64,
        /// The kinematics error.
        source: JointVectorError,
    },
    /// The robot's collision geometry cannot serve the clearance queries.
    #[error("robot collision geometry: {0}")]
    Obstacles(#[source] ContactError),
    /// A clearance query refused its input (not expected for a valid setup).
    #[error("clearance of segment C{} at t = {time_s} s: {source}", .segment + 1)]
    Clearance {
        /// Index of the segment in the setup.
        segment: usize,
        /// Time (s).
        time_s: f64,
        /// The query's error.
        source: ContactError,
    },
    /// The connected geometry refused its input (e.g. more sub-segments than it supports).
    #[error("segment C{}: {source}", .segment + 1)]
    Geometry {
        /// Index of the segment in the setup.
        segment: usize,
        /// The geometry error.
        source: ConnectError,
    },
    /// The static solver refused its input (not expected for a valid setup and cable).
    #[error("segment C{}: {source}", .segment + 1)]
    Statics {
        /// Index of the segment in the setup.
        segment: usize,
        /// The statics error.
        source: StaticsError,
    },
    /// The simulation refused its input (robot colliders, poses): not a property of the
    /// candidate.
    #[error("cable simulation: {0}")]
    Dynamics(#[source] DynamicsError),
}
