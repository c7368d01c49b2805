//! The static poses of an axis-range box at which each cable piece is tested: a grid over
//! the joints that change the piece's shape, not over the whole box.
//!
//! A piece between clamps on links A and B takes its shape from two things only: the
//! joints on the path between A and B (the *traversed* joints, which place B against A)
//! and gravity's direction in A's frame (set by the joints from the base up to A, the
//! *upstream* joints). So the grid of a piece is
//!
//! - every gravity direction A takes over the upstream joints' grid (the other joints at
//!   the box's middle), one pose per direction, directions closer than a resolution kept
//!   once; an upstream joint that never turns gravity in A's frame (a vertical first axis)
//!   is held at its middle;
//! - times the traversed joints' grid.
//!
//! The joints beyond B, and the upstream joints' own places, move other links past the
//! piece without changing its shape: they are left at the box's middle here, and met by
//! the stress motions' sweep and motion tests (each axis end to end) and by an independent
//! check over the whole box ([`JointRanges::grid_values`] at a finer step).
//!
//! The grid of every piece of a setup is one [`CellMotion`] of the design's cell: its poses
//! as the samples of a [`Motion`] (one per second: a list of poses, not a motion in time —
//! it is solved statically, never simulated) and, in its [`RangeGrid`], which of them are
//! each piece's own.

use super::{CellMotion, JointRanges, Motion, MotionError, traversed_joints};
use crate::robot::Robot;
use nalgebra::Vector3;
use std::collections::HashMap;

/// The most poses one piece's grid may have: beyond it the step is too fine for the box
/// (each pose is one static solve of every piece the search decides).
pub const MAX_GRID_POSES_PER_PIECE: usize = 20_000;

/// The most upstream-joint combinations enumerated to find one piece's gravity directions.
pub const MAX_UPSTREAM_COMBINATIONS: usize = 200_000;

/// Which poses of a grid's [`CellMotion`] each piece is tested at.
#[derive(Debug, Clone, PartialEq)]
pub struct RangeGrid {
    /// Two gravity directions closer than this (degrees) count as one.
    pub gravity_resolution_deg: f64,
    /// Per piece (segment), the samples of the grid's motion it is tested at, in grid
    /// order.
    pub per_segment: Vec<Vec<usize>>,
    /// Per piece, the joints (joint-vector indices) whose grid it takes: upstream joints
    /// that turn gravity in its start link, then the traversed ones.
    pub gridded: Vec<Vec<usize>>,
}

impl JointRanges {
    /// The values (rad or m) of `robot`'s joint `j` on a grid at most `step_deg` apart
    /// (degrees, or millimetres for a prismatic joint) over its range, both ends included,
    /// evenly spaced; one value for a range of no width.
    pub fn grid_values(&self, robot: &Robot, j: usize, step_deg: f64) -> Vec<f64> {
        let (per_si, _) = robot.actuated_joint(j).kind.display_unit();
        let [min, max] = self.ranges[j];
        if max <= min {
            return vec![min];
        }
        let n = ((max - min) * per_si / step_deg).ceil().clamp(1.0, 1e6) as usize;
        (0..=n)
            .map(|i| min + (max - min) * i as f64 / n as f64)
            .collect()
    }

