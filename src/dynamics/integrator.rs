//! [`SegmentDynamics`]: one cable segment stepped in time by BDF2 (see the module
//! documentation of [`dynamics`](super)).

use nalgebra::Point3;

use crate::pose::Pose;
use crate::statics::newton::{Workspace, minimize};
use crate::statics::rod::{Inertia, Rod};
use crate::statics::{
    FarEnd, Pin, RodParameters, SolverOptions, StaticsError, check_input, clamped_pose,
};

/// How a cable is stepped in time (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegratorSettings {
    /// Length of one step (s): the guides' poses are given at the end of each step.
    pub time_step_s: f64,
    /// Newton's stopping rule for each step (force residual, iterations).
    pub solver: SolverOptions,
    /// How often a step whose Newton iteration fails is retried as twice as many backward
    /// Euler substeps (guide poses interpolated), at most: a step of `h / 2^k` is always
    /// closer to the last state, so Newton converges once the substeps are short enough.
    pub max_step_halvings: usize,
}

impl Default for IntegratorSettings {
    /// Steps of 1/240 s, Newton stopped at 1e-6 N like the statics of the attachment test
    /// ([`SolverOptions::STRESS_CHECK`]), up to 8 halvings (1/61440 s).
    fn default() -> Self {
        Self {
            time_step_s: 1.0 / 240.0,
            solver: SolverOptions::STRESS_CHECK,
            max_step_halvings: 8,
        }
    }
}

impl IntegratorSettings {
    /// Checks that every value is finite and in range.
    pub fn validate(&self) -> Result<(), DynamicsError> {
        let step = self.time_step_s;
        if !(step.is_finite() && step > 0.0 && step <= MAX_TIME_STEP_S) {
            return Err(DynamicsError::Invalid {
                what: format!("time step {step} s must be finite, > 0 and ≤ {MAX_TIME_STEP_S} s"),
            });
        }
        let tolerance = self.solver.force_tolerance_n;
        if !(tolerance.is_finite() && tolerance > 0.0) || self.solver.max_iterations == 0 {
            return Err(DynamicsError::Invalid {
                what: format!(
                    "solver tolerance {tolerance} N must be finite and > 0, with at least one \
                     iteration"
                ),
            });
        }
        if self.max_step_halvings > MAX_HALVINGS {
            return Err(DynamicsError::Invalid {
                what: format!(
                    "{} step halvings: at most {MAX_HALVINGS}",
                    self.max_step_halvings
                ),
            });
        }
        Ok(())
    }
}

/// Longest accepted time step (s): a typo guard.
const MAX_TIME_STEP_S: f64 = 1.0;
/// Most step halvings accepted (2^20 substeps of one step would take minutes).
const MAX_HALVINGS: usize = 20;
/// Fastest node (m/s) before a step is called diverged: a robot flange moves at a few m/s.
const MAX_NODE_SPEED_M_S: f64 = 100.0;

/// Why a step or a start failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DynamicsError {
    /// Settings or poses that cannot describe a simulation.
    #[error("invalid cable dynamics: {what}")]
    Invalid {
        /// What is wrong.
        what: String,
    },
    /// The start shape is not a cable the statics accept.
    #[error(transparent)]
    Shape(#[from] StaticsError),
    /// Newton's method did not converge even on the shortest substeps.
    #[error(
        "no converged step even in {substeps} substeps: {reason} (after {iterations} \
         iterations, residual {residual_n:.3e} N)"
    )]
    NotConverged {
        /// Substeps of the last try.
        substeps: usize,
        /// Why Newton stopped.
        reason: String,
        /// Newton iterations of the last substep tried.
        iterations: usize,
        /// Largest force component left (N).
        residual_n: f64,
    },
    /// A node moved faster than any cable on a robot can.
    #[error("node {node} moves at {speed_m_s:.1} m/s: the simulation diverged")]
    TooFast {
        /// Node index (0 at the start guide).
        node: usize,
        /// Its speed (m/s).
        speed_m_s: f64,
    },
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    /// Newton iterations over all substeps.
    pub iterations: usize,
    /// Substeps taken (1 unless the step was retried).
    pub substeps: usize,
}

/// One cable segment in motion: clamped at its start guide and at its end guide (or free at
/// its end, a cantilever), its `S − 1` (or `S`) free nodes carrying the lumped masses of
/// the statics.
#[derive(Debug, Clone)]
pub struct SegmentDynamics {
    params: RodParameters,
    start: Pose,
    far_end: FarEnd,
    sub_segments: usize,
    /// Free coordinates now, and one step ago (for BDF2).
    x: Vec<f64>,
    x_before: Vec<f64>,
    /// Velocities of the free coordinates now, and one step ago.
    v: Vec<f64>,
    v_before: Vec<f64>,
    /// The step that led to the current state when BDF2 may continue from it (`None` after
    /// a start or a retried step: the next step is backward Euler).
    last_step_s: Option<f64>,
    /// Total twist Ψ (rad) now, the branch reference of the next step.
    twist_rad: f64,
    inertia: Inertia,
    workspace: Workspace,
    /// A swivel clamp between the ends, if any: where it holds its node now.
    pin: Option<Pin>,
}

