//! The *connected geometry* of a cable segment: an initial shape that joins two guide frames
//! with exactly the cable's natural length, the start of the static equilibrium solve.
//!
//! The cable is `S` rigid sub-segments of pitch `l`: `S + 1` nodes, node 0 and node `S` at the
//! guide origins, every adjacent pair exactly `l` apart. Two candidate curves are built, and
//! the less bent one is used:
//!
//! - **Hermite** (the paper's curve): tangents `α v0`, `α v1` with `α` such that the arc length
//!   is `S·l`.
//! - **Bowed**, only with slack (`α > d`, `d = |P1 − P0|`): the Hermite curve at `α = d` plus
//!   a bow `β n w(t)`, `w = 16 t²(1 − t)²`, towards the sag direction (made perpendicular to
//!   the chord), with `β` such that the arc length is `S·l`. With coaxial guides the Hermite
//!   curve can only lengthen by folding back along the axis (cusps, 180° kinks); the bow gives
//!   the single smooth arch a hanging cable takes.
//!
//! The candidate curve with the smaller continuous bending energy `∫ κ² ds` is chosen before
//! any node is placed (ties, also two infinite energies of cusped curves: Hermite); the
//! discrete `Σ θ²/l` of a placed chain converges to it. Its nodes are placed at equal arc
//! length and then moved by the minimum-norm Gauss–Newton projection onto the rigid-chain
//! constraints (module `chain`): arc-length nodes have chords short by `≈ l³κ²/24`, and the
//! projection lengthens them by moving the nodes slightly off the curve. If that projection
//! fails, the other candidate is placed instead.
//!
//! Frames are rotation-minimizing frames along the nodes, fed with the exact curve tangents at
//! the nodes' parameters, from the start guide's x axis; the twist left at the end guide is
//! spread linearly so that the first and last frames are the guide orientations.

use nalgebra::{Point3, Rotation3, Unit, Vector3};

use super::chain::project_onto_rigid_chain;
pub use super::error::{ConnectError, MAX_SUB_SEGMENTS};
use super::frames::guided_frames;
use super::guides::{GuidePair, check_cable, check_sag};
use super::hermite::{
    ArcLengthError, CurveParameter, HermiteCurve, ParameterSearch, arc_length_tolerance,
};
use crate::pose::Pose;

/// A perpendicular component shorter than this (of a unit vector) does not define a bow
/// direction: the vector is (nearly) along the chord.
const MIN_BOW_COMPONENT: f64 = 1e-6;
/// Largest sine of the angle between a guide tangent and the chord for coaxial guides.
const COAXIAL_TOLERANCE: f64 = 1e-12;
/// An estimated α within this fraction of the guide distance is refined before deciding
/// whether there is slack for a bow (`α > d`); the estimate is good to ~1e-6 relative.
const DECISION_REL_MARGIN: f64 = 1e-3;
/// Bending energies at estimated shape parameters decide only when one exceeds the other by
/// this factor: a ~1e-6 relative change of a parameter cannot move a smooth curve's energy by
/// 10 %. Closer energies are recomputed at the refined roots.
const CLEAR_ENERGY_RATIO: f64 = 1.1;

/// Nodes and frames of a cable segment between two guides (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ConnectedGeometry {
    /// Hermite tangent scale of the curve the nodes were placed on (m): `α` with arc length
    /// `S·l` for [`CurveFamily::Hermite`] (0 for a taut straight cable), the guide distance
    /// for [`CurveFamily::Bowed`].
    pub alpha_m: f64,
    /// Bow height `β` of the curve (m); 0 for the Hermite curve.
    pub bow_m: f64,
    /// Which candidate curve was kept.
    pub curve: CurveFamily,
    /// Sub-segment pitch (m).
    pub pitch_m: f64,
    /// S+1 nodes from the start guide origin to the end guide origin inclusive (m).
    pub nodes: Vec<Point3<f64>>,
    /// S+1 node frames (columns: normal, binormal, tangent); first = start guide orientation,
    /// last = end guide orientation.
    pub frames: Vec<Rotation3<f64>>,
    /// Twist mismatch Δψ (rad) found at the end guide and distributed linearly.
    pub twist_correction_rad: f64,
}

