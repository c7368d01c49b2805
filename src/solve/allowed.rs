//! The ranges a mounting allows: per axis, how far it may turn (or slide) with every other
//! axis anywhere in a box before a piece of the cable breaks a limit — what a dress-pack
//! vendor prints as "J4 −170…+190°", and what the fitter jogs each axis to as the last
//! check.
//!
//! Each axis is widened from its range in the box towards its URDF limits, one end at a
//! time. A value is allowed when every piece the axis shapes holds at that axis value with
//! the other axes on the box's grid ([`PieceChecker`], the independent box check's cold
//! solves); the scan steps outward at the grid's step, and the first failing step is
//! bisected against the last holding one down to [`ALLOWED_RANGE_RESOLUTION_DEG`]. Then the
//! axis is driven end to end over what it allows at its URDF speed (the others at the box's
//! middle, as a design's stress motions are), and the range is shrunk towards the box's by
//! bisection until that motion holds.

use super::box_check::{BoxFailure, MAX_BOX_CHECK_POSES, PieceChecker};
use super::options::{SolveError, SolveOptions};
use super::ranges::STRESS_MOTION_RATE_HZ;
use super::report::{AllowedAxis, AllowedRanges, RangeEnd};
use super::search::test_options;
use crate::motion::{Cell, JointRanges};
use crate::motion_test;
use crate::path::CablePath;
use crate::setup::Setup;
use std::time::Instant;

/// How close (degrees; millimetres for a prismatic joint) each end of an allowed range is
/// found to the value where the cable first fails.
pub const ALLOWED_RANGE_RESOLUTION_DEG: f64 = 1.0;

/// A joint without URDF limits (continuous) is widened at most this far each way from the
/// box's middle (degrees).
pub const CONTINUOUS_JOINT_SPAN_DEG: f64 = 360.0;

/// Halvings of the full-speed shrink (the range is then within 1/32 of the widening).
const FULL_SPEED_BISECTIONS: usize = 5;

/// The box the ranges a mounting allows are asked within, and its words: `ranges` when given
/// (`narrowed`: a design's box narrowed from its file), else the box the motions of `cell`
/// span (each joint between its least and greatest value over them). `None` with neither.
pub fn allowed_box(
    ranges: Option<(&JointRanges, bool)>,
    cell: Option<&Cell>,
) -> Option<(JointRanges, String)> {
    let file = |r: &JointRanges| (r.source.as_ref()).map(|p| p.display().to_string());
    match (ranges, cell) {
        (Some((r, false)), _) => Some((
            r.clone(),
            file(r).map_or("the ranges given".into(), |f| format!("the ranges of {f}")),
        )),
        (Some((r, true)), _) => Some((
            r.clone(),
            file(r).map_or("the box answered".into(), |f| {
                format!("the box answered (narrowed from {f})")
            }),
        )),
        (None, Some(cell)) => Some((
            JointRanges::spanned(cell)?,
            match cell.motions.len() {
                1 => "the motion's extremes",
                _ => "the motions' extremes",
            }
            .into(),
        )),
        (None, None) => None,
    }
}