    /// The box's grid for pieces between the links of `pieces` (`(start link, end link)`,
    /// indices into `robot.links`; equal for a piece within one link) under gravity
    /// `gravity_m_s2` (world frame): every pose of every piece's grid once, as the samples of
    /// the cell motion `axis-range grid`, with its [`RangeGrid`]. Refused when a piece's grid has more than
    /// [`MAX_GRID_POSES_PER_PIECE`] poses or its upstream joints more than
    /// [`MAX_UPSTREAM_COMBINATIONS`] combinations at this step.
    pub fn grid(
        &self,
        robot: &Robot,
        gravity_m_s2: &Vector3<f64>,
        pieces: &[(usize, usize)],
        step_deg: f64,
        gravity_resolution_deg: f64,
    ) -> Result<CellMotion, MotionError> {
        if !(step_deg.is_finite() && step_deg > 0.0) {
            return Err(MotionError::data(format!(
                "the grid step {step_deg} must be > 0"
            )));
        }
        let down = gravity_m_s2
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::zeros);
        let resolution = gravity_resolution_deg.to_radians().cos();
        let centre = self.centre();
        let root = &robot.links[0].name;
        let mut samples: Vec<Vec<f64>> = Vec::new();
        let mut index: HashMap<Vec<u64>, usize> = HashMap::new();
        let mut per_segment = Vec::with_capacity(pieces.len());
        let mut gridded = Vec::with_capacity(pieces.len());
        for &(a, b) in pieces {
            let (name_a, name_b) = (&robot.links[a].name, &robot.links[b].name);
            let traversed = traversed_joints(robot, name_a, name_b)?;
            let upstream: Vec<usize> = traversed_joints(robot, root, name_a)?
                .into_iter()
                .filter(|j| !traversed.contains(j))
                .collect();
            let gravity_in_a = |joints: &[f64]| gravity_in(robot, joints, a, &down);
            let mut turning = Vec::new();
            for &j in &upstream {
                if self.turns_gravity(robot, a, &down, j, step_deg)? {
                    turning.push(j);
                }
            }
            let axes = |joints: &[usize]| -> Vec<(usize, Vec<f64>)> {
                (joints.iter())
                    .map(|&j| (j, self.grid_values(robot, j, step_deg)))
                    .collect()
            };
            let up_axes = axes(&turning);
            let upstream_count = combination_count(&up_axes);
            if upstream_count > MAX_UPSTREAM_COMBINATIONS as f64 {
                return Err(too_fine(
                    format!(
                        "the piece from {name_a} to {name_b}: {upstream_count:.0} combinations of \
                         the joints that turn gravity in {name_a}"
                    ),
                    step_deg,
                ));
            }
            let mut directions: Vec<Vector3<f64>> = Vec::new();
            let mut representatives: Vec<Vec<f64>> = Vec::new();
            for joints in combinations(&centre, &up_axes) {
                let g = gravity_in_a(&joints)?;
                if !directions.iter().any(|d| d.dot(&g) >= resolution) {
                    directions.push(g);
                    representatives.push(joints);
                }
            }
            let along = axes(&traversed);
            let poses = representatives.len() as f64 * combination_count(&along);
            if poses > MAX_GRID_POSES_PER_PIECE as f64 {
                return Err(too_fine(
                    format!(
                        "the piece from {name_a} to {name_b}: {} gravity directions × {:.0} \
                         places of the joints between its links = {poses:.0} poses",
                        representatives.len(),
                        combination_count(&along)
                    ),
                    step_deg,
                ));
            }
            let mut own = Vec::new();
            for representative in &representatives {
                for joints in combinations(representative, &along) {
                    let key: Vec<u64> = joints.iter().map(|v| v.to_bits()).collect();
                    let k = *index.entry(key).or_insert_with(|| {
                        samples.push(joints);
                        samples.len() - 1
                    });
                    own.push(k);
                }
            }
            per_segment.push(own);
            gridded.push(turning.into_iter().chain(traversed).collect());
        }
        let times_s = (0..samples.len()).map(|k| k as f64).collect();
        Ok(CellMotion {
            name: "axis-range grid".into(),
            file: None,
            cycles_per_hour: None,
            motion: Motion::new(robot, times_s, samples)?,
            grid: Some(RangeGrid {
                gravity_resolution_deg,
                per_segment,
                gridded,
            }),
        })
    }

    /// The box's corner with every joint at its minimum (`end` 0) or maximum (1).
    /// Whether joint `j`, moved over its grid at `step_deg`, turns gravity (`down`, a unit
    /// vector in the world) in link `link`'s frame: tried with the other joints at the box's
    /// middle and at its two corners. A vertical first axis turns it in no link.
    pub fn turns_gravity(
        &self,
        robot: &Robot,
        link: usize,
        down: &Vector3<f64>,
        j: usize,
        step_deg: f64,
    ) -> Result<bool, MotionError> {
        for corner in [self.centre(), self.corner(0), self.corner(1)] {
            let at = |v: f64| {
                let mut joints = corner.clone();
                joints[j] = v;
                gravity_in(robot, &joints, link, down)
            };
            let base = at(corner[j])?;
            for v in self.grid_values(robot, j, step_deg) {
                if (at(v)? - base).norm() > 1e-9 {
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    fn corner(&self, end: usize) -> Vec<f64> {
        self.ranges.iter().map(|r| r[end]).collect()
    }
}

/// Gravity's direction `down` (world) in the frame of `robot`'s link `link` at `joints`.
fn gravity_in(
    robot: &Robot,
    joints: &[f64],
    link: usize,
    down: &Vector3<f64>,
) -> Result<Vector3<f64>, MotionError> {
    let poses = robot
        .link_poses(joints)
        .map_err(|e| MotionError::data(e.to_string()))?;
    Ok(poses[link].rotation.inverse_transform_vector(down))
}

/// How many joint vectors [`combinations`] gives (as a float: it may be astronomically
/// many).
pub fn combination_count(axes: &[(usize, Vec<f64>)]) -> f64 {
    axes.iter().map(|(_, values)| values.len() as f64).product()
}

/// Every joint vector of `base` with the joints of `axes` (joint index, its values) set to
/// each combination of their values, counted like an odometer (the last axis fastest);
/// `base` alone when there are no axes.
pub fn combinations<'a>(
    base: &'a [f64],
    axes: &'a [(usize, Vec<f64>)],
) -> impl Iterator<Item = Vec<f64>> + 'a {
    let mut digits: Option<Vec<usize>> = Some(vec![0; axes.len()]);
    std::iter::from_fn(move || {
        let current = digits.as_mut()?;
        let mut joints = base.to_vec();
        for (k, (j, values)) in axes.iter().enumerate() {
            joints[*j] = values[current[k]];
        }
        match (0..axes.len())
            .rev()
            .find(|&k| current[k] + 1 < axes[k].1.len())
        {
            Some(k) => {
                current[k] += 1;
                current[k + 1..].iter_mut().for_each(|d| *d = 0);
            }
            None => digits = None,
        }
        Some(joints)
    })
}

fn too_fine(what: String, step_deg: f64) -> MotionError {
    MotionError::data(format!(
        "the axis-range grid at {step_deg}° is too fine for this box ({what}); give a coarser \
         step or narrower ranges"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::narrow_pick_and_place;

    /// On the Viper (a vertical first axis): the grid of a piece between link_3 and link_5
    /// takes joints 4 and 5 at every grid value (ends included, ⌈width / step⌉ + 1 each)
    /// under every gravity direction joints 2–3 give link_3, never joint 1 (it turns
    /// nothing about gravity); a piece within link_3 takes only those directions. Every pose
    /// lies in the box.
    #[test]
    fn a_piece_is_gridded_over_the_joints_that_shape_it_and_nothing_else() {
        let (setup, _) = narrow_pick_and_place();
        let robot = &setup.robot;
        let index = |name: &str| robot.actuated_index(name).expect(name);
        let link = |name: &str| robot.link_index(name).expect(name);
        let mut ranges = JointRanges::urdf(robot).expect("limits");
        let deg = |a: f64, b: f64| [a.to_radians(), b.to_radians()];
        let box_deg = [
            ("joint_1", -90.0, 45.0),
            ("joint_2", -80.0, -50.0),
            ("joint_3", 200.0, 230.0),
            ("joint_4", -35.0, 35.0),
            ("joint_5", 10.0, 53.0),
            ("joint_6", -20.0, 20.0),
        ];
        for (name, a, b) in box_deg {
            ranges.ranges[index(name)] = deg(a, b);
            ranges.named[index(name)] = true;
        }
        let pieces = [
            (link("link_3"), link("link_5")),
            (link("link_3"), link("link_3")),
        ];
        let step = 10.0;
        let grid = ranges
            .grid(robot, &setup.gravity_m_s2, &pieces, step, 3.0)
            .unwrap_or_else(|e| panic!("{e}"));
        let spec = grid.grid.as_ref().expect("a grid");
        let count = |a: f64, b: f64| ((b - a) / step).ceil() as usize + 1;
        let (j2, j3, j4, j5) = (
            index("joint_2"),
            index("joint_3"),
            index("joint_4"),
            index("joint_5"),
        );
        assert_eq!(spec.gridded[0], vec![j2, j3, j4, j5]);
        assert_eq!(spec.gridded[1], vec![j2, j3]);
        let along = count(-35.0, 35.0) * count(10.0, 53.0);
        let directions = spec.per_segment[1].len();
        assert!(directions > 1 && directions <= count(-80.0, -50.0) * count(200.0, 230.0));
        assert_eq!(spec.per_segment[0].len(), directions * along);
        let samples = grid.motion.samples();
        for &k in spec.per_segment.iter().flatten() {
            assert!(ranges.contains(&samples[k]));
            assert_eq!(
                samples[k][index("joint_1")],
                ranges.centre()[index("joint_1")]
            );
        }
        let values = ranges.grid_values(robot, j5, step);
        assert_eq!(values.len(), count(10.0, 53.0));
        assert_eq!(values[0], ranges.ranges[j5][0]);
        assert_eq!(*values.last().expect("a value"), ranges.ranges[j5][1]);
    }
}
