//! Two pieces of one cable through a sliding guide: a ring (or roller) that holds the cable's
//! place and direction and lets it slide through. The cable's total length between the two
//! outer clamps is given; how much of it lies on either side of the guide is not: the
//! equilibrium is the split that minimises the total energy, each piece in its own
//! equilibrium at that split. Without friction that is where the pieces pull equally on the
//! guide along its axis (the energy's derivative with respect to the split is the difference
//! of the two axial forces there, plus that of the bending energy densities, which a limp
//! cable does not have).
//!
//! Each piece keeps its number of sub-segments; its pitch is its share of the length over
//! that number, so the split is continuous. The split is found by a golden-section search on
//! the total energy between the shortest lengths that reach the guide from either side.

use super::{Equilibrium, FarEnd, RodParameters, SolverOptions, StaticSolver, StaticsError};
use crate::geometry::{connect, sag_direction};
use crate::pose::Pose;

/// A sliding guide between two clamps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slide {
    /// The guide's pose: the cable passes through its origin along its +z.
    pub guide: Pose,
    /// The cable's length from the start clamp to the end clamp through the guide (m).
    pub total_m: f64,
    /// Sub-segments of the piece before the guide and of the piece after it.
    pub sub_segments: (usize, usize),
}

/// The equilibrium of two pieces through a sliding guide.
#[derive(Debug, Clone, PartialEq)]
pub struct SlidEquilibrium {
    /// The length of the piece before the guide (m); the rest is after it.
    pub split_m: f64,
    /// The piece from the start clamp to the guide, and the one from the guide to the end
    /// clamp.
    pub pieces: [Equilibrium; 2],
    /// Total potential energy of both (J).
    pub energy_j: f64,
    /// Energy evaluations (pairs of static solves) the search took.
    pub evaluations: usize,
}

/// Splits the golden-section search resolves to (m): far below the millimetres the limits
/// are judged on.
const SPLIT_TOLERANCE_M: f64 = 1e-7;

/// Gap kept from the lengths that just reach the guide (relative): a taut piece is a stiff
/// problem with nothing to learn.
const REACH_MARGIN: f64 = 1e-4;

/// The equilibrium of the cable from `start` through `slide` to `end` under `params` (its
/// pitch ignored: each piece's follows from the split).
pub fn solve_through_slide(
    params: &RodParameters,
    start: &Pose,
    slide: &Slide,
    end: &Pose,
    options: &SolverOptions,
) -> Result<SlidEquilibrium, StaticsError> {
    let invalid = |what: String| StaticsError::InvalidInput { what };
    let (na, nb) = slide.sub_segments;
    if na == 0 || nb == 0 {
        return Err(invalid(
            "each side of a sliding guide needs sub-segments".into(),
        ));
    }
    let reach = |a: &Pose, b: &Pose| (b.translation.vector - a.translation.vector).norm();
    let low = reach(start, &slide.guide) * (1.0 + REACH_MARGIN);
    let high = slide.total_m - reach(&slide.guide, end) * (1.0 + REACH_MARGIN);
    if !(slide.total_m.is_finite() && low < high) {
        return Err(invalid(format!(
            "{:.4} m of cable cannot reach from the start clamp through the sliding guide to \
             the end clamp ({:.4} m and {:.4} m in straight lines)",
            slide.total_m,
            reach(start, &slide.guide),
            reach(&slide.guide, end)
        )));
    }
    let mut solver = StaticSolver::default();
    let mut evaluations = 0;
    let mut at = |split: f64| -> Result<(f64, [Equilibrium; 2]), StaticsError> {
        evaluations += 1;
        let first = piece(
            &mut solver,
            params,
            (start, &slide.guide),
            split,
            na,
            options,
        )?;
        let rest = slide.total_m - split;
        let second = piece(&mut solver, params, (&slide.guide, end), rest, nb, options)?;
        Ok((
            first.energy.total_j() + second.energy.total_j(),
            [first, second],
        ))
    };
    // Golden-section search for the least energy over [low, high].
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (low, high);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (at(c)?.0, at(d)?.0);
    while b - a > SPLIT_TOLERANCE_M {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - ratio * (b - a);
            fc = at(c)?.0;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + ratio * (b - a);
            fd = at(d)?.0;
        }
    }
    let split_m = 0.5 * (a + b);
    let (energy_j, pieces) = at(split_m)?;
    Ok(SlidEquilibrium {
        split_m,
        pieces,
        energy_j,
        evaluations,
    })
}

/// The equilibrium of a piece of `length_m` in `sub_segments` between `guides`, from the
/// connected geometry.
fn piece(
    solver: &mut StaticSolver,
    params: &RodParameters,
    (start, end): (&Pose, &Pose),
    length_m: f64,
    sub_segments: usize,
    options: &SolverOptions,
) -> Result<Equilibrium, StaticsError> {
    let pitch_m = length_m / sub_segments as f64;
    let sag = sag_direction(&params.gravity_m_s2);
    let shape = connect(start, end, sub_segments, pitch_m, &sag).map_err(|e| {
        StaticsError::InvalidInput {
            what: format!("no start shape for a piece of {length_m:.4} m: {e}"),
        }
    })?;
    let params = RodParameters { pitch_m, ..*params };
    solver.solve(
        &params,
        start,
        &FarEnd::Clamped(*end),
        &shape.nodes,
        Some(shape.twist_correction_rad),
        options,
    )
}
