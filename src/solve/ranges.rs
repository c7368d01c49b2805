//! A design for axis ranges: the cell that stands for a box of joint values.

use super::report::{AxisFailures, AxisRange, RangeDesign, RangeProbe, Status};
use super::{Solution, SolveError, SolveOptions, solve_cell_remembering};
use crate::attachment::{
    CostEstimate, Evaluator, GRAVITY_RESOLUTION_DEG, LazyAttachment, SAMPLE_PAIRS, SAMPLE_POSES,
    SegmentPoses, VerdictMemory,
};
use crate::dictionary::Dictionary;
use crate::motion::{Cell, JointRanges, MotionError};
use crate::progress;
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
/// motions of `given`), and that cell. When the box has no path:
///
/// - when chains held every static pose but failed a stress motion at speed, the same box
///   with the axes reaching full speed [`RAMP_FACTORS`] times slower (no narrower range slows
///   an axis down);
/// - else the axis to narrow: each ranged axis in turn narrowed to half its width — keeping
///   the end away from where the blocking pieces failed ([`AxisFailures::kept_end`]), else
///   about its middle — the most blamed first ([`AxisFailures::blame`]), until one has a
///   path (each half-box also with the gentler ramps when it fails at speed); that one
///   widened back by bisection (to an eighth of its width); when no single axis suffices,
///   every ranged axis halved.
///
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
    let named: Vec<usize> = (0..ranges.ranges.len())
        .filter(|&j| ranges.named[j])
        .collect();
    let mut design = Designer {
        setup,
        given,
        grid_step_deg,
        options,
        dictionary,
        asked: ranges,
        design: RangeDesign {
            file: (ranges.source.as_ref()).map(|p| p.display().to_string()),
            grid_step_deg,
            asked: axis_ranges(robot, ranges, &named),
            answered: axis_ranges(robot, ranges, &named),
            time_to_full_speed_asked_s: ranges.time_to_full_speed_s,
            time_to_full_speed_answered_s: ranges.time_to_full_speed_s,
            failures: Vec::new(),
            tried: Vec::new(),
        },
        noted: false,
        most_s: None,
        memory: VerdictMemory::new(),
    };
    let rotary = |j: usize| robot.actuated_joint(j).kind.is_rotary();
    // Without deciding every piece for the diagnosis: the pieces it decided tell which end of
    // an axis to narrow from.
    let first = design.attempt(ranges, false)?;
    if first.solved() {
        return Ok(first.answer(design.design, ranges.clone()));
    }
    // At most: the gentler ramps; each axis alone, each with the gentler ramps; two
    // bisections; every axis together, with the gentler ramps.
    let ramps = RAMP_FACTORS.len();
    let boxes = ramps + named.len() * (1 + ramps) + 2 + usize::from(named.len() > 1) * (1 + ramps);
    // A narrower box has no more grid poses than the first, so no more pieces to decide.
    let each_s = design.most_s.unwrap_or(0.0).max(first.time_s);
    progress::note(&format!(
        "the box asked has no path ({}); finding what to change tries up to {boxes} more \
         boxes, stopping at the first with a path, each up to about {} (every candidate \
         piece decided) plus its motion tests",
        duration(first.time_s),
        duration(each_s)
    ));
    // The axes in the order they are narrowed: the most blamed first.
    let failures = failures_per_axis(&first, &named, ranges, setup);
    let mut order: Vec<usize> = (0..named.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(failures[k].blame()));
    design.design.failures = failures.clone();
    let mut best = design.gentler(ranges, &first, &[])?;
    // Each axis alone at half its width, until one suffices; that one widened back by
    // bisection at the ramp it needed.
    for &k in &order {
        if best.is_some() {
            break;
        }
        let j = named[k];
        let kept_end = failures[k].kept_end();
        let half = ranges.narrowed(j, 0.5, kept_end, rotary(j));
        let tried = design.probe(&half, &[j])?;
        let Some((half, tried)) = design
            .gentler(&half, &tried, &[j])?
            .or(tried.solved_in(half))
        else {
            continue;
        };
        let ramp = half.time_to_full_speed_s;
        let (mut solved, mut unsolved) = (0.5, 1.0);
        let mut answer = (half, tried);
        for _ in 0..2 {
            let keep = 0.5 * (solved + unsolved);
            let wider = JointRanges {
                time_to_full_speed_s: ramp,
                ..ranges.narrowed(j, keep, kept_end, rotary(j))
            };
            let tried = design.probe(&wider, &[j])?;
            if tried.solved() {
                solved = keep;
                answer = (wider, tried);
            } else {
                unsolved = keep;
            }
        }
        best = Some(answer);
    }
    if best.is_none() && named.len() > 1 {
        let every = (named.iter().zip(&failures)).fold(ranges.clone(), |r, (&j, f)| {
            r.narrowed(j, 0.5, f.kept_end(), rotary(j))
        });
        let tried = design.probe(&every, &named)?;
        best = design
            .gentler(&every, &tried, &named)?
            .or(tried.solved_in(every));
    }
    let Some((narrowed, answer)) = best else {
        // No box tried has a path: the box asked, with its whole diagnosis.
        let whole = design.attempt(ranges, options.diagnose)?;
        return Ok(whole.answer(design.design, ranges.clone()));
    };
    design.design.answered = axis_ranges(robot, &narrowed, &named);
    design.design.time_to_full_speed_answered_s = narrowed.time_to_full_speed_s;
    Ok(answer.answer(design.design, narrowed))
}

