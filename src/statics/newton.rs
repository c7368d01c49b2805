//! Newton's method with a backtracking line search on the segment energy.
//!
//! Each step solves `(H + μI + k ∇Ψ∇Ψᵀ) d = −∇E` with the banded Cholesky factorization and
//! one Sherman–Morrison correction for the rank-one twist term. `μ = 0` unless the banded
//! part is not positive definite (a compressed or buckling configuration), then it grows
//! from `1e-8 · max diag` by factors of 10 until the factorization succeeds: a step between
//! Newton and steepest descent that always goes downhill. The step length keeps every node
//! within one pitch of where it was and satisfies the Armijo condition; near the solution,
//! where energy differences drown in rounding, a step that halves the force residual is
//! accepted as well.

use super::banded::{BandCholesky, SymmetricBand};
use super::rod::{Evaluation, Rod};

/// Armijo sufficient-decrease constant.
const ARMIJO: f64 = 1e-4;
/// Step halvings tried before the line search gives up.
const MAX_HALVINGS: usize = 40;
/// Relative size of the first diagonal shift.
const FIRST_SHIFT: f64 = 1e-8;
/// Diagonal shifts tried before the step falls back to steepest descent.
const MAX_SHIFTS: usize = 30;

/// Where Newton's method ended.
#[derive(Debug, Clone)]
pub(crate) struct NewtonResult {
    pub(crate) x: Vec<f64>,
    pub(crate) evaluation: Evaluation,
    pub(crate) iterations: usize,
    pub(crate) residual: f64,
    /// `None` when converged, else why not.
    pub(crate) failure: Option<String>,
}

/// Minimizes the rod energy from `x` until the largest force component is at most
/// `tolerance` (N) or `max_iterations` steps were taken.
pub(crate) fn minimize(
    rod: &Rod,
    mut x: Vec<f64>,
    twist: f64,
    tolerance: f64,
    max_iterations: usize,
) -> NewtonResult {
    let mut hessian = SymmetricBand::zeros(x.len());
    let mut evaluation = rod.evaluate(&x, twist, Some(&mut hessian));
    let mut iterations = 0;
    let failure = loop {
        let residual = max_abs(&evaluation.gradient);
        if !residual.is_finite() || !evaluation.energy.is_finite() {
            break Some("the energy or the forces became non-finite".to_string());
        }
        if residual <= tolerance {
            break None;
        }
        if iterations == max_iterations {
            break Some(format!("no convergence in {max_iterations} iterations"));
        }
        let direction = descent_direction(&hessian, &evaluation, rod.twist_stiffness());
        match line_search(rod, &x, &evaluation, &direction) {
            Some((next, next_evaluation)) => {
                x = next;
                evaluation = next_evaluation;
            }
            None => break Some("the line search found no lower energy".to_string()),
        }
        iterations += 1;
        hessian.clear();
        evaluation = rod.evaluate(&x, evaluation.twist, Some(&mut hessian));
    };
    NewtonResult {
        residual: max_abs(&evaluation.gradient),
        x,
        evaluation,
        iterations,
        failure,
    }
}

/// The Newton direction, with the smallest diagonal shift that makes the banded part
/// positive definite; steepest descent if no shift does.
fn descent_direction(hessian: &SymmetricBand, evaluation: &Evaluation, twist: f64) -> Vec<f64> {
    let mut shift = 0.0;
    for _ in 0..MAX_SHIFTS {
        let mut shifted = hessian.clone();
        shifted.add_to_diagonal(shift);
        if let Ok(factor) = shifted.cholesky() {
            let direction = rank_one_solve(&factor, evaluation, twist);
            if dot(&direction, &evaluation.gradient) < 0.0 {
                return direction;
            }
        }
        shift = if shift == 0.0 {
            FIRST_SHIFT * hessian.max_diagonal().max(f64::MIN_POSITIVE)
        } else {
            10.0 * shift
        };
    }
    evaluation.gradient.iter().map(|g| -g).collect()
}

/// Solves `(B + k g gᵀ) d = −∇E` by Sherman–Morrison, `B` factored, `g = ∇Ψ`.
fn rank_one_solve(factor: &BandCholesky, evaluation: &Evaluation, k: f64) -> Vec<f64> {
    let mut direction: Vec<f64> = evaluation.gradient.iter().map(|g| -g).collect();
    factor.solve_in_place(&mut direction);
    if k == 0.0 || evaluation.twist_gradient.is_empty() {
        return direction;
    }
    let g = &evaluation.twist_gradient;
    let mut z = g.clone();
    factor.solve_in_place(&mut z);
    let coefficient = k * dot(g, &direction) / (1.0 + k * dot(g, &z));
    for (d, z) in direction.iter_mut().zip(&z) {
        *d -= coefficient * z;
    }
    direction
}

/// Backtracking from the longest step that moves no node by more than one pitch.
fn line_search(
    rod: &Rod,
    x: &[f64],
    evaluation: &Evaluation,
    direction: &[f64],
) -> Option<(Vec<f64>, Evaluation)> {
    let slope = dot(&evaluation.gradient, direction);
    let residual = max_abs(&evaluation.gradient);
    let longest = max_node_displacement(direction);
    let pitch = rod.params().pitch_m;
    let mut step = if longest > pitch {
        pitch / longest
    } else {
        1.0
    };
    let roundoff = 1e-12 * evaluation.energy.abs();
    for _ in 0..MAX_HALVINGS {
        // The retracted point first; the plain one where the retraction is ill-posed (a
        // straight chain between clamps cannot change its chord lengths to first order).
        for retract in [true, false] {
            let trial = if retract {
                rod.retracted_step(x, direction, step)
            } else {
                x.iter().zip(direction).map(|(x, d)| x + step * d).collect()
            };
            let trial_evaluation = rod.evaluate(&trial, evaluation.twist, None);
            let decrease = trial_evaluation.energy - evaluation.energy;
            let armijo = decrease <= ARMIJO * step * slope;
            let forces_halved =
                decrease <= roundoff && max_abs(&trial_evaluation.gradient) <= 0.5 * residual;
            if trial_evaluation.energy.is_finite() && (armijo || forces_halved) {
                return Some((trial, trial_evaluation));
            }
        }
        step *= 0.5;
    }
    None
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
