//! Time stepping, damping and sanity bounds of a cable simulation.

use nalgebra::Vector3;

use super::error::{RigidChainError, invalid};

/// Largest accepted number of solver substeps per step (a typo guard: 10⁴ substeps of a
/// 50-body chain already take about a second per step).
const MAX_SUBSTEPS: usize = 10_000;
/// Shortest accepted time step (s): rapier steps in single precision.
const MIN_TIME_STEP_S: f64 = 1e-7;
/// Longest accepted time step (s): a typo guard.
const MAX_TIME_STEP_S: f64 = 1.0;

/// How a cable world is stepped (SI units).
///
/// Rapier splits every step of `time_step_s` into `substeps` solver substeps (its
/// `num_solver_iterations`), each with `sweeps_per_substep` Gauss–Seidel sweeps over the
/// joints. A chain of rigid bodies passes a correction on by one body per sweep, so the joints
/// never quite close: measured on a 500 mm span (50 sub-segments), the joint gaps — hence the
/// stretch error — scale like `h² / sweeps` with the substep `h = time_step_s / substeps`
/// and do not depend on `time_step_s` itself:
///
/// | substep `h` | sweeps | stretch | cost per simulated second |
/// |---|---|---|---|
/// | 1/240 s (rapier default 1/60 s × 4) | 1 | 1.295 | ≈ 20 ms |
/// | 1/960 s | 1 | 1.021 | ≈ 60 ms |
/// | 1/3840 s (the presets) | 1 | 1.0013 | ≈ 220 ms |
/// | 1/1920 s | 4 | 1.0013 | ≈ 160 ms |
/// | 1/3840 s | 4 | 1.0003 | ≈ 300 ms |
///
/// The largest gap is at the guides (≈ 0.13 mm at 1/3840 s, one sweep); the relaxed shape is
/// then within 0.4 mm of the exact discrete equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsSettings {
    /// Length of one step (s): kinematic targets are reached and results are recorded once
    /// per step.
    pub time_step_s: f64,
    /// Solver substeps per step (rapier `num_solver_iterations`), ≥ 1.
    pub substeps: usize,
    /// Gauss–Seidel sweeps over the constraints per substep (rapier
    /// `num_internal_pgs_iterations`), ≥ 1.
    pub sweeps_per_substep: usize,
    /// Linear damping of every sub-segment (1/s): `v ← v / (1 + h·c)` per substep `h`.
    pub linear_damping_per_s: f64,
    /// Angular damping of every sub-segment (1/s), same form.
    pub angular_damping_per_s: f64,
    /// Damping of the joints' angular springs (N·m·s/rad); above ~1e-4 it kinks
    /// the shape, so 0 in both presets.
    pub joint_damping_nms_per_rad: f64,
    /// Gravity (m/s²), world frame.
    pub gravity_m_s2: Vector3<f64>,
    /// Coulomb friction coefficient between the cable and robot colliders (1).
    pub contact_friction: f64,
    /// Gap (m) below which rapier keeps a cable–robot pair as a (speculative) contact. Rapier's
    /// default, 20 mm, let warm-started impulses from earlier steps keep pushing pairs that had
    /// drifted apart again: measured on the bundled pick-and-place, 0.08–0.37 N on a
    /// sub-segment 19.6 mm from the forearm, decaying over ~10 steps. 5 mm still catches an
    /// approach of 1.2 m/s within one 1/240 s step.
    pub contact_prediction_m: f64,
    /// Bounds beyond which a step is reported as a blow-up.
    pub bounds: BlowUpBounds,
}

/// Sanity bounds checked after every step: beyond them the state is meaningless and the step
/// returns [`RigidChainError::BlowUp`]. They are far outside anything a correctly stepped cable
/// does (even rapier's default stepping, which stretches a cable by ~26 %, stays inside).
#[derive(Debug, Clone, PartialEq)]
pub struct BlowUpBounds {
    /// Largest linear speed of a sub-segment (m/s).
    pub max_speed_m_s: f64,
    /// Largest gap between the two anchors of a joint, in sub-segment pitches (1 = the chain
    /// is torn apart by a whole sub-segment).
    pub max_joint_gap_pitches: f64,
    /// Largest stretch of a segment (centerline length / natural length).
    pub max_stretch: f64,
}

impl Default for BlowUpBounds {
    /// 50 m/s (a robot flange moves at most a few m/s), a gap of one pitch, stretch 2.
    fn default() -> Self {
        Self {
            max_speed_m_s: 50.0,
            max_joint_gap_pitches: 1.0,
            max_stretch: 2.0,
        }
    }
}

