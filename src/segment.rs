//! One cable piece between two clamp frames, shaped as a program asks for it: its connected
//! geometry (the start shape: the Hermite curve, or the paper's straight cable dragged into
//! place) and its equilibrium (Newton on the cable's energy, optionally turned by whole turns
//! at the end clamp, or the rigid chain relaxed in rapier3d). What `cable-dict segment`
//! computes; the search itself uses [`crate::attachment`].

use crate::cable::CableSpec;
use crate::geometry::{ConnectError, CurveFamily, connect, sag_direction};
use crate::pose::Pose;
use crate::statics::turns::solve_turned;
use crate::statics::{RodParameters, SolverOptions, StaticSolver, StaticsError};
use crate::stress::FirstSelfContact;
use nalgebra::{Point3, Rotation3, Vector3};
use std::time::Instant;

/// How the start shape is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConnectKind {
    /// Hermite curve and rotation-minimizing frames ([`connect`]).
    Hermite,
    /// A straight cable dragged into the end clamp by the physics engine (feature
    /// `rigid-chain`).
    Linear,
}

/// How the equilibrium is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolverKind {
    /// Newton's method on the cable's energy.
    QuasiStatic,
    /// Damped rigid-body relaxation in rapier3d (feature `rigid-chain`).
    Rapier,
}

/// One piece to shape: its clamp frames (world, +z along the cable), gravity and methods.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PieceRequest {
    /// The start clamp's frame.
    pub start: Pose,
    /// The end clamp's frame.
    pub end: Pose,
    /// Gravity (m/s², world frame).
    pub gravity_m_s2: Vector3<f64>,
    /// How the start shape is made.
    pub connect: ConnectKind,
    /// How the equilibrium is found.
    pub solver: SolverKind,
    /// Whole turns added at the end clamp (quasi-static solver).
    pub twist_turns: i32,
}

/// Why a piece has no shape: the request cannot be computed, or it has no answer (a cable
/// too short for its clamps, a solve that does not converge).
#[derive(Debug, thiserror::Error)]
pub enum PieceError {
    /// The request is invalid (a non-finite frame, too many sub-segments, a method this build
    /// lacks).
    #[error("{0}")]
    Input(String),
    /// Valid, but there is no shape.
    #[error("{0}")]
    NoShape(String),
}

/// The connected geometry, by either method.
pub struct Connected {
    /// `hermite`, `bowed` or `linear`.
    pub curve: &'static str,
    /// Hermite tangent scale (m); `None` for the linear method.
    pub alpha_m: Option<f64>,
    /// Bow height (m); `None` for the linear method.
    pub bow_m: Option<f64>,
    /// Twist spread over the frames (rad); `None` for the linear method.
    pub twist_correction_rad: Option<f64>,
    /// Nodes (m, world frame).
    pub nodes: Vec<Point3<f64>>,
    /// Each sub-segment's frame.
    pub frames: Vec<Rotation3<f64>>,
    /// Time taken (µs).
    pub time_us: f64,
}

/// The converged geometry and how the solver got there.
pub struct Converged {
    /// Newton iterations, or simulation steps for rapier.
    pub iterations: usize,
    /// Largest force left on a node (N), or node motion in the last window (m) for rapier.
    pub residual: f64,
    /// `N` or `m`.
    pub residual_unit: &'static str,
    /// Total twist between the guides (rad); `None` for rapier.
    pub twist_rad: Option<f64>,
    /// The extra turn of the end guide (deg) at which the cable first passed through itself
    /// while `--twist-turns` turned it; `None` when it never did (or no turns were asked).
    pub self_contact_from_deg: Option<f64>,
    /// Nodes (m, world frame).
    pub nodes: Vec<Point3<f64>>,
    /// Each sub-segment's frame.
    pub frames: Vec<Rotation3<f64>>,
    /// Time taken (µs).
    pub time_us: f64,
}

