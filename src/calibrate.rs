//! A cable's stiffness from bench measurements an engineer can make with a ruler.
//!
//! **Bending stiffness `EI`: the heavy cantilever.** A length `L` of cable is clamped
//! horizontally and left to hang under its own weight `w = ρ g` per length; its free end
//! droops by `δ` (or leaves at an angle `θ_L` below the horizontal). The shape is the heavy
//! elastica: with `θ(s)` the angle below the horizontal at arc length `s`,
//!
//! ```text
//! EI θ'' = −w (L − s) cos θ,   θ(0) = 0 (clamped),   θ'(L) = 0 (free end: no moment),
//! δ = ∫₀ᴸ sin θ ds.
//! ```
//!
//! In units of `L` the shape depends on one number, `κ = w L³ / EI`, so a measured `δ / L`
//! (or `θ_L`) gives `κ`, hence `EI = w L³ / κ`, exactly — no small-deflection formula
//! (`δ = wL⁴/8EI`, wrong by 10 % at `δ/L` ≈ 0.3). The boundary value problem is solved by
//! shooting from the free end, where the shape's two conditions are known (`θ'(L) = 0`, and
//! a trial tip angle): the angle reached at the clamp changes sign once in the tip angle
//! and in `κ` over the range inverted, so a bracketed secant search finds both without a
//! starting guess. Integration: classical fourth-order Runge–Kutta, 4000 steps (tested: an
//! independent multiple-shooting solution's EI comes back to 1e-9).
//!
//! **Torsional stiffness `GJ`**: a length `L_t` clamped at one end, a torque `T` applied at
//! the other (a weight on a lever arm), the end turns by `φ`: `GJ = T L_t / φ`; or a ratio
//! `GJ / EI` taken from a comparable cable (cables/README.md).

use std::f64::consts::FRAC_PI_2;

/// Runge–Kutta steps over the cantilever.
const STEPS: usize = 4000;
/// Root-finding rounds at most (the bracketed secant converges in about ten).
const ROUNDS: usize = 200;
/// Largest load parameter `wL³/EI` inverted: the free end then droops by 0.94 of the length
/// and leaves nearly vertically (89.6°). Beyond, the angle at the clamp grows so steeply
/// with the end angle that shooting from the free end loses the solution; a shorter length
/// of the same cable measures it (κ falls with L³).
const MAX_LOAD_PARAMETER: f64 = 100.0;
/// Smallest load parameter inverted: a droop of 1.25e-7 of the length, beyond what a ruler
/// measures.
const MIN_LOAD_PARAMETER: f64 = 1e-6;

/// What was measured on the cantilever's free end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TipMeasurement {
    /// Vertical drop of the free end below the clamp (m).
    Droop(f64),
    /// Angle of the cable at the free end below the horizontal (rad).
    EndAngle(f64),
}

/// A heavy-cantilever bench measurement (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CantileverTest {
    /// Free length from the clamp's edge to the end (m).
    pub length_m: f64,
    /// Mass per length of the cable (kg/m).
    pub mass_per_length_kg_m: f64,
    /// Gravitational acceleration (m/s²).
    pub gravity_m_s2: f64,
    /// The droop or the end angle.
    pub tip: TipMeasurement,
}

/// The shape of a heavy cantilever with load parameter `κ = wL³/EI`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CantileverShape {
    /// `κ = w L³ / EI`.
    pub load_parameter: f64,
    /// Angle of the free end below the horizontal (rad).
    pub end_angle_rad: f64,
    /// Droop of the free end over the length, `δ / L`.
    pub droop_over_length: f64,
}

/// Why a measurement gives no stiffness.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    /// A value that is not finite or not positive.
    #[error("{what} = {value} must be a finite number > 0")]
    NotPositive {
        /// The quantity, with its unit.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A droop outside what the inversion covers.
    #[error(
        "a droop of {droop_mm} mm over a {length_mm} mm cantilever is outside what can be \
         inverted, {min_mm:.6} to {max_mm:.1} mm: check that the droop is the vertical drop of \
         the free end below the clamp; a cable that droops more is measured on a shorter \
         length, one that droops less on a longer one"
    )]
    DroopOutOfRange {
        /// The droop (mm).
        droop_mm: f64,
        /// The length (mm).
        length_mm: f64,
        /// The smallest droop inverted (mm).
        min_mm: f64,
        /// The largest droop inverted (mm).
        max_mm: f64,
    },
    /// An end angle outside what the inversion covers.
    #[error(
        "an end angle of {angle_deg}° below the horizontal is outside what a cable shows: \
         between {min_deg:.6}° and {max_deg:.1}°"
    )]
    AngleOutOfRange {
        /// The angle (degrees).
        angle_deg: f64,
        /// The smallest angle inverted (degrees).
        min_deg: f64,
        /// The largest angle inverted (degrees).
        max_deg: f64,
    },
}