/// The curve family a connected geometry was placed on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveFamily {
    /// The cubic Hermite curve with tangent scale α (the paper's connected geometry).
    Hermite,
    /// The Hermite curve at α = guide distance, bowed towards the sag direction.
    Bowed,
}

impl ConnectedGeometry {
    /// Number of rigid sub-segments `S`.
    pub fn sub_segment_count(&self) -> usize {
        self.nodes.len().saturating_sub(1)
    }

    /// Natural cable length `S·l` (m).
    pub fn natural_length_m(&self) -> f64 {
        self.sub_segment_count() as f64 * self.pitch_m
    }
}

/// [`ConnectError::TooShort`] when the guides are farther apart than `S·l` (beyond the
/// arc-length tolerance of [`connect`], which makes the same check).
pub fn reaches(
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    pitch_m: f64,
) -> Result<(), ConnectError> {
    let natural = sub_segments as f64 * pitch_m;
    let distance = (end.translation.vector - start.translation.vector).norm();
    if distance > natural + arc_length_tolerance(natural) {
        return Err(ConnectError::TooShort {
            distance_m: distance,
            natural_length_m: natural,
            required_stretch: distance / natural,
        });
    }
    Ok(())
}

/// Guides closer than this (m) are one place for [`connect`]: 1 µm, far below any clamp.
/// A cable leaving and arriving there the same way is refused (a full loop); turned guides
/// at one place are joined by a loop the curves can start from.
pub const COINCIDENT_GUIDES_M: f64 = 1e-6;

/// Connects the `start` guide to the `end` guide with `sub_segments` rigid sub-segments of
/// `pitch_m` metres; `sag_direction` is where a slack cable should bow to (gravity, usually).
/// See the module documentation for the algorithm.
///
/// Returns [`ConnectError::TooShort`] when the guides are farther apart than `S·l` (beyond the
/// 1e-12 m length tolerance); guides `S·l` apart give the straight cable, α = 0.
/// [`ConnectError::InvalidInput`] for guides at one place facing the same way, `S = 0`, `S > MAX_SUB_SEGMENTS`, a pitch that is not
/// finite and positive, a non-finite pose or a zero or non-finite sag direction;
/// [`ConnectError::NoSolution`] for a single sub-segment between guides not `l` apart, or if
/// no candidate could be projected onto the rigid chain (the message names the residual).
///
/// The twist mismatch is measured with `atan2` on the principal branch `(−π, π]`: an exact
/// half turn is corrected by `+π`.
pub fn connect(
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    pitch_m: f64,
    sag_direction: &Unit<Vector3<f64>>,
) -> Result<ConnectedGeometry, ConnectError> {
    check_cable(sub_segments, pitch_m)?;
    let guides = GuidePair::from_poses(start, end)?;
    let sag = check_sag(sag_direction)?;
    reaches(start, end, sub_segments, pitch_m)?;
    let natural = sub_segments as f64 * pitch_m;
    let distance = (guides.end_point - guides.start_point).norm();
    if distance < COINCIDENT_GUIDES_M && guides.start_tangent.dot(&guides.end_tangent) > 0.0 {
        // Leaving and entering one point in the same direction: only a full loop joins them,
        // and the curves fold onto themselves (cusps the solver cannot start from).
        return Err(ConnectError::InvalidInput {
            what: format!(
                "the two guides are at the same place ({:.3} mm apart) with the cable leaving \
                 and arriving the same way: a {:.1} mm cable would have to make a full loop \
                 (S = 0 joins coincident guides)",
                distance * 1e3,
                natural * 1e3
            ),
        });
    }
    let tolerance = arc_length_tolerance(natural);
    let base = HermiteCurve::new(
        guides.start_point,
        guides.start_tangent,
        guides.end_point,
        guides.end_tangent,
        0.0,
    );
    let chosen = if natural - distance <= tolerance {
        straight_chain(base, sub_segments)
    } else if sub_segments == 1 {
        return Err(ConnectError::NoSolution {
            reason: format!(
                "a single rigid sub-segment spans exactly {:.1} mm, but the guides are {:.1} mm apart",
                natural * 1e3,
                distance * 1e3
            ),
        });
    } else {
        least_bent_candidate(&guides, &base, sub_segments, pitch_m, &sag)?
    };
    Ok(chosen.into_geometry(&guides, pitch_m))
}

