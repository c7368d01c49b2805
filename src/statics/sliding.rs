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
    clamp_loads,
};
use crate::geometry::{connect, sag_direction};
use crate::pose::Pose;
use crate::setup::GuideKind;
use nalgebra::{Point3, Vector3};

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

/// Half the window around a previous split or travel searched first (m).
const NEAR_WINDOW_M: f64 = 0.02;

/// [`least_energy`] on the window of ±[`NEAR_WINDOW_M`] around `near` (within `[low, high]`)
/// first, then on the whole range when the least lies at an edge of the window inside it.
fn least_near(
    (low, high): (f64, f64),
    near: Option<f64>,
    stops: &[f64],
    mut energy: impl FnMut(f64) -> Result<f64, StaticsError>,
) -> Result<(f64, usize), StaticsError> {
    let Some(near) = near.filter(|n| n.is_finite()) else {
        return least_energy((low, high), stops, energy);
    };
    let window = (
        (near - NEAR_WINDOW_M).max(low),
        (near + NEAR_WINDOW_M).min(high),
    );
    if window.0 >= window.1 {
        return least_energy((low, high), stops, energy);
    }
    let (at, evaluations) = least_energy(window, stops, &mut energy)?;
    let near_edge = |edge: f64| (at - edge).abs() <= 4.0 * SPLIT_TOLERANCE_M;
    if (window.0 > low && near_edge(window.0)) || (window.1 < high && near_edge(window.1)) {
        let (at, more) = least_energy((low, high), stops, energy)?;
        return Ok((at, evaluations + more));
    }
    Ok((at, evaluations))
}

