//! # cable-dict
//!
//! Designs the external cable path of an industrial robot arm: segment lengths and guide
//! (clamp) placements such that the cable never touches the robot, never over-stretches and
//! never bends below its minimum bend radius along a given motion.
//!
//! The modules follow the pipeline of the design brief:
//!
//! - [`pose`]: rigid poses and the URDF roll–pitch–yaw convention shared by every module.
//! - [`robot`]: URDF loading, forward kinematics and collision geometry of the arm.
//! - [`cable`]: the physical specification of a cable (stiffness, mass, bend radius).
//! - [`geometry`]: the *connected geometry* of a segment — a cubic Hermite curve carrying the
//!   discrete cable, with rotation-minimizing frames.
//! - [`stress`]: the stress metrics evaluated on a cable shape (stretch, bend radius).
//!
//! All quantities are SI (metres, radians, kilograms, seconds) unless a name carries its unit
//! (`length_mm`, `angle_deg`); conversion happens only at file and command-line boundaries.

pub mod cable;
pub mod geometry;
pub mod pose;
pub mod robot;
pub mod stress;
