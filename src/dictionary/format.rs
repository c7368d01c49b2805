//! The `.cdict` byte layout, version 4 (docs/cdict-format.md): a checksummed preamble, a
//! checksummed section table, then four sections at 16-byte aligned offsets — the header
//! (bincode), the gravity directions, the PV records and the margin records (fixed-size,
//! little-endian, read in place from the memory map). Version 1 stored verdicts instead of
//! margins, version 2 one block per segment of one setup instead of one per link's clamp
//! catalogue, version 3 three margins (no twist); all are refused with the command that
//! rebuilds them.
//!
//! [`parse`] checks everything that is O(1) or O(header): magic, version, length, the
//! preamble's and the table's checksums, every section's bounds, alignment and record size,
//! and the header's own checksum; [`verify_sections`] checks the bulk sections' checksums.

use super::error::Problem;
use crate::attachment::{MARGIN_COUNT, MarginValues};
use crate::path::Pv;
use serde::{Deserialize, Serialize};
use std::ops::Range;
use xxhash_rust::xxh3::xxh3_64;

#[cfg(target_endian = "big")]
compile_error!("the .cdict records are read in place as little-endian values");

/// The first 8 bytes of every dictionary (the CR LF catches text-mode copies).
pub const MAGIC: [u8; 8] = *b"CDICT\0\r\n";
/// The format version this build writes and reads.
pub const FORMAT_VERSION: u32 = 4;
/// Bytes of the preamble; the section table follows.
pub const PREAMBLE_LEN: usize = 64;
/// Bytes of one section-table entry.
pub const TABLE_ENTRY_LEN: usize = 32;
/// Section offsets are multiples of this (the widest record field is 8 bytes).
pub const ALIGNMENT: usize = 16;
/// Version of the physics behind the stored results: bumped whenever the static solver or
/// the metrics change what they compute, so that old dictionaries are refused, not trusted.
/// 2: cables in EI/GJ, the `L D Lᵀ` Newton solver, retraction to 5e-13.
/// 3: the end clamp turned by the installed cable's twist; lengths continued per direction.
/// 4: lengths continued in fixed blocks ([`crate::attachment::CONTINUATION_BLOCK`]).
/// 5: a cable leaving and re-entering one clamp place the same way is refused (a full loop
/// from a clamp into itself), not solved ([`crate::geometry::COINCIDENT_GUIDES_M`]).
/// 6: clamp zones counted in the cable's sub-segments, not along its current shape
/// ([`crate::stress::ClampZone`]); a mesh is the union of its shells' solids.
/// 7: the clearance margin is also the cable's clearance to itself
/// ([`crate::stress::self_contact`]).
/// 8: the clearance to itself counts only where the cable comes back toward itself (a local
/// minimum of the distance between its parts), not its own neighbourhood.
/// 9: a fourth margin, the twist per length against the cable's torsion limit.
pub const PHYSICS_VERSION: u32 = 9;
/// Largest header accepted when decoding (the URDF text dominates it).
pub const HEADER_LIMIT: usize = 64 << 20;

/// The four sections, in file order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionKind {
    /// bincode-encoded [`Header`].
    Header = 1,
    /// Gravity directions in the link frame: `[f64; 3]` unit vectors.
    Directions = 2,
    /// [`PvRecord`]s.
    Pvs = 3,
    /// [`MarginRecord`]s, `directions` per PV, PV-major.
    Results = 4,
}

impl SectionKind {
    /// Every kind, in file order.
    pub const ALL: [SectionKind; 4] = [
        SectionKind::Header,
        SectionKind::Directions,
        SectionKind::Pvs,
        SectionKind::Results,
    ];

    /// Name used in messages.
    pub fn name(self) -> &'static str {
        match self {
            SectionKind::Header => "header",
            SectionKind::Directions => "directions",
            SectionKind::Pvs => "pvs",
            SectionKind::Results => "results",
        }
    }

    /// Bytes per record (1 for the header's free-form bytes).
    fn record_len(self) -> usize {
        match self {
            SectionKind::Header => 1,
            SectionKind::Directions => size_of::<[f64; 3]>(),
            SectionKind::Pvs => size_of::<PvRecord>(),
            SectionKind::Results => size_of::<MarginRecord>(),
        }
    }
}

