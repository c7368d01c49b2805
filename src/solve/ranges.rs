//! A design for axis ranges: the cell that stands for a box of joint values.

use super::report::{AxisFailures, AxisRange, RangeDesign, RangeProbe, Status};
use super::{Solution, SolveError, SolveOptions, solve_cell};
use crate::attachment::GRAVITY_RESOLUTION_DEG;
use crate::dictionary::Dictionary;
use crate::motion::{Cell, JointRanges, MotionError};
use crate::robot::Robot;
use crate::setup::Setup;
use std::time::Instant;

/// Sample rate of the stress motions (Hz), as the bundled motions'.
pub const STRESS_MOTION_RATE_HZ: f64 = 100.0;

/// The axis-range grid's step when none is asked for (degrees; millimetres for a prismatic
/// joint).
pub const DEFAULT_GRID_STEP_DEG: f64 = 10.0;

/// The cell a design for `ranges` answers on `setup`: the stress motions (each ranged axis
/// end to end at its URDF speed, alone and together: [`JointRanges::stress_motions`]), the
/// motions of `given`, then the box's grid of static poses at `grid_step_deg` for every
/// piece of the setup ([`JointRanges::grid`]), each piece's gravity directions kept to
/// [`GRAVITY_RESOLUTION_DEG`].
pub fn range_cell(
    setup: &Setup,
    ranges: &JointRanges,
    given: Option<Cell>,
    grid_step_deg: f64,
) -> Result<Cell, MotionError> {
    let robot = &setup.robot;
    let mut cell = ranges.stress_motions(robot, STRESS_MOTION_RATE_HZ)?;
    cell.motions
        .extend(given.into_iter().flat_map(|g| g.motions));
    let pieces: Vec<(usize, usize)> = (0..setup.segment_count())
        .map(|m| {
            let (a, b) = setup.segment_guides(m);
            (setup.guides[a].body, setup.guides[b].body)
        })
        .collect();
    cell.motions.push(ranges.grid(
        robot,
        &setup.gravity_m_s2,
        &pieces,
        grid_step_deg,
        GRAVITY_RESOLUTION_DEG,
    )?);
    Ok(cell)
}

/// The shortest path for the box `ranges` on `setup` (the cell of [`range_cell`], with the
/// motions of `given`), and that cell. When the box has no path, the axis to narrow: each
/// ranged axis in turn narrowed to half its width — keeping the end away from where the
/// diagnosis's closest misses had it, else about its middle — the one whose stress motion
/// failed most chains and dropped most pieces (and with most misses) first, until one
/// has a path; that one widened back by bisection (to an eighth of its width); when no
/// single axis suffices, every ranged axis halved.
/// The report's [`RangeDesign`] says what was asked, what is answered and every box tried;
/// the box answered is returned with the cell.
pub fn solve_ranges(
    setup: &Setup,
    ranges: &JointRanges,
    given: Option<&Cell>,
    grid_step_deg: f64,
    options: &SolveOptions,
    dictionary: Option<&Dictionary>,
) -> Result<(Solution, Cell, JointRanges), SolveError> {
    let robot = &setup.robot;
    let attempt = |r: &JointRanges, diagnose: bool| -> Result<Attempt, SolveError> {
        let clock = Instant::now();
        let cell = range_cell(setup, r, given.cloned(), grid_step_deg)?;
        let options = SolveOptions {
            diagnose,
            ..options.clone()
        };
        let solution = solve_cell(setup, &cell, &options, dictionary)?;
        Ok(Attempt {
            solution,
            cell,
            time_s: clock.elapsed().as_secs_f64(),
        })
    };
    let axes = |r: &JointRanges, which: &[usize]| -> Vec<AxisRange> {
        which.iter().map(|&j| axis_range(robot, r, j)).collect()
    };
    let rotary = |j: usize| robot.actuated_joint(j).kind.is_rotary();
    let named: Vec<usize> = (0..ranges.ranges.len())
        .filter(|&j| ranges.named[j])
        .collect();
    let mut design = RangeDesign {
        file: (ranges.source.as_ref()).map(|p| p.display().to_string()),
        grid_step_deg,
        asked: axes(ranges, &named),
        answered: axes(ranges, &named),
        failures: Vec::new(),
        tried: Vec::new(),
    };
    // Without deciding every piece for the diagnosis: the closest misses of the pieces it
    // decided tell which end of an axis to narrow from.
    let first = attempt(ranges, false)?;
    if first.solved() {
        return Ok(first.answer(design, ranges.clone()));
    }
    // The axes in the order they are narrowed: the one whose stress motion failed most first.
    design.failures = failures_per_axis(&first, &named, ranges, robot);
    let mut order: Vec<usize> = (0..named.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(design.failures[k].total()));
    let mut probe = |r: &JointRanges, changed: &[usize]| -> Result<Attempt, SolveError> {
        let tried = attempt(r, false)?;
        let probe = RangeProbe {
            narrowed: axes(r, changed),
            length_mm: tried.length_mm(),
            time_s: tried.time_s,
        };
        log::info!("axis ranges: {}", probe.words());
        design.tried.push(probe);
        Ok(tried)
    };
    // Each axis alone at half its width, until one suffices; that one widened back by
    // bisection.
    let mut best: Option<(JointRanges, Attempt)> = None;
    for &k in &order {
        let j = named[k];
        let kept_end = design.failures[k].kept_end();
        let half = ranges.narrowed(j, 0.5, kept_end, rotary(j));
        let tried = probe(&half, &[j])?;
        if !tried.solved() {
            continue;
        }
        let (mut solved, mut unsolved) = (0.5, 1.0);
        let mut answer = (half, tried);
        for _ in 0..2 {
            let keep = 0.5 * (solved + unsolved);
            let wider = ranges.narrowed(j, keep, kept_end, rotary(j));
            let tried = probe(&wider, &[j])?;
            if tried.solved() {
                solved = keep;
                answer = (wider, tried);
            } else {
                unsolved = keep;
            }
        }
        best = Some(answer);
        break;
    }
    if best.is_none() && named.len() > 1 {
        let every = (named.iter().zip(&design.failures)).fold(ranges.clone(), |r, (&j, f)| {
            r.narrowed(j, 0.5, f.kept_end(), rotary(j))
        });
        let tried = probe(&every, &named)?;
        if tried.solved() {
            best = Some((every, tried));
        }
    }
    let Some((narrowed, answer)) = best else {
        // No box tried has a path: the box asked, with its whole diagnosis.
        return Ok(attempt(ranges, options.diagnose)?.answer(design, ranges.clone()));
    };
    design.answered = axes(&narrowed, &named);
    Ok(answer.answer(design, narrowed))
}

