//! Reference solver for the planar heavy elastica (continuous, inextensible, unshearable rod).
//!
//! This module is an *independent* reference: it is written from the continuum equations and
//! uses only `std` and `nalgebra`, nothing from the `cable_dict` crate.
//!
//! # Model and sign conventions
//!
//! The rod lies in the x–z plane, gravity acts along −z. Arc length `s ∈ [0, L]`, position
//! `r(s) = (x(s), z(s))`, tangent angle `θ(s)` measured from +x towards +z:
//!
//! ```text
//! x' = cos θ,   z' = sin θ                      (' = d/ds, unit tangent t = (cos θ, sin θ))
//! ```
//!
//! *Angles and moments* are positive in the sense that turns +x towards +z: counter-clockwise
//! in a drawing with x to the right and z up (the viewer then looks along +y); as a vector,
//! a positive moment `C` is `−C ŷ`. The planar cross product used everywhere is
//! `a × b = a_x b_z − a_z b_x`, positive in the same sense (it is `−(a × b)·ŷ` in 3-D).
//!
//! *Internal force and moment.* `n(s) = (n_x, n_z)` and `M(s)` are the force and moment that
//! the part of the rod beyond the cut, `(s, L]`, exerts on the part before it, `[0, s)`.
//! Tension therefore means `n · t > 0`. Constitutive law (Euler–Bernoulli):
//!
//! ```text
//! M = EI θ'
//! ```
//!
//! (a rod bent with `θ' > 0` pushes back: the far part twists the near part in the +θ sense).
//!
//! *Balance* of the piece `[s, s + ds]` under the weight `−w ẑ ds`:
//!
//! ```text
//! n' = (0, w)          ⇒  n_x = const,  n_z(s) = n_z(0) + w s
//! M' + t × n = 0       ⇒  EI θ'' = M' = n_x sin θ − n_z cos θ
//! ```
//!
//! *Clamp reactions.* The clamp at `s = 0` plays the role of "the part before", so the force
//! and moment it exerts on the rod are `F₀ = −n(0)`, `C₀ = −M(0)`. The clamp at `s = L` plays
//! the role of "the part beyond": `F_L = n(L)`, `C_L = M(L)`. Global equilibrium then reads
//!
//! ```text
//! F₀ + F_L − w L ẑ = 0
//! C₀ + C_L + r(L) × F_L − w ∫₀ᴸ x ds = 0        (moments about the origin, r(0) = 0)
//! ```
//!
//! which the tests check with an independent quadrature of the computed shape.
//!
//! *End angles.* Both `θ0` and `θ1` are angles of the tangent in the direction of
//! **increasing s**. A cable that leaves the start clamp downwards has `θ0 = −π/2`; a cable
//! that arrives at the end clamp going upwards (the end clamp's cable exit points down) has
//! `θ1 = +π/2`. The angle is *not* reduced modulo 2π: `θ1` and `θ1 + 2π` are different
//! problems (one more full turn of the rod).
//!
//! # Numerical method
//!
//! Everything is made dimensionless with `L` and `EI`: `s̄ = s/L`, `x̄ = x/L`, `M̄ = M L/EI`,
//! `n̄ = n L²/EI`, `w̄ = w L³/EI` (the single load parameter of the heavy elastica).
//!
//! * **ODE**: state `(x̄, z̄, θ, M̄)` with parameters `(n̄_x, n̄_z(0), w̄)`, integrated with the
//!   classical fixed-step 4th-order Runge–Kutta method (default 8192 steps over the rod).
//! * **Multiple shooting**: the rod is cut into `K` segments (default 32). The unknowns are the
//!   start forces and moment `(n̄_x, n̄_z(0), M̄(0))` (clamped–clamped) or `M̄(0)` alone
//!   (cantilever, where `n(s) = w (s − L) ẑ` is known), plus the state at the `K − 1` interior
//!   cuts. The equations are continuity at the cuts and the end conditions
//!   (`x, z, θ` at `s = L` for a clamp, `M(L) = 0` for a free end). With `K = 1` this is plain
//!   single shooting; the cuts keep the Newton matrix well conditioned when the rod is under
//!   large tension (the linearised equation grows like `exp(s √(T/EI))`).
//! * **Newton** with the exact Jacobian of the discrete RK4 map (variational equations
//!   integrated with the same RK4 steps), dense LU.
//! * **Homotopy / continuation**: pseudo-arclength continuation (which follows the solution
//!   path around folds) from a configuration that solves a related problem exactly to the
//!   requested one. Continuation runs on a coarse RK4 grid, the final Newton iterations on the
//!   fine one.
//!   - Cantilever: the weight is ramped from `w = 0` (straight rod).
//!   - Clamped ends, tried in the order of [`Start::ALL`] until a *stable* equilibrium is
//!     found: (1) the inextensible catenary through both end points with the elastica's clamp
//!     boundary layers `tan((θ − φ)/4) = tan((θ_c − φ)/4)·exp(−d/√(EI/T))` superposed, closed
//!     by a Newton homotopy `F(u) − (1 − λ) F(u_guess) = 0`; (2) the same without boundary
//!     layers; (3) the cantilever hanging from the start clamp, its free end moved linearly to
//!     the end pose; (4) an unloaded circular arc from `θ0` to `θ1`, weight and end pose
//!     ramped together. Different starts may reach different equilibria (e.g. for case 1 the
//!     cantilever start ends on an unstable upward arch); [`solve_clamped_from_start`] exposes
//!     a single start and returns whatever it reaches.
//! * **Stability**: [`Elastica::morse_index`] counts the negative eigenvalues of the second
//!   variation of the potential energy `∫ (EI θ'²/2 + w z) ds` under the end constraints,
//!   `Q[η] = ∫ EI η'² + (n_x cos θ + n_z sin θ) η² ds` with `η(0) = η(L) = 0`,
//!   `∫ η cos θ = ∫ η sin θ = 0` (clamped) or `η(L)` free (cantilever), from the Sylvester
//!   inertia of its finite-difference matrix (a discrete Sturm / conjugate-point count) and a
//!   2×2 Schur complement for the constraints. [`solve_clamped`] returns `Err` rather than an
//!   unstable equilibrium; [`solve_cantilever`] returns the equilibrium reached by the load
//!   ramp, stable or not (a standing column above Greenhill's load stays straight).
//! * **Dense output**: the RK4 nodes are stored; between nodes the state is interpolated with
//!   cubic Hermite polynomials that use the exact ODE derivatives (`x' = cos θ`, `θ' = M/EI`, …),
//!   which is 4th-order accurate like the nodes themselves.
//!
//! # Accuracy
//!
//! The discretisation error is `O(h⁴)`. Measured by `step_halving_convergence` in
//! `tests/elastica_reference.rs` for the three reference cases (heavy sag, U-loop, S-bend with
//! `L = 0.4–0.5 m`, `EI = 5.1e-4 N·m²`, `w = 0.26·9.81 N/m`), as the largest position
//! difference along the rod against a 32768-step solution:
//!
//! | steps | 256 | 512 | 1024 | 2048 | 4096 | 8192 (default) |
//! |-------|-----|-----|------|------|------|----------------|
//! | case 1 | 5.4e-9 m | 3.4e-10 | 2.1e-11 | 1.3e-12 | 8e-14 | 7e-15 |
//! | case 2 | 3.5e-10 m | 2.2e-11 | 1.4e-12 | 8e-14 | 6e-15 | 2e-15 |
//! | case 3 | 2.5e-9 m | 1.6e-10 | 1.0e-11 | 5.9e-13 | 3.8e-14 | 2e-15 |
//!
//! i.e. an observed order of 4.00 and, with the default 8192 steps, round-off level
//! (`< 1e-14 m`, the 8192- and 16384-step solutions differ by `< 1e-14 m`). The Newton residual
//! is `~1e-15` (dimensionless). The reference is therefore accurate to far better than
//! `1e-6 m` — more than 10⁶× finer than the 1 mm the discrete solver is held to.
//!
//! *Stiff (tension-dominated) limit.* The boundary-layer width is `ℓ = √(EI/T)`. The defaults
//! handle `ℓ` down to about `L/150` (case 1 with `EI = 5.1e-6`). For thinner layers, use more
//! segments (segment length ≲ 4ℓ) and finer continuation steps; e.g. `EI = 5.1e-7`
//! (`ℓ ≈ 1 mm`) works with `segments: 128, continuation_steps_per_segment: 64,
//! steps: 32768` (≈10 s: the dense LU grows as `segments³`).