/// One cable piece between two clamps of one link's catalogue, in the dense grid (start
/// clamp, end clamp, length) of its link: a pair of clamps' lengths are neighbours, so a
/// shard holds whole pairs and solves their lengths by continuation.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PvRecord {
    /// Length S in sub-segments.
    pub sub_segments: u32,
    /// Index of the start clamp in its link's catalogue ([`LinkEntry::clamps`]).
    pub start: u16,
    /// Index of the end clamp in its link's catalogue.
    pub end: u16,
    /// Index of its link's entry in [`Header::links`].
    pub link: u16,
    /// [`PvRecord::ADMISSIBLE`] | [`PvRecord::CANDIDATE`] | [`PvRecord::D1_ALL`] |
    /// [`PvRecord::D2_ALL`] | [`PvRecord::TOO_SHORT`].
    pub flags: u16,
    /// This PV's interpolation error per unit of neighbour spread (clearance, stretch,
    /// curvature, twist), in sixteenths, rounded up: the largest `(error − one unit) / spread`
    /// that flipped a margin's sign, measured anywhere on the sphere — leaving each stored
    /// direction out in turn, and at the probe directions — × [`ERROR_SAFETY`]. A piece
    /// that changes branch somewhere (a loop that can hang on either side of its link) gets
    /// a large factor everywhere, so the lookup leaves it to the exact check.
    pub error_factor: [u8; MARGIN_COUNT],
}

impl PvRecord {
    /// S = 0 exactly when the two clamps coincide: a real cable (or a real single clamp).
    /// Other grid cells are placeholders and were not evaluated.
    pub const ADMISSIBLE: u16 = 1;
    /// The length is one of the build setup's candidate lengths of an intra-link segment
    /// (others are robustness neighbours only).
    pub const CANDIDATE: u16 = 2;
    /// In D1 for every stored direction (whole dictionaries only).
    pub const D1_ALL: u16 = 4;
    /// In D2 for every stored direction (whole dictionaries only).
    pub const D2_ALL: u16 = 8;
    /// The cable is shorter than the distance between its clamps: it fails under every
    /// direction (its margins are not measured).
    pub const TOO_SHORT: u16 = 16;
    /// Every flag a writer sets.
    pub const KNOWN: u16 =
        Self::ADMISSIBLE | Self::CANDIDATE | Self::D1_ALL | Self::D2_ALL | Self::TOO_SHORT;

    /// [`PvRecord::error_factor`] as numbers.
    pub fn error_factors(&self) -> MarginValues {
        self.error_factor.map(|f| f64::from(f) / 16.0)
    }

    /// The stored sixteenths of an error factor, rounded up, saturated at 255.
    pub fn quantize_factor(factor: f64) -> u8 {
        (factor * 16.0).ceil().clamp(0.0, 255.0) as u8
    }

    /// True when `flag` is set.
    pub fn has(&self, flag: u16) -> bool {
        self.flags & flag != 0
    }

    /// The PV (length and configurations) this record stores.
    pub fn pv(&self) -> Pv {
        Pv::new(
            self.sub_segments as usize,
            usize::from(self.start),
            usize::from(self.end),
        )
    }
}

/// The four margins of one PV under one gravity direction, in fixed point: how far the
/// static equilibrium is from each limit of the embedded setup, positive when the limit
/// holds ([`crate::attachment::Margins`]). Values beyond the `i16` range saturate (a
/// saturated margin is at least that large; a cable without a torsion limit stores the
/// positive maximum); [`MarginRecord::NOT_MEASURED`] in all four
/// marks a direction without an equilibrium (a failed solve, a cable too short for its
/// clamps, a grid placeholder).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MarginRecord {
    /// Clearance − contact limit, in [`MARGIN_UNITS`]`[0]` mm (saturates at ±327 mm; no
    /// clearance measured, e.g. every node in a clamp zone: the positive maximum).
    pub clearance: i16,
    /// Stretch limit − stretch, in [`MARGIN_UNITS`]`[1]` (saturates at ±0.33).
    pub stretch: i16,
    /// 1/(minimum bend radius) − 1/(bend radius), in [`MARGIN_UNITS`]`[2]` 1/m (saturates
    /// at ±65 1/m).
    pub bend: i16,
    /// Torsion limit − |twist per length|, in [`MARGIN_UNITS`]`[3]` deg/m (saturates at
    /// ±3 276 deg/m).
    pub twist: i16,
}

/// The fixed-point units of a [`MarginRecord`]'s fields: clearance (mm), stretch ratio,
/// curvature (1/m), twist (deg/m). Rounding costs half a unit, which the lookup adds to its
/// error bound.
pub const MARGIN_UNITS: MarginValues = [0.01, 1e-5, 0.002, 0.1];

