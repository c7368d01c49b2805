//! Velocity profiles of synchronized point-to-point moves.
//!
//! All joints of a move follow one normalized profile `s(t)` rising from 0 to 1:
//! `q_j(t) = q0_j + Δ_j·s(t)`. They start and stop together and the path in joint space is
//! the straight line between the waypoints. Joint `j` moves at `Δ_j·s'(t)` and accelerates
//! at `Δ_j·s''(t)`, so with speed limits `v_j` and acceleration limits `a_j`:
//!
//! - **trapezoidal**: `s` accelerates at `A = min_j a_j/|Δ_j|` up to `V = min_j v_j/|Δ_j|`,
//!   cruises, and brakes at `A`: duration `T = 1/V + V/A`; when `V²/A > 1` the cruise speed
//!   is never reached (triangular profile, `T = 2·√(1/A)`). For a single joint this is the
//!   textbook `T = Δ/v + v/a` (or `2·√(Δ/a)`). When one joint binds both minima — always
//!   when accelerations are given as a time to full speed — `T` is exactly the slowest
//!   joint's own shortest time; otherwise `T` can exceed it slightly, the price of the
//!   straight joint-space path.
//! - **quintic**: `s(τ) = 10τ³ − 15τ⁴ + 6τ⁵` with `τ = t/T`, zero speed and acceleration at
//!   both ends. Its peak speed is `s'(½) = 15/(8T)` and its peak acceleration, at
//!   `τ = ½ ∓ √3/6`, is `|s''| = 10√3/(3T²)`; hence joint `j` peaks at `15|Δ_j|/(8T)` and
//!   `10√3|Δ_j|/(3T²)`, and the shortest duration within all limits is
//!   `T = max_j max(15|Δ_j|/(8v_j), √(10√3|Δ_j|/(3a_j)))`.

use serde::{Deserialize, Serialize};

/// The shape of the velocity profile of every move.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Profile {
    /// Constant acceleration, cruise, constant deceleration (triangular for short moves).
    Trapezoidal,
    /// The quintic polynomial `10τ³ − 15τ⁴ + 6τ⁵`: zero speed and acceleration at both ends.
    Quintic,
}

impl Profile {
    /// The name used in waypoint files.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Trapezoidal => "trapezoidal",
            Profile::Quintic => "quintic",
        }
    }
}

/// One synchronized move: the normalized profile `s(t)` (0 → 1) every joint follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SyncMove {
    profile: Profile,
    duration_s: f64,
    /// Trapezoidal: cruise (or peak) rate of `s` (1/s).
    rate: f64,
    /// Trapezoidal: acceleration of `s` (1/s²).
    accel: f64,
    /// Trapezoidal: duration of the acceleration (= deceleration) phase (s).
    ramp_s: f64,
}

impl SyncMove {
    /// The fastest synchronized move of displacements `deltas` (rad / m, signed) within speed
    /// limits `max_speeds` (rad/s / m/s) and acceleration limits `max_accels` (rad/s² /
    /// m/s²), all positive, one per joint. Joints that do not move do not constrain it; a move
    /// where no joint moves takes no time.
    pub fn plan(profile: Profile, deltas: &[f64], max_speeds: &[f64], max_accels: &[f64]) -> Self {
        let moving = || {
            deltas
                .iter()
                .zip(max_speeds.iter().zip(max_accels))
                .filter(|(d, _)| **d != 0.0)
                .map(|(d, (v, a))| (d.abs(), *v, *a))
        };
        let mut plan = SyncMove {
            profile,
            duration_s: 0.0,
            rate: 0.0,
            accel: 0.0,
            ramp_s: 0.0,
        };
        if moving().next().is_none() {
            return plan;
        }
        match profile {
            Profile::Trapezoidal => {
                let rate = moving()
                    .map(|(d, v, _)| v / d)
                    .fold(f64::INFINITY, f64::min);
                let accel = moving()
                    .map(|(d, _, a)| a / d)
                    .fold(f64::INFINITY, f64::min);
                plan.accel = accel;
                if rate * rate <= accel {
                    plan.rate = rate;
                    plan.ramp_s = rate / accel;
                    plan.duration_s = 1.0 / rate + rate / accel;
                } else {
                    plan.ramp_s = (1.0 / accel).sqrt();
                    plan.rate = accel * plan.ramp_s;
                    plan.duration_s = 2.0 * plan.ramp_s;
                }
            }
            Profile::Quintic => {
                let peak_accel = 10.0 * 3f64.sqrt() / 3.0;
                plan.duration_s = moving()
                    .map(|(d, v, a)| (15.0 * d / (8.0 * v)).max((peak_accel * d / a).sqrt()))
                    .fold(0.0, f64::max);
            }
        }
        plan
    }

    /// The profile shape.
    pub fn profile(&self) -> Profile {
        self.profile
    }

    /// Duration of the move (s).
    pub fn duration_s(&self) -> f64 {
        self.duration_s
    }

    /// The fraction `s` of the move done at `t_s` seconds after its start: 0 before, 1 after,
    /// exactly 1 at `t_s == duration_s()`.
    pub fn fraction(&self, t_s: f64) -> f64 {
        let total = self.duration_s;
        if t_s <= 0.0 || total == 0.0 {
            return if total == 0.0 && t_s > 0.0 { 1.0 } else { 0.0 };
        }
        if t_s >= total {
            return 1.0;
        }
        match self.profile {
            Profile::Trapezoidal => {
                let (a, ramp) = (self.accel, self.ramp_s);
                if t_s <= ramp {
                    0.5 * a * t_s * t_s
                } else if t_s <= total - ramp {
                    0.5 * a * ramp * ramp + self.rate * (t_s - ramp)
                } else {
                    let left = total - t_s;
                    1.0 - 0.5 * a * left * left
                }
            }
            Profile::Quintic => {
                let tau = t_s / total;
                tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau))
            }
        }
    }
}