use nalgebra::{DMatrix, DVector};

/// Dimensionless state `(x̄, z̄, θ, M̄)`.
type State = [f64; 4];

/// Number of variational columns carried with the state: derivatives with respect to the
/// segment's initial state (columns 0–3, in state order), to `n̄_x` (4), to `n̄_z(0)` (5) and to
/// `w̄` (6).
const NCOL: usize = 7;
/// Length of the augmented state (state + `NCOL` variations of 4 components).
const AUG: usize = 4 + 4 * NCOL;
type Var = [[f64; 4]; NCOL];

/// Tolerance of the continuation correctors (dimensionless residual, ∞-norm).
const TRACK_TOL: f64 = 1e-9;
/// Acceptance tolerance of the final Newton solve on the fine grid.
const FINAL_TOL: f64 = 1e-10;

/// Numerical options of the reference solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Number of RK4 steps over the whole rod for the final solution (rounded up to a multiple
    /// of `segments`).
    pub steps: usize,
    /// Number of multiple-shooting segments (1 = single shooting).
    pub segments: usize,
    /// RK4 steps per segment during continuation (capped at the final steps per segment).
    pub continuation_steps_per_segment: usize,
    /// Maximum number of pseudo-arclength steps per homotopy.
    pub max_continuation_steps: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            steps: 8192,
            segments: 32,
            continuation_steps_per_segment: 32,
            max_continuation_steps: 3000,
        }
    }
}

impl Options {
    fn steps_per_segment(&self) -> usize {
        self.steps.div_ceil(self.segments).max(1)
    }

    fn coarse_steps_per_segment(&self) -> usize {
        self.continuation_steps_per_segment
            .clamp(1, self.steps_per_segment())
    }
}

#[derive(Clone, Copy, Debug)]
struct Loads {
    nx: f64,
    nz0: f64,
    wbar: f64,
}

impl Loads {
    fn nz(&self, s: f64) -> f64 {
        self.nz0 + self.wbar * s
    }
}

fn rhs(s: f64, y: &State, l: &Loads) -> State {
    let (sn, cs) = y[2].sin_cos();
    [cs, sn, y[3], l.nx * sn - l.nz(s) * cs]
}

fn rhs_aug(s: f64, y: &[f64; AUG], l: &Loads) -> [f64; AUG] {
    let (sn, cs) = y[2].sin_cos();
    let nz = l.nz(s);
    let mut d = [0.0; AUG];
    d[0] = cs;
    d[1] = sn;
    d[2] = y[3];
    d[3] = l.nx * sn - nz * cs;
    // ∂M̄'/∂θ and the explicit dependence of M̄' on (n̄_x, n̄_z(0), w̄).
    let a = l.nx * cs + nz * sn;
    let forcing = [0.0, 0.0, 0.0, 0.0, sn, -cs, -s * cs];
    for (j, f) in forcing.iter().enumerate() {
        let o = 4 + 4 * j;
        let dth = y[o + 2];
        d[o] = -sn * dth;
        d[o + 1] = cs * dth;
        d[o + 2] = y[o + 3];
        d[o + 3] = a * dth + f;
    }
    d
}

fn axpy<const D: usize>(y: &[f64; D], a: f64, k: &[f64; D]) -> [f64; D] {
    let mut out = *y;
    for (o, ki) in out.iter_mut().zip(k) {
        *o += a * ki;
    }
    out
}

