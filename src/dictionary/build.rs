//! Building a dictionary (or one shard of it): the three margins of every cable piece between
//! two clamps of one link's catalogue ([`link_catalogues`]: every link with two or more clamp
//! places among the setup's guides) under every sampled gravity direction in the link's
//! frame, through the same static test as the attachment test
//! ([`Evaluator::link_frame_metrics`]: a pair of clamps' lengths solved by continuation,
//! exactly as `solve --setup` does at one pose), then the same at probe directions between
//! the stored ones, where the interpolation error is measured and stored per piece.
//!
//! The lengths are the same for every link: the candidate lengths of the setup's intra-link
//! segments (all of them together) and their robustness neighbours.
//!
//! Work is spread over pairs of clamp configurations with rayon and collected in PV order,
//! so the bytes do not depend on the thread count. A failed solve is stored as unmeasured;
//! it never stops the build.

use super::catalogue::{LinkCatalogue, link_catalogues};
use super::directions::{
    Interpolated, MAX_DIRECTION_COUNT, MIN_DIRECTION_COUNT, Neighbours, covering_radius,
    fibonacci_sphere, probe_directions,
};
use super::error::Problem;
use super::format::{
    ClampEntry, DirectionParameters, ERROR_SAFETY, EmbeddedSetup, HEADER_LIMIT, Header, LinkEntry,
    MARGIN_UNITS, MarginRecord, PHYSICS_VERSION, PvRecord, ShardRange, SolverParameters, encode,
};
use crate::attachment::{
    ConnectMethod, Evaluator, Margins, Rejection, needed_pvs, robust_neighbours,
};
use crate::path::Pv;
use crate::progress;
use crate::setup::{Robustness, Setup};
use crate::statics::SolverOptions;
use nalgebra::Vector3;
use rayon::prelude::*;
use std::collections::BTreeSet;
use std::ops::Range;

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
    /// The margins, `directions.len()` per PV record.
    pub results: Vec<MarginRecord>,
}

impl Built {
    /// The file's bytes.
    pub fn to_bytes(&self) -> Result<Vec<u8>, Problem> {
        encode(&self.header, &self.directions, &self.pvs, &self.results)
    }

    /// Sets the D1/D2 flags and the header's counts from the margins as they are now, as a
    /// build does after its last margin: for a whole dictionary whose margins were changed.
    pub fn derive_flags(&mut self, robustness: &Robustness) {
        finalize(self, robustness);
    }
}

/// Builds the dictionary of `setup`'s clamp catalogue (or one shard of it).
pub fn build(setup: &Setup, options: &BuildOptions) -> Result<Built, Problem> {
    check_buildable(setup, options)?;
    let (stored_lengths, candidate_lengths) = catalogue_lengths(setup);
    let catalogues = link_catalogues(setup, &candidate_lengths);
    check_catalogues(&catalogues, stored_lengths.len(), options.directions)?;
    let directions = fibonacci_sphere(options.directions);
    let probes = probe_directions(probe_count(options.directions));
    let mut header = header(
        setup,
        &catalogues,
        &stored_lengths,
        &directions,
        probes.len(),
    );
    let stored = match options.shard {
        Some((index, count)) => {
            let shard = ShardRange::new(index, count, header.pv_total);
            header.shard = Some(shard);
            shard.first_pv..shard.end_pv
        }
        None => 0..header.pv_total,
    };
    let mut pvs: Vec<PvRecord> = stored
        .clone()
        .map(|g| pv_record(&catalogues, &header, g))
        .collect();
    let evaluators = catalogues
        .iter()
        .map(|c| Evaluator::new(&c.setup, ConnectMethod::Hermite))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| Problem::Build(e.to_string()))?;
    let sample = DirectionSample::new(directions, probes);
    let pairs = pairs_in(&header, &stored);
    progress::begin("dictionary build", pairs.len() as u64);
    let solved: Vec<SolvedPair> = pairs
        .par_iter()
        .map(|pair| {
            let evaluator = &evaluators[pair.slot];
            let solved = solve_pair(evaluator, &header, pair, &stored, &sample);
            progress::advance(1);
            solved
        })
        .collect();
    progress::end();
    let n = sample.stored.len();
    let mut results = vec![MarginRecord::UNMEASURED; pvs.len() * n];
    for solved in &solved {
        let entry = &mut header.links[solved.pair.slot];
        for (g, piece) in &solved.pieces {
            let k = (g - stored.start) as usize;
            match &piece.rows {
                Some(rows) => results[k * n..(k + 1) * n].copy_from_slice(rows),
                None => pvs[k].flags |= PvRecord::TOO_SHORT,
            }
            pvs[k].error_factor = piece.error_factor;
            for (worst, factor) in entry.margin_error.iter_mut().zip(pvs[k].error_factors()) {
                *worst = worst.max(factor);
            }
        }
    }
    log::info!("built {} PVs × {n} directions", pvs.len());
    let mut built = Built {
        header,
        directions: sample.stored,
        pvs,
        results,
    };
    if built.header.shard.is_none() {
        finalize(&mut built, &setup.robustness);
    }
    Ok(built)
}

