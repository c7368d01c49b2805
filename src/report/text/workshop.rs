//! The summary `solve` prints by default, for the people who mount the cable: the physical
//! clamps with their places and cable marks, the pieces between them, the installation pose,
//! the length tolerance, what the design leaves out and the worst values over the motion.
//! No search vocabulary: that is `solve -v` ([`SolveReport`]'s `{:#}`) and the JSON.

use crate::life::estimate::CableLife;
use crate::motion_test::{Constraint, GuideSlide, MotionTestReport, Worst};
use crate::mounting::{self, MountingPlan, rows};
use crate::setup::Thresholds;
use crate::solve::{
    AllowedAxis, AllowedRanges, BindingMotion, MotionVerdict, PieceBinding, RangeEnd, SolveReport,
};
use crate::text_table::{count_words, decimal};
use std::fmt;

/// Writes the summary of `report`.
pub(super) fn write_summary(report: &SolveReport, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    let i = &report.inputs;
    writeln!(f, "{} — {}", report.status.describe(), report.explanation)?;
    writeln!(
        f,
        "robot setup {}, cable {}, {}",
        i.setup_file,
        i.cable,
        super::motion_words(report),
    )?;
    if let Some(dictionary) = &i.dictionary {
        super::details::write_dictionary(f, dictionary)?;
    }
    if let Some(design) = &report.ranges {
        super::ranges::write_ranges(f, design)?;
    }
    if let Some(plan) = &report.mounting {
        write_clamps(f, plan)?;
        write_pieces(f, plan)?;
        write_installation(f, plan)?;
    }
    if let (Some(test), Some(plan)) = (&report.motion_test, &report.mounting) {
        if report.motions.len() > 1 {
            write_motions(f, &report.limits(), &report.motions, &report.binding, plan)?;
        }
        write_worst(f, report, test, plan)?;
    }
    if let Some(allowed) = &report.allowed_ranges {
        write_allowed_ranges(f, allowed, report.mounting.as_ref())?;
    }
    if let Some(diagnosis) = &report.diagnosis {
        writeln!(f, "\nwhy there is no path")?;
        for line in diagnosis.to_string().lines() {
            writeln!(f, "  {line}")?;
        }
    }
    writeln!(
        f,
        "\nplacements in the link frames, the search's counts and margins, timings: `solve -v`; \
         every value: `--json`; pictures, a 3D view and an installation sheet: `--report DIR`"
    )
}

/// The ranges the mounting allows, as a vendor prints them, then what ends each.
pub(super) fn write_allowed_ranges(
    f: &mut fmt::Formatter<'_>,
    allowed: &AllowedRanges,
    plan: Option<&MountingPlan>,
) -> fmt::Result {
    let piece = |segment: &str| MountingPlan::piece_words_in(plan, segment);
    if let Some(failed) = &allowed.box_failure {
        let at: Vec<String> = (failed.failure.iter())
            .flat_map(|failure| &failure.joints)
            .map(|(joint, v)| format!("{joint} {}", decimal(*v, 1)))
            .collect();
        return writeln!(
            f,
            "\nallowed ranges: none — with every axis anywhere in {}, {} fails (at {}: {}); \
             give the ranges the cell needs (`--ranges`)",
            allowed.within,
            piece(&failed.segment),
            at.join(", "),
            (failed.failure.as_ref()).map_or("", |failure| failure.reason.as_str())
        );
    }
    let all: Vec<String> = allowed.axes.iter().map(AllowedAxis::words).collect();
    writeln!(f, "\nallowed ranges: {}", all.join(", "))?;
    writeln!(
        f,
        "  each axis alone, the others anywhere in {} (on a {}° grid; each end to {}°); jog \
         each axis to its ends as the last check",
        allowed.within, allowed.step_deg, allowed.resolution_deg
    )?;
    for axis in &allowed.axes {
        let shapes = match axis.shapes.is_empty() {
            true => "bends no piece".to_string(),
            false => {
                let pieces: Vec<String> = axis.shapes.iter().map(|s| piece(s)).collect();
                format!("bends {}", pieces.join(", "))
            }
        };
        match (&axis.below, &axis.above) {
            (RangeEnd::Limit, RangeEnd::Limit) => {
                writeln!(f, "  {}: {shapes}; its limits", axis.joint)?
            }
            (below @ RangeEnd::FullSpeed { .. }, _) => writeln!(
                f,
                "  {}: {shapes}; {}",
                axis.joint,
                axis.end_words(below, &piece)
            )?,
            (below, above) => writeln!(
                f,
                "  {}: {shapes}; below, {}; above, {}",
                axis.joint,
                axis.end_words(below, &piece),
                axis.end_words(above, &piece)
            )?,
        }
    }
    Ok(())
}