impl MarginRecord {
    /// The marker of a direction without an equilibrium.
    pub const NOT_MEASURED: i16 = i16::MIN;

    /// A direction without an equilibrium.
    pub const UNMEASURED: MarginRecord = MarginRecord {
        clearance: Self::NOT_MEASURED,
        stretch: Self::NOT_MEASURED,
        bend: Self::NOT_MEASURED,
        twist: Self::NOT_MEASURED,
    };

    /// The record of `margins` (clearance mm, stretch, curvature 1/m, twist deg/m; `None`:
    /// no equilibrium), rounded and saturated.
    pub fn quantize(margins: Option<MarginValues>) -> MarginRecord {
        let Some(values) = margins else {
            return Self::UNMEASURED;
        };
        let fixed = |k: usize| {
            let units = (values[k] / MARGIN_UNITS[k]).round();
            // NaN (never produced by the metrics) maps to the most negative value.
            units.clamp(-f64::from(i16::MAX), f64::from(i16::MAX)) as i16
        };
        MarginRecord {
            clearance: fixed(0),
            stretch: fixed(1),
            bend: fixed(2),
            twist: fixed(3),
        }
    }

    /// The margins in their units (clearance mm, stretch, curvature 1/m, twist deg/m),
    /// `None` for a direction without an equilibrium.
    pub fn values(&self) -> Option<MarginValues> {
        let raw = self.raw();
        if raw.contains(&Self::NOT_MEASURED) {
            return None;
        }
        Some(std::array::from_fn(|k| f64::from(raw[k]) * MARGIN_UNITS[k]))
    }

    /// True for a well-formed record: all fields measured, or none.
    pub fn is_consistent(&self) -> bool {
        let missing = self
            .raw()
            .iter()
            .filter(|&&v| v == Self::NOT_MEASURED)
            .count();
        missing == 0 || missing == MARGIN_COUNT
    }

    /// The stored fields, in the order of [`MARGIN_UNITS`].
    fn raw(&self) -> [i16; MARGIN_COUNT] {
        [self.clearance, self.stretch, self.bend, self.twist]
    }
}

/// Everything about a dictionary that is not bulk data. Encoded with bincode 2 (standard
/// configuration: little-endian, variable-length integers).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// [`PHYSICS_VERSION`] of the build.
    pub physics_version: u32,
    /// The setup: its file name (for messages) and the texts of the setup, URDF and cable
    /// files, so that the dictionary is self-contained.
    pub setup: EmbeddedSetup,
    /// Content hash of the setup ([`crate::setup::Setup::content_hash`]).
    pub setup_hash: u64,
    /// How each PV was evaluated.
    pub solver: SolverParameters,
    /// The sampled gravity directions.
    pub directions: DirectionParameters,
    /// The clamp catalogue of every link with two or more clamp places, in the robot's link
    /// order.
    pub links: Vec<LinkEntry>,
    /// PVs of all links together (the length of a whole dictionary's PV section).
    pub pv_total: u64,
    /// `Some` for one shard of a sharded build.
    pub shard: Option<ShardRange>,
}

/// The setup files' texts and the robot's mesh files.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EmbeddedSetup {
    /// File name of the setup (no folders: the bytes must not depend on the machine).
    pub file_name: String,
    /// The setup TOML.
    pub text: String,
    /// The URDF.
    pub robot_text: String,
    /// The cable TOML.
    pub cable_text: String,
    /// Every mesh file the URDF references, under the URI written in it.
    pub meshes: Vec<crate::robot::MeshFile>,
}

/// Static solver and metric settings of the build.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverParameters {
    /// Connected geometry: always `hermite` (Hermite curve + RMF, then the Newton solver).
    pub connect: String,
    /// Residual force tolerance of the Newton solver (N).
    pub force_tolerance_n: f64,
    /// Newton iteration limit.
    pub max_iterations: u32,
    /// Which links clearance is measured against: `own link`.
    pub clearance_links: String,
}

/// The direction sample.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DirectionParameters {
    /// `fibonacci` (the golden-angle spiral lattice).
    pub method: String,
    /// Number of directions N.
    pub count: u32,
    /// Largest angle from any direction on the sphere to its nearest sample (rad), an upper
    /// estimate: how far a looked-up direction can be from the stored ones.
    pub covering_radius_rad: f64,
    /// Probe directions (between the stored ones) at which the build measured the
    /// interpolation error of every PV.
    pub probes: u32,
    /// Magnitude of gravity (m/s²), from the setup.
    pub gravity_m_s2: f64,
}

