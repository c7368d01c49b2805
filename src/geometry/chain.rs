//! Projection of a polyline onto the rigid-chain constraints `|x_{k+1} − x_k| = l` with both
//! end nodes fixed, and the discrete bending energy of a chain between two guides.
//!
//! Nodes resampled at equal *arc length* on a smooth curve have chords `≈ l − l³κ²/24`, a
//! little short of the pitch. The discrete cable model needs them exact, so the interior nodes
//! are moved by minimum-norm Gauss–Newton corrections: with the constraints
//! `c_k = |e_k|² − l²` on the chords `e_k = x_{k+1} − x_k` (`k = 0 … S−1`) and the unknowns
//! `x_1 … x_{S−1}`, a step is `Δx = −Jᵀ (J Jᵀ)⁻¹ c`, the smallest move that zeroes the
//! linearized residual. `J Jᵀ` is tridiagonal — chord `k` shares a node only with chords
//! `k ± 1` — with diagonal `4|e_k|²` times the number of free ends of chord `k` and
//! off-diagonal `−4 e_k·e_{k+1}`, so each step is O(S) by the Thomas algorithm (run from both
//! ends at once, see `solve_twisted`).
//!
//! The step is a descent direction of `Σ c_k²` (its slope is `−2 Σ c_k²`), and because the
//! constraints are quadratic that sum is an exact quartic along it. On ordinary bends the full
//! step lowers it and the residual falls quadratically (2–3 steps from arc-length nodes); the
//! evaluation of the moved nodes that shows it also assembles the next `J Jᵀ`. For chains
//! that are almost straight or folded, `J Jᵀ` is nearly singular (a straight chain cannot
//! lengthen its chords to first order) and the full step overshoots by orders of magnitude;
//! then the quartic's minimizer is taken, found without trial evaluations. Where
//! `J Jᵀ` is singular to working precision, its diagonal is damped (Levenberg–Marquardt),
//! which keeps a descent direction.

use nalgebra::{Point3, Vector3};

/// Iteration limit of the projection (it converges in 2–3 iterations on ordinary bends).
const MAX_ITERATIONS: usize = 50;
/// Iteration limit of the one-dimensional line-search minimization.
const MAX_LINE_SEARCH_ITERATIONS: usize = 60;
/// Largest multiple of a (damped) step the line search considers.
const MAX_STEP_SCALE: f64 = 1e6;
/// Relative damping of the diagonal of `J Jᵀ` tried in turn when the plain system is singular
/// to working precision (a nearly straight chain).
const DAMPING: [f64; 5] = [0.0, 1e-12, 1e-9, 1e-6, 1e-3];
/// Absolute chord tolerance (m) for coordinates of order 1 m.
const CHORD_TOLERANCE: f64 = 1e-13;

/// The projection did not reach the chord tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProjectionFailure {
    /// Largest `| |e_k| − l |` reached (m).
    pub residual_m: f64,
    /// Iterations spent.
    pub iterations: usize,
}

/// Moves `nodes[1 .. S−1]` (`S = nodes.len() − 1`) until every chord is `pitch` long within
/// [`chord_tolerance`]; `nodes[0]` and `nodes[S]` stay. Returns the iterations used.
pub(crate) fn project_onto_rigid_chain(
    nodes: &mut [Point3<f64>],
    pitch: f64,
) -> Result<usize, ProjectionFailure> {
    // | |e| − l | = |c| / (|e| + l) ≤ |c| / l: a bound on |c| = ||e|² − l²| that needs no
    // square root and is at most twice as strict as the chord tolerance itself.
    let residual_limit = chord_tolerance(nodes, pitch) * pitch;
    let mut work = Workspace::new(nodes.len().saturating_sub(1));
    let mut state = work.evaluate(nodes, pitch);
    for iteration in 0..MAX_ITERATIONS {
        if state.max_residual <= residual_limit {
            return Ok(iteration);
        }
        // Plain Gauss–Newton first; if J Jᵀ is singular to working precision, increasingly
        // damped (Levenberg–Marquardt) steps, still descent directions.
        let stepped = DAMPING
            .iter()
            .any(|&damping| work.gauss_newton_step(damping));
        match stepped.then(|| work.line_search(nodes, pitch, state.merit)) {
            Some(Some(next)) => state = next,
            _ => return Err(ProjectionFailure::at(nodes, pitch, iteration)),
        }
    }
    if state.max_residual <= residual_limit {
        Ok(MAX_ITERATIONS)
    } else {
        Err(ProjectionFailure::at(nodes, pitch, MAX_ITERATIONS))
    }
}