impl DynamicsSettings {
    /// Static relaxation (the convergent geometry, the paper's baseline): substep 1/3840 s
    /// (1/240 s steps of 16 substeps, the accuracy limit) and a heavy linear damping
    /// of 40 1/s, about twice the critical damping of a 10–50 cm cable's swinging mode
    /// (ω ≈ √(g/sag) ≈ 10–20 rad/s), so the cable creeps into equilibrium without swinging.
    /// No angular damping: the joint springs are integrated implicitly and do not ring.
    pub fn relaxation(gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            time_step_s: 1.0 / 240.0,
            substeps: 16,
            sweeps_per_substep: 1,
            linear_damping_per_s: 40.0,
            angular_damping_per_s: 0.0,
            joint_damping_nms_per_rad: 0.0,
            gravity_m_s2,
            contact_friction: 0.5,
            contact_prediction_m: 0.005,
            bounds: BlowUpBounds::default(),
        }
    }

    /// Dynamic motion test: the same substep as [`DynamicsSettings::relaxation`] with 4
    /// sweeps per substep, and a light linear damping of 5 1/s, about a quarter of the
    /// critical damping of the swinging mode: the cable keeps its inertia — it swings out
    /// when the arm accelerates and overshoots when it stops — while residual swinging decays
    /// within a fraction of a second (e-folding time 2/c = 0.4 s).
    ///
    /// The bend radius is judged per joint, so the joint gaps matter more here than for the
    /// shape: with one sweep a cable held still settled 3–9 % below the static bend radius
    /// (bundled pick-and-place C2: 52.4 vs 54.2 mm; tests' forearm loop: 33.6 vs 30.9 mm at a
    /// guide), biasing the test against candidates the statics accept; with four sweeps it
    /// stays within 1 % (54.1 mm; 31.1 mm) for ≈ 1.3–2× the cost.
    pub fn motion(gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            sweeps_per_substep: 4,
            linear_damping_per_s: 5.0,
            ..Self::relaxation(gravity_m_s2)
        }
    }

    /// Rapier's own defaults (1/60 s, 4 substeps) with the relaxation damping: fast but
    /// inaccurate (a hanging cable stretches by ~26 %). For comparisons only.
    pub fn rapier_defaults(gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            time_step_s: 1.0 / 60.0,
            substeps: 4,
            sweeps_per_substep: 1,
            ..Self::relaxation(gravity_m_s2)
        }
    }

    /// Solver substep length `time_step_s / substeps` (s).
    pub fn substep_s(&self) -> f64 {
        self.time_step_s / self.substeps.max(1) as f64
    }

    /// Checks that every value is finite and in range.
    pub fn validate(&self) -> Result<(), RigidChainError> {
        let bounds = &self.bounds;
        let ranges = [
            (
                "time_step_s",
                self.time_step_s,
                MIN_TIME_STEP_S,
                MAX_TIME_STEP_S,
            ),
            (
                "linear_damping_per_s",
                self.linear_damping_per_s,
                0.0,
                f64::MAX,
            ),
            (
                "angular_damping_per_s",
                self.angular_damping_per_s,
                0.0,
                f64::MAX,
            ),
            (
                "joint_damping_nms_per_rad",
                self.joint_damping_nms_per_rad,
                0.0,
                f64::MAX,
            ),
            ("contact_friction", self.contact_friction, 0.0, f64::MAX),
            (
                "contact_prediction_m",
                self.contact_prediction_m,
                f64::MIN_POSITIVE,
                1.0,
            ),
            (
                "bounds.max_speed_m_s",
                bounds.max_speed_m_s,
                f64::MIN_POSITIVE,
                f64::MAX,
            ),
            (
                "bounds.max_joint_gap_pitches",
                bounds.max_joint_gap_pitches,
                f64::MIN_POSITIVE,
                f64::MAX,
            ),
            (
                "bounds.max_stretch",
                bounds.max_stretch,
                1.0 + f64::EPSILON,
                f64::MAX,
            ),
            ("substeps", self.substeps as f64, 1.0, MAX_SUBSTEPS as f64),
            (
                "sweeps_per_substep",
                self.sweeps_per_substep as f64,
                1.0,
                MAX_SUBSTEPS as f64,
            ),
        ];
        for (name, value, low, high) in ranges {
            if !(low..=high).contains(&value) {
                return Err(invalid(format!(
                    "`{name}` = {value} must be finite and in [{low:e}, {high:e}]"
                )));
            }
        }
        if !self.gravity_m_s2.iter().all(|g| g.is_finite()) {
            return Err(invalid(format!(
                "gravity {:?} m/s² must be finite",
                self.gravity_m_s2.as_slice()
            )));
        }
        Ok(())
    }
}

/// When a relaxation counts as at rest: the geometric test (the kinetic energy
/// never settles because of solver jitter).
///
/// The simulation is cut into windows of `window_s`; the cable is at rest when no node moved
/// more than `max_motion_m` away from where it was at the start of the window.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceWindow {
    /// Length of one window (s, simulated); rounded up to whole steps.
    pub window_s: f64,
    /// Largest node displacement within a window for the cable to be at rest (m).
    pub max_motion_m: f64,
    /// Simulated-time budget (s); beyond it [`RigidChainError::NotConverged`].
    pub max_time_s: f64,
}

impl Default for ConvergenceWindow {
    /// Windows of 0.05 s, at rest below 0.02 mm of motion per window, within 20 s.
    ///
    /// With the relaxation damping the slowest mode creeps with a time constant of order
    /// `c/ω² ≈ 0.1–0.4 s`, so 0.02 mm of motion per 0.05 s window leaves at most ≈ 0.2 mm
    /// to go.
    fn default() -> Self {
        Self {
            window_s: 0.05,
            max_motion_m: 2e-5,
            max_time_s: 20.0,
        }
    }
}

impl ConvergenceWindow {
    /// Checks that every value is finite and positive.
    pub fn validate(&self) -> Result<(), RigidChainError> {
        for (name, value) in [
            ("window_s", self.window_s),
            ("max_motion_m", self.max_motion_m),
            ("max_time_s", self.max_time_s),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(format!(
                    "convergence window `{name}` = {value} must be finite and > 0"
                )));
            }
        }
        Ok(())
    }
}