/// One link's clamp catalogue and its block of PV records: every ordered pair of its
/// clamps × every stored length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinkEntry {
    /// The link (URDF name) the clamps move with.
    pub link: String,
    /// The clamps, in the order the PV records index them.
    pub clamps: Vec<ClampEntry>,
    /// Every length stored, ascending: the candidate lengths and their robustness neighbours.
    pub lengths: Vec<u32>,
    /// Index of the link's first PV record in the whole dictionary.
    pub first_pv: u64,
    /// |D1| over every stored direction (0 in a shard).
    pub d1_all: u64,
    /// |D2| over every stored direction (0 in a shard).
    pub d2_all: u64,
    /// The largest [`PvRecord::error_factor`] of this file's PVs (clearance, stretch,
    /// curvature, twist): how irregular the link's worst piece is (for `info`).
    pub margin_error: MarginValues,
}

/// One clamp of a link's catalogue: where a setup's guide configuration must be to use the
/// stored pieces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClampEntry {
    /// The configuration's name in the build setup, prefixed with its guide (`G2/site 3`).
    pub name: String,
    /// Position of the clamp frame in the link's frame (m).
    pub position_m: [f64; 3],
    /// Orientation of the clamp frame in the link's frame: unit quaternion `[x, y, z, w]`.
    pub rotation_xyzw: [f64; 4],
}

impl ClampEntry {
    /// Finite position and a unit quaternion (to 1e-9).
    fn is_well_formed(&self) -> bool {
        let finite = self.position_m.iter().all(|v| v.is_finite());
        let norm: f64 = self.rotation_xyzw.iter().map(|q| q * q).sum();
        finite && (norm - 1.0).abs() <= 1e-9
    }
}

impl PvRecord {
    /// The error bound of a margin of this PV interpolated from neighbours of `spread`:
    /// its error factor (at least [`MIN_ERROR_FACTOR`]) × spread, plus one fixed-point unit.
    pub fn error_bound(&self, spread: MarginValues) -> MarginValues {
        let factors = self.error_factors();
        std::array::from_fn(|k| factors[k].max(MIN_ERROR_FACTOR) * spread[k] + MARGIN_UNITS[k])
    }
}

/// Factor on the largest interpolation error measured for a PV.
pub const ERROR_SAFETY: f64 = 1.5;
/// Least error factor the lookup applies: half the neighbours' spread, whatever was measured
/// (a weighted mean lies inside the neighbours' range; the truth may lie outside it).
pub const MIN_ERROR_FACTOR: f64 = 1.0;

impl LinkEntry {
    /// PV records of this link: lengths × clamps × clamps (saturating; a header [`parse`]
    /// accepted never saturates).
    pub fn pv_count(&self) -> u64 {
        self.checked_pv_count().unwrap_or(u64::MAX)
    }

    /// [`SegmentEntry::pv_count`], `None` on overflow (a forged header).
    fn checked_pv_count(&self) -> Option<u64> {
        let clamps = self.clamps.len() as u64;
        (self.lengths.len() as u64)
            .checked_mul(clamps)?
            .checked_mul(clamps)
    }

    /// Index of (i, j, S) within the link's block, `None` when not stored.
    pub fn grid_index(&self, sub_segments: usize, start: usize, end: usize) -> Option<u64> {
        let clamps = self.clamps.len();
        let length = self
            .lengths
            .binary_search(&u32::try_from(sub_segments).ok()?)
            .ok()?;
        let count = self.lengths.len();
        (start < clamps && end < clamps).then(|| ((start * clamps + end) * count + length) as u64)
    }
}

/// The PVs one shard covers: `first_pv..end_pv` of the whole dictionary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardRange {
    /// 0-based shard index.
    pub index: u32,
    /// Number of shards.
    pub count: u32,
    /// First PV (inclusive).
    pub first_pv: u64,
    /// Last PV (exclusive).
    pub end_pv: u64,
}

impl ShardRange {
    /// Shard `index` of `count` over `total` PVs: contiguous, sizes differing by at most one.
    pub fn new(index: u32, count: u32, total: u64) -> ShardRange {
        let bound = |k: u32| total * u64::from(k) / u64::from(count);
        ShardRange {
            index,
            count,
            first_pv: bound(index),
            end_pv: bound(index + 1),
        }
    }
}