impl ProjectionFailure {
    fn at(nodes: &[Point3<f64>], pitch: f64, iterations: usize) -> Self {
        Self {
            residual_m: max_chord_error(nodes, pitch),
            iterations,
        }
    }
}

/// Chord tolerance (m): [`CHORD_TOLERANCE`], or a few ulp of the coordinates where those
/// are so large that 1e-13 m is below their resolution. A chain of `S` chords of about `l`
/// stays within `S·l` of its first node, which bounds the coordinates without visiting them.
pub(crate) fn chord_tolerance(nodes: &[Point3<f64>], pitch: f64) -> f64 {
    let first = nodes
        .first()
        .map_or(0.0, |p| p.x.abs().max(p.y.abs()).max(p.z.abs()));
    let scale = first + nodes.len() as f64 * pitch;
    CHORD_TOLERANCE.max(32.0 * f64::EPSILON * scale)
}

/// Largest `| |x_{k+1} − x_k| − pitch |` (m); NaN if any chord is NaN.
pub(crate) fn max_chord_error(nodes: &[Point3<f64>], pitch: f64) -> f64 {
    nodes
        .windows(2)
        .map(|w| ((w[1] - w[0]).norm() - pitch).abs())
        .fold(
            0.0,
            |m: f64, e| if e.is_nan() { f64::NAN } else { m.max(e) },
        )
}

/// Discrete bending energy `Σ θ_j²` (rad²) of a chain between two guides: `θ_j` are the
/// angles between adjacent directions of `[v0, e_0, …, e_{S−1}, v1]`, the same joints as
/// [`crate::stress::min_bend_radius`] uses. The equilibrium minimizes bending energy, so the
/// less bent of two starting shapes is the better start. `connect` compares the continuous
/// energy of the curves instead (`∫ κ² ds`, which `Σ θ²/l` converges to); this stays as a check.
#[cfg(test)]
pub(crate) fn bending_energy(
    nodes: &[Point3<f64>],
    start_tangent: &Vector3<f64>,
    end_tangent: &Vector3<f64>,
) -> f64 {
    let mut previous = *start_tangent;
    let mut energy = 0.0;
    for direction in nodes
        .windows(2)
        .map(|w| w[1] - w[0])
        .chain(std::iter::once(*end_tangent))
    {
        let angle = previous
            .cross(&direction)
            .norm()
            .atan2(previous.dot(&direction));
        energy += angle * angle;
        previous = direction;
    }
    energy
}

/// Size of the constraint residuals `c_k = |e_k|² − l²` (m², m⁴).
#[derive(Debug, Clone, Copy)]
struct Residuals {
    /// `Σ c_k²`, the merit function of the line search.
    merit: f64,
    /// `max |c_k|`.
    max_residual: f64,
}

/// Per-chord data of one projection step: chord `k` is row `k` of `J Jᵀ λ = c`.
#[derive(Debug, Clone, Copy, Default)]
struct ChordState {
    /// `e_k` at the current nodes.
    chord: Vector3<f64>,
    /// `c_k = |e_k|² − l²` (m²).
    residual: f64,
    /// `(J Jᵀ)_{k,k}` (m²).
    diagonal: f64,
    /// `(J Jᵀ)_{k,k+1}` (m²); 0 for the last row.
    off: f64,
    /// Elimination: the coefficient left coupling row `k` to its unsolved neighbour.
    upper: f64,
    /// Elimination: the modified right-hand side, then the multiplier `λ_k`.
    solution: f64,
}