/// Probe directions for `n` stored ones: a quarter as many (at least 8), so that measuring
/// the interpolation error costs a quarter of the build.
pub(super) fn probe_count(n: usize) -> usize {
    (n / 4).max(8)
}

/// The stored directions, the probes, each probe's interpolation neighbours, and each stored
/// direction's neighbours among the others (leave-one-out).
pub(super) struct DirectionSample {
    stored: Vec<[f64; 3]>,
    probes: Vec<[f64; 3]>,
    probe_neighbours: Vec<Neighbours>,
    left_out_neighbours: Vec<Neighbours>,
}

impl DirectionSample {
    pub(super) fn new(stored: Vec<[f64; 3]>, probes: Vec<[f64; 3]>) -> DirectionSample {
        let probe_neighbours = probes
            .iter()
            .map(|p| Neighbours::of(&stored, &Vector3::from(*p)))
            .collect();
        let left_out_neighbours = (0..stored.len())
            .map(|k| Neighbours::excluding(&stored, &Vector3::from(stored[k]), Some(k)))
            .collect();
        DirectionSample {
            stored,
            probes,
            probe_neighbours,
            left_out_neighbours,
        }
    }
}

/// The largest sign-flipping interpolation error per unit of neighbour spread, per margin.
#[derive(Default)]
struct ErrorRatio([f64; 3]);

impl ErrorRatio {
    /// Adds the comparison of `interpolated` with the `exact` margins (clamped to the stored
    /// range): only an error that flips a margin's sign can flip a verdict.
    fn add(&mut self, interpolated: &Interpolated, exact: &[f64; 3]) {
        for k in 0..3 {
            let range = f64::from(i16::MAX) * MARGIN_UNITS[k];
            let exact = exact[k].clamp(-range, range);
            let mean = interpolated.mean[k];
            if (mean < 0.0) != (exact < 0.0) {
                let excess = (mean - exact).abs() - MARGIN_UNITS[k];
                let spread = interpolated.spread[k].max(MARGIN_UNITS[k]);
                self.0[k] = self.0[k].max(excess / spread);
            }
        }
    }

    /// The stored factor: [`ERROR_SAFETY`] × the largest ratio of the three, in sixteenths,
    /// for all three margins: a piece that changes branch moves its whole shape, so an
    /// irregular margin makes the others suspect too.
    fn factor(&self) -> [u8; 3] {
        let worst = self.0.iter().fold(0.0f64, |a, &b| a.max(b));
        [PvRecord::quantize_factor(ERROR_SAFETY * worst); 3]
    }
}

/// One pair of clamps of one link's catalogue: the unit of work (its lengths are solved
/// together, by continuation).
pub(super) struct Pair {
    /// Position of the link in the header.
    pub slot: usize,
    pub start: usize,
    pub end: usize,
}