impl Header {
    /// PVs whose records this file holds.
    pub fn stored_pvs(&self) -> Range<u64> {
        match self.shard {
            Some(shard) => shard.first_pv..shard.end_pv,
            None => 0..self.pv_total,
        }
    }
}

/// Byte ranges of the four sections, checked against the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Decoded header.
    pub header: Header,
    /// Byte range of each section, indexed like [`SectionKind::ALL`].
    pub sections: [Range<usize>; 4],
    /// Stored checksum of each section.
    pub checksums: [u64; 4],
}

impl Layout {
    /// Byte range of `kind`.
    pub fn range(&self, kind: SectionKind) -> Range<usize> {
        self.sections[kind as usize - 1].clone()
    }
}

/// Serializes a dictionary: preamble, table, the four sections.
pub fn encode(
    header: &Header,
    directions: &[[f64; 3]],
    pvs: &[PvRecord],
    results: &[MarginRecord],
) -> Result<Vec<u8>, Problem> {
    let header_bytes = bincode::serde::encode_to_vec(header, bincode::config::standard())
        .map_err(|e| Problem::Header(format!("cannot encode: {e}")))?;
    let bodies: [&[u8]; 4] = [
        &header_bytes,
        bytemuck::cast_slice(directions),
        bytemuck::cast_slice(pvs),
        bytemuck::cast_slice(results),
    ];
    let table_end = PREAMBLE_LEN + TABLE_ENTRY_LEN * bodies.len();
    let mut out = vec![0u8; table_end];
    let mut table = Vec::with_capacity(TABLE_ENTRY_LEN * bodies.len());
    for (kind, body) in SectionKind::ALL.iter().zip(bodies) {
        out.resize(out.len().next_multiple_of(ALIGNMENT), 0);
        table.extend_from_slice(&(*kind as u32).to_le_bytes());
        table.extend_from_slice(&0u32.to_le_bytes());
        table.extend_from_slice(&(out.len() as u64).to_le_bytes());
        table.extend_from_slice(&(body.len() as u64).to_le_bytes());
        table.extend_from_slice(&xxh3_64(body).to_le_bytes());
        out.extend_from_slice(body);
    }
    out[PREAMBLE_LEN..table_end].copy_from_slice(&table);
    let preamble = Preamble {
        magic: MAGIC,
        version: FORMAT_VERSION,
        section_count: bodies.len() as u32,
        file_len: out.len() as u64,
        table_offset: PREAMBLE_LEN as u64,
        table_checksum: xxh3_64(&table),
        checksum: 0,
    };
    out[..PREAMBLE_LEN].copy_from_slice(&preamble.sealed());
    Ok(out)
}

/// The fixed bytes at the start of a file (docs/cdict-format.md): where each field lies is
/// said once, in [`Preamble::FIELDS`], for writing and reading alike.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Preamble {
    magic: [u8; 8],
    version: u32,
    section_count: u32,
    /// The whole file's length (bytes).
    file_len: u64,
    /// Where the section table starts (bytes from the file's start).
    table_offset: u64,
    /// xxh3-64 of the section table.
    table_checksum: u64,
    /// xxh3-64 of the preamble's bytes before it.
    checksum: u64,
}

impl Preamble {
    /// The byte range of each field: magic, version, section count, file length, table
    /// offset, table checksum, (reserved, zero), the preamble's own checksum.
    const FIELDS: [Range<usize>; 7] = [0..8, 8..12, 12..16, 16..24, 24..32, 32..40, 56..64];
    /// The bytes the preamble's own checksum covers.
    const CHECKED: Range<usize> = 0..56;

    /// Its bytes, with the checksum of the others set.
    fn sealed(&self) -> [u8; PREAMBLE_LEN] {
        let mut bytes = [0u8; PREAMBLE_LEN];
        let [magic, version, count, len, offset, table, _] = Preamble::FIELDS;
        bytes[magic].copy_from_slice(&self.magic);
        bytes[version].copy_from_slice(&self.version.to_le_bytes());
        bytes[count].copy_from_slice(&self.section_count.to_le_bytes());
        bytes[len].copy_from_slice(&self.file_len.to_le_bytes());
        bytes[offset].copy_from_slice(&self.table_offset.to_le_bytes());
        bytes[table].copy_from_slice(&self.table_checksum.to_le_bytes());
        let checksum = xxh3_64(&bytes[Preamble::CHECKED]);
        bytes[Preamble::FIELDS[6].clone()].copy_from_slice(&checksum.to_le_bytes());
        bytes
    }

