//! The *connected geometry* of a cable segment: an initial shape that joins two guide frames
//! with exactly the cable's natural length, used to start the static equilibrium solve.
//!
//! The cable is `S` rigid sub-segments of pitch `l`. The shape is a cubic Hermite curve
//! between the guide origins with tangents `α v0`, `α v1` (`v` = guide +z), carrying `S + 1`
//! nodes that form a valid configuration of the rigid-link model: node 0 and node `S` are the
//! guide origins and every adjacent pair is exactly `l` apart (Euclidean chord, not arc length:
//! equal arc-length spacing would leave each chord `≈ l³κ²/24` short). Frames are carried
//! along the nodes as rotation-minimizing frames and the remaining twist is spread linearly so
//! that the first and last frames are the guide orientations.
//!
//! # α: arc length versus discrete length
//!
//! 1. `α_arc` solves `L(α) = S·l` for the arc length `L` (Newton–Raphson, see
//!    [`HermiteCurve::alpha_for_arc_length`]).
//! 2. A *chord walk* places nodes on the curve: from `t₀ = 0`, each `t_k` is the first
//!    parameter after `t_{k−1}` with `|p(t_k) − p(t_{k−1})| = l`. With `k` full steps fitting
//!    in `t ≤ 1`, the discrete length is `F(α) = k·l + |P1 − n_k|`. `F` is continuous in α,
//!    `F(0) = |P1 − P0|`, and `F ≤ L` (a chord is never longer than its arc), with
//!    `L − F = O(L (lκ)²)` for curvature κ.
//! 3. The returned α solves `F(α) = S·l`, starting from `α_arc` (where `F ≤ S·l`) with the
//!    slope `dL/dα` and then secant slopes, inside a bracket with bisection fallback. It is a
//!    little larger than `α_arc`, by a relative `O((lκ)²)`: the polyline needs a slightly longer
//!    curve to reach the same length.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, UnitQuaternion, Vector3};

use super::hermite::{ArcLengthError, ArcLengthFit, HermiteCurve, arc_length_tolerance};
use super::rmf::double_reflection;
use crate::pose::Pose;

/// Largest accepted sub-segment count; bounds the memory of one connected geometry.
pub const MAX_SUB_SEGMENTS: usize = 1_000_000;
/// Iteration limit of the discrete-length root find (each iteration is one chord walk).
const MAX_LENGTH_ITERATIONS: usize = 100;
/// The discrete-length root find gives up beyond this multiple of (natural length + guide
/// distance) for α.
const ALPHA_LIMIT_FACTOR: f64 = 1e6;
/// Parameter steps one chord-walk step may take while looking for its crossing.
const MAX_MARCH_STEPS: usize = 10_000;
/// Iteration limit of the safeguarded Newton solve for one crossing.
const MAX_CROSSING_ITERATIONS: usize = 100;

/// Nodes and frames of a cable segment between two guides (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ConnectedGeometry {
    /// Hermite tangent scale actually used (m).
    pub alpha_m: f64,
    /// Sub-segment pitch (m).
    pub pitch_m: f64,
    /// S+1 nodes from the start guide origin to the end guide origin inclusive (m).
    pub nodes: Vec<Point3<f64>>,
    /// S+1 node frames (columns: normal, binormal, tangent); first = start guide orientation, last = end guide orientation.
    pub frames: Vec<Rotation3<f64>>,
    /// Twist mismatch Δψ (rad) found at the end guide and distributed linearly.
    pub twist_correction_rad: f64,
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
    /// Zero sub-segments, a non-positive or non-finite pitch, or a non-finite guide pose.
    #[error("invalid connected-geometry input: {what}")]
    InvalidInput {
        /// What is wrong, for people.
        what: String,
    },
    /// A root find failed (not expected for finite, valid input; reported rather than hidden).
    #[error("no connected geometry found: {reason}")]
    NoSolution {
        /// What failed, for people.
        reason: String,
    },
}

