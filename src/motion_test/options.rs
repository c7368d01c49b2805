//! [`MotionTestOptions`]: how a motion test is stepped and what it keeps.

use super::MotionTestError;
use crate::rigid_chain::DynamicsSettings;
use crate::setup::Setup;
use nalgebra::Vector3;

/// Default settle tail (s) after the motion's last sample, holding the last pose.
///
/// The motion preset's linear damping (5 1/s) lets a swinging cable decay with an e-folding
/// time of 0.4 s, and a 10–50 cm loop swings with a period of about 0.3–0.6 s: within 0.5 s
/// the overshoot after the final stop reaches its first (largest) extreme.
pub const DEFAULT_SETTLE_TAIL_S: f64 = 0.5;

/// Longest accepted settle tail (s): a typo guard.
const MAX_SETTLE_TAIL_S: f64 = 3600.0;

/// How [`run`](super::run) simulates and what it records.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionTestOptions {
    /// Stepping, damping and blow-up bounds of the cable simulation. Its gravity must be the
    /// setup's (the initial equilibrium is solved under the setup's gravity).
    pub settings: DynamicsSettings,
    /// Simulated time after the motion's end, holding its last pose (s, ≥ 0), so that the
    /// overshoot after the final stop is seen.
    pub settle_tail_s: f64,
    /// Stop at the end of the first step with a violation: enough to reject a candidate
    /// (the k-best fallback); the report then covers the simulation up to that step only.
    pub stop_at_first_violation: bool,
    /// Keep one [`SeriesPoint`](super::SeriesPoint) per step in the report.
    pub record_series: bool,
    /// Count a contact force in the simulation on a sub-segment outside the clamp zones as a
    /// contact violation too ([`Constraint::ContactForce`](super::Constraint::ContactForce),
    /// the paper's impulse criterion). Rapier resolves contacts at about zero clearance —
    /// measured: a cable pressed onto a link with 0.3–1.5 N stayed within −0.25…+0.43 mm of
    /// it — so under a zero clearance threshold the clearance alone sees a contact only
    /// through the solver's residual penetration. Off: contact is judged by the clearance
    /// alone (e.g. under a negative clearance threshold, which tolerates touching).
    pub contact_force_is_violation: bool,
    /// Keep the cable's shape every this many seconds of simulated time (and at the last
    /// instant) in [`MotionTestReport::shapes`](super::MotionTestReport::shapes), e.g. for an
    /// animation; `None`: keep only the final shape.
    pub shape_interval_s: Option<f64>,
}

impl MotionTestOptions {
    /// The full test under `gravity_m_s2`: [`DynamicsSettings::motion`] (1/240 s steps of 16
    /// substeps, DESIGN §4's accuracy limit), a [`DEFAULT_SETTLE_TAIL_S`] tail, no early stop,
    /// the series recorded, contact forces counted as contact.
    pub fn new(gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            settings: DynamicsSettings::motion(gravity_m_s2),
            settle_tail_s: DEFAULT_SETTLE_TAIL_S,
            stop_at_first_violation: false,
            record_series: true,
            contact_force_is_violation: true,
            shape_interval_s: None,
        }
    }

    /// [`MotionTestOptions::new`] with the setup's gravity.
    pub fn for_setup(setup: &Setup) -> Self {
        Self::new(setup.gravity_m_s2)
    }

    /// Checks the settings, the tail, and that the gravity is the setup's.
    pub(super) fn validate(&self, setup: &Setup) -> Result<(), MotionTestError> {
        let invalid = |what: String| MotionTestError::Options { what };
        self.settings
            .validate()
            .map_err(|e| invalid(format!("settings: {e}")))?;
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
        if self.settings.gravity_m_s2 != setup.gravity_m_s2 {
            return Err(invalid(format!(
                "settings gravity {:?} m/s² differs from the setup's {:?} m/s²",
                self.settings.gravity_m_s2.as_slice(),
                setup.gravity_m_s2.as_slice()
            )));
        }
        Ok(())
    }
}
