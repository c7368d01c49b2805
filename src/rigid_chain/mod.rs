//! The discrete cable as a chain of rigid bodies in rapier3d — the reference paper's kind of
//! simulation, kept as its baseline: the whole cable simulated in time while the guides (and
//! the robot's links) move kinematically (the motion test's `rigid-chain` engine; the
//! default engine is [`crate::dynamics`]), and the static relaxation and the previous
//! connected-geometry method of the paper's pipelines.
//!
//! The model is the crate's discrete cable (module [`cable`](crate::cable)): rigid
//! sub-segments of pitch `l` joined at the nodes by bending springs `kb` and torsion springs
//! `kt`, clamped in position and orientation at every guide. See [`CableWorld`] for how it
//! maps onto rapier bodies and joints, and [`DynamicsSettings`] for the stepping that makes
//! it accurate (solver substep ≤ 1/3840 s).
//!
//! - [`CableWorld`]: build, move guides and robot, step, read nodes and per-step
//!   [`StepRecord`]s (contact force, stretch, bend radius per segment).
//! - [`relax`] / [`settle`]: static relaxation under gravity with a geometric convergence
//!   window ([`ConvergenceWindow`]).
//! - [`connect_linear`]: the paper's previous connected-geometry method (straight cable
//!   dragged into the end guide), the baseline for [`connect`](crate::geometry::connect).
//!
//! Rapier notes (0.36.1, default `f32` build):
//!
//! - Its public math types are glam (`rapier3d::math::{Vector, Rotation, Pose}` = `Vec3`,
//!   `Quat`, `Pose3`); the conversion happens inside this module, every public item is
//!   nalgebra `f64` in SI units.
//! - A joint's `local_frame1/2` are poses in each body's frame; with identity rotations the
//!   rest state is "both bodies' frames aligned". Angular motors act about the axes of the
//!   *first* body's joint frame and measure the angle as `2·asin(q_axis)` of the relative
//!   rotation `frame1⁻¹·frame2`. `MotorModel::ForceBased` makes the stiffness a true N·m/rad.
//! - `num_solver_iterations` is the number of *substeps* (the TGS solver divides `dt` by
//!   it); `num_internal_pgs_iterations` the sweeps per substep.
//! - Bodies whose state turns non-finite are quarantined (disabled) by rapier instead of
//!   poisoning the world; [`CableWorld::step`] reports them as a blow-up.
//!
//! Without the `rigid-chain` feature only the settings and the error remain (what the motion
//! test's options name); the engine itself needs rapier3d.

#[cfg(feature = "rigid-chain")]
mod build;
#[cfg(feature = "rigid-chain")]
mod convert;
mod error;
#[cfg(feature = "rigid-chain")]
mod record;
#[cfg(feature = "rigid-chain")]
mod relax;
#[cfg(feature = "rigid-chain")]
mod robot;
mod settings;
#[cfg(feature = "rigid-chain")]
mod world;

#[cfg(feature = "rigid-chain")]
pub use build::SegmentShape;
pub use error::{BlowUpQuantity, RigidChainError};
#[cfg(feature = "rigid-chain")]
pub use record::{ContactSummary, SegmentRecord, StepRecord, SubSegmentContact};
#[cfg(feature = "rigid-chain")]
pub use relax::{LinearConnect, Relaxation, Settled, connect_linear, interpolate, relax, settle};
pub use settings::{BlowUpBounds, ConvergenceWindow, DynamicsSettings};
#[cfg(feature = "rigid-chain")]
pub use world::CableWorld;
