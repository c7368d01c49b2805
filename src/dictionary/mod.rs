//! Dictionaries: the motion-independent part of the attachment test, computed
//! once per robot + cable + guide catalogue and shared as a `.cdict` file.
//!
//! An intra-link segment's shape depends only on gravity's direction in its link's frame. A
//! build gathers the clamp places of each link from all of the setup's guides on it (the
//! link's catalogue, [`link_catalogues`]) and evaluates every ordered pair of places × every
//! length (the candidate lengths of the setup's intra-link segments and their robustness
//! neighbours) under N gravity directions sampled on the sphere ([`directions`]); it stores,
//! per piece and direction, the three margins ([`format`](mod@format)), plus the
//! interpolation error measured at probe directions between them. Any setup of the same
//! robot, cable, gravity, limits and installation pose whose intra-link guides take their
//! places from the catalogues can use the file ([`MotionLookup::new`] checks and maps them,
//! naming the first thing that differs). Solving a motion asks the
//! question `solve --setup` answers exactly — does the piece hold its limits under every
//! gravity direction the motion produces in its link's frame — by interpolating the margins
//! at those directions, widened by the error bound; only pieces the bound cannot decide are
//! solved ([`MotionLookup`]).
//!
//! - [`build()`]: the whole dictionary or one shard (`--shard i/n`), in parallel, the same
//!   bytes at any thread count.
//! - [`Dictionary::open`]: a memory map with O(1) structural checks; [`Dictionary::verify`]
//!   checks every checksum and record.
//! - [`merge()`]: shards → the whole dictionary, the same bytes as a single build
//!   (`merge_signed_by`: each shard signed by a trusted key).
//! - [`write_dictionary`]: atomic replacement (temporary file, fsync, rename).
//!
//! The byte layout is documented in docs/cdict-format.md.

mod build;
mod catalogue;
mod derive;
pub mod directions;
mod error;
pub mod format;
mod info;
mod lookup;
mod merge;
mod reader;
mod recompute;

pub use build::{BuildOptions, Built, MAX_RESULT_BYTES, build};
pub use catalogue::{LinkCatalogue, link_catalogues};
pub use directions::DEFAULT_DIRECTION_COUNT;
pub use error::{DictionaryError, Problem};
pub use info::{Info, LinkInfo};
pub use lookup::{
    DirectionAnswer, LookupError, MotionLookup, StoredSegment, UNDECIDED_SAMPLE_DIRECTIONS,
};
pub use merge::merge;
#[cfg(feature = "signatures")]
pub use merge::merge_signed_by;
pub use reader::Dictionary;
pub use recompute::{Disagreement, RECOMPUTE_TOLERANCE_UNITS, RecomputeChoice, Recomputed};

use crate::atomic_file::write_atomically;
use std::path::Path;

/// Encodes `built` and replaces `path` with it atomically: readers (and an interrupted
/// writer) never leave a file that opens half-written.
pub fn write_dictionary(path: &Path, built: &Built) -> Result<(), DictionaryError> {
    let bytes = built
        .to_bytes()
        .map_err(|problem| DictionaryError::new(path, problem))?;
    write_atomically(path, &bytes)
        .map_err(|e| DictionaryError::new(path, Problem::Write(e.to_string())))
}

/// Every check [`Dictionary::verify`] makes, on bytes in memory (any alignment): the
/// structure, every checksum, every record and the meaning of the header. For fuzzing and
/// for tools that hold a file in memory.
pub fn check_bytes(bytes: &[u8]) -> Result<format::Header, Problem> {
    let dictionary = Dictionary::from_bytes(bytes, "memory").map_err(|e| e.problem)?;
    dictionary.verify().map_err(|e| e.problem)?;
    Ok(dictionary.header().clone())
}