impl CantileverTest {
    /// The bending stiffness `EI` (N·m²) this measurement implies, with the shape it has.
    pub fn bending_stiffness(&self) -> Result<(f64, CantileverShape), CalibrationError> {
        positive("length (m)", self.length_m)?;
        positive("mass per length (kg/m)", self.mass_per_length_kg_m)?;
        positive("gravity (m/s²)", self.gravity_m_s2)?;
        let (stiffest, limpest) = (
            cantilever_shape(MIN_LOAD_PARAMETER),
            cantilever_shape(MAX_LOAD_PARAMETER),
        );
        let shape = match self.tip {
            TipMeasurement::Droop(droop) => {
                let ratio = droop / self.length_m;
                let range = stiffest.droop_over_length..=limpest.droop_over_length;
                if !range.contains(&ratio) {
                    return Err(CalibrationError::DroopOutOfRange {
                        droop_mm: droop * 1e3,
                        length_mm: self.length_m * 1e3,
                        min_mm: range.start() * self.length_m * 1e3,
                        max_mm: range.end() * self.length_m * 1e3,
                    });
                }
                shape_with_droop(ratio)
            }
            TipMeasurement::EndAngle(angle) => {
                let range = stiffest.end_angle_rad..=limpest.end_angle_rad;
                if !range.contains(&angle) {
                    return Err(CalibrationError::AngleOutOfRange {
                        angle_deg: angle.to_degrees(),
                        min_deg: range.start().to_degrees(),
                        max_deg: range.end().to_degrees(),
                    });
                }
                shape_with_end_angle(angle)
            }
        };
        let weight = self.mass_per_length_kg_m * self.gravity_m_s2;
        Ok((weight * self.length_m.powi(3) / shape.load_parameter, shape))
    }
}

/// The torsional stiffness `GJ = T L / φ` (N·m²) of a length `length_m` twisted by
/// `angle_rad` under the torque `torque_nm`.
pub fn torsion_stiffness(
    length_m: f64,
    torque_nm: f64,
    angle_rad: f64,
) -> Result<f64, CalibrationError> {
    positive("twist length (m)", length_m)?;
    positive("torque (N·m)", torque_nm)?;
    positive("twist angle (rad)", angle_rad)?;
    Ok(torque_nm * length_m / angle_rad)
}

/// The heavy cantilever's shape for the load parameter `κ` (> 0).
pub fn cantilever_shape(load_parameter: f64) -> CantileverShape {
    // The tip angle that makes the clamp horizontal: bracketed by 0 (the clamp is then
    // reached pointing upwards, θ < 0) and π/2 (a vertical cable stays vertical, θ = π/2).
    let tip = root(0.0, FRAC_PI_2, |tip| {
        from_tip(load_parameter, tip).clamp_angle
    });
    let shape = from_tip(load_parameter, tip);
    CantileverShape {
        load_parameter,
        end_angle_rad: tip,
        droop_over_length: shape.droop_over_length,
    }
}

/// The shape whose droop over length is `ratio`: `κ` in `ln κ` (the droop grows with `κ`
/// from 0 towards the whole length).
fn shape_with_droop(ratio: f64) -> CantileverShape {
    let log_kappa = root(
        MIN_LOAD_PARAMETER.ln(),
        MAX_LOAD_PARAMETER.ln(),
        |log_kappa| cantilever_shape(log_kappa.exp()).droop_over_length - ratio,
    );
    cantilever_shape(log_kappa.exp())
}

