//! What can be wrong with a dictionary file, a build or a merge — each case its own variant,
//! so that callers (and tests) can tell them apart, and every message names the file.

use std::path::PathBuf;

/// A dictionary operation failed on `path`.
#[derive(Debug, thiserror::Error)]
#[error("{}: {problem}", path.display())]
pub struct DictionaryError {
    /// The file concerned (a dictionary, a shard or a setup).
    pub path: PathBuf,
    /// What is wrong.
    pub problem: Problem,
}

impl DictionaryError {
    /// `problem` with `path`.
    pub fn new(path: impl Into<PathBuf>, problem: Problem) -> Self {
        Self {
            path: path.into(),
            problem,
        }
    }
}

/// The specific failure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Problem {
    /// The file could not be read or mapped.
    #[error("cannot read it: {0}")]
    Io(String),
    /// The file could not be written.
    #[error("cannot write it: {0}")]
    Write(String),
    /// Too short for a preamble, or the magic bytes are not a dictionary's.
    #[error("not a cable-dict dictionary: {0}")]
    NotADictionary(String),
    /// Written by a newer cable-dict.
    #[error(
        "format version {found} is newer than this cable-dict reads (version {supported}); \
         open it with a newer cable-dict"
    )]
    FutureVersion {
        /// The file's version.
        found: u32,
        /// The newest version this build reads.
        supported: u32,
    },
    /// Written by an older cable-dict in a format this one no longer reads.
    #[error(
        "format version {found} is no longer read; this cable-dict reads version 4 (margins, \
         the twist's among them, per direction for every pair of clamps of each link's \
         catalogue): rebuild it from the \
         setup it was built for with `cable-dict build SETUP.toml -o FILE.cdict` (`cable-dict \
         info` on it with the cable-dict that wrote it names that setup)"
    )]
    OldVersion {
        /// The file's version.
        found: u32,
    },
    /// A version number no cable-dict ever wrote.
    #[error("format version {found} is not a known version (this cable-dict reads {supported})")]
    UnknownVersion {
        /// The file's version.
        found: u32,
        /// The version this build reads.
        supported: u32,
    },
    /// The file is shorter or longer than its preamble says (e.g. an interrupted copy).
    #[error(
        "the preamble says the file has {expected} bytes, it has {actual}: truncated or \
         appended to"
    )]
    Length {
        /// Bytes the preamble announces.
        expected: u64,
        /// Bytes on disk.
        actual: u64,
    },
    /// A checksum does not match the bytes it covers.
    #[error(
        "{place}: checksum mismatch (stored {stored:016x}, computed {computed:016x}); the file \
         is damaged"
    )]
    Checksum {
        /// `preamble`, `section table` or `section 'results'`, …
        place: String,
        /// The checksum in the file.
        stored: u64,
        /// The checksum of the bytes.
        computed: u64,
    },
    /// A section is missing, duplicated, out of bounds, misaligned or of the wrong size.
    #[error("{place}: {detail}")]
    Layout {
        /// Where, e.g. `section table entry 3`.
        place: String,
        /// What is wrong.
        detail: String,
    },
    /// The header section does not decode, or contradicts the other sections.
    #[error("header: {0}")]
    Header(String),
    /// The embedded setup does not load.
    #[error("embedded setup: {0}")]
    Setup(String),
    /// The embedded setup's content hash differs from the one the header records.
    #[error(
        "the embedded setup hashes to {computed:016x}, the header records {stored:016x}: the \
         header was altered or written by an incompatible cable-dict"
    )]
    SetupHash {
        /// Hash in the header.
        stored: u64,
        /// Hash of the embedded texts.
        computed: u64,
    },
    /// The dictionary does not fit what was asked of it (another setup, a motion, a shard).
    #[error("{0}")]
    Mismatch(String),
    /// A shard given where a whole dictionary is needed.
    #[error(
        "this is shard {index}/{count} of a build, not a whole dictionary; merge the shards \
         first (cable-dict merge)"
    )]
    Shard {
        /// 0-based shard index.
        index: u32,
        /// Number of shards.
        count: u32,
    },
    /// Shards that do not make one dictionary.
    #[error("{0}")]
    Merge(String),
    /// The build cannot run for this setup or these options.
    #[error("{0}")]
    Build(String),
    /// A signature that does not hold, or a signature required and missing.
    #[error("{0}")]
    Provenance(String),
}

impl From<crate::provenance::ProvenanceError> for DictionaryError {
    /// Names the file the provenance error blames (the signature file, or the dictionary).
    fn from(error: crate::provenance::ProvenanceError) -> Self {
        let at = error
            .line
            .map(|l| format!("line {l}: "))
            .unwrap_or_default();
        DictionaryError::new(error.file, Problem::Provenance(at + &error.problem))
    }
}
