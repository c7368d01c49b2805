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
use super::derive::{catalogue_lengths, check_file_name, finalize, header, probe_count, pv_record};
use super::directions::{
    Interpolated, MAX_DIRECTION_COUNT, MIN_DIRECTION_COUNT, Neighbours, fibonacci_sphere,
    probe_directions,
};
use super::error::Problem;
use super::format::{
    ERROR_SAFETY, HEADER_LIMIT, Header, MARGIN_UNITS, MarginRecord, PvRecord, ShardRange, encode,
};
use crate::attachment::{ConnectMethod, Evaluator, MARGIN_COUNT, MarginValues, Margins, Rejection};
use crate::progress;
use crate::setup::{Robustness, Setup};
use nalgebra::Vector3;
use rayon::prelude::*;
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
        finalize(&mut self.header, &mut self.pvs, &self.results, robustness);
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
        built.derive_flags(&setup.robustness);
    }
    Ok(built)
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
struct ErrorRatio(MarginValues);

impl ErrorRatio {
    /// Adds the comparison of `interpolated` with the `exact` margins (clamped to the stored
    /// range): only an error that flips a margin's sign can flip a verdict.
    fn add(&mut self, interpolated: &Interpolated, exact: &MarginValues) {
        for k in 0..MARGIN_COUNT {
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

    /// The stored factor: [`ERROR_SAFETY`] × the largest ratio of the margins, in
    /// sixteenths, for all of them: a piece that changes branch moves its whole shape, so an
    /// irregular margin makes the others suspect too.
    fn factor(&self) -> [u8; MARGIN_COUNT] {
        let worst = self.0.iter().fold(0.0f64, |a, &b| a.max(b));
        [PvRecord::quantize_factor(ERROR_SAFETY * worst); MARGIN_COUNT]
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
    pub error_factor: [u8; MARGIN_COUNT],
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
    let margins_at = |d: &[f64; 3]| -> Vec<Result<MarginValues, Rejection>> {
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
                error_factor: if short {
                    [0; MARGIN_COUNT]
                } else {
                    ratio.factor()
                },
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
    check_file_name(&name)?;
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