/// The pairs with at least one PV in `stored`, in PV order.
fn pairs_in(header: &Header, stored: &Range<u64>) -> Vec<Pair> {
    let mut pairs = Vec::new();
    for (slot, entry) in header.links.iter().enumerate() {
        let count = entry.lengths.len() as u64;
        let block = entry.first_pv..entry.first_pv + entry.pv_count();
        let first = block.start.max(stored.start);
        let end = block.end.min(stored.end);
        if first >= end {
            continue;
        }
        let first_pair = (first - block.start) / count;
        let end_pair = (end - block.start).div_ceil(count);
        let nb = entry.clamps.len() as u64;
        pairs.extend((first_pair..end_pair).map(|p| Pair {
            slot,
            start: (p / nb) as usize,
            end: (p % nb) as usize,
        }));
    }
    pairs
}

/// A solved pair: its PVs in the stored range (global index and piece).
struct SolvedPair<'p> {
    pair: &'p Pair,
    pieces: Vec<(u64, Piece)>,
}

/// One PV's margins under every stored direction (`None`: too short for its clamps) and its
/// error factor.
pub(super) struct Piece {
    pub rows: Option<Vec<MarginRecord>>,
    pub error_factor: [u8; 3],
}

/// Every admissible length of `pair` under every stored direction, then at the probes; each
/// length's interpolation error measured leaving each stored direction out and at the
/// probes. All its admissible lengths are solved, also those of another shard (solving them
/// together shares the continuation's work); its pieces in the stored range are kept.
fn solve_pair<'p>(
    evaluator: &Evaluator<'_>,
    header: &Header,
    pair: &'p Pair,
    stored: &Range<u64>,
    sample: &DirectionSample,
) -> SolvedPair<'p> {
    let lengths = pair_lengths(evaluator.setup(), header, pair);
    let pieces = solve_lengths(evaluator, pair, &lengths, sample)
        .into_iter()
        .filter(|(g, _)| stored.contains(g))
        .collect();
    SolvedPair { pair, pieces }
}

/// The admissible stored lengths (> 0) of `pair`, with their global PV indices, ascending.
fn pair_lengths(setup: &Setup, header: &Header, pair: &Pair) -> Vec<(u64, usize)> {
    let entry = &header.links[pair.slot];
    entry
        .lengths
        .iter()
        .map(|&s| s as usize)
        .filter(|&s| s > 0 && setup.is_admissible(0, s, pair.start, pair.end))
        .filter_map(|s| {
            let local = entry.grid_index(s, pair.start, pair.end)?;
            Some((entry.first_pv + local, s))
        })
        .collect()
}

/// The pieces of `lengths` (global index, sub-segments; ascending) of `pair`: margins under
/// every stored direction and error factors. A piece's values depend only on its clamps, its
/// length and the directions (the lengths are continued in fixed blocks), so solving one
/// length alone gives what solving it with the others gives.
pub(super) fn solve_lengths(
    evaluator: &Evaluator<'_>,
    pair: &Pair,
    lengths: &[(u64, usize)],
    sample: &DirectionSample,
) -> Vec<(u64, Piece)> {
    // The evaluator's setup is the link's catalogue: one segment, both guides every clamp.
    let m = 0;
    let limits = &evaluator.setup().thresholds;
    let sub_segments: Vec<usize> = lengths.iter().map(|&(_, s)| s).collect();
    let margins_at = |d: &[f64; 3]| -> Vec<Result<[f64; 3], Rejection>> {
        let down = Vector3::from(*d);
        let metrics = evaluator.link_frame_metrics(m, (pair.start, pair.end), &sub_segments, &down);
        metrics
            .into_iter()
            .map(|r| r.map(|metrics| Margins::of(&metrics, limits).to_array()))
            .collect()
    };
    let n = sample.stored.len();
    let mut rows = vec![Vec::with_capacity(n); lengths.len()];
    let mut too_short = vec![false; lengths.len()];
    for d in &sample.stored {
        for (i, margins) in margins_at(d).into_iter().enumerate() {
            too_short[i] |= margins == Err(Rejection::TooShort);
            rows[i].push(MarginRecord::quantize(margins.ok()));
        }
    }
    let mut ratios: Vec<ErrorRatio> = lengths.iter().map(|_| ErrorRatio::default()).collect();
    for (i, rows) in rows.iter().enumerate() {
        for (k, neighbours) in sample.left_out_neighbours.iter().enumerate() {
            let exact = rows[k].values();
            let interpolated = neighbours.interpolate(|j| rows[j].values());
            if let (Some(exact), Some(interpolated)) = (exact, interpolated) {
                ratios[i].add(&interpolated, &exact);
            }
        }
    }
    for (probe, neighbours) in sample.probes.iter().zip(&sample.probe_neighbours) {
        for (i, exact) in margins_at(probe).into_iter().enumerate() {
            let interpolated = neighbours.interpolate(|k| rows[i][k].values());
            if let (Ok(exact), Some(interpolated)) = (exact, interpolated) {
                ratios[i].add(&interpolated, &exact);
            }
        }
    }
    lengths
        .iter()
        .zip(rows)
        .zip(too_short)
        .zip(ratios)
        .map(|((((g, _), rows), short), ratio)| {
            let piece = Piece {
                rows: (!short).then_some(rows),
                error_factor: if short { [0; 3] } else { ratio.factor() },
            };
            (*g, piece)
        })
        .collect()
}