/// One candidate shape: its curve, the nodes' parameters on it and the projected nodes.
struct Candidate {
    family: CurveFamily,
    curve: HermiteCurve,
    params: Vec<f64>,
    nodes: Vec<Point3<f64>>,
}

impl Candidate {
    /// Nodes at equal arc length on `curve`, projected onto the rigid chain.
    fn place(
        family: CurveFamily,
        curve: HermiteCurve,
        sub_segments: usize,
        pitch: f64,
    ) -> Result<Self, String> {
        let params = curve.equal_arc_length_parameters(sub_segments);
        let mut nodes: Vec<Point3<f64>> = params.iter().map(|&t| curve.point(t)).collect();
        // The monomial form rounds p(1); the end node is the guide origin exactly.
        nodes[0] = curve.start();
        nodes[sub_segments] = curve.end();
        project_onto_rigid_chain(&mut nodes, pitch).map_err(|failure| {
            format!(
                "{family:?} candidate: the rigid-chain projection stopped at a chord error of {:.3e} m after {} iterations",
                failure.residual_m, failure.iterations
            )
        })?;
        Ok(Self {
            family,
            curve,
            params,
            nodes,
        })
    }

    /// Frames along the nodes, packed with the shape data.
    fn into_geometry(self, guides: &GuidePair, pitch_m: f64) -> ConnectedGeometry {
        let (frames, twist) = guided_frames(
            &self.curve,
            &self.params,
            &self.nodes,
            guides.start_normal,
            &guides.end_normal,
        );
        ConnectedGeometry {
            alpha_m: self.curve.alpha_m(),
            bow_m: self.curve.bow_m(),
            curve: self.family,
            pitch_m,
            nodes: self.nodes,
            frames,
            twist_correction_rad: twist,
        }
    }
}

/// The taut cable: nodes evenly on the line between the guides, α = 0. Here `J Jᵀ` of the
/// projection is singular (no chord can lengthen to first order), so it is built directly.
fn straight_chain(curve: HermiteCurve, sub_segments: usize) -> Candidate {
    let (start, chord) = (curve.start(), curve.end() - curve.start());
    let fraction = |k: usize| k as f64 / sub_segments as f64;
    let mut nodes: Vec<Point3<f64>> = (0..=sub_segments)
        .map(|k| start + fraction(k) * chord)
        .collect();
    nodes[sub_segments] = curve.end();
    Candidate {
        family: CurveFamily::Hermite,
        // Any interior parameter of the α = 0 curve has the chord as its tangent.
        params: (0..=sub_segments).map(fraction).collect(),
        curve,
        nodes,
    }
}

/// Builds the Hermite curve and, with slack, the bowed one, and places nodes on the one with
/// the smaller continuous bending energy `∫ κ² ds` (ties and failed bows: Hermite). If the
/// winner cannot be placed (its root find or its projection fails), the other curve is placed
/// instead.
///
/// Coaxial guides (both tangents along the chord): with slack the Hermite curve can only fold
/// back along the axis, two cusps where `∫ κ² ds` is infinite, so the bow wins without a
/// search for α; the Hermite curve is built only if the bow cannot be placed.
fn least_bent_candidate(
    guides: &GuidePair,
    base: &HermiteCurve,
    sub_segments: usize,
    pitch: f64,
    sag: &Unit<Vector3<f64>>,
) -> Result<Candidate, ConnectError> {
    let natural = sub_segments as f64 * pitch;
    let chord = guides.end_point - guides.start_point;
    let hermite_later = || {
        Contender::new(
            CurveFamily::Hermite,
            base.clone(),
            CurveParameter::Alpha,
            natural,
        )
        .map_err(|error| error.to_string())
    };
    if is_coaxial(guides, &chord) {
        let bowed = bowed_contender(base, &chord, sag, guides, natural)
            .map_err(|error| format!("Bowed candidate: {error}"));
        let order = std::iter::once(bowed).chain(std::iter::once_with(hermite_later));
        return place_first(order, sub_segments, pitch);
    }
    let mut hermite = hermite_later().map_err(|reason| ConnectError::NoSolution { reason })?;
    // Without slack beyond α = d the Hermite curve needs no fold, and L(α = d) ≥ S·l leaves
    // no room for a bow. An estimate too close to d to tell is refined first.
    let distance = chord.norm();
    let alpha = hermite.value();
    let undecided = alpha.is_nan() || (alpha - distance).abs() <= DECISION_REL_MARGIN * distance;
    if undecided {
        hermite.refine().map_err(arc_length_failure)?;
    }
    // A failed bow root leaves the Hermite curve alone.
    let bowed = (hermite.value() > distance)
        .then(|| bowed_contender(base, &chord, sag, guides, natural))
        .and_then(Result::ok);
    let order = match bowed {
        Some(bowed) => by_bending_energy(hermite, bowed),
        None => [Some(hermite), None],
    };
    place_first(order.into_iter().flatten().map(Ok), sub_segments, pitch)
}