/// Connects the `start` guide to the `end` guide with `sub_segments` rigid sub-segments of
/// `pitch_m` metres (see the module documentation for the algorithm).
///
/// Returns [`ConnectError::TooShort`] when the guides are farther apart than `S·l` (beyond the
/// 1e-12 m length tolerance); guides exactly `S·l` apart give the straight cable, α = 0.
pub fn connect(
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    pitch_m: f64,
) -> Result<ConnectedGeometry, ConnectError> {
    check_cable(sub_segments, pitch_m)?;
    let guides = GuidePair::from_poses(start, end)?;
    let natural = sub_segments as f64 * pitch_m;
    let distance = (guides.end_point - guides.start_point).norm();
    let tolerance = arc_length_tolerance(natural);
    if distance > natural + tolerance {
        return Err(ConnectError::TooShort {
            distance_m: distance,
            natural_length_m: natural,
            required_stretch: distance / natural,
        });
    }
    let mut curve = HermiteCurve::new(
        guides.start_point,
        guides.start_tangent,
        guides.end_point,
        guides.end_tangent,
        0.0,
    );
    let fit = curve
        .alpha_and_slope_for_arc_length(natural)
        .map_err(arc_length_failure)?;
    let scale = guides
        .start_point
        .coords
        .norm()
        .max(guides.end_point.coords.norm())
        + natural;
    let mut walk = ChordWalk::new(pitch_m, sub_segments, scale);
    let alpha = DiscreteLengthSolver::new(natural, tolerance, distance)
        .solve(&mut curve, fit, &mut walk)
        .map_err(|error| explain_tight_bend(error, &curve, pitch_m))?;
    let (nodes, params) = walk.connected_nodes(sub_segments, guides.end_point)?;
    let tangents = node_tangents(&curve, &params, &nodes);
    let mut frames = double_reflection(&nodes, &tangents, guides.start_normal);
    let twist = frames
        .last()
        .map_or(0.0, |last| twist_mismatch(last, &guides.end_normal));
    distribute_twist(&mut frames, twist);
    Ok(ConnectedGeometry {
        alpha_m: alpha,
        pitch_m,
        nodes,
        frames,
        twist_correction_rad: twist,
    })
}

fn check_cable(sub_segments: usize, pitch_m: f64) -> Result<(), ConnectError> {
    let invalid = |what: String| Err(ConnectError::InvalidInput { what });
    if sub_segments == 0 {
        return invalid("a segment needs at least one sub-segment".into());
    }
    if sub_segments > MAX_SUB_SEGMENTS {
        return invalid(format!(
            "{sub_segments} sub-segments exceed the limit {MAX_SUB_SEGMENTS}"
        ));
    }
    if !(pitch_m.is_finite() && pitch_m > 0.0) {
        return invalid(format!(
            "sub-segment pitch {pitch_m} m must be finite and > 0"
        ));
    }
    if !(sub_segments as f64 * pitch_m).is_finite() {
        return invalid("natural cable length is not finite".into());
    }
    Ok(())
}

/// Adds the curve's tightest bend to a discrete-length failure. `F` can only jump (and the root
/// find fail) where the curve bends to a radius below half the pitch: for larger radii the
/// distance from a node grows monotonically until it exceeds `l` (Schur's comparison theorem),
/// so the first crossing is unique. Such a shape is far below any cable's bend radius anyway.
fn explain_tight_bend(error: ConnectError, curve: &HermiteCurve, pitch_m: f64) -> ConnectError {
    match error {
        ConnectError::NoSolution { reason } => {
            let radius = min_bend_radius(curve, 512);
            let note = if radius < 0.5 * pitch_m {
                ", below half the sub-segment pitch"
            } else {
                ""
            };
            ConnectError::NoSolution {
                reason: format!(
                    "{reason}; the Hermite curve bends to a radius of {:.2} mm{note}",
                    radius * 1e3
                ),
            }
        }
        other => other,
    }
}