/// A range design under way: what it solves with, and what it has tried.
struct Designer<'a> {
    setup: &'a Setup,
    given: Option<&'a Cell>,
    grid_step_deg: f64,
    options: &'a SolveOptions,
    dictionary: Option<&'a Dictionary>,
    asked: &'a JointRanges,
    design: RangeDesign,
    /// The grid of the first box was noted (before it was solved).
    noted: bool,
    /// What deciding every candidate piece of the first box's grid takes, estimated before
    /// it was solved (s; `None` when nobody listens to progress).
    most_s: Option<f64>,
    /// What the boxes solved so far learnt of the pieces: the next box tests a piece only
    /// at the poses new to it.
    memory: VerdictMemory,
}

impl Designer<'_> {
    /// Solves the box `r`.
    fn attempt(&mut self, r: &JointRanges, diagnose: bool) -> Result<Attempt, SolveError> {
        let cell = range_cell(self.setup, r, self.given.cloned(), self.grid_step_deg)?;
        if !std::mem::replace(&mut self.noted, true) {
            self.most_s = note_estimate(self.setup, &cell, self.grid_step_deg, self.options)?;
        }
        let clock = Instant::now();
        let options = SolveOptions {
            diagnose,
            ..self.options.clone()
        };
        let solution = solve_cell_remembering(
            self.setup,
            &cell,
            &options,
            self.dictionary,
            Some(&mut self.memory),
        )?;
        Ok(Attempt {
            solution,
            cell,
            time_s: clock.elapsed().as_secs_f64(),
        })
    }

    /// Solves the box `r` (its axes `changed` named in the record) as one of the boxes tried.
    fn probe(&mut self, r: &JointRanges, changed: &[usize]) -> Result<Attempt, SolveError> {
        let tried = self.attempt(r, false)?;
        let probe = RangeProbe {
            narrowed: axis_ranges(&self.setup.robot, r, changed),
            time_to_full_speed_s: (r.time_to_full_speed_s != self.asked.time_to_full_speed_s)
                .then_some(r.time_to_full_speed_s),
            length_mm: tried.length_mm(),
            time_s: tried.time_s,
        };
        progress::note(&format!(
            "  tried {} ({:.0} s)",
            probe.words(),
            probe.time_s
        ));
        self.design.tried.push(probe);
        Ok(tried)
    }

    /// When chains of box `r` held every static pose but failed a stress motion at speed
    /// (`tried`), the same box with gentler ramps ([`RAMP_FACTORS`]) until one has a path.
    fn gentler(
        &mut self,
        r: &JointRanges,
        tried: &Attempt,
        changed: &[usize],
    ) -> Result<Option<(JointRanges, Attempt)>, SolveError> {
        let ranged = r.named.iter().filter(|&&n| n).count();
        let mut at_speed = !tried.solved() && failed_at_speed(tried, ranged);
        for factor in RAMP_FACTORS {
            if !at_speed {
                break;
            }
            let gentler = JointRanges {
                time_to_full_speed_s: factor * self.asked.time_to_full_speed_s,
                ..r.clone()
            };
            let tried = self.probe(&gentler, changed)?;
            if tried.solved() {
                return Ok(Some((gentler, tried)));
            }
            at_speed = failed_at_speed(&tried, ranged);
        }
        Ok(None)
    }
}

/// The gentler ramps a design whose stress motions fail at speed tries, as multiples of the
/// time to full speed asked: twice and four times as long (a quarter of the acceleration).
pub const RAMP_FACTORS: [f64; 2] = [2.0, 4.0];

/// Whether chains of `attempt` failed the motion test in a stress motion (the first
/// `ranged + 1` motions of its cell: each ranged axis alone, then every one together).
fn failed_at_speed(attempt: &Attempt, ranged: usize) -> bool {
    let stress: Vec<&str> = (attempt.cell.motions.iter())
        .take(ranged + 1)
        .map(|m| m.name.as_str())
        .collect();
    (attempt.solution.report.candidates.iter())
        .filter(|c| c.passed == Some(false))
        .any(|c| {
            c.motion
                .as_deref()
                .is_some_and(|name| stress.contains(&name))
        })
}

