//! Forward kinematics: the world pose of every link for a joint vector.

use super::{Joint, JointDrive, JointKind, JointVectorError, Robot};
use crate::pose::Pose;
use nalgebra::{Translation3, UnitQuaternion};

/// Slack (rad or m) when checking limits, so that a limit typed in degrees or millimetres and
/// converted to SI is not refused for a last-bit rounding difference.
const LIMIT_TOLERANCE: f64 = 1e-9;

impl Robot {
    /// World (base-frame) pose of every link, indexed like [`Robot::links`].
    ///
    /// `joints` is the joint vector (rad / m). Limits are not checked here — call
    /// [`Robot::check_limits`] first where values come from a user.
    pub fn link_poses(&self, joints: &[f64]) -> Result<Vec<Pose>, JointVectorError> {
        self.check_length(joints)?;
        let mut poses = vec![Pose::identity(); self.links.len()];
        for joint in &self.joints {
            let value = joint_value(joint, joints).unwrap_or(0.0);
            poses[joint.child_link] =
                poses[joint.parent_link] * joint.origin * joint_motion(joint, value);
        }
        Ok(poses)
    }

    /// Checks the length, finiteness and limits of a joint vector, mimic joints included.
    pub fn check_limits(&self, joints: &[f64]) -> Result<(), JointVectorError> {
        self.check_length(joints)?;
        for joint in &self.joints {
            let (Some(value), Some(limits)) = (joint_value(joint, joints), joint.limits) else {
                continue;
            };
            if !value.is_finite() {
                return Err(JointVectorError::NotFinite {
                    joint: joint.name.clone(),
                    value,
                });
            }
            if value < limits.lower - LIMIT_TOLERANCE || value > limits.upper + LIMIT_TOLERANCE {
                let (scale, unit) = joint.kind.display_unit();
                return Err(JointVectorError::OutOfLimits {
                    joint: joint.name.clone(),
                    value: round_for_display(value * scale),
                    lower: round_for_display(limits.lower * scale),
                    upper: round_for_display(limits.upper * scale),
                    unit,
                });
            }
        }
        Ok(())
    }

    fn check_length(&self, joints: &[f64]) -> Result<(), JointVectorError> {
        if joints.len() != self.dof() {
            let names: Vec<&str> = (0..self.dof())
                .map(|i| self.actuated_joint(i).name.as_str())
                .collect();
            return Err(JointVectorError::Length {
                expected: self.dof(),
                got: joints.len(),
                names: names.join(", "),
            });
        }
        if let Some(i) = joints.iter().position(|v| !v.is_finite()) {
            return Err(JointVectorError::NotFinite {
                joint: self.actuated_joint(i).name.clone(),
                value: joints[i],
            });
        }
        Ok(())
    }
}

/// Rounds to 1e-9 so that limits converted to degrees print as typed (120, not 119.99…).
fn round_for_display(value: f64) -> f64 {
    (value * 1e9).round() / 1e9
}

/// The joint's own value (rad / m) for a joint vector; `None` for fixed joints.
fn joint_value(joint: &Joint, joints: &[f64]) -> Option<f64> {
    match joint.drive {
        JointDrive::None => None,
        JointDrive::Actuated { index } => Some(joints[index]),
        JointDrive::Mimic {
            index,
            multiplier,
            offset,
        } => Some(multiplier * joints[index] + offset),
    }
}

/// The motion of the child frame relative to the joint frame.
fn joint_motion(joint: &Joint, value: f64) -> Pose {
    match joint.kind {
        JointKind::Revolute | JointKind::Continuous => Pose::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&joint.axis, value),
        ),
        JointKind::Prismatic => Pose::from_parts(
            Translation3::from(joint.axis.into_inner() * value),
            UnitQuaternion::identity(),
        ),
        JointKind::Fixed => Pose::identity(),
    }
}