/// Smallest radius of curvature `|p'|³ / |p' × p''|` over `samples + 1` parameters (m).
fn min_bend_radius(curve: &HermiteCurve, samples: usize) -> f64 {
    (0..=samples)
        .map(|i| {
            let t = i as f64 / samples as f64;
            let (velocity, acceleration) = (curve.derivative(t), curve.second_derivative(t));
            velocity.norm().powi(3) / velocity.cross(&acceleration).norm()
        })
        .filter(|radius| !radius.is_nan())
        .fold(f64::INFINITY, f64::min)
}

fn arc_length_failure(error: ArcLengthError) -> ConnectError {
    ConnectError::NoSolution {
        reason: error.to_string(),
    }
}

/// Positions, tangents (+z) and reference normals (+x) of the two guides.
struct GuidePair {
    start_point: Point3<f64>,
    end_point: Point3<f64>,
    start_tangent: Unit<Vector3<f64>>,
    end_tangent: Unit<Vector3<f64>>,
    start_normal: Unit<Vector3<f64>>,
    end_normal: Unit<Vector3<f64>>,
}

impl GuidePair {
    fn from_poses(start: &Pose, end: &Pose) -> Result<Self, ConnectError> {
        let (start_point, start_rotation) = guide_parts(start, "start")?;
        let (end_point, end_rotation) = guide_parts(end, "end")?;
        Ok(Self {
            start_point,
            end_point,
            start_tangent: Unit::new_unchecked(start_rotation * Vector3::z()),
            end_tangent: Unit::new_unchecked(end_rotation * Vector3::z()),
            start_normal: Unit::new_unchecked(start_rotation * Vector3::x()),
            end_normal: Unit::new_unchecked(end_rotation * Vector3::x()),
        })
    }
}

/// The origin and (re-normalized) rotation of a guide pose, rejecting non-finite values.
fn guide_parts(pose: &Pose, which: &str) -> Result<(Point3<f64>, Rotation3<f64>), ConnectError> {
    let point = Point3::from(pose.translation.vector);
    let quaternion = pose.rotation.into_inner();
    let finite = point
        .iter()
        .chain(quaternion.coords.iter())
        .all(|v| v.is_finite());
    let norm = quaternion.norm();
    if !finite || !(norm > 1e-6) {
        return Err(ConnectError::InvalidInput {
            what: format!("{which} guide pose is not a finite rigid transform"),
        });
    }
    let rotation = UnitQuaternion::new_unchecked(quaternion / norm).to_rotation_matrix();
    Ok((point, rotation))
}

/// Chord walk along the curve, with buffers reused between walks.
struct ChordWalk {
    pitch: f64,
    /// Full steps after which the walk stops: `F` is then already far above `S·l`.
    max_steps: usize,
    /// Chord accuracy the crossing solve aims at (m): a few ulp of the coordinates.
    chord_tolerance: f64,
    /// `t_0 … t_k` of the latest walk.
    params: Vec<f64>,
    /// `n_0 … n_k` of the latest walk.
    nodes: Vec<Point3<f64>>,
    /// Parameters of the walk before, whose steps warm-start the next walk.
    previous_params: Vec<f64>,
}

impl ChordWalk {
    fn new(pitch: f64, sub_segments: usize, coordinate_scale: f64) -> Self {
        let max_steps = 2 * sub_segments + 8;
        Self {
            pitch,
            max_steps,
            chord_tolerance: 8.0 * f64::EPSILON * coordinate_scale.max(pitch),
            params: Vec::with_capacity(max_steps + 1),
            nodes: Vec::with_capacity(max_steps + 1),
            previous_params: Vec::with_capacity(max_steps + 1),
        }
    }

    /// Walks `curve` and returns the discrete length `F = k·l + |P1 − n_k|` (m).
    fn run(&mut self, curve: &HermiteCurve) -> Result<f64, ConnectError> {
        std::mem::swap(&mut self.params, &mut self.previous_params);
        self.params.clear();
        self.nodes.clear();
        self.params.push(0.0);
        self.nodes.push(curve.start());
        let mut crossing = CrossingSearch::new(curve, self.pitch, self.chord_tolerance);
        for k in 0..self.max_steps {
            let (t, node) = (self.params[k], self.nodes[k]);
            let hint = self.previous_step(k);
            match crossing.next(t, node, hint)? {
                Some(next) => {
                    self.params.push(next);
                    self.nodes.push(curve.point(next));
                }
                None => break,
            }
        }
        let steps = self.nodes.len() - 1;
        let remainder = (curve.end() - self.nodes[steps]).norm();
        Ok(steps as f64 * self.pitch + remainder)
    }

