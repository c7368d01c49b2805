//! [`MotionTestOptions`]: how a motion test is stepped and what it keeps.

use super::MotionTestError;
use crate::dynamics::IntegratorSettings;
use crate::rigid_chain::DynamicsSettings;
use crate::setup::Setup;
use nalgebra::Vector3;
use serde::Serialize;

/// Default settle tail (s) after the motion's last sample, holding the last pose: long
/// enough for a 10–50 cm loop (a swinging period of 0.3–0.6 s) to reach its first, largest
/// overshoot after the final stop.
pub const DEFAULT_SETTLE_TAIL_S: f64 = 0.5;

/// Longest accepted settle tail (s): a typo guard.
const MAX_SETTLE_TAIL_S: f64 = 3600.0;

/// What simulates the cable.
#[derive(Debug, Clone, PartialEq)]
pub enum Engine {
    /// The statics' cable model integrated implicitly ([`crate::dynamics`]): the default, at
    /// rest and in slow motion the very equilibrium the attachment test judged.
    Implicit(IntegratorSettings),
    /// Rigid sub-segments jointed in rapier3d ([`crate::rigid_chain`]): the reference
    /// paper's kind of simulation, kept as its baseline. It leaves the static equilibrium
    /// at rest for cables stiffer than the paper's.
    RigidChain(DynamicsSettings),
}

/// The engine's name, for options and reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EngineKind {
    /// [`Engine::Implicit`].
    Implicit,
    /// [`Engine::RigidChain`].
    RigidChain,
}

impl std::fmt::Display for EngineKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            EngineKind::Implicit => "implicit",
            EngineKind::RigidChain => "rigid-chain",
        })
    }
}

impl EngineKind {
    /// The engine with its default settings under `gravity_m_s2`.
    pub fn with_defaults(self, gravity_m_s2: Vector3<f64>) -> Engine {
        match self {
            EngineKind::Implicit => Engine::Implicit(IntegratorSettings::default()),
            EngineKind::RigidChain => Engine::RigidChain(DynamicsSettings::motion(gravity_m_s2)),
        }
    }
}

impl Engine {
    /// Which engine this is.
    pub fn kind(&self) -> EngineKind {
        match self {
            Engine::Implicit(_) => EngineKind::Implicit,
            Engine::RigidChain(_) => EngineKind::RigidChain,
        }
    }

    /// The step (s): the cable is measured once per step.
    pub fn time_step_s(&self) -> f64 {
        match self {
            Engine::Implicit(settings) => settings.time_step_s,
            Engine::RigidChain(settings) => settings.time_step_s,
        }
    }
}

/// How [`run`](super::run) simulates and what it records; the default is
/// [`MotionTestOptions::new`] with the implicit engine at its defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionTestOptions {
    /// The cable simulation and its settings.
    pub engine: Engine,
    /// Simulated time after the motion's end, holding its last pose (s, ≥ 0), so that the
    /// overshoot after the final stop is seen.
    pub settle_tail_s: f64,
    /// Stop at the end of the first step with a violation: enough to reject a candidate
    /// (the k-best fallback); the report then covers the simulation up to that step only.
    pub stop_at_first_violation: bool,
    /// Keep one [`SeriesPoint`](super::SeriesPoint) per step in the report.
    pub record_series: bool,
    /// With the rigid chain: count a contact force on a sub-segment outside the clamp zones
    /// as a contact violation too ([`Constraint::ContactForce`](super::Constraint::ContactForce),
    /// the paper's impulse criterion; rapier resolves contacts at about zero clearance, so
    /// under a zero clearance threshold the clearance alone sees a contact only through the
    /// solver's residual penetration). The implicit engine has no contact forces: the first
    /// contact is judged by the exact clearance.
    pub contact_force_is_violation: bool,
    /// Keep the cable's shape every this many seconds of simulated time (and at the last
    /// instant) in [`MotionTestReport::shapes`](super::MotionTestReport::shapes), e.g. for an
    /// animation; `None`: keep only the final shape.
    pub shape_interval_s: Option<f64>,
    /// Simulate no step: only the cable at rest at the motion's first pose, its pieces
    /// joined at their clamps and measured as the full test's first step measures them. A
    /// static check of the whole cable (two pieces hanging into each other, which no check
    /// of one piece sees); a failure is exactly the full test's failure at its first step,
    /// and `passed` says only that the first pose holds.
    pub first_pose_only: bool,
}

impl Default for MotionTestOptions {
    fn default() -> Self {
        Self::new(Engine::Implicit(IntegratorSettings::default()))
    }
}

impl MotionTestOptions {
    /// The full test with `engine`: a [`DEFAULT_SETTLE_TAIL_S`] tail, no early stop, the
    /// series recorded, contact forces counted as contact.
    pub fn new(engine: Engine) -> Self {
        Self {
            engine,
            settle_tail_s: DEFAULT_SETTLE_TAIL_S,
            stop_at_first_violation: false,
            record_series: true,
            contact_force_is_violation: true,
            shape_interval_s: None,
            first_pose_only: false,
        }
    }

    /// The step of the engine (s).
    pub fn time_step_s(&self) -> f64 {
        self.engine.time_step_s()
    }

    /// Checks the engine's settings, the tail, and that a rigid chain's gravity is the
    /// setup's.
    pub(super) fn validate(&self, setup: &Setup) -> Result<(), MotionTestError> {
        let invalid = |what: String| MotionTestError::Options { what };
        match &self.engine {
            Engine::Implicit(settings) => settings
                .validate()
                .map_err(|e| invalid(format!("implicit engine: {e}")))?,
            Engine::RigidChain(settings) => {
                settings
                    .validate()
                    .map_err(|e| invalid(format!("rigid chain: {e}")))?;
                if settings.gravity_m_s2 != setup.gravity_m_s2 {
                    return Err(invalid(format!(
                        "rigid-chain gravity {:?} m/s² differs from the setup's {:?} m/s²",
                        settings.gravity_m_s2.as_slice(),
                        setup.gravity_m_s2.as_slice()
                    )));
                }
            }
        }
        let tail = self.settle_tail_s;
        if !(tail.is_finite() && (0.0..=MAX_SETTLE_TAIL_S).contains(&tail)) {
            return Err(invalid(format!(
                "settle_tail_s = {tail} must be finite and in [0, {MAX_SETTLE_TAIL_S}] s"
            )));
        }
        if let Some(interval) = self.shape_interval_s
            && !(interval.is_finite() && interval > 0.0)
        {
            return Err(invalid(format!(
                "shape_interval_s = {interval} must be finite and positive"
            )));
        }
        Ok(())
    }
}