/// Solves the symmetric tridiagonal system `(diagonal, off) λ = residual` into `solution` by
/// eliminating from both ends towards the middle row (a twisted factorization): the two
/// sweeps are independent chains of divisions, which the processor overlaps, where the
/// Thomas algorithm is one chain twice as long. Above the middle, row `k` becomes
/// `λ_k + u_k λ_{k+1} = y_k`; below it, `w_k λ_{k−1} + λ_k = z_k`; the middle row then has one
/// unknown, and back substitution runs outwards. `false` if a pivot is not positive (the
/// matrix is positive semi-definite, so that means singular) or not finite.
fn solve_twisted(rows: &mut [ChordState]) -> bool {
    let n = rows.len();
    let middle = n / 2;
    let mut positive = true;
    // Each sweep's chain is pivot → b²/pivot → next pivot; 1/pivot and the rest hang off it.
    let (mut pivot_up, mut y, mut pivot_down, mut z) = (1.0, 0.0, 1.0, 0.0);
    for i in 0..middle.max(n - 1 - middle) {
        if i < middle {
            let b = if i > 0 { rows[i - 1].off } else { 0.0 };
            let pivot = rows[i].diagonal - b * b / pivot_up;
            positive &= pivot > 0.0 && pivot.is_finite();
            let inverse = 1.0 / pivot;
            y = (rows[i].residual - b * y) * inverse;
            (rows[i].upper, rows[i].solution) = (rows[i].off * inverse, y);
            pivot_up = pivot;
        }
        let k = n - 1 - i;
        if k > middle {
            let b = rows[k].off;
            let pivot = rows[k].diagonal - b * b / pivot_down;
            positive &= pivot > 0.0 && pivot.is_finite();
            let inverse = 1.0 / pivot;
            z = (rows[k].residual - b * z) * inverse;
            (rows[k].upper, rows[k].solution) = (rows[k - 1].off * inverse, z);
            pivot_down = pivot;
        }
    }
    let before = middle.checked_sub(1).map_or((0.0, 0.0, 0.0), |k| {
        (rows[k].off, rows[k].upper, rows[k].solution)
    });
    let after = rows
        .get(middle + 1)
        .map_or((0.0, 0.0), |r| (r.upper, r.solution));
    let b_after = rows[middle].off;
    let pivot = rows[middle].diagonal - before.0 * before.1 - b_after * after.0;
    positive &= pivot > 0.0 && pivot.is_finite();
    rows[middle].solution =
        (rows[middle].residual - before.0 * before.2 - b_after * after.1) / pivot;
    for i in 1..=middle.max(n - 1 - middle) {
        if i <= middle {
            let k = middle - i;
            rows[k].solution -= rows[k].upper * rows[k + 1].solution;
        }
        if middle + i < n {
            let k = middle + i;
            rows[k].solution -= rows[k].upper * rows[k - 1].solution;
        }
    }
    positive
}

/// Buffers of one projection, sized for `S` chords.
struct Workspace {
    chords: Vec<ChordState>,
    /// The Gauss–Newton step of the nodes (first and last stay zero).
    step: Vec<Vector3<f64>>,
    /// Largest `|Δx_j|²` of the step.
    largest_move_squared: f64,
}

impl Workspace {
    fn new(chords: usize) -> Self {
        Self {
            chords: vec![ChordState::default(); chords],
            step: vec![Vector3::zeros(); chords + 1],
            largest_move_squared: 0.0,
        }
    }

