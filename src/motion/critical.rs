//! Critical poses of an inter-link segment (algorithm in the [module](super)
//! docs).

use super::{Motion, MotionError};
use crate::robot::{JointDrive, Robot};

/// Default tolerance (rad or m) within which consecutive samples count as dwelling at a
/// joint's extreme.
pub const DWELL_TOLERANCE: f64 = 1e-6;

/// One critical pose: a sample of the motion and why it was chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalPose {
    /// Index of the sample in the motion.
    pub sample: usize,
    /// Time of the sample (s).
    pub time_s: f64,
    /// The joint vector at that sample (rad / m, joint-vector order).
    pub joints: Vec<f64>,
    /// Why, e.g. `joint_4 max`, or `joint_6 min while joint_5 rests at its max (1.20–1.70 s)`;
    /// several
    /// reasons for one sample are joined by `; `.
    pub reason: String,
}

/// The joint-vector indices (ascending) of the joints on the kinematic path between links
/// `link_a` and `link_b` (URDF names): the joints whose motion changes the pose of one link
/// relative to the other. A mimic joint on the path counts as the joint it follows; fixed
/// joints do not count. Empty for the same link (or links joined only by fixed joints).
pub fn traversed_joints(
    robot: &Robot,
    link_a: &str,
    link_b: &str,
) -> Result<Vec<usize>, MotionError> {
    let a = link(robot, link_a)?;
    let b = link(robot, link_b)?;
    let up_a = ancestors(robot, a);
    let up_b = ancestors(robot, b);
    let common = up_a
        .iter()
        .position(|l| up_b.contains(l))
        .map_or(0, |i| up_a[i]);
    let mut joints: Vec<usize> = path_joints(robot, a, common)
        .chain(path_joints(robot, b, common))
        .filter_map(|j| match robot.joints[j].drive {
            JointDrive::None => None,
            JointDrive::Actuated { index } | JointDrive::Mimic { index, .. } => Some(index),
        })
        .collect();
    joints.sort_unstable();
    joints.dedup();
    Ok(joints)
}

/// [`critical_poses_with_tolerance`] with [`DWELL_TOLERANCE`].
pub fn critical_poses(
    motion: &Motion,
    traversed: &[usize],
) -> Result<Vec<CriticalPose>, MotionError> {
    critical_poses_with_tolerance(motion, traversed, DWELL_TOLERANCE)
}

/// The critical poses of a segment whose traversed joints (joint-vector indices) are
/// `traversed`, sorted by time, one per sample. Samples within `tolerance` (rad or m) of a
/// joint's extreme, consecutive with the extreme's first instant, form its dwell.
pub fn critical_poses_with_tolerance(
    motion: &Motion,
    traversed: &[usize],
    tolerance: f64,
) -> Result<Vec<CriticalPose>, MotionError> {
    let mut joints = traversed.to_vec();
    joints.sort_unstable();
    joints.dedup();
    if let Some(&bad) = joints.iter().find(|&&j| j >= motion.dof()) {
        return Err(MotionError::data(format!(
            "traversed joint index {bad} is beyond the motion's {} joints",
            motion.dof()
        )));
    }
    let mut picks: Vec<Pick> = Vec::new();
    for &j in &joints {
        for kind in [Extreme::Max, Extreme::Min] {
            picks.extend(extreme_picks(motion, &joints, j, kind, tolerance));
        }
    }
    Ok(merge(motion, picks))
}

/// A critical sample and why: a joint's extreme (`joint_5 min`), over the whole motion or
/// within another joint's dwell at its extreme (`during`: `joint_6 rests at its max
/// (0.00–2.30 s)`).
struct Pick {
    sample: usize,
    extreme: String,
    during: Option<String>,
}

/// The critical samples for one extreme of joint `j` (see the module docs).
fn extreme_picks(
    motion: &Motion,
    joints: &[usize],
    j: usize,
    kind: Extreme,
    tolerance: f64,
) -> Vec<Pick> {
    let samples = motion.samples();
    let value = |sample: usize, joint: usize| samples[sample][joint];
    let names = motion.joint_names();
    let first = kind.first_index(0..motion.len(), |i| value(i, j));
    let run = dwell(motion.len(), first, tolerance, |i| value(i, j));
    let spread = |k: usize| {
        let (lo, hi) = run
            .clone()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
                (lo.min(value(i, k)), hi.max(value(i, k)))
            });
        hi - lo
    };
    let moving: Vec<usize> = joints
        .iter()
        .copied()
        .filter(|&k| k != j && spread(k) > tolerance)
        .collect();
    if moving.is_empty() {
        // A joint that rests the whole motion has one pose, not a maximum and a minimum.
        let still = *run.start() == 0 && *run.end() + 1 == motion.len();
        let extreme = match still {
            true => format!("{} (does not move)", names[j]),
            false => format!("{} {}", names[j], kind.name()),
        };
        return vec![Pick {
            sample: first,
            extreme,
            during: None,
        }];
    }
    let times = motion.times_s();
    let during = format!(
        "{} rests at its {} ({:.2}–{:.2} s)",
        names[j],
        kind.name(),
        times[*run.start()],
        times[*run.end()]
    );
    let mut picks = Vec::new();
    for k in moving {
        for other in [Extreme::Max, Extreme::Min] {
            picks.push(Pick {
                sample: other.first_index(run.clone(), |i| value(i, k)),
                extreme: format!("{} {}", names[k], other.name()),
                during: Some(during.clone()),
            });
        }
    }
    picks
}

