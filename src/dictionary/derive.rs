//! What a build derives from its setup alone, and the checks that a stored file is that: the
//! header (catalogues, lengths, solver and direction settings), the records' flags, where a
//! global PV index lies, the embedded setup's file name. A build writes with these rules and
//! the reader verifies with the same ones, so the two cannot drift apart.

use super::catalogue::{LinkCatalogue, link_catalogues};
use super::directions::{
    MAX_DIRECTION_COUNT, MIN_DIRECTION_COUNT, covering_radius, fibonacci_sphere,
};
use super::error::Problem;
use super::format::{
    ClampEntry, DirectionParameters, EmbeddedSetup, Header, LinkEntry, MarginRecord,
    PHYSICS_VERSION, PvRecord, ShardRange, SolverParameters,
};
use crate::attachment::{MARGIN_COUNT, needed_pvs, robust_neighbours};
use crate::geometry::reaches;
use crate::path::Pv;
use crate::setup::{Robustness, Setup};
use crate::statics::SolverOptions;
use std::collections::BTreeSet;
/// Probe directions for `n` stored ones: a quarter as many (at least 8), so that measuring
/// the interpolation error costs a quarter of the build.
pub(super) fn probe_count(n: usize) -> usize {
    (n / 4).max(8)
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

/// The header of a whole dictionary of `setup`'s `catalogues` (no shard).
pub(super) fn header(
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
            margin_error: [0.0; MARGIN_COUNT],
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

/// The header entry of one clamp place.
fn clamp_entry(clamp: &crate::setup::GuideConfiguration) -> ClampEntry {
    let q = clamp.pose.rotation.quaternion();
    ClampEntry {
        name: clamp.name.clone(),
        position_m: clamp.pose.translation.vector.into(),
        rotation_xyzw: [q.i, q.j, q.k, q.w],
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

/// The record of global PV `g` (flags: admissible, candidate).
pub(super) fn pv_record(catalogues: &[LinkCatalogue], header: &Header, g: u64) -> PvRecord {
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
        error_factor: [0; MARGIN_COUNT],
    }
}

/// Whether the piece of global index `g` is a real cable too short to reach between its
/// clamps — what a build stores unmeasured with TOO_SHORT: its clamps' distance in their
/// link's frame beyond its length ([`reaches`], the connected geometry's own test; the same
/// under every direction of gravity).
fn too_short(catalogues: &[LinkCatalogue], header: &Header, g: u64) -> bool {
    let (slot, pv) = pv_at(header, g);
    let catalogue = &catalogues[slot].setup;
    if pv.sub_segments == 0 || !catalogue.is_admissible(0, pv.sub_segments, pv.start, pv.end) {
        return false;
    }
    let (a, b) = catalogue.segment_guides(0);
    reaches(
        &catalogue.guides[a].pose_in_body(pv.start),
        &catalogue.guides[b].pose_in_body(pv.end),
        pv.sub_segments,
        catalogue.cable.sub_segment_pitch_m,
    )
    .is_err()
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
pub(super) fn finalize(
    header: &mut Header,
    pvs: &mut [PvRecord],
    results: &[MarginRecord],
    robustness: &Robustness,
) {
    let sets = all_direction_sets(header, pvs, results, robustness);
    for (record, (d1, d2)) in pvs.iter_mut().zip(&sets) {
        record.flags &= !(PvRecord::D1_ALL | PvRecord::D2_ALL);
        record.flags |= all_direction_flags(*d1, *d2);
    }
    for entry in &mut header.links {
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
/// catalogues, TOO_SHORT from the clamps' distance ([`too_short`]), and (whole dictionaries)
/// D1_ALL and D2_ALL from the stored margins. A flag is
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
        if too_short(catalogues, header, g) {
            expected |= PvRecord::TOO_SHORT;
        }
        let mut compared = PvRecord::ADMISSIBLE | PvRecord::CANDIDATE | PvRecord::TOO_SHORT;
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

/// The embedded setup's name is a plain file name, as a build writes it: no folder, no
/// `..`, no control character — it is shown on terminals and in reports.
pub(super) fn check_file_name(name: &str) -> Result<(), Problem> {
    let plain = !name.is_empty()
        && name.len() <= 255
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\'])
        && crate::escape::terminal(name) == name;
    if plain {
        return Ok(());
    }
    Err(Problem::Header(format!(
        "the embedded setup's file name \"{}\" is not a plain file name (a build writes the \
         setup's own name, without folders)",
        crate::escape::terminal(name)
    )))
}
