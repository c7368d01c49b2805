//! Connected geometry of a cable segment: the cubic Hermite curve between two guide frames,
//! its rotation-minimizing frames, and the discrete rigid-link cable placed on it.
//!
//! - [`hermite`]: the curve, its arc length and the tangent scale α for a given length.
//! - [`rmf`]: rotation-minimizing frames by double reflection.
//! - [`connected`]: [`connect`], which puts `S` sub-segments of pitch `l` between two guides.
//!
//! See `docs/connected-geometry.md` for the algorithm, conventions and measured accuracy.

pub mod connected;
pub mod hermite;
pub mod rmf;

pub use connected::{ConnectError, ConnectedGeometry, connect};
pub use hermite::HermiteCurve;
pub use rmf::double_reflection;