    /// Stores the chords and constraint values of `nodes` and the undamped `J Jᵀ`; returns
    /// `Σ c_k²` and `max |c_k|` (NaN if any is NaN).
    fn evaluate(&mut self, nodes: &[Point3<f64>], pitch: f64) -> Residuals {
        let pitch_squared = pitch * pitch;
        let (mut merit, mut max_residual) = (0.0, 0.0_f64);
        // Symmetric tridiagonal J Jᵀ: a_k = 4|e_k|²·(free ends), b_k = −4 e_k·e_{k+1}.
        for (state, pair) in self.chords.iter_mut().zip(nodes.windows(2)) {
            let chord = pair[1] - pair[0];
            let length_squared = chord.norm_squared();
            let residual = length_squared - pitch_squared;
            state.chord = chord;
            state.residual = residual;
            state.diagonal = 8.0 * length_squared;
            merit += residual * residual;
            max_residual = max_residual.max(residual.abs());
        }
        let count = self.chords.len();
        for k in 1..count {
            let product = self.chords[k - 1].chord.dot(&self.chords[k].chord);
            self.chords[k - 1].off = -4.0 * product;
        }
        if let Some(last) = self.chords.last_mut() {
            // The end chords have one free end (exact: powers of two).
            last.off = 0.0;
            last.diagonal *= 0.5;
        }
        if count > 1 {
            self.chords[0].diagonal *= 0.5;
        }
        Residuals {
            merit,
            // `f64::max` drops NaN; the merit keeps it.
            max_residual: if merit.is_nan() {
                f64::NAN
            } else {
                max_residual
            },
        }
    }

    /// Computes `Δx = −Jᵀ (J Jᵀ + μ D)⁻¹ c` at the stored chords into `self.step`, `D` the
    /// diagonal of `J Jᵀ` and `μ = damping` (0: the Gauss–Newton step); `false` if the system
    /// is singular (a zero-length chord, or a straight chain with no slack to take).
    fn gauss_newton_step(&mut self, damping: f64) -> bool {
        let count = self.chords.len();
        if count < 2 {
            // One chord between two fixed nodes: nothing can move.
            return false;
        }
        if damping != 0.0 {
            for (k, state) in self.chords.iter_mut().enumerate() {
                let free_ends = if k == 0 || k == count - 1 { 1.0 } else { 2.0 };
                state.diagonal = 4.0 * free_ends * state.chord.norm_squared() * (1.0 + damping);
            }
        }
        if !solve_twisted(&mut self.chords) {
            return false;
        }
        // Node j ends chord j−1 and starts chord j: ∂c_{j−1}/∂x_j = 2e_{j−1}, ∂c_j/∂x_j = −2e_j.
        let (mut largest, mut finite) = (0.0_f64, true);
        for (step, pair) in self.step[1..count].iter_mut().zip(self.chords.windows(2)) {
            *step = 2.0 * (pair[1].chord * pair[1].solution - pair[0].chord * pair[0].solution);
            finite &= step.iter().all(|v| v.is_finite());
            largest = largest.max(step.norm_squared());
        }
        self.largest_move_squared = largest;
        finite
    }

    /// Moves the nodes by `scale Δx` and evaluates them there.
    fn apply(&mut self, nodes: &mut [Point3<f64>], scale: f64, pitch: f64) -> Residuals {
        for (node, step) in nodes.iter_mut().zip(&self.step) {
            *node += scale * step;
        }
        self.evaluate(nodes, pitch)
    }

    /// Applies the step `s Δx` that lowers `Σ c_k²` along `Δx` — the full step if it does, else
    /// the quartic's minimizer; returns the new residuals, or `None` (nodes unchanged) if
    /// neither lowers `merit`.
    ///
    /// The constraints are quadratic, so along the step they are exactly
    /// `c_k(s) = c_k + s B_k + s² C_k` with `B_k = 2 e_k·Δe_k`, `C_k = |Δe_k|²` (for the
    /// undamped step `B_k = −c_k`), and the merit is a quartic in `s`. On ordinary bends the
    /// full (minimum-norm) step lowers it, which for a step shorter than a tenth of the pitch
    /// one evaluation of the moved nodes shows; a longer step is taken if the quartic says it
    /// lowers the merit. Otherwise — nearly singular `J Jᵀ`, a nearly straight or folded
    /// chain, where the full step overshoots by orders of magnitude — the quartic's minimizer,
    /// found without trial evaluations.
    fn line_search(
        &mut self,
        nodes: &mut [Point3<f64>],
        pitch: f64,
        merit: f64,
    ) -> Option<Residuals> {
        // A short step is simply tried; a long one could only be undone with round-off.
        let short = self.largest_move_squared <= 0.01 * pitch * pitch;
        if short {
            let full = self.apply(nodes, 1.0, pitch);
            if full.merit < merit {
                return Some(full);
            }
            self.apply(nodes, -1.0, pitch);
        }
        let slope = self.merit_slope();
        // f(1) = f(0) + 2 ∫₀¹ g: the full step whenever it helps, so that ordinary
        // projections are plain Gauss–Newton.
        let full_step_merit =
            merit + 2.0 * slope[0] + slope[1] + 2.0 * slope[2] / 3.0 + 0.5 * slope[3];
        let scale = if !short && full_step_merit < merit {
            1.0
        } else {
            quartic_minimizer(&slope)
        };
        let residuals = self.apply(nodes, scale, pitch);
        if residuals.merit < merit {
            return Some(residuals);
        }
        self.apply(nodes, -scale, pitch);
        None
    }