fn write_clamps(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    writeln!(f, "\n{}", rows::count_words(plan))?;
    let clamp_rows = rows::clamp_rows(plan);
    let width = (clamp_rows.iter().chain(&rows::sliding_rows(plan)))
        .map(|r| r.name.chars().count())
        .max()
        .unwrap_or(0);
    let link_width = (clamp_rows.iter().chain(&rows::sliding_rows(plan)))
        .map(|r| r.link.chars().count())
        .max()
        .unwrap_or(0);
    for row in clamp_rows.into_iter().chain(rows::sliding_rows(plan)) {
        let note = row
            .note
            .as_deref()
            .map(|n| format!("  ({n})"))
            .unwrap_or_default();
        let mark = match row.slides {
            true => "no mark".to_string(),
            false => format!("mark {:>5} mm", row.mark_mm),
        };
        writeln!(
            f,
            "  {:<width$}  on {:<link_width$}  {mark}{note}",
            row.name, row.link
        )?;
        let around = if row.around.is_empty() {
            String::new()
        } else {
            format!("; {}", row.around)
        };
        writeln!(f, "      {}{around}", row.along)?;
        if !row.cable.is_empty() {
            writeln!(f, "      cable {}; {}", row.cable, row.height)?;
        }
    }
    for warning in plan.warnings() {
        writeln!(f, "  warning: {warning}")?;
    }
    Ok(())
}

fn write_pieces(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    writeln!(
        f,
        "\n{}; {}",
        rows::length_words(plan),
        plan.tolerance_words()
    )?;
    let pieces = rows::piece_rows(plan);
    let width = pieces
        .iter()
        .map(|p| p.name.chars().count())
        .max()
        .unwrap_or(0);
    for piece in pieces {
        writeln!(
            f,
            "  {:<width$}  {:>5} mm  {}",
            piece.name, piece.length_mm, piece.across
        )?;
    }
    writeln!(f, "  {}", mounting::cut_words(plan))
}

fn write_installation(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    writeln!(f, "\n{}", plan.installation_words())
}

/// Each motion of a cell: holds (with its tightest bend and closest approach to the robot),
/// fails (what, when, where on the cable) or not run; then the motion that binds each piece.
pub fn write_motions(
    f: &mut impl fmt::Write,
    limits: &Limits,
    motions: &[MotionVerdict],
    binding: &[PieceBinding],
    plan: &MountingPlan,
) -> fmt::Result {
    writeln!(f, "\neach motion (simulated):")?;
    let width = motions
        .iter()
        .map(|m| m.name.chars().count())
        .max()
        .unwrap_or(0);
    for m in motions {
        writeln!(
            f,
            "  {:<width$}  {}",
            m.name,
            motion_verdict_words(limits, m, plan)
        )?;
        // What the sliding parts did over it: how far the cable slid, a retraction's travel.
        for row in (m.motion_test.iter()).flat_map(|t| t.slides.iter().map(slide_row)) {
            writeln!(f, "  {:<width$}    {}: {}", "", row.name, row.short)?;
        }
    }
    if binding.is_empty() {
        return Ok(());
    }
    writeln!(
        f,
        "\nthe motion that comes closest to each limit, piece by piece:"
    )?;
    for piece in binding {
        let name = plan
            .place_on_cable(&piece.segment, None)
            .map(|words| words.trim_start_matches("on ").to_string())
            .unwrap_or_else(|| format!("cable piece {}", piece.segment));
        let words = |what: &str, b: &Option<BindingMotion>| {
            b.as_ref().map(|b| {
                format!(
                    "{what} {} mm in {} (t = {:.2} s)",
                    decimal(b.value_mm, 1),
                    b.motion,
                    b.time_s
                )
            })
        };
        let parts: Vec<String> = [
            words("bend radius", &piece.bend_radius),
            words("clearance", &piece.clearance),
        ]
        .into_iter()
        .flatten()
        .collect();
        writeln!(f, "  {name}: {}", parts.join("; "))?;
    }
    Ok(())
}

