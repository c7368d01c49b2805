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

mod least;
mod track;

pub use track::SlideTrack;

use super::{
    Equilibrium, FarEnd, Hold, Holds, RodParameters, SolverOptions, StaticSolver, StaticsError,
};
use crate::geometry::{connect, sag_direction};
use crate::pose::Pose;
use crate::setup::GuideKind;
use least::least_near;
use nalgebra::Point3;

/// A sliding guide between two clamps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slide {
    /// The guide's pose: the cable passes through its origin along its +z.
    pub guide: Pose,
    /// The cable's length from the start clamp to the end clamp through the guide (m).
    pub total_m: f64,
    /// Sub-segments of the piece before the guide and of the piece after it.
    pub sub_segments: (usize, usize),
    /// A split to search around first (m): the previous pose's, in a sweep; the whole range
    /// when the least lies at the edge of the window around it.
    pub near_m: Option<f64>,
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
    let [before, after] = sides(&params.holds).map(|holds| RodParameters { holds, ..*params });
    // Each split starts from the least energy's pieces so far.
    let mut best: Option<(f64, [Equilibrium; 2])> = None;
    let mut at = |split: f64| -> Result<(f64, [Equilibrium; 2]), StaticsError> {
        let warm = best.as_ref().map(|(_, pieces)| pieces);
        let first = piece(
            &mut solver,
            &before,
            (start, &slide.guide),
            (split, na),
            warm.map(|p| &p[0]),
            options,
        )?;
        let rest = slide.total_m - split;
        let second = piece(
            &mut solver,
            &after,
            (&slide.guide, end),
            (rest, nb),
            warm.map(|p| &p[1]),
            options,
        )?;
        let energy = first.energy.total_j() + second.energy.total_j();
        if best.as_ref().is_none_or(|(least, _)| energy < *least) {
            best = Some((energy, [first.clone(), second.clone()]));
        }
        Ok((energy, [first, second]))
    };
    let (split_m, evaluations) =
        least_near((low, high), slide.near_m, &[], |split| Ok(at(split)?.0))?;
    let (energy_j, pieces) = at(split_m)?;
    Ok(SlidEquilibrium {
        split_m,
        pieces,
        energy_j,
        evaluations,
    })
}

impl SlidEquilibrium {
    /// Both pieces as one cable from the start clamp to the end clamp in `sub_segments`
    /// equal steps along it (the pieces' pitches differ with the split; the limits are
    /// judged on one pitch): points on the two polygons at equal arc lengths, the clamps'
    /// ends kept. The polygon's corners are cut by at most a pitch's chord error.
    pub fn nodes_evenly(&self, sub_segments: usize) -> Vec<Point3<f64>> {
        let [first, second] = &self.pieces;
        let polygon: Vec<Point3<f64>> = (first.nodes.iter())
            .chain(second.nodes.iter().skip(1))
            .copied()
            .collect();
        evenly(&polygon, sub_segments)
    }
}