impl SegmentDynamics {
    /// The segment at rest in the shape `nodes` (`S + 1` nodes, from the start guide's
    /// origin; for a clamped end, ending at the end guide's origin) with total twist
    /// `twist_rad`, e.g. a static [`Equilibrium`](crate::statics::Equilibrium).
    pub fn at_rest(
        params: &RodParameters,
        start: Pose,
        far_end: FarEnd,
        nodes: &[Point3<f64>],
        twist_rad: f64,
    ) -> Result<Self, DynamicsError> {
        check_input(
            params,
            &start,
            &far_end,
            nodes,
            &SolverOptions::STRESS_CHECK,
        )?;
        if !twist_rad.is_finite() {
            return Err(DynamicsError::Invalid {
                what: format!("twist {twist_rad} rad is not finite"),
            });
        }
        let sub_segments = nodes.len() - 1;
        let rod = Rod::new(*params, start, clamped_pose(&far_end), sub_segments);
        let x = rod.free_coordinates(nodes);
        let free = rod.free_nodes();
        let inertia = Inertia {
            weights: vec![0.0; free],
            anchors: vec![0.0; 3 * free],
        };
        Ok(Self {
            params: *params,
            start,
            far_end,
            sub_segments,
            x_before: x.clone(),
            v: vec![0.0; x.len()],
            v_before: vec![0.0; x.len()],
            x,
            last_step_s: None,
            twist_rad,
            inertia,
            workspace: Workspace::default(),
            pin: None,
        })
    }

    /// The same segment held between its ends by the swivel clamp `pin` (a piece through a
    /// swivel clamp between two pieces).
    pub fn with_pin(mut self, pin: Pin) -> Self {
        self.pin = Some(pin);
        self
    }

    /// Moves the swivel clamp, if any, to `clamp` (its origin and +z) for the next step: it
    /// holds its node there through the whole step, as the end clamps hold theirs at the
    /// step's end poses.
    pub fn move_pin(&mut self, clamp: &Pose) {
        if let Some(pin) = &mut self.pin {
            *pin = Pin::held_by(clamp, pin.node, pin.cone_rad);
        }
    }

    /// Advances by `step_s` to the guide poses `start` and `far_end` (the poses at the end of
    /// the step). On a failed Newton iteration the step is retried in 2, 4, … backward Euler
    /// substeps with the guides interpolated between their old and new poses; when even the
    /// shortest fail, the state is left as it was and the error says why.
    pub fn step(
        &mut self,
        start: Pose,
        far_end: FarEnd,
        step_s: f64,
        settings: &IntegratorSettings,
    ) -> Result<StepReport, DynamicsError> {
        let (old_start, old_end) = (self.start, self.far_end);
        let bdf2 = self
            .last_step_s
            .is_some_and(|h| (h - step_s).abs() <= 1e-12 * step_s);
        let mut last_error = match self.advance(start, far_end, step_s, bdf2, settings) {
            Ok(iterations) => {
                self.last_step_s = Some(step_s);
                return Ok(StepReport {
                    iterations,
                    substeps: 1,
                });
            }
            Err(error) => error,
        };
        let saved = self.clone_state();
        for halvings in 1..=settings.max_step_halvings {
            let substeps = 1usize << halvings;
            let h = step_s / substeps as f64;
            let mut iterations = 0;
            let mut failed = None;
            for k in 1..=substeps {
                let s = k as f64 / substeps as f64;
                let guides = (
                    interpolate(&old_start, &start, s),
                    interpolate_end(&old_end, &far_end, s),
                );
                match self.advance(guides.0, guides.1, h, false, settings) {
                    Ok(n) => iterations += n,
                    Err(error) => {
                        failed = Some(error);
                        break;
                    }
                }
            }
            match failed {
                None => {
                    self.last_step_s = None;
                    return Ok(StepReport {
                        iterations,
                        substeps,
                    });
                }
                Some(error) => {
                    last_error = match error {
                        DynamicsError::NotConverged {
                            reason,
                            iterations,
                            residual_n,
                            ..
                        } => DynamicsError::NotConverged {
                            substeps,
                            reason,
                            iterations,
                            residual_n,
                        },
                        other => other,
                    };
                    self.restore_state(&saved, old_start, old_end);
                }
            }
        }
        Err(last_error)
    }