/// One motion's verdict in a line: `holds: tightest bend radius 62.1 mm, closest to the robot
/// 9.3 mm`, `fails: …`, or `not run: an earlier motion failed`.
pub fn motion_verdict_words(limits: &Limits, m: &MotionVerdict, plan: &MountingPlan) -> String {
    let Some(test) = &m.motion_test else {
        return match m.grid_poses {
            Some(poses) => format!(
                "{poses} static poses of the box: every piece held every limit at the poses of \
                 the joints that shape it"
            ),
            None => "not run: an earlier motion failed".into(),
        };
    };
    if !test.passed {
        return verdict_words(limits, test, Some(plan)).replacen("failed", "fails", 1);
    }
    let rows = worst_rows(limits, test, Some(plan));
    let shown = rows
        .iter()
        .filter(|r| {
            matches!(
                r.what,
                "tightest bend radius" | "tightest flexing bend" | "closest to the robot"
            )
        })
        .map(|r| format!("{} {} (margin {})", r.what, r.value, r.margin));
    format!("holds: {}", shown.collect::<Vec<_>>().join(", "))
}

/// The worst value of each limit over the motion test, against its limit.
fn write_worst(
    f: &mut fmt::Formatter<'_>,
    report: &SolveReport,
    test: &MotionTestReport,
    plan: &MountingPlan,
) -> fmt::Result {
    // For a cell, the motion this test is over: the one the path is judged by.
    let over = match report.motions.get(report.shown_motion) {
        Some(m) if report.motions.len() > 1 => m.name.as_str(),
        _ => "the motion",
    };
    writeln!(
        f,
        "\nover {over} (simulated): {}",
        verdict_words(&report.limits(), test, Some(plan))
    )?;
    let rows = worst_rows(&report.limits(), test, Some(plan));
    for row in rows {
        match &row.when {
            Some(when) => writeln!(
                f,
                "  {:<21} {:>9} ({}) at {when}, {}",
                row.what, row.value, row.limit, row.place
            )?,
            None => writeln!(f, "  {:<21} {:>9}: {}", row.what, row.value, row.place)?,
        }
    }
    let not_stated = &report.inputs.limits.not_stated;
    if !not_stated.is_empty() {
        writeln!(f, "  the cable file states {}", not_stated.join("; "))?;
    }
    if let Some(life) = &report.life {
        writeln!(f, "\n{}", life_words(life, Some(plan)))?;
    }
    if let Some(trade) = life_trade_words(report) {
        writeln!(f, "{trade}")?;
    }
    let loads = load_rows(test, Some(plan));
    if !loads.is_empty() {
        writeln!(
            f,
            "\ntwist of each piece (from the cable as laid), the bend radius it kept, and loads \
             on each clamp, over {over}:"
        )?;
        let width = loads
            .iter()
            .map(|r| r.name.chars().count())
            .max()
            .unwrap_or(0);
        for row in loads {
            writeln!(f, "  {:<width$}  {}", row.name, row.words)?;
        }
    }
    Ok(())
}