/// `count + 1` points along `polygon` at equal arc lengths, its ends kept.
pub fn evenly(polygon: &[Point3<f64>], count: usize) -> Vec<Point3<f64>> {
    let (Some(first), Some(last)) = (polygon.first(), polygon.last()) else {
        return Vec::new();
    };
    if count == 0 || polygon.len() < 2 {
        return vec![*first];
    }
    let edges: Vec<f64> = polygon.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let total: f64 = edges.iter().sum();
    let mut points = Vec::with_capacity(count + 1);
    points.push(*first);
    let (mut edge, mut walked) = (0, 0.0);
    for k in 1..count {
        let target = total * k as f64 / count as f64;
        while edge + 1 < edges.len() && walked + edges[edge] < target {
            walked += edges[edge];
            edge += 1;
        }
        let t = match edges[edge] > 0.0 {
            true => ((target - walked) / edges[edge]).clamp(0.0, 1.0),
            false => 0.0,
        };
        points.push(polygon[edge] + (polygon[edge + 1] - polygon[edge]) * t);
    }
    points.push(*last);
    points
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
    near_m: Option<f64>,
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
        holds: sides(&params.holds)[1],
        ..*params
    };
    // The stored cable given out, its weight counted at the outlet.
    let stored_per_m =
        -params.mass_per_length_kg_m * params.gravity_m_s2.dot(&unit.outlet.translation.vector);
    let mut solver = StaticSolver::default();
    // Each travel starts from the least energy's piece so far.
    let mut best: Option<(f64, Equilibrium)> = None;
    let mut at = |travel: f64| -> Result<(f64, Equilibrium), StaticsError> {
        let piece = piece(
            &mut solver,
            &params,
            (&unit.outlet, end),
            (rest_length_m + travel, sub_segments),
            best.as_ref().map(|(_, piece)| piece),
            options,
        )?;
        let energy = piece.energy.total_j() + unit.energy_j(travel) - stored_per_m * travel;
        if best.as_ref().is_none_or(|(least, _)| energy < *least) {
            best = Some((energy, piece.clone()));
        }
        Ok((energy, piece))
    };
    // The stops within reach: zero travel (when the rest length reaches) and the full one.
    let stops: Vec<f64> = [0.0, unit.travel_max_m]
        .into_iter()
        .filter(|&stop| stop >= low)
        .collect();
    let (travel_m, evaluations) = if low < unit.travel_max_m {
        least_near((low, unit.travel_max_m), near_m, &stops, |travel| {
            Ok(at(travel)?.0)
        })?
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

/// How the sides of a piece held by its clamps as `holds` are held around a guide the cable
/// slides (and turns) through: the side before it, the side after it.
fn sides(holds: &Holds) -> [Holds; 2] {
    [
        Holds {
            start: holds.start,
            end: Hold::Rotating,
        },
        Holds {
            start: Hold::Rotating,
            end: holds.end,
        },
    ]
}

/// How near (relative) a piece's length must be to the warm start's for the search to start
/// from it.
const WARM_SHARE: f64 = 0.02;

/// The equilibrium of a piece of `length_m` in `sub_segments` between `guides`: from `warm`
/// (the nearest split's solution, re-pitched by the solver) when given and it converges,
/// else from the connected geometry.
fn piece(
    solver: &mut StaticSolver,
    params: &RodParameters,
    (start, end): (&Pose, &Pose),
    (length_m, sub_segments): (f64, usize),
    warm: Option<&Equilibrium>,
    options: &SolverOptions,
) -> Result<Equilibrium, StaticsError> {
    let pitch_m = length_m / sub_segments as f64;
    let params = RodParameters { pitch_m, ..*params };
    let far = FarEnd::Clamped(*end);
    // Only a near length: a start shape far from its pitch costs Newton more than the
    // connected geometry does.
    let near = |w: &&Equilibrium| {
        let warm_m: f64 = w.nodes.windows(2).map(|e| (e[1] - e[0]).norm()).sum();
        w.nodes.len() == sub_segments + 1 && (warm_m - length_m).abs() <= WARM_SHARE * length_m
    };
    if let Some(warm) = warm.filter(near)
        && let Ok(solved) = solver.solve(
            &params,
            start,
            &far,
            &warm.nodes,
            Some(warm.twist_rad),
            options,
        )
    {
        return Ok(solved);
    }
    let sag = sag_direction(&params.gravity_m_s2);
    let shape = connect(start, end, sub_segments, pitch_m, &sag).map_err(|e| {
        StaticsError::InvalidInput {
            what: format!("no start shape for a piece of {length_m:.4} m: {e}"),
        }
    })?;
    solver.solve(
        &params,
        start,
        &far,
        &shape.nodes,
        Some(shape.twist_correction_rad),
        options,
    )
}

/// Where the cable through a sliding guide or a retraction's outlet settled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Slid {
    /// Through a sliding guide: the cable's length before the guide (m).
    Split {
        /// From the start clamp to the guide (m).
        before_m: f64,
    },
    /// Out of a retraction: the cable pulled out beyond the unit's rest, and the spring's
    /// force there.
    Travel {
        /// Travel (m), within the unit's stops.
        travel_m: f64,
        /// Spring force (N).
        force_n: f64,
    },
}

impl Slid {
    /// The reading of a cable at rest where it settled (no stop taking a pull).
    pub fn reading(&self) -> SlideReading {
        let (amount_m, force_n) = match *self {
            Slid::Split { before_m } => (before_m, None),
            Slid::Travel { travel_m, force_n } => (travel_m, Some(force_n)),
        };
        SlideReading {
            amount_m,
            force_n,
            stop_force_n: 0.0,
        }
    }
}

/// A piece through a sliding guide or out of a retraction at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlideReading {
    /// The cable before the sliding guide, or the retraction's travel (m).
    pub amount_m: f64,
    /// The retraction's spring force (N); `None` for a sliding guide.
    pub force_n: Option<f64>,
    /// How much harder than its spring the cable pulls on a retraction at its end stop: the
    /// force the stop takes (N); 0 off the stop.
    pub stop_force_n: f64,
}