/// Refuses what a dictionary cannot represent.
fn check_buildable(setup: &Setup, options: &BuildOptions) -> Result<(), Problem> {
    let name = setup
        .source
        .file_name()
        .unwrap_or_default()
        .to_string_lossy();
    super::reader::check_file_name(&name)?;
    if !(MIN_DIRECTION_COUNT..=MAX_DIRECTION_COUNT).contains(&options.directions) {
        return Err(Problem::Build(format!(
            "--directions must be {MIN_DIRECTION_COUNT} to {MAX_DIRECTION_COUNT}, got {}",
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
    let embedded: usize = setup.text.len()
        + setup.robot_text.len()
        + setup.cable_text.len()
        + setup
            .robot
            .mesh_files
            .iter()
            .map(|f| f.bytes.len())
            .sum::<usize>();
    // The rest of the header (catalogues, lengths) needs far less than the last megabyte.
    if embedded > HEADER_LIMIT - (1 << 20) {
        return Err(Problem::Build(format!(
            "the setup, URDF, cable and mesh files take {:.1} MB; a dictionary embeds at most \
             {} MB: simplify the collision meshes",
            embedded as f64 / 1e6,
            (HEADER_LIMIT >> 20) - 1
        )));
    }
    Ok(())
}

/// Most bytes of margin records a build holds in memory (and writes): 4 GiB.
pub const MAX_RESULT_BYTES: u128 = 4 << 30;

/// Refuses a setup whose links offer no two clamp places (nothing to store), more clamps on
/// one link than a PV record can index, or more margin records than [`MAX_RESULT_BYTES`].
fn check_catalogues(
    catalogues: &[LinkCatalogue],
    lengths: usize,
    directions: usize,
) -> Result<(), Problem> {
    if catalogues.is_empty() {
        return Err(Problem::Build(
            "no link of the setup offers two or more clamp places: nothing to store".into(),
        ));
    }
    let widest = catalogues.iter().map(|c| c.clamps().len()).max();
    if widest.unwrap_or(0) > usize::from(u16::MAX) || catalogues.len() > usize::from(u16::MAX) {
        return Err(Problem::Build(format!(
            "a PV record indexes at most {} clamps of one link and {} links",
            u16::MAX,
            u16::MAX
        )));
    }
    let pieces: u128 = catalogues
        .iter()
        .map(|c| (c.clamps().len() as u128).pow(2) * lengths as u128)
        .sum();
    let bytes = pieces * directions as u128 * size_of::<MarginRecord>() as u128;
    if bytes > MAX_RESULT_BYTES {
        return Err(Problem::Build(format!(
            "{pieces} pieces × {directions} directions need {:.1} GB of margins, at most {} GB: \
             use fewer directions, fewer clamp places (a larger spacing_mm) or narrower length \
             windows",
            bytes as f64 / 1e9,
            MAX_RESULT_BYTES >> 30
        )));
    }
    Ok(())
}

/// The lengths every link's catalogue stores (ascending): the candidate lengths of all the
/// setup's intra-link segments with their robustness neighbours, and those candidates alone.
pub(super) fn catalogue_lengths(setup: &Setup) -> (Vec<u32>, Vec<usize>) {
    let mut stored = BTreeSet::new();
    let mut candidates = BTreeSet::new();
    for m in (0..setup.segment_count()).filter(|&m| setup.is_intra_link(m)) {
        stored.extend(stored_lengths(setup, m));
        candidates.extend(setup.segments[m].lengths.iter().copied().filter(|&s| s > 0));
    }
    (
        stored.into_iter().collect(),
        candidates.into_iter().collect(),
    )
}

/// The header of a whole dictionary of `setup`'s `catalogues` (no shard).
fn header(
    setup: &Setup,
    catalogues: &[LinkCatalogue],
    lengths: &[u32],
    directions: &[[f64; 3]],
    probes: usize,
) -> Header {
    let file_name = setup
        .source
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut links = Vec::new();
    let mut first_pv = 0;
    for catalogue in catalogues {
        let entry = LinkEntry {
            link: setup.robot.links[catalogue.body].name.clone(),
            clamps: catalogue.clamps().iter().map(clamp_entry).collect(),
            lengths: lengths.to_vec(),
            first_pv,
            d1_all: 0,
            d2_all: 0,
            margin_error: [0.0; 3],
        };
        first_pv += entry.pv_count();
        links.push(entry);
    }
    let solver = SolverOptions::STRESS_CHECK;
    Header {
        physics_version: PHYSICS_VERSION,
        setup: EmbeddedSetup {
            file_name,
            text: setup.text.clone(),
            robot_text: setup.robot_text.clone(),
            cable_text: setup.cable_text.clone(),
            meshes: setup.robot.mesh_files.clone(),
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
            probes: probes as u32,
            gravity_m_s2: setup.gravity_m_s2.norm(),
        },
        links,
        pv_total: first_pv,
        shard: None,
    }
}

/// `Ok` (with the link catalogues of `setup`, for the records' checks) when `header` and
/// `directions` are what a build of `setup` (the embedded one) writes: the documented direction sample for the header's count, the same solver
/// settings, catalogues, lengths and grid; else the first part that differs. Only the
/// fields the margins determine (|D1|, |D2|, the error bounds) are not derived here.
pub(super) fn check_derivation(
    header: &Header,
    directions: &[[f64; 3]],
    setup: &Setup,
) -> Result<Vec<LinkCatalogue>, Problem> {
    let count = header.directions.count as usize;
    if !(MIN_DIRECTION_COUNT..=MAX_DIRECTION_COUNT).contains(&count) {
        return Err(Problem::Header(format!(
            "{count} gravity directions; a build samples {MIN_DIRECTION_COUNT} to \
             {MAX_DIRECTION_COUNT}"
        )));
    }
    let sample = fibonacci_sphere(count);
    let bits = |d: &[[f64; 3]]| -> Vec<u64> { d.iter().flatten().map(|x| x.to_bits()).collect() };
    if bits(directions) != bits(&sample) {
        return Err(Problem::Header(format!(
            "the directions section is not the Fibonacci sample of {count} directions"
        )));
    }
    let (stored_lengths, candidate_lengths) = catalogue_lengths(setup);
    let catalogues = link_catalogues(setup, &candidate_lengths);
    let mut expected = self::header(
        setup,
        &catalogues,
        &stored_lengths,
        &sample,
        probe_count(count),
    );
    for (entry, stored) in expected.links.iter_mut().zip(&header.links) {
        entry.d1_all = stored.d1_all;
        entry.d2_all = stored.d2_all;
        entry.margin_error = stored.margin_error;
    }
    expected.shard = header
        .shard
        .map(|s| ShardRange::new(s.index, s.count, expected.pv_total));
    match first_difference(&expected, header) {
        None => Ok(catalogues),
        Some(part) => Err(Problem::Header(format!(
            "{part} is not what a build of the embedded setup writes (forged or from \
             another version: rebuild it)"
        ))),
    }
}

/// The first part of `stored` that differs from `expected`, named.
fn first_difference(expected: &Header, stored: &Header) -> Option<String> {
    let (e, s) = (&expected.directions, &stored.directions);
    let parts: [(&str, bool); 9] = [
        (
            "the physics version",
            expected.physics_version == stored.physics_version,
        ),
        ("the setup hash", expected.setup_hash == stored.setup_hash),
        ("the solver settings", expected.solver == stored.solver),
        ("the direction method", e.method == s.method),
        (
            "the covering radius",
            e.covering_radius_rad.to_bits() == s.covering_radius_rad.to_bits(),
        ),
        ("the probe count", e.probes == s.probes),
        (
            "the gravity",
            e.gravity_m_s2.to_bits() == s.gravity_m_s2.to_bits(),
        ),
        (
            "the number of link catalogues",
            expected.links.len() == stored.links.len(),
        ),
        ("the shard range", expected.shard == stored.shard),
    ];
    if let Some((part, _)) = parts.iter().find(|(_, same)| !same) {
        return Some(part.to_string());
    }
    for (e, s) in expected.links.iter().zip(&stored.links) {
        if e != s {
            return Some(format!("the catalogue of link {}", s.link));
        }
    }
    (expected.pv_total != stored.pv_total).then(|| "the PV total".to_string())
}

/// The header entry of one clamp place.
fn clamp_entry(clamp: &crate::setup::GuideConfiguration) -> ClampEntry {
    let q = clamp.pose.rotation.quaternion();
    ClampEntry {
        name: clamp.name.clone(),
        position_m: clamp.pose.translation.vector.into(),
        rotation_xyzw: [q.i, q.j, q.k, q.w],
    }
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
fn pv_record(catalogues: &[LinkCatalogue], header: &Header, g: u64) -> PvRecord {
    let (slot, pv) = pv_at(header, g);
    let catalogue = &catalogues[slot].setup;
    let admissible = catalogue.is_admissible(0, pv.sub_segments, pv.start, pv.end);
    let candidate = admissible && catalogue.segments[0].lengths.contains(&pv.sub_segments);
    PvRecord {
        sub_segments: pv.sub_segments as u32,
        start: pv.start as u16,
        end: pv.end as u16,
        link: slot as u16,
        flags: if admissible { PvRecord::ADMISSIBLE } else { 0 }
            | if candidate { PvRecord::CANDIDATE } else { 0 },
        error_factor: [0; 3],
        reserved: 0,
    }
}

/// The link (its position in the header) and PV of global index `g`, which must be below
/// `header.pv_total` of a header [`parse`](super::format::parse) accepted.
pub(super) fn pv_at(header: &Header, g: u64) -> (usize, Pv) {
    let position = header.links.partition_point(|e| e.first_pv <= g);
    let slot = position.saturating_sub(1);
    let entry = &header.links[slot];
    let local = (g - entry.first_pv) as usize;
    let clamps = entry.clamps.len();
    let count = entry.lengths.len();
    let pair = local / count;
    let pv = Pv::new(
        entry.lengths[local % count] as usize,
        pair / clamps % clamps,
        pair % clamps,
    );
    (slot, pv)
}

/// Sets the all-directions D1/D2 flags and counts of a whole dictionary: D1 = candidates that
/// pass every direction; D2 = those whose robustness neighbours (candidates or not) do too.
pub(super) fn finalize(built: &mut Built, robustness: &Robustness) {
    let sets = all_direction_sets(&built.header, &built.pvs, &built.results, robustness);
    for (record, (d1, d2)) in built.pvs.iter_mut().zip(&sets) {
        record.flags &= !(PvRecord::D1_ALL | PvRecord::D2_ALL);
        record.flags |= all_direction_flags(*d1, *d2);
    }
    for entry in &mut built.header.links {
        let block = entry.first_pv as usize..(entry.first_pv + entry.pv_count()) as usize;
        let of_link = &sets[block];
        entry.d1_all = of_link.iter().filter(|(d1, _)| *d1).count() as u64;
        entry.d2_all = of_link.iter().filter(|(_, d2)| *d2).count() as u64;
    }
}

/// The D1_ALL and D2_ALL bits of a record that belongs to D1 and to D2 at every direction.
fn all_direction_flags(d1: bool, d2: bool) -> u16 {
    (if d1 { PvRecord::D1_ALL } else { 0 }) | (if d2 { PvRecord::D2_ALL } else { 0 })
}

/// Per record of a whole dictionary, whether it belongs to D1 and to D2 at every stored
/// direction, from its flags ADMISSIBLE and CANDIDATE and the stored margins alone.
fn all_direction_sets(
    header: &Header,
    pvs: &[PvRecord],
    results: &[MarginRecord],
    robustness: &Robustness,
) -> Vec<(bool, bool)> {
    let n = header.directions.count as usize;
    let holds = |r: &MarginRecord| r.values().is_some_and(|v| v.iter().all(|&m| m >= 0.0));
    let passes_all: Vec<bool> = results
        .chunks_exact(n.max(1))
        .zip(pvs)
        .map(|(rows, record)| {
            record.has(PvRecord::ADMISSIBLE) && (record.sub_segments == 0 || rows.iter().all(holds))
        })
        .collect();
    let mut sets = vec![(false, false); pvs.len()];
    for entry in &header.links {
        let first = entry.first_pv as usize;
        let passes = |pv: &Pv| {
            entry
                .grid_index(pv.sub_segments, pv.start, pv.end)
                .is_some_and(|i| passes_all.get(first + i as usize) == Some(&true))
        };
        for g in first..first + entry.pv_count() as usize {
            let record = &pvs[g];
            if !(record.has(PvRecord::CANDIDATE) && passes_all[g]) {
                continue;
            }
            let robust = robust_neighbours(&record.pv(), robustness.delta_s, robustness.range)
                .is_some_and(|n| n.iter().all(passes));
            sets[g] = (true, robust);
        }
    }
    sets
}

/// The records' flags are what a build of `setup` derives: ADMISSIBLE and CANDIDATE from the
/// catalogues, and (whole dictionaries) D1_ALL and D2_ALL from the stored margins. A flag is
/// not covered by a checksum's meaning: forged, it changes what `info` counts and which
/// records `verify --recompute` draws from.
pub(super) fn check_flags(
    setup: &Setup,
    catalogues: &[LinkCatalogue],
    header: &Header,
    pvs: &[PvRecord],
    results: &[MarginRecord],
) -> Result<(), Problem> {
    let stored = header.stored_pvs();
    let whole = header.shard.is_none();
    let sets = whole.then(|| all_direction_sets(header, pvs, results, &setup.robustness));
    for (k, record) in pvs.iter().enumerate() {
        let g = stored.start + k as u64;
        let mut expected = pv_record(catalogues, header, g).flags;
        let mut compared = PvRecord::ADMISSIBLE | PvRecord::CANDIDATE;
        if let Some(sets) = &sets {
            let (d1, d2) = sets[k];
            expected |= all_direction_flags(d1, d2);
            compared |= PvRecord::D1_ALL | PvRecord::D2_ALL;
        }
        let differing = (record.flags ^ expected) & compared;
        if differing != 0 {
            return Err(Problem::Layout {
                place: format!("PV record {g}"),
                detail: format!(
                    "flags {} {} not what the embedded setup and the stored margins give \
                     (forged or from another version: rebuild it)",
                    flag_names(differing),
                    if differing.count_ones() == 1 {
                        "is"
                    } else {
                        "are"
                    }
                ),
            });
        }
    }
    Ok(())
}

/// The names of the flags set in `flags`.
fn flag_names(flags: u16) -> String {
    [
        (PvRecord::ADMISSIBLE, "ADMISSIBLE"),
        (PvRecord::CANDIDATE, "CANDIDATE"),
        (PvRecord::D1_ALL, "D1_ALL"),
        (PvRecord::D2_ALL, "D2_ALL"),
        (PvRecord::TOO_SHORT, "TOO_SHORT"),
    ]
    .iter()
    .filter(|(bit, _)| flags & bit != 0)
    .map(|(_, name)| *name)
    .collect::<Vec<_>>()
    .join(", ")
}
