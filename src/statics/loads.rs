//! What a piece of cable puts on its clamps: the force and the moment at each clamp's point,
//! from the same energy the statics and the dynamics minimize.
//!
//! The clamp holds the cable's end node and its direction and twist. By virtual work, the
//! force the cable puts on the clamp is `−∂E/∂p` and the moment about the clamp's point
//! `−∂E/∂θ`, the derivatives of the piece's potential energy with respect to a shift `p` and a
//! small turn `θ` of the clamp with every free node held where it is (at an equilibrium this
//! is the load; in the motion test the inertial forces reach the clamp through the same
//! elastic terms, so it is the dynamic load). They are taken by central differences of the
//! terms of the energy that move with the clamp (`Rod::clamp_energy`). The half sub-segment of cable at a clamp, whose mass the discrete model puts on
//! no free node, hangs on that clamp: its weight is added.

use super::rod::{Rod, RodParameters};
use crate::pose::Pose;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use serde::Serialize;

/// Shift of a clamp (m) for the differences of the force: small beside the pitch, large
/// beside the energy's rounding (stretch stiffness × shift² ≫ 1e-16 J).
const SHIFT_M: f64 = 1e-7;
/// Turn of a clamp (rad) for the differences of the moment.
const TURN_RAD: f64 = 1e-6;

/// The load a piece of cable puts on one clamp, world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ClampLoad {
    /// Force (N).
    pub force_n: [f64; 3],
    /// Moment about the clamp's point (N·m).
    pub moment_n_m: [f64; 3],
}

impl ClampLoad {
    /// No load.
    pub const ZERO: ClampLoad = ClampLoad {
        force_n: [0.0; 3],
        moment_n_m: [0.0; 3],
    };

    /// The size of the force (N).
    pub fn force_magnitude_n(&self) -> f64 {
        Vector3::from(self.force_n).norm()
    }

    /// The size of the moment (N·m).
    pub fn moment_magnitude_n_m(&self) -> f64 {
        Vector3::from(self.moment_n_m).norm()
    }

    /// The sum of two loads on one clamp point (two pieces held by one clamp).
    pub fn plus(&self, other: &ClampLoad) -> ClampLoad {
        ClampLoad {
            force_n: (Vector3::from(self.force_n) + Vector3::from(other.force_n)).into(),
            moment_n_m: (Vector3::from(self.moment_n_m) + Vector3::from(other.moment_n_m)).into(),
        }
    }
}

/// The loads on the start clamp at `start` and, for a clamped end, on the end clamp at `end`
/// of a piece in the shape `nodes` (`S + 1` nodes, the first and last at the clamps) with
/// total twist `twist_rad`, under `params` (gravity included).
pub fn clamp_loads(
    params: &RodParameters,
    start: &Pose,
    end: Option<&Pose>,
    nodes: &[Point3<f64>],
    twist_rad: f64,
) -> (ClampLoad, Option<ClampLoad>) {
    let sub_segments = nodes.len().saturating_sub(1);
    let rod = |start: Pose, end: Option<Pose>| Rod::new(*params, start, end, sub_segments);
    let x = rod(*start, end.copied()).free_coordinates(nodes);
    // Only the terms that move with a clamp: their derivatives are the whole energy's.
    let energy = |start: Pose, end: Option<Pose>, at_end: bool| {
        rod(start, end).clamp_energy(&x, twist_rad, at_end)
    };
    let half_weight = 0.5 * params.mass_per_length_kg_m * params.pitch_m * params.gravity_m_s2;
    let start_load = load(
        start,
        |moved| energy(moved, end.copied(), false),
        &half_weight,
    );
    let end_load =
        end.map(|end| load(end, |moved| energy(*start, Some(moved), true), &half_weight));
    (start_load, end_load)
}

/// `−∂E/∂p` and `−∂E/∂θ` of `energy` (a function of the clamp's pose) at `clamp`, plus the
/// weight `hanging` of the cable on the clamp itself.
fn load(clamp: &Pose, energy: impl Fn(Pose) -> f64, hanging: &Vector3<f64>) -> ClampLoad {
    let mut force = *hanging;
    let mut moment = Vector3::zeros();
    for axis in 0..3 {
        let unit = Vector3::ith(axis, 1.0);
        let shifted = |s: f64| {
            Isometry3::from_parts(
                Translation3::from(clamp.translation.vector + s * unit),
                clamp.rotation,
            )
        };
        force[axis] -= (energy(shifted(SHIFT_M)) - energy(shifted(-SHIFT_M))) / (2.0 * SHIFT_M);
        let turned = |a: f64| {
            Isometry3::from_parts(
                clamp.translation,
                UnitQuaternion::from_scaled_axis(a * unit) * clamp.rotation,
            )
        };
        moment[axis] = -(energy(turned(TURN_RAD)) - energy(turned(-TURN_RAD))) / (2.0 * TURN_RAD);
    }
    ClampLoad {
        force_n: force.into(),
        moment_n_m: moment.into(),
    }
}