/// Notes how many static poses of the box's grid each piece is tested at and what the
/// box's static tests will cost, measured on a sample before it starts: at least its
/// search's first widening (when its shortest chain holds), at most every candidate piece
/// (when no chain holds: the search then decides them all) — the motion tests' verdicts
/// decide where between. Nothing is measured when nobody listens. Returns the most (s).
fn note_estimate(
    setup: &Setup,
    cell: &Cell,
    grid_step_deg: f64,
    options: &SolveOptions,
) -> Result<Option<f64>, SolveError> {
    let Some(grid) = cell.grid().filter(|_| progress::listening()) else {
        return Ok(None);
    };
    let counts: Vec<String> = (grid.per_segment.iter().enumerate())
        .map(|(m, poses)| format!("{} {}", setup.segment_name(m), poses.len()))
        .collect();
    progress::note(&format!(
        "axis-range grid ({grid_step_deg}° apart): each piece tested at up to {} static poses",
        counts.join(", ")
    ));
    let setup = options.setup_for(setup)?;
    let poses = SegmentPoses::for_cell(&setup, cell, options.intra_link)?;
    let evaluator = Evaluator::new(&setup, options.method)?;
    let lazy = LazyAttachment::new(&evaluator, &poses, None);
    let (least, most) = (
        CostEstimate::first_round(&lazy),
        CostEstimate::measure(&evaluator, &poses),
    );
    let threads = rayon::current_num_threads();
    progress::note(&format!(
        "a box takes about {} if its shortest chain holds ({} pieces), up to {} if every \
         candidate piece must be decided ({} pieces), plus its motion tests (on {threads} \
         threads; measured on {SAMPLE_PAIRS} clamp pairs per piece at up to {SAMPLE_POSES} \
         poses)",
        duration(least.wall_s(threads)),
        least.pieces(),
        duration(most.wall_s(threads)),
        most.pieces(),
    ));
    Ok(Some(most.wall_s(threads)))
}

/// `seconds` as people read a wait: "40 s", "12 min", "3.5 h".
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 90.0 => format!("{:.0} s", s.max(1.0)),
        s if s < 5400.0 => format!("{:.0} min", s / 60.0),
        s => format!("{:.1} h", s / 3600.0),
    }
}

/// Per ranged axis (in `named` order), the chains its own stress motion failed and the
/// pieces its static sweep dropped in `attempt`, and in which half of its range of `ranges`
/// the diagnosis's closest misses had it.
fn failures_per_axis(
    attempt: &Attempt,
    named: &[usize],
    ranges: &JointRanges,
    setup: &Setup,
) -> Vec<AxisFailures> {
    let robot = &setup.robot;
    let report = &attempt.solution.report;
    // The joints that shape each piece (the grid's): an axis that does not — a vertical
    // first axis under a wrist piece — is not blamed for where the piece failed.
    let gridded = attempt.cell.grid();
    let shapes = |segment: &str, j: usize| -> bool {
        let m = (0..setup.segment_count()).find(|&m| setup.segment_name(m) == segment);
        match (gridded, m) {
            (Some(grid), Some(m)) => grid.gridded.get(m).is_some_and(|g| g.contains(&j)),
            _ => true,
        }
    };
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
            failed_in_half: [0, 0],
        })
        .collect();
    // Each closest miss counts once, each rejecting pose for the pieces it rejected.
    let segments = (report.diagnosis.iter()).flat_map(|d| &d.segments);
    let failed = segments.flat_map(|s| {
        let misses = (s.nearest_misses.iter()).map(|miss| (miss.at.motion, miss.at.time_s, 1));
        let rejecting =
            (s.rejecting_poses.iter()).map(|at| (at.at.motion, at.at.time_s, at.pieces));
        misses
            .chain(rejecting)
            .map(move |at| (s.segment.as_str(), at))
    });
    for (segment, (motion, time_s, pieces)) in failed {
        // A grid's pose is its sample at `time_s` (one a second), a motion's its moment.
        let Some(pose) = (attempt.cell.motions.get(motion)).map(|m| m.motion.joints_at(time_s))
        else {
            continue;
        };
        for (k, &j) in named.iter().enumerate() {
            let [a, b] = ranges.ranges[j];
            let middle = 0.5 * (a + b);
            if !shapes(segment, j) {
                continue;
            } else if pose[j] < middle - 1e-9 {
                failures[k].failed_in_half[0] += pieces;
            } else if pose[j] > middle + 1e-9 {
                failures[k].failed_in_half[1] += pieces;
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

    /// `(box, self)` when it has a path.
    fn solved_in(self, r: JointRanges) -> Option<(JointRanges, Attempt)> {
        self.solved().then_some((r, self))
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

/// The ranges of joints `which` in `ranges`, in the unit people give them.
fn axis_ranges(robot: &Robot, ranges: &JointRanges, which: &[usize]) -> Vec<AxisRange> {
    which
        .iter()
        .map(|&j| axis_range(robot, ranges, j))
        .collect()
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
