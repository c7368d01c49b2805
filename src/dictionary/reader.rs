//! Opening a dictionary: a memory map, the O(1) structural checks of [`parse`], and
//! zero-copy access to its records; [`Dictionary::verify`] checks every byte.

use super::catalogue::LinkCatalogue;
use super::derive::{check_derivation, check_file_name, check_flags, pv_at};
use super::error::{DictionaryError, Problem};
use super::format::{
    Header, Layout, LinkEntry, MarginRecord, PHYSICS_VERSION, PvRecord, SectionKind, parse,
    verify_sections,
};
use crate::attachment::{MARGIN_COUNT, MarginValues};
use crate::path::Pv;
#[cfg(feature = "signatures")]
use crate::provenance::{Provenance, ProvenanceError, SecretKey, TrustedKeys};
use crate::robot::MeshFile;
use crate::setup::Setup;
use memmap2::Mmap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// An open dictionary: a file mapped into memory, or bytes held in memory; the same checks
/// and the same in-place reading either way.
#[derive(Debug)]
pub struct Dictionary {
    path: PathBuf,
    map: Bytes,
    layout: Layout,
    /// The embedded setup, loaded once (parsing the URDF and meshes is the costly part of
    /// `verify` and of every caller that needs the setup).
    embedded: OnceLock<Setup>,
    /// Set once [`Dictionary::verify`] has passed, so that a second call (e.g. by
    /// [`Dictionary::recompute`] after the command line's) is free: files are replaced by
    /// rename, never changed in place — and a run that must not depend on that reads the file
    /// into memory ([`Dictionary::read`]).
    verified: OnceLock<()>,
}

impl Dictionary {
    /// Maps `path` and checks its structure (magic, version, length, preamble and table
    /// checksums, section bounds, record sizes, the header). Cost: independent of the size of
    /// the bulk sections.
    pub fn open(path: impl AsRef<Path>) -> Result<Dictionary, DictionaryError> {
        let path = path.as_ref();
        let error = |problem| DictionaryError::new(path, problem);
        let file = File::open(path).map_err(|e| error(Problem::Io(e.to_string())))?;
        // SAFETY: the map is read-only and dictionaries are immutable once written: builds
        // and merges replace files by rename, never in place. A file truncated by another
        // process while mapped would fault, as with any mapped reader.
        let map = unsafe { Mmap::map(&file) }.map_err(|e| error(Problem::Io(e.to_string())))?;
        Dictionary::over(path, Bytes::Mapped(map))
    }

    /// The dictionary in `path` read into private memory, with [`Dictionary::open`]'s checks:
    /// what is checked afterwards — [`Dictionary::verify`], the signatures — is what every
    /// lookup reads, whatever happens to the file meanwhile (a file changed in place under a
    /// memory map would change what a run reads after its signature was checked). What a
    /// run that trusts the file opens; it holds the whole file (the length its header
    /// declares, checked before the copy).
    pub fn read(path: impl AsRef<Path>) -> Result<Dictionary, DictionaryError> {
        let mapped = Dictionary::open(&path)?;
        Dictionary::from_bytes(&mapped.map[..], path)
    }

    /// The dictionary in `bytes` (any alignment: they are copied once into memory aligned for
    /// in-place reading), named `name` in its errors; the same checks as [`Dictionary::open`].
    pub fn from_bytes(bytes: &[u8], name: impl AsRef<Path>) -> Result<Dictionary, DictionaryError> {
        let mut words = vec![0u64; bytes.len().div_ceil(size_of::<u64>())];
        bytemuck::cast_slice_mut::<u64, u8>(&mut words)[..bytes.len()].copy_from_slice(bytes);
        Dictionary::over(name.as_ref(), Bytes::Memory(words, bytes.len()))
    }

    fn over(path: &Path, map: Bytes) -> Result<Dictionary, DictionaryError> {
        let error = |problem| DictionaryError::new(path, problem);
        let layout = parse(&map).map_err(error)?;
        check_alignment(&map, &layout).map_err(error)?;
        Ok(Dictionary {
            path: path.to_path_buf(),
            map,
            layout,
            embedded: OnceLock::new(),
            verified: OnceLock::new(),
        })
    }

    #[cfg(feature = "signatures")]
    /// Who signed this file ([`crate::provenance::check`]: every signature beside it must
    /// hold for these bytes), its signers looked up in `trusted`.
    pub fn provenance(&self, trusted: Option<&TrustedKeys>) -> Result<Provenance, ProvenanceError> {
        crate::provenance::check(&self.path, &self.map, trusted)
    }

