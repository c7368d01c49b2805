//! What a design for axis ranges asked and answered, in words: one wording for the summary
//! and `solve -v`.

use crate::solve::{AxisRange, RangeDesign};
use std::fmt;

/// What a design for axis ranges asked, what it answers, and the boxes it tried.
pub(super) fn write_ranges(f: &mut fmt::Formatter<'_>, design: &RangeDesign) -> fmt::Result {
    let list = |ranges: &[AxisRange]| -> String {
        ranges
            .iter()
            .map(AxisRange::words)
            .collect::<Vec<_>>()
            .join(", ")
    };
    writeln!(
        f,
        "axis ranges{}: {} (each piece at the box's poses {}° apart; each axis end to end at \
         its URDF speed, full speed in {} s)",
        design
            .file
            .as_ref()
            .map(|file| format!(" of {file}"))
            .unwrap_or_default(),
        list(&design.asked),
        design.grid_step_deg,
        design.time_to_full_speed_asked_s
    )?;
    if design.time_to_full_speed_answered_s != design.time_to_full_speed_asked_s {
        writeln!(
            f,
            "  at the acceleration asked the box has no path: the axes must take {} s to full \
             speed, not {} s — the path below is for that",
            design.time_to_full_speed_answered_s, design.time_to_full_speed_asked_s
        )?;
    }
    let narrowed: Vec<String> = design
        .narrowed()
        .map(|(asked, answered)| {
            format!("{} (asked {}…{})", answered.words(), asked.min, asked.max)
        })
        .collect();
    if !narrowed.is_empty() {
        writeln!(
            f,
            "  the ranges asked have no path: narrow {} — the path below is for that box",
            narrowed.join(", ")
        )?;
    } else if !design.tried.is_empty()
        && design.time_to_full_speed_answered_s == design.time_to_full_speed_asked_s
    {
        writeln!(
            f,
            "  the ranges asked have no path, and none of the boxes tried below has one"
        )?;
    }
    let failed: Vec<String> = (design.failures.iter())
        .filter(|a| a.motion_tests_failed + a.sweep_drops > 0)
        .map(|a| {
            let plural = |n: usize, one: &str, many: &str| match n {
                1 => format!("1 {one}"),
                n => format!("{n} {many}"),
            };
            format!(
                "{} end to end failed {} and dropped {}",
                a.joint,
                plural(a.motion_tests_failed, "motion test", "motion tests"),
                plural(a.sweep_drops, "piece", "pieces")
            )
        })
        .collect();
    if !failed.is_empty() {
        writeln!(f, "  in the box asked: {}", failed.join("; "))?;
    }
    let halves: Vec<String> = (design.failures.iter())
        .filter(|a| a.failed_in_half != [0, 0])
        .map(|a| {
            let [low, high] = a.failed_in_half;
            format!("{} {low} in its lower half, {high} in its upper", a.joint)
        })
        .collect();
    if !halves.is_empty() {
        writeln!(
            f,
            "  where the pieces failed: {} (each axis is narrowed from the end where more \
             failed)",
            halves.join("; ")
        )?;
    }
    for probe in &design.tried {
        writeln!(f, "  tried {}", probe.words())?;
    }
    Ok(())
}