    /// One implicit step of `h` to the given guide poses (BDF2 when `bdf2`, else backward
    /// Euler); returns the Newton iterations. The state is unchanged on failure.
    fn advance(
        &mut self,
        start: Pose,
        far_end: FarEnd,
        h: f64,
        bdf2: bool,
        settings: &IntegratorSettings,
    ) -> Result<usize, DynamicsError> {
        let beta = if bdf2 { 2.0 * h / 3.0 } else { h };
        let rod = self.rod(start, far_end);
        for (f, weight) in self.inertia.weights.iter_mut().enumerate() {
            *weight = rod.node_mass(f + 1) / (beta * beta);
        }
        for (i, anchor) in self.inertia.anchors.iter_mut().enumerate() {
            *anchor = if bdf2 {
                (4.0 * self.x[i] - self.x_before[i]) / 3.0
                    + beta * (4.0 * self.v[i] - self.v_before[i]) / 3.0
            } else {
                self.x[i] + h * self.v[i]
            };
        }
        let guess: Vec<f64> = self.x.iter().zip(&self.v).map(|(x, v)| x + h * v).collect();
        let rod = rod.with_inertia(std::mem::take(&mut self.inertia));
        let result = minimize(
            &rod,
            guess,
            self.twist_rad,
            settings.solver.force_tolerance_n,
            settings.solver.max_iterations,
            &mut self.workspace,
        );
        self.inertia = rod.into_inertia().unwrap_or_default();
        if let Some(reason) = result.failure {
            return Err(DynamicsError::NotConverged {
                substeps: 1,
                reason,
                iterations: result.iterations,
                residual_n: result.residual,
            });
        }
        let velocity: Vec<f64> = if bdf2 {
            (0..self.x.len())
                .map(|i| (3.0 * result.x[i] - 4.0 * self.x[i] + self.x_before[i]) / (2.0 * h))
                .collect()
        } else {
            result
                .x
                .iter()
                .zip(&self.x)
                .map(|(a, b)| (a - b) / h)
                .collect()
        };
        if let Some((node, speed_m_s)) = fastest_node(&velocity)
            && speed_m_s > MAX_NODE_SPEED_M_S
        {
            return Err(DynamicsError::TooFast { node, speed_m_s });
        }
        self.x_before = std::mem::replace(&mut self.x, result.x);
        self.v_before = std::mem::replace(&mut self.v, velocity);
        self.twist_rad = self.workspace.evaluation.twist;
        self.start = start;
        self.far_end = far_end;
        Ok(result.iterations)
    }

    /// All `S + 1` nodes now (m).
    pub fn nodes(&self) -> Vec<Point3<f64>> {
        self.rod(self.start, self.far_end).nodes(&self.x)
    }

    /// The segment's energy between the guides `start` and `far_end`.
    fn rod(&self, start: Pose, far_end: FarEnd) -> Rod {
        Rod::new(
            self.params,
            start,
            clamped_pose(&far_end),
            self.sub_segments,
        )
        .with_pin(self.pin)
    }

    /// Total twist Ψ between the guides (rad).
    pub fn twist_rad(&self) -> f64 {
        self.twist_rad
    }

    /// The start guide's pose now.
    pub fn start(&self) -> Pose {
        self.start
    }

    /// The far end now.
    pub fn far_end(&self) -> FarEnd {
        self.far_end
    }

    fn clone_state(&self) -> SavedState {
        SavedState {
            x: self.x.clone(),
            x_before: self.x_before.clone(),
            v: self.v.clone(),
            v_before: self.v_before.clone(),
            twist_rad: self.twist_rad,
        }
    }

    fn restore_state(&mut self, saved: &SavedState, start: Pose, far_end: FarEnd) {
        self.x.clone_from(&saved.x);
        self.x_before.clone_from(&saved.x_before);
        self.v.clone_from(&saved.v);
        self.v_before.clone_from(&saved.v_before);
        self.twist_rad = saved.twist_rad;
        self.start = start;
        self.far_end = far_end;
    }
}

/// The state a retried step starts from again.
struct SavedState {
    x: Vec<f64>,
    x_before: Vec<f64>,
    v: Vec<f64>,
    v_before: Vec<f64>,
    twist_rad: f64,
}

/// The fastest free node (index from 1) and its speed, if any.
fn fastest_node(velocity: &[f64]) -> Option<(usize, f64)> {
    velocity
        .chunks_exact(3)
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .enumerate()
        .fold(None, |best: Option<(usize, f64)>, (f, speed)| match best {
            Some((_, fastest)) if fastest >= speed => best,
            _ => Some((f + 1, speed)),
        })
}

/// The pose a fraction `s` of the way from `a` to `b` (translation linear, rotation by
/// spherical interpolation).
fn interpolate(a: &Pose, b: &Pose, s: f64) -> Pose {
    a.lerp_slerp(b, s)
}

fn interpolate_end(a: &FarEnd, b: &FarEnd, s: f64) -> FarEnd {
    match (a, b) {
        (FarEnd::Clamped(a), FarEnd::Clamped(b)) => FarEnd::Clamped(interpolate(a, b, s)),
        _ => *b,
    }
}
