//! Closed-form small vibrations of the two continuous rods the dynamics tests use, written
//! from the textbook equations (nothing from the `cable_dict` crate).
//!
//! - **Euler–Bernoulli cantilever** (no gravity): `EI w'''' + ρ ẅ = 0`, clamped at `x = 0`,
//!   free at `x = L`. Modes `ω_n = (β_n L)² √(EI / (ρ L⁴))` with `cos βL cosh βL = −1`
//!   (βL = 1.8751, 4.6941, …) and shapes
//!   `φ(x) = cosh βx − cos βx − σ (sinh βx − sin βx)`,
//!   `σ = (cosh βL + cos βL) / (sinh βL + sin βL)`.
//! - **Hanging chain** (Bernoulli 1732, Euler): an inextensible chain of length `L` hanging
//!   from a fixed point, tension `ρ g s` at height `s` above the free end. Lateral modes
//!   `u(s) = J0(2ω √(s / g))`, `ω_n = (j_(0,n) / 2) √(g / L)` with `j_(0,n)` the zeros of
//!   the Bessel function `J0` (2.4048, 5.5201, …).

/// The Bessel function `J0(x)` by its power series (exact to rounding for `x` ≤ 20).
pub fn bessel_j0(x: f64) -> f64 {
    let q = -0.25 * x * x;
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..200 {
        term *= q / (k as f64 * k as f64);
        sum += term;
        if term.abs() < 1e-18 * sum.abs().max(1e-300) {
            break;
        }
    }
    sum
}

/// The `n`-th positive zero of `J0` (n = 1, 2, …), by bisection between sign changes.
pub fn bessel_j0_zero(n: usize) -> f64 {
    let mut found = 0;
    let mut a = 0.0;
    let step = 0.01;
    loop {
        let b: f64 = a + step;
        if bessel_j0(a).signum() != bessel_j0(b).signum() {
            found += 1;
            if found == n {
                return bisect(bessel_j0, a, b);
            }
        }
        a = b;
    }
}

/// The `n`-th root of `cos z cosh z + 1 = 0` (n = 1, 2, …): `β_n L` of the cantilever.
pub fn cantilever_beta_l(n: usize) -> f64 {
    let f = |z: f64| z.cos() * z.cosh() + 1.0;
    let mut found = 0;
    let mut a: f64 = 0.1;
    loop {
        let b = a + 0.01;
        if f(a).signum() != f(b).signum() {
            found += 1;
            if found == n {
                return bisect(f, a, b);
            }
        }
        a = b;
    }
}

/// Angular frequency (rad/s) of the cantilever's mode `n`.
pub fn cantilever_omega(n: usize, length_m: f64, ei_nm2: f64, mass_per_length: f64) -> f64 {
    let beta_l = cantilever_beta_l(n);
    beta_l * beta_l * (ei_nm2 / (mass_per_length * length_m.powi(4))).sqrt()
}

/// The cantilever's mode `n` shape at `x` (clamped at 0; unnormalized).
pub fn cantilever_mode(n: usize, length_m: f64, x: f64) -> f64 {
    let beta_l = cantilever_beta_l(n);
    let b = beta_l / length_m;
    let sigma = (beta_l.cosh() + beta_l.cos()) / (beta_l.sinh() + beta_l.sin());
    (b * x).cosh() - (b * x).cos() - sigma * ((b * x).sinh() - (b * x).sin())
}

/// Angular frequency (rad/s) of the hanging chain's mode `n`.
pub fn hanging_chain_omega(n: usize, length_m: f64, g: f64) -> f64 {
    0.5 * bessel_j0_zero(n) * (g / length_m).sqrt()
}

/// The hanging chain's mode `n` lateral shape at height `s` above the free end.
pub fn hanging_chain_mode(n: usize, length_m: f64, s: f64) -> f64 {
    bessel_j0(bessel_j0_zero(n) * (s / length_m).sqrt())
}

fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (f(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Published values: j01 = 2.404826, j02 = 5.520078 (Abramowitz & Stegun, Table 9.5);
    /// β1L = 1.875104, β2L = 4.694091 (any vibration handbook).
    #[test]
    fn roots_match_the_tables() {
        assert!((bessel_j0_zero(1) - 2.404826).abs() < 1e-6);
        assert!((bessel_j0_zero(2) - 5.520078).abs() < 1e-6);
        assert!((cantilever_beta_l(1) - 1.875104).abs() < 1e-6);
        assert!((cantilever_beta_l(2) - 4.694091).abs() < 1e-6);
    }
}
