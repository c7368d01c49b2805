//! Retraction of a Newton trial point onto its predicted edge lengths.
//!
//! The axial stiffness `EA/l` is thousands of times the bending stiffness `kb/l²`. The
//! quadratic model of the energy sees no cost in turning an edge (its Hessian across the
//! edge is zero at rest length), but a finite turn lengthens the edge by `δ²/2l` and the
//! stiff spring makes that expensive: unretracted steps are cut to a few millimetres and
//! Newton crawls. So every trial point is moved back, by the smallest correction, to the edge
//! lengths the linearized step predicts, `|e_i| + t_i·δe_i`. The correction is second order
//! in the step, so near the solution it vanishes fast enough to keep Newton's quadratic
//! convergence, and far from it the step follows the cable's nearly inextensible motion.
//!
//! With constraints `c_i = |e_i|² − L_i²` over the free nodes, a Gauss–Newton step is
//! `Δx = −Jᵀ (J Jᵀ)⁻¹ c`; `J Jᵀ` is tridiagonal (an edge shares a node only with its
//! neighbours), solved by the Thomas algorithm.

use nalgebra::{Point3, Vector3};

/// Gauss–Newton iterations of one retraction, at most.
const ITERATIONS: usize = 8;
/// Relative error of the squared lengths at which the retraction stops: an edge then is
/// within 5e-13 of its length, an axial force of at most 5e-7 N even at EA = 1e6 N
/// (below the solver's 1e-6 N); 1e-14 took 4.9 Gauss–Newton rounds per retraction where
/// this takes 2.7, for the same Newton steps.
const TOLERANCE: f64 = 1e-12;
/// Relative diagonal damping: `J Jᵀ` is singular for a straight chain between clamps.
const DAMPING: f64 = 1e-12;

/// Buffers a retraction reuses.
#[derive(Debug, Clone, Default)]
pub(crate) struct Retraction {
    edges: Vec<Vector3<f64>>,
    lambda: Vec<f64>,
    ratios: Vec<f64>,
}

/// Moves the free nodes (`free[k]`) so that edge `i` (node `i` → `i + 1`) gets length
/// `targets[i]`. Returns false, leaving `nodes` unspecified, if the iteration produced
/// non-finite values.
pub(crate) fn restore_lengths(
    nodes: &mut [Point3<f64>],
    targets: &[f64],
    free: &[bool],
    buffers: &mut Retraction,
) -> bool {
    let count = targets.len();
    let Retraction {
        edges,
        lambda,
        ratios,
    } = buffers;
    lambda.clear();
    lambda.resize(count, 0.0);
    ratios.clear();
    ratios.resize(count, 0.0);
    for _ in 0..ITERATIONS {
        edges.clear();
        edges.extend(nodes.windows(2).map(|w| w[1] - w[0]));
        let mut worst: f64 = 0.0;
        for i in 0..count {
            lambda[i] = edges[i].norm_squared() - targets[i] * targets[i];
            worst = worst.max(lambda[i].abs() / (targets[i] * targets[i]));
        }
        if worst <= TOLERANCE {
            break;
        }
        let diagonal = |i: usize| {
            let ends = f64::from(u8::from(free[i]) + u8::from(free[i + 1]));
            4.0 * edges[i].norm_squared() * ends * (1.0 + DAMPING)
        };
        let off = |i: usize| {
            if free[i + 1] {
                -4.0 * edges[i].dot(&edges[i + 1])
            } else {
                0.0
            }
        };
        solve_tridiagonal(diagonal, off, lambda, ratios);
        for (k, node) in nodes.iter_mut().enumerate() {
            if !free[k] {
                continue;
            }
            let mut step = Vector3::zeros();
            if k > 0 {
                step -= 2.0 * lambda[k - 1] * edges[k - 1];
            }
            if k < count {
                step += 2.0 * lambda[k] * edges[k];
            }
            *node += step;
        }
    }
    nodes.iter().all(|p| p.coords.iter().all(|c| c.is_finite()))
}

/// Solves the symmetric tridiagonal system with `diagonal(i)` and `off(i)` = entry
/// `(i, i + 1)` by the Thomas algorithm; `rhs` becomes the solution (non-finite if a pivot
/// vanishes).
fn solve_tridiagonal(
    diagonal: impl Fn(usize) -> f64,
    off: impl Fn(usize) -> f64,
    rhs: &mut [f64],
    ratios: &mut [f64],
) {
    let n = rhs.len();
    for i in 0..n {
        let coupling = if i > 0 { off(i - 1) } else { 0.0 };
        let previous_ratio = if i > 0 { ratios[i - 1] } else { 0.0 };
        let previous_value = if i > 0 { rhs[i - 1] } else { 0.0 };
        let pivot = diagonal(i) - coupling * previous_ratio;
        ratios[i] = if i + 1 < n { off(i) / pivot } else { 0.0 };
        rhs[i] = (rhs[i] - coupling * previous_value) / pivot;
    }
    for i in (0..n.saturating_sub(1)).rev() {
        rhs[i] -= ratios[i] * rhs[i + 1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bent_chain_gets_its_target_lengths_with_clamped_and_free_ends() {
        let nodes: Vec<Point3<f64>> = (0..=6)
            .map(|k| {
                let a = 0.3 * k as f64;
                Point3::new(0.05 * a.sin(), 0.05 * (1.0 - a.cos()), 0.002 * k as f64)
            })
            .collect();
        let targets: Vec<f64> = (0..6).map(|i| 0.0155 + 0.0002 * i as f64).collect();
        for free_end in [false, true] {
            let mut moved = nodes.clone();
            let mut free = vec![true; 7];
            free[0] = false;
            free[6] = free_end;
            assert!(restore_lengths(
                &mut moved,
                &targets,
                &free,
                &mut Retraction::default()
            ));
            for (i, w) in moved.windows(2).enumerate() {
                assert!(((w[1] - w[0]).norm() - targets[i]).abs() < 1e-14);
            }
            assert_eq!(moved[0], nodes[0]);
            assert_eq!(moved[6] == nodes[6], !free_end);
        }
    }
}
