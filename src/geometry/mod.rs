//! Connected geometry of a cable segment: the cubic Hermite curve between two guide frames
//! (optionally bowed towards the sag direction), its rotation-minimizing frames, and the
//! discrete rigid-link cable placed on it.
//!
//! - [`hermite`]: the curve, its arc length, the shape parameter (tangent scale α or bow
//!   height β) for a given length, and nodes at equal arc length.
//! - `chain`: projection of nodes onto the rigid-chain constraints, bending energy.
//! - [`rmf`]: rotation-minimizing frames by double reflection.
//! - `frames`: node frames from guide to guide (RMF plus a linear twist).
//! - `guides`: validation of the input of [`connect`].
//! - [`connected`]: [`connect`], which puts `S` sub-segments of pitch `l` between two guides.
//!
//! See `docs/connected-geometry.md` for the algorithm, conventions and measured accuracy.

mod chain;
pub mod connected;
mod error;
pub(crate) mod frames;
mod guides;
pub mod hermite;
pub mod rmf;

pub use connected::{
    COINCIDENT_GUIDES_M, ConnectError, ConnectedGeometry, CurveFamily, connect, reaches,
    sag_direction,
};
pub use hermite::{CurveParameter, HermiteCurve};
pub use rmf::double_reflection;
