//! Building a dictionary (or one shard of it): every PV of every intra-link segment, under
//! every sampled gravity direction in the segment's link frame, through the same static test
//! as the attachment test ([`Evaluator::check_in_link_frame`]).
//!
//! Work is spread over PVs with rayon and collected in PV order, so the bytes do not depend
//! on the thread count. A failed solve is stored as such (verdict `Diverged`); it never stops
//! the build.

use super::directions::{MIN_DIRECTION_COUNT, covering_radius, fibonacci_sphere};
use super::error::Problem;
use super::format::{
    DirectionParameters, EmbeddedSetup, Header, PHYSICS_VERSION, PvRecord, ResultRecord,
    SegmentEntry, ShardRange, SolverParameters, Verdict, encode,
};
use crate::attachment::{Check, ConnectMethod, Evaluator, needed_pvs, robust_neighbours};
use crate::path::Pv;
use crate::progress;
use crate::robot::Shape;
use crate::setup::{Robustness, Setup};
use crate::statics::SolverOptions;
use rayon::prelude::*;
use std::collections::BTreeSet;

/// What to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuildOptions {
    /// Gravity directions N.
    pub directions: usize,
    /// `Some((i, n))`: only shard `i` (0-based) of `n`.
    pub shard: Option<(u32, u32)>,
}

/// A dictionary or shard in memory, ready to be encoded.
#[derive(Debug, Clone, PartialEq)]
pub struct Built {
    /// The header.
    pub header: Header,
    /// The sampled directions.
    pub directions: Vec<[f64; 3]>,
    /// The PV records this file holds.
    pub pvs: Vec<PvRecord>,
    /// The results, `directions.len()` per PV record.
    pub results: Vec<ResultRecord>,
}

impl Built {
    /// The file's bytes.
    pub fn to_bytes(&self) -> Result<Vec<u8>, Problem> {
        encode(&self.header, &self.directions, &self.pvs, &self.results)
    }
}

/// Builds the dictionary of `setup`'s intra-link segments (or one shard of it).
pub fn build(setup: &Setup, options: &BuildOptions) -> Result<Built, Problem> {
    check_buildable(setup, options)?;
    let directions = fibonacci_sphere(options.directions);
    let mut header = header(setup, &directions)?;
    let stored = match options.shard {
        Some((index, count)) => {
            let shard = ShardRange::new(index, count, header.pv_total);
            header.shard = Some(shard);
            shard.first_pv..shard.end_pv
        }
        None => 0..header.pv_total,
    };
    let pvs: Vec<PvRecord> = stored.map(|g| pv_record(setup, &header, g)).collect();
    let evaluator =
        Evaluator::new(setup, ConnectMethod::Hermite).map_err(|e| Problem::Build(e.to_string()))?;
    let gravity = header.directions.gravity_m_s2;
    progress::begin("dictionary build", pvs.len() as u64);
    let results: Vec<ResultRecord> = pvs
        .par_iter()
        .map(|record| {
            let rows = evaluate_pv(&evaluator, record, &directions, gravity);
            progress::advance(1);
            rows
        })
        .collect::<Vec<_>>()
        .concat();
    progress::end();
    log::info!("built {} PVs × {} directions", pvs.len(), directions.len());
    let mut built = Built {
        header,
        directions,
        pvs,
        results,
    };
    if built.header.shard.is_none() {
        finalize(&mut built, &setup.robustness);
    }
    Ok(built)
}