/// Places the first contender whose root find and projection succeed; `NoSolution` naming
/// every failure otherwise.
fn place_first(
    order: impl Iterator<Item = Result<Contender, String>>,
    sub_segments: usize,
    pitch: f64,
) -> Result<Candidate, ConnectError> {
    let mut failures = Vec::new();
    for contender in order {
        let placed = contender.and_then(|mut contender| {
            contender
                .refine()
                .map_err(|error| format!("{:?} candidate: {error}", contender.family))?;
            Candidate::place(contender.family, contender.curve, sub_segments, pitch)
        });
        match placed {
            Ok(candidate) => return Ok(candidate),
            Err(reason) => failures.push(reason),
        }
    }
    Err(ConnectError::NoSolution {
        reason: failures.join("; "),
    })
}

/// Both guide tangents point along the chord, to [`COAXIAL_TOLERANCE`]. The Hermite curve
/// is then `p' = f(t) × axis` with a scalar quadratic `f`; it is no longer than the chord
/// until `f` changes sign (α > 3d), so with slack it folds, `p' = 0` at two cusps. A tilt
/// within the tolerance leaves dips narrower than the 1e-9 of a cusp.
fn is_coaxial(guides: &GuidePair, chord: &Vector3<f64>) -> bool {
    let Some(axis) = Unit::try_new(*chord, 0.0) else {
        return false;
    };
    [guides.start_tangent, guides.end_tangent]
        .iter()
        .all(|v| v.dot(&axis) > 0.0 && v.cross(&axis).norm() <= COAXIAL_TOLERANCE)
}

/// The direction a slack cable bows towards in its start shape: gravity's, or straight down
/// (−z) without gravity.
pub fn sag_direction(gravity_m_s2: &Vector3<f64>) -> Unit<Vector3<f64>> {
    Unit::try_new(*gravity_m_s2, 0.0).unwrap_or(-Vector3::z_axis())
}

/// A candidate curve whose shape parameter may still be the estimate of the root find's cheap
/// phase (see [`HermiteCurve::parameter_search`]).
struct Contender {
    family: CurveFamily,
    parameter: CurveParameter,
    search: ParameterSearch,
    /// The curve at [`Self::value`].
    curve: HermiteCurve,
}

impl Contender {
    /// Starts the search for the parameter that gives `curve` the arc length `natural`; a
    /// search whose cheap phase found no estimate is completed right away.
    fn new(
        family: CurveFamily,
        mut curve: HermiteCurve,
        parameter: CurveParameter,
        natural: f64,
    ) -> Result<Self, ArcLengthError> {
        let mut search = curve.parameter_search(parameter, natural)?;
        let value = match search.estimate() {
            Some(estimate) => estimate,
            None => search.finish()?,
        };
        curve.set_parameter(parameter, value);
        Ok(Self {
            family,
            parameter,
            search,
            curve,
        })
    }

    /// The current value of the shape parameter (m): the estimate or the root.
    fn value(&self) -> f64 {
        match self.parameter {
            CurveParameter::Alpha => self.curve.alpha_m(),
            CurveParameter::Bow => self.curve.bow_m(),
        }
    }

    /// Completes the root find and moves the curve to the root (no-op once converged).
    fn refine(&mut self) -> Result<(), ArcLengthError> {
        if !self.search.is_converged() {
            let root = self.search.finish()?;
            self.curve.set_parameter(self.parameter, root);
        }
        Ok(())
    }
}

