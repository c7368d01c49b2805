//! Robot motions: the motion CSV, waypoint files and the trajectory generator, and the
//! critical poses of a cable segment.
//!
//! # Motion CSV
//!
//! ```text
//! # comment lines start with '#', anywhere; blank lines are ignored
//! time_s,joint_1_deg,joint_2_deg,joint_3_deg,joint_4_deg,joint_5_deg,joint_6_rad
//! 0,0,-90,180,0,0,0
//! 0.01,0.0123,-90,180,0,0,0
//! ```
//!
//! - The first line that is not a comment is the header: `time_s`, then one column per
//!   actuated joint of the robot named `<URDF joint name>_deg` or `_rad` (`_mm` or `_m` for
//!   prismatic joints), in any order, each joint exactly once. Units may differ from column
//!   to column.
//! - Every following line is one sample: as many comma-separated numbers as header columns,
//!   finite, times (s) strictly increasing, values within the URDF joint limits (1e-9 rad/m
//!   slack), mimic joints' derived values included. At least one sample.
//! - Errors ([`MotionError`]) name the file, the line, the column and joint, and the problem:
//!   unknown, fixed or duplicated joints, missing joints, wrong units, wrong number of values,
//!   non-numbers, NaN or infinities, times that do not increase, values beyond limits.
//! - [`Motion::to_csv`] / [`Motion::write_csv`] write rotary joints in degrees and prismatic
//!   ones in millimetres, in joint-vector order, each number in the shortest decimal form
//!   that reads back to the same double, after `# ` comment lines. [`Motion`] keeps its
//!   values on doubles that convert exactly to and from degrees (millimetres), so a written
//!   motion reads back bit for bit. Files are written atomically (temporary file in the same
//!   folder, fsync, rename).
//!
//! # Waypoint file (TOML)
//!
//! ```toml
//! description = "Pick in front, place on the right"   # optional, copied into the CSV
//! robot = "../../robots/viper_s850/viper_s850.urdf"   # relative to this file
//! sample_rate_hz = 100.0
//! speed_scale = 0.5              # fraction (0, 1] of every joint's URDF speed limit
//! profile = "trapezoidal"        # or "quintic"
//! time_to_full_speed_s = 0.25    # a_j = v_j / t ... or, instead, one value per joint:
//! # acceleration_deg_s2 = [600, 600, 700, 900, 900, 1200]   (mm/s² for prismatic joints)
//!
//! [[waypoint]]
//! name = "home"                  # optional, default "waypoint <n>"
//! joints_deg = [0, -90, 180, 0, 0, 0]   # joint-vector order; mm for prismatic joints
//! dwell_s = 0.5                  # optional, default 0: rest here before moving on
//! ```
//!
//! Unknown keys are refused; every number must be finite (rates, scales, times and
//! accelerations positive, dwells ≥ 0); a waypoint beyond the joint limits is refused with its
//! index, name and line. The robot starts at the first waypoint at `t = 0`, rests `dwell_s`,
//! then moves to the next with a synchronized point-to-point move ([`SyncMove`]: all joints
//! start and stop together on the straight joint-space line; profiles and duration formulas
//! in [`profile`]). Samples: the grid `k / sample_rate_hz` plus every arrival and departure
//! instant (the last sample is exactly the end). See [`WaypointFile::generate`].
//!
//! # Critical poses
//!
//! A segment between guides on links A and B *traverses* the actuated joints on the
//! kinematic path between A and B ([`traversed_joints`]; Viper s850: `link_3`–`link_4` →
//! `joint_4`, `link_4`–`link_6` → `joint_5`, `joint_6`). [`critical_poses`] then picks, for
//! each traversed joint `j` and each of its global maximum and minimum over the samples:
//!
//! 1. the first sample `i` where `j` takes that exact extreme value (ties: the first
//!    instant);
//! 2. its *dwell*: the consecutive samples around `i` within [`DWELL_TOLERANCE`] (1e-6 rad or
//!    m) of the extreme;
//! 3. the other traversed joints that *move* during the dwell (their values in it spread by
//!    more than the tolerance): if there are none, sample `i` is critical (reason
//!    `joint_j max`); otherwise, for each of them, `k`, the first samples of the dwell where
//!    `k` is largest and smallest are critical (reason `joint_k min while joint_j rests at
//!    its max (t0–t1 s)`), and `i` itself is not. A joint that never moves gives one pose
//!    (`joint_j (does not move)`).
//!
//! Poses on the same sample are merged (reasons joined by `; `) and sorted by time. So one
//! traversed joint gives 2 poses; two give 4 when the extremes are isolated or the robot
//! rests as a whole at them, and up to 8 when one joint rests at an extreme while the other
//! moves; fewer when extremes coincide (a joint that never moves rests at both extremes the
//! whole motion, so the other joint's extremes stand for it). No traversed joint gives no
//! pose. Only sampled instants are candidates: an extreme between two samples is not
//! interpolated (the generator samples every waypoint exactly, where point-to-point moves
//! have their extremes).

mod cell;
mod critical;
mod csv;
mod error;
mod generate;
mod grid;
pub mod profile;
mod ranges;
mod sampled;
mod units;
mod waypoints;

pub use cell::{Cell, CellMotion, MAX_CELL_MOTIONS};
pub use critical::{
    CriticalPose, DWELL_TOLERANCE, critical_poses, critical_poses_with_tolerance, traversed_joints,
};
pub use error::MotionError;
pub use generate::{Generated, WaypointTiming};
pub use grid::{
    MAX_GRID_POSES_PER_PIECE, MAX_UPSTREAM_COMBINATIONS, RangeGrid, combination_count, combinations,
};
pub use profile::{Profile, SyncMove};
pub use ranges::{DEFAULT_TIME_TO_FULL_SPEED_S, JointRanges, MAX_STROKE_S, STROKE_END_DWELL_S};
pub use sampled::{MAX_MOTION_DURATION_S, Motion};
pub use waypoints::{Acceleration, Waypoint, WaypointFile};
