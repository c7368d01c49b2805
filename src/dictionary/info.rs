//! What `cable-dict info` shows of a dictionary: build parameters, the embedded setup and
//! per-link catalogue sizes, read from the header and the PV flags (no checksum pass).

use super::format::{FORMAT_VERSION, PvRecord};
use super::reader::{Dictionary, embedded_setup};
use crate::attachment::MarginValues;
use serde::Serialize;

/// A dictionary's description.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Info {
    /// The file.
    pub file: String,
    /// Its size (bytes).
    pub file_bytes: usize,
    /// `.cdict` format version.
    pub format_version: u32,
    /// Physics version of the stored results.
    pub physics_version: u32,
    /// Setup file name as built.
    pub setup_file: String,
    /// Content hash of the setup (16 hex digits).
    pub setup_hash: String,
    /// Robot name, or why the embedded setup does not load.
    pub robot: String,
    /// Cable name (empty when the setup does not load).
    pub cable: String,
    /// Sampled directions N.
    pub directions: u32,
    /// Direction sampling method.
    pub direction_method: String,
    /// Probe directions of the error measurement.
    pub probes: u32,
    /// Neighbourhood radius of the lookup (deg).
    pub covering_radius_deg: f64,
    /// Connected geometry and solver of the build.
    pub solver: String,
    /// `i/n` for a shard, `None` for a whole dictionary.
    pub shard: Option<String>,
    /// PVs in a whole dictionary.
    pub pv_total: u64,
    /// PV records in this file.
    pub pv_records: usize,
    /// Mesh files embedded with the URDF.
    pub mesh_files: usize,
    /// The links' clamp catalogues.
    pub links: Vec<LinkInfo>,
    /// Who signed the file (`None` until the caller checks the signatures:
    /// [`Dictionary::provenance`], or when they do not hold).
    pub provenance: Option<crate::provenance::Provenance>,
    /// Why the signatures beside the file do not hold, when they do not.
    pub signature_problem: Option<String>,
}

/// One link's clamp catalogue in a dictionary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinkInfo {
    /// The link (URDF name).
    pub link: String,
    /// Stored lengths (sub-segments), shortest and longest.
    pub lengths: [u32; 2],
    /// Number of stored lengths.
    pub length_count: usize,
    /// Clamp places.
    pub clamps: usize,
    /// PV records (grid cells) of the link: clamps × clamps × lengths.
    pub pvs: u64,
    /// Candidate PVs (admissible, with a candidate length) held in this file.
    pub candidates: usize,
    /// |D1| for every stored direction (0 in a shard).
    pub d1_all: u64,
    /// |D2| for every stored direction (0 in a shard).
    pub d2_all: u64,
    /// The lookup's error bound: clearance (mm), stretch, curvature (1/m).
    pub margin_error: MarginValues,
    /// Share of the candidate pieces' lookups the dictionary cannot decide (the exact check
    /// then solves them), over gravity directions spread over the sphere
    /// ([`Dictionary::undecided_share`]); `None` without candidates (and in a shard).
    pub undecided_share: Option<f64>,
}

impl Info {
    /// Describes `dictionary`.
    pub fn of(dictionary: &Dictionary) -> Info {
        let header = dictionary.header();
        let (robot, cable) = match embedded_setup(header) {
            Ok(setup) => (setup.robot.name, setup.cable.name),
            Err(problem) => (format!("(embedded setup: {problem})"), String::new()),
        };
        let records = dictionary.pv_records();
        let links = header
            .links
            .iter()
            .enumerate()
            .map(|(slot, e)| {
                let candidates = records
                    .iter()
                    .filter(|r| usize::from(r.link) == slot && r.has(PvRecord::CANDIDATE))
                    .count();
                LinkInfo {
                    link: e.link.clone(),
                    lengths: [
                        e.lengths.first().copied().unwrap_or(0),
                        e.lengths.last().copied().unwrap_or(0),
                    ],
                    length_count: e.lengths.len(),
                    clamps: e.clamps.len(),
                    pvs: e.pv_count(),
                    candidates,
                    d1_all: e.d1_all,
                    d2_all: e.d2_all,
                    margin_error: e.margin_error,
                    undecided_share: match header.shard {
                        Some(_) => None,
                        None => dictionary.undecided_share(slot),
                    },
                }
            })
            .collect();
        let solver = &header.solver;
        Info {
            file: dictionary.path().display().to_string(),
            file_bytes: dictionary.file_len(),
            format_version: FORMAT_VERSION,
            physics_version: header.physics_version,
            setup_file: header.setup.file_name.clone(),
            setup_hash: format!("{:016x}", header.setup_hash),
            robot,
            cable,
            directions: header.directions.count,
            direction_method: header.directions.method.clone(),
            probes: header.directions.probes,
            covering_radius_deg: header.directions.covering_radius_rad.to_degrees(),
            solver: format!(
                "{} connect, Newton to {:e} N in ≤ {} iterations, clearance to the {}",
                solver.connect,
                solver.force_tolerance_n,
                solver.max_iterations,
                solver.clearance_links
            ),
            shard: header.shard.map(|s| format!("{}/{}", s.index, s.count)),
            pv_total: header.pv_total,
            pv_records: records.len(),
            mesh_files: header.setup.meshes.len(),
            links,
            provenance: None,
            signature_problem: None,
        }
    }
}
