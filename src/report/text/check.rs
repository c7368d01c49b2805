//! What `check` prints: the verdict of an installed cable over each motion.

use super::workshop::write_motions;
use crate::mounting::rows;
use crate::solve::Check;
use crate::text_table::decimal;
use std::fmt;

impl fmt::Display for Check {
    /// `holds — …` or `fails — …`, the mounting in a line, then each motion's verdict and
    /// the motion that binds each piece.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let failing: Vec<&str> = (self.motions.iter())
            .filter(|m| m.motion_test.as_ref().is_some_and(|t| !t.passed))
            .map(|m| m.name.as_str())
            .collect();
        match failing.len() {
            0 => writeln!(
                f,
                "holds — the cable as mounted held every limit over {}",
                match self.motions.len() {
                    1 => "the motion".to_string(),
                    n => format!("all {n} motions"),
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
        write_motions(f, &limits, &self.motions, &self.binding, &self.mounting)
    }
}
