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
//! the total energy between the shortest lengths that reach the guide from either side. The
//! cable turns freely in the guide (a ring takes no torque).
//!
//! A retraction system is a sliding guide (its outlet) with a spring behind it instead of a
//! second piece: [`solve_through_retraction`] finds the travel where the spring's force
//! balances the free piece's pull, within the unit's stops.

use super::{
    Equilibrium, FarEnd, Hold, Holds, RodParameters, SolverOptions, StaticSolver, StaticsError,
};
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
    let (start_hold, end_hold) = (params.holds.start, params.holds.end);
    let before = RodParameters {
        holds: Holds {
            start: start_hold,
            end: Hold::Rotating,
        },
        ..*params
    };
    let after = RodParameters {
        holds: Holds {
            start: Hold::Rotating,
            end: end_hold,
        },
        ..*params
    };
    let mut at = |split: f64| -> Result<(f64, [Equilibrium; 2]), StaticsError> {
        let first = piece(
            &mut solver,
            &before,
            (start, &slide.guide),
            split,
            na,
            options,
        )?;
        let rest = slide.total_m - split;
        let second = piece(&mut solver, &after, (&slide.guide, end), rest, nb, options)?;
        Ok((
            first.energy.total_j() + second.energy.total_j(),
            [first, second],
        ))
    };
    let (split_m, evaluations) = least_energy((low, high), &[], |split| Ok(at(split)?.0))?;
    let (energy_j, pieces) = at(split_m)?;
    Ok(SlidEquilibrium {
        split_m,
        pieces,
        energy_j,
        evaluations,
    })
}

/// A retraction system: the cable leaves its outlet (a sliding guide) towards the tool, and
/// a spring inside pulls the cable stored behind the outlet back with `preload_n` plus
/// `rate_n_per_m` per metre pulled out, up to `travel_max_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RetractionUnit {
    /// The outlet's pose: the cable leaves through its origin along its +z.
    pub outlet: Pose,
    /// The spring's force at zero travel, where the unit rests on its stop (N).
    pub preload_n: f64,
    /// How much the force grows per metre of cable pulled out (N/m).
    pub rate_n_per_m: f64,
    /// The most cable the unit can give out (m).
    pub travel_max_m: f64,
}

impl RetractionUnit {
    /// The spring's force at `travel_m` (N).
    pub fn force_n(&self, travel_m: f64) -> f64 {
        self.preload_n + self.rate_n_per_m * travel_m
    }

    /// The spring's energy at `travel_m` from zero travel (J).
    pub fn energy_j(&self, travel_m: f64) -> f64 {
        travel_m * (self.preload_n + 0.5 * self.rate_n_per_m * travel_m)
    }
}

/// The equilibrium of the free piece out of a retraction system.
#[derive(Debug, Clone, PartialEq)]
pub struct RetractedEquilibrium {
    /// Cable pulled out of the unit beyond its rest (m), in `[0, travel_max_m]`.
    pub travel_m: f64,
    /// The free piece from the outlet to the end clamp: `rest_length_m + travel_m` long.
    pub piece: Equilibrium,
    /// The spring's force at that travel (N).
    pub force_n: f64,
    /// Energy evaluations (static solves) the search took.
    pub evaluations: usize,
}

/// The equilibrium of the cable out of `unit`'s outlet to the clamp `end`, `rest_length_m`
/// long at zero travel in `sub_segments`: the travel of least total energy — the free
/// piece's, the spring's and that of the stored cable given out (counted at the outlet's
/// height, so that in equilibrium the spring's force equals the free piece's pull at the
/// outlet; the unit carries the stored cable's weight). At the stops (zero travel, or
/// `travel_max_m`) the stop takes the difference. Fails when even the full travel does not
/// reach `end`.
pub fn solve_through_retraction(
    params: &RodParameters,
    unit: &RetractionUnit,
    end: &Pose,
    (rest_length_m, sub_segments): (f64, usize),
    options: &SolverOptions,
) -> Result<RetractedEquilibrium, StaticsError> {
    let invalid = |what: String| StaticsError::InvalidInput { what };
    let finite = [
        unit.preload_n,
        unit.rate_n_per_m,
        unit.travel_max_m,
        rest_length_m,
    ];
    if sub_segments == 0 || finite.iter().any(|v| !v.is_finite() || *v < 0.0) {
        return Err(invalid(format!(
            "a retraction needs a free piece of sub-segments and finite, non-negative preload,              rate, travel and length ({finite:?})"
        )));
    }
    let reach = (end.translation.vector - unit.outlet.translation.vector).norm();
    let low = (reach * (1.0 + REACH_MARGIN) - rest_length_m).max(0.0);
    if low >= unit.travel_max_m && low > 0.0 {
        return Err(invalid(format!(
            "{:.4} m of free cable with all {:.4} m of the retraction's travel cannot reach from              its outlet to the clamp {reach:.4} m away",
            rest_length_m, unit.travel_max_m
        )));
    }
    let params = RodParameters {
        holds: Holds {
            start: Hold::Rotating,
            end: params.holds.end,
        },
        ..*params
    };
    // The stored cable given out, its weight counted at the outlet.
    let stored_per_m =
        -params.mass_per_length_kg_m * params.gravity_m_s2.dot(&unit.outlet.translation.vector);
    let mut solver = StaticSolver::default();
    let mut at = |travel: f64| -> Result<(f64, Equilibrium), StaticsError> {
        let piece = piece(
            &mut solver,
            &params,
            (&unit.outlet, end),
            rest_length_m + travel,
            sub_segments,
            options,
        )?;
        let energy = piece.energy.total_j() + unit.energy_j(travel) - stored_per_m * travel;
        Ok((energy, piece))
    };
    // The stops within reach: zero travel (when the rest length reaches) and the full one.
    let stops: Vec<f64> = [0.0, unit.travel_max_m]
        .into_iter()
        .filter(|&stop| stop >= low)
        .collect();
    let (travel_m, evaluations) = if low < unit.travel_max_m {
        least_energy((low, unit.travel_max_m), &stops, |travel| Ok(at(travel)?.0))?
    } else {
        (unit.travel_max_m, 0)
    };
    let (_, piece) = at(travel_m)?;
    Ok(RetractedEquilibrium {
        travel_m,
        piece,
        force_n: unit.force_n(travel_m),
        evaluations: evaluations + 1,
    })
}

/// The argument of least `energy` on `[low, high]` (golden-section search to
/// [`SPLIT_TOLERANCE_M`], then compared with the `stops`: ends of the interval where a stop
/// holds the cable), and the evaluations it took.
fn least_energy(
    (low, high): (f64, f64),
    stops: &[f64],
    mut energy: impl FnMut(f64) -> Result<f64, StaticsError>,
) -> Result<(f64, usize), StaticsError> {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (low, high);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (energy(c)?, energy(d)?);
    let mut evaluations = 2;
    while b - a > SPLIT_TOLERANCE_M {
        evaluations += 1;
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - ratio * (b - a);
            fc = energy(c)?;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + ratio * (b - a);
            fd = energy(d)?;
        }
    }
    // A least at a stop: the search closes in on it from inside; the stop itself is exact.
    let inside = 0.5 * (a + b);
    let mut best = (energy(inside)?, inside);
    evaluations += 1;
    for &stop in stops {
        if (stop - inside).abs() <= 2.0 * SPLIT_TOLERANCE_M {
            best = (energy(stop)?, stop);
            evaluations += 1;
        }
    }
    Ok((best.1, evaluations))
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