/// The argument of least `energy` on `[low, high]` (Brent's method: parabolic steps through
/// the three best points, golden-section steps where those do not shrink the bracket, to
/// [`SPLIT_TOLERANCE_M`]), then compared with the `stops` (ends of the interval where a
/// stop holds the cable), and the evaluations it took. The energy of a split is smooth, so
/// the parabolic steps converge superlinearly: 10 to 15 evaluations where golden sections
/// alone take 35.
fn least_energy(
    (low, high): (f64, f64),
    stops: &[f64],
    mut energy: impl FnMut(f64) -> Result<f64, StaticsError>,
) -> Result<(f64, usize), StaticsError> {
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    const MAX_EVALUATIONS: usize = 100;
    let (mut a, mut b) = (low, high);
    let mut x = a + GOLDEN * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = energy(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let mut evaluations = 1;
    // The step before last, and the last one.
    let (mut e, mut d): (f64, f64) = (0.0, 0.0);
    while evaluations < MAX_EVALUATIONS {
        let middle = 0.5 * (a + b);
        let tol = 0.5 * SPLIT_TOLERANCE_M;
        if (x - middle).abs() <= 2.0 * tol - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // The parabola through x, w and v.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let previous = e;
            if p.abs() < (0.5 * q * previous).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = tol.copysign(middle - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= middle { a - x } else { b - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = energy(u)?;
        evaluations += 1;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    // A least at a stop: the search closes in on it from inside; the stop itself is exact.
    let mut best = (fx, x);
    for &stop in stops {
        if (stop - x).abs() <= 4.0 * SPLIT_TOLERANCE_M {
            best = (energy(stop)?, stop);
            evaluations += 1;
        }
    }
    Ok((best.1, evaluations))
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

/// The cable through a sliding guide or out of a retraction followed over a motion,
/// quasi-statically: at each new pose of the clamps the pieces are carried along and
/// solved again, and the split (or travel) moves only where the pull on one side exceeds
/// the other's by more than the guide's friction can hold — Coulomb friction on the force
/// the guide holds the cable across with, `μ·|R⊥|` (the capstan rule for the small turn a
/// guide that holds the cable's direction gives it) — to where the difference is that
/// friction. A retraction's outlet slides freely within its stops.
#[derive(Debug, Clone)]
pub struct SlideTrack {
    kind: GuideKind,
    /// The pieces' sub-segments (one for a retraction's free piece).
    sub_segments: Vec<usize>,
    /// The cable's whole length between the clamps (sliding), or the free piece's at rest
    /// (retraction) (m).
    length_m: f64,
    /// The split (m before the guide) or the travel (m).
    coordinate: f64,
    pieces: Vec<Equilibrium>,
    guides: (Pose, Pose, Pose),
    solver: StaticSolver,
    /// The pull a retraction's end stop takes (N).
    stop_force_n: f64,
}

/// Step (m) of the finite differences of the energy in the split.
const TRACK_DIFFERENCE_M: f64 = 1e-3;
/// The most a split or travel moves in one step of the motion (m): the cable slides at most
/// 10 mm per step, so one Newton step on the split never leaps to another branch.
const TRACK_MAX_MOVE_M: f64 = 0.01;

impl SlideTrack {
    /// The track started from `solved` ([`solve_through`]) between `guides` (start clamp,
    /// guide, end clamp).
    pub fn start(
        kind: GuideKind,
        solved: &ThroughEquilibrium,
        guides: (Pose, Pose, Pose),
    ) -> SlideTrack {
        let pieces = solved.pieces.clone();
        let total: usize = solved.sub_segments.iter().sum();
        let (coordinate, length_m) = match solved.slid {
            Slid::Split { before_m } => (before_m, solved.pitch_m * total as f64),
            Slid::Travel { travel_m, .. } => (
                travel_m,
                solved.pitch_m * solved.sub_segments[0] as f64 - travel_m,
            ),
        };
        SlideTrack {
            kind,
            sub_segments: solved.sub_segments.clone(),
            length_m,
            coordinate,
            pieces,
            guides,
            solver: StaticSolver::default(),
            stop_force_n: 0.0,
        }
    }

    /// Where it is now: split or travel, spring force, the end stop's pull.
    pub fn reading(&self) -> SlideReading {
        SlideReading {
            amount_m: self.coordinate,
            force_n: self.force_n(),
            stop_force_n: self.stop_force_n,
        }
    }

    /// The split (sliding: m of cable before the guide) or travel (retraction, m) now.
    pub fn coordinate(&self) -> f64 {
        self.coordinate
    }

    /// The cable as the limits judge it now ([`ThroughEquilibrium::nodes`]) and the pitch of
    /// those nodes.
    pub fn nodes(&self) -> (Vec<Point3<f64>>, f64) {
        match self.kind {
            GuideKind::Retraction { .. } => (
                self.pieces[0].nodes.clone(),
                (self.length_m + self.coordinate) / self.sub_segments[0] as f64,
            ),
            _ => {
                let total: usize = self.sub_segments.iter().sum();
                let polygon: Vec<Point3<f64>> = (self.pieces[0].nodes.iter())
                    .chain(self.pieces[1].nodes.iter().skip(1))
                    .copied()
                    .collect();
                (evenly(&polygon, total), self.length_m / total as f64)
            }
        }
    }

    /// The retraction's outlet now, where its free piece starts; `None` for a sliding guide.
    pub fn outlet(&self) -> Option<Pose> {
        matches!(self.kind, GuideKind::Retraction { .. }).then_some(self.guides.1)
    }

    /// The spring's force now (N); `None` for a sliding guide.
    pub fn force_n(&self) -> Option<f64> {
        match self.kind {
            GuideKind::Retraction {
                preload_n,
                rate_n_per_m,
                ..
            } => Some(preload_n + rate_n_per_m * self.coordinate),
            _ => None,
        }
    }

    /// Follows the clamps and the guide to `guides`: the pieces carried along, the split or
    /// travel moved by one Newton step on the energy's derivative towards the friction's
    /// edge where the friction does not hold it (at most [`TRACK_MAX_MOVE_M`]), the pieces
    /// solved there.
    pub fn step(
        &mut self,
        params: &RodParameters,
        guides: (Pose, Pose, Pose),
        options: &SolverOptions,
    ) -> Result<(), StaticsError> {
        let (start, through, end) = guides;
        let (old_start, old_through, old_end) = self.guides;
        let carried: Vec<Vec<Point3<f64>>> = match self.kind {
            GuideKind::Retraction { .. } => vec![super::continuation::follow_guides(
                &self.pieces[0].nodes,
                (&old_through, &old_end),
                (&through, &end),
                self.piece_pitch(0, self.coordinate),
            )],
            _ => vec![
                super::continuation::follow_guides(
                    &self.pieces[0].nodes,
                    (&old_start, &old_through),
                    (&start, &through),
                    self.piece_pitch(0, self.coordinate),
                ),
                super::continuation::follow_guides(
                    &self.pieces[1].nodes,
                    (&old_through, &old_end),
                    (&through, &end),
                    self.piece_pitch(1, self.coordinate),
                ),
            ],
        };
        let twists: Vec<f64> = self.pieces.iter().map(|p| p.twist_rad).collect();
        let (low, high) = self.range(&guides);
        let c0 = self.coordinate.clamp(low, high);
        let solve = |track: &mut SlideTrack, c: f64| {
            track.solve_at(params, &guides, (&carried, &twists), c, options)
        };
        let (e0, pieces0) = solve(self, c0)?;
        let h = TRACK_DIFFERENCE_M.min(0.5 * (high - low));
        let mut next = c0;
        self.stop_force_n = 0.0;
        if h > 0.0 {
            let lower = (c0 - h).max(low);
            let upper = (c0 + h).min(high);
            let (e_lower, _) = solve(self, lower)?;
            let (e_upper, _) = solve(self, upper)?;
            let slope = (e_upper - e_lower) / (upper - lower);
            // At a stop only one side is known: no curvature, a full step downhill.
            let curvature = match lower < c0 && c0 < upper {
                true => {
                    2.0 * ((e_upper - e0) / (upper - c0) - (e0 - e_lower) / (c0 - lower))
                        / (upper - lower)
                }
                false => 0.0,
            };
            let hold = self.friction_holds_n(params, &guides, &pieces0);
            let at_end_stop = matches!(self.kind, GuideKind::Retraction { travel_max_m, .. }
                if c0 >= travel_max_m - SPLIT_TOLERANCE_M);
            if at_end_stop && slope < 0.0 {
                self.stop_force_n = -slope;
            }
            if slope.abs() > hold {
                let target = hold.copysign(slope);
                let newton = match curvature > 0.0 {
                    true => -(slope - target) / curvature,
                    false => -TRACK_MAX_MOVE_M.copysign(slope),
                };
                next = (c0 + newton.clamp(-TRACK_MAX_MOVE_M, TRACK_MAX_MOVE_M)).clamp(low, high);
            }
        }
        self.pieces = match next == c0 {
            true => pieces0,
            false => solve(self, next)?.1,
        };
        self.coordinate = next;
        self.guides = guides;
        Ok(())
    }

    /// The pitch of piece `k` at split or travel `c` (m).
    fn piece_pitch(&self, k: usize, c: f64) -> f64 {
        let n = self.sub_segments[k] as f64;
        match (self.kind, k) {
            (GuideKind::Retraction { .. }, _) => (self.length_m + c) / n,
            (_, 0) => c / n,
            _ => (self.length_m - c) / n,
        }
    }

    /// The splits (or travels) the pieces reach at `guides` with, within a retraction's stops.
    fn range(&self, (start, through, end): &(Pose, Pose, Pose)) -> (f64, f64) {
        let reach = |a: &Pose, b: &Pose| {
            (b.translation.vector - a.translation.vector).norm() * (1.0 + REACH_MARGIN)
        };
        match self.kind {
            GuideKind::Retraction { travel_max_m, .. } => {
                ((reach(through, end) - self.length_m).max(0.0), travel_max_m)
            }
            _ => (reach(start, through), self.length_m - reach(through, end)),
        }
    }

    /// The pieces' energy at split or travel `c` (with the spring's and the stored cable's
    /// for a retraction), and the pieces, each solved from its `carried` shape.
    fn solve_at(
        &mut self,
        params: &RodParameters,
        (start, through, end): &(Pose, Pose, Pose),
        (carried, twists): (&[Vec<Point3<f64>>], &[f64]),
        c: f64,
        options: &SolverOptions,
    ) -> Result<(f64, Vec<Equilibrium>), StaticsError> {
        let [before, after] = sides(&params.holds);
        let ends: Vec<(Pose, Pose, Holds)> = match self.kind {
            GuideKind::Retraction { .. } => vec![(*through, *end, after)],
            _ => vec![(*start, *through, before), (*through, *end, after)],
        };
        let mut pieces = Vec::with_capacity(ends.len());
        let mut energy = 0.0;
        for (k, (a, b, holds)) in ends.into_iter().enumerate() {
            let piece_params = RodParameters {
                pitch_m: self.piece_pitch(k, c),
                holds,
                ..*params
            };
            let piece = self.solver.solve(
                &piece_params,
                &a,
                &FarEnd::Clamped(b),
                &carried[k],
                Some(twists[k]),
                options,
            )?;
            energy += piece.energy.total_j();
            pieces.push(piece);
        }
        if let GuideKind::Retraction {
            preload_n,
            rate_n_per_m,
            ..
        } = self.kind
        {
            let stored_per_m =
                -params.mass_per_length_kg_m * params.gravity_m_s2.dot(&through.translation.vector);
            energy += c * (preload_n + 0.5 * rate_n_per_m * c) - stored_per_m * c;
        }
        Ok((energy, pieces))
    }

    /// The difference of pulls a sliding guide's friction holds (N): `μ` times the force
    /// across the guide's axis the two pieces' loads on it add up to; 0 for a retraction.
    fn friction_holds_n(
        &self,
        params: &RodParameters,
        (start, through, end): &(Pose, Pose, Pose),
        pieces: &[Equilibrium],
    ) -> f64 {
        let GuideKind::Sliding { friction } = self.kind else {
            return 0.0;
        };
        if friction == 0.0 {
            return 0.0;
        }
        let load = |k: usize, (a, b): (&Pose, &Pose)| {
            let params = RodParameters {
                pitch_m: self.piece_pitch(k, self.coordinate),
                ..*params
            };
            clamp_loads(&params, a, Some(b), &pieces[k].nodes, pieces[k].twist_rad)
        };
        let (_, before) = load(0, (start, through));
        let (after, _) = load(1, (through, end));
        let before = before.map_or(Vector3::zeros(), |l| Vector3::from(l.force_n));
        let across = before + Vector3::from(after.force_n);
        let axis = through.rotation * Vector3::z();
        friction * (across - axis * across.dot(&axis)).norm()
    }
}