    /// Parameter step `t_{k+1} − t_k` of the previous walk, if it had one.
    fn previous_step(&self, k: usize) -> Option<f64> {
        let (from, to) = (
            self.previous_params.get(k)?,
            self.previous_params.get(k + 1)?,
        );
        Some(to - from)
    }

    /// The `S + 1` nodes and parameters of a walk at the root `F = S·l`: the walk's first `S`
    /// nodes and the end guide origin (the walk's node `S`, if it got one, is within the
    /// length tolerance of it).
    fn connected_nodes(
        &self,
        sub_segments: usize,
        end: Point3<f64>,
    ) -> Result<(Vec<Point3<f64>>, Vec<f64>), ConnectError> {
        let steps = self.nodes.len() - 1;
        if steps + 1 < sub_segments || steps > sub_segments {
            return Err(ConnectError::NoSolution {
                reason: format!("chord walk ended after {steps} steps, expected {sub_segments}"),
            });
        }
        let mut nodes = Vec::with_capacity(sub_segments + 1);
        nodes.extend_from_slice(&self.nodes[..sub_segments]);
        nodes.push(end);
        let mut params = Vec::with_capacity(sub_segments + 1);
        params.extend_from_slice(&self.params[..sub_segments]);
        params.push(1.0);
        Ok((nodes, params))
    }
}

/// Finds successive chord crossings `|p(t) − n| = l` on one curve.
struct CrossingSearch<'a> {
    curve: &'a HermiteCurve,
    pitch: f64,
    /// Tolerance on `g = |p − n|² − l²` equivalent to the chord tolerance.
    gap_tolerance: f64,
    third_derivative_bound: f64,
}

impl<'a> CrossingSearch<'a> {
    fn new(curve: &'a HermiteCurve, pitch: f64, chord_tolerance: f64) -> Self {
        Self {
            curve,
            pitch,
            gap_tolerance: 2.0 * pitch * chord_tolerance,
            third_derivative_bound: curve.third_derivative_norm() / 6.0,
        }
    }

    /// The first `t > from_t` (≤ 1) with `|p(t) − node| = l`, `None` if the curve ends first.
    ///
    /// `hint` is the step the previous walk took here; it usually lands within a hair of the
    /// crossing, so Newton needs one or two iterations. Without a usable hint the curve is
    /// marched in parameter steps whose arc length is bounded (from `|p'|`, `|p''|`, `|p'''|`)
    /// by a little more than the distance still missing, so an excursion beyond `l` cannot be
    /// stepped over unless it is shorter than ~`0.1 l`.
    fn next(
        &mut self,
        from_t: f64,
        node: Point3<f64>,
        hint: Option<f64>,
    ) -> Result<Option<f64>, ConnectError> {
        let mut lower = from_t;
        if let Some(step) = hint.filter(|step| *step > 0.0) {
            let t = (from_t + step).min(1.0);
            let gap = self.gap(t, &node);
            if gap >= 0.0 {
                return Ok(Some(self.refine(&node, from_t, t, t)));
            }
            if t >= 1.0 {
                return Ok(None);
            }
            lower = t;
        }
        match self.march(lower, &node)? {
            Some((a, b)) => Ok(Some(self.refine(&node, a, b, b))),
            None => Ok(None),
        }
    }

    /// `g(t) = |p(t) − node|² − l²`: negative inside the sphere of radius `l`.
    #[inline]
    fn gap(&self, t: f64, node: &Point3<f64>) -> f64 {
        (self.curve.point(t) - node).norm_squared() - self.pitch * self.pitch
    }