/// The two contenders, the one with the smaller `∫ κ² ds` first (ties: Hermite).
///
/// The energies are first compared at the estimates of the shape parameters (the cheap phase
/// of the root finds, ~1e-6 relative). Only when neither exceeds the other by the factor
/// [`CLEAR_ENERGY_RATIO`] (or both are infinite) are both roots refined and the energies
/// recomputed. Otherwise the loser's root is never refined: its curve is not placed unless the
/// winner fails.
fn by_bending_energy(mut hermite: Contender, mut bowed: Contender) -> [Option<Contender>; 2] {
    let (mut e_hermite, mut e_bowed) = (
        hermite.curve.bending_energy_integral(),
        bowed.curve.bending_energy_integral(),
    );
    let clear =
        e_hermite > CLEAR_ENERGY_RATIO * e_bowed || e_bowed > CLEAR_ENERGY_RATIO * e_hermite;
    let estimated = !(hermite.search.is_converged() && bowed.search.is_converged());
    if !clear && estimated {
        // A failed refinement is reported when the contender is placed.
        if hermite.refine().is_ok() {
            e_hermite = hermite.curve.bending_energy_integral();
        }
        if bowed.refine().is_ok() {
            e_bowed = bowed.curve.bending_energy_integral();
        }
    }
    if e_bowed < e_hermite {
        [Some(bowed), Some(hermite)]
    } else {
        [Some(hermite), Some(bowed)]
    }
}

/// The bowed contender: the Hermite curve at α = guide distance, bowed towards the sag
/// direction, its bow height searched for arc length `natural`.
fn bowed_contender(
    base: &HermiteCurve,
    chord: &Vector3<f64>,
    sag: &Unit<Vector3<f64>>,
    guides: &GuidePair,
    natural: f64,
) -> Result<Contender, ArcLengthError> {
    let direction = bow_direction(chord, sag, guides);
    let curve = base.with_alpha(chord.norm()).with_bow(direction, 0.0);
    Contender::new(CurveFamily::Bowed, curve, CurveParameter::Bow, natural)
}

/// The unit bow direction `n`: the part of `sag` perpendicular to the chord. If `sag` is
/// (nearly) along the chord, the start guide's x axis made perpendicular instead, then its
/// z axis (one of the two always has a perpendicular part ≥ 1/√2). Coincident guides have no
/// chord: `sag` itself.
fn bow_direction(
    chord: &Vector3<f64>,
    sag: &Unit<Vector3<f64>>,
    guides: &GuidePair,
) -> Unit<Vector3<f64>> {
    let Some(axis) = Unit::try_new(*chord, 0.0) else {
        return *sag;
    };
    let across =
        |v: &Vector3<f64>| Unit::try_new(v - v.dot(&axis) * axis.into_inner(), MIN_BOW_COMPONENT);
    across(sag)
        .or_else(|| across(&guides.start_normal))
        .or_else(|| across(&guides.start_tangent))
        .unwrap_or(*sag)
}

