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
///
/// The banded part alone can be indefinite where the whole Hessian is not: its twist term
/// `kΨ∇²Ψ` may bend a soft mode (a hanging loop swinging about its chord) negative that the
/// rank-one `k∇Ψ∇Ψᵀ` makes positive again. Shifting then would turn every step into a damped
/// one and Newton would crawl, so the unshifted system is first solved by conjugate gradients
/// preconditioned with the shifted factorization; only when that finds negative curvature is
/// the shifted step taken.
fn descent_direction(hessian: &SymmetricBand, evaluation: &Evaluation, twist: f64) -> Vec<f64> {
    let mut shift = 0.0;
    for _ in 0..MAX_SHIFTS {
        let mut shifted = hessian.clone();
        shifted.add_to_diagonal(shift);
        if let Ok(factor) = shifted.cholesky() {
            let preconditioner = RankOneUpdated {
                factor: &factor,
                update: &evaluation.twist_gradient,
                stiffness: twist,
            };
            let exact = (shift > 0.0)
                .then(|| conjugate_gradients(hessian, &preconditioner, evaluation))
                .flatten();
            let direction =
                exact.unwrap_or_else(|| preconditioner.solve(negated(&evaluation.gradient)));
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
    negated(&evaluation.gradient)
}

/// `B + k g gᵀ` with `B` factored: solves by Sherman–Morrison, multiplies directly.
struct RankOneUpdated<'a> {
    factor: &'a BandCholesky,
    /// `g = ∇Ψ`; empty without a twist term.
    update: &'a [f64],
    /// `k`.
    stiffness: f64,
}

impl RankOneUpdated<'_> {
    /// `(B + k g gᵀ)⁻¹ rhs`.
    fn solve(&self, mut rhs: Vec<f64>) -> Vec<f64> {
        self.factor.solve_in_place(&mut rhs);
        if self.stiffness == 0.0 || self.update.is_empty() {
            return rhs;
        }
        let g = self.update;
        let mut z = g.to_vec();
        self.factor.solve_in_place(&mut z);
        let coefficient = self.stiffness * dot(g, &rhs) / (1.0 + self.stiffness * dot(g, &z));
        for (d, z) in rhs.iter_mut().zip(&z) {
            *d -= coefficient * z;
        }
        rhs
    }
}

/// Conjugate-gradient iterations of the unshifted Newton system, at most.
const CG_ITERATIONS: usize = 40;
/// Relative residual at which the conjugate gradients stop.
const CG_TOLERANCE: f64 = 1e-10;

/// Solves `(H + k g gᵀ) d = −∇E` (`H` the unshifted banded Hessian) by conjugate gradients
/// preconditioned with the shifted system; `None` on negative curvature or no convergence.
fn conjugate_gradients(
    hessian: &SymmetricBand,
    preconditioner: &RankOneUpdated<'_>,
    evaluation: &Evaluation,
) -> Option<Vec<f64>> {
    let multiply = |x: &[f64]| {
        let mut product = hessian.multiply(x);
        let g = preconditioner.update;
        if !g.is_empty() {
            let scale = preconditioner.stiffness * dot(g, x);
            product.iter_mut().zip(g).for_each(|(p, g)| *p += scale * g);
        }
        product
    };
    let mut residual = negated(&evaluation.gradient);
    let target = CG_TOLERANCE * dot(&residual, &residual).sqrt();
    let mut solution = vec![0.0; residual.len()];
    let mut preconditioned = preconditioner.solve(residual.clone());
    let mut direction = preconditioned.clone();
    let mut rho = dot(&residual, &preconditioned);
    for _ in 0..CG_ITERATIONS {
        let product = multiply(&direction);
        let curvature = dot(&direction, &product);
        if curvature.is_nan() || curvature <= 0.0 {
            return None;
        }
        let step = rho / curvature;
        axpy(&mut solution, step, &direction);
        axpy(&mut residual, -step, &product);
        if dot(&residual, &residual).sqrt() <= target {
            return Some(solution);
        }
        preconditioned = preconditioner.solve(residual.clone());
        let next_rho = dot(&residual, &preconditioned);
        let beta = next_rho / rho;
        rho = next_rho;
        for (d, z) in direction.iter_mut().zip(&preconditioned) {
            *d = z + beta * *d;
        }
    }
    None
}

/// `y += a x`.
fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += a * x);
}

fn negated(values: &[f64]) -> Vec<f64> {
    values.iter().map(|v| -v).collect()
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