/// The predicted life in words: rounds (and hours, years) to failure, where the cable fails
/// first, in the fitter's names when `plan` is the path's, and the rated point behind it.
pub fn life_words(life: &CableLife, plan: Option<&MountingPlan>) -> String {
    let count = count_words;
    let w = &life.weakest;
    let place = plan
        .and_then(|p| p.place_on_cable(&w.segment_name, Some(w.from_start_mm)))
        .unwrap_or_else(|| {
            format!(
                "on cable piece {}, {} mm from its start",
                w.segment_name,
                decimal(w.from_start_mm, 0)
            )
        });
    let time = match (life.hours_to_failure, life.years_to_failure) {
        (Some(hours), Some(years)) if hours.is_finite() => format!(
            "; {} hours at the stated cycles per hour, {} years around the clock",
            count(hours),
            decimal(years, 1)
        ),
        _ => String::new(),
    };
    let basis = match (life.rated_cycles, life.conductor_offset_mm) {
        (Some(cycles), _) => {
            let mut rated = vec![format!("{} cycles", count(cycles))];
            if let Some(r) = life.rated_bend_radius_mm {
                rated.push(format!("flexed to {} mm", decimal(r, 0)));
            }
            if let Some(t) = life.rated_torsion_deg_per_m {
                rated.push(format!("twisted ±{}°/m", decimal(t, 0)));
            }
            let exponent = decimal(life.exponent, 1);
            let default = if life.exponent_stated {
                ""
            } else {
                ", the default"
            };
            format!(
                "the datasheet's rating: {}; exponent {exponent}{default}",
                rated.join(", ")
            )
        }
        (None, offset) => format!(
            "annealed copper's strain–life line, the copper straining {} mm from the axis: \
             no rated life in the cable file",
            decimal(offset.unwrap_or(f64::NAN), 2)
        ),
    };
    format!(
        "predicted life: {} cycles{time}; it fails first {place} ({basis})",
        count(life.cycles_to_failure)
    )
}

/// The length and predicted life of every path a life goal weighed, in the order tried:
/// `paths weighed by their life: 760 mm 105.2 million cycles, 780 mm 220.0 million cycles
/// (the answer)`; `None` without a life goal.
pub fn life_trade_words(report: &SolveReport) -> Option<String> {
    let answer = report.optimal_length_mm;
    let weighed: Vec<String> = (report.candidates.iter())
        .filter_map(|c| {
            let cycles = c.life_cycles?;
            let words = format!("{} cycles", count_words(cycles));
            let chosen = c.passed == Some(true) && answer == Some(c.total_length_mm);
            let mark = if chosen { " (the answer)" } else { "" };
            Some(format!(
                "{} mm {words}{mark}",
                decimal(c.total_length_mm, 0)
            ))
        })
        .collect();
    (!weighed.is_empty()).then(|| format!("paths weighed by their life: {}", weighed.join(", ")))
}

/// What the wordings of a motion test need besides the test: the limits it was held to and
/// the cable model's sub-segment length (places along a piece are counted in it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// The limits.
    pub thresholds: Thresholds,
    /// Sub-segment length (mm).
    pub sub_segment_pitch_mm: f64,
}

impl SolveReport {
    /// The limits its motion tests were held to, for their wordings.
    pub fn limits(&self) -> Limits {
        Limits {
            thresholds: self.thresholds,
            sub_segment_pitch_mm: self.sub_segment_pitch_mm,
        }
    }
}

/// One piece's largest twist or one clamp's largest loads over the motion test, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadRow {
    /// `piece 1 → 2`, `clamp 1`, `gripper connector`.
    pub name: String,
    /// `largest twist −35° (−125°/m) at t = 4.91 s`.
    pub words: String,
    /// The same for a table cell: `−35° (−125°/m), t = 4.91 s`.
    pub short: String,
}

