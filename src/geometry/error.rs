//! Why a connected geometry cannot be built, and the bound on its size: shared by the input
//! checks ([`super::guides`]) and the construction ([`super::connected`]).

/// Largest accepted sub-segment count; bounds the memory of one connected geometry.
pub const MAX_SUB_SEGMENTS: usize = 1_000_000;

/// Why two guides cannot be connected by the requested cable.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ConnectError {
    /// The guides are farther apart than the cable's natural length.
    #[error(
        "segment too short: guides are {distance_mm:.1} mm apart but the cable is {natural_mm:.1} mm long (would need stretch {required_stretch:.3})",
        distance_mm = .distance_m * 1e3,
        natural_mm = .natural_length_m * 1e3
    )]
    TooShort {
        /// Distance between the guide origins (m).
        distance_m: f64,
        /// Natural cable length `S·l` (m).
        natural_length_m: f64,
        /// `distance / (S·l)`: the stretch ratio the cable would need.
        required_stretch: f64,
    },
    /// Zero sub-segments, a non-positive or non-finite pitch, a non-finite guide pose or sag
    /// direction.
    #[error("invalid connected-geometry input: {what}")]
    InvalidInput {
        /// What is wrong, for people.
        what: String,
    },
    /// No rigid chain found (a single sub-segment between guides not exactly `l` apart, or a
    /// root find or projection that failed; the latter is not expected for valid input).
    #[error("no connected geometry found: {reason}")]
    NoSolution {
        /// What failed, for people.
        reason: String,
    },
}
