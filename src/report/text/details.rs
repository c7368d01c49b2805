//! The detailed summary `solve -v` prints: the search's counts, margins, sweep, motion test
//! and timings in its own words.

use crate::solve::*;
use std::fmt;

impl SolveReport {
    /// The search's details (`solve -v`).
    pub(super) fn write_details(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.inputs;
        writeln!(f, "{} — {}", self.status.describe(), self.explanation)?;
        writeln!(
            f,
            "setup {} (hash {}), cable {}, {}, {}, {} samples",
            i.setup_file,
            i.setup_hash,
            i.cable,
            i.method,
            super::motion_words(self),
            i.motion_samples
        )?;
        if let Some(d) = &i.dictionary {
            write_dictionary(f, d)?;
        }
        if let Some(design) = &self.ranges {
            super::ranges::write_ranges(f, design)?;
        }
        if let (Some(path), Some(total)) = (&self.optimal, self.optimal_length_mm) {
            writeln!(f, "\ncable path — total {total:.0} mm")?;
            write_path(f, path)?;
        }
        write_sets(f, &self.segments, &self.chains)?;
        write_margins(f, &self.margins)?;
        let sweep = &self.static_sweep;
        if sweep.poses > 0 {
            let per_segment = dropped_per_segment(sweep);
            let per_segment = if per_segment.is_empty() {
                per_segment
            } else {
                format!(" ({per_segment})")
            };
            writeln!(
                f,
                "\nstatic sweep: {} cable pieces solved at {} motion poses, {} dropped{per_segment}",
                sweep.pvs_swept,
                sweep.poses,
                sweep.rejected.len(),
            )?;
        }
        if let Some(report) = &self.motion_test {
            writeln!(
                f,
                "\nmotion test ({} engine): {}",
                self.motion_engine,
                report.summary()
            )?;
        }
        if self.candidates.len() > 1 {
            writeln!(f, "\nchains tried in the motion test")?;
            for c in &self.candidates {
                let outcome = match (c.passed, &c.failure) {
                    (Some(true), _) => "passed".to_string(),
                    (_, Some(failure)) => failure.clone(),
                    (None, None) => "not tested".to_string(),
                    (Some(false), None) => "failed".to_string(),
                };
                writeln!(f, "  #{} ({:.0} mm): {outcome}", c.rank, c.total_length_mm)?;
            }
        }
        if let Some(diagnosis) = &self.diagnosis {
            writeln!(f, "\nwhy there is no path")?;
            for line in diagnosis.to_string().lines() {
                writeln!(f, "  {line}")?;
            }
        }
        let t = &self.timings;
        writeln!(
            f,
            "\ntimings: critical poses {:.3} s, attachment {:.2} s, chain search {:.3} s, static sweep {:.2} s, motion test {:.2} s, total {:.2} s",
            t.critical_poses_s,
            t.attachment_s,
            t.chain_s,
            t.static_sweep_s,
            t.motion_test_s,
            t.total_s
        )
    }
}

fn write_path(f: &mut fmt::Formatter<'_>, path: &NamedPath) -> fmt::Result {
    use crate::text_table::{Align, TextTable, decimals};
    let triple = |v: [f64; 3]| format!("({})", decimals(&v, 1));
    let mut pieces = TextTable::new(
        2,
        &[
            ("piece", Align::Left),
            ("clamps", Align::Left),
            ("links", Align::Left),
            ("kind", Align::Left),
            ("length", Align::Right),
        ],
    );
    for s in &path.segments {
        pieces.row(vec![
            s.name.clone(),
            format!("{}→{}", s.from_guide, s.to_guide),
            format!("{}→{}", s.from_link, s.to_link),
            s.kind.to_string(),
            format!("{:.0} mm", s.length_mm),
        ]);
    }
    let mut clamps = TextTable::new(
        2,
        &[
            ("clamp", Align::Left),
            ("link", Align::Left),
            ("placement", Align::Left),
            ("xyz (mm)", Align::Right),
            ("rpy (deg)", Align::Right),
        ],
    );
    for g in &path.guides {
        clamps.row(vec![
            g.name.clone(),
            g.link.clone(),
            g.configuration.clone(),
            triple(g.xyz_mm),
            triple(g.rpy_deg),
        ]);
    }
    write!(f, "{pieces}{clamps}")?;
    if !path.left_out.is_empty() {
        writeln!(f, "  left out (optional): {}", path.left_out.join(", "))?;
    }
    Ok(())
}

