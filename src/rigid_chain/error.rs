//! Why a dynamic simulation of the cable was refused or stopped.

use std::fmt;

/// What went wrong in a cable simulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RigidChainError {
    /// The input cannot be simulated: no sub-segments, a non-finite pose or setting, node and
    /// frame lists of the wrong length, chords that are not one pitch long, guides of
    /// consecutive segments that do not coincide, a robot collider rapier cannot build, …
    #[error("invalid dynamics input: {what}")]
    InvalidInput {
        /// What is wrong, for people.
        what: String,
    },
    /// The simulation left the range where it means anything (see [`BlowUpQuantity`]). The
    /// world that reported it is unusable: every later step returns the same error.
    #[error(
        "the cable simulation blew up at step {step} (t = {time_s:.4} s), segment {segment}{}: {quantity} = {value:.4e} exceeds the sanity bound {bound:.4e}",
        sub_segment.map(|s| format!(", sub-segment {s}")).unwrap_or_default()
    )]
    BlowUp {
        /// 1-based index of the step that failed.
        step: usize,
        /// Simulated time at the end of that step (s).
        time_s: f64,
        /// Segment where it was detected.
        segment: usize,
        /// Sub-segment (0-based from the segment's start guide) when one is to blame; for a
        /// joint gap, the sub-segment after the joint (`S` for the joint at the end guide).
        sub_segment: Option<usize>,
        /// Which quantity left its bound.
        quantity: BlowUpQuantity,
        /// Its value (unit of the quantity; NaN or infinite for [`BlowUpQuantity::NonFinite`]).
        value: f64,
        /// The bound it exceeded (same unit).
        bound: f64,
    },
    /// A relaxation used up its simulated-time budget while the cable was still moving.
    #[error(
        "the cable did not come to rest within {steps} steps ({time_s:.3} s simulated): nodes still moved {motion_mm:.4} mm over the last window, more than {threshold_mm:.4} mm",
        motion_mm = .window_motion_m * 1e3,
        threshold_mm = .threshold_m * 1e3
    )]
    NotConverged {
        /// Steps taken.
        steps: usize,
        /// Simulated time (s).
        time_s: f64,
        /// Largest node displacement over the last convergence window (m).
        window_motion_m: f64,
        /// The displacement below which the cable counts as at rest (m).
        threshold_m: f64,
    },
}

/// The quantities watched for a blow-up after every step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlowUpQuantity {
    /// A body's pose or velocity became NaN or infinite (rapier quarantined it, or we saw it).
    NonFinite,
    /// Linear speed of a sub-segment (m/s).
    Speed,
    /// Distance between the two anchors of a joint that should coincide (m).
    JointGap,
    /// Centerline length of the segment over its natural length (1).
    Stretch,
}

impl fmt::Display for BlowUpQuantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BlowUpQuantity::NonFinite => "a non-finite pose or velocity",
            BlowUpQuantity::Speed => "speed (m/s)",
            BlowUpQuantity::JointGap => "joint gap (m)",
            BlowUpQuantity::Stretch => "stretch",
        })
    }
}

/// Shorthand for [`RigidChainError::InvalidInput`].
pub(super) fn invalid(what: impl Into<String>) -> RigidChainError {
    RigidChainError::InvalidInput { what: what.into() }
}
