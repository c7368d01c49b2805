//! Newton's method with a backtracking line search on the segment energy.
//!
//! Each step solves `(H + k ∇Ψ∇Ψᵀ) d = −∇E` with a banded `L D Lᵀ` factorization of `H` and
//! one Sherman–Morrison correction for the rank-one twist term. Where that matrix is not
//! positive definite (a compressed or buckling configuration), a diagonal shift is added
//! until it is, which the factorization's inertia tells: a step between Newton and steepest
//! descent that always goes downhill. The step length keeps every node within
//! [`MAX_STEP_PITCHES`] pitches of where it was and satisfies the Armijo condition; near the
//! solution, where energy differences drown in rounding, a step that halves the force
//! residual is accepted as well.
//!
//! All buffers live in a [`Workspace`], so that the iterations allocate nothing and a
//! sequence of solves (a time integration, a sweep over poses) reuses them.

use super::banded::{BandLdlt, SymmetricBand};
use super::rod::{Evaluation, Rod, Scratch};

/// Armijo sufficient-decrease constant.
const ARMIJO: f64 = 1e-4;
/// Step halvings tried before the line search gives up.
const MAX_HALVINGS: usize = 40;
/// Longest node move of one step, in pitches. Measured on the bundled pick-and-place
/// attachment test (3578 solves from the connected geometry): a cap of 1 pitch took a median
/// of 8 Newton steps, 3 pitches 6, 10 pitches 6 with more failed trial steps.
const MAX_STEP_PITCHES: f64 = 3.0;
/// Relative size of the first diagonal shift.
const FIRST_SHIFT: f64 = 1e-8;
/// Diagonal shifts tried before the step falls back to steepest descent.
const MAX_SHIFTS: usize = 30;
/// Pivots below this, relative to the largest diagonal entry, are not trusted.
const TINY_PIVOT: f64 = 1e-13;

/// Where Newton's method ended.
#[derive(Debug, Clone)]
pub(crate) struct NewtonResult {
    pub(crate) x: Vec<f64>,
    pub(crate) iterations: usize,
    pub(crate) residual: f64,
    /// `None` when converged, else why not.
    pub(crate) failure: Option<String>,
}

/// Buffers of Newton's method, reused across iterations and solves.
#[derive(Debug, Clone, Default)]
pub(crate) struct Workspace {
    hessian: SymmetricBand,
    /// The Hessian at the first trial point of a line search: the full step is usually
    /// taken, and then it is the next iteration's Hessian.
    trial_hessian: SymmetricBand,
    /// Whether `trial_hessian` belongs to the accepted trial point.
    trial_has_hessian: bool,
    factor: BandLdlt,
    /// The evaluation at the current iterate (after a solve: at its result).
    pub(crate) evaluation: Evaluation,
    trial_evaluation: Evaluation,
    scratch: Scratch,
    direction: Vec<f64>,
    /// `B⁻¹ ∇Ψ` of the current factorization.
    solved_update: Vec<f64>,
    trial: Vec<f64>,
    /// The diagonal shift the last step needed (0: none): the next shifted attempt starts
    /// near it instead of climbing from the smallest shift again.
    last_shift: f64,
}

/// A line search that finds no lower energy ends the solve as converged when the largest
/// force is within this factor of the tolerance (the energy's rounding floor: measured on the
/// robot-level pick-and-place catalogue, solves stalled there at 1.8e-6 and 3.4e-6 N for a
/// 1e-6 N tolerance, between neighbours that converged).
const STALL_TOLERANCE_FACTOR: f64 = 10.0;

/// Minimizes the rod energy from `x` until the largest force component is at most
/// `tolerance` (N) — or within [`STALL_TOLERANCE_FACTOR`] of it where the energy can no
/// longer decrease — or `max_iterations` steps were taken; the evaluation at the result is
/// left in `workspace.evaluation`.
pub(crate) fn minimize(
    rod: &Rod,
    mut x: Vec<f64>,
    twist: f64,
    tolerance: f64,
    max_iterations: usize,
    workspace: &mut Workspace,
) -> NewtonResult {
    let ws = workspace;
    ws.last_shift = 0.0;
    ws.evaluate_with_hessian(rod, &x, twist);
    let mut iterations = 0;
    let failure = loop {
        let residual = max_abs(&ws.evaluation.gradient);
        if !residual.is_finite() || !ws.evaluation.energy.is_finite() {
            break Some("the energy or the forces became non-finite".to_string());
        }
        if residual <= tolerance {
            break None;
        }
        if iterations == max_iterations {
            break Some(format!("no convergence in {max_iterations} iterations"));
        }
        ws.descent_direction(rod.twist_stiffness());
        if !ws.line_search(rod, &x) {
            // At a minimum the energy stops decreasing in floating point a little before the
            // forces reach a tight tolerance: that is convergence, not a failure.
            if residual <= STALL_TOLERANCE_FACTOR * tolerance {
                break None;
            }
            break Some("the line search found no lower energy".to_string());
        }
        std::mem::swap(&mut x, &mut ws.trial);
        iterations += 1;
        if ws.trial_has_hessian {
            std::mem::swap(&mut ws.evaluation, &mut ws.trial_evaluation);
            std::mem::swap(&mut ws.hessian, &mut ws.trial_hessian);
        } else {
            ws.evaluate_with_hessian(rod, &x, ws.trial_evaluation.twist);
        }
    };
    NewtonResult {
        residual: max_abs(&ws.evaluation.gradient),
        x,
        iterations,
        failure,
    }
}

impl Workspace {
    /// The evaluation and Hessian at `x` (twist on the branch nearest `twist`).
    fn evaluate_with_hessian(&mut self, rod: &Rod, x: &[f64], twist: f64) {
        rod.evaluate_into(
            x,
            twist,
            Some(&mut self.hessian),
            &mut self.evaluation,
            &mut self.scratch,
        );
    }

