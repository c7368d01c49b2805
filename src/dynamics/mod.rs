//! Dynamics of the cable: the discrete elastic rod of the statics (module
//! [`statics`](crate::statics)) with its lumped masses, integrated in time by an implicit
//! method while its guides move — the engine of the motion test.
//!
//! **One cable model.** A step does not approximate the statics' energy with other springs
//! or bodies: it minimizes the very same energy plus an inertial term,
//!
//! ```text
//! x_(n+1) = argmin  E(x) + Σ_k m_k |x_k − x̂_k|² / (2 β²)
//! ```
//!
//! whose stationarity condition is the implicit equation of motion `m ẍ = −∇E(x)` (gravity
//! is part of `E`). With the backward differentiation formula of order 2 (BDF2),
//! `β = 2h/3` and `x̂ = (4x_n − x_(n−1))/3 + β (4v_n − v_(n−1))/3`; the first step after a
//! start (or a retried one) is backward Euler, `β = h`, `x̂ = x_n + h v_n`. Newton's method
//! on the same banded system as the statics (warm-started from `x_n + h v_n`) solves it.
//! Consequences, by construction:
//!
//! - a cable at rest at its static equilibrium stays there exactly (the inertial term and
//!   the forces vanish, Newton takes no step);
//! - as the motion slows down, the accelerations and with them the inertial forces vanish,
//!   and every step is a static solve warm-started from the last one;
//! - any stiffness a cable can have is stable: an implicit step has no stability limit, so
//!   the time step is chosen for accuracy, not for the stiffest spring.
//!
//! The twist is quasi-static, as in the statics: the cable's rotational inertia about its
//! own axis is negligible (for an 8 mm cable, `ρ r²/2` ≈ 2e-6 kg·m of a 0.26 kg/m cable),
//! so the twist is uniform at every instant and follows the guides.
//!
//! BDF2 is second-order accurate and L-stable: it damps oscillations at the step frequency
//! (the axial and fine bending modes the discretization adds) and keeps the slow ones the
//! motion test is about (a 1–5 Hz swinging loop loses < 1e-3 of its amplitude per period
//! at the default step). No other damping is added: a real cable damps more, so the test
//! is, if anything, strict.
//!
//! Contact is not a force here: the motion test's clearance threshold is ≥ 0, so the first
//! contact already fails a candidate; the clearance is measured exactly at every step
//! (module [`stress`](crate::stress)).
//!
//! - [`IntegratorSettings`]: the time step and the Newton stopping rule.
//! - [`SegmentDynamics`]: one segment between two guides (or a cantilever), stepped with
//!   the guides' poses at the end of each step.

mod integrator;

pub use integrator::{DynamicsError, IntegratorSettings, SegmentDynamics, StepReport};
