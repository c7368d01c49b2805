//! The shape parameter (tangent scale α or bow height β) that gives a [`HermiteCurve`] a
//! prescribed arc length: a bracketed Newton iteration on the convex `L(q)`, first on a cheap
//! fixed-panel 10-point Gauss rule, then on the adaptive rule, whose later evaluations start
//! from the panels the previous one accepted.
//!
//! The quadrature also gives `d²L/dq²`, so the residual a Newton step `δ` leaves is known
//! before it is evaluated: `½ L'' δ²` (Taylor). A step whose predicted residual is a thousandth
//! of the tolerance needs no confirming evaluation. The search can also pause after the cheap
//! phase and resume later: `connect` refines only the candidate curve it places.

use super::arc_length::{
    ArcLengthError, InitialEdges, LengthSums, QuadratureScratch, arc_length_tolerance,
};
use super::{CurveParameter, HermiteCurve};

/// The cheap phase stops at this relative residual (the 10-point rule on the initial panels
/// is good to ~1e-6 on ordinary bends); the adaptive phase takes it from there.
const COARSE_REL_TOL: f64 = 1e-6;
/// A length from the cheap rule farther than this fraction from the target is on the same
/// side of it as the precise length.
const ROUGH_LENGTH_MARGIN: f64 = 0.01;
/// Iteration limit of the parameter root find (Newton, doubling and bisection steps together).
const MAX_ROOT_ITERATIONS: usize = 200;
/// The root find gives up beyond this multiple of (target + chord): no finite-length cable
/// needs a larger tangent scale or bow.
const PARAMETER_LIMIT_FACTOR: f64 = 1e6;
/// A Newton step is accepted without evaluating its result when the Taylor prediction of the
/// residual it leaves, `½ L'' δ²`, is below this fraction of the tolerance. The margin covers
/// the change of `L''` across the (short) step and the error of its cheap quadrature, both a
/// few per cent at most where the speed has no sharp minimum.
const PREDICTION_FRACTION: f64 = 0.1;
/// Predictions are trusted only for steps shorter than this fraction of `|q| + target`: a
/// cusp forming inside a long step would put a kink into `L(q)` that `L''` cannot see.
const PREDICTION_STEP_FRACTION: f64 = 1e-3;

/// A root find of `L(q) = target`, paused after its cheap phase; see
/// [`HermiteCurve::parameter_search`].
#[derive(Debug, Clone)]
pub(crate) enum ParameterSearch {
    /// The root, to the full tolerance.
    Converged(f64),
    /// The precise phase, not yet run.
    Pending {
        /// Root of the cheap fixed-panel arc length (~1e-6 relative on ordinary bends), if
        /// that phase converged.
        estimate: Option<f64>,
        /// Boxed: the search is moved around while it waits, the bracket holds a curve.
        bracket: Box<NewtonBracket>,
    },
}

impl ParameterSearch {
    /// The root if converged, else the cheap phase's root, if any.
    pub(crate) fn estimate(&self) -> Option<f64> {
        match self {
            Self::Converged(root) => Some(*root),
            Self::Pending { estimate, .. } => *estimate,
        }
    }

    /// Whether [`Self::estimate`] is the converged root.
    pub(crate) fn is_converged(&self) -> bool {
        matches!(self, Self::Converged(_))
    }

    /// Runs the precise phase until `|L − target|` is within the tolerance; returns the root.
    pub(crate) fn finish(&mut self) -> Result<f64, ArcLengthError> {
        let root = match self {
            Self::Converged(root) => return Ok(*root),
            Self::Pending { bracket, .. } => bracket.run()?,
        };
        *self = Self::Converged(root);
        Ok(root)
    }
}

impl HermiteCurve {
    /// The tangent scale α ≥ 0 (m) for which the arc length equals `target_m`, to
    /// `|L(α) − target| < 1e-12 m` (or 64 ulp of the target for cables longer than ~70 m).
    ///
    /// See [`Self::parameter_for_arc_length`]. Errors: [`ArcLengthError::BelowChord`] for a
    /// target below `|P1 − P0|`, [`ArcLengthError::InvalidInput`] for non-finite data or a
    /// negative target.
    pub fn alpha_for_arc_length(&self, target_m: f64) -> Result<f64, ArcLengthError> {
        self.parameter_for_arc_length(CurveParameter::Alpha, target_m)
    }

    /// The bow height β ≥ 0 (m), at this curve's α and bow direction, for which the arc length
    /// equals `target_m`, to `|L(β) − target| < 1e-12 m`. Needs the unbowed curve to be
    /// shorter than the target; see [`Self::parameter_for_arc_length`].
    pub fn bow_for_arc_length(&self, target_m: f64) -> Result<f64, ArcLengthError> {
        self.parameter_for_arc_length(CurveParameter::Bow, target_m)
    }

