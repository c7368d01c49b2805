//! A piece through a sliding guide or out of a retraction followed over a motion.

use super::{
    REACH_MARGIN, SPLIT_TOLERANCE_M, Slid, SlideReading, ThroughEquilibrium, evenly, sides,
};
use crate::pose::Pose;
use crate::setup::GuideKind;
use crate::statics::{
    Equilibrium, FarEnd, Holds, RodParameters, SolverOptions, StaticSolver, StaticsError,
    clamp_loads, continuation,
};
use nalgebra::{Point3, Vector3};

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

/// The pieces at a split and the energy's slope and curvature there.
struct Derivatives {
    pieces: Vec<Equilibrium>,
    /// Slope (N) and curvature (N/m); `None` where the range is a point.
    slope: Option<(f64, f64)>,
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
            GuideKind::Retraction { .. } => vec![continuation::follow_guides(
                &self.pieces[0].nodes,
                (&old_through, &old_end),
                (&through, &end),
                self.piece_pitch(0, self.coordinate),
            )],
            _ => vec![
                continuation::follow_guides(
                    &self.pieces[0].nodes,
                    (&old_start, &old_through),
                    (&start, &through),
                    self.piece_pitch(0, self.coordinate),
                ),
                continuation::follow_guides(
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
        let at = self.derivatives(params, &guides, (&carried, &twists), c0, options)?;
        let mut next = c0;
        self.stop_force_n = 0.0;
        if let Some((slope, curvature)) = at.slope {
            let hold = self.friction_holds_n(params, &guides, &at.pieces);
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
            true => at.pieces,
            false => (self.solve_at(params, &guides, (&carried, &twists), next, options)?).1,
        };
        self.coordinate = next;
        self.guides = guides;
        Ok(())
    }

    /// The pieces solved at `c0` from `carried` between `guides`, and (where the range
    /// around it allows) the energy's slope (N) and curvature (N/m) there by finite
    /// differences of [`TRACK_DIFFERENCE_M`]; at a stop only the one-sided slope (curvature 0).
    fn derivatives(
        &mut self,
        params: &RodParameters,
        guides: &(Pose, Pose, Pose),
        (carried, twists): (&[Vec<Point3<f64>>], &[f64]),
        c0: f64,
        options: &SolverOptions,
    ) -> Result<Derivatives, StaticsError> {
        let (low, high) = self.range(guides);
        let (e0, pieces) = self.solve_at(params, guides, (carried, twists), c0, options)?;
        let h = TRACK_DIFFERENCE_M.min(0.5 * (high - low));
        if h <= 0.0 {
            return Ok(Derivatives {
                pieces,
                slope: None,
            });
        }
        let lower = (c0 - h).max(low);
        let upper = (c0 + h).min(high);
        let (e_lower, _) = self.solve_at(params, guides, (carried, twists), lower, options)?;
        let (e_upper, _) = self.solve_at(params, guides, (carried, twists), upper, options)?;
        let slope = (e_upper - e_lower) / (upper - lower);
        // At a stop only one side is known: no curvature, a full step downhill.
        let curvature = match lower < c0 && c0 < upper {
            true => {
                2.0 * ((e_upper - e0) / (upper - c0) - (e0 - e_lower) / (c0 - lower))
                    / (upper - lower)
            }
            false => 0.0,
        };
        Ok(Derivatives {
            pieces,
            slope: Some((slope, curvature)),
        })
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
