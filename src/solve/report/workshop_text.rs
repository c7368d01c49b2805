//! The summary `solve` prints by default, for the people who mount the cable: the physical
//! clamps with their places and cable marks, the pieces between them, the installation pose,
//! the length tolerance, what the design leaves out and the worst values over the motion.
//! No search vocabulary: that is `solve -v` ([`SolveReport`]'s `{:#}`) and the JSON.

use super::data::SolveReport;
use crate::motion_test::{MotionTestReport, Worst};
use crate::mounting::{MountingPlan, PhysicalClamp};
use crate::text_table::{decimal, decimals};
use std::fmt;

/// Writes the summary of `report`.
pub(super) fn write_summary(report: &SolveReport, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    let i = &report.inputs;
    writeln!(f, "{} — {}", report.status.describe(), report.explanation)?;
    writeln!(
        f,
        "robot setup {}, cable {}, motion {}{:.2} s",
        i.setup_file,
        i.cable,
        i.motion_file
            .as_deref()
            .map(|m| format!("{m}, "))
            .unwrap_or_default(),
        i.motion_duration_s,
    )?;
    if let Some(dictionary) = &i.dictionary {
        super::text::write_dictionary(f, dictionary)?;
    }
    if let Some(plan) = &report.mounting {
        write_clamps(f, plan)?;
        write_pieces(f, plan)?;
        write_installation(f, plan)?;
    }
    if let (Some(test), Some(plan)) = (&report.motion_test, &report.mounting) {
        write_worst(f, report, test, plan)?;
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

fn write_clamps(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    let mounted = plan.clamps.iter().filter(|c| c.fitting.is_none()).count();
    writeln!(
        f,
        "\nclamps to mount: {mounted}; mark on the cable = length from its end at {}",
        plan.clamps.last().map(end_name).unwrap_or_default()
    )?;
    for clamp in &plan.clamps {
        writeln!(
            f,
            "  {:<28} on {:<10} mark {:>5} mm{}",
            clamp.label(),
            clamp.link,
            decimal(clamp.mark_mm, 0),
            role_note(clamp)
        )?;
        match &clamp.place {
            Some(place) => writeln!(f, "      {}", place.describe())?,
            None => {
                let xyz = decimals(&clamp.xyz_mm, 1);
                writeln!(
                    f,
                    "      on the robot's base link, at ({xyz}) mm in its frame"
                )?
            }
        }
    }
    Ok(())
}

/// `the gripper connector` for a fitting, else the clamp's label.
fn end_name(clamp: &PhysicalClamp) -> String {
    match &clamp.fitting {
        Some(fitting) => format!("the {fitting} ({})", clamp.guides.join(" = ")),
        None => clamp.label(),
    }
}

fn role_note(clamp: &PhysicalClamp) -> &'static str {
    match (clamp.role, clamp.fitting.is_some()) {
        ("start", _) => "  (first clamp: the cable before it is outside this design)",
        ("end", true) => "  (the cable's end: a fixed fitting, not a clamp to place)",
        ("end", false) => "  (last clamp: the cable beyond it is outside this design)",
        _ => "",
    }
}

fn write_pieces(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    writeln!(
        f,
        "\ncable between the clamps: {} mm; {}",
        decimal(plan.length_mm, 0),
        plan.tolerance_words()
    )?;
    if let Some(cut) = &plan.cut {
        writeln!(f, "  {}", cut.describe())?;
    }
    for piece in &plan.pieces {
        let (from, to) = (
            &plan.clamps[piece.from_clamp],
            &plan.clamps[piece.from_clamp + 1],
        );
        let across = if piece.across_joints.is_empty() {
            "on one link".to_string()
        } else {
            format!("across {}", piece.across_joints.join(", "))
        };
        writeln!(
            f,
            "  {:<28} {:>5} mm  {across}",
            format!("{} → {}", from.guides.join(" = "), to.guides.join(" = ")),
            decimal(piece.length_mm, 0)
        )?;
    }
    Ok(())
}

fn write_installation(f: &mut fmt::Formatter<'_>, plan: &MountingPlan) -> fmt::Result {
    writeln!(f, "\n{}", plan.installation_words())
}

/// The worst value of each limit over the motion test, against its limit.
fn write_worst(
    f: &mut fmt::Formatter<'_>,
    report: &SolveReport,
    test: &MotionTestReport,
    plan: &MountingPlan,
) -> fmt::Result {
    let verdict = match &test.failure {
        None => "held every limit".to_string(),
        Some(failure) => format!("failed: {}", failure.reason),
    };
    writeln!(f, "\nover the motion (simulated): {verdict}")?;
    let t = &report.thresholds;
    let rows: [(&str, &Option<Worst>, String); 4] = [
        (
            "closest to the robot",
            &test.worst_clearance,
            format!("limit {} mm", decimal(t.contact_clearance_m * 1e3, 1)),
        ),
        (
            "closest to itself",
            &test.worst_self_clearance,
            "limit 0.0 mm".to_string(),
        ),
        (
            "tightest bend radius",
            &test.worst_bend,
            format!("limit {} mm", decimal(t.min_bend_radius_m * 1e3, 1)),
        ),
        (
            "most stretched",
            &test.worst_stretch,
            format!("limit {}", t.stretch),
        ),
    ];
    for (what, worst, limit) in rows {
        if let Some(w) = worst {
            let value = match w.unit {
                "m" => format!("{} mm", decimal(w.value * 1e3, 1)),
                _ => decimal(w.value, 4),
            };
            writeln!(
                f,
                "  {what:<21} {value:>9} ({limit}) at t = {:.2} s, {}",
                w.time_s,
                where_on_cable(report, plan, w)
            )?;
        }
    }
    Ok(())
}

/// `between G2 = G3 and G4, 25 mm from G2 = G3, near link_4`: the place of a worst value
/// on the mounted cable.
fn where_on_cable(report: &SolveReport, plan: &MountingPlan, w: &Worst) -> String {
    let pitch_mm = report.sub_segment_pitch_mm;
    let segment = report
        .optimal
        .as_ref()
        .and_then(|p| p.segments.iter().find(|s| s.name == w.segment_name));
    let clamp_of = |guide: &str| {
        plan.clamps
            .iter()
            .find(|c| c.guides.iter().any(|g| g == guide))
            .map(|c| c.guides.join(" = "))
            .unwrap_or_else(|| guide.to_string())
    };
    let mut words = match segment {
        Some(s) => format!(
            "between {} and {}",
            clamp_of(&s.from_guide),
            clamp_of(&s.to_guide)
        ),
        None => format!("on {}", w.segment_name),
    };
    let along = w
        .place
        .sub_segment
        .map(|k| (k as f64 + 0.5) * pitch_mm)
        .or(w.place.node.map(|n| n as f64 * pitch_mm));
    if let (Some(along), Some(s)) = (along, segment) {
        words.push_str(&format!(
            ", {} mm from {}",
            decimal(along, 0),
            clamp_of(&s.from_guide)
        ));
    }
    if let Some(link) = &w.place.link {
        words.push_str(&format!(", near {link}"));
    }
    words
}
