//! # cable-dict
//!
//! Designs the external cable path of an industrial robot arm: segment lengths and guide
//! (clamp) placements such that the cable never touches the robot, never over-stretches and
//! never bends below its minimum bend radius along a given motion.
//!
//! The modules follow the pipeline of the design brief:
//!
//! - [`atomic_file`]: replacing a file so that readers never see a torn one.
//! - [`json`]: JSON output with numbers at 12 significant digits.
//! - [`input`]: reading input files with their size bounded (devices, pipes, huge files refused).
//! - [`pose`]: rigid poses and the URDF roll–pitch–yaw convention shared by every module.
//! - [`progress`]: progress of long stages, reported to a sink a front end draws.
//! - [`escape`]: names from inputs shown safely on a terminal, in HTML or SVG and in Markdown.
//! - [`text_table`]: plain-text tables whose columns are as wide as their widest cell.
//! - [`robot`]: URDF loading, forward kinematics and collision geometry of the arm.
//! - [`cable`]: the physical specification of a cable (stiffness, mass, bend radius).
//! - [`calibrate`]: a cable's bending and torsional stiffness from bench measurements.
//! - [`life`]: how long the cable lasts: rainflow counting of each point's bending and
//!   twisting, and its damage on the cable's life curve (Miner's rule).
//! - [`geometry`]: the *connected geometry* of a segment — a cubic Hermite curve carrying the
//!   discrete cable, with rotation-minimizing frames.
//! - [`statics`]: the quasi-static equilibrium of a cable clamped at its guides.
//! - [`segment`]: one cable piece between two clamp frames, shaped as asked (start shape,
//!   equilibrium, turned or relaxed in rapier3d): what `cable-dict segment` computes.
//! - [`dynamics`]: the same cable model in motion, integrated implicitly: the motion test's
//!   engine.
//! - [`rigid_chain`]: the cable as rigid bodies in rapier3d, the paper's baseline.
//! - [`stress`]: the stress metrics evaluated on a cable shape (contact, stretch, bend radius).
//! - [`setup`]: the setup file — robot, cable, guide catalogue, length candidates, limits.
//! - [`sites`]: clamp sites generated on the links' surfaces, with the cable's directions.
//! - [`motion`]: sampled robot motions, their generation from waypoints, critical poses.
//! - [`motion_test`]: the whole cable simulated along the motion; worst contact, stretch and bend radius.
//! - [`path`]: parameter vectors (PVs) and whole cable paths (ECPVs).
//! - [`attachment`]: the attachment test — which PVs hold the stress limits at the critical
//!   poses (D1) and are robust to a length error (D2).
//! - [`chain`]: the shortest chain of robust PVs through the guides' configurations, and the
//!   next-shortest ones.
//! - [`solve`]: the whole pipeline from a setup and a motion to the optimal cable path d*.
//! - [`mounting`]: the answer as a fitter mounts it — physical clamps numbered from the base,
//!   fittings, places measured from the link's features, marks on the cable.
//! - [`dictionary`]: the intra-link results precomputed per robot, cable and guide catalogue
//!   over sampled gravity directions, in a shareable memory-mapped `.cdict` file.
//! - [`provenance`]: who vouches for a dictionary — Ed25519 signatures beside it, checked
//!   against the keys a team trusts.
//! - [`report`] (feature `report`): the report folder of a solve — summary, SVG plots, a glTF
//!   scene of robot, cable and motion test, and a page that shows them.
//!
//! ```
//! use cable_dict::{cable::CableSpec, geometry::connect, pose::pose_from_mm_deg, robot::Robot};
//! use nalgebra::Vector3;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let robot = Robot::from_urdf_file("robots/viper_s850/viper_s850.urdf")?;
//! let poses = robot.link_poses(&[0.0; 6])?;
//! let flange = poses[robot.link_index("tool0").ok_or("no tool0")?];
//! assert!((flange.translation.vector - Vector3::new(0.35, 0.0, 0.82)).norm() < 1e-12);
//!
//! let cable = CableSpec::from_file("cables/smc_le_cp_3.toml")?;
//! let start = pose_from_mm_deg([0.0, 0.0, 0.0], [0.0, 90.0, 0.0]);
//! let end = pose_from_mm_deg([250.0, 0.0, -150.0], [0.0, 150.0, 0.0]);
//! let segment = connect(&start, &end, 40, cable.sub_segment_pitch_m, &-Vector3::z_axis())?;
//! assert_eq!(segment.nodes.len(), 41);
//! # Ok(())
//! # }
//! ```
//!
//! All quantities are SI (metres, radians, kilograms, seconds) unless a name carries its unit
//! (`length_mm`, `angle_deg`); conversion happens only at file and command-line boundaries.

pub mod atomic_file;
pub mod attachment;
pub mod cable;
pub mod calibrate;
pub mod chain;
pub mod dictionary;
pub mod dynamics;
pub mod escape;
#[cfg(test)]
mod fixtures;
pub mod geometry;
pub mod input;
pub mod json;
pub mod life;
pub mod motion;
pub mod motion_test;
pub mod mounting;
pub mod path;
pub mod pose;
pub mod progress;
pub mod provenance;
#[cfg(feature = "report")]
pub mod report;
pub mod rigid_chain;
pub mod robot;
pub mod segment;
pub mod setup;
pub mod sites;
pub mod solve;
pub mod statics;
pub mod stress;
pub mod text_table;