    /// Steps forward from `t` (inside the sphere) until the curve is outside; returns the
    /// bracket `(inside, outside)`, or `None` if `t = 1` is reached inside.
    fn march(&self, mut t: f64, node: &Point3<f64>) -> Result<Option<(f64, f64)>, ConnectError> {
        for _ in 0..MAX_MARCH_STEPS {
            let distance = (self.curve.point(t) - node).norm();
            let missing = 1.1 * (self.pitch - distance).max(0.0) + 0.01 * self.pitch;
            let step = self.parameter_step_for_arc(t, missing);
            let next = (t + step).min(1.0).max(next_up(t));
            if self.gap(next, node) >= 0.0 {
                return Ok(Some((t, next)));
            }
            if next >= 1.0 {
                return Ok(None);
            }
            t = next;
        }
        Err(ConnectError::NoSolution {
            reason: "chord walk did not advance along the curve".into(),
        })
    }

    /// Largest `h ≤ 1 − t` whose arc-length bound `|p'| h + |p''| h²/2 + |p'''| h³/6` does not
    /// exceed `arc` (Newton from the right on the convex bound, a few iterations suffice).
    fn parameter_step_for_arc(&self, t: f64, arc: f64) -> f64 {
        let s1 = self.curve.derivative(t).norm();
        let s2 = self.curve.second_derivative(t).norm();
        let s3 = self.third_derivative_bound;
        let remaining = 1.0 - t;
        let mut h = if s1 > 0.0 {
            (arc / s1).min(remaining)
        } else {
            remaining
        };
        for _ in 0..16 {
            let excess = h * (s1 + h * (0.5 * s2 + h * s3)) - arc;
            if !(excess > 0.0) {
                break;
            }
            let slope = s1 + h * (s2 + 3.0 * h * s3);
            let next = h - excess / slope;
            let converged = next > 0.99 * h;
            h = next;
            if converged {
                break;
            }
        }
        h.max(0.0)
    }

    /// Solves `g(t) = 0` in the bracket `[inside, outside]` by Newton from `start`, bisecting
    /// whenever Newton leaves the bracket or does not halve `|g|`.
    fn refine(&self, node: &Point3<f64>, mut inside: f64, mut outside: f64, start: f64) -> f64 {
        let mut t = start;
        let mut previous_gap = f64::INFINITY;
        for _ in 0..MAX_CROSSING_ITERATIONS {
            let offset = self.curve.point(t) - node;
            let gap = offset.norm_squared() - self.pitch * self.pitch;
            if gap.abs() <= self.gap_tolerance {
                return t;
            }
            if gap < 0.0 {
                inside = t;
            } else {
                outside = t;
            }
            if outside - inside <= 4.0 * f64::EPSILON * outside.abs().max(f64::MIN_POSITIVE) {
                return outside;
            }
            let slope = 2.0 * offset.dot(&self.curve.derivative(t));
            let newton = t - gap / slope;
            let bracketed = newton > inside.min(outside) && newton < inside.max(outside);
            let progressed = gap.abs() <= 0.5 * previous_gap;
            t = if bracketed && progressed {
                newton
            } else {
                0.5 * (inside + outside)
            };
            previous_gap = gap.abs();
        }
        outside
    }
}

/// The next representable `f64` above a non-negative finite `t`.
fn next_up(t: f64) -> f64 {
    f64::from_bits(t.to_bits() + 1)
}

/// Root find of `F(α) = S·l`, started at `α_arc` with `dL/dα` as the first slope.
struct DiscreteLengthSolver {
    target: f64,
    tolerance: f64,
    alpha_limit: f64,
    /// Largest α known with `F < S·l`, and its residual.
    lo: (f64, f64),
    /// Smallest α known with `F > S·l`, once found.
    hi: Option<(f64, f64)>,
}

impl DiscreteLengthSolver {
    fn new(target: f64, tolerance: f64, distance: f64) -> Self {
        Self {
            target,
            tolerance,
            alpha_limit: ALPHA_LIMIT_FACTOR * (target + distance),
            // F(0) = |P1 − P0| ≤ S·l.
            lo: (0.0, distance - target),
            hi: None,
        }
    }

