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
//!    [`HermiteCurve::alpha_for_arc_length`]). Here it only starts the search below, so the
//!    cheap first phase of that solver (fixed-panel quadrature, 1e-7 relative) is used.
//! 2. A *chord walk* places nodes on the curve: from `t₀ = 0`, each `t_k` is the first
//!    parameter after `t_{k−1}` with `|p(t_k) − p(t_{k−1})| = l`. With `k` full steps fitting
//!    in `t ≤ 1`, the discrete length is `F(α) = k·l + |P1 − n_k|`. `F` is continuous in α
//!    while the curve bends no tighter than `l/2`, `F(0) = |P1 − P0|`, and `F ≤ L` (a chord is
//!    never longer than its arc), with `L − F = O(L (lκ)²)` for curvature κ.
//! 3. The returned α solves `F(α) = S·l` to 1e-12 m. It is a little larger than `α_arc`, by a
//!    relative `O((lκ)²)` (measured +0.2 % to +0.8 % on 250–500 mm bends): the polyline needs
//!    a slightly longer curve to reach the same length.
//!
//! Two solvers find that root:
//!
//! - **Whole-chain Newton** (fast path): unknowns `α, t_1 … t_{S−1}`, equations
//!   `|p(t_k) − p(t_{k−1})| = l` for `k = 1 … S`, from nodes at equal arc-length spacing at
//!   `α_arc`. The Jacobian is bidiagonal plus one column, so each step is O(S); three steps
//!   usually. Accepted when every link is `l` long within 1e-12 m.
//! - **Bracketed walks** (fallback): chord walks at successive α, warm-started from the walk
//!   before, with a quasi-Newton step (`dL/dα`, then secants) inside a bracket and bisection.
//!
//! Both give the same chain on curves that bend no tighter than `l/2` (then every crossing is
//! the only one within reach). Coaxial guides with slack are the known weak spot of the
//! Hermite family: the curve stays on the axis and can only fold back on itself.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, UnitQuaternion, Vector3};

use super::hermite::{ArcLengthError, ArcLengthFit, HermiteCurve, Precision, arc_length_tolerance};
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
/// Iteration limit of the whole-chain Newton solve (it converges in 3–5 when it works).
const MAX_CHAIN_ITERATIONS: usize = 12;
/// Fewest panels of the arc-length grid behind the whole-chain Newton's initial chain.
const MIN_ARC_GRID_PANELS: usize = 16;
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
/// [`ConnectError::InvalidInput`] for `S = 0`, `S > MAX_SUB_SEGMENTS`, a pitch that is not
/// finite and positive, or a non-finite pose; [`ConnectError::NoSolution`] when no α places
/// the chain (a single sub-segment between guides not exactly `l` apart, or curves that fold
/// or bend tighter than half the pitch).
///
/// The twist mismatch is measured with `atan2` on the principal branch `(−π, π]`: an exact
/// half turn is corrected by `+π`.
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
    if sub_segments == 1 && distance < natural - tolerance {
        return Err(ConnectError::NoSolution {
            reason: format!(
                "a single rigid sub-segment spans exactly {:.1} mm, but the guides are {:.1} mm apart",
                natural * 1e3,
                distance * 1e3
            ),
        });
    }
    let mut curve = HermiteCurve::new(
        guides.start_point,
        guides.start_tangent,
        guides.end_point,
        guides.end_tangent,
        0.0,
    );
    // α_arc only starts the search for the discrete-length root, so the cheap estimate does.
    let fit = curve
        .alpha_and_slope_for_arc_length(natural, Precision::Estimate)
        .map_err(arc_length_failure)?;
    let chain = match whole_chain_newton(&mut curve, fit.alpha_m, sub_segments, pitch_m, tolerance)
    {
        Some(chain) => chain,
        None => chain_by_walks(&mut curve, fit, sub_segments, pitch_m, distance)?,
    };
    let RigidChain {
        alpha,
        params,
        nodes,
    } = chain;
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

/// `S + 1` nodes on the curve with tangent scale `alpha`, every adjacent pair `l` apart.
struct RigidChain {
    alpha: f64,
    /// Curve parameters `t_0 = 0 … t_S = 1` of the nodes.
    params: Vec<f64>,
    nodes: Vec<Point3<f64>>,
}