    /// Half the derivative of the merit along the step at the stored chords, as cubic
    /// coefficients: `Σ cB + s Σ(B² + 2cC) + 3s² Σ BC + 2s³ Σ C²`.
    fn merit_slope(&self) -> [f64; 4] {
        let mut slope = [0.0; 4];
        for (state, steps) in self.chords.iter().zip(self.step.windows(2)) {
            let change = steps[1] - steps[0];
            let (c, b, cc) = (
                state.residual,
                2.0 * state.chord.dot(&change),
                change.norm_squared(),
            );
            slope[0] += c * b;
            slope[1] += b * b + 2.0 * c * cc;
            slope[2] += 3.0 * b * cc;
            slope[3] += 2.0 * cc * cc;
        }
        slope
    }
}

/// The minimizer `s > 0` of a quartic merit along a descent direction, given half its
/// derivative `g(s) = g0 + g1 s + g2 s² + g3 s³` with `g0 < 0` and `g3 ≥ 0`: the first root of
/// `g`, bracketed by doubling from `s = 1` and found by bisection-safeguarded Newton. If `g0`
/// is not negative (round-off), 1: the caller's merit test decides.
fn quartic_minimizer(g: &[f64; 4]) -> f64 {
    let value = |s: f64| g[0] + s * (g[1] + s * (g[2] + s * g[3]));
    let derivative = |s: f64| g[1] + s * (2.0 * g[2] + s * 3.0 * g[3]);
    if g[0].is_nan() || g[0] >= 0.0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    while value(hi) < 0.0 && hi < MAX_STEP_SCALE {
        (lo, hi) = (hi, 2.0 * hi);
    }
    let mut s = hi;
    for _ in 0..MAX_LINE_SEARCH_ITERATIONS {
        let current = value(s);
        if current < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let newton = s - current / derivative(s);
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let done = (next - s).abs() <= 1e-9 * next;
        s = next;
        if done {
            break;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nodes at equal arc length on a circle of radius `r`: chords `2r sin(l/2r)`, short of `l`.
    fn arc_nodes(r: f64, l: f64, count: usize) -> Vec<Point3<f64>> {
        (0..=count)
            .map(|k| {
                let phi = k as f64 * l / r;
                Point3::new(r * phi.sin(), r * (1.0 - phi.cos()), 0.0)
            })
            .collect()
    }

    #[test]
    fn projection_makes_every_chord_one_pitch_and_keeps_the_ends() {
        let (r, l) = (0.05, 0.01);
        let mut nodes = arc_nodes(r, l, 20);
        let (first, last) = (nodes[0], nodes[20]);
        let before = max_chord_error(&nodes, l);
        let iterations = project_onto_rigid_chain(&mut nodes, l).unwrap();
        let after = max_chord_error(&nodes, l);
        println!("circle arc: chord error {before:.2e} → {after:.2e} m in {iterations} steps");
        assert!(after < 1e-13 && iterations <= 4);
        assert_eq!((nodes[0], nodes[20]), (first, last));
        // The chain stays in the plane of the arc.
        assert!(nodes.iter().all(|p| p.z == 0.0));
    }

    #[test]
    fn a_nearly_straight_chain_takes_its_slack_by_bowing() {
        let l = 0.01;
        // 30 chords on a line, 1e-6 m of slack, a 1e-9 m wiggle to break the symmetry.
        let mut nodes: Vec<_> = (0..=30)
            .map(|k| {
                let x = k as f64 * (0.3 - 1e-6) / 30.0;
                Point3::new(
                    x,
                    1e-9 * (std::f64::consts::PI * k as f64 / 30.0).sin(),
                    0.0,
                )
            })
            .collect();
        let iterations = project_onto_rigid_chain(&mut nodes, l).unwrap();
        let sag = nodes.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
        // A shallow arch of height h over d is longer by 8h²/(3d): h ≈ √(3 d ε / 8).
        let expected = (3.0 * 0.3 * 1e-6 / 8.0_f64).sqrt();
        println!(
            "nearly straight: {iterations} steps, sag {sag:.3e} m (shallow arc {expected:.3e} m)"
        );
        assert!(max_chord_error(&nodes, l) < 1e-13);
        assert!((sag / expected - 1.0).abs() < 0.1, "{sag}");
    }

    #[test]
    fn a_straight_chain_without_slack_or_a_single_chord_cannot_move() {
        let mut straight: Vec<_> = (0..=4)
            .map(|k| Point3::new(0.0, 0.0, 0.009 * k as f64))
            .collect();
        assert!(project_onto_rigid_chain(&mut straight, 0.01).is_err());
        let mut single = vec![Point3::origin(), Point3::new(0.0, 0.0, 0.01)];
        assert_eq!(project_onto_rigid_chain(&mut single, 0.01), Ok(0));
    }

    /// The twisted elimination against a dense LU solve, for every size from 1 to 9 (odd and
    /// even middles, the single-row and two-row edge cases).
    #[test]
    fn twisted_elimination_matches_a_dense_solve() {
        for n in 1..=9 {
            let rows: Vec<ChordState> = (0..n)
                .map(|k| {
                    let x = k as f64;
                    ChordState {
                        diagonal: 4.0 + (1.3 * x).sin(),
                        off: if k + 1 < n {
                            -1.0 - 0.3 * (0.7 * x).cos()
                        } else {
                            0.0
                        },
                        residual: (2.1 * x).cos() + 0.5,
                        ..ChordState::default()
                    }
                })
                .collect();
            let mut dense = nalgebra::DMatrix::zeros(n, n);
            for k in 0..n {
                dense[(k, k)] = rows[k].diagonal;
                if k + 1 < n {
                    dense[(k, k + 1)] = rows[k].off;
                    dense[(k + 1, k)] = rows[k].off;
                }
            }
            let rhs = nalgebra::DVector::from_iterator(n, rows.iter().map(|r| r.residual));
            let expected = dense.lu().solve(&rhs).unwrap();
            let mut solved = rows.clone();
            assert!(solve_twisted(&mut solved));
            for k in 0..n {
                assert!(
                    (solved[k].solution - expected[k]).abs() < 1e-14,
                    "n = {n}, row {k}"
                );
            }
        }
        let mut singular = vec![
            ChordState {
                diagonal: 1.0,
                off: -1.0,
                ..ChordState::default()
            },
            ChordState {
                diagonal: 1.0,
                ..ChordState::default()
            },
        ];
        assert!(!solve_twisted(&mut singular));
    }

    #[test]
    fn bending_energy_sums_squared_joint_angles() {
        // Quarter turn at the start guide, then straight, then straight into the end guide.
        let nodes = [
            Point3::origin(),
            Point3::new(0.01, 0.0, 0.0),
            Point3::new(0.02, 0.0, 0.0),
        ];
        let energy = bending_energy(&nodes, &Vector3::z(), &Vector3::x());
        let quarter = std::f64::consts::FRAC_PI_2;
        assert!((energy - quarter * quarter).abs() < 1e-15);
    }
}