    /// Returns the root α; on return `curve` has that α and `walk` holds its walk.
    fn solve(
        mut self,
        curve: &mut HermiteCurve,
        fit: ArcLengthFit,
        walk: &mut ChordWalk,
    ) -> Result<f64, ConnectError> {
        let mut alpha = fit.alpha_m;
        let mut slope = fit.slope;
        let mut previous: Option<(f64, f64)> = None;
        for _ in 0..MAX_LENGTH_ITERATIONS {
            curve.set_alpha(alpha);
            let residual = walk.run(curve)? - self.target;
            if residual.abs() < self.tolerance {
                return Ok(alpha);
            }
            if let Some(secant) = previous.and_then(|p| secant_slope(p, (alpha, residual))) {
                slope = secant;
            }
            let progressed = previous.is_none_or(|(_, r)| residual.abs() <= 0.5 * r.abs());
            self.record(alpha, residual);
            previous = Some((alpha, residual));
            alpha = self.next_alpha(alpha, residual, slope, progressed)?;
        }
        Err(self.failure("iteration limit reached"))
    }

    fn record(&mut self, alpha: f64, residual: f64) {
        if residual < 0.0 {
            if alpha >= self.lo.0 {
                self.lo = (alpha, residual);
            }
        } else if self.hi.is_none_or(|(hi, _)| alpha < hi) {
            self.hi = Some((alpha, residual));
        }
    }

    /// Quasi-Newton step if it stays in the bracket (and the last step halved the residual);
    /// bisection inside a bracket; geometric growth while no upper bracket is known.
    fn next_alpha(
        &self,
        alpha: f64,
        residual: f64,
        slope: f64,
        progressed: bool,
    ) -> Result<f64, ConnectError> {
        let newton = alpha - residual / slope;
        let newton_ok = slope > 0.0 && newton.is_finite();
        let lo = self.lo.0;
        match self.hi {
            None => {
                let grown = 2.0 * lo.max(alpha) + walk_scale(self.target);
                let next = if newton_ok && newton > lo {
                    newton.min(grown)
                } else {
                    grown
                };
                if next > self.alpha_limit {
                    return Err(self.failure("the discrete length stays below the cable length"));
                }
                Ok(next)
            }
            Some((hi, _)) => {
                if hi - lo <= 4.0 * f64::EPSILON * hi {
                    return Err(self.failure("the discrete length jumps across the cable length"));
                }
                let inside = newton_ok && newton > lo && newton < hi;
                Ok(if inside && progressed {
                    newton
                } else {
                    0.5 * (lo + hi)
                })
            }
        }
    }

    fn failure(&self, why: &str) -> ConnectError {
        ConnectError::NoSolution {
            reason: format!(
                "{why} (tangent scale bracket [{:.6e}, {}] m, cable length {} m)",
                self.lo.0,
                self.hi
                    .map_or("none".to_string(), |(hi, _)| format!("{hi:.6e}")),
                self.target
            ),
        }
    }
}

/// A small α increment that makes growth progress even from α = 0 (m).
fn walk_scale(target: f64) -> f64 {
    0.01 * target
}

/// Slope of the secant through two `(α, residual)` points, if positive and finite.
fn secant_slope(a: (f64, f64), b: (f64, f64)) -> Option<f64> {
    let slope = (b.1 - a.1) / (b.0 - a.0);
    (slope.is_finite() && slope > 0.0).then_some(slope)
}

/// Unit tangents at the nodes: the guide axes at both ends, `p'/|p'|` inside; at a cusp
/// (`p' = 0`) the direction of the neighbouring chord pair instead.
fn node_tangents(
    curve: &HermiteCurve,
    params: &[f64],
    nodes: &[Point3<f64>],
) -> Vec<Unit<Vector3<f64>>> {
    let last = params.len() - 1;
    let mut tangents = Vec::with_capacity(params.len());
    for (k, &t) in params.iter().enumerate() {
        let tangent = match k {
            0 => Some(curve.start_tangent()),
            _ if k == last => Some(curve.end_tangent()),
            _ => curve
                .unit_tangent(t)
                .or_else(|| Unit::try_new(nodes[k + 1] - nodes[k - 1], f64::MIN_POSITIVE)),
        };
        let fallback = tangents.last().copied().unwrap_or(curve.start_tangent());
        tangents.push(tangent.unwrap_or(fallback));
    }
    tangents
}