    #[cfg(feature = "signatures")]
    /// Signs this file with `key` ([`crate::provenance::sign`]).
    pub fn sign(&self, key: &SecretKey) -> Result<Provenance, ProvenanceError> {
        crate::provenance::sign(&self.path, &self.map, key)
    }

    /// The file it was opened from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The decoded header.
    pub fn header(&self) -> &Header {
        &self.layout.header
    }

    /// Size of the file (bytes).
    pub fn file_len(&self) -> usize {
        self.map.len()
    }

    /// The sampled gravity directions (unit vectors in the link frame).
    pub fn directions(&self) -> &[[f64; 3]] {
        bytemuck::cast_slice(self.section(SectionKind::Directions))
    }

    /// The PV records this file holds.
    pub fn pv_records(&self) -> &[PvRecord] {
        bytemuck::cast_slice(self.section(SectionKind::Pvs))
    }

    /// The margin records, `directions().len()` per PV record.
    pub fn results(&self) -> &[MarginRecord] {
        bytemuck::cast_slice(self.section(SectionKind::Results))
    }

    /// The position in [`Header::links`] of the catalogue of the link called `link`.
    pub fn link_slot(&self, link: &str) -> Option<usize> {
        self.header().links.iter().position(|e| e.link == link)
    }

    /// The catalogue entry at position `slot`.
    pub fn link(&self, slot: usize) -> Option<&LinkEntry> {
        self.header().links.get(slot)
    }

    /// The record and stored margins of piece `pv` (clamp indices of the catalogue) of the
    /// link at `slot`, one row per direction; `None` when the dictionary does not hold it.
    /// O(log lengths).
    pub fn lookup(&self, slot: usize, pv: &Pv) -> Option<(&PvRecord, &[MarginRecord])> {
        let entry = self.link(slot)?;
        let local = entry.grid_index(pv.sub_segments, pv.start, pv.end)?;
        let stored = self.header().stored_pvs();
        let g = usize::try_from((entry.first_pv + local).checked_sub(stored.start)?).ok()?;
        let n = self.directions().len();
        let first = g.checked_mul(n)?;
        let rows = self.results().get(first..first.checked_add(n)?)?;
        Some((self.pv_records().get(g)?, rows))
    }

    /// Checks every section's checksum, that the records agree with the header (grid
    /// positions, flags, margin records, the all-directions |D1| and |D2| counts, the error
    /// bounds) and what the header means ([`check_setup_meaning`]).
    pub fn verify(&self) -> Result<(), DictionaryError> {
        if self.verified.get().is_some() {
            return Ok(());
        }
        let error = |problem| DictionaryError::new(&self.path, problem);
        verify_sections(&self.map, &self.layout).map_err(error)?;
        check_records(self.header(), self.pv_records(), self.results()).map_err(error)?;
        let setup = self.embedded().map_err(error)?;
        let catalogues =
            check_setup_meaning(self.header(), self.directions(), setup).map_err(error)?;
        let (header, records) = (self.header(), self.pv_records());
        check_flags(setup, &catalogues, header, records, self.results()).map_err(error)?;
        let _ = self.verified.set(());
        Ok(())
    }

    /// The embedded setup, loaded on first use and checked against the header's hash.
    pub(super) fn embedded(&self) -> Result<&Setup, Problem> {
        if let Some(setup) = self.embedded.get() {
            return Ok(setup);
        }
        let setup = embedded_setup(self.header())?;
        Ok(self.embedded.get_or_init(|| setup))
    }

    /// The embedded setup, loaded and checked against the header's content hash; refuses a
    /// shard and a dictionary of another physics version.
    pub fn setup(&self) -> Result<Setup, DictionaryError> {
        let error = |problem| DictionaryError::new(&self.path, problem);
        let header = self.header();
        if let Some(shard) = header.shard {
            return Err(error(Problem::Shard {
                index: shard.index,
                count: shard.count,
            }));
        }
        let setup = self.embedded().map_err(error)?;
        check_physics_version(header).map_err(error)?;
        Ok(setup.clone())
    }

    fn section(&self, kind: SectionKind) -> &[u8] {
        &self.map[self.layout.range(kind)]
    }
}

/// The bytes a [`Dictionary`] reads: a read-only map of its file, or memory aligned for the
/// widest record field (8 bytes) holding the first `len` bytes of its words.
#[derive(Debug)]
enum Bytes {
    Mapped(Mmap),
    Memory(Vec<u64>, usize),
}