fn arc_length_failure(error: ArcLengthError) -> ConnectError {
    ConnectError::NoSolution {
        reason: error.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn down() -> Unit<Vector3<f64>> {
        -Vector3::z_axis()
    }

    #[test]
    fn a_single_sub_segment_needs_guides_exactly_one_pitch_apart() {
        let start = pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]);
        let exact = pose_from_xyz_rpy([0.0, 0.0, 0.01], [0.0, 0.0, 0.4]);
        let geometry = connect(&start, &exact, 1, 0.01, &down()).unwrap();
        assert_eq!(geometry.nodes.len(), 2);
        assert!((geometry.twist_correction_rad - 0.4).abs() < 1e-12);
        let closer = pose_from_xyz_rpy([0.0, 0.0, 0.005], [0.0, 0.0, 0.0]);
        assert!(matches!(
            connect(&start, &closer, 1, 0.01, &down()),
            Err(ConnectError::NoSolution { .. })
        ));
        let two = connect(
            &start,
            // Two links along a circle of radius 30 mm bending towards +x.
            &pose_from_xyz_rpy([0.00648, 0.0, 0.01862], [0.0, 0.6698, 0.0]),
            2,
            0.01,
            &down(),
        )
        .unwrap();
        for pair in two.nodes.windows(2) {
            assert!(((pair[1] - pair[0]).norm() - 0.01).abs() < 1e-13);
        }
    }

    /// The premise of the coaxial shortcut: for guides coaxial to within the tolerance, the
    /// Hermite curve of any slack cable folds (infinite `∫ κ² ds`), so the bow wins, as the
    /// full comparison (for a larger tilt) also finds.
    #[test]
    fn coaxial_hermite_curves_with_slack_fold() {
        let start = pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0]);
        for tilt in [0.0, 1e-13, 0.9 * COAXIAL_TOLERANCE, 1e-6] {
            let end = pose_from_xyz_rpy([0.4, 0.0, 0.0], [0.0, FRAC_PI_2 + tilt, 0.0]);
            let guides = GuidePair::from_poses(&start, &end).unwrap();
            let chord = guides.end_point - guides.start_point;
            assert_eq!(is_coaxial(&guides, &chord), tilt < COAXIAL_TOLERANCE);
            for natural in [0.41, 0.5, 1.0] {
                let curve = HermiteCurve::between_guides(&start, &end, 0.0);
                let alpha = curve.alpha_for_arc_length(natural).unwrap();
                let energy = curve.with_alpha(alpha).bending_energy_integral();
                if tilt < COAXIAL_TOLERANCE {
                    assert_eq!(energy, f64::INFINITY, "tilt {tilt}, length {natural}");
                }
                let geometry = connect(&start, &end, 50, natural / 50.0, &down()).unwrap();
                assert_eq!(geometry.curve, CurveFamily::Bowed, "tilt {tilt}");
            }
        }
    }

    #[test]
    fn the_bow_direction_falls_back_when_sag_is_along_the_chord() {
        let guides = GuidePair::from_poses(
            &pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0]),
            &pose_from_xyz_rpy([0.0, 0.0, -0.3], [0.0, FRAC_PI_2, 0.0]),
        )
        .unwrap();
        let chord = guides.end_point - guides.start_point;
        // Sag across the chord: kept as it is.
        let across = bow_direction(&chord, &Vector3::x_axis(), &guides);
        assert!((across.into_inner() - Vector3::x()).norm() < 1e-15);
        // Sag along the chord (straight down): the start guide's x axis, here world −z, is
        // along the chord too, so its z axis (world +x) decides.
        let along = bow_direction(&chord, &down(), &guides);
        assert!(along.dot(&chord).abs() < 1e-15);
        assert!((along.into_inner() - Vector3::x()).norm() < 1e-12);
        // Coincident guides: the sag direction itself.
        let none = bow_direction(&Vector3::zeros(), &down(), &guides);
        assert_eq!(none, down());
    }

    /// Extreme but finite input may fail, never panic or hang.
    #[test]
    fn extreme_input_does_not_panic() {
        let start = pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]);
        let ends = [
            pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]),
            pose_from_xyz_rpy([1e-13, 0.0, 0.0], [PI, 0.0, 0.0]),
            pose_from_xyz_rpy([1e150, 0.0, 0.0], [0.0, 0.0, 0.0]),
            pose_from_xyz_rpy([0.0, 0.0, -0.3], [PI, 0.0, 0.0]),
        ];
        let sags = [
            down(),
            Vector3::x_axis(),
            Unit::new_unchecked(Vector3::zeros()),
        ];
        for end in &ends {
            for (sub_segments, pitch) in
                [(1, 0.01), (3, 0.01), (40, 1e-300), (40, 1e-9), (7, 1e100)]
            {
                for sag in &sags {
                    let _ = connect(&start, end, sub_segments, pitch, sag);
                }
            }
        }
        let mut unnormalized = start;
        unnormalized.rotation =
            nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(2.0, 0.0, 0.0, 0.0));
        let end = pose_from_xyz_rpy([0.1, 0.0, 0.1], [0.0, 0.0, 0.0]);
        assert!(connect(&unnormalized, &end, 20, 0.01, &down()).is_ok());
        let mut zero = start;
        zero.rotation =
            nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0));
        assert!(matches!(
            connect(&zero, &end, 20, 0.01, &down()),
            Err(ConnectError::InvalidInput { .. })
        ));
        for bad in [Vector3::zeros(), Vector3::new(f64::NAN, 0.0, 1.0)] {
            assert!(matches!(
                connect(&start, &end, 20, 0.01, &Unit::new_unchecked(bad)),
                Err(ConnectError::InvalidInput { .. })
            ));
        }
    }
}