/// The cable of one piece through a sliding guide or out of a retraction, as the limits
/// judge it.
#[derive(Debug, Clone, PartialEq)]
pub struct ThroughEquilibrium {
    /// The free cable: from the start clamp through the sliding guide to the end clamp at
    /// equal steps ([`SlidEquilibrium::nodes_evenly`]), or from a retraction's outlet to
    /// the end clamp.
    pub nodes: Vec<Point3<f64>>,
    /// The cable length between two nodes (m).
    pub pitch_m: f64,
    /// Where the nodes start when not at the start clamp: the retraction's outlet.
    pub from: Option<Pose>,
    /// The split or the travel.
    pub slid: Slid,
    /// Static solves taken.
    pub solves: usize,
    /// The pieces as solved: before and after a sliding guide, or the free piece out of a
    /// retraction.
    pub pieces: Vec<Equilibrium>,
    /// Their sub-segments, in the order of `pieces`.
    pub sub_segments: Vec<usize>,
}

/// The equilibrium of a piece of `sub_segments` at `pitch_m` from the clamp `start` through
/// the guide `through` of `kind` (a sliding guide, or a retraction's outlet whose stored
/// cable at rest is `stored_sub_segments` of them) to the clamp `end`. A sliding guide's
/// pieces get sub-segments in proportion to their straight runs, then once more in
/// proportion to the split found when their pitches differ by more than a quarter. `near_m`:
/// a split or travel to search around first (a sweep's previous pose's).
pub fn solve_through(
    params: &RodParameters,
    (kind, stored_sub_segments): (GuideKind, usize),
    (start, through, end): (&Pose, &Pose, &Pose),
    (sub_segments, pitch_m): (usize, f64),
    near_m: Option<f64>,
    options: &SolverOptions,
) -> Result<ThroughEquilibrium, StaticsError> {
    let invalid = |what: String| StaticsError::InvalidInput { what };
    let total_m = sub_segments as f64 * pitch_m;
    match kind {
        GuideKind::Sliding { .. } => {
            if sub_segments < 2 {
                return Err(invalid(format!(
                    "{sub_segments} sub-segments cannot pass through a sliding guide"
                )));
            }
            let reach = |a: &Pose, b: &Pose| (b.translation.vector - a.translation.vector).norm();
            let share = |before: f64| {
                ((sub_segments as f64 * before).round() as usize).clamp(1, sub_segments - 1)
            };
            let runs = reach(start, through) + reach(through, end);
            let mut before = share(reach(start, through) / runs.max(f64::MIN_POSITIVE));
            let mut solves = 0;
            loop {
                let slide = Slide {
                    guide: *through,
                    total_m,
                    sub_segments: (before, sub_segments - before),
                    near_m,
                };
                let solved = solve_through_slide(params, start, &slide, end, options)?;
                solves += 2 * solved.evaluations;
                let pitches = (
                    solved.split_m / before as f64,
                    (total_m - solved.split_m) / (sub_segments - before) as f64,
                );
                let again = share(solved.split_m / total_m);
                if pitches.0.max(pitches.1) <= 1.25 * pitches.0.min(pitches.1)
                    || again == before
                    || solves > 2 * MAX_SPLIT_EVALUATIONS
                {
                    return Ok(ThroughEquilibrium {
                        nodes: solved.nodes_evenly(sub_segments),
                        pitch_m,
                        from: None,
                        slid: Slid::Split {
                            before_m: solved.split_m,
                        },
                        solves,
                        pieces: solved.pieces.to_vec(),
                        sub_segments: vec![before, sub_segments - before],
                    });
                }
                before = again;
            }
        }
        GuideKind::Retraction {
            preload_n,
            rate_n_per_m,
            travel_max_m,
        } => {
            let Some(free) = sub_segments
                .checked_sub(stored_sub_segments)
                .filter(|&n| n > 0)
            else {
                return Err(invalid(format!(
                    "{sub_segments} sub-segments leave none free beyond the {stored_sub_segments} \
                     stored in the retraction"
                )));
            };
            let unit = RetractionUnit {
                outlet: *through,
                preload_n,
                rate_n_per_m,
                travel_max_m,
            };
            let rest_m = free as f64 * pitch_m;
            let solved =
                solve_through_retraction(params, &unit, end, (rest_m, free), near_m, options)?;
            Ok(ThroughEquilibrium {
                nodes: solved.piece.nodes.clone(),
                pitch_m: (rest_m + solved.travel_m) / free as f64,
                from: Some(*through),
                slid: Slid::Travel {
                    travel_m: solved.travel_m,
                    force_n: solved.force_n,
                },
                solves: solved.evaluations,
                pieces: vec![solved.piece],
                sub_segments: vec![free],
            })
        }
        other => Err(invalid(format!(
            "a {} clamp is not a guide the cable slides through",
            other.word()
        ))),
    }
}

/// Energy evaluations one split search may take before the pitches are left as they are.
const MAX_SPLIT_EVALUATIONS: usize = 100;
