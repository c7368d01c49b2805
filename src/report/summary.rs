//! `summary.md`: the result of a solve for people — the path, the set sizes, the margins,
//! the motion test, the timings and the inputs with their hashes.

use super::hashes::Hashed;
use super::text::{life_words, motion_verdict_words, verdict_words, worst_rows};
use crate::escape::markdown as text;
use crate::motion_test::MotionTestReport;
use crate::mounting::{self, MountingPlan, rows};
use crate::solve::{AllowedRanges, NamedPath, SolveReport};
use crate::text_table::{decimal, decimals};
use std::fmt::Write as _;

/// The whole `summary.md`; `files` are the report's other files with what each shows, and
/// `notes` anything the report could not draw.
pub fn summary_markdown(
    report: &SolveReport,
    inputs: &[Hashed],
    files: &[(&str, &str)],
    notes: &[String],
) -> String {
    let mut md = String::new();
    heading(&mut md, report);
    if let Some(plan) = &report.mounting {
        mounting_tables(&mut md, plan);
    }
    if let Some(allowed) = &report.allowed_ranges {
        allowed_table(&mut md, allowed, report.mounting.as_ref());
    }
    if let (Some(plan), true) = (&report.mounting, report.motions.len() > 1) {
        motions_table(&mut md, report, plan);
    }
    if let Some(test) = &report.motion_test {
        motion_test_table(&mut md, report, test);
    }
    // The search's details, in its own words (the glossary explains them).
    if let (Some(path), Some(total)) = (&report.optimal, report.optimal_length_mm) {
        path_tables(&mut md, path, total);
    }
    sets_table(&mut md, report);
    margins_table(&mut md, report);
    candidates_table(&mut md, report);
    timings_table(&mut md, report);
    inputs_table(&mut md, inputs, report);
    section(&mut md, "Files");
    for (file, what) in files {
        let _ = writeln!(md, "- [`{file}`]({file}): {what}");
    }
    if !notes.is_empty() {
        section(&mut md, "Notes");
        for note in notes {
            let _ = writeln!(md, "- {}", text(note));
        }
    }
    md
}

/// The range each axis allows, what ends it, and the box it was asked within.
fn allowed_table(md: &mut String, allowed: &AllowedRanges, plan: Option<&MountingPlan>) {
    let piece = |segment: &str| MountingPlan::piece_words_in(plan, segment);
    section(md, "Allowed ranges");
    if let Some(failed) = &allowed.box_failure {
        let _ = writeln!(
            md,
            "None: with every axis anywhere in {}, {} fails ({}).",
            text(&allowed.within),
            text(&piece(&failed.segment)),
            text((failed.failure.as_ref()).map_or("", |f| f.reason.as_str()))
        );
        return;
    }
    let _ = writeln!(
        md,
        "Each axis alone, the others anywhere in {} (a {}° grid; each end to {}°).\n",
        text(&allowed.within),
        allowed.step_deg,
        allowed.resolution_deg
    );
    header(
        md,
        &["axis", "allows", "asked within", "limits", "below", "above"],
    );
    for axis in &allowed.axes {
        let pair = |[a, b]: [f64; 2]| format!("{}…{}", decimal(a, 1), decimal(b, 1));
        row(
            md,
            &[
                axis.joint.clone(),
                (axis.words().strip_prefix(&axis.joint))
                    .unwrap_or_default()
                    .trim()
                    .to_string(),
                pair(axis.within),
                axis.limits.map_or("none (continuous)".into(), pair),
                axis.end_words(&axis.below, &piece),
                axis.end_words(&axis.above, &piece),
            ],
        );
    }
}

fn section(md: &mut String, title: &str) {
    let _ = write!(md, "\n## {title}\n\n");
}

/// A Markdown table row; the cells are text (names from the inputs among them), never
/// markup.
fn row(md: &mut String, cells: &[String]) {
    let cells: Vec<String> = cells.iter().map(|cell| text(cell)).collect();
    let _ = writeln!(md, "| {} |", cells.join(" | "));
}

/// A Markdown table header with its rule.
fn header(md: &mut String, titles: &[&str]) {
    row(
        md,
        &titles.iter().map(|t| t.to_string()).collect::<Vec<_>>(),
    );
    let _ = writeln!(md, "|{}", " --- |".repeat(titles.len()));
}

fn heading(md: &mut String, report: &SolveReport) {
    let verdict = report.status.describe();
    let _ = writeln!(md, "# Cable path: {verdict}\n");
    let _ = writeln!(md, "{}.\n", text(&capitalized(&report.explanation)));
    if let Some(diagnosis) = &report.diagnosis {
        let diagnosis = crate::escape::terminal(&diagnosis.to_string()).into_owned();
        let fence = fence_for(&diagnosis);
        let _ = writeln!(
            md,
            "## Why there is no path\n\n{fence}text\n{diagnosis}{fence}\n"
        );
    }
    if let Some(total) = report.optimal_length_mm {
        let _ = writeln!(
            md,
            "Total cable length **{total:.0} mm**, {} cable pieces, {}.",
            report
                .optimal
                .as_ref()
                .map_or(0, |path| path.segments.len()),
            report.inputs.method
        );
    }
}