    /// The value `q ≥ 0` (m) of one shape parameter, all else fixed, for which the arc length
    /// equals `target_m` (to 1e-12 m, or 64 ulp of the target beyond ~70 m).
    ///
    /// `L(q)` is convex. With `L(0) < target` the root in `q > 0` is unique and lies on the
    /// increasing branch (`L` may first dip if the curve already bulges the other way), so
    /// Newton–Raphson started right of the root decreases monotonically onto it and a step
    /// from the left overshoots to the right at most once. The iteration keeps a bracket
    /// `[lo, hi]` (`lo` starts at 0, `hi` is found by doubling or by a Newton step when that
    /// is smaller) and bisects when a Newton step leaves the bracket or fails to halve the
    /// residual — e.g. on the flat stretch of `L(α)` near 0 when both tangents point along the
    /// chord, near cusps, or where `L(β)` still decreases. Newton first runs on a cheap
    /// fixed-panel quadrature (also convex) to 1e-6 relative, then on the adaptive one.
    ///
    /// A Newton step `δ` leaves the residual `½ L''(ξ) δ²`. Where the speed has no sharp
    /// minimum (no cusp can form nearby) and the step is short, `½ L'' δ²` from the quadrature
    /// predicts it; a step predicted below a thousandth of the tolerance is the root without a
    /// confirming evaluation (usually the first adaptive step). Near cusps every result is
    /// evaluated.
    ///
    /// Errors: [`ArcLengthError::BelowChord`] for a target below `|P1 − P0|`,
    /// [`ArcLengthError::BelowZeroParameter`] if `L(0)` already exceeds it,
    /// [`ArcLengthError::InvalidInput`] for non-finite data or a negative target,
    /// [`ArcLengthError::NotConverged`] if the root find fails.
    pub fn parameter_for_arc_length(
        &self,
        parameter: CurveParameter,
        target_m: f64,
    ) -> Result<f64, ArcLengthError> {
        self.parameter_search(parameter, target_m)?.finish()
    }

    /// The root find of [`Self::parameter_for_arc_length`], paused after its cheap phase:
    /// [`ParameterSearch::estimate`] is then the root of the fixed-panel 10-point Gauss arc
    /// length (~1e-6 relative on ordinary bends, not error-controlled), and
    /// [`ParameterSearch::finish`] runs the precise phase. Same errors, except that
    /// [`ArcLengthError::NotConverged`] may only come from `finish`.
    pub(crate) fn parameter_search(
        &self,
        parameter: CurveParameter,
        target_m: f64,
    ) -> Result<ParameterSearch, ArcLengthError> {
        let chord = self.chord_length();
        self.check_arc_length_problem(target_m, chord)?;
        let tolerance = arc_length_tolerance(target_m);
        if target_m < chord - tolerance {
            return Err(ArcLengthError::BelowChord {
                chord_m: chord,
                target_m,
            });
        }
        let mut curve = self.clone();
        curve.set_parameter(parameter, 0.0);
        let at_zero = match parameter {
            // The unbowed curve at α = 0 is the straight chord, whatever the tangents.
            CurveParameter::Alpha if self.bow_m == 0.0 => chord,
            _ => curve.length_compared_to(target_m),
        };
        if (at_zero - target_m).abs() <= tolerance {
            return Ok(ParameterSearch::Converged(0.0));
        }
        if at_zero > target_m {
            return Err(ArcLengthError::BelowZeroParameter {
                parameter,
                at_zero_m: curve.arc_length(),
                target_m,
            });
        }
        let start = match parameter {
            // |p'(α)| ≥ α |∂p'/∂α| − |p'(0)|, so L(α) ≥ α K − L(0) with K = ∫ |∂p'/∂α| dt:
            // from (target + L(0)) / K, right of the root, Newton decreases monotonically.
            CurveParameter::Alpha => (target_m + at_zero) / curve.sensitivity_length(parameter),
            // Height of the triangle of side length target/2 over a base of L(0): the highest
            // any curve of that length reaches, so Newton starts right of the root.
            CurveParameter::Bow => 0.5 * (target_m * target_m - at_zero * at_zero).sqrt(),
        };
        let problem = Problem {
            parameter,
            target: target_m,
            tolerance,
            limit: PARAMETER_LIMIT_FACTOR * (target_m + chord),
        };
        Ok(NewtonBracket::search(problem, curve, start))
    }

    /// The arc length, precise only where it is within 1 % of `target_m`: farther away the
    /// cheap fixed-panel rule tells the two apart just as well.
    fn length_compared_to(&self, target_m: f64) -> f64 {
        let initial = self.initial_edges();
        let rough = self
            .coarse_sums(CurveParameter::Alpha, initial.edges())
            .length;
        if (rough - target_m).abs() > ROUGH_LENGTH_MARGIN * target_m {
            rough
        } else {
            self.arc_length()
        }
    }

