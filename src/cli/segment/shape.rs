//! The two shapes of a segment: connected (the start shape) and converged (the equilibrium).

use super::super::Failure;
use super::{Args, Connect, Solver};
use cable_dict::cable::CableSpec;
use cable_dict::geometry::{ConnectError, CurveFamily, connect, sag_direction};
use cable_dict::rigid_chain::{
    ConvergenceWindow, DynamicsSettings, LinearConnect, RigidChainError, SegmentShape,
    connect_linear, relax,
};
use cable_dict::statics::turns::solve_turned;
use cable_dict::statics::{RodParameters, SolverOptions, StaticSolver, StaticsError};
use cable_dict::stress::FirstSelfContact;
use nalgebra::{Point3, Rotation3};
use std::time::Instant;

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
    pub nodes: Vec<Point3<f64>>,
    pub frames: Vec<Rotation3<f64>>,
    pub time_us: f64,
}

/// The converged geometry and how the solver got there.
pub struct Converged {
    /// Newton iterations, or simulation steps for rapier.
    pub iterations: usize,
    /// Largest force left on a node (N), or node motion in the last window (m) for rapier.
    pub residual: f64,
    pub residual_unit: &'static str,
    /// Total twist between the guides (rad); `None` for rapier.
    pub twist_rad: Option<f64>,
    /// The extra turn of the end guide (deg) at which the cable first passed through itself
    /// while `--twist-turns` turned it; `None` when it never did (or no turns were asked).
    pub self_contact_from_deg: Option<f64>,
    pub nodes: Vec<Point3<f64>>,
    pub frames: Vec<Rotation3<f64>>,
    pub time_us: f64,
}

/// The connected geometry of `args` with `sub_segments` sub-segments.
pub fn connected(
    cable: &CableSpec,
    args: &Args,
    sub_segments: usize,
) -> Result<Connected, Failure> {
    let timer = Instant::now();
    let pitch = cable.sub_segment_pitch_m;
    match args.connect {
        Connect::Hermite => {
            let sag = sag_direction(&args.gravity);
            let geometry = connect(&args.start, &args.end, sub_segments, pitch, &sag).map_err(
                |e| match e {
                    ConnectError::InvalidInput { .. } => Failure::input(e),
                    ConnectError::TooShort { .. } | ConnectError::NoSolution { .. } => {
                        Failure::unsolved(e)
                    }
                },
            )?;
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
        Connect::Linear => {
            let settings = DynamicsSettings::relaxation(args.gravity);
            let plan = LinearConnect::default();
            let linear = connect_linear(
                cable,
                &args.start,
                &args.end,
                sub_segments,
                &settings,
                &plan,
            )
            .map_err(dynamics_failure)?;
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

/// The static equilibrium from the connected shape.
pub fn converged(cable: &CableSpec, args: &Args, start: &Connected) -> Result<Converged, Failure> {
    let timer = Instant::now();
    match args.solver {
        Solver::QuasiStatic => {
            let params = RodParameters::new(cable, args.gravity);
            let mut watch = FirstSelfContact::new(cable.diameter_m, cable.sub_segment_pitch_m);
            let equilibrium = solve_turned(
                &mut StaticSolver::default(),
                &params,
                &args.start,
                &args.end,
                &start.nodes,
                start.twist_correction_rad,
                f64::from(args.twist_turns) * std::f64::consts::TAU,
                &SolverOptions::default(),
                |angle, equilibrium, crossed| watch.step(angle, &equilibrium.nodes, crossed),
            )
            .map_err(|e| match e {
                StaticsError::InvalidInput { .. } => Failure::input(e),
                StaticsError::NotConverged { .. } => Failure::unsolved(e),
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
        Solver::Rapier => {
            let shape = SegmentShape {
                start_guide: args.start,
                end_guide: args.end,
                nodes: &start.nodes,
                frames: &start.frames,
            };
            let settings = DynamicsSettings::relaxation(args.gravity);
            let relaxed = relax(cable, &shape, &settings, &ConvergenceWindow::default())
                .map_err(dynamics_failure)?;
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

fn dynamics_failure(error: RigidChainError) -> Failure {
    match error {
        RigidChainError::InvalidInput { .. } => Failure::input(error),
        _ => Failure::unsolved(error),
    }
}

fn micros(timer: Instant) -> f64 {
    timer.elapsed().as_secs_f64() * 1e6
}