/// Maximum or minimum.
#[derive(Clone, Copy)]
enum Extreme {
    Max,
    Min,
}

impl Extreme {
    fn name(self) -> &'static str {
        match self {
            Extreme::Max => "max",
            Extreme::Min => "min",
        }
    }

    /// The first index in `range` where `value` is extreme (exact comparison).
    fn first_index(
        self,
        range: impl Iterator<Item = usize>,
        value: impl Fn(usize) -> f64,
    ) -> usize {
        let mut best: Option<(usize, f64)> = None;
        for i in range {
            let v = value(i);
            let better = match (self, best) {
                (_, None) => true,
                (Extreme::Max, Some((_, b))) => v > b,
                (Extreme::Min, Some((_, b))) => v < b,
            };
            if better {
                best = Some((i, v));
            }
        }
        best.map_or(0, |(i, _)| i)
    }
}

/// The consecutive samples around `at` within `tolerance` of the value at `at`.
fn dwell(
    len: usize,
    at: usize,
    tolerance: f64,
    value: impl Fn(usize) -> f64,
) -> std::ops::RangeInclusive<usize> {
    let extreme = value(at);
    let near = |i: usize| (value(i) - extreme).abs() <= tolerance;
    let mut start = at;
    while start > 0 && near(start - 1) {
        start -= 1;
    }
    let mut end = at;
    while end + 1 < len && near(end + 1) {
        end += 1;
    }
    start..=end
}

/// One pose per sample, by time. Its reason lists each extreme once: the motion's own
/// extremes first, then per dwell the extremes within it that are not already among them
/// (`joint_5 min; joint_5 max while joint_6 rests at its max (0.00–2.30 s)`).
fn merge(motion: &Motion, mut picks: Vec<Pick>) -> Vec<CriticalPose> {
    picks.sort_by_key(|p| p.sample);
    let mut poses: Vec<CriticalPose> = Vec::new();
    for same in picks.chunk_by(|a, b| a.sample == b.sample) {
        let sample = same[0].sample;
        let mut plain: Vec<&str> = Vec::new();
        for pick in same.iter().filter(|p| p.during.is_none()) {
            if !plain.contains(&pick.extreme.as_str()) {
                plain.push(&pick.extreme);
            }
        }
        let mut clauses: Vec<String> = plain.iter().map(|e| e.to_string()).collect();
        let mut dwells: Vec<(&str, Vec<&str>)> = Vec::new();
        for pick in same.iter().filter(|p| !plain.contains(&p.extreme.as_str())) {
            let Some(during) = pick.during.as_deref() else {
                continue;
            };
            match dwells.iter_mut().find(|(d, _)| *d == during) {
                Some((_, extremes)) => extremes.push(&pick.extreme),
                None => dwells.push((during, vec![&pick.extreme])),
            }
        }
        for (during, extremes) in dwells {
            clauses.push(format!("{} while {during}", extremes.join(" and ")));
        }
        poses.push(CriticalPose {
            sample,
            time_s: motion.times_s()[sample],
            joints: motion.samples()[sample].clone(),
            reason: clauses.join("; "),
        });
    }
    poses
}

/// Index of the link called `name`, or an error listing the links.
fn link(robot: &Robot, name: &str) -> Result<usize, MotionError> {
    robot.link_index(name).ok_or_else(|| {
        let names: Vec<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();
        MotionError::data(format!(
            "robot `{}` has no link `{name}` (its links: {})",
            robot.name,
            names.join(", ")
        ))
    })
}

/// `link` and its ancestors up to the root, nearest first.
fn ancestors(robot: &Robot, link: usize) -> Vec<usize> {
    let mut chain = vec![link];
    let mut current = link;
    while let Some(joint) = robot.links[current].parent_joint {
        current = robot.joints[joint].parent_link;
        chain.push(current);
    }
    chain
}

/// The joints (indices into `robot.joints`) from `link` up to its ancestor `top`.
fn path_joints(robot: &Robot, link: usize, top: usize) -> impl Iterator<Item = usize> + '_ {
    let mut current = link;
    std::iter::from_fn(move || {
        if current == top {
            return None;
        }
        let joint = robot.links[current].parent_joint?;
        current = robot.joints[joint].parent_link;
        Some(joint)
    })
}