    fn check_arc_length_problem(&self, target_m: f64, chord: f64) -> Result<(), ArcLengthError> {
        let data_finite = self
            .start_tangent
            .iter()
            .chain(self.end_tangent.iter())
            .chain(self.bow_direction.iter())
            .chain([self.alpha_m, self.bow_m].iter())
            .all(|v| v.is_finite());
        if !chord.is_finite() || !data_finite {
            return Err(ArcLengthError::InvalidInput {
                what: "curve end points, tangents or shape parameters are not finite".into(),
            });
        }
        if !target_m.is_finite() || target_m < 0.0 {
            return Err(ArcLengthError::InvalidInput {
                what: format!("target arc length {target_m} m must be finite and ≥ 0"),
            });
        }
        Ok(())
    }
}

/// Arc-length quadrature used by a Newton phase.
#[derive(Debug, Clone)]
enum Quadrature {
    /// 10-point Gauss on the initial panels: cheap, ~1e-6 relative on ordinary bends.
    Coarse,
    /// Adaptive Gauss–Kronrod, ~1e-15 relative. Each evaluation starts from the panels the
    /// previous one accepted (near the root they usually pass as they are) plus the initial
    /// edges at the current parameter value.
    Adaptive {
        /// Accepted panel edges of the previous evaluation (empty before the first).
        partition: Vec<f64>,
        /// Buffers of the quadrature.
        scratch: QuadratureScratch,
    },
}

impl Quadrature {
    fn adaptive() -> Self {
        Self::Adaptive {
            partition: Vec::new(),
            scratch: QuadratureScratch::default(),
        }
    }

    /// `L` and `dL/dq` of `curve`, and its initial panel edges.
    fn evaluate(
        &mut self,
        curve: &HermiteCurve,
        parameter: CurveParameter,
    ) -> (LengthSums, InitialEdges) {
        let initial = curve.initial_edges();
        let sums = match self {
            Self::Coarse => curve.coarse_sums(parameter, initial.edges()),
            Self::Adaptive { partition, scratch } => {
                // The cusps move with the parameter: their new places join the old edges.
                for &edge in initial.edges() {
                    let at = partition.partition_point(|&t| t < edge);
                    if partition.get(at) != Some(&edge) {
                        partition.insert(at, edge);
                    }
                }
                let sums = curve.adaptive_sums(parameter, partition, scratch);
                std::mem::swap(partition, &mut scratch.accepted);
                sums
            }
        };
        (sums, initial)
    }
}

/// What a root find solves: `L(q) = target` within `tolerance`, `0 ≤ q ≤ limit`.
#[derive(Debug, Clone, Copy)]
struct Problem {
    parameter: CurveParameter,
    target: f64,
    tolerance: f64,
    limit: f64,
}

/// State of the bracketed Newton iteration on `L(q) − target`, `q ≥ 0`, `L(0) < target`.
#[derive(Debug, Clone)]
pub(crate) struct NewtonBracket {
    problem: Problem,
    curve: HermiteCurve,
    quadrature: Quadrature,
    /// The value to evaluate next.
    value: f64,
    /// Largest q known with `L < target`.
    lo: f64,
    /// Smallest q known with `L ≥ target`, once found.
    hi: Option<f64>,
    /// Best value evaluated so far and its `|L − target|`.
    best: (f64, f64),
    previous_residual: f64,
    /// Whether the last step was a Newton step.
    after_newton: bool,
    iterations: usize,
}

/// One step of the iteration: a Newton step or a safeguard (doubling, bisection).
struct Step {
    value: f64,
    newton: bool,
}

impl NewtonBracket {
    fn new(problem: Problem, curve: HermiteCurve, quadrature: Quadrature, start: f64) -> Self {
        Self {
            problem,
            curve,
            quadrature,
            value: start,
            lo: 0.0,
            hi: None,
            best: (0.0, f64::INFINITY),
            previous_residual: f64::INFINITY,
            after_newton: false,
            iterations: 0,
        }
    }

    /// Two phases: Newton on the cheap fixed-panel arc length (also convex) to a loose
    /// tolerance, run here, then Newton on the adaptive arc length from there, left to
    /// [`ParameterSearch::finish`]. The bracket restarts between phases because the two
    /// quadratures differ slightly. A failed coarse phase just leaves the precise one its
    /// default start.
    fn search(problem: Problem, curve: HermiteCurve, start: f64) -> ParameterSearch {
        let start = if start.is_finite() && start > 0.0 {
            start
        } else {
            problem.target
        };
        let loose = Problem {
            tolerance: problem.tolerance.max(COARSE_REL_TOL * problem.target),
            ..problem
        };
        let mut coarse = Self::new(loose, curve, Quadrature::Coarse, start);
        let estimate = coarse.run().ok();
        let start = estimate.unwrap_or(start);
        ParameterSearch::Pending {
            estimate,
            bracket: Box::new(Self::new(
                problem,
                coarse.curve,
                Quadrature::adaptive(),
                start,
            )),
        }
    }

