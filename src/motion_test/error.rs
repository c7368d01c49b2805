//! Why a motion test could not be run at all (invalid input), as opposed to a candidate that
//! failed it (a [`MotionTestReport`](super::MotionTestReport) with `passed == false`).

use crate::geometry::ConnectError;
use crate::path::PathError;
use crate::rigid_chain::RigidChainError;
use crate::robot::JointVectorError;
use crate::statics::StaticsError;
use crate::stress::ContactError;

/// Invalid input to [`run`](super::run): the path, motion or options do not fit the setup.
#[derive(Debug, thiserror::Error)]
pub enum MotionTestError {
    /// The path does not fit the setup.
    #[error(transparent)]
    Path(#[from] PathError),
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
    #[error("clearance of segment {segment} at t = {time_s} s: {source}")]
    Clearance {
        /// The segment's name.
        segment: String,
        /// Time (s).
        time_s: f64,
        /// The query's error.
        source: ContactError,
    },
    /// The connected geometry refused its input (e.g. more sub-segments than it supports).
    #[error("segment {segment}: {source}")]
    Geometry {
        /// The segment's name.
        segment: String,
        /// The geometry error.
        source: ConnectError,
    },
    /// The static solver refused its input (not expected for a valid setup and cable).
    #[error("segment {segment}: {source}")]
    Statics {
        /// The segment's name.
        segment: String,
        /// The statics error.
        source: StaticsError,
    },
    /// The simulation refused its input (robot colliders, poses): not a property of the
    /// candidate.
    #[error("cable simulation: {0}")]
    Dynamics(#[source] RigidChainError),
}
