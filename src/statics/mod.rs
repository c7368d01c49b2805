//! Static equilibrium of the discrete cable under gravity: the *convergent geometry*.
//!
//! A segment of `S` sub-segments is clamped at its start guide in position and orientation,
//! and at its end guide the same way (or left free, for cantilever checks). The equilibrium
//! is the minimum of the potential energy of [`rod`](self) — stretch, bending, twist and
//! gravity over the free node positions — found by Newton's method with a line search
//! (module `newton`), started from the connected geometry or a previous solution.
//!
//! The model is the discrete elastic rod of Bergou et al. (2008) for an isotropic cable:
//! node positions are the unknowns, the material frame follows by parallel transport, and the
//! twist, uniform at equilibrium, enters through one total angle. Every term couples nodes at
//! most two apart, so the Hessian is banded (half-bandwidth 8) except the rank-one part of
//! the twist, and a step costs `O(S)`.
//!
//! The guides clamp the cable fully, so the segments of a whole cable are independent
//! static problems: [`solve_cable`] solves them one after another.

mod banded;
pub mod continuation;
mod joint;
mod loads;
pub(crate) mod newton;
mod retract;
pub(crate) mod rod;
pub mod sliding;
pub mod swivel;
pub mod turns;

pub use loads::{ClampLoad, clamp_loads};
pub use rod::{EnergyTerms, Hold, Holds, PIN_STIFFNESS_PER_AXIAL, Pin, RodParameters};

use nalgebra::{Point3, Rotation3, Vector3};

use crate::pose::Pose;
use rod::Rod;

/// How the far end of a segment is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FarEnd {
    /// Clamped in position and orientation by a guide (its +z is the cable direction).
    Clamped(Pose),
    /// Free: no force, no moment (a cantilever).
    Free,
}

/// Stopping rule of the Newton iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Converged when no force component on a free node exceeds this (N).
    pub force_tolerance_n: f64,
    /// Newton steps allowed before giving up.
    pub max_iterations: usize,
}

impl Default for SolverOptions {
    /// 1e-8 N: about 4e-7 of the weight of one 10 mm sub-segment of the bundled cables, which
    /// leaves node positions accurate to well under a micrometre.
    fn default() -> Self {
        Self {
            force_tolerance_n: 1e-8,
            max_iterations: 100,
        }
    }
}

impl SolverOptions {
    /// The stopping rule for shapes whose stress metrics are judged (attachment test, the
    /// motion test's initial shape): 1e-6 N is 4e-5 of the weight of one 10 mm sub-segment of
    /// the bundled cables; on the softest mode of a sagging span (a few N/m) it leaves the
    /// nodes within about a micrometre, far below the millimetres the limits are judged on,
    /// while the default 1e-8 N sits at the rounding floor of long spans and is not always
    /// reached.
    pub const STRESS_CHECK: SolverOptions = SolverOptions {
        force_tolerance_n: 1e-6,
        max_iterations: 200,
    };
}

/// A converged equilibrium shape (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// `S + 1` nodes from the start guide origin to the end guide origin (or the free end).
    pub nodes: Vec<Point3<f64>>,
    /// `S + 1` node frames (columns normal, binormal, tangent); the first and last are the
    /// guide orientations.
    pub frames: Vec<Rotation3<f64>>,
    /// Total twist Ψ between the guides (rad); 0 for a free end.
    pub twist_rad: f64,
    /// Potential energy at the solution, term by term (J).
    pub energy: EnergyTerms,
    /// Newton steps taken.
    pub iterations: usize,
    /// Largest force component left on a free node (N).
    pub residual_n: f64,
}

/// Why no equilibrium was returned.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticsError {
    /// Parameters or the start shape cannot describe a cable.
    #[error("invalid static problem: {what}")]
    InvalidInput {
        /// What is wrong.
        what: String,
    },
    /// Newton's method stopped without meeting the force tolerance.
    #[error(
        "static solve did not converge: {reason} (after {iterations} iterations, residual {residual_n:.3e} N)"
    )]
    NotConverged {
        /// Why it stopped.
        reason: String,
        /// Newton steps taken.
        iterations: usize,
        /// Largest force component left (N); NaN if the state became non-finite.
        residual_n: f64,
    },
}

