//! An installed cable checked against motions: the motion test of one given path over every
//! motion of a cell, no search. What gates a new robot program: does the cable mounted as
//! the sheet said survive it, and if not, which limit fails where on the cable and when.

use super::box_check::{BoxCheck, MAX_BOX_CHECK_POSES, check_box};
use super::options::{SolveError, SolveOptions};
use super::ranges::STRESS_MOTION_RATE_HZ;
use super::report::{
    AllowedRanges, MotionVerdict, NamedPath, PieceBinding, binding, life, motion_verdicts,
    named_path,
};
use super::search::test_options;
use crate::motion::{Cell, JointRanges};
use crate::motion_test;
use crate::mounting::{MountingPlan, mounting_plan};
use crate::path::CablePath;
use crate::setup::{Setup, Thresholds};
use std::time::Instant;

/// The verdict of one mounting over every motion of a cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// The path checked, with its clamps' and pieces' names.
    pub path: NamedPath,
    /// How it is mounted: clamps, places and cable marks.
    pub mounting: MountingPlan,
    /// Its total length (mm).
    pub length_mm: f64,
    /// Every motion with the path's motion test over it, in the cell's order.
    pub motions: Vec<MotionVerdict>,
    /// Per piece, the motion that comes closest to each limit (several motions only).
    pub binding: Vec<PieceBinding>,
    /// The predicted life of the mounting over these motions (with a rated life).
    pub life: Option<crate::life::estimate::CableLife>,
    /// The limits held to.
    pub thresholds: Thresholds,
    /// The cable model's sub-segment length (mm).
    pub sub_segment_pitch_mm: f64,
    /// Wall time of the whole check (s).
    pub wall_time_s: f64,
    /// Over an axis-range box ([`check_ranges`]): every piece at a grid of the box's poses.
    pub over_box: Option<BoxCheck>,
    /// The ranges the mounting allows per axis, when asked ([`super::allowed_ranges`]).
    pub allowed_ranges: Option<AllowedRanges>,
}

impl Check {
    /// Every motion held every limit.
    pub fn holds(&self) -> bool {
        (self.motions.iter()).all(|m| m.motion_test.as_ref().is_some_and(|t| t.passed))
            && self.over_box.as_ref().is_none_or(BoxCheck::holds)
    }
}

/// The motion test of `path` (indices into `setup`) over every motion of `cell`, each run
/// whole (to its first violation, as a solve runs it), with `options`' engine.
pub fn check_mounting(
    setup: &Setup,
    path: &CablePath,
    cell: &Cell,
    options: &SolveOptions,
) -> Result<Check, SolveError> {
    let clock = Instant::now();
    path.check(setup)
        .map_err(|e| SolveError::Options(format!("the path does not fit the setup: {e}")))?;
    let test = test_options(setup, options);
    let runs = (cell.motions.iter())
        .map(|m| motion_test::run(setup, path, &m.motion, &test).map(Some))
        .collect::<Result<Vec<_>, _>>()?;
    let motions = motion_verdicts(cell, &runs);
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    Ok(Check {
        path: named_path(setup, path),
        mounting: mounting_plan(setup, path),
        length_mm: path.total_sub_segments() as f64 * pitch_mm,
        binding: binding(setup, &motions),
        life: life(setup, &motions),
        motions,
        thresholds: setup.thresholds,
        sub_segment_pitch_mm: pitch_mm,
        wall_time_s: clock.elapsed().as_secs_f64(),
        over_box: None,
        allowed_ranges: None,
    })
}

/// `path` over the box `ranges`: the motion test over its stress motions (each ranged axis
/// end to end at its URDF speed, alone and together) and over the motions of `given`, then
/// every piece at a grid of the box's poses `grid_step_deg` apart ([`check_box`]).
pub fn check_ranges(
    setup: &Setup,
    path: &CablePath,
    ranges: &JointRanges,
    given: Option<Cell>,
    grid_step_deg: f64,
    options: &SolveOptions,
) -> Result<Check, SolveError> {
    let clock = Instant::now();
    let mut cell = ranges.stress_motions(&setup.robot, STRESS_MOTION_RATE_HZ)?;
    cell.motions
        .extend(given.into_iter().flat_map(|g| g.motions));
    let mut check = check_mounting(setup, path, &cell, options)?;
    check.over_box = Some(check_box(
        setup,
        path,
        ranges,
        grid_step_deg,
        MAX_BOX_CHECK_POSES,
    )?);
    check.wall_time_s = clock.elapsed().as_secs_f64();
    Ok(check)
}