    /// The Newton direction of `H + μI + k g gᵀ` (banded part `H`, twist term `k g gᵀ`) into
    /// `direction`, with the smallest shift `μ` of a series (0, then from near the last
    /// step's shift or `1e-8 · max |H_ii|`, ×10) that makes the matrix positive definite: a
    /// step between Newton and steepest descent that always goes downhill; steepest descent
    /// if no shift does.
    ///
    /// The banded part alone can be indefinite where the whole Hessian is not: its twist term
    /// `kΨ∇²Ψ` may bend a soft mode (a hanging loop swinging about its chord) negative that
    /// the rank-one `k g gᵀ` makes positive again. Shifting then would turn every step into a
    /// damped one and Newton would crawl. The factorization's inertia tells the two cases
    /// apart: with one negative eigenvalue of `H`, `H + k g gᵀ` is positive definite exactly
    /// when `1 + k gᵀH⁻¹g < 0` (its determinant is `det H · (1 + k gᵀH⁻¹g)`, and a rank-one
    /// update moves at most one eigenvalue across zero).
    fn descent_direction(&mut self, twist: f64) {
        let mut shift = 0.0;
        for _ in 0..MAX_SHIFTS {
            if self.solve_shifted(shift, twist) {
                self.last_shift = shift;
                return;
            }
            shift = if shift > 0.0 {
                10.0 * shift
            } else if self.last_shift > 0.0 {
                0.1 * self.last_shift
            } else {
                FIRST_SHIFT * self.hessian.max_diagonal().max(f64::MIN_POSITIVE)
            };
        }
        self.direction.clear();
        self.direction
            .extend(self.evaluation.gradient.iter().map(|g| -g));
    }

    /// The Newton direction with diagonal shift `shift`, if that system is positive definite
    /// and its direction goes downhill.
    fn solve_shifted(&mut self, shift: f64, twist: f64) -> bool {
        if self
            .hessian
            .ldlt_into(shift, TINY_PIVOT, &mut self.factor)
            .is_err()
        {
            return false;
        }
        let update = &self.evaluation.twist_gradient;
        let has_update = twist != 0.0 && !update.is_empty();
        self.direction.clear();
        self.direction
            .extend(self.evaluation.gradient.iter().map(|g| -g));
        self.solved_update.clear();
        if has_update {
            self.solved_update.extend_from_slice(update);
            self.factor
                .solve_many_in_place(&mut [&mut self.direction, &mut self.solved_update]);
        } else {
            self.factor.solve_in_place(&mut self.direction);
        }
        let denominator = 1.0 + twist * dot(update, &self.solved_update);
        let positive_definite = match self.factor.negative {
            0 => true,
            1 => has_update && denominator < 0.0,
            _ => false,
        };
        if !positive_definite {
            return false;
        }
        // (B + k g gᵀ)⁻¹ r = B⁻¹r − k (gᵀB⁻¹r) / (1 + k gᵀB⁻¹g) · B⁻¹g (Sherman–Morrison).
        if has_update {
            let coefficient = twist * dot(update, &self.direction) / denominator;
            for (d, z) in self.direction.iter_mut().zip(&self.solved_update) {
                *d -= coefficient * z;
            }
        }
        dot(&self.direction, &self.evaluation.gradient) < 0.0
    }

    /// Backtracking from the longest step that moves no node by more than
    /// [`MAX_STEP_PITCHES`]; the accepted point goes to `trial` and its evaluation to
    /// `trial_evaluation`. False when no step is accepted.
    fn line_search(&mut self, rod: &Rod, x: &[f64]) -> bool {
        let slope = dot(&self.evaluation.gradient, &self.direction);
        let residual = max_abs(&self.evaluation.gradient);
        let longest = max_node_displacement(&self.direction);
        let reach = MAX_STEP_PITCHES * rod.params().pitch_m;
        let mut step = if longest > reach {
            reach / longest
        } else {
            1.0
        };
        let energy = self.evaluation.energy;
        let roundoff = 1e-12 * energy.abs();
        for halving in 0..MAX_HALVINGS {
            // The retracted point first; the plain one where the retraction is ill-posed (a
            // straight chain between clamps cannot change its chord lengths to first order).
            for retract in [true, false] {
                if retract {
                    rod.retracted_step(
                        x,
                        &self.direction,
                        step,
                        &mut self.trial,
                        &mut self.scratch,
                    );
                } else {
                    self.trial.clear();
                    self.trial
                        .extend(x.iter().zip(&self.direction).map(|(x, d)| x + step * d));
                }
                // The first trial point gets its Hessian too: it is usually the next iterate.
                self.trial_has_hessian = halving == 0 && retract;
                rod.evaluate_into(
                    &self.trial,
                    self.evaluation.twist,
                    self.trial_has_hessian.then_some(&mut self.trial_hessian),
                    &mut self.trial_evaluation,
                    &mut self.scratch,
                );
                let trial = &self.trial_evaluation;
                let decrease = trial.energy - energy;
                let armijo = decrease <= ARMIJO * step * slope;
                let forces_halved =
                    decrease <= roundoff && max_abs(&trial.gradient) <= 0.5 * residual;
                if trial.energy.is_finite() && (armijo || forces_halved) {
                    return true;
                }
            }
            step *= 0.5;
        }
        false
    }
}

fn max_node_displacement(direction: &[f64]) -> f64 {
    direction
        .chunks_exact(3)
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0, f64::max)
}

/// Largest absolute value; NaN if any value is NaN.
pub(crate) fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m: f64, v| {
        if v.is_nan() || v.abs() > m {
            v.abs()
        } else {
            m
        }
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}