/// The fast path to `F(α) = S·l`: whole-chain Newton from `α_arc`, accepted if every link of
/// the chain it found is `l` long within `tolerance` (m). `None` if it fails. On curves that
/// bend no tighter than `l/2` this is the chain the walk would find (the crossings are unique
/// there); otherwise it is still a valid rigid chain on the curve.
fn whole_chain_newton(
    curve: &mut HermiteCurve,
    alpha_arc: f64,
    sub_segments: usize,
    pitch: f64,
    tolerance: f64,
) -> Option<RigidChain> {
    let mut params = Vec::with_capacity(sub_segments + 1);
    let alpha = ChainNewton::new(pitch, sub_segments).solve(curve, alpha_arc, &mut params)?;
    let last = params.len() - 1;
    let nodes: Vec<Point3<f64>> = params
        .iter()
        .enumerate()
        .map(|(k, &t)| match k {
            0 => curve.start(),
            _ if k == last => curve.end(),
            _ => curve.point(t),
        })
        .collect();
    let rigid = nodes
        .windows(2)
        .all(|pair| ((pair[1] - pair[0]).norm() - pitch).abs() < tolerance);
    rigid.then_some(RigidChain {
        alpha,
        params,
        nodes,
    })
}

/// The robust path: bracketed root find of `F(α) = S·l` over chord walks from `α_arc`.
fn chain_by_walks(
    curve: &mut HermiteCurve,
    fit: ArcLengthFit,
    sub_segments: usize,
    pitch: f64,
    distance: f64,
) -> Result<RigidChain, ConnectError> {
    let natural = sub_segments as f64 * pitch;
    let tolerance = arc_length_tolerance(natural);
    let mut walk = ChordWalk::new(pitch, sub_segments);
    let alpha = DiscreteLengthSolver::new(natural, tolerance, distance)
        .solve(curve, fit, &mut walk)
        .map_err(|error| explain_tight_bend(error, curve, pitch))?;
    let (nodes, params) = walk.connected_nodes(sub_segments, curve.end())?;
    Ok(RigidChain {
        alpha,
        params,
        nodes,
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
/// Coaxial guides are the common case: the Hermite curve stays on their axis and can only
/// gain length by folding back on itself (cusps at α > 3|P1 − P0|).
fn explain_tight_bend(error: ConnectError, curve: &HermiteCurve, pitch_m: f64) -> ConnectError {
    let ConnectError::NoSolution { reason } = error else {
        return error;
    };
    let shape = match tightest_bend(curve, 512) {
        Bend::Cusp => "the Hermite curve folds back on itself (a cusp)".to_string(),
        Bend::Radius(radius) => {
            let note = if radius < 0.5 * pitch_m {
                ", below half the sub-segment pitch"
            } else {
                ""
            };
            format!(
                "the Hermite curve bends to a radius of {:.2} mm{note}",
                radius * 1e3
            )
        }
    };
    ConnectError::NoSolution {
        reason: format!("{reason}; {shape}"),
    }
}

/// The tightest bend of a curve.
enum Bend {
    /// The velocity vanishes somewhere: the curve reverses.
    Cusp,
    /// Smallest radius of curvature (m).
    Radius(f64),
}

/// Smallest radius of curvature `|p'|³ / |p' × p''|` over `samples + 1` parameters, or a cusp
/// where the velocity turns by more than 90° between neighbouring samples.
fn tightest_bend(curve: &HermiteCurve, samples: usize) -> Bend {
    let mut min_radius = f64::INFINITY;
    let mut previous_velocity: Option<Vector3<f64>> = None;
    for i in 0..=samples {
        let t = i as f64 / samples as f64;
        let (velocity, acceleration) = (curve.derivative(t), curve.second_derivative(t));
        if previous_velocity.is_some_and(|previous| previous.dot(&velocity) < 0.0) {
            return Bend::Cusp;
        }
        previous_velocity = Some(velocity);
        let radius = velocity.norm().powi(3) / velocity.cross(&acceleration).norm();
        if !radius.is_nan() {
            min_radius = min_radius.min(radius);
        }
    }
    Bend::Radius(min_radius)
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
    if !finite || norm.is_nan() || norm <= 1e-6 {
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
    /// `t_0 … t_k` of the latest walk.
    params: Vec<f64>,
    /// `n_0 … n_k` of the latest walk.
    nodes: Vec<Point3<f64>>,
    /// Parameters of the walk before, whose steps warm-start the next walk.
    previous_params: Vec<f64>,
}

impl ChordWalk {
    fn new(pitch: f64, sub_segments: usize) -> Self {
        let max_steps = 2 * sub_segments + 8;
        Self {
            pitch,
            max_steps,
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
        let mut crossing = CrossingSearch::new(curve, self.pitch);
        for k in 0..self.max_steps {
            let (t, node) = (self.params[k], self.nodes[k]);
            let hint = self.previous_step(k);
            match crossing.next(t, node, hint)? {
                Some(sample) => {
                    self.params.push(sample.t);
                    self.nodes.push(sample.point);
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
    /// `|g|` below which the next Newton step is accepted unevaluated.
    final_step_gap: f64,
    third_derivative_bound: f64,
}

impl<'a> CrossingSearch<'a> {
    fn new(curve: &'a HermiteCurve, pitch: f64) -> Self {
        let chord_tolerance = chord_tolerance(curve, pitch);
        Self {
            curve,
            pitch,
            gap_tolerance: 2.0 * pitch * chord_tolerance,
            final_step_gap: final_step_gap(pitch, chord_tolerance),
            third_derivative_bound: curve.third_derivative_norm() / 6.0,
        }
    }

    /// The first `t > from_t` (≤ 1) with `|p(t) − node| = l`, `None` if the curve ends first.
    ///
    /// A probe is placed where the crossing is expected: the step the previous walk took here
    /// (`hint`), else a step predicted from the local speed, acceleration and curvature. An
    /// outside probe brackets the crossing; from an inside probe one Newton step forward
    /// usually lands on it. Failing both, the curve is marched in parameter steps whose arc
    /// length is bounded (from `|p'|`, `|p''|`, `|p'''|`) by a little more than the distance
    /// still missing. While the curve bends no tighter than `l/2`, the distance from the node
    /// grows monotonically up to `l`, so the crossing found is the first one.
    fn next(
        &mut self,
        from_t: f64,
        node: Point3<f64>,
        hint: Option<f64>,
    ) -> Result<Option<Sample>, ConnectError> {
        let bound = ArcBound::at(self.curve, from_t, self.third_derivative_bound);
        let plausible = |step: &f64| *step > 0.0 && bound.arc(*step) <= 1.5 * self.pitch;
        let step = hint
            .filter(plausible)
            .or_else(|| self.predicted_step(from_t).filter(plausible));
        let Some(step) = step else {
            return self.march_and_refine(from_t, &node);
        };
        let probe = self.sample((from_t + step).min(1.0), &node);
        if probe.gap.abs() <= self.gap_tolerance {
            return Ok(Some(probe));
        }
        if probe.gap > 0.0 {
            return Ok(Some(self.refine(&node, from_t, probe)));
        }
        // Inside the sphere: the curve cannot have left and come back if the arc is shorter
        // than the way out and back in.
        let distance = (probe.gap + self.pitch * self.pitch).max(0.0).sqrt();
        if bound.arc(probe.t - from_t) >= 2.0 * self.pitch - distance {
            return self.march_and_refine(from_t, &node);
        }
        if probe.t >= 1.0 {
            return Ok(None);
        }
        let newton = probe.t - probe.gap / probe.slope;
        let modest = bound.arc(newton - from_t) < 2.0 * self.pitch - distance;
        if probe.slope > 0.0 && newton > probe.t && newton <= 1.0 && modest {
            let next = self.sample(newton, &node);
            if next.gap >= 0.0 || next.gap.abs() <= self.gap_tolerance {
                return Ok(Some(self.refine(&node, probe.t, next)));
            }
            return self.march_and_refine(newton, &node);
        }
        self.march_and_refine(probe.t, &node)
    }

    /// Parameter step whose chord is expected to be `l`: the arc `l (1 + (κl)²/24)` (a chord
    /// is shorter than its arc) converted to a parameter step with the speed and its rate of
    /// change. `None` where the speed vanishes.
    fn predicted_step(&self, t: f64) -> Option<f64> {
        let velocity = self.curve.derivative(t);
        let acceleration = self.curve.second_derivative(t);
        let speed_squared = velocity.norm_squared();
        if speed_squared.is_nan() || speed_squared <= 0.0 {
            return None;
        }
        let speed = speed_squared.sqrt();
        let curvature_squared =
            velocity.cross(&acceleration).norm_squared() / speed_squared.powi(3);
        let arc = self.pitch * (1.0 + curvature_squared * self.pitch * self.pitch / 24.0);
        let speed_rate = velocity.dot(&acceleration) / speed;
        let step = arc / speed - 0.5 * speed_rate * arc * arc / (speed * speed_squared);
        (step > 0.0 && step.is_finite()).then_some(step)
    }

    /// Marches to a bracket from `from_t` and solves for the crossing in it.
    fn march_and_refine(
        &self,
        from_t: f64,
        node: &Point3<f64>,
    ) -> Result<Option<Sample>, ConnectError> {
        Ok(self
            .march(from_t, node)?
            .map(|(inside, outside)| self.refine(node, inside, self.sample(outside, node))))
    }

    /// The curve at `t` relative to the sphere of radius `l` about `node`.
    #[inline]
    fn sample(&self, t: f64, node: &Point3<f64>) -> Sample {
        let point = self.curve.point(t);
        let offset = point - node;
        Sample {
            t,
            point,
            gap: offset.norm_squared() - self.pitch * self.pitch,
            slope: 2.0 * offset.dot(&self.curve.derivative(t)),
        }
    }

    /// Steps forward from `t` (inside the sphere) until the curve is outside; returns the
    /// bracket `(inside, outside)`, or `None` if `t = 1` is reached inside.
    fn march(&self, mut t: f64, node: &Point3<f64>) -> Result<Option<(f64, f64)>, ConnectError> {
        for _ in 0..MAX_MARCH_STEPS {
            let distance = (self.curve.point(t) - node).norm();
            let missing = 1.1 * (self.pitch - distance).max(0.0) + 0.01 * self.pitch;
            let step = self.parameter_step_for_arc(t, missing);
            let next = (t + step).min(1.0).max(next_up(t));
            if (self.curve.point(next) - node).norm_squared() >= self.pitch * self.pitch {
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

    /// Largest `h ≤ 1 − t` whose arc-length bound does not exceed `arc`.
    fn parameter_step_for_arc(&self, t: f64, arc: f64) -> f64 {
        ArcBound::at(self.curve, t, self.third_derivative_bound).step_for(arc, 1.0 - t)
    }

    /// Solves `g(t) = 0` in the bracket `[inside, start.t]` (`g(start) ≥ 0`) by Newton from
    /// `start`, bisecting whenever Newton leaves the bracket or does not halve `|g|`.
    fn refine(&self, node: &Point3<f64>, mut inside: f64, start: Sample) -> Sample {
        let mut outside = start.t;
        let mut current = start;
        let mut previous_gap = f64::INFINITY;
        for _ in 0..MAX_CROSSING_ITERATIONS {
            if current.gap.abs() <= self.gap_tolerance {
                return current;
            }
            if current.gap < 0.0 {
                inside = current.t;
            } else {
                outside = current.t;
            }
            if outside - inside <= 4.0 * f64::EPSILON * outside.abs().max(f64::MIN_POSITIVE) {
                break;
            }
            let newton = current.t - current.gap / current.slope;
            let bracketed = newton > inside && newton < outside;
            let progressed = current.gap.abs() <= 0.5 * previous_gap;
            if bracketed && progressed && current.gap.abs() <= self.final_step_gap {
                return Sample {
                    t: newton,
                    point: self.curve.point(newton),
                    ..current
                };
            }
            previous_gap = current.gap.abs();
            let t = if bracketed && progressed {
                newton
            } else {
                0.5 * (inside + outside)
            };
            current = self.sample(t, node);
        }
        self.sample(outside, node)
    }
}

/// Chord accuracy (m) the crossing solves aim at: a few ulp of the curve's coefficients, the
/// round-off level of evaluating `p(t)` (far below the 1e-12 m length tolerance).
fn chord_tolerance(curve: &HermiteCurve, pitch: f64) -> f64 {
    8.0 * f64::EPSILON * curve.coefficient_scale().max(pitch)
}

/// `|g| = ||p − n|² − l²|` below which one more Newton step is taken without evaluating its
/// result: Newton squares the chord error `e ≈ |g| / 2l` with a factor below ~3/l while the
/// curve bends no tighter than l/2, so from `e ≤ 0.3 √(tol·l)` the step lands within `tol`.
/// (Only speed depends on this: the verifying walk re-checks every chord.)
fn final_step_gap(pitch: f64, chord_tolerance: f64) -> f64 {
    0.6 * pitch * (chord_tolerance * pitch).sqrt()
}

/// Upper bound of the arc length from `t` over a parameter step `h`:
/// `|p'(t)| h + |p''(t)| h²/2 + |c₃| h³`, since `|p'(t + τ)| ≤ |p'(t)| + |p''(t)| τ + 3|c₃| τ²`.
/// It lets the walk step along the curve without stepping over an excursion.
#[derive(Debug, Clone, Copy)]
struct ArcBound {
    speed: f64,
    acceleration: f64,
    cubic: f64,
}

impl ArcBound {
    fn at(curve: &HermiteCurve, t: f64, cubic: f64) -> Self {
        Self {
            speed: curve.derivative(t).norm(),
            acceleration: curve.second_derivative(t).norm(),
            cubic,
        }
    }

    fn arc(&self, h: f64) -> f64 {
        h * (self.speed + h * (0.5 * self.acceleration + h * self.cubic))
    }

    /// Largest `h ≤ limit` with `arc(h) ≤ arc` (Newton from the right on the convex bound; a
    /// few iterations suffice, the bound is conservative anyway).
    fn step_for(&self, arc: f64, limit: f64) -> f64 {
        let mut h = if self.speed > 0.0 {
            (arc / self.speed).min(limit)
        } else {
            limit
        };
        for _ in 0..16 {
            let excess = self.arc(h) - arc;
            if excess.is_nan() || excess <= 0.0 {
                break;
            }
            let slope = self.speed + h * (self.acceleration + 3.0 * h * self.cubic);
            let next = h - excess / slope;
            let converged = next > 0.99 * h;
            h = next;
            if converged {
                break;
            }
        }
        h.max(0.0)
    }
}

/// A point of the curve in a crossing search: parameter, position, `g` and `g'`.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    point: Point3<f64>,
    /// `g(t) = |p(t) − node|² − l²` (m²): negative inside the sphere of radius `l`.
    gap: f64,
    /// `g'(t)` (m² per unit parameter).
    slope: f64,
}

/// The next representable `f64` above a non-negative finite `t`.
fn next_up(t: f64) -> f64 {
    f64::from_bits(t.to_bits() + 1)
}

/// Newton's method on the whole chain at once: unknowns `α, t_1 … t_{S−1}`, equations
/// `|p(t_k) − p(t_{k−1})|² = l²` for `k = 1 … S` with `t_0 = 0`, `t_S = 1`. The Jacobian is
/// lower bidiagonal in the `t_k` plus one column for α, so a forward sweep expresses each
/// correction as `δt_k = a_k + b_k δα` and the last equation fixes `δα`: O(S) per iteration,
/// with curve evaluations that do not depend on each other (unlike the node-by-node walk).
///
/// It only accelerates the root find of `F(α) = S·l`: its result is confirmed by a chord
/// walk warm-started from the chain it found, and the bracketed walk-based solver takes over
/// if it fails or the walk disagrees.
struct ChainNewton {
    pitch: f64,
    sub_segments: usize,
    /// `|g|` of every chord below which one last update is applied without re-evaluation.
    final_step_gap: f64,
    /// Forward-sweep coefficients `(a_k, b_k)`, `k = 1 … S−1`.
    sweep: Vec<(f64, f64)>,
    /// `(arc length, speed)` at the grid parameters of the initial chain.
    grid: Vec<(f64, f64)>,
}

impl ChainNewton {
    fn new(pitch: f64, sub_segments: usize) -> Self {
        Self {
            pitch,
            sub_segments,
            final_step_gap: 0.0,
            sweep: Vec::with_capacity(sub_segments),
            grid: Vec::with_capacity(sub_segments.max(MIN_ARC_GRID_PANELS) + 1),
        }
    }

    /// Solves from `alpha`, leaving the chain parameters `t_0 … t_S` in `params`; returns the
    /// α found, or `None` if the iteration fails (non-monotone chain, negative α, no
    /// convergence).
    fn solve(
        &mut self,
        curve: &mut HermiteCurve,
        alpha: f64,
        params: &mut Vec<f64>,
    ) -> Option<f64> {
        if self.sub_segments < 2 {
            return None;
        }
        curve.set_alpha(alpha);
        self.final_step_gap = final_step_gap(self.pitch, chord_tolerance(curve, self.pitch));
        self.initial_chain(curve, params)?;
        let mut alpha = alpha;
        for _ in 0..MAX_CHAIN_ITERATIONS {
            let (delta_alpha, max_gap) = self.forward_sweep(curve, params)?;
            alpha += delta_alpha;
            for (t, (a, b)) in params[1..self.sub_segments].iter_mut().zip(&self.sweep) {
                *t += a + b * delta_alpha;
            }
            let monotone = params.windows(2).all(|pair| pair[0] < pair[1]);
            if !(monotone && alpha >= 0.0 && alpha.is_finite()) {
                return None;
            }
            curve.set_alpha(alpha);
            if max_gap <= self.final_step_gap {
                return Some(alpha);
            }
        }
        None
    }

    /// Parameters at equal arc-length spacing: the arc length is accumulated on a uniform grid
    /// of parameter panels (3-point Gauss–Legendre each) and inverted by cubic Hermite
    /// interpolation of `t(s)`, whose slope is `1/|p'|`. At `α_arc` these chords are short by
    /// only `O(l³κ²)`, so two or three Newton sweeps finish the job.
    fn initial_chain(&mut self, curve: &HermiteCurve, params: &mut Vec<f64>) -> Option<()> {
        let panels = self.sub_segments.max(MIN_ARC_GRID_PANELS);
        let width = 1.0 / panels as f64;
        self.grid.clear();
        let mut arc = 0.0;
        self.grid.push((0.0, curve.derivative(0.0).norm()));
        for j in 0..panels {
            let mid = (j as f64 + 0.5) * width;
            let offset = 0.5 * width * (0.6_f64).sqrt();
            let speeds = [mid - offset, mid, mid + offset].map(|t| curve.derivative(t).norm());
            arc += 0.5 * width * (5.0 * speeds[0] + 8.0 * speeds[1] + 5.0 * speeds[2]) / 9.0;
            let t = (j + 1) as f64 * width;
            self.grid.push((arc, curve.derivative(t).norm()));
        }
        let spacing = arc / self.sub_segments as f64;
        params.clear();
        params.push(0.0);
        let mut j = 0;
        for k in 1..self.sub_segments {
            let target = k as f64 * spacing;
            while j + 1 < panels && self.grid[j + 1].0 < target {
                j += 1;
            }
            params.push(invert_arc_length(
                &self.grid[j..j + 2],
                j as f64 * width,
                width,
                target,
            ));
        }
        params.push(1.0);
        let valid = params.windows(2).all(|pair| pair[0] < pair[1]);
        valid.then_some(())
    }

    /// One Newton step: fills the sweep coefficients and returns `(δα, max_k |g_k|)` at the
    /// current chain. `None` if a chord does not leave its start node forwards (`g'_k ≤ 0`)
    /// or the step is singular.
    fn forward_sweep(&mut self, curve: &HermiteCurve, params: &[f64]) -> Option<(f64, f64)> {
        let last = self.sub_segments;
        self.sweep.clear();
        let mut previous = (
            curve.start().coords,
            curve.derivative(0.0),
            Vector3::zeros(),
        );
        let (mut a_previous, mut b_previous) = (0.0, 0.0);
        let mut max_gap: f64 = 0.0;
        for (k, &t) in params.iter().enumerate().skip(1) {
            let current = if k == last {
                // p(1) = P1 whatever α, so ∂p/∂α vanishes there.
                (curve.end().coords, Vector3::zeros(), Vector3::zeros())
            } else {
                (
                    curve.point(t).coords,
                    curve.derivative(t),
                    curve.point_alpha_derivative(t),
                )
            };
            let chord = current.0 - previous.0;
            let gap = chord.norm_squared() - self.pitch * self.pitch;
            max_gap = max_gap.max(gap.abs());
            let d_alpha = 2.0 * chord.dot(&(current.2 - previous.2));
            // t_0 is fixed, so the first chord does not depend on a previous parameter.
            let d_previous = if k == 1 {
                0.0
            } else {
                -2.0 * chord.dot(&previous.1)
            };
            if k == last {
                let delta_alpha =
                    -(gap + d_previous * a_previous) / (d_alpha + d_previous * b_previous);
                return delta_alpha.is_finite().then_some((delta_alpha, max_gap));
            }
            let d_current = 2.0 * chord.dot(&current.1);
            if d_current.is_nan() || d_current <= 0.0 {
                return None;
            }
            // The reciprocal does not depend on the recurrence, so it is computed off the
            // critical path; the recurrence itself is then two fused multiply–adds per node.
            let inverse = -1.0 / d_current;
            a_previous = (gap + d_previous * a_previous) * inverse;
            b_previous = (d_alpha + d_previous * b_previous) * inverse;
            self.sweep.push((a_previous, b_previous));
            previous = current;
        }
        None
    }
}

/// The parameter at arc length `target` within one grid panel `[t_a, t_a + width]`, whose
/// ends carry `(arc length, speed)`: cubic Hermite interpolation of `t(s)` with slopes
/// `1/speed`, or linear where a speed vanishes (a cusp).
fn invert_arc_length(ends: &[(f64, f64)], t_a: f64, width: f64, target: f64) -> f64 {
    let ((s_a, speed_a), (s_b, speed_b)) = (ends[0], ends[1]);
    let span = s_b - s_a;
    if span.is_nan() || span <= 0.0 {
        return t_a + 0.5 * width;
    }
    let u = ((target - s_a) / span).clamp(0.0, 1.0);
    if !(speed_a > 0.0 && speed_b > 0.0) {
        return t_a + u * width;
    }
    let (u2, u3) = (u * u, u * u * u);
    let slope_a = span / speed_a;
    let slope_b = span / speed_b;
    t_a + (-2.0 * u3 + 3.0 * u2) * width + (u3 - 2.0 * u2 + u) * slope_a + (u3 - u2) * slope_b
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
    principal_angle(target_normal.dot(&binormal), target_normal.dot(&normal))
}

/// `atan2(y, x)` on `(−π, π]`: `atan2` itself returns `−π` for `y = −0`, `x < 0`.
fn principal_angle(y: f64, x: f64) -> f64 {
    let angle = y.atan2(x);
    if angle <= -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        angle
    }
}

/// Rotates frame `k` about its own tangent by `twist · k / S`, so the first frame is kept and
/// the last turns by the whole `twist`. The angles advance by a fixed step, so their sines
/// and cosines follow by rotation recurrence, re-seeded exactly every few frames to bound
/// round-off; the last frame is always seeded exactly.
fn distribute_twist(frames: &mut [Rotation3<f64>], twist: f64) {
    const RESEED_INTERVAL: usize = 16;
    let last = frames.len().saturating_sub(1);
    let step = twist / last.max(1) as f64;
    let (step_sin, step_cos) = step.sin_cos();
    let (mut sin, mut cos) = (0.0, 1.0);
    for (k, frame) in frames.iter_mut().enumerate().skip(1) {
        (sin, cos) = if k % RESEED_INTERVAL == 0 || k == last {
            (step * k as f64).sin_cos()
        } else {
            (
                sin * step_cos + cos * step_sin,
                cos * step_cos - sin * step_sin,
            )
        };
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
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Guide pairs of the integration tests: S-bends, a bend, a U-loop, a hairpin, coincident
    /// guides; `(start, end, sub-segments)`.
    fn cases() -> Vec<(Pose, Pose, usize)> {
        let along_x = pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0]);
        let up = pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]);
        let down = pose_from_xyz_rpy([0.0; 3], [PI, 0.0, 0.0]);
        let mut cases = vec![
            (
                along_x,
                pose_from_xyz_rpy([0.15, 0.05, 0.025], [0.7, 1.0, 0.2]),
                25,
            ),
            (
                along_x,
                pose_from_xyz_rpy([0.3, 0.1, 0.05], [0.7, 1.0, 0.2]),
                50,
            ),
            (
                up,
                pose_from_xyz_rpy([0.2, 0.0, 0.1], [0.0, FRAC_PI_2, 0.0]),
                35,
            ),
            (down, pose_from_xyz_rpy([0.1, 0.0, 0.0], [PI, 0.0, 0.3]), 40),
            (up, pose_from_xyz_rpy([0.1, 0.0, 0.0], [PI, 0.0, 0.0]), 30),
        ];
        cases.push((up, pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0]), 40));
        cases
    }

    fn curve_between(start: &Pose, end: &Pose) -> HermiteCurve {
        HermiteCurve::between_guides(start, end, 0.0)
    }

    /// The whole-chain Newton and the bracketed walk root find are independent algorithms
    /// for the same chain: they must agree.
    #[test]
    fn whole_chain_newton_agrees_with_the_walk_root_find() {
        for (start, end, sub_segments) in cases() {
            let natural = sub_segments as f64 * 0.01;
            let mut curve = curve_between(&start, &end);
            let fit = curve
                .alpha_and_slope_for_arc_length(natural, Precision::Exact)
                .unwrap();
            let tolerance = arc_length_tolerance(natural);
            let fast = whole_chain_newton(&mut curve, fit.alpha_m, sub_segments, 0.01, tolerance)
                .expect("whole-chain Newton converges on these cases");
            let distance = (end.translation.vector - start.translation.vector).norm();
            let walked = chain_by_walks(&mut curve, fit, sub_segments, 0.01, distance).unwrap();
            assert!(
                (fast.alpha - walked.alpha).abs() < 1e-10,
                "{} vs {}",
                fast.alpha,
                walked.alpha
            );
            for (a, b) in fast.nodes.iter().zip(&walked.nodes) {
                assert!((a - b).norm() < 1e-10);
            }
            for pair in walked.nodes.windows(2) {
                assert!(((pair[1] - pair[0]).norm() - 0.01).abs() < 1e-12);
            }
        }
    }

    /// `F` is continuous in α and brackets the root between α_arc and above.
    #[test]
    fn discrete_length_is_below_the_arc_length_and_continuous() {
        let (start, end, sub_segments) = cases()[1];
        let mut curve = curve_between(&start, &end);
        let natural = sub_segments as f64 * 0.01;
        let alpha_arc = curve.alpha_for_arc_length(natural).unwrap();
        let mut walk = ChordWalk::new(0.01, sub_segments);
        let mut previous: Option<f64> = None;
        for i in 0..=200 {
            let alpha = alpha_arc * (0.9 + 0.001 * i as f64);
            curve.set_alpha(alpha);
            let discrete = walk.run(&curve).unwrap();
            assert!(discrete <= curve.arc_length() + 1e-15);
            if let Some(previous) = previous {
                // dF/dα ≈ dL/dα ≈ 0.33 here, and the α step is 1.4e-3 m.
                assert!((discrete - previous).abs() < 1e-3, "jump at α = {alpha}");
            }
            previous = Some(discrete);
        }
    }

    #[test]
    fn a_half_turn_twist_is_reported_as_plus_pi() {
        let frame = Rotation3::identity();
        // atan2(−0, −1) = −π: the branch cut itself.
        let target = Unit::new_unchecked(Vector3::new(-1.0, -0.0, 0.0));
        assert_eq!(principal_angle(-0.0, -1.0), PI);
        assert_eq!(twist_mismatch(&frame, &target), PI);
        let quarter = Unit::new_unchecked(Vector3::new(0.0, 1.0, 0.0));
        assert!((twist_mismatch(&frame, &quarter) - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn a_single_sub_segment_needs_guides_exactly_one_pitch_apart() {
        let start = pose_from_xyz_rpy([0.0; 3], [0.0, 0.0, 0.0]);
        let exact = pose_from_xyz_rpy([0.0, 0.0, 0.01], [0.0, 0.0, 0.4]);
        let geometry = connect(&start, &exact, 1, 0.01).unwrap();
        assert_eq!(geometry.nodes.len(), 2);
        assert!((geometry.twist_correction_rad - 0.4).abs() < 1e-12);
        let closer = pose_from_xyz_rpy([0.0, 0.0, 0.005], [0.0, 0.0, 0.0]);
        assert!(matches!(
            connect(&start, &closer, 1, 0.01),
            Err(ConnectError::NoSolution { .. })
        ));
        let two = connect(
            &start,
            // Two links along a circle of radius 30 mm bending towards +x.
            &pose_from_xyz_rpy([0.00648, 0.0, 0.01862], [0.0, 0.6698, 0.0]),
            2,
            0.01,
        )
        .unwrap();
        for pair in two.nodes.windows(2) {
            assert!(((pair[1] - pair[0]).norm() - 0.01).abs() < 1e-12);
        }
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
        for end in &ends {
            for (sub_segments, pitch) in
                [(1, 0.01), (3, 0.01), (40, 1e-300), (40, 1e-9), (7, 1e100)]
            {
                let _ = connect(&start, end, sub_segments, pitch);
            }
        }
        let mut unnormalized = start;
        unnormalized.rotation =
            UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(2.0, 0.0, 0.0, 0.0));
        let end = pose_from_xyz_rpy([0.1, 0.0, 0.1], [0.0, 0.0, 0.0]);
        assert!(connect(&unnormalized, &end, 20, 0.01).is_ok());
        let mut zero = start;
        zero.rotation =
            UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0));
        assert!(matches!(
            connect(&zero, &end, 20, 0.01),
            Err(ConnectError::InvalidInput { .. })
        ));
    }
}