fn rk4<const D: usize>(
    f: impl Fn(f64, &[f64; D]) -> [f64; D],
    s: f64,
    h: f64,
    y: &[f64; D],
) -> [f64; D] {
    let k1 = f(s, y);
    let k2 = f(s + 0.5 * h, &axpy(y, 0.5 * h, &k1));
    let k3 = f(s + 0.5 * h, &axpy(y, 0.5 * h, &k2));
    let k4 = f(s + h, &axpy(y, h, &k3));
    let mut out = *y;
    for i in 0..D {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}

/// Integrates one segment `[s0, s1]` with `steps` RK4 steps, together with the variations
/// (initial values `var0`). `visit(i, y)` is called for the initial node (`i = 0`) and after
/// every step.
fn integrate_aug(
    start: &State,
    var0: &Var,
    span: (f64, f64),
    steps: usize,
    loads: &Loads,
    mut visit: impl FnMut(usize, &[f64; AUG]),
) -> [f64; AUG] {
    let mut y = [0.0; AUG];
    y[..4].copy_from_slice(start);
    for (j, col) in var0.iter().enumerate() {
        y[4 + 4 * j..8 + 4 * j].copy_from_slice(col);
    }
    let h = (span.1 - span.0) / steps as f64;
    visit(0, &y);
    for i in 0..steps {
        let s = span.0 + i as f64 * h;
        y = rk4(|s, y| rhs_aug(s, y, loads), s, h, &y);
        visit(i + 1, &y);
    }
    y
}

/// Plain RK4 over one segment; `visit(i, y)` sees the initial node and every step.
fn integrate_plain(
    start: &State,
    span: (f64, f64),
    steps: usize,
    loads: &Loads,
    mut visit: impl FnMut(usize, &State),
) -> State {
    let h = (span.1 - span.0) / steps as f64;
    let mut y = *start;
    visit(0, &y);
    for i in 0..steps {
        let s = span.0 + i as f64 * h;
        y = rk4(|s, y| rhs(s, y, loads), s, h, &y);
        visit(i + 1, &y);
    }
    y
}

fn split_aug(y: &[f64; AUG]) -> (State, Var) {
    let mut st = [0.0; 4];
    st.copy_from_slice(&y[..4]);
    let mut var = [[0.0; 4]; NCOL];
    for (j, col) in var.iter_mut().enumerate() {
        col.copy_from_slice(&y[4 + 4 * j..8 + 4 * j]);
    }
    (st, var)
}

fn identity_var() -> Var {
    let mut v = [[0.0; 4]; NCOL];
    for (j, col) in v.iter_mut().enumerate().take(4) {
        col[j] = 1.0;
    }
    v
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Clamped at both ends; unknowns `(n̄_x, n̄_z(0), M̄(0), interior states…)`.
    Clamped,
    /// Clamped at `s = 0`, free at `s = L`; unknowns `(M̄(0), interior states…)`.
    Free,
}

#[derive(Clone, Copy, Debug)]
struct Problem {
    kind: Kind,
    theta0: f64,
    segments: usize,
}

impl Problem {
    fn offset(&self) -> usize {
        match self.kind {
            Kind::Clamped => 3,
            Kind::Free => 1,
        }
    }

    fn n_unknowns(&self) -> usize {
        self.offset() + 4 * (self.segments - 1)
    }

    fn loads(&self, u: &DVector<f64>, wbar: f64) -> Loads {
        match self.kind {
            Kind::Clamped => Loads {
                nx: u[0],
                nz0: u[1],
                wbar,
            },
            Kind::Free => Loads {
                nx: 0.0,
                nz0: -wbar,
                wbar,
            },
        }
    }

    fn start(&self, u: &DVector<f64>, k: usize) -> State {
        if k == 0 {
            [0.0, 0.0, self.theta0, u[self.offset() - 1]]
        } else {
            let o = self.offset() + 4 * (k - 1);
            [u[o], u[o + 1], u[o + 2], u[o + 3]]
        }
    }

    fn span(&self, k: usize) -> (f64, f64) {
        let kk = self.segments as f64;
        (k as f64 / kk, (k + 1) as f64 / kk)
    }

    /// Builds the unknown vector from a function giving the state at `s̄`.
    fn unknowns_from(&self, head: &[f64], state_at: impl Fn(f64) -> State) -> DVector<f64> {
        let mut u = DVector::zeros(self.n_unknowns());
        for (i, h) in head.iter().enumerate() {
            u[i] = *h;
        }
        for k in 1..self.segments {
            let st = state_at(self.span(k).0);
            let o = self.offset() + 4 * (k - 1);
            for i in 0..4 {
                u[o + i] = st[i];
            }
        }
        u
    }

    /// State at `s̄ = 1` obtained by integrating the last segment (plain RK4).
    fn end_state(&self, u: &DVector<f64>, wbar: f64, steps_per_segment: usize) -> State {
        let k = self.segments - 1;
        integrate_plain(
            &self.start(u, k),
            self.span(k),
            steps_per_segment,
            &self.loads(u, wbar),
            |_, _| {},
        )
    }
}

/// Homotopy `λ ∈ [0, 1]`: weight `w̄(λ) = w̄_a + λ (w̄_b − w̄_a)`, (clamped) end pose
/// `E(λ) = E_a + λ (E_b − E_a)`, and optionally a Newton homotopy `F(u, λ) − (1 − λ) d = 0`
/// that closes the residual `d` of an inconsistent initial guess.
struct Homotopy {
    prob: Problem,
    wbar_a: f64,
    wbar_b: f64,
    end_a: [f64; 3],
    end_b: [f64; 3],
    defect: Option<DVector<f64>>,
}

impl Homotopy {
    fn wbar(&self, lam: f64) -> f64 {
        self.wbar_a + lam * (self.wbar_b - self.wbar_a)
    }

    fn target(&self, lam: f64) -> [f64; 3] {
        let mut e = [0.0; 3];
        for (i, ei) in e.iter_mut().enumerate() {
            *ei = self.end_a[i] + lam * (self.end_b[i] - self.end_a[i]);
        }
        e
    }

    fn is_trivial(&self) -> bool {
        self.wbar_a == self.wbar_b && self.end_a == self.end_b && self.defect.is_none()
    }

    /// Residual `F(u, λ)` and Jacobian `[∂F/∂u | ∂F/∂λ]` (n × (n + 1)).
    fn eval(&self, u: &DVector<f64>, lam: f64, m: usize) -> (DVector<f64>, DMatrix<f64>) {
        let p = &self.prob;
        let n = p.n_unknowns();
        let off = p.offset();
        let kk = p.segments;
        let wbar = self.wbar(lam);
        let dw = self.wbar_b - self.wbar_a;
        let loads = p.loads(u, wbar);
        let target = self.target(lam);
        let mut f = DVector::zeros(n);
        let mut jac = DMatrix::zeros(n, n + 1);
        for k in 0..kk {
            let start = p.start(u, k);
            let y = integrate_aug(&start, &identity_var(), p.span(k), m, &loads, |_, _| {});
            let (end, var) = split_aug(&y);
            let last = k + 1 == kk;
            let comps: &[usize] = match (last, p.kind) {
                (false, _) => &[0, 1, 2, 3],
                (true, Kind::Clamped) => &[0, 1, 2],
                (true, Kind::Free) => &[3],
            };
            for (r, &ci) in comps.iter().enumerate() {
                let row = 4 * k + r;
                if !last {
                    f[row] = end[ci] - u[off + 4 * k + ci];
                    jac[(row, off + 4 * k + ci)] = -1.0;
                } else if p.kind == Kind::Clamped {
                    f[row] = end[ci] - target[ci];
                    jac[(row, n)] -= self.end_b[ci] - self.end_a[ci];
                } else {
                    f[row] = end[ci];
                }
                if k == 0 {
                    jac[(row, off - 1)] += var[3][ci];
                } else {
                    for (j, col) in var.iter().enumerate().take(4) {
                        jac[(row, off + 4 * (k - 1) + j)] += col[ci];
                    }
                }
                match p.kind {
                    Kind::Clamped => {
                        jac[(row, 0)] += var[4][ci];
                        jac[(row, 1)] += var[5][ci];
                        jac[(row, n)] += var[6][ci] * dw;
                    }
                    Kind::Free => {
                        // n̄_z(0) = −w̄ is tied to the load.
                        jac[(row, n)] += (var[6][ci] - var[5][ci]) * dw;
                    }
                }
            }
        }
        if let Some(d) = &self.defect {
            f.axpy(-(1.0 - lam), d, 1.0);
            let mut col = jac.column_mut(n);
            col += d;
        }
        (f, jac)
    }
}

/// Newton at fixed `λ`. Returns the best iterate if its residual is below `tol`.
fn newton_fixed(
    h: &Homotopy,
    u: DVector<f64>,
    lam: f64,
    m: usize,
    tol: f64,
    max_iter: usize,
) -> Result<(DVector<f64>, f64), String> {
    let n = u.len();
    let mut u = u;
    let mut best: Option<(DVector<f64>, f64)> = None;
    for _ in 0..=max_iter {
        let (f, jac) = h.eval(&u, lam, m);
        let res = f.amax();
        if !res.is_finite() {
            break;
        }
        if best.as_ref().is_none_or(|(_, r)| res < *r) {
            best = Some((u.clone(), res));
        } else if res <= tol {
            // Stagnated at round-off.
            break;
        }
        if res < 1e-14 {
            break;
        }
        let ju = jac.columns(0, n).into_owned();
        let Some(dx) = ju.lu().solve(&(-f)) else {
            break;
        };
        u += dx;
    }
    match best {
        Some((u, res)) if res <= tol => Ok((u, res)),
        Some((_, res)) => Err(format!(
            "Newton did not converge at λ = {lam} (residual {res:.3e})"
        )),
        None => Err(format!("Newton diverged at λ = {lam}")),
    }
}

fn bordered(jac: &DMatrix<f64>, t: &DVector<f64>) -> DMatrix<f64> {
    let n = jac.nrows();
    let mut a = DMatrix::zeros(n + 1, n + 1);
    a.rows_mut(0, n).copy_from(jac);
    a.row_mut(n).copy_from(&t.transpose());
    a
}

/// Unit tangent of the solution path at `v = (u, λ)`, oriented along `t_ref`.
fn tangent(
    h: &Homotopy,
    v: &DVector<f64>,
    m: usize,
    t_ref: &DVector<f64>,
) -> Result<DVector<f64>, String> {
    let n = v.len() - 1;
    let u = v.rows(0, n).into_owned();
    let (_, jac) = h.eval(&u, v[n], m);
    let mut rhs = DVector::zeros(n + 1);
    rhs[n] = 1.0;
    let t = bordered(&jac, t_ref)
        .lu()
        .solve(&rhs)
        .ok_or_else(|| "singular path tangent".to_string())?;
    let norm = t.norm();
    if !norm.is_finite() || norm == 0.0 {
        return Err("degenerate path tangent".into());
    }
    let t = t / norm;
    Ok(if t.dot(t_ref) < 0.0 { -t } else { t })
}

/// Pseudo-arclength corrector (Keller): solves `F(v) = 0`, `t·(v − v_p) = 0`.
fn correct(
    h: &Homotopy,
    vp: &DVector<f64>,
    t: &DVector<f64>,
    m: usize,
    ds: f64,
) -> Option<(DVector<f64>, usize)> {
    let n = vp.len() - 1;
    let mut w = vp.clone();
    for it in 0..10 {
        let u = w.rows(0, n).into_owned();
        let (f, jac) = h.eval(&u, w[n], m);
        let mut g = DVector::zeros(n + 1);
        g.rows_mut(0, n).copy_from(&f);
        g[n] = t.dot(&(&w - vp));
        let dx = bordered(&jac, t).lu().solve(&(-g))?;
        w += &dx;
        let step = dx.amax();
        if !step.is_finite() || (&w - vp).norm() > 2.0 * ds.max(1e-3) {
            return None;
        }
        if step <= 1e-10 * (1.0 + w.amax()) && f.amax() <= TRACK_TOL {
            return Some((w, it + 1));
        }
    }
    None
}

/// Follows the homotopy from the solution `u0` at `λ = 0` to `λ = 1` (coarse grid `m`).
fn track(
    h: &Homotopy,
    u0: DVector<f64>,
    m: usize,
    max_steps: usize,
) -> Result<DVector<f64>, String> {
    let n = u0.len();
    let (u0, _) = newton_fixed(h, u0, 0.0, m, TRACK_TOL, 20)?;
    if h.is_trivial() {
        return Ok(u0);
    }
    let mut v = DVector::zeros(n + 1);
    v.rows_mut(0, n).copy_from(&u0);
    let mut e_lam = DVector::zeros(n + 1);
    e_lam[n] = 1.0;
    let mut t = tangent(h, &v, m, &e_lam)?;
    let mut ds = 0.02;
    let ds_max = 20.0;
    for _ in 0..max_steps {
        let vp = &v + ds * &t;
        let accepted = correct(h, &vp, &t, m, ds).and_then(|(w, iters)| {
            let tw = tangent(h, &w, m, &t).ok()?;
            (tw.dot(&t) > 0.9).then_some((w, tw, iters))
        });
        match accepted {
            Some((w, _, _)) if w[n] < -0.5 => {
                return Err("continuation path turned back (λ < −0.5)".into());
            }
            Some((w, tw, iters)) => {
                if w[n] >= 1.0 {
                    let a = (1.0 - v[n]) / (w[n] - v[n]);
                    let guess = (&v + a * (&w - &v)).rows(0, n).into_owned();
                    let (u, _) = newton_fixed(h, guess, 1.0, m, TRACK_TOL, 30)?;
                    return Ok(u);
                }
                v = w;
                t = tw;
                if iters <= 3 {
                    ds = (ds * 1.6).min(ds_max);
                }
            }
            None => {
                ds *= 0.5;
                if ds < 1e-10 || v[n] < -0.5 {
                    return Err(format!("continuation stalled at λ = {:.6}", v[n]));
                }
            }
        }
    }
    Err(format!(
        "continuation did not reach λ = 1 in {max_steps} steps (λ = {:.6})",
        v[n]
    ))
}

/// Continuation on the coarse grid, then Newton on the fine grid.
fn continuation(
    h: &Homotopy,
    u0: DVector<f64>,
    opts: &Options,
) -> Result<(DVector<f64>, f64), String> {
    let coarse = opts.coarse_steps_per_segment();
    let u = track(h, u0, coarse, opts.max_continuation_steps)?;
    newton_fixed(h, u, 1.0, opts.steps_per_segment(), FINAL_TOL, 20)
}

/// Solved planar elastica (clamped–clamped or cantilever) with dense output.
#[derive(Clone, Debug)]
pub struct Elastica {
    length: f64,
    ei: f64,
    weight: f64,
    theta0: f64,
    kind: Kind,
    segments: usize,
    /// Dimensionless internal force at `s = 0` and load parameter.
    loads: Loads,
    /// Dimensionless states `(x̄, z̄, θ, M̄)` at `s̄ = i / steps`, `i = 0..=steps`.
    nodes: Vec<State>,
    /// Converged unknown vector (dimensionless), kept for continuation.
    unknowns: DVector<f64>,
    residual: f64,
    morse: usize,
}

/// A clamped–clamped solution (same type as the cantilever).
pub type ClampedElastica = Elastica;

impl Elastica {
    /// Rod length `L` (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Bending stiffness `EI` (N·m²).
    pub fn ei(&self) -> f64 {
        self.ei
    }

    /// Weight per length `w` (N/m), acting along −z.
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// Number of RK4 steps of the stored solution.
    pub fn steps(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Dimensionless Newton residual (∞-norm; lengths in units of `L`, angles in rad, moments in
    /// `EI/L`) of the final solve.
    pub fn residual(&self) -> f64 {
        self.residual
    }

    fn force_scale(&self) -> f64 {
        self.ei / (self.length * self.length)
    }

    fn moment_scale(&self) -> f64 {
        self.ei / self.length
    }

    fn derivative(&self, sbar: f64, y: &State) -> State {
        rhs(sbar, y, &self.loads)
    }

    /// Cubic Hermite interpolation of state component `c` at dimensionless `sbar`.
    fn interp(&self, sbar: f64, c: usize) -> f64 {
        let n = self.steps();
        let sbar = sbar.clamp(0.0, 1.0);
        let pos = sbar * n as f64;
        let i = (pos.floor() as usize).min(n - 1);
        let t = pos - i as f64;
        let h = 1.0 / n as f64;
        let (s0, s1) = (i as f64 * h, (i + 1) as f64 * h);
        let (y0, y1) = (&self.nodes[i], &self.nodes[i + 1]);
        let (d0, d1) = (self.derivative(s0, y0)[c], self.derivative(s1, y1)[c]);
        let t2 = t * t;
        let t3 = t2 * t;
        (2.0 * t3 - 3.0 * t2 + 1.0) * y0[c]
            + (t3 - 2.0 * t2 + t) * h * d0
            + (-2.0 * t3 + 3.0 * t2) * y1[c]
            + (t3 - t2) * h * d1
    }

    /// Position `(x, z)` (m) at arc length `s_m` (clamped to `[0, L]`).
    pub fn position(&self, s_m: f64) -> [f64; 2] {
        let sb = s_m / self.length;
        [
            self.length * self.interp(sb, 0),
            self.length * self.interp(sb, 1),
        ]
    }

    /// Tangent angle `θ(s)` (rad) from +x towards +z, direction of increasing `s`.
    pub fn angle(&self, s_m: f64) -> f64 {
        self.interp(s_m / self.length, 2)
    }

    /// Bending moment `M(s) = EI θ'(s)` (N·m): moment exerted by the part beyond `s` on the
    /// part before it, positive in the +x → +z sense.
    pub fn moment(&self, s_m: f64) -> f64 {
        self.moment_scale() * self.interp(s_m / self.length, 3)
    }

    /// Curvature `θ'(s)` (1/m).
    pub fn curvature(&self, s_m: f64) -> f64 {
        self.moment(s_m) / self.ei
    }

    /// Internal force `n(s)` (N): force exerted by the part beyond `s` on the part before it.
    pub fn internal_force(&self, s_m: f64) -> [f64; 2] {
        let sb = (s_m / self.length).clamp(0.0, 1.0);
        [
            self.force_scale() * self.loads.nx,
            self.force_scale() * self.loads.nz(sb),
        ]
    }

    /// Force (N) the clamp at `s = 0` exerts on the rod: `−n(0)`.
    pub fn force_at_start(&self) -> [f64; 2] {
        let n = self.internal_force(0.0);
        [-n[0], -n[1]]
    }

    /// Moment (N·m, +x → +z sense) the clamp at `s = 0` exerts on the rod: `−M(0)`.
    pub fn moment_at_start(&self) -> f64 {
        -self.moment_scale() * self.nodes[0][3]
    }

    /// Force (N) the clamp at `s = L` exerts on the rod: `n(L)` (zero for a cantilever).
    pub fn force_at_end(&self) -> [f64; 2] {
        self.internal_force(self.length)
    }

    /// Moment (N·m, +x → +z sense) the clamp at `s = L` exerts on the rod: `M(L)`.
    pub fn moment_at_end(&self) -> f64 {
        self.moment_scale() * self.nodes[self.steps()][3]
    }

    /// Computed end pose `(x(L), z(L), θ(L))` (m, m, rad).
    pub fn end_pose(&self) -> [f64; 3] {
        let e = &self.nodes[self.steps()];
        [self.length * e[0], self.length * e[1], e[2]]
    }

    /// Minimum over `[0, L]` of the Hermite interpolant of component `c` (sign `sign` = +1 for
    /// the minimum, −1 for the maximum); returns `(s̄, value)`.
    fn extreme(&self, c: usize, sign: f64) -> (f64, f64) {
        let n = self.steps();
        let h = 1.0 / n as f64;
        let (imin, _) = self
            .nodes
            .iter()
            .enumerate()
            .map(|(i, y)| (i, sign * y[c]))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        let g = |s: f64| sign * self.interp(s, c);
        let (mut a, mut b) = ((imin.max(1) - 1) as f64 * h, ((imin + 1).min(n)) as f64 * h);
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let mut c1 = b - r * (b - a);
        let mut c2 = a + r * (b - a);
        let (mut g1, mut g2) = (g(c1), g(c2));
        for _ in 0..80 {
            if g1 < g2 {
                b = c2;
                c2 = c1;
                g2 = g1;
                c1 = b - r * (b - a);
                g1 = g(c1);
            } else {
                a = c1;
                c1 = c2;
                g1 = g2;
                c2 = a + r * (b - a);
                g2 = g(c2);
            }
        }
        let mut best = (imin as f64 * h, sign * self.nodes[imin][c]);
        for s in [0.5 * (a + b), 0.0, 1.0] {
            let v = g(s);
            if v < sign * best.1 {
                best = (s, sign * v);
            }
        }
        best
    }

    /// Lowest point of the rod: `(s, [x, z])` in metres.
    pub fn lowest_point(&self) -> (f64, [f64; 2]) {
        let (sb, _) = self.extreme(1, 1.0);
        let s = sb * self.length;
        (s, self.position(s))
    }

    /// Lowest `z` (m) reached by the rod, i.e. `min_s z(s)` — negative when the rod hangs below
    /// the start clamp. (Named after the sag it measures for clamps at `z = 0`.)
    pub fn max_sag(&self) -> f64 {
        self.lowest_point().1[1]
    }

    /// `(min θ, max θ)` over the rod (rad).
    pub fn angle_extremes(&self) -> (f64, f64) {
        (self.extreme(2, 1.0).1, self.extreme(2, -1.0).1)
    }

    /// Morse index of the equilibrium: the number of independent admissible perturbations that
    /// lower the potential energy to second order. It is the number of negative eigenvalues of
    /// the second variation
    ///
    /// ```text
    /// Q[η] = ∫₀ᴸ EI η'² + (n_x cos θ + n_z sin θ) η² ds,
    /// ```
    ///
    /// over angle perturbations `η` with `η(0) = 0` and, for clamped ends, `η(L) = 0` and
    /// `∫ η cos θ = ∫ η sin θ = 0` (the end position is kept), `η(L)` free for a cantilever.
    /// Evaluated on the RK4 nodes by the Sylvester inertia of the finite-difference matrix
    /// (tridiagonal LDLᵀ pivots, i.e. a discrete Sturm/Jacobi conjugate-point count) and, for
    /// the two position constraints, the inertia of the 2×2 Schur complement. Robust also when
    /// high tension makes the continuous Jacobi fields grow like `exp(s √(T/EI))`.
    pub fn morse_index(&self) -> usize {
        self.morse
    }

    /// `true` if the equilibrium is a strict local minimum of the potential energy (Morse
    /// index 0), i.e. stable under the end constraints.
    pub fn is_stable(&self) -> bool {
        self.morse == 0
    }

    /// Potential energy `∫₀ᴸ (EI θ'²/2 + w z) ds` (J): bending energy plus the potential of the
    /// weight relative to `z = 0`. Integrated exactly over the cubic Hermite interpolants
    /// (corrected trapezoidal rule, 4th order).
    pub fn potential_energy(&self) -> f64 {
        let n = self.steps();
        let h = 1.0 / n as f64;
        let (mut bend, mut height) = (0.0, 0.0);
        for i in 0..n {
            let (s0, s1) = (i as f64 * h, (i + 1) as f64 * h);
            let (y0, y1) = (&self.nodes[i], &self.nodes[i + 1]);
            let (d0, d1) = (self.derivative(s0, y0), self.derivative(s1, y1));
            // g = M̄²/2, g' = M̄ M̄'.
            let (g0, g1) = (0.5 * y0[3] * y0[3], 0.5 * y1[3] * y1[3]);
            let (dg0, dg1) = (y0[3] * d0[3], y1[3] * d1[3]);
            bend += 0.5 * h * (g0 + g1) + h * h / 12.0 * (dg0 - dg1);
            height += 0.5 * h * (y0[1] + y1[1]) + h * h / 12.0 * (d0[1] - d1[1]);
        }
        self.moment_scale() * bend + self.weight * self.length * self.length * height
    }

    /// `count` points `(x, z)` equally spaced in arc length, including both ends.
    pub fn polyline(&self, count: usize) -> Vec<[f64; 2]> {
        let count = count.max(2);
        (0..count)
            .map(|i| self.position(self.length * i as f64 / (count - 1) as f64))
            .collect()
    }

    /// Continues this clamped–clamped solution to another weight and end pose (same length,
    /// stiffness and start angle) by pseudo-arclength continuation. Useful to follow a motion.
    pub fn continue_to(&self, weight_n_per_m: f64, end: [f64; 3]) -> Result<Elastica, String> {
        self.continue_to_with(weight_n_per_m, end, &Options::default())
    }

    /// [`Elastica::continue_to`] with explicit options (the segment count of `self` is kept).
    pub fn continue_to_with(
        &self,
        weight_n_per_m: f64,
        end: [f64; 3],
        opts: &Options,
    ) -> Result<Elastica, String> {
        if self.kind != Kind::Clamped {
            return Err("continue_to needs a clamped–clamped solution".into());
        }
        check_clamped_input(self.length, self.ei, weight_n_per_m, self.theta0, end)?;
        let opts = Options {
            segments: self.segments,
            ..*opts
        };
        let l = self.length;
        let prob = Problem {
            kind: Kind::Clamped,
            theta0: self.theta0,
            segments: self.segments,
        };
        let u0 = self.unknowns.clone();
        let wbar_a = self.loads.wbar;
        let end_a = prob.end_state(&u0, wbar_a, opts.coarse_steps_per_segment());
        let h = Homotopy {
            prob,
            wbar_a,
            wbar_b: weight_n_per_m * l.powi(3) / self.ei,
            end_a: [end_a[0], end_a[1], end_a[2]],
            end_b: [end[0] / l, end[1] / l, end[2]],
            defect: None,
        };
        let (u, res) = continuation(&h, u0, &opts)?;
        Ok(build(
            self.length,
            self.ei,
            weight_n_per_m,
            &h,
            u,
            res,
            &opts,
        ))
    }
}

/// Morse index (number of negative eigenvalues) of the second variation of the energy on the
/// dimensionless nodes, see [`Elastica::morse_index`].
fn morse_index(kind: Kind, loads: &Loads, nodes: &[State]) -> usize {
    let n = nodes.len() - 1;
    let h = 1.0 / n as f64;
    let q = |i: usize| {
        let th = nodes[i][2];
        loads.nx * th.cos() + loads.nz(i as f64 * h) * th.sin()
    };
    // Unknowns η_1 … η_{n−1} (clamped) or η_1 … η_n (free end, natural condition).
    let last = match kind {
        Kind::Clamped => n - 1,
        Kind::Free => n,
    };
    let off = -1.0 / h;
    let diag = |i: usize| {
        if i == n {
            1.0 / h + 0.5 * h * q(i)
        } else {
            2.0 / h + h * q(i)
        }
    };
    // LDLᵀ of the tridiagonal matrix: the signs of the pivots give its inertia (Sylvester).
    let mut d = vec![0.0; last + 1];
    let mut negatives = 0;
    for i in 1..=last {
        d[i] = diag(i) - if i > 1 { off * off / d[i - 1] } else { 0.0 };
        if d[i] == 0.0 {
            d[i] = f64::MIN_POSITIVE;
        }
        if d[i] < 0.0 {
            negatives += 1;
        }
    }
    if kind == Kind::Free {
        return negatives;
    }
    // Constraints ∫ η cos θ = ∫ η sin θ = 0. With K = [[A, C], [Cᵀ, 0]]:
    // In(K) = In(A) + In(−Cᵀ A⁻¹ C) = In(Zᵀ A Z) + (2, 2, 0), Z a basis of ker Cᵀ.
    let mut s = [[0.0; 2]; 2];
    let mut cols = [vec![0.0; last + 1], vec![0.0; last + 1]];
    for i in 1..=last {
        cols[0][i] = h * nodes[i][2].cos();
        cols[1][i] = h * nodes[i][2].sin();
    }
    let mut sols = cols.clone();
    for x in sols.iter_mut() {
        for i in 2..=last {
            x[i] -= off / d[i - 1] * x[i - 1];
        }
        for i in 1..=last {
            x[i] /= d[i];
        }
        for i in (1..last).rev() {
            x[i] -= off / d[i] * x[i + 1];
        }
    }
    for (a, ca) in cols.iter().enumerate() {
        for (b, xb) in sols.iter().enumerate() {
            s[a][b] = (1..=last).map(|i| ca[i] * xb[i]).sum();
        }
    }
    let (tr, det) = (s[0][0] + s[1][1], s[0][0] * s[1][1] - s[0][1] * s[1][0]);
    let positives = if det < 0.0 {
        1
    } else if tr > 0.0 {
        2
    } else {
        0
    };
    (negatives + positives).saturating_sub(2)
}

/// Dense trace of the converged solution (fine grid) plus the stability index.
fn build(
    length: f64,
    ei: f64,
    weight: f64,
    h: &Homotopy,
    u: DVector<f64>,
    residual: f64,
    opts: &Options,
) -> Elastica {
    let p = h.prob;
    let m = opts.steps_per_segment();
    let loads = p.loads(&u, h.wbar(1.0));
    let mut nodes = Vec::with_capacity(m * p.segments + 1);
    for k in 0..p.segments {
        let last = k + 1 == p.segments;
        integrate_plain(&p.start(&u, k), p.span(k), m, &loads, |i, y| {
            if i < m || last {
                nodes.push(*y);
            }
        });
    }
    let morse = morse_index(p.kind, &loads, &nodes);
    Elastica {
        length,
        ei,
        weight,
        theta0: p.theta0,
        kind: p.kind,
        segments: p.segments,
        loads,
        nodes,
        unknowns: u,
        residual,
        morse,
    }
}

fn check_common(length_m: f64, ei_nm2: f64, weight: f64, theta0: f64) -> Result<(), String> {
    if !(length_m.is_finite() && length_m > 0.0) {
        return Err(format!("length must be positive, got {length_m}"));
    }
    if !(ei_nm2.is_finite() && ei_nm2 > 0.0) {
        return Err(format!("EI must be positive, got {ei_nm2}"));
    }
    if !weight.is_finite() || !theta0.is_finite() {
        return Err("weight and angle must be finite".into());
    }
    Ok(())
}

fn check_clamped_input(
    length_m: f64,
    ei_nm2: f64,
    weight: f64,
    theta0: f64,
    end: [f64; 3],
) -> Result<(), String> {
    check_common(length_m, ei_nm2, weight, theta0)?;
    if end.iter().any(|v| !v.is_finite()) {
        return Err("end pose must be finite".into());
    }
    let chord = end[0].hypot(end[1]);
    if chord >= length_m {
        return Err(format!(
            "end point at distance {chord} m is out of reach of a rod of length {length_m} m"
        ));
    }
    Ok(())
}

fn check_options(opts: &Options) -> Result<(), String> {
    if opts.segments == 0 || opts.steps == 0 {
        return Err("steps and segments must be positive".into());
    }
    Ok(())
}

/// Cantilever clamped at the origin with angle `theta0_rad`, free end at `s = L`.
pub fn solve_cantilever(
    length_m: f64,
    ei_nm2: f64,
    weight_n_per_m: f64,
    theta0_rad: f64,
) -> Result<Elastica, String> {
    solve_cantilever_with(
        length_m,
        ei_nm2,
        weight_n_per_m,
        theta0_rad,
        &Options::default(),
    )
}

/// [`solve_cantilever`] with explicit numerical options.
pub fn solve_cantilever_with(
    length_m: f64,
    ei_nm2: f64,
    weight_n_per_m: f64,
    theta0_rad: f64,
    opts: &Options,
) -> Result<Elastica, String> {
    check_common(length_m, ei_nm2, weight_n_per_m, theta0_rad)?;
    check_options(opts)?;
    let wbar = weight_n_per_m * length_m.powi(3) / ei_nm2;
    let (h, u) = cantilever_dimensionless(theta0_rad, wbar, opts)?;
    let (u, res) = newton_fixed(&h, u, 1.0, opts.steps_per_segment(), FINAL_TOL, 20)?;
    Ok(build(length_m, ei_nm2, weight_n_per_m, &h, u, res, opts))
}

/// Cantilever solved on the coarse grid (load ramped from zero).
fn cantilever_dimensionless(
    theta0: f64,
    wbar: f64,
    opts: &Options,
) -> Result<(Homotopy, DVector<f64>), String> {
    let prob = Problem {
        kind: Kind::Free,
        theta0,
        segments: opts.segments,
    };
    let (c, s) = (theta0.cos(), theta0.sin());
    let u0 = prob.unknowns_from(&[0.0], |sb| [sb * c, sb * s, theta0, 0.0]);
    let h = Homotopy {
        prob,
        wbar_a: 0.0,
        wbar_b: wbar,
        end_a: [0.0; 3],
        end_b: [0.0; 3],
        defect: None,
    };
    let u = track(
        &h,
        u0,
        opts.coarse_steps_per_segment(),
        opts.max_continuation_steps,
    )?;
    Ok((h, u))
}

/// Clamped–clamped heavy elastica: clamp at the origin with tangent angle `theta0_rad`, clamp
/// at `end = [x1, z1, θ1]` (m, m, rad; `θ1` is the tangent angle in the direction of increasing
/// `s`, not reduced modulo 2π).
pub fn solve_clamped(
    length_m: f64,
    ei_nm2: f64,
    weight_n_per_m: f64,
    theta0_rad: f64,
    end: [f64; 3],
) -> Result<Elastica, String> {
    solve_clamped_with(
        length_m,
        ei_nm2,
        weight_n_per_m,
        theta0_rad,
        end,
        &Options::default(),
    )
}

/// [`solve_clamped`] with explicit numerical options.
pub fn solve_clamped_with(
    length_m: f64,
    ei_nm2: f64,
    weight_n_per_m: f64,
    theta0_rad: f64,
    end: [f64; 3],
    opts: &Options,
) -> Result<Elastica, String> {
    check_clamped_input(length_m, ei_nm2, weight_n_per_m, theta0_rad, end)?;
    check_options(opts)?;
    let l = length_m;
    let wbar = weight_n_per_m * l.powi(3) / ei_nm2;
    let target = [end[0] / l, end[1] / l, end[2]];
    let prob = Problem {
        kind: Kind::Clamped,
        theta0: theta0_rad,
        segments: opts.segments,
    };
    let mut errors = Vec::new();
    for start in Start::ALL {
        let attempt = clamped_attempt(start, &prob, wbar, target, opts)
            .map(|(h, u, res)| build(l, ei_nm2, weight_n_per_m, &h, u, res, opts));
        match attempt {
            Ok(sol) if sol.is_stable() => return Ok(sol),
            Ok(sol) => errors.push(format!(
                "{start:?} start: reached an unstable equilibrium (Morse index {})",
                sol.morse_index()
            )),
            Err(e) => errors.push(format!("{start:?} start: {e}")),
        }
    }
    Err(format!(
        "no stable clamped elastica found: {}",
        errors.join("; ")
    ))
}

/// Like [`solve_clamped_with`] but with a single, explicitly chosen homotopy start, returning
/// whatever equilibrium it reaches — stable or not (check [`Elastica::is_stable`]). Different
/// starts can reach different equilibria of the same boundary-value problem.
pub fn solve_clamped_from_start(
    start: Start,
    length_m: f64,
    ei_nm2: f64,
    weight_n_per_m: f64,
    theta0_rad: f64,
    end: [f64; 3],
    opts: &Options,
) -> Result<Elastica, String> {
    check_clamped_input(length_m, ei_nm2, weight_n_per_m, theta0_rad, end)?;
    check_options(opts)?;
    let l = length_m;
    let wbar = weight_n_per_m * l.powi(3) / ei_nm2;
    let prob = Problem {
        kind: Kind::Clamped,
        theta0: theta0_rad,
        segments: opts.segments,
    };
    let target = [end[0] / l, end[1] / l, end[2]];
    let (h, u, res) = clamped_attempt(start, &prob, wbar, target, opts)?;
    Ok(build(l, ei_nm2, weight_n_per_m, &h, u, res, opts))
}

/// How the homotopy of a clamped–clamped problem is started ([`solve_clamped`] tries them in
/// the order of [`Start::ALL`] and returns the first stable result).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// Inextensible catenary through both end points (needs `x1 > 0`, `w ≥ 0`) with the
    /// elastica's clamp boundary layers `tan((θ − φ)/4) = tan((θ_c − φ)/4) e^{−d/√(EI/T)}`
    /// superposed on its angle `φ(s)`. Newton homotopy `F(u) − (1 − λ) F(u_guess) = 0` closes
    /// the guess's defects. For `w = 0` the guess uses `w̄ = 20` and the weight is ramped to
    /// zero.
    CatenaryWithBoundaryLayers,
    /// The plain catenary (no boundary layers), otherwise as above.
    Catenary,
    /// Cantilever hanging from the start clamp under the full weight; its free end is moved to
    /// the end clamp.
    Cantilever,
    /// Unloaded circular arc from `θ0` to `θ1`; weight and end pose are ramped together.
    Arc,
}

impl Start {
    /// All starts, in the order [`solve_clamped`] tries them.
    pub const ALL: [Start; 4] = [
        Start::CatenaryWithBoundaryLayers,
        Start::Catenary,
        Start::Cantilever,
        Start::Arc,
    ];
}

fn clamped_attempt(
    start: Start,
    prob: &Problem,
    wbar: f64,
    target: [f64; 3],
    opts: &Options,
) -> Result<(Homotopy, DVector<f64>, f64), String> {
    let coarse = opts.coarse_steps_per_segment();
    let th0 = prob.theta0;
    let (u0, wbar_a, newton_homotopy) = match start {
        Start::Catenary | Start::CatenaryWithBoundaryLayers => {
            if wbar < 0.0 || target[0] <= 1e-6 {
                return Err("catenary start needs w ≥ 0 and x1 > 0".into());
            }
            let wguess = if wbar > 0.0 { wbar } else { 20.0 };
            let cat = closed_form::Catenary::through(target[0], target[1], 1.0)?;
            // Tension of a string: horizontal component H = w a, n = H (1, tan φ).
            let hbar = wguess * cat.a;
            let phi = |sb: f64| cat.angle(cat.x_at_arc_length(sb));
            let dphi = |sb: f64| phi(sb).cos().powi(2) / cat.a;
            let layers = start == Start::CatenaryWithBoundaryLayers;
            // Clamp boundary layers of width ℓ = √(EI/T): ℓ² ψ'' = sin ψ, ψ = θ − φ, decaying
            // solution tan(ψ/4) = tan(ψ_c/4) e^{−d/ℓ} (d = distance from the clamp).
            let layer = |psi_c: f64, sb_end: f64| {
                let ell = (phi(sb_end).cos() / hbar).sqrt();
                (if layers { (psi_c / 4.0).tan() } else { 0.0 }, ell)
            };
            let (c0, l0) = layer(th0 - phi(0.0), 0.0);
            let (c1, l1) = layer(target[2] - phi(1.0), 1.0);
            let bl = |c: f64, ell: f64, d: f64| {
                let e = c * (-d / ell).exp();
                (4.0 * e.atan(), -4.0 * e / (ell * (1.0 + e * e)))
            };
            let theta = |sb: f64| {
                let (a0, d0) = bl(c0, l0, sb);
                let (a1, d1) = bl(c1, l1, 1.0 - sb);
                (phi(sb) + a0 + a1, dphi(sb) + d0 - d1)
            };
            // Positions by cumulative Simpson quadrature of (cos θ, sin θ).
            let sub = 64;
            let nk = prob.segments;
            let hq = 1.0 / (nk * sub) as f64;
            let mut nodes = vec![[0.0, 0.0]; nk + 1];
            let mut r = [0.0, 0.0];
            for k in 0..nk {
                for i in 0..sub {
                    let sa = (k * sub + i) as f64 * hq;
                    let (ta, tm, tb) = (theta(sa).0, theta(sa + 0.5 * hq).0, theta(sa + hq).0);
                    r[0] += hq / 6.0 * (ta.cos() + 4.0 * tm.cos() + tb.cos());
                    r[1] += hq / 6.0 * (ta.sin() + 4.0 * tm.sin() + tb.sin());
                }
                nodes[k + 1] = r;
            }
            let state_at = |sb: f64| {
                let k = ((sb * nk as f64).round() as usize).min(nk);
                let (th, dth) = theta(sb);
                [nodes[k][0], nodes[k][1], th, dth]
            };
            let head = [hbar, hbar * phi(0.0).tan(), theta(0.0).1];
            (prob.unknowns_from(&head, state_at), wguess, true)
        }
        Start::Cantilever => {
            // Same unknowns as the cantilever, preceded by its known force n̄(0).
            let (_, uc) = cantilever_dimensionless(th0, wbar, opts)?;
            let mut u0 = prob.unknowns_from(&[0.0, -wbar], |_| [0.0; 4]);
            u0.rows_mut(2, uc.len()).copy_from(&uc);
            (u0, wbar, false)
        }
        Start::Arc => {
            let d = target[2] - th0;
            if d.abs() < 0.1 {
                return Err("arc start needs θ1 ≠ θ0".into());
            }
            let u0 = prob.unknowns_from(&[0.0, 0.0, d], |sb| {
                [
                    ((th0 + d * sb).sin() - th0.sin()) / d,
                    (th0.cos() - (th0 + d * sb).cos()) / d,
                    th0 + d * sb,
                    d,
                ]
            });
            (u0, 0.0, false)
        }
    };
    let mut h = Homotopy {
        prob: *prob,
        wbar_a,
        wbar_b: wbar,
        end_a: target,
        end_b: target,
        defect: None,
    };
    if newton_homotopy {
        h.defect = Some(h.eval(&u0, 0.0, coarse).0);
    } else {
        let ea = prob.end_state(&u0, wbar_a, coarse);
        h.end_a = [ea[0], ea[1], ea[2]];
    }
    let (u, res) = continuation(&h, u0, opts)?;
    Ok((h, u, res))
}

/// Closed-form limits: linear (small-deflection) beam theory and the catenary.
///
/// Deflections are positive **downwards** (`δ = −z`), `x` is measured from the clamp at the
/// origin along the undeformed (horizontal) rod.
pub mod closed_form {
    /// Tip deflection of a horizontal cantilever under its own weight, `w L⁴ / (8 EI)` (m).
    pub fn cantilever_tip_deflection(length_m: f64, ei_nm2: f64, weight_n_per_m: f64) -> f64 {
        weight_n_per_m * length_m.powi(4) / (8.0 * ei_nm2)
    }

    /// Midspan deflection of a clamped–clamped beam without axial force, `w L⁴ / (384 EI)` (m).
    pub fn clamped_clamped_midspan_deflection(
        length_m: f64,
        ei_nm2: f64,
        weight_n_per_m: f64,
    ) -> f64 {
        weight_n_per_m * length_m.powi(4) / (384.0 * ei_nm2)
    }

    /// Cantilever deflection curve `w x² (6L² − 4Lx + x²) / (24 EI)` (m, downwards).
    pub fn cantilever_deflection(length_m: f64, ei_nm2: f64, weight_n_per_m: f64, x: f64) -> f64 {
        let l = length_m;
        weight_n_per_m * x * x * (6.0 * l * l - 4.0 * l * x + x * x) / (24.0 * ei_nm2)
    }

    /// Clamped–clamped deflection curve `w x² (L − x)² / (24 EI)` (m, downwards).
    pub fn clamped_clamped_deflection(
        length_m: f64,
        ei_nm2: f64,
        weight_n_per_m: f64,
        x: f64,
    ) -> f64 {
        let d = length_m - x;
        weight_n_per_m * x * x * d * d / (24.0 * ei_nm2)
    }

    /// Complete elliptic integral of the first kind `K(k) = ∫₀^{π/2} dφ / √(1 − k² sin²φ)`
    /// (modulus `k`, `0 ≤ k < 1`; infinite at `k = 1`), by the arithmetic–geometric mean.
    pub fn elliptic_k(k: f64) -> f64 {
        let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
        for _ in 0..60 {
            let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
            a = an;
            b = bn;
            if (a - b).abs() <= 1e-16 * a {
                break;
            }
        }
        std::f64::consts::FRAC_PI_2 / a
    }

    /// Complete elliptic integral of the second kind `E(k) = ∫₀^{π/2} √(1 − k² sin²φ) dφ`, by the
    /// AGM: `E = K (1 − Σ 2ⁿ⁻¹ cₙ²)` with `c₀ = k` (`0 ≤ k ≤ 1`).
    pub fn elliptic_e(k: f64) -> f64 {
        if k >= 1.0 {
            return 1.0;
        }
        let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
        let mut sum = 0.5 * k * k;
        let mut pow = 0.5;
        for _ in 0..60 {
            let c = 0.5 * (a - b);
            let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
            a = an;
            b = bn;
            pow *= 2.0;
            sum += pow * c * c;
            if c.abs() <= 1e-17 * a {
                break;
            }
        }
        std::f64::consts::FRAC_PI_2 / a * (1.0 - sum)
    }

    /// First (symmetric) buckled mode of a weightless clamped–clamped elastica with both clamps
    /// horizontal, length `L`, span `D < L` (Euler's elastica): one half-period of the
    /// inflectional elastica between the clamps.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct BuckledFirstMode {
        /// Elliptic modulus `k = sin(α/2)`, `α` the largest tangent angle (rad).
        pub modulus: f64,
        /// Largest tangent angle `α` (rad), reached at `s = L/4` and `3L/4`.
        pub max_angle: f64,
        /// Midspan deflection `k L / K(k)` (m).
        pub midspan_deflection: f64,
        /// Compressive axial force `P = EI (4 K(k) / L)²` (N).
        pub axial_force: f64,
        /// Magnitude of the clamp moments `2 EI k (4 K(k)/L)` (N·m), equal at both ends.
        pub clamp_moment: f64,
    }

    /// Solves `D / L = 2 E(k)/K(k) − 1` for `k` (bisection) and evaluates the mode.
    pub fn clamped_buckled_first_mode(
        length_m: f64,
        ei_nm2: f64,
        span_m: f64,
    ) -> Result<BuckledFirstMode, String> {
        let ratio = span_m / length_m;
        if !(ratio > -1.0 && ratio < 1.0) {
            return Err(format!("span/length must be in (−1, 1), got {ratio}"));
        }
        let f = |k: f64| 2.0 * elliptic_e(k) / elliptic_k(k) - 1.0 - ratio;
        // f decreases from 1 − ratio (k = 0) to −1 − ratio (k → 1).
        let (mut lo, mut hi) = (0.0f64, 1.0f64 - 1e-16);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let k = 0.5 * (lo + hi);
        let kk = elliptic_k(k);
        let lambda = 4.0 * kk / length_m;
        Ok(BuckledFirstMode {
            modulus: k,
            max_angle: 2.0 * k.asin(),
            midspan_deflection: k * length_m / kk,
            axial_force: ei_nm2 * lambda * lambda,
            clamp_moment: 2.0 * ei_nm2 * k * lambda,
        })
    }

    /// Inextensible catenary (heavy string, zero bending stiffness) through the origin:
    /// `z(x) = z_v + a (cosh((x − x_v)/a) − 1)`, `a = H/w`, lowest point `(x_v, z_v)`.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Catenary {
        /// Catenary parameter `a = H / w` (m).
        pub a: f64,
        /// Abscissa of the vertex (lowest point of the infinite curve) (m).
        pub x_vertex: f64,
        /// Height of the vertex (m).
        pub z_vertex: f64,
    }

    impl Catenary {
        /// Catenary of length `length_m` from `(0, 0)` to `(dx, dz)`, `dx > 0`.
        ///
        /// With `u = dx/(2a)`: `√(L² − dz²) = 2 a sinh u` and `x_v = dx/2 − a atanh(dz/L)`.
        pub fn through(dx: f64, dz: f64, length_m: f64) -> Result<Catenary, String> {
            if !(dx > 0.0 && dx.hypot(dz) < length_m && length_m.is_finite()) {
                return Err(format!(
                    "catenary needs dx > 0 and a chord shorter than the length, got \
                     dx {dx}, dz {dz}, length {length_m}"
                ));
            }
            let u = solve_sinh_ratio((length_m * length_m - dz * dz).sqrt() / dx)?;
            let a = dx / (2.0 * u);
            let x_vertex = 0.5 * dx - a * (dz / length_m).atanh();
            let z_vertex = -a * ((x_vertex / a).cosh() - 1.0);
            Ok(Catenary {
                a,
                x_vertex,
                z_vertex,
            })
        }

        /// Height `z(x)` (m).
        pub fn z(&self, x: f64) -> f64 {
            self.z_vertex + self.a * (((x - self.x_vertex) / self.a).cosh() - 1.0)
        }

        /// Tangent angle `atan(dz/dx)` (rad) at `x`.
        pub fn angle(&self, x: f64) -> f64 {
            ((x - self.x_vertex) / self.a).sinh().atan()
        }

        /// Arc length from `x = 0` to `x` (m).
        pub fn arc_length(&self, x: f64) -> f64 {
            let a = self.a;
            a * (((x - self.x_vertex) / a).sinh() + (self.x_vertex / a).sinh())
        }

        /// Abscissa reached after arc length `s` from `x = 0` (m).
        pub fn x_at_arc_length(&self, s: f64) -> f64 {
            let a = self.a;
            self.x_vertex + a * (s / a - (self.x_vertex / a).sinh()).asinh()
        }
    }

    /// Root `u > 0` of `sinh(u) = r u`, `r > 1`.
    fn solve_sinh_ratio(r: f64) -> Result<f64, String> {
        if !(r > 1.0 && r.is_finite()) {
            return Err(format!("sinh(u) = r u needs r > 1, got {r}"));
        }
        // f(u) = sinh u − r u is convex on u > 0 and u₀ = √(6(r−1)) satisfies f(u₀) ≥ 0, so
        // Newton from u₀ decreases monotonically to the root.
        let mut u = (6.0 * (r - 1.0)).sqrt();
        // For large r, v = ln(2 r u₀ + 1) < u₀ is a closer point with f(v) ≥ 0, because
        // sinh v ≥ (eᵛ − 1)/2 = r u₀ ≥ r v.
        let v = (2.0 * r * u + 1.0).ln();
        if v < u {
            u = v;
        }
        for _ in 0..200 {
            let f = u.sinh() - r * u;
            let df = u.cosh() - r;
            let step = f / df;
            u -= step;
            if step.abs() <= 1e-15 * u {
                break;
            }
        }
        if !(u.is_finite() && u > 0.0) {
            return Err("catenary parameter iteration failed".into());
        }
        Ok(u)
    }

    /// Catenary parameter `a = H / w` (m) for a chain of length `length_m` hung between two
    /// points at equal height a horizontal distance `span_m` apart: the root of
    /// `L = 2 a sinh(D / (2a))`.
    pub fn catenary_parameter(span_m: f64, length_m: f64) -> Result<f64, String> {
        if !(span_m > 0.0 && length_m > span_m && length_m.is_finite()) {
            return Err(format!(
                "catenary needs 0 < span < length, got span {span_m}, length {length_m}"
            ));
        }
        Ok(span_m / (2.0 * solve_sinh_ratio(length_m / span_m)?))
    }

    /// Sag of the catenary below its end points, `a (cosh(D/(2a)) − 1)` (m, positive).
    pub fn catenary_sag(span_m: f64, length_m: f64) -> Result<f64, String> {
        let a = catenary_parameter(span_m, length_m)?;
        Ok(a * ((span_m / (2.0 * a)).cosh() - 1.0))
    }

    /// Catenary height `z(x) = a (cosh((x − D/2)/a) − cosh(D/(2a)))` (m, ≤ 0), for the end
    /// points `(0, 0)` and `(D, 0)`.
    pub fn catenary_z(span_m: f64, length_m: f64, x: f64) -> Result<f64, String> {
        let a = catenary_parameter(span_m, length_m)?;
        Ok(a * (((x - 0.5 * span_m) / a).cosh() - (span_m / (2.0 * a)).cosh()))
    }
}