/// Per ranged axis (in `named` order), the chains its own stress motion failed and the
/// pieces its static sweep dropped in `attempt`, and in which half of its range of `ranges`
/// the diagnosis's closest misses had it.
fn failures_per_axis(
    attempt: &Attempt,
    named: &[usize],
    ranges: &JointRanges,
    robot: &Robot,
) -> Vec<AxisFailures> {
    let report = &attempt.solution.report;
    let axis_of = |motion: &Option<String>| -> Option<usize> {
        let name = motion.as_deref()?;
        let i = (attempt.cell.motions.iter()).position(|m| m.name == name)?;
        (i < named.len()).then_some(i)
    };
    let mut failures: Vec<AxisFailures> = (named.iter())
        .map(|&j| AxisFailures {
            joint: robot.actuated_joint(j).name.clone(),
            motion_tests_failed: 0,
            sweep_drops: 0,
            closest_misses: [0, 0],
        })
        .collect();
    let misses = (report.diagnosis.iter())
        .flat_map(|d| &d.segments)
        .flat_map(|s| &s.nearest_misses);
    for miss in misses {
        // A grid's pose is its sample at `time_s` (one a second), a motion's its moment.
        let Some(pose) =
            (attempt.cell.motions.get(miss.motion)).map(|m| m.motion.joints_at(miss.time_s))
        else {
            continue;
        };
        for (k, &j) in named.iter().enumerate() {
            let [a, b] = ranges.ranges[j];
            let middle = 0.5 * (a + b);
            if pose[j] < middle - 1e-9 {
                failures[k].closest_misses[0] += 1;
            } else if pose[j] > middle + 1e-9 {
                failures[k].closest_misses[1] += 1;
            }
        }
    }
    for k in report.candidates.iter().filter_map(|c| axis_of(&c.motion)) {
        failures[k].motion_tests_failed += 1;
    }
    for k in (report.static_sweep.rejected.iter()).filter_map(|r| axis_of(&r.motion)) {
        failures[k].sweep_drops += 1;
    }
    failures
}

/// One box solved.
struct Attempt {
    solution: Solution,
    cell: Cell,
    time_s: f64,
}

impl Attempt {
    fn solved(&self) -> bool {
        self.solution.report.status == Status::Solved
    }

    fn length_mm(&self) -> Option<f64> {
        self.solved()
            .then_some(self.solution.report.optimal_length_mm)
            .flatten()
    }

    fn answer(
        mut self,
        design: RangeDesign,
        answered: JointRanges,
    ) -> (Solution, Cell, JointRanges) {
        self.solution.report.ranges = Some(design);
        (self.solution, self.cell, answered)
    }
}

/// Joint `j`'s range in `ranges`, in the unit people give it.
fn axis_range(robot: &Robot, ranges: &JointRanges, j: usize) -> AxisRange {
    let joint = robot.actuated_joint(j);
    let (scale, unit) = joint.kind.display_unit();
    let tidy = |v: f64| (v * scale * 10.0).round() / 10.0;
    AxisRange {
        joint: joint.name.clone(),
        min: tidy(ranges.ranges[j][0]),
        max: tidy(ranges.ranges[j][1]),
        unit,
    }
}