/// The range of every actuated joint `path` allows on `setup` with the other joints anywhere
/// in `ranges` (`within` says which box that is), on a grid of `step_deg`; `options` give the
/// motion test's engine.
pub fn allowed_ranges(
    setup: &Setup,
    path: &CablePath,
    ranges: &JointRanges,
    within: &str,
    step_deg: f64,
    options: &SolveOptions,
) -> Result<AllowedRanges, SolveError> {
    let clock = Instant::now();
    let checker = PieceChecker::new(setup, path, step_deg, MAX_BOX_CHECK_POSES)?;
    let mut allowed = AllowedRanges {
        within: within.to_string(),
        step_deg,
        resolution_deg: ALLOWED_RANGE_RESOLUTION_DEG,
        box_failure: None,
        axes: Vec::new(),
        wall_time_s: 0.0,
    };
    for piece in &checker.pieces {
        let over = checker.over(piece, ranges)?;
        if over.failure.is_some() {
            allowed.box_failure = Some(over);
            allowed.wall_time_s = clock.elapsed().as_secs_f64();
            return Ok(allowed);
        }
    }
    let robot = &setup.robot;
    for j in 0..robot.dof() {
        let joint = robot.actuated_joint(j);
        let (per_si, unit) = joint.kind.display_unit();
        let middle = ranges.centre()[j];
        let limits = match joint.limits {
            Some(l) => [l.lower, l.upper],
            None if joint.kind.is_rotary() => {
                let span = CONTINUOUS_JOINT_SPAN_DEG.to_radians();
                [middle - span, middle + span]
            }
            None => ranges.ranges[j],
        };
        // The pieces this axis shapes: it lies between their links, or it turns gravity in
        // their start link somewhere in its whole range.
        let mut whole = ranges.clone();
        whole.ranges[j] = [
            limits[0].min(ranges.ranges[j][0]),
            limits[1].max(ranges.ranges[j][1]),
        ];
        let mut shaped = Vec::new();
        for piece in &checker.pieces {
            let turns = piece.upstream.contains(&j)
                && whole.turns_gravity(robot, piece.start_link, &checker.down, j, step_deg)?;
            if piece.between.contains(&j) || turns {
                shaped.push(piece);
            }
        }
        // The first piece that fails with the axis at `v` and the others over the box.
        let fails_at = |v: f64| -> Result<Option<(String, BoxFailure)>, SolveError> {
            let mut slice = ranges.clone();
            slice.ranges[j] = [v, v];
            for &piece in &shaped {
                let over = checker.over(piece, &slice)?;
                if let Some(failure) = over.failure {
                    return Ok(Some((over.segment, failure)));
                }
            }
            Ok(None)
        };
        let widen = Widen {
            step: step_deg / per_si,
            resolution: ALLOWED_RANGE_RESOLUTION_DEG / per_si,
        };
        // Towards the limits, never back into the box (a motion may pass a URDF limit).
        let [far_lo, far_hi] = whole.ranges[j];
        let (mut lo, mut below) = widen.end(ranges.ranges[j][0], far_lo, &fails_at)?;
        let (mut hi, mut above) = widen.end(ranges.ranges[j][1], far_hi, &fails_at)?;
        let [box_lo, box_hi] = ranges.ranges[j];
        if !shaped.is_empty() && (lo < box_lo || hi > box_hi) {
            // At full speed over [lo, hi]; shrunk towards the box's range until it holds.
            let full_speed = |[a, b]: [f64; 2]| -> Result<Option<String>, SolveError> {
                let mut stroke = ranges.clone();
                stroke.named = vec![false; stroke.named.len()];
                stroke.named[j] = true;
                stroke.ranges[j] = [a, b];
                let cell = stroke.stress_motions(robot, STRESS_MOTION_RATE_HZ)?;
                let test = test_options(setup, options);
                let run = motion_test::run(setup, path, &cell.motions[0].motion, &test)?;
                Ok(run.failure.map(|f| f.reason))
            };
            if let Some(reason) = full_speed([lo, hi])? {
                let at = |t: f64| [box_lo + t * (lo - box_lo), box_hi + t * (hi - box_hi)];
                let (mut holds, mut fails) = (0.0, 1.0);
                for _ in 0..FULL_SPEED_BISECTIONS {
                    let t = 0.5 * (holds + fails);
                    match full_speed(at(t))? {
                        None => holds = t,
                        Some(_) => fails = t,
                    }
                }
                let statics = [lo * per_si, hi * per_si];
                [lo, hi] = at(holds);
                below = RangeEnd::FullSpeed {
                    statics,
                    reason: reason.clone(),
                };
                above = RangeEnd::FullSpeed { statics, reason };
            }
        }
        let show = |v: f64| v * per_si;
        let inward = |v: f64, from: f64, up: bool| -> f64 {
            let r = ALLOWED_RANGE_RESOLUTION_DEG;
            let rounded = match up {
                true => (show(v) / r + 1e-9).floor() * r,
                false => (show(v) / r - 1e-9).ceil() * r,
            };
            match up {
                true => rounded.max(show(from)),
                false => rounded.min(show(from)),
            }
        };
        let in_units = |e: RangeEnd| match e {
            RangeEnd::Fails {
                at,
                piece,
                joints,
                reason,
            } => RangeEnd::Fails {
                at: show(at),
                piece,
                joints,
                reason,
            },
            other => other,
        };
        allowed.axes.push(AllowedAxis {
            joint: joint.name.clone(),
            unit,
            limits: joint.limits.map(|l| [show(l.lower), show(l.upper)]),
            within: [show(box_lo), show(box_hi)],
            allowed: [inward(lo, box_lo, false), inward(hi, box_hi, true)],
            shapes: shaped.iter().map(|p| setup.segment_name(p.m)).collect(),
            below: in_units(below),
            above: in_units(above),
        });
    }
    allowed.wall_time_s = clock.elapsed().as_secs_f64();
    Ok(allowed)
}

/// The outward scan of one end (SI units: rad or m).
struct Widen {
    step: f64,
    resolution: f64,
}

impl Widen {
    /// From `from` (holds) towards `limit`: the last value that holds and what ends there.
    fn end(
        &self,
        from: f64,
        limit: f64,
        fails_at: &dyn Fn(f64) -> Result<Option<(String, BoxFailure)>, SolveError>,
    ) -> Result<(f64, RangeEnd), SolveError> {
        let dir = if limit < from { -1.0 } else { 1.0 };
        let mut held = from;
        loop {
            let left = (limit - held) * dir;
            if left <= 1e-12 {
                return Ok((limit, RangeEnd::Limit));
            }
            let next = held + dir * left.min(self.step);
            let Some(mut failure) = fails_at(next)? else {
                held = next;
                continue;
            };
            let mut failed = next;
            while (failed - held).abs() > self.resolution {
                let mid = 0.5 * (held + failed);
                match fails_at(mid)? {
                    None => held = mid,
                    Some(f) => (failed, failure) = (mid, f),
                }
            }
            let (piece, failure) = failure;
            return Ok((
                held,
                RangeEnd::Fails {
                    at: failed,
                    piece,
                    joints: failure.joints,
                    reason: failure.reason,
                },
            ));
        }
    }
}