/// Refuses what a dictionary cannot represent.
fn check_buildable(setup: &Setup, options: &BuildOptions) -> Result<(), Problem> {
    if options.directions < MIN_DIRECTION_COUNT || options.directions > u32::MAX as usize {
        return Err(Problem::Build(format!(
            "--directions must be at least {MIN_DIRECTION_COUNT}, got {}",
            options.directions
        )));
    }
    if let Some((index, count)) = options.shard
        && (count == 0 || index >= count)
    {
        return Err(Problem::Build(format!(
            "--shard {index}/{count}: the index must be 0 … count − 1 and the count at least 1"
        )));
    }
    let widest = setup.guides.iter().map(|g| g.configurations.len()).max();
    if widest.unwrap_or(0) > usize::from(u16::MAX) || setup.segment_count() > usize::from(u16::MAX)
    {
        return Err(Problem::Build(format!(
            "a PV record holds configuration and segment indices below {}",
            u16::MAX
        )));
    }
    crate::attachment::check_size(setup).map_err(Problem::Build)?;
    if setup.gravity_m_s2.norm() == 0.0 {
        return Err(Problem::Build(
            "the setup has no gravity, so there is no direction to sample; use solve --setup"
                .into(),
        ));
    }
    if !(0..setup.segment_count()).any(|m| setup.is_intra_link(m)) {
        return Err(Problem::Build(
            "the setup has no intra-link segment (two guides on one link): nothing to store".into(),
        ));
    }
    let meshes = setup.robot.links.iter().flat_map(|l| &l.colliders);
    if meshes
        .into_iter()
        .any(|c| matches!(c.shape, Shape::Mesh(_)))
    {
        return Err(Problem::Build(
            "the robot has mesh colliders; a dictionary embeds the URDF text but not mesh \
             files, so it would not be self-contained (not supported yet)"
                .into(),
        ));
    }
    Ok(())
}

/// The header of a whole dictionary of `setup` (no shard).
fn header(setup: &Setup, directions: &[[f64; 3]]) -> Result<Header, Problem> {
    let file_name = setup
        .source
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut segments = Vec::new();
    let mut first_pv = 0;
    for m in (0..setup.segment_count()).filter(|&m| setup.is_intra_link(m)) {
        let (a, b) = setup.segment_guides(m);
        let entry = SegmentEntry {
            segment: m as u32,
            link: setup.robot.links[setup.guides[a].link].name.clone(),
            lengths: stored_lengths(setup, m),
            start_configurations: setup.guides[a].configurations.len() as u32,
            end_configurations: setup.guides[b].configurations.len() as u32,
            first_pv,
            d1_all: 0,
            d2_all: 0,
        };
        first_pv += entry.pv_count();
        segments.push(entry);
    }
    let solver = SolverOptions::STRESS_CHECK;
    Ok(Header {
        physics_version: PHYSICS_VERSION,
        setup: EmbeddedSetup {
            file_name,
            text: setup.text.clone(),
            robot_text: setup.robot_text.clone(),
            cable_text: setup.cable_text.clone(),
        },
        setup_hash: setup.content_hash,
        solver: SolverParameters {
            connect: "hermite".into(),
            force_tolerance_n: solver.force_tolerance_n,
            max_iterations: solver.max_iterations as u32,
            clearance_links: "own link".into(),
        },
        directions: DirectionParameters {
            method: "fibonacci".into(),
            count: directions.len() as u32,
            covering_radius_rad: covering_radius(directions),
            gravity_m_s2: setup.gravity_m_s2.norm(),
        },
        segments,
        pv_total: first_pv,
        shard: None,
    })
}

/// The setup's candidate lengths of segment `m` and their robustness neighbours, ascending:
/// the lengths the attachment test evaluates ([`needed_pvs`]).
fn stored_lengths(setup: &Setup, m: usize) -> Vec<u32> {
    let robustness = &setup.robustness;
    let candidates: Vec<Pv> = setup.segments[m]
        .lengths
        .iter()
        .map(|&s| Pv::new(s, 0, 0))
        .collect();
    let needed = needed_pvs(&candidates, robustness.delta_s, robustness.range);
    let lengths: BTreeSet<u32> = needed.iter().map(|pv| pv.sub_segments as u32).collect();
    lengths.into_iter().collect()
}