/// The largest twist of every piece and the largest loads on every clamp over `test`, named
/// as the fitter names them when `plan` is the tested path's.
pub fn load_rows(test: &MotionTestReport, plan: Option<&MountingPlan>) -> Vec<LoadRow> {
    let mut rows: Vec<LoadRow> =
        test.twists
            .iter()
            .map(|t| {
                let name = plan
                    .and_then(|p| p.place_on_cable(&t.segment_name, None))
                    .map(|words| words.trim_start_matches("on ").to_string())
                    .unwrap_or_else(|| format!("cable piece {}", t.segment_name));
                let (twist, per_m) = (decimal(t.twist_deg, 0), decimal(t.twist_deg_per_m, 0));
                // Which bend radius the piece kept: the flexing one where its shape changed.
                let kept = test.pieces.iter().find(|p| p.segment == t.segment).map_or(
                    String::new(),
                    |p| {
                        let radius = decimal(p.bend_radius_limit_m * 1e3, 0);
                        if p.flexes {
                            format!("; flexes: bend radius kept ≥ {radius} mm")
                        } else {
                            format!("; does not flex: bend radius kept ≥ {radius} mm")
                        }
                    },
                );
                LoadRow {
                    name,
                    words: format!(
                        "largest twist {twist}° ({per_m}°/m) at t = {:.2} s{kept}",
                        t.time_s
                    ),
                    short: format!("{twist}° ({per_m}°/m), t = {:.2} s", t.time_s),
                }
            })
            .collect();
    rows.extend(test.clamp_loads.iter().map(|c| {
        let name = plan
            .and_then(|p| c.guides.iter().find_map(|g| p.clamp_of_guide(g)))
            .map(|clamp| clamp.name())
            .unwrap_or_else(|| c.guides.join(" = "));
        let (force, moment) = (decimal(c.max_force_n, 2), decimal(c.max_moment_n_m, 3));
        // A rotating clamp between two pieces: how far the cable turned in it.
        let turned = (test.clamp_turns.iter())
            .find(|t| c.guides.contains(&t.guide))
            .map_or(String::new(), |t| {
                format!(
                    "; the cable turned in it by up to {}° at t = {:.2} s",
                    decimal(t.largest_turn_deg, 0),
                    t.time_s
                )
            });
        LoadRow {
            name,
            words: format!(
                "largest force {force} N at t = {:.2} s, largest moment {moment} N·m at t = \
                 {:.2} s{turned}",
                c.force_time_s, c.moment_time_s
            ),
            short: format!(
                "{force} N (t = {:.2} s); {moment} N·m (t = {:.2} s)",
                c.force_time_s, c.moment_time_s
            ),
        }
    }));
    rows.extend(test.slides.iter().map(slide_row));
    rows
}

/// How far the cable slid through a sliding guide, or a retraction's travel and force.
fn slide_row(s: &GuideSlide) -> LoadRow {
    let mm = |m: f64| decimal(m * 1e3, 0);
    match (s.travel_max_m, s.peak_force_n) {
        (Some(travel), Some(force)) => {
            let stop = match s.end_stop_s > 0.0 {
                true => format!("; on its end stop for {:.2} s", s.end_stop_s),
                false => String::new(),
            };
            LoadRow {
                name: format!("retraction outlet {}", s.guide),
                words: format!(
                    "cable pulled out {}–{} mm of its {} mm travel (most at t = {:.2} s), spring \
                     force up to {} N{stop}",
                    mm(s.least_m),
                    mm(s.most_m),
                    mm(travel),
                    s.most_time_s,
                    decimal(force, 2)
                ),
                short: format!(
                    "travel {}–{} of {} mm, up to {} N",
                    mm(s.least_m),
                    mm(s.most_m),
                    mm(travel),
                    decimal(force, 2)
                ),
            }
        }
        _ => LoadRow {
            name: format!("sliding guide {}", s.guide),
            words: format!(
                "the cable slid {} mm through it: {}–{} mm of cable before it (least at t = \
                 {:.2} s, most at t = {:.2} s; {} mm at the start)",
                mm(s.most_m - s.least_m),
                mm(s.least_m),
                mm(s.most_m),
                s.least_time_s,
                s.most_time_s,
                mm(s.first_m)
            ),
            short: format!(
                "slid {} mm ({}–{} mm before it)",
                mm(s.most_m - s.least_m),
                mm(s.least_m),
                mm(s.most_m)
            ),
        },
    }
}