impl std::ops::Deref for Bytes {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match self {
            Bytes::Mapped(map) => map,
            Bytes::Memory(words, len) => &bytemuck::cast_slice(words)[..*len],
        }
    }
}

/// The records agree with the header: grid positions, zero padding, margin records, flags,
/// and (whole dictionaries) the |D1|/|D2| counts. `results` holds `header.directions.count`
/// rows per PV record, as [`parse`] checked.
fn check_records(
    header: &Header,
    pv_records: &[PvRecord],
    results: &[MarginRecord],
) -> Result<(), Problem> {
    let stored = header.stored_pvs();
    let mut counts = vec![(0u64, 0u64); header.links.len()];
    let mut worst = vec![[0.0f64; MARGIN_COUNT]; header.links.len()];
    let n = usize::try_from(header.directions.count).unwrap_or(usize::MAX);
    for (k, record) in pv_records.iter().enumerate() {
        let g = stored.start + k as u64;
        let place = || format!("PV record {g}");
        let (slot, pv) = pv_at(header, g);
        let at_place = usize::from(record.link) == slot && record.pv() == pv;
        let unmeasured = !record.has(PvRecord::ADMISSIBLE)
            || record.sub_segments == 0
            || record.has(PvRecord::TOO_SHORT);
        if !at_place || (unmeasured && record.error_factor != [0; MARGIN_COUNT]) {
            return Err(record_error(place(), "does not match its grid position"));
        }
        let rows = results.get(k * n..(k + 1) * n).unwrap_or_default();
        check_results(record, rows).map_err(|detail| record_error(place(), &detail))?;
        for (w, factor) in worst[slot].iter_mut().zip(record.error_factors()) {
            *w = w.max(factor);
        }
        counts[slot].0 += u64::from(record.has(PvRecord::D1_ALL));
        counts[slot].1 += u64::from(record.has(PvRecord::D2_ALL));
    }
    for (entry, worst) in header.links.iter().zip(worst) {
        let bits = |e: MarginValues| e.map(f64::to_bits);
        if bits(entry.margin_error) != bits(worst) {
            return Err(Problem::Header(format!(
                "link {}: error bounds {:?} in the header, the records' largest are {worst:?}",
                entry.link, entry.margin_error
            )));
        }
    }
    if header.shard.is_some() {
        return Ok(());
    }
    for (entry, (d1, d2)) in header.links.iter().zip(counts) {
        if (d1, d2) != (entry.d1_all, entry.d2_all) {
            return Err(Problem::Header(format!(
                "link {}: |D1| {} and |D2| {} in the header, {d1} and {d2} flagged",
                entry.link, entry.d1_all, entry.d2_all
            )));
        }
    }
    Ok(())
}

/// The rows of one PV: well-formed margin records, measured only for a real cable that
/// reaches between its clamps, flags that the rows justify.
fn check_results(record: &PvRecord, rows: &[MarginRecord]) -> Result<(), String> {
    let cable = record.has(PvRecord::ADMISSIBLE)
        && record.sub_segments > 0
        && !record.has(PvRecord::TOO_SHORT);
    let mut all_hold = true;
    for (d, row) in rows.iter().enumerate() {
        let values = row.values();
        if !row.is_consistent() || (values.is_some() && !cable) {
            return Err(format!("direction {d}: inconsistent margin record"));
        }
        all_hold &= values.is_some_and(|v| v.iter().all(|&m| m >= 0.0));
    }
    let passes = record.has(PvRecord::ADMISSIBLE) && (record.sub_segments == 0 || all_hold);
    let d1 = record.has(PvRecord::D1_ALL);
    let d2 = record.has(PvRecord::D2_ALL);
    let short_ok = !record.has(PvRecord::TOO_SHORT)
        || (record.has(PvRecord::ADMISSIBLE) && record.sub_segments > 0);
    if record.flags & !PvRecord::KNOWN != 0
        || (d1 && !(passes && record.has(PvRecord::CANDIDATE)))
        || (d2 && !d1)
        || !short_ok
    {
        return Err(format!(
            "flags {:#06x} contradict its margins",
            record.flags
        ));
    }
    Ok(())
}

fn record_error(place: String, detail: &str) -> Problem {
    Problem::Layout {
        place,
        detail: detail.into(),
    }
}

