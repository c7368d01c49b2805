//! What `sites` prints: the candidates a setup's search will try, guide by guide and
//! segment by segment.

use crate::attachment::CostEstimate;
use crate::setup::{ConfigurationOrigin, Guide, GuideConfiguration, Setup};
use nalgebra::Vector3;
use std::fmt::Write as _;

/// What `sites` prints: the twist references, every guide with its sites (or, with `all`,
/// every configuration), the candidate pieces per segment and, when `estimate` is given,
/// what testing them all costs here.
pub fn catalogue_listing(setup: &Setup, all: bool, estimate: Option<&CostEstimate>) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "setup {}", setup.source.display());
    match &setup.installation {
        Some(installation) => {
            let joints: Vec<String> = installation
                .joints
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let (scale, unit) = setup.robot.actuated_joint(i).kind.display_unit();
                    format!("{:.1} {unit}", v * scale)
                })
                .collect();
            let _ = writeln!(
                out,
                "cable installed untwisted at [{}]: clamp twist references derived from the route",
                joints.join(", ")
            );
        }
        None => {
            let _ = writeln!(
                out,
                "clamp twist references: the configurations' written +x axes"
            );
        }
    }
    for guide in &setup.guides {
        guide_listing(&mut out, setup, guide, all);
    }
    let _ = writeln!(
        out,
        "\ncandidate pieces (length × start × end configuration)"
    );
    match crate::attachment::check_size(setup) {
        Err(too_many) => {
            let _ = writeln!(out, "  too many for solve and build: {too_many}");
        }
        Ok(()) => {
            let total: u128 = (0..setup.segment_count())
                .map(|m| setup.pv_count(m) as u128)
                .sum();
            let _ = writeln!(
                out,
                "  {total} in all, spans included (solve and build take up to {})",
                crate::attachment::MAX_CANDIDATE_PIECES
            );
        }
    }
    for m in 0..setup.segment_count() {
        let (a, b) = setup.segment_guides(m);
        let _ = writeln!(
            out,
            "  {:<6} {}→{}  {} lengths × {} × {} = {} ({} describe a real cable)",
            setup.segment_name(m),
            setup.guides[a].name,
            setup.guides[b].name,
            setup.segments[m].lengths.len(),
            setup.guides[a].configurations.len(),
            setup.guides[b].configurations.len(),
            setup.pv_count(m),
            setup.admissible_pv_count(m),
        );
    }
    if let Some(estimate) = estimate {
        let _ = write!(
            out,
            "\ntesting every candidate piece at one pose (the installation pose) takes {}; \
             `solve` tests only the pieces a chain shorter than the answer can use, and each \
             motion has its own test poses\n",
            estimate.describe(rayon::current_num_threads())
        );
    }
    out
}

fn guide_listing(out: &mut String, setup: &Setup, guide: &Guide, all: bool) {
    let link = &setup.robot.links[guide.link].name;
    let own = |c: &&GuideConfiguration| !matches!(c.origin, ConfigurationOrigin::Coincident { .. });
    let copies = guide.configurations.len() - guide.configurations.iter().filter(own).count();
    let sites = site_count(guide);
    let _ = writeln!(
        out,
        "\n{}{} on {link}: {} configuration{}{}{}",
        guide.name,
        if guide.optional {
            " (optional: the search may leave it out)"
        } else {
            ""
        },
        guide.configurations.len(),
        if guide.configurations.len() == 1 {
            ""
        } else {
            "s"
        },
        match sites {
            0 => String::new(),
            n => format!(" at {n} generated sites"),
        },
        match copies {
            0 => String::new(),
            n => format!(" ({n} shared with the neighbouring guide: one clamp for both)"),
        },
    );
    let mut last_site = None;
    for c in guide.configurations.iter().filter(own) {
        let site = match c.origin {
            ConfigurationOrigin::Generated { site, .. } => Some(site),
            _ => None,
        };
        if !all && site.is_some() && site == last_site {
            continue;
        }
        last_site = site;
        let normal = c.pose.rotation * Vector3::x();
        let along = c.pose.rotation * Vector3::z();
        let p = c.position_mm;
        let _ = match (site, all) {
            (Some(k), false) => writeln!(
                out,
                "  {:<10} at ({:7.1}, {:7.1}, {:7.1}) mm, surface normal ({:5.2}, {:5.2}, {:5.2})",
                format!("site {}", k + 1),
                p[0],
                p[1],
                p[2],
                normal.x,
                normal.y,
                normal.z
            ),
            _ => writeln!(
                out,
                "  {:<34} at ({:7.1}, {:7.1}, {:7.1}) mm, cable along ({:5.2}, {:5.2}, {:5.2})",
                c.name, p[0], p[1], p[2], along.x, along.y, along.z
            ),
        };
    }
}

/// Number of distinct generated sites of a guide.
fn site_count(guide: &Guide) -> usize {
    let mut sites: Vec<usize> = guide
        .configurations
        .iter()
        .filter_map(|c| match c.origin {
            ConfigurationOrigin::Generated { site, .. } => Some(site),
            _ => None,
        })
        .collect();
    sites.dedup();
    sites.len()
}