/// Solves one segment for static equilibrium from the shape `initial_nodes` (`S + 1` nodes;
/// the first and, for a clamped end, the last are replaced by the guide origins).
///
/// `initial_twist_rad` picks the branch of the total twist (e.g. the previous pose's
/// solution when a guide turns by more than half a turn); `None` takes the principal branch
/// `(−π, π]` of the start shape. A [`StaticSolver`] does the same with reused buffers.
pub fn solve_segment(
    params: &RodParameters,
    start: &Pose,
    far_end: &FarEnd,
    initial_nodes: &[Point3<f64>],
    initial_twist_rad: Option<f64>,
    options: &SolverOptions,
) -> Result<Equilibrium, StaticsError> {
    StaticSolver::default().solve(
        params,
        start,
        far_end,
        initial_nodes,
        initial_twist_rad,
        options,
    )
}

/// [`solve_segment`] with buffers kept from one solve to the next: for many solves in a
/// row (an attachment test, a sweep over the poses of a motion), where allocating them anew
/// would cost a noticeable part of a solve.
#[derive(Debug, Clone, Default)]
pub struct StaticSolver {
    workspace: newton::Workspace,
}

impl StaticSolver {
    /// See [`solve_segment`].
    pub fn solve(
        &mut self,
        params: &RodParameters,
        start: &Pose,
        far_end: &FarEnd,
        initial_nodes: &[Point3<f64>],
        initial_twist_rad: Option<f64>,
        options: &SolverOptions,
    ) -> Result<Equilibrium, StaticsError> {
        self.solve_pinned(
            params,
            (start, None, far_end),
            initial_nodes,
            initial_twist_rad,
            options,
        )
    }

    /// [`StaticSolver::solve`] with a swivel clamp `pin` holding one interior node between
    /// the clamps `start` and `far_end` (a piece through a swivel clamp).
    pub fn solve_pinned(
        &mut self,
        params: &RodParameters,
        (start, pin, far_end): (&Pose, Option<&Pin>, &FarEnd),
        initial_nodes: &[Point3<f64>],
        initial_twist_rad: Option<f64>,
        options: &SolverOptions,
    ) -> Result<Equilibrium, StaticsError> {
        check_input(params, start, far_end, initial_nodes, options)?;
        if let Some(pin) = pin {
            let finite = pin
                .position
                .iter()
                .chain(pin.axis.iter())
                .all(|c| c.is_finite());
            if !(finite && pin.node >= 1 && pin.node + 1 < initial_nodes.len()) {
                return Err(StaticsError::InvalidInput {
                    what: format!(
                        "a swivel clamp must hold an interior node of a finite place: node {} \
                         of {}",
                        pin.node,
                        initial_nodes.len()
                    ),
                });
            }
        }
        let rod = Rod::new(
            *params,
            *start,
            clamped_pose(far_end),
            initial_nodes.len() - 1,
        )
        .with_pin(pin.copied());
        let x = rod.free_coordinates(initial_nodes);
        let twist = match initial_twist_rad {
            Some(twist) => twist,
            None => rod.evaluate(&x, 0.0, None).twist,
        };
        let result = newton::minimize(
            &rod,
            x,
            twist,
            options.force_tolerance_n,
            options.max_iterations,
            &mut self.workspace,
        );
        if let Some(reason) = result.failure {
            return Err(StaticsError::NotConverged {
                reason,
                iterations: result.iterations,
                residual_n: result.residual,
            });
        }
        let nodes = rod.nodes(&result.x);
        let evaluation = &self.workspace.evaluation;
        Ok(Equilibrium {
            frames: rod.frames(&nodes, evaluation.twist),
            nodes,
            twist_rad: evaluation.twist,
            energy: evaluation.terms,
            iterations: result.iterations,
            residual_n: result.residual,
        })
    }
}