/// The connected geometry of `request` with `sub_segments` sub-segments.
pub fn connected(
    cable: &CableSpec,
    request: &PieceRequest,
    sub_segments: usize,
) -> Result<Connected, PieceError> {
    let timer = Instant::now();
    let pitch = cable.sub_segment_pitch_m;
    match request.connect {
        ConnectKind::Hermite => {
            let sag = sag_direction(&request.gravity_m_s2);
            let geometry = connect(&request.start, &request.end, sub_segments, pitch, &sag)
                .map_err(|e| match e {
                    ConnectError::InvalidInput { .. } => PieceError::Input(e.to_string()),
                    ConnectError::TooShort { .. } | ConnectError::NoSolution { .. } => {
                        PieceError::NoShape(e.to_string())
                    }
                })?;
            Ok(Connected {
                curve: match geometry.curve {
                    CurveFamily::Hermite => "hermite",
                    CurveFamily::Bowed => "bowed",
                },
                alpha_m: Some(geometry.alpha_m),
                bow_m: Some(geometry.bow_m),
                twist_correction_rad: Some(geometry.twist_correction_rad),
                time_us: micros(timer),
                nodes: geometry.nodes,
                frames: geometry.frames,
            })
        }
        #[cfg(not(feature = "rigid-chain"))]
        ConnectKind::Linear => Err(without_rigid_chain()),
        #[cfg(feature = "rigid-chain")]
        ConnectKind::Linear => {
            use crate::rigid_chain::{DynamicsSettings, LinearConnect, connect_linear};
            let settings = DynamicsSettings::relaxation(request.gravity_m_s2);
            let plan = LinearConnect::default();
            let linear = connect_linear(
                cable,
                &request.start,
                &request.end,
                sub_segments,
                &settings,
                &plan,
            )
            .map_err(rigid_chain_failure)?;
            Ok(Connected {
                curve: "linear",
                alpha_m: None,
                bow_m: None,
                twist_correction_rad: None,
                time_us: micros(timer),
                nodes: linear.nodes,
                frames: linear.frames,
            })
        }
    }
}

/// The equilibrium of `request` from its connected shape `start`.
pub fn converged(
    cable: &CableSpec,
    request: &PieceRequest,
    start: &Connected,
) -> Result<Converged, PieceError> {
    let timer = Instant::now();
    match request.solver {
        SolverKind::QuasiStatic => {
            let params = RodParameters::new(cable, request.gravity_m_s2);
            let mut watch = FirstSelfContact::new(cable.diameter_m, cable.sub_segment_pitch_m);
            let equilibrium = solve_turned(
                &mut StaticSolver::default(),
                &params,
                &request.start,
                &request.end,
                &start.nodes,
                start.twist_correction_rad,
                f64::from(request.twist_turns) * std::f64::consts::TAU,
                &SolverOptions::default(),
                |angle, equilibrium, crossed| watch.step(angle, &equilibrium.nodes, crossed),
            )
            .map_err(|e| match e {
                StaticsError::InvalidInput { .. } => PieceError::Input(e.to_string()),
                StaticsError::NotConverged { .. } => PieceError::NoShape(e.to_string()),
            })?;
            Ok(Converged {
                iterations: equilibrium.iterations,
                residual: equilibrium.residual_n,
                residual_unit: "N",
                twist_rad: Some(equilibrium.twist_rad),
                self_contact_from_deg: watch.at.map(f64::to_degrees),
                time_us: micros(timer),
                nodes: equilibrium.nodes,
                frames: equilibrium.frames,
            })
        }
        #[cfg(not(feature = "rigid-chain"))]
        SolverKind::Rapier => Err(without_rigid_chain()),
        #[cfg(feature = "rigid-chain")]
        SolverKind::Rapier => {
            use crate::rigid_chain::{ConvergenceWindow, DynamicsSettings, SegmentShape, relax};
            let shape = SegmentShape {
                start_guide: request.start,
                end_guide: request.end,
                nodes: &start.nodes,
                frames: &start.frames,
            };
            let settings = DynamicsSettings::relaxation(request.gravity_m_s2);
            let relaxed = relax(cable, &shape, &settings, &ConvergenceWindow::default())
                .map_err(rigid_chain_failure)?;
            Ok(Converged {
                iterations: relaxed.steps,
                residual: relaxed.final_window_motion_m,
                residual_unit: "m",
                twist_rad: None,
                self_contact_from_deg: None,
                time_us: micros(timer),
                nodes: relaxed.nodes,
                frames: relaxed.frames,
            })
        }
    }
}

#[cfg(feature = "rigid-chain")]
fn rigid_chain_failure(error: crate::rigid_chain::RigidChainError) -> PieceError {
    match error {
        crate::rigid_chain::RigidChainError::InvalidInput { .. } => {
            PieceError::Input(error.to_string())
        }
        _ => PieceError::NoShape(error.to_string()),
    }
}

#[cfg(not(feature = "rigid-chain"))]
fn without_rigid_chain() -> PieceError {
    PieceError::Input("the linear and rapier methods need the rigid-chain feature".into())
}

fn micros(timer: Instant) -> f64 {
    timer.elapsed().as_secs_f64() * 1e6
}