    /// The fields of the first [`PREAMBLE_LEN`] bytes, unchecked.
    fn read(bytes: &[u8; PREAMBLE_LEN]) -> Preamble {
        let [magic, version, count, len, offset, table, checksum] = Preamble::FIELDS;
        let mut magic_bytes = [0u8; 8];
        magic_bytes.copy_from_slice(&bytes[magic]);
        Preamble {
            magic: magic_bytes,
            version: u32_at(bytes, version.start),
            section_count: u32_at(bytes, count.start),
            file_len: u64_at(bytes, len.start),
            table_offset: u64_at(bytes, offset.start),
            table_checksum: u64_at(bytes, table.start),
            checksum: u64_at(bytes, checksum.start),
        }
    }
}

/// Checks the structure of `bytes` and decodes the header. Costs O(header), independent of
/// the bulk sections' size; their checksums are [`verify_sections`]'s job.
pub fn parse(bytes: &[u8]) -> Result<Layout, Problem> {
    let table = parse_preamble(bytes)?;
    let mut sections: [Option<(Range<usize>, u64)>; 4] = Default::default();
    for (i, entry) in table.chunks_exact(TABLE_ENTRY_LEN).enumerate() {
        let (kind, range, checksum) = parse_entry(i, entry, bytes.len())?;
        let slot = &mut sections[kind as usize - 1];
        if slot.is_some() {
            return Err(layout(
                format!("section table entry {i}"),
                format!("a second '{}' section", kind.name()),
            ));
        }
        *slot = Some((range, checksum));
    }
    let mut ranges: [Range<usize>; 4] = Default::default();
    let mut checksums = [0u64; 4];
    for (k, kind) in SectionKind::ALL.iter().enumerate() {
        let (range, checksum) = sections[k].clone().ok_or_else(|| {
            layout(
                "section table".into(),
                format!("no '{}' section", kind.name()),
            )
        })?;
        ranges[k] = range;
        checksums[k] = checksum;
    }
    check_canonical(bytes, table, &ranges)?;
    let header_bytes = &bytes[ranges[0].clone()];
    check_checksum(SectionKind::Header, header_bytes, checksums[0])?;
    let header = decode_header(header_bytes)?;
    let layout = Layout {
        header,
        sections: ranges,
        checksums,
    };
    check_counts(&layout)?;
    Ok(layout)
}

/// The one byte layout [`encode`] writes: reserved bytes zero, the sections in kind order,
/// each at the next multiple of [`ALIGNMENT`] after the previous one, zero padding between
/// them, the file ending with the last — so no two sections overlap and no byte is left
/// unchecked.
fn check_canonical(bytes: &[u8], table: &[u8], ranges: &[Range<usize>; 4]) -> Result<(), Problem> {
    if bytes[40..56].iter().any(|&b| b != 0) {
        return Err(layout(
            "preamble".into(),
            "reserved bytes 40..56 are not zero".into(),
        ));
    }
    for (i, entry) in table.chunks_exact(TABLE_ENTRY_LEN).enumerate() {
        if u32_at(entry, 4) != 0 || u32_at(entry, 0) != SectionKind::ALL[i] as u32 {
            return Err(layout(
                format!("section table entry {i}"),
                "not the canonical entry (kind order, reserved bytes zero)".into(),
            ));
        }
    }
    let mut end = PREAMBLE_LEN + table.len();
    for (kind, range) in SectionKind::ALL.iter().zip(ranges) {
        let start = end.next_multiple_of(ALIGNMENT);
        if range.start != start || bytes[end..start].iter().any(|&b| b != 0) {
            return Err(layout(
                format!("section '{}'", kind.name()),
                format!(
                    "starts at {}, not at {start} after zero padding (sections overlap or \
                     leave a gap)",
                    range.start
                ),
            ));
        }
        end = range.end;
    }
    if end != bytes.len() {
        return Err(layout(
            "file".into(),
            format!("{} bytes follow the last section", bytes.len() - end),
        ));
    }
    Ok(())
}

/// Checks the checksums of the directions, PV and result sections (the header's was checked
/// by [`parse`]).
pub fn verify_sections(bytes: &[u8], layout: &Layout) -> Result<(), Problem> {
    for (k, kind) in SectionKind::ALL.iter().enumerate().skip(1) {
        check_checksum(
            *kind,
            &bytes[layout.sections[k].clone()],
            layout.checksums[k],
        )?;
    }
    Ok(())
}

