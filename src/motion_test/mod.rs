//! The *motion test*: the whole cable of a candidate path — every segment,
//! clamped at every guide — simulated dynamically while the guides and the robot's links
//! follow the motion at its real timing; the worst contact, stretch and bend radius over
//! time decide whether the candidate passes.
//!
//! What [`run`] does:
//!
//! 1. **Cable.** Segments with S = 0 are dropped: their two guides coincide (one clamp), so
//!    the segments before and after share it. Every other segment is simulated with its
//!    own sub-segments; results always name the setup's segment index (C1 = 0).
//! 2. **Initial shape** at the motion's first sample: the guides' world poses, per segment
//!    the connected geometry (bowing towards gravity) and then the quasi-static equilibrium
//!    (Newton stopped at 1e-6 N like the attachment test), so the cable starts at rest in
//!    the shape the attachment test judged. Guides farther apart than a segment's length,
//!    no connected geometry or no equilibrium make a *failed candidate* (a report with the
//!    reason), not an error.
//! 3. **Stepping** with [`MotionTestOptions::engine`]: by default [`Engine::Implicit`], the
//!    statics' cable model integrated by BDF2 ([`crate::dynamics`]) in steps of 1/240 s, so
//!    that a cable at rest stays at its static equilibrium and a slow motion gives the
//!    static sweep's values; [`Engine::RigidChain`] is the paper's kind of rapier3d
//!    simulation, kept as its baseline. Step `k` ends at `t0 + k·dt` on the motion's time
//!    axis; the guides' and links' poses for it are those at that instant, joints
//!    interpolated linearly between samples ([`Motion::joints_at`]). The motion part takes
//!    `⌈duration / dt⌉` steps; then [`MotionTestOptions::settle_tail_s`] (default
//!    [`DEFAULT_SETTLE_TAIL_S`] = 0.5 s) holds the last pose so that the cable's overshoot
//!    after the final stop is seen.
//! 4. **Metrics**, for the initial equilibrium and after every step, per segment, from its
//!    nodes exactly as the attachment test measures a static shape:
//!    - *contact*: the exact signed clearance to every link collider
//!      ([`min_clearance`](crate::stress::min_clearance), f64, capsules of the cable radius),
//!      excluding `thresholds.clamp_zone_m` of cable at each guide (counted in the cable's
//!      sub-segments, see [`ClampZone`](crate::stress::ClampZone)) against the guide's own
//!      link (and the link that one is fixed to); violated when below
//!      `thresholds.contact_clearance_m` (≥ 0: the first touch already fails, so the
//!      implicit engine needs no contact forces); with the rigid chain also rapier's contact
//!      force outside the clamp zones ([`MotionTestOptions::contact_force_is_violation`]);
//!    - *stretch*: centreline length / natural length; violated above `thresholds.stretch`;
//!    - *bend radius*: the smallest over the joints, guide axes included; violated below
//!      `thresholds.min_bend_radius_m`.
//! 5. **Report** ([`MotionTestReport`]): pass/fail, the worst value of each metric with its
//!    time, segment and place, the first violation, optionally the series, the final shape,
//!    and the cost. A step the engine cannot take (no converged implicit step even on short
//!    substeps, a rigid chain leaving its sanity bounds) is a failed candidate "simulation
//!    diverged at t = … (…)". Only input that does not fit the setup is an [`Err`]: see
//!    [`MotionTestError`].
//!
//! The run is deterministic: every segment's computation is fixed whatever the thread
//! count (the implicit engine steps the independent segments in parallel; rapier runs
//! single-threaded), so the same inputs give the same report bits (except `wall_time_s`).
//!
//! With [`MotionTestOptions::stop_at_first_violation`] the run ends at the first step with a
//! violation — enough to reject a candidate while trying the next-shortest ones; the winner
//! is worth a full run for its report.

mod clearance;
mod engine;
mod error;
mod initial;
mod options;
mod plan;
mod report;
mod simulate;
mod tracker;

pub use error::MotionTestError;
pub use options::{DEFAULT_SETTLE_TAIL_S, Engine, EngineKind, MotionTestOptions};
pub use report::{
    ClampLoadPeak, ClampTurn, Constraint, Failure, FailureCause, GuideSlide, MotionTestReport,
    PieceLifeDamage, PieceTwist, PieceWorst, Place, SLIDE_SAMPLE_S, SegmentNodes, SeriesPoint,
    ShapeFrame, SlidePoint, Violation, Worst,
};

use crate::motion::Motion;
use crate::path::CablePath;
use crate::setup::Setup;
use crate::stress::Obstacles;
use clearance::ClearanceQuery;
use plan::Plan;
use simulate::Context;
use std::time::Instant;
use tracker::{RunFacts, Tracker};

/// Runs the motion test of `path` (lengths and guide configurations of `setup`) along
/// `motion` (see the module documentation).
///
/// Lengths need not be among the segment's candidates. `Ok` with `passed == false` for a
/// candidate that fails (a limit violated, a segment too
/// short at the first pose, no initial shape, a diverging simulation). `Err` for input that
/// does not fit: path vectors of the wrong length, a configuration index out of range, S = 0
/// between guides that do not coincide (or S > 0 between guides that do), no segment with
/// S > 0, a motion for other joints, invalid options, or robot geometry the simulation or the
/// clearance query cannot use.
pub fn run(
    setup: &Setup,
    path: &CablePath,
    motion: &Motion,
    options: &MotionTestOptions,
) -> Result<MotionTestReport, MotionTestError> {
    let clock = Instant::now();
    options.validate(setup)?;
    plan::check_motion(setup, motion)?;
    let plan = Plan::new(setup, path)?;
    let obstacles = Obstacles::from_robot(&setup.robot).map_err(MotionTestError::Obstacles)?;
    let zones = plan.clamp_zones(setup);
    let context = Context {
        setup,
        plan,
        motion,
        options,
        clearance: ClearanceQuery::new(obstacles, 0.5 * setup.cable.diameter_m, zones),
    };
    let mut tracker = Tracker::new(
        setup,
        options.record_series,
        options.contact_force_is_violation,
    )
    .keeping_shapes(options.shape_interval_s);
    let ended = context.simulate(&mut tracker)?;
    let dt = options.time_step_s();
    let facts = RunFacts {
        motion_duration_s: motion.duration_s(),
        steps: ended.steps,
        simulated_s: ended.steps as f64 * dt,
        wall_time_s: clock.elapsed().as_secs_f64(),
    };
    Ok(tracker.into_report(ended.failure, facts))
}