/// One limit's worst value over the motion test, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct WorstRow {
    /// `closest to the robot`.
    pub what: &'static str,
    /// `9.3 mm`, `1.0000`, or `none` for a cable that never approaches itself.
    pub value: String,
    /// `limit 0.0 mm`.
    pub limit: String,
    /// What is left to the limit: `9.3 mm`, `∞`.
    pub margin: String,
    /// `t = 5.10 s`; `None` for a limit never approached (no part of the cable comes back
    /// toward another).
    pub when: Option<String>,
    /// `on piece 2 → gripper connector, 25 mm from clamp 2, near link_4`.
    pub place: String,
}

/// `held every limit`, or what failed and where, in the fitter's names when `plan` is the
/// tested path's.
pub fn verdict_words(
    limits: &Limits,
    test: &MotionTestReport,
    plan: Option<&MountingPlan>,
) -> String {
    match (&test.failure, &test.first_violation) {
        (None, _) => "held every limit".to_string(),
        (Some(_), Some(v)) => {
            let row = worst_row_of(limits, plan, v.constraint, &v.to_worst(), v.threshold);
            format!(
                "failed: {} {} ({}) at {}, {}",
                row.what,
                row.value,
                row.limit,
                row.when.unwrap_or_default(),
                row.place
            )
        }
        (Some(failure), None) => format!("failed: {}", failure.reason),
    }
}

/// The worst value of each limit over `test`, places in the fitter's names when `plan` is
/// the tested path's (else the setup's piece names).
pub fn worst_rows(
    limits: &Limits,
    test: &MotionTestReport,
    plan: Option<&MountingPlan>,
) -> Vec<WorstRow> {
    let t = &limits.thresholds;
    let mut rows = vec![
        (
            Constraint::Contact,
            test.worst_clearance.clone(),
            t.contact_clearance_m,
        ),
        (
            Constraint::SelfContact,
            test.worst_self_clearance.clone(),
            0.0,
        ),
    ];
    rows.extend(bend_rows(test, t));
    rows.push((Constraint::Stretch, test.worst_stretch.clone(), t.stretch));
    if test.worst_twist.is_some() {
        let limit = t.torsion_limit_deg_per_m.unwrap_or(f64::INFINITY);
        rows.push((Constraint::Twist, test.worst_twist.clone(), limit));
    }
    rows.into_iter()
        .filter_map(|(constraint, worst, limit)| match worst {
            Some(w) => Some(worst_row_of(limits, plan, constraint, &w, limit)),
            // No approach to itself is an answer too: the cable never comes back toward itself.
            None if constraint == Constraint::SelfContact && test.steps > 0 => Some(WorstRow {
                what: "closest to itself",
                value: "none".into(),
                limit: "limit 0.0 mm".into(),
                margin: "∞".into(),
                when: None,
                place: "no part of the cable comes back toward another".into(),
            }),
            None => None,
        })
        .collect()
}