/// The preamble's checks; returns the section table's bytes.
fn parse_preamble(bytes: &[u8]) -> Result<&[u8], Problem> {
    let Some(first) = bytes.first_chunk::<PREAMBLE_LEN>() else {
        return Err(Problem::NotADictionary(format!(
            "{} bytes, shorter than the {PREAMBLE_LEN}-byte preamble",
            bytes.len()
        )));
    };
    let preamble = Preamble::read(first);
    if preamble.magic != MAGIC {
        return Err(Problem::NotADictionary(format!(
            "the first bytes are {:02x?}, not the magic {:02x?}",
            preamble.magic, MAGIC
        )));
    }
    let version = preamble.version;
    if version > FORMAT_VERSION {
        return Err(Problem::FutureVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    if (1..FORMAT_VERSION).contains(&version) {
        return Err(Problem::OldVersion { found: version });
    }
    if version != FORMAT_VERSION {
        return Err(Problem::UnknownVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    check_bytes("preamble", &first[Preamble::CHECKED], preamble.checksum)?;
    let expected = preamble.file_len;
    if expected != bytes.len() as u64 {
        return Err(Problem::Length {
            expected,
            actual: bytes.len() as u64,
        });
    }
    let count = preamble.section_count as usize;
    let offset = preamble.table_offset;
    if count != SectionKind::ALL.len() || offset != PREAMBLE_LEN as u64 {
        return Err(layout(
            "preamble".into(),
            format!(
                "{count} sections at offset {offset}; version {FORMAT_VERSION} has {} at \
                 {PREAMBLE_LEN}",
                SectionKind::ALL.len()
            ),
        ));
    }
    let table_end = PREAMBLE_LEN + count * TABLE_ENTRY_LEN;
    let table = bytes.get(PREAMBLE_LEN..table_end).ok_or_else(|| {
        layout(
            "section table".into(),
            "extends past the end of the file".into(),
        )
    })?;
    check_bytes("section table", table, preamble.table_checksum)?;
    Ok(table)
}

/// One table entry: its kind, checked byte range and checksum.
fn parse_entry(
    i: usize,
    entry: &[u8],
    file_len: usize,
) -> Result<(SectionKind, Range<usize>, u64), Problem> {
    let place = || format!("section table entry {i}");
    let code = u32_at(entry, 0);
    let kind = SectionKind::ALL
        .into_iter()
        .find(|k| *k as u32 == code)
        .ok_or_else(|| layout(place(), format!("unknown section kind {code}")))?;
    let (offset, len) = (u64_at(entry, 8), u64_at(entry, 16));
    let end = offset
        .checked_add(len)
        .filter(|&end| end <= file_len as u64);
    let Some(end) = end else {
        return Err(layout(
            place(),
            format!(
                "section '{}' at {offset} + {len} bytes ends past the end of the file \
                 ({file_len} bytes)",
                kind.name()
            ),
        ));
    };
    let table_end = (PREAMBLE_LEN + SectionKind::ALL.len() * TABLE_ENTRY_LEN) as u64;
    if offset < table_end || offset % ALIGNMENT as u64 != 0 {
        return Err(layout(
            place(),
            format!(
                "section '{}' starts at {offset}: inside the table or not a multiple of \
                 {ALIGNMENT}",
                kind.name()
            ),
        ));
    }
    if len % kind.record_len() as u64 != 0 {
        return Err(layout(
            place(),
            format!(
                "section '{}' has {len} bytes, not a whole number of {}-byte records",
                kind.name(),
                kind.record_len()
            ),
        ));
    }
    Ok((kind, offset as usize..end as usize, u64_at(entry, 24)))
}

fn decode_header(bytes: &[u8]) -> Result<Header, Problem> {
    let config = bincode::config::standard().with_limit::<HEADER_LIMIT>();
    let (header, used): (Header, usize) = bincode::serde::decode_from_slice(bytes, config)
        .map_err(|e| Problem::Header(format!("does not decode: {e}")))?;
    if used != bytes.len() {
        return Err(Problem::Header(format!(
            "{} bytes follow the encoded header",
            bytes.len() - used
        )));
    }
    Ok(header)
}

/// The sections' record counts agree with the header.
fn check_counts(layout: &Layout) -> Result<(), Problem> {
    let header = &layout.header;
    let count = |kind: SectionKind| (layout.range(kind).len() / kind.record_len()) as u64;
    let directions = u64::from(header.directions.count);
    if count(SectionKind::Directions) != directions {
        return Err(Problem::Header(format!(
            "announces {directions} directions, the section holds {}",
            count(SectionKind::Directions)
        )));
    }
    check_links(header)?;
    let grid: u64 = header.links.iter().map(LinkEntry::pv_count).sum();
    let stored = header.stored_pvs();
    if grid != header.pv_total || stored.start > stored.end || stored.end > header.pv_total {
        return Err(Problem::Header(format!(
            "the links hold {grid} PVs, the header says {} and stores {}..{}",
            header.pv_total, stored.start, stored.end
        )));
    }
    let pvs = stored.end - stored.start;
    if count(SectionKind::Pvs) != pvs {
        return Err(Problem::Header(format!(
            "announces {pvs} PV records, the section holds {}",
            count(SectionKind::Pvs)
        )));
    }
    let results = pvs.checked_mul(directions);
    if results != Some(count(SectionKind::Results)) {
        return Err(Problem::Header(format!(
            "{pvs} PVs × {directions} directions, but the results section holds {} records",
            count(SectionKind::Results)
        )));
    }
    Ok(())
}

/// The link table is a valid grid: catalogues of 2 to 65 535 clamps at finite poses with
/// unit rotations, strictly ascending lengths, blocks that follow each other; a shard's
/// index is below its count.
fn check_links(header: &Header) -> Result<(), Problem> {
    let mut next = 0u64;
    if header.links.len() > usize::from(u16::MAX) {
        return Err(Problem::Header(format!(
            "{} link entries, at most {}",
            header.links.len(),
            u16::MAX
        )));
    }
    for entry in &header.links {
        let name = format!("link {}", entry.link);
        if entry.clamps.len() < 2 || entry.clamps.len() > usize::from(u16::MAX) {
            return Err(Problem::Header(format!(
                "{name} has {} clamps, not 2 to {}",
                entry.clamps.len(),
                u16::MAX
            )));
        }
        if let Some(clamp) = entry.clamps.iter().find(|c| !c.is_well_formed()) {
            return Err(Problem::Header(format!(
                "{name}: clamp '{}' has a non-finite position or a rotation that is not a unit \
                 quaternion",
                clamp.name
            )));
        }
        if entry.lengths.is_empty() || entry.lengths.windows(2).any(|w| w[0] >= w[1]) {
            return Err(Problem::Header(format!(
                "{name}: lengths are not strictly ascending"
            )));
        }
        if entry
            .margin_error
            .iter()
            .any(|e| !(e.is_finite() && *e >= 0.0))
        {
            return Err(Problem::Header(format!(
                "{name}: the interpolation error bound {:?} is not finite and non-negative",
                entry.margin_error
            )));
        }
        if entry.first_pv != next {
            return Err(Problem::Header(format!(
                "{name} starts at PV {}, the previous links end at {next}",
                entry.first_pv
            )));
        }
        next = entry
            .checked_pv_count()
            .and_then(|count| next.checked_add(count))
            .ok_or_else(|| Problem::Header(format!("{name}: the PV count overflows")))?;
    }
    if let Some(shard) = header.shard
        && shard.index >= shard.count
    {
        return Err(Problem::Header(format!(
            "shard {}/{}: the index is not below the count",
            shard.index, shard.count
        )));
    }
    Ok(())
}

fn check_checksum(kind: SectionKind, bytes: &[u8], stored: u64) -> Result<(), Problem> {
    check_bytes(&format!("section '{}'", kind.name()), bytes, stored)
}

fn check_bytes(place: &str, bytes: &[u8], stored: u64) -> Result<(), Problem> {
    let computed = xxh3_64(bytes);
    if computed == stored {
        Ok(())
    } else {
        Err(Problem::Checksum {
            place: place.into(),
            stored,
            computed,
        })
    }
}

fn layout(place: String, detail: String) -> Problem {
    Problem::Layout { place, detail }
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    let mut word = [0u8; 4];
    word.copy_from_slice(&bytes[at..at + 4]);
    u32::from_le_bytes(word)
}

fn u64_at(bytes: &[u8], at: usize) -> u64 {
    let mut word = [0u8; 8];
    word.copy_from_slice(&bytes[at..at + 8]);
    u64::from_le_bytes(word)
}