    /// Iterates until the residual is (measured or predicted) within the tolerance.
    fn run(&mut self) -> Result<f64, ArcLengthError> {
        loop {
            if let Some(root) = self.iterate()? {
                return Ok(root);
            }
        }
    }

    /// Evaluates `L` at the current value and steps: `Some(root)` when the evaluated residual
    /// is within the tolerance, or when the next value's predicted one is well within it.
    fn iterate(&mut self) -> Result<Option<f64>, ArcLengthError> {
        if self.iterations == MAX_ROOT_ITERATIONS {
            return Err(self.failure());
        }
        self.iterations += 1;
        let (problem, value) = (self.problem, self.value);
        self.curve.set_parameter(problem.parameter, value);
        let (sums, initial) = self.quadrature.evaluate(&self.curve, problem.parameter);
        let residual = sums.length - problem.target;
        if residual.abs() < problem.tolerance {
            return Ok(Some(value));
        }
        if residual.abs() < self.best.1 {
            self.best = (value, residual.abs());
        }
        if residual < 0.0 {
            self.lo = value;
        } else {
            self.hi = Some(value);
        }
        // Newton that does not halve the residual is not converging: bisect instead. (After
        // a doubling or bisection step there is no Newton step to judge.)
        let progressed = !self.after_newton || residual.abs() <= 0.5 * self.previous_residual;
        self.previous_residual = residual.abs();
        let step = self
            .next_value(value, residual, sums.slope, progressed)
            .ok_or_else(|| self.failure())?;
        self.value = step.value;
        self.after_newton = step.newton;
        let certain = self
            .prediction(&step, value, &sums, &initial)
            .is_some_and(|p| p <= PREDICTION_FRACTION * problem.tolerance);
        Ok(certain.then_some(step.value))
    }

    /// `½ L'' δ²` for a short Newton step `δ` from `value` on a curve without sharp speed
    /// minima; `None` where that Taylor estimate is not to be trusted.
    fn prediction(
        &self,
        step: &Step,
        value: f64,
        sums: &LengthSums,
        initial: &InitialEdges,
    ) -> Option<f64> {
        let delta = step.value - value;
        let short = delta.abs() <= PREDICTION_STEP_FRACTION * (value.abs() + self.problem.target);
        if !(step.newton && short && initial.is_smooth()) {
            return None;
        }
        // The adaptive rule leaves L'' out; the cheap one on the initial panels will do.
        let rate = sums.slope_rate.unwrap_or_else(|| {
            let coarse = self
                .curve
                .coarse_sums(self.problem.parameter, initial.edges());
            coarse.slope_rate.unwrap_or(f64::NAN)
        });
        // L'' ≥ 0 (convexity); round-off may leave it slightly negative.
        let prediction = 0.5 * rate.max(0.0) * delta * delta;
        (rate.is_finite() && prediction.is_finite()).then_some(prediction)
    }

    fn failure(&self) -> ArcLengthError {
        ArcLengthError::NotConverged {
            parameter: self.problem.parameter,
            target_m: self.problem.target,
            residual_m: self.best.1,
        }
    }

    /// Next iterate: Newton if it stays inside the bracket, doubling while no upper bracket
    /// is known, bisection otherwise; `None` once the bracket cannot shrink any further or the
    /// parameter exceeds its limit.
    fn next_value(&self, value: f64, residual: f64, slope: f64, progressed: bool) -> Option<Step> {
        let newton = value - residual / slope;
        let newton_ok = slope > 0.0 && newton.is_finite();
        match self.hi {
            None => {
                // Doubling from 0 would stall: restart from the target length.
                let doubled = if value > 0.0 {
                    2.0 * value
                } else {
                    self.problem.target
                };
                let step = if newton_ok && newton > value && newton < doubled {
                    Step {
                        value: newton,
                        newton: true,
                    }
                } else {
                    Step {
                        value: doubled,
                        newton: false,
                    }
                };
                (step.value <= self.problem.limit).then_some(step)
            }
            Some(hi) => {
                if hi - self.lo <= 4.0 * f64::EPSILON * hi {
                    return None;
                }
                let inside = newton_ok && newton > self.lo && newton < hi && progressed;
                Some(if inside {
                    Step {
                        value: newton,
                        newton: true,
                    }
                } else {
                    Step {
                        value: 0.5 * (self.lo + hi),
                        newton: false,
                    }
                })
            }
        }
    }
}