/// Every record section starts at an address its records may be read from in place.
fn check_alignment(bytes: &[u8], layout: &Layout) -> Result<(), Problem> {
    let ok =
        bytemuck::try_cast_slice::<u8, [f64; 3]>(&bytes[layout.range(SectionKind::Directions)])
            .is_ok()
            && bytemuck::try_cast_slice::<u8, PvRecord>(&bytes[layout.range(SectionKind::Pvs)])
                .is_ok()
            && bytemuck::try_cast_slice::<u8, MarginRecord>(
                &bytes[layout.range(SectionKind::Results)],
            )
            .is_ok();
    if ok {
        Ok(())
    } else {
        Err(Problem::Layout {
            place: "memory map".into(),
            detail: "a section is not aligned for in-place reading".into(),
        })
    }
}

/// What the bytes mean, beyond their checksums: the physics version is this program's, and
/// the header and `directions` are what a build of the embedded `setup` (loaded and checked
/// against its hash) writes; the link catalogues that build makes, for the records' checks.
fn check_setup_meaning(
    header: &Header,
    directions: &[[f64; 3]],
    setup: &Setup,
) -> Result<Vec<LinkCatalogue>, Problem> {
    check_physics_version(header)?;
    check_derivation(header, directions, setup)
}

/// Margins of another physics version are not what this version would compute.
fn check_physics_version(header: &Header) -> Result<(), Problem> {
    if header.physics_version == PHYSICS_VERSION {
        return Ok(());
    }
    Err(Problem::Mismatch(format!(
        "built with physics version {}, this cable-dict computes version {PHYSICS_VERSION}: \
         rebuild it (cable-dict build)",
        header.physics_version
    )))
}

/// The setup embedded in `header`, with its content hash checked.
pub(super) fn embedded_setup(header: &Header) -> Result<Setup, Problem> {
    let embedded = &header.setup;
    check_file_name(&embedded.file_name)?;
    let setup = Setup::from_texts(
        &embedded.text,
        Path::new(&embedded.file_name),
        &embedded.robot_text,
        &embedded.cable_text,
        &embedded.meshes,
    )
    .map_err(|e| Problem::Setup(e.to_string()))?;
    if setup.content_hash != header.setup_hash {
        return Err(Problem::SetupHash {
            stored: header.setup_hash,
            computed: setup.content_hash,
        });
    }
    if let Some(problem) = meshes_not_read(&embedded.meshes, &setup.robot.mesh_files) {
        return Err(Problem::Header(problem));
    }
    Ok(setup)
}

/// What is wrong with the meshes a dictionary embeds, if anything, against those its robot
/// reads (`read`): bytes the robot does not read would ride along unchecked (and be written
/// out by any tool that unpacks the file) — a mesh under a URI the URDF does not use, or a
/// second copy under one it uses (only one is read). A build embeds each mesh it reads once.
fn meshes_not_read(embedded: &[MeshFile], read: &[MeshFile]) -> Option<String> {
    let mut uris = std::collections::BTreeSet::new();
    embedded.iter().find_map(|mesh| {
        let uri = crate::escape::terminal(&mesh.uri);
        if !read.iter().any(|r| r.uri == mesh.uri) {
            Some(format!(
                "the embedded mesh `{uri}` is not a mesh the embedded URDF uses (a build \
                 embeds only those)"
            ))
        } else if !uris.insert(mesh.uri.as_str()) {
            Some(format!(
                "the embedded mesh `{uri}` is embedded twice (a build embeds each mesh once)"
            ))
        } else {
            None
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(uri: &str) -> MeshFile {
        MeshFile {
            uri: uri.into(),
            bytes: vec![0; 84],
        }
    }

    /// Every mesh the robot reads, each once, passes; one it does not read, or a second copy
    /// of one it reads (which no reader would ever look at), is named.
    #[test]
    fn embedded_meshes_are_those_the_robot_reads_each_once() {
        let read = [mesh("base.stl"), mesh("arm.stl")];
        assert_eq!(meshes_not_read(&read, &read), None);
        let extra = [mesh("base.stl"), mesh("payload.stl")];
        let problem = meshes_not_read(&extra, &read).expect("payload.stl is not read");
        assert!(problem.contains("`payload.stl` is not a mesh the embedded URDF uses"));
        let twice = [mesh("base.stl"), mesh("arm.stl"), mesh("base.stl")];
        let problem = meshes_not_read(&twice, &read).expect("base.stl twice");
        assert!(
            problem.contains("`base.stl` is embedded twice"),
            "{problem}"
        );
    }
}
