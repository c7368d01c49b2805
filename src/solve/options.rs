//! What `solve` takes besides the setup and the motion, and why it can fail.

use crate::attachment::{ConnectMethod, IntraLinkCriterion};
use crate::chain::ChainError;
use crate::dictionary::LookupError;
use crate::motion::MotionError;
use crate::motion_test::{EngineKind, MotionTestError};
use crate::setup::{Setup, SetupError};
use crate::stress::contact::ContactError;

/// What `solve` does besides the defaults of the setup.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOptions {
    /// Connected geometry and static solver of the attachment test.
    pub method: ConnectMethod,
    /// `Some(1)`: the paper's method 1 (one guide per link: intra-link segments only at
    /// S = 0); `Some(2)` or `None`: as the setup declares.
    pub max_guides_per_link: Option<usize>,
    /// Chains tried in the motion test, at most (≥ 1): the budget of motion tests.
    pub k_best: usize,
    /// Run the motion test; without it the shortest chain d̂ is the answer.
    pub motion_test: bool,
    /// Before each dynamic motion test, sweep the chain's PVs statically over every pose of
    /// the motion ([`MotionSweep`]) and drop those that fail. Off: the paper's pipeline,
    /// where only the dynamic test follows the critical poses.
    pub static_sweep: bool,
    /// Learn from failed motion tests how far each segment's cable swings past its static
    /// shapes, and set aside, while other chains remain, the pieces whose static shapes keep
    /// less than that inside a limit ([`super::learn`]). Off: chains go to the motion test
    /// strictly shortest first (the answer is then the shortest that passes, within the
    /// budget). Needs the static sweep.
    pub learn: bool,
    /// Keep the cable's shape every this many seconds in each motion test's report
    /// ([`MotionTestOptions::shape_interval_s`]), e.g. for the report's animation.
    pub shape_interval_s: Option<f64>,
    /// What simulates the cable in the motion test, at its default settings.
    pub engine: EngineKind,
    /// Which poses the intra-link segments are tested at (the dictionary's criterion, or
    /// the paper's one pose).
    pub intra_link: IntraLinkCriterion,
    /// How much of the attachment test runs: only the pieces a chain shorter than the
    /// answer could use (the default), or every candidate first (the reference the lazy
    /// search is tested against; same path, slower).
    pub search: SearchKind,
    /// When there is no chain, decide every candidate piece to say why (the diagnosis).
    /// Off: "unsolved" as soon as the search knows it, as the narrowing of axis ranges asks
    /// of each box it tries.
    pub diagnose: bool,
    /// What the answer's predicted life must be ([`LifeGoal`]); `None`: the shortest path
    /// that holds every limit, whatever its life.
    pub life_goal: Option<LifeGoal>,
}

/// What a solve asks of the answer's predicted life (the cable file must give a life curve).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LifeGoal {
    /// The shortest path that holds every limit and lasts at least this many cycles (of the
    /// motion; of a round of the cell's motions).
    AtLeast {
        /// Cycles.
        cycles: f64,
    },
    /// Of the paths that hold every limit and are at most this much longer than the shortest
    /// such path, the one that lasts longest.
    Longest {
        /// mm.
        within_mm: f64,
    },
}

/// How the attachment test and the chain search work together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SearchKind {
    /// Pieces are evaluated as the search for the shortest chain needs them
    /// ([`LazyAttachment`]).
    #[default]
    Lazy,
    /// Every candidate piece is evaluated, then the chains are searched (the paper's order).
    Exhaustive,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: ConnectMethod::Hermite,
            max_guides_per_link: None,
            k_best: 50,
            motion_test: true,
            static_sweep: true,
            learn: true,
            shape_interval_s: None,
            engine: EngineKind::Implicit,
            intra_link: IntraLinkCriterion::GravityDirections,
            search: SearchKind::Lazy,
            diagnose: true,
            life_goal: None,
        }
    }
}

impl SolveOptions {
    /// The setup as these options solve it: restricted to one guide per link for method 1.
    /// The indices of a [`SolveReport`]'s paths refer to this setup.
    pub fn setup_for(&self, setup: &Setup) -> Result<Setup, SolveError> {
        if self.k_best == 0 {
            return Err(SolveError::Options("--k-best must be at least 1".into()));
        }
        if self.life_goal.is_some() && !setup.cable.datasheet.predicts_life() {
            return Err(SolveError::Options(format!(
                "a life goal (--min-life-cycles, --prefer life) needs the cable's life curve: \
                 a [rated_life] table or conductor_offset_mm in {}",
                setup.cable_path.display()
            )));
        }
        if self.life_goal.is_some() && !self.motion_test {
            return Err(SolveError::Options(
                "a life goal (--min-life-cycles, --prefer life) needs the motion test: the life \
                 is predicted from it"
                    .into(),
            ));
        }
        match self.max_guides_per_link {
            Some(1) => Ok(setup.inter_link_only()?),
            Some(2) | None => Ok(setup.clone()),
            Some(n) => Err(SolveError::Options(format!(
                "max guides per link must be 1 or 2, got {n}"
            ))),
        }
    }
}

/// Why `solve` could not run (not: "no path found", which is a [`Status`]).
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The options do not fit the setup.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The motion does not fit the robot.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// The robot's collision geometry cannot be used for clearance queries.
    #[error(transparent)]
    Obstacles(#[from] ContactError),
    /// The chain search refused the sets (a bug if it happens: the sets come from the setup).
    #[error("chain search: {0}")]
    Chain(#[from] ChainError),
    /// The motion test refused its input.
    #[error("motion test: {0}")]
    MotionTest(#[from] MotionTestError),
    /// Invalid options.
    #[error("{0}")]
    Options(String),
    /// The dictionary cannot answer for this setup and motion.
    #[error(transparent)]
    Dictionary(#[from] LookupError),
}