/// Angle (rad) about the frame's tangent that turns its normal onto `target_normal`, on the
/// principal branch `(−π, π]`: an exact half turn is reported as `+π`, never `−π`.
fn twist_mismatch(frame: &Rotation3<f64>, target_normal: &Unit<Vector3<f64>>) -> f64 {
    let m = frame.matrix();
    let (normal, binormal) = (m.column(0), m.column(1));
    let angle = target_normal
        .dot(&binormal)
        .atan2(target_normal.dot(&normal));
    if angle <= -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        angle
    }
}

/// Rotates frame `k` about its own tangent by `twist · k / S`, so the first frame is kept and
/// the last turns by the whole `twist`.
fn distribute_twist(frames: &mut [Rotation3<f64>], twist: f64) {
    let segments = frames.len().saturating_sub(1).max(1) as f64;
    for (k, frame) in frames.iter_mut().enumerate().skip(1) {
        let (sin, cos) = (twist * k as f64 / segments).sin_cos();
        let m = frame.matrix();
        let (normal, binormal, tangent) = (m.column(0), m.column(1), m.column(2));
        let twisted_normal = normal * cos + binormal * sin;
        let twisted_binormal = binormal * cos - normal * sin;
        *frame = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[
            twisted_normal,
            twisted_binormal,
            tangent.into_owned(),
        ]));
    }
}

#[cfg(test)]
mod perf_tmp {
    use super::*;
    use nalgebra::{Isometry3, Translation3};

    #[test]
    fn perf_phases() {
        for s in [25usize, 50] {
            let len = s as f64 * 0.01;
            let start =
                crate::pose::pose_from_xyz_rpy([0.0; 3], [0.0, std::f64::consts::FRAC_PI_2, 0.0]);
            let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
            let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
            let end = Isometry3::from_parts(
                Translation3::new(0.6 * len, 0.2 * len, 0.1 * len),
                UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
            );
            let curve = HermiteCurve::between_guides(&start, &end, 0.0);
            let n = 20000;
            let t0 = std::time::Instant::now();
            let mut fit = None;
            for _ in 0..n {
                fit = Some(
                    std::hint::black_box(&curve)
                        .alpha_and_slope_for_arc_length(len)
                        .unwrap(),
                );
            }
            let fit = fit.unwrap();
            let dt_alpha = t0.elapsed().as_secs_f64() / n as f64;
            let c2 = curve.with_alpha(fit.alpha_m);
            let t0 = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(std::hint::black_box(&c2).arc_length_with_alpha_derivative());
            }
            let dt_quad = t0.elapsed().as_secs_f64() / n as f64;
            let mut walk = ChordWalk::new(0.01, s, 1.0);
            let t0 = std::time::Instant::now();
            for _ in 0..n {
                walk.params.clear();
                std::hint::black_box(walk.run(&c2).unwrap());
            }
            let dt_walk = t0.elapsed().as_secs_f64() / n as f64;
            let t0 = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(walk.run(&c2).unwrap());
            }
            let dt_walk_hint = t0.elapsed().as_secs_f64() / n as f64;
            let t0 = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(connect(&start, &end, s, 0.01).unwrap());
            }
            let dt_all = t0.elapsed().as_secs_f64() / n as f64;
            println!(
                "S={s}: alpha {:.2} us, quad {:.2} us, walk {:.2} us, hinted walk {:.2} us, connect {:.2} us",
                dt_alpha * 1e6,
                dt_quad * 1e6,
                dt_walk * 1e6,
                dt_walk_hint * 1e6,
                dt_all * 1e6
            );
        }
    }
}