/// The record of global PV `g` (flags: admissible, candidate).
fn pv_record(setup: &Setup, header: &Header, g: u64) -> PvRecord {
    let (slot, pv) = pv_at(header, g);
    let entry = &header.segments[slot];
    let m = entry.segment as usize;
    let admissible = setup.is_admissible(m, pv.sub_segments, pv.start, pv.end);
    let candidate = admissible && setup.segments[m].lengths.contains(&pv.sub_segments);
    PvRecord {
        sub_segments: pv.sub_segments as u32,
        start: pv.start as u16,
        end: pv.end as u16,
        segment: entry.segment as u16,
        flags: if admissible { PvRecord::ADMISSIBLE } else { 0 }
            | if candidate { PvRecord::CANDIDATE } else { 0 },
        reserved: 0,
    }
}

/// The segment (its position in the header) and PV of global index `g`, which must be below
/// `header.pv_total` of a header [`parse`](super::format::parse) accepted.
pub(super) fn pv_at(header: &Header, g: u64) -> (usize, Pv) {
    let position = header.segments.partition_point(|e| e.first_pv <= g);
    let slot = position.saturating_sub(1);
    let entry = &header.segments[slot];
    let local = (g - entry.first_pv) as usize;
    let (na, nb) = (
        entry.start_configurations as usize,
        entry.end_configurations as usize,
    );
    let pv = Pv::new(
        entry.lengths[local / (na * nb)] as usize,
        local / nb % na,
        local % nb,
    );
    (slot, pv)
}

/// The results of one PV under every direction.
fn evaluate_pv(
    evaluator: &Evaluator<'_>,
    record: &PvRecord,
    directions: &[[f64; 3]],
    gravity_m_s2: f64,
) -> Vec<ResultRecord> {
    if !record.has(PvRecord::ADMISSIBLE) {
        return vec![result(Verdict::NotEvaluated, None); directions.len()];
    }
    let pv = record.pv();
    directions
        .iter()
        .map(|d| {
            let gravity = nalgebra::Vector3::from(*d) * gravity_m_s2;
            let check = evaluator.check_in_link_frame(record.segment as usize, &pv, &gravity);
            from_check(&check)
        })
        .collect()
}

fn from_check(check: &Check) -> ResultRecord {
    result(
        Verdict::from_rejection(check.rejection),
        check.metrics.as_ref(),
    )
}

fn result(verdict: Verdict, metrics: Option<&crate::attachment::Metrics>) -> ResultRecord {
    let nan = f32::NAN;
    ResultRecord {
        clearance_mm: metrics
            .and_then(|m| m.clearance_m)
            .map_or(nan, |c| (c * 1e3) as f32),
        stretch: metrics.map_or(nan, |m| m.stretch as f32),
        min_bend_radius_mm: metrics.map_or(nan, |m| (m.min_bend_radius_m * 1e3) as f32),
        verdict: verdict as u8,
        reserved: [0; 3],
    }
}

/// Sets the all-directions D1/D2 flags and counts of a whole dictionary: D1 = candidates that
/// pass every direction; D2 = those whose robustness neighbours (candidates or not) do too.
pub(super) fn finalize(built: &mut Built, robustness: &Robustness) {
    let n = built.directions.len();
    let passes_all: Vec<bool> = built
        .results
        .chunks_exact(n.max(1))
        .map(|rows| rows.iter().all(|r| r.verdict == Verdict::Pass as u8))
        .collect();
    let header = &mut built.header;
    for entry in &mut header.segments {
        let block = entry.first_pv as usize..(entry.first_pv + entry.pv_count()) as usize;
        let passes = |pv: &Pv| {
            entry
                .grid_index(pv.sub_segments, pv.start, pv.end)
                .is_some_and(|i| passes_all[entry.first_pv as usize + i as usize])
        };
        let (mut d1, mut d2) = (0, 0);
        for g in block {
            let record = &mut built.pvs[g];
            if !(record.has(PvRecord::CANDIDATE) && passes_all[g]) {
                continue;
            }
            record.flags |= PvRecord::D1_ALL;
            d1 += 1;
            let robust = robust_neighbours(&record.pv(), robustness.delta_s, robustness.range);
            if robust.is_some_and(|n| n.iter().all(passes)) {
                record.flags |= PvRecord::D2_ALL;
                d2 += 1;
            }
        }
        entry.d1_all = d1;
        entry.d2_all = d2;
    }
}