fn write_sets(f: &mut fmt::Formatter<'_>, segments: &[SegmentReport], chains: &str) -> fmt::Result {
    writeln!(
        f,
        "\ncable pieces  {:>10} {:>13} {:>11} {:>10}  rejected (first limit violated)",
        "candidates", "after pruning", "hold limits", "robust"
    )?;
    for s in segments {
        let rejected: Vec<String> = s
            .rejections
            .iter()
            .map(|(r, n)| format!("{} {n}", r.name()))
            .collect();
        writeln!(
            f,
            "  {:<11} {:>10} {:>13} {:>11} {:>10}  {}",
            s.segment,
            s.d0,
            s.d0_pruned,
            s.d1,
            s.d2,
            rejected.join(", ")
        )?;
    }
    writeln!(
        f,
        "  (after pruning: pieces whose clamp placements a neighbouring piece can share; \
         robust: holds the limits at every test pose also with the tolerated length errors)"
    )?;
    writeln!(f, "  chains of robust pieces through the clamps: {chains}")
}

fn write_margins(f: &mut fmt::Formatter<'_>, margins: &[Margin]) -> fmt::Result {
    if margins.is_empty() {
        return Ok(());
    }
    writeln!(f, "\nstatic margins at the binding test pose")?;
    for m in margins {
        // A stretch ratio to 1e-4, lengths to 0.1 mm.
        let (scale, digits, unit) = match m.constraint {
            "stretch" => (1.0, 4, ""),
            _ => (1e3, 1, " mm"),
        };
        let (value, threshold, margin) = (m.value * scale, m.threshold * scale, m.margin * scale);
        writeln!(
            f,
            "  {:<4} {:<12} {value:>8.digits$}{unit} (limit {threshold}{unit}, margin \
             {margin:+.digits$}{unit}) at t = {:.2} s ({})",
            m.segment,
            m.constraint.replace('_', " "),
            m.time_s,
            m.reason
        )?;
    }
    Ok(())
}

/// Where the intra-link pieces came from: the dictionary, what its lookups decided, the exact
/// checks of the pieces the answer took from it (and every record they contradicted), and
/// who signed it.
pub(super) fn write_dictionary(f: &mut fmt::Formatter<'_>, d: &DictionaryUse) -> fmt::Result {
    writeln!(
        f,
        "intra-link pieces from dictionary {} ({} stored gravity directions, at most \
             {:.1}° from any direction)",
        d.file, d.directions, d.covering_radius_deg,
    )?;
    for s in &d.segments {
        let p = &s.pieces;
        writeln!(
            f,
            "  {}: {} gravity directions of the motion; {} pieces hold by the stored \
                 margins, {} were solved — those the file rejects or finds too close to a \
                 limit — ({} of them failed)",
            s.segment, s.gravity_directions, p.holds, p.solved, p.solved_failed
        )?;
    }
    let c = &d.certification;
    match (c.pieces_solved, c.disagreements.len()) {
        (0, _) => writeln!(f, "  certified: the chains offered took no stored piece")?,
        (n, k) => writeln!(
            f,
            "  certified: the stored pieces the chains offered and their robustness \
                 neighbours solved exactly ({n} pieces); {}",
            match k {
                0 => "the file agrees".to_string(),
                1 => "1 record contradicted".to_string(),
                k => format!("{k} records contradicted"),
            }
        )?,
    }
    for disagreement in &c.disagreements {
        writeln!(f, "  {}", disagreement.describe(&d.file))?;
    }
    if let Some(provenance) = &d.provenance {
        writeln!(f, "  {}", provenance.describe())?;
    }
    Ok(())
}