/// The shape whose free end leaves at `angle` below the horizontal: `κ` such that starting
/// at the tip with that angle reaches the clamp horizontal.
fn shape_with_end_angle(angle: f64) -> CantileverShape {
    // The clamp angle falls as κ grows: its negative is the increasing function.
    let log_kappa = root(
        MIN_LOAD_PARAMETER.ln(),
        MAX_LOAD_PARAMETER.ln(),
        |log_kappa| -from_tip(log_kappa.exp(), angle).clamp_angle,
    );
    let kappa = log_kappa.exp();
    CantileverShape {
        load_parameter: kappa,
        end_angle_rad: angle,
        droop_over_length: from_tip(kappa, angle).droop_over_length,
    }
}

/// The result of integrating from the free end towards the clamp.
struct FromTip {
    /// `θ` at the clamp (0 for the true shape).
    clamp_angle: f64,
    /// `∫ sin θ` over the length, in units of the length.
    droop_over_length: f64,
}

/// Integrates `θ'' = −κ u cos θ` in `u` = distance from the free end (units of the length),
/// from `θ = tip`, `θ' = 0` at `u = 0` to `u = 1`, with `∫ sin θ du` alongside.
fn from_tip(kappa: f64, tip: f64) -> FromTip {
    let h = 1.0 / STEPS as f64;
    // State: θ, θ', ∫ sin θ.
    let rate = |u: f64, y: [f64; 3]| [y[1], -kappa * u * y[0].cos(), y[0].sin()];
    let mut y = [tip, 0.0, 0.0];
    for k in 0..STEPS {
        let u = k as f64 * h;
        let add =
            |y: [f64; 3], d: [f64; 3], f: f64| [y[0] + f * d[0], y[1] + f * d[1], y[2] + f * d[2]];
        let k1 = rate(u, y);
        let k2 = rate(u + 0.5 * h, add(y, k1, 0.5 * h));
        let k3 = rate(u + 0.5 * h, add(y, k2, 0.5 * h));
        let k4 = rate(u + h, add(y, k3, h));
        for i in 0..3 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    FromTip {
        clamp_angle: y[0],
        droop_over_length: y[2],
    }
}

/// The root of an increasing `f` between `low` and `high` (clamped to them if `f` does not
/// change sign), by the Illinois variant of the bracketed secant method: it keeps a bracket
/// like bisection and converges superlinearly.
fn root(mut low: f64, mut high: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (mut f_low, mut f_high) = (f(low), f(high));
    if f_low >= 0.0 {
        return low;
    }
    if f_high <= 0.0 {
        return high;
    }
    let mut side = 0;
    for _ in 0..ROUNDS {
        let x = (low * f_high - high * f_low) / (f_high - f_low);
        if !(x > low && x < high) || high - low <= 4.0 * f64::EPSILON * high.abs().max(1.0) {
            break;
        }
        let fx = f(x);
        if fx == 0.0 {
            return x;
        }
        if fx < 0.0 {
            (low, f_low) = (x, fx);
            if side == -1 {
                f_high *= 0.5;
            }
            side = -1;
        } else {
            (high, f_high) = (x, fx);
            if side == 1 {
                f_low *= 0.5;
            }
            side = 1;
        }
    }
    if f_high < -f_low { high } else { low }
}

fn positive(what: &'static str, value: f64) -> Result<f64, CalibrationError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CalibrationError::NotPositive { what, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small loads: the linear beam's `δ = wL⁴/8EI` and `θ_L = wL³/6EI`, i.e. `δ/L = κ/8`,
    /// `θ_L = κ/6`, to the next order in `κ`.
    #[test]
    fn a_lightly_loaded_cantilever_is_the_linear_beam() {
        let kappa = 1e-3;
        let shape = cantilever_shape(kappa);
        assert!((shape.droop_over_length / (kappa / 8.0) - 1.0).abs() < 1e-3);
        assert!((shape.end_angle_rad / (kappa / 6.0) - 1.0).abs() < 1e-3);
    }

    /// Droop and end angle invert the same shape.
    #[test]
    fn droop_and_end_angle_give_the_same_load_parameter() {
        for kappa in [1e-4, 0.5, 3.0, 20.0, 90.0] {
            let shape = cantilever_shape(kappa);
            let by_droop = shape_with_droop(shape.droop_over_length);
            let by_angle = shape_with_end_angle(shape.end_angle_rad);
            assert!(
                (by_droop.load_parameter / kappa - 1.0).abs() < 1e-9,
                "{by_droop:?}"
            );
            assert!(
                (by_angle.load_parameter / kappa - 1.0).abs() < 1e-9,
                "{by_angle:?}"
            );
        }
    }
}