/// The tightest bend of the pieces that keep the fixed radius and of those that flex (each
/// against its own limit), or the whole cable's against the fixed radius when the engine
/// kept no pieces.
fn bend_rows(test: &MotionTestReport, t: &Thresholds) -> Vec<(Constraint, Option<Worst>, f64)> {
    // Without a flexing radius larger than the fixed one, one limit holds every piece.
    if test.pieces.is_empty() || t.flexing_bend_radius_m() <= t.min_bend_radius_m {
        return vec![(
            Constraint::BendRadius,
            test.worst_bend.clone(),
            t.min_bend_radius_m,
        )];
    }
    let tightest = |flexing: bool| {
        test.pieces
            .iter()
            .filter(|p| p.flexes == flexing)
            .filter_map(|p| p.worst_bend.as_ref())
            .min_by(|a, b| a.value.total_cmp(&b.value))
            .cloned()
    };
    let mut rows = vec![(Constraint::BendRadius, tightest(false), t.min_bend_radius_m)];
    if let Some(worst) = tightest(true) {
        rows.push((
            Constraint::FlexingBendRadius,
            Some(worst),
            t.flexing_bend_radius_m(),
        ));
    }
    rows
}

/// One row: `w`, the worst of `constraint`, against `limit`.
fn worst_row_of(
    limits: &Limits,
    plan: Option<&MountingPlan>,
    constraint: Constraint,
    w: &Worst,
    limit: f64,
) -> WorstRow {
    let length = |v: f64| {
        if v.is_finite() {
            format!("{} mm", decimal(v * 1e3, 1))
        } else {
            "∞".to_string()
        }
    };
    let (what, value, limit_text, margin) = match constraint {
        Constraint::Contact => (
            "closest to the robot",
            length(w.value),
            length(limit),
            length(w.value - limit),
        ),
        Constraint::SelfContact => (
            "closest to itself",
            length(w.value),
            length(limit),
            length(w.value - limit),
        ),
        Constraint::BendRadius | Constraint::FlexingBendRadius => (
            match constraint {
                Constraint::BendRadius => "tightest bend radius",
                _ => "tightest flexing bend",
            },
            length(w.value),
            length(limit),
            length(w.value - limit),
        ),
        Constraint::Twist if limit.is_finite() => (
            "most twisted",
            format!("{} °/m", decimal(w.value, 0)),
            format!("±{} °/m", decimal(limit, 0)),
            format!("{} °/m", decimal(limit - w.value, 0)),
        ),
        Constraint::Twist => (
            "most twisted",
            format!("{} °/m", decimal(w.value, 0)),
            "not stated by the cable file".to_string(),
            "—".to_string(),
        ),
        Constraint::Stretch => (
            "most stretched",
            decimal(w.value, 4),
            decimal(limit, 2),
            decimal(limit - w.value, 4),
        ),
        Constraint::ContactForce => (
            "largest contact force",
            format!("{} N", decimal(w.value, 3)),
            "0 N".to_string(),
            format!("{} N", decimal(-w.value, 3)),
        ),
        Constraint::Travel => (
            "largest pull on a retraction's end stop",
            format!("{} N", decimal(w.value, 2)),
            format!("{} N", decimal(limit, 2)),
            format!("{} N", decimal(limit - w.value, 2)),
        ),
    };
    WorstRow {
        what,
        value,
        limit: format!("limit {limit_text}"),
        margin,
        when: Some(format!("t = {:.2} s", w.time_s)),
        place: where_on_cable(limits, plan, w),
    }
}

/// `on piece 2 → gripper connector, 25 mm from clamp 2, near link_4`: the place of a worst
/// value on the mounted cable, in the fitter's names.
fn where_on_cable(limits: &Limits, plan: Option<&MountingPlan>, w: &Worst) -> String {
    let pitch_mm = limits.sub_segment_pitch_mm;
    let along = w
        .place
        .sub_segment
        .map(|k| (k as f64 + 0.5) * pitch_mm)
        .or(w.place.node.map(|n| n as f64 * pitch_mm));
    let mut words = plan
        .and_then(|plan| plan.place_on_cable(&w.segment_name, along))
        .unwrap_or_else(|| format!("on cable piece {}", w.segment_name));
    if let Some(link) = &w.place.link {
        words.push_str(&format!(", near {link}"));
    }
    words
}
