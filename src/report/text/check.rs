//! What `check` prints: the verdict of an installed cable over each motion.

use super::workshop::{life_words, write_allowed_ranges, write_motions};
use crate::mounting::rows;
use crate::solve::{BoxCheck, Check};
use crate::text_table::decimal;
use std::fmt;

impl fmt::Display for Check {
    /// `holds — …` or `fails — …`, the mounting in a line, then each motion's verdict and
    /// the motion that binds each piece.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut failing: Vec<&str> = (self.motions.iter())
            .filter(|m| m.motion_test.as_ref().is_some_and(|t| !t.passed))
            .map(|m| m.name.as_str())
            .collect();
        if self.over_box.as_ref().is_some_and(|b| !b.holds()) {
            failing.push("the box's static poses");
        }
        match failing.len() {
            0 => writeln!(
                f,
                "holds — the cable as mounted held every limit over {}",
                match (self.motions.len(), &self.over_box) {
                    (1, None) => "the motion".to_string(),
                    (n, None) => format!("all {n} motions"),
                    (n, Some(_)) => format!("all {n} motions and the box's static poses"),
                }
            )?,
            n => writeln!(
                f,
                "fails — {n} of {} motions {}: {}",
                self.motions.len(),
                if n == 1 { "fails" } else { "fail" },
                failing.join(", ")
            )?,
        }
        writeln!(
            f,
            "mounting checked: {} mm of cable, {}",
            decimal(self.length_mm, 0),
            rows::count_words(&self.mounting)
        )?;
        let limits = super::Limits {
            thresholds: self.thresholds,
            sub_segment_pitch_mm: self.sub_segment_pitch_mm,
        };
        write_motions(f, &limits, &self.motions, &self.binding, &self.mounting)?;
        if let Some(life) = &self.life {
            writeln!(f, "\n{}", life_words(life, Some(&self.mounting)))?;
        }
        if let Some(over_box) = &self.over_box {
            write_box(f, over_box)?;
        }
        if let Some(allowed) = &self.allowed_ranges {
            write_allowed_ranges(f, allowed, Some(&self.mounting))?;
        }
        Ok(())
    }
}

/// Each piece over the box's grid: how many poses, its least values, where it fails.
fn write_box(f: &mut fmt::Formatter<'_>, over_box: &BoxCheck) -> fmt::Result {
    writeln!(
        f,
        "\nover the box's static poses ({}° apart in the joints that shape each piece, solved \
         one by one):",
        over_box.step_deg
    )?;
    for piece in &over_box.pieces {
        let least = format!(
            "{} poses, least bend radius {} mm{}",
            piece.poses,
            decimal(piece.least_bend_radius_mm, 1),
            piece
                .least_clearance_mm
                .map(|c| format!(", least clearance {} mm", decimal(c, 1)))
                .unwrap_or_default()
        );
        match &piece.failure {
            None => writeln!(f, "  {}: holds — {least}", piece.segment)?,
            Some(failure) => {
                let at: Vec<String> = (failure.joints.iter())
                    .map(|(joint, v)| format!("{joint} {}", decimal(*v, 1)))
                    .collect();
                writeln!(
                    f,
                    "  {}: fails at {}: {} — {least}",
                    piece.segment,
                    at.join(", "),
                    failure.reason
                )?
            }
        }
    }
    Ok(())
}