/// The answer as the workshop mounts it: physical clamps, marks, places, pieces, tolerance,
/// cut length and installation pose.
fn mounting_tables(md: &mut String, plan: &MountingPlan) {
    section(md, "How to mount it");
    let _ = writeln!(
        md,
        "{}. Printable sheet: [install.html](install.html).\n",
        text(&capitalized(&rows::count_words(plan)))
    );
    for warning in plan.warnings() {
        let _ = writeln!(md, "**Warning:** {}.\n", text(&warning));
    }
    header(
        md,
        &["clamp", "link", "mark (mm)", "place on the link", "cable"],
    );
    for clamp in rows::clamp_rows(plan)
        .into_iter()
        .chain(rows::sliding_rows(plan))
    {
        let note = clamp.note.filter(|_| clamp.slides).unwrap_or_default();
        let place = [clamp.along, clamp.around]
            .into_iter()
            .filter(|s| !s.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        let cable = [clamp.cable, clamp.height, note]
            .into_iter()
            .filter(|s| !s.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        row(md, &[clamp.name, clamp.link, clamp.mark_mm, place, cable]);
    }
    let _ = writeln!(md);
    header(md, &["piece", "length (mm)", "crosses"]);
    for piece in rows::piece_rows(plan) {
        row(md, &[piece.name, piece.length_mm, piece.across]);
    }
    let notes = [
        format!("{}.", capitalized(&rows::length_words(plan))),
        format!("{}.", capitalized(&plan.tolerance_words())),
        format!("{}.", capitalized(&mounting::cut_words(plan))),
        format!("{}.", capitalized(&plan.installation_words())),
        "The cable before the first clamp and beyond the last is outside this design.".into(),
    ];
    let _ = writeln!(md);
    for note in notes {
        let _ = writeln!(md, "- {}", text(&note));
    }
}

fn path_tables(md: &mut String, path: &NamedPath, total_mm: f64) {
    section(md, &format!("The path as searched ({total_mm:.0} mm)"));
    header(md, &["piece", "from", "to", "links", "kind", "length (mm)"]);
    for s in &path.segments {
        row(
            md,
            &[
                s.name.clone(),
                s.from_guide.clone(),
                s.to_guide.clone(),
                format!("{} → {}", s.from_link, s.to_link),
                s.kind.to_string(),
                format!("{:.0}", s.length_mm),
            ],
        );
    }
    let _ = writeln!(md, "\nWhere each clamp goes, in its link's frame:\n");
    header(
        md,
        &[
            "clamp",
            "link",
            "placement",
            "x, y, z (mm)",
            "roll, pitch, yaw (deg)",
        ],
    );
    for g in &path.guides {
        row(
            md,
            &[
                g.name.clone(),
                g.link.clone(),
                g.configuration.clone(),
                decimals(&g.xyz_mm, 1),
                decimals(&g.rpy_deg, 1),
            ],
        );
    }
    if !path.left_out.is_empty() {
        let _ = writeln!(
            md,
            "\nOptional clamps this path leaves out: {}.",
            text(&path.left_out.join(", "))
        );
    }
}

fn sets_table(md: &mut String, report: &SolveReport) {
    section(md, "Cable pieces tested (attachment test)");
    let sets = [
        "candidates",
        "after pruning",
        "hold the limits",
        "robust to a length error",
    ];
    header(
        md,
        &[&["piece", "clamps", "kind", "test poses"][..], &sets].concat(),
    );
    for s in &report.segments {
        row(
            md,
            &[
                s.segment.clone(),
                format!("{} → {}", s.from_guide, s.to_guide),
                s.kind.to_string(),
                s.test_poses.len().to_string(),
                s.d0.to_string(),
                s.d0_pruned.to_string(),
                s.d1.to_string(),
                s.d2.to_string(),
            ],
        );
    }
    let _ = writeln!(
        md,
        "\nChains of robust pieces through the clamps: {}.",
        report.chains
    );
    if let Some(d) = &report.inputs.dictionary {
        let _ = writeln!(
            md,
            "\nIntra-link pieces from the dictionary {} ({} gravity directions, at most {:.1}° \
             from any direction).",
            text(&d.file),
            d.directions,
            d.covering_radius_deg
        );
    }
}

fn margins_table(md: &mut String, report: &SolveReport) {
    if report.margins.is_empty() {
        return;
    }
    section(md, "Static margins at the binding test pose");
    header(
        md,
        &["piece", "limit", "value", "threshold", "margin", "pose"],
    );
    for m in &report.margins {
        let show = |v: f64| match m.constraint {
            "stretch" => format!("{v:.4}"),
            _ => format!("{:.1} mm", v * 1e3),
        };
        row(
            md,
            &[
                m.segment.clone(),
                m.constraint.replace('_', " "),
                show(m.value),
                show(m.threshold),
                show(m.margin),
                format!("t = {:.2} s, {}", m.time_s, m.reason),
            ],
        );
    }
}

/// A cell: each motion's verdict, then the motion that binds each piece.
fn motions_table(md: &mut String, report: &SolveReport, plan: &MountingPlan) {
    section(md, "Motions of the cell");
    header(md, &["motion", "cycles per hour", "duration", "verdict"]);
    let limits = report.limits();
    for m in &report.motions {
        row(
            md,
            &[
                m.name.clone(),
                m.cycles_per_hour.map_or("–".into(), |c| decimal(c, 0)),
                format!("{} s", decimal(m.duration_s, 2)),
                motion_verdict_words(&limits, m, plan),
            ],
        );
    }
    if report.binding.is_empty() {
        return;
    }
    let _ = writeln!(md);
    header(
        md,
        &["piece", "tightest bend radius", "closest to the robot"],
    );
    let binding = |b: &Option<crate::solve::BindingMotion>| match b {
        Some(b) => format!(
            "{} mm in {} (t = {:.2} s)",
            decimal(b.value_mm, 1),
            b.motion,
            b.time_s
        ),
        None => "–".into(),
    };
    for piece in &report.binding {
        row(
            md,
            &[
                piece.segment.clone(),
                binding(&piece.bend_radius),
                binding(&piece.clearance),
            ],
        );
    }
}

fn motion_test_table(md: &mut String, report: &SolveReport, test: &MotionTestReport) {
    section(md, "Motion test");
    let plan = report.mounting.as_ref();
    let _ = writeln!(
        md,
        "{} ({:.2} s simulated in {:.1} s).\n",
        text(&capitalized(&verdict_words(&report.limits(), test, plan))),
        test.simulated_s,
        test.wall_time_s
    );
    header(md, &["limit", "worst", "limit", "margin", "when, where"]);
    for w in worst_rows(&report.limits(), test, plan) {
        row(
            md,
            &[
                w.what.into(),
                w.value,
                w.limit.trim_start_matches("limit ").to_string(),
                w.margin,
                match &w.when {
                    Some(when) => format!("{when}, {}", w.place),
                    None => w.place.clone(),
                },
            ],
        );
    }
    if let Some(w) = &test.worst_contact_force {
        row(
            md,
            &[
                "largest contact force".into(),
                format!("{:.3} N", w.value),
                "0 N".into(),
                "—".into(),
                format!("t = {:.2} s, cable piece {}", w.time_s, w.segment_name),
            ],
        );
    }
    if let Some(life) = &report.life {
        let _ = writeln!(md, "\n{}.", text(&capitalized(&life_words(life, plan))));
    }
}

fn candidates_table(md: &mut String, report: &SolveReport) {
    if report.candidates.is_empty() {
        return;
    }
    section(md, "Candidates tried");
    header(md, &["rank", "length (mm)", "outcome"]);
    for c in &report.candidates {
        let outcome = match (c.passed, &c.failure) {
            (Some(true), _) => "passed".to_string(),
            (Some(false), Some(why)) => format!("failed: {why}"),
            (Some(false), None) => "failed".to_string(),
            (None, _) => "not tested".to_string(),
        };
        row(
            md,
            &[
                c.rank.to_string(),
                format!("{:.0}", c.total_length_mm),
                outcome,
            ],
        );
    }
    let sweep = &report.static_sweep;
    if sweep.poses > 0 {
        let _ = writeln!(
            md,
            "\nThe static sweep solved {} cable pieces at {} motion poses and dropped {}.",
            sweep.pvs_swept,
            sweep.poses,
            sweep.rejected.len()
        );
    }
}

fn timings_table(md: &mut String, report: &SolveReport) {
    section(md, "Timings");
    let t = &report.timings;
    header(md, &["stage", "time (s)"]);
    for (stage, s) in [
        ("critical poses", t.critical_poses_s),
        ("attachment test", t.attachment_s),
        ("chain search", t.chain_s),
        ("static sweep", t.static_sweep_s),
        ("motion test", t.motion_test_s),
        ("total", t.total_s),
    ] {
        row(md, &[stage.into(), format!("{s:.3}")]);
    }
}

fn inputs_table(md: &mut String, inputs: &[Hashed], report: &SolveReport) {
    section(md, "Inputs");
    header(md, &["input", "file", "xxh3-64"]);
    for input in inputs {
        row(
            md,
            &[
                input.role.to_string(),
                input.file.clone(),
                input.hash.clone(),
            ],
        );
    }
    let i = &report.inputs;
    let _ = writeln!(
        md,
        "\nSetup content hash {} (FNV-1a of the loaded setup), cable {}, motion {:.2} s in {} samples.",
        i.setup_hash,
        text(&i.cable),
        i.motion_duration_s,
        i.motion_samples
    );
}

/// A code fence longer than any run of backticks in `content`, so that nothing in it ends
/// the block early.
fn fence_for(content: &str) -> String {
    let longest = content.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    "`".repeat(longest.max(2) + 1)
}

/// `text` with its first letter in upper case.
pub(super) fn capitalized(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or(String::new(), |first| {
        first.to_uppercase().chain(chars).collect()
    })
}