/// The potential energy of the shape `nodes` (`S + 1` nodes; the first and, for a clamped
/// end, the last are taken to be at the guide origins) and its total twist, on the branch
/// nearest `twist_branch_rad`. For reports and for checks of the solver: at an equilibrium,
/// the derivatives of this energy with respect to the guide poses are the clamp reactions.
pub fn potential_energy(
    params: &RodParameters,
    start: &Pose,
    far_end: &FarEnd,
    nodes: &[Point3<f64>],
    twist_branch_rad: f64,
) -> Result<(EnergyTerms, f64), StaticsError> {
    check_input(params, start, far_end, nodes, &SolverOptions::default())?;
    let rod = Rod::new(*params, *start, clamped_pose(far_end), nodes.len() - 1);
    let evaluation = rod.evaluate(&rod.free_coordinates(nodes), twist_branch_rad, None);
    Ok((evaluation.terms, evaluation.twist))
}

pub(crate) fn clamped_pose(far_end: &FarEnd) -> Option<Pose> {
    match far_end {
        FarEnd::Clamped(pose) => Some(*pose),
        FarEnd::Free => None,
    }
}

/// One segment of a whole cable: its guides and its start shape.
#[derive(Debug, Clone, Copy)]
pub struct SegmentStart<'a> {
    /// The guide at the segment's start.
    pub start: Pose,
    /// The guide at the segment's end.
    pub end: Pose,
    /// Start shape, `S + 1` nodes.
    pub nodes: &'a [Point3<f64>],
    /// Branch of the total twist, as in [`solve_segment`].
    pub twist_rad: Option<f64>,
}

/// Solves every segment of a cable clamped at all its guides: clamps transmit force and
/// moment, so each segment is in equilibrium on its own. One result per segment, in order.
pub fn solve_cable(
    params: &RodParameters,
    segments: &[SegmentStart<'_>],
    options: &SolverOptions,
) -> Vec<Result<Equilibrium, StaticsError>> {
    segments
        .iter()
        .map(|s| {
            solve_segment(
                params,
                &s.start,
                &FarEnd::Clamped(s.end),
                s.nodes,
                s.twist_rad,
                options,
            )
        })
        .collect()
}

pub(crate) fn check_input(
    params: &RodParameters,
    start: &Pose,
    far_end: &FarEnd,
    nodes: &[Point3<f64>],
    options: &SolverOptions,
) -> Result<(), StaticsError> {
    let invalid = |what: String| Err(StaticsError::InvalidInput { what });
    let positive = [
        ("pitch", params.pitch_m),
        ("bending stiffness", params.bending_stiffness_n_m2),
        ("torsion stiffness", params.torsion_stiffness_n_m2),
        ("axial stiffness", params.axial_stiffness_n),
        ("force tolerance", options.force_tolerance_n),
    ];
    for (name, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            return invalid(format!("{name} must be finite and > 0, got {value}"));
        }
    }
    let mass = params.mass_per_length_kg_m;
    let mass_ok = mass.is_finite() && mass >= 0.0;
    if !mass_ok || !finite_vector(&params.gravity_m_s2) {
        return invalid("mass per length and gravity must be finite (mass ≥ 0)".into());
    }
    if nodes.len() < 2 {
        return invalid(format!(
            "a segment needs at least 2 nodes, got {}",
            nodes.len()
        ));
    }
    if let Some(k) = nodes.iter().position(|p| !finite_vector(&p.coords)) {
        return invalid(format!("start shape node {k} is not finite"));
    }
    let end_ok = match far_end {
        FarEnd::Clamped(pose) => finite_pose(pose),
        FarEnd::Free => true,
    };
    if !finite_pose(start) || !end_ok {
        return invalid("a guide pose is not finite".into());
    }
    Ok(())
}

fn finite_vector(v: &Vector3<f64>) -> bool {
    v.iter().all(|c| c.is_finite())
}

fn finite_pose(pose: &Pose) -> bool {
    finite_vector(&pose.translation.vector) && pose.rotation.coords.iter().all(|c| c.is_finite())
}

#[cfg(test)]
mod tests;
