//! The one reader of result JSONs (`solve --json`, `-o`, a report's result.json) for the
//! commands that take a path from one: `export-scene --result` and `check`. A result from
//! another team is untrusted input: size-bounded, parsed into the types that wrote it, every
//! index checked against the setup before use ([`CablePath::check`]).

use super::output::Failure;
use cable_dict::motion_test::EngineKind;
use cable_dict::path::CablePath;
use cable_dict::solve::{CandidateOutcome, shown_index};
use std::path::{Path, PathBuf};

/// What the commands read of a result JSON.
pub struct ResultFile {
    file: PathBuf,
    read: ResultCandidates,
}

/// A candidate of a result, as chosen.
pub struct Chosen {
    /// Its path (indices into the setup it was solved with).
    pub path: CablePath,
    /// `candidate 3 (650 mm) passed the motion test`: what the solve found for it.
    pub motion_test: String,
}

/// The part of a result JSON the commands read, with the types that wrote it.
#[derive(serde::Deserialize)]
struct ResultCandidates {
    candidates: Vec<CandidateOutcome>,
    /// Absent in results written before it existed.
    #[serde(default)]
    unsolved: Option<ResultUnsolved>,
    /// Read by `check` only (`export-scene` takes any result that lists candidates).
    #[serde(default)]
    inputs: Option<ResultInputs>,
    /// Absent when the solve ran no motion test.
    #[serde(default)]
    motion_test: Option<ResultMotionTest>,
}

/// `inputs` of a result JSON: which setup it was solved with.
#[derive(serde::Deserialize)]
struct ResultInputs {
    setup_file: String,
    setup_hash: String,
}

/// `motion_test.engine` of a result JSON.
#[derive(serde::Deserialize)]
struct ResultMotionTest {
    engine: EngineKind,
}

/// `unsolved.closest.candidate` of a result JSON: the candidate shown when none passed.
#[derive(serde::Deserialize)]
struct ResultUnsolved {
    closest: Option<ResultClosest>,
}

/// See [`ResultUnsolved`].
#[derive(serde::Deserialize)]
struct ResultClosest {
    candidate: usize,
}

impl ResultFile {
    /// Reads `file`; a file that is not a result JSON is invalid input, named.
    pub fn read(file: &Path) -> Result<ResultFile, Failure> {
        let fail = |what: String| Failure::input(anyhow::anyhow!("{}: {what}", file.display()));
        let text = cable_dict::input::read_text(file, cable_dict::input::RESULT).map_err(fail)?;
        let read = serde_json::from_str(&text)
            .map_err(|e| fail(format!("not a cable-dict result JSON: {e}")))?;
        Ok(ResultFile {
            file: file.to_path_buf(),
            read,
        })
    }

    /// Candidate `rank`, or the one the result shows (the one that passed, else the closest
    /// miss, else the last tried), with a line saying what the motion test found for it: a
    /// piece can hold its limits at one pose and still fail along the motion.
    pub fn chosen(&self, rank: Option<usize>) -> Result<Chosen, Failure> {
        let fail =
            |what: String| Failure::input(anyhow::anyhow!("{}: {what}", self.file.display()));
        let candidates = &self.read.candidates;
        let chosen = match rank {
            Some(rank) => candidates.iter().find(|c| c.rank == rank),
            None => {
                let closest = (self.read.unsolved.as_ref())
                    .and_then(|u| u.closest.as_ref())
                    .map(|c| c.candidate);
                shown_index(candidates.iter().map(|c| c.passed), closest).map(|i| &candidates[i])
            }
        };
        let chosen = chosen.ok_or_else(|| match rank {
            Some(rank) => fail(format!(
                "no candidate of rank {rank} (it lists {})",
                candidates.len()
            )),
            None => fail("it lists no candidate: the solve found no chain".into()),
        })?;
        let mut path = chosen.path.clone();
        if path.segments.is_empty() {
            // Results written before spans existed list no segments: one per guide pair.
            path.segments = (0..path.lengths.len()).collect();
        }
        let name = format!(
            "candidate {} ({:.0} mm)",
            chosen.rank, chosen.total_length_mm
        );
        let motion_test = match (chosen.passed, &chosen.failure) {
            (Some(true), _) => format!("{name} passed the motion test"),
            (Some(false), Some(why)) => format!("{name} FAILED the motion test: {why}"),
            (Some(false), None) => format!("{name} FAILED the motion test"),
            (None, _) => format!("{name} was not motion-tested"),
        };
        Ok(Chosen { path, motion_test })
    }

    /// The setup file the result names, as found: as written (relative to the current
    /// folder), else relative to the result's folder.
    pub fn setup_file(&self) -> Result<PathBuf, Failure> {
        let inputs = self.read.inputs.as_ref().ok_or_else(|| {
            Failure::input(anyhow::anyhow!(
                "{}: it names no setup (no `inputs`): give it with --setup",
                self.file.display()
            ))
        })?;
        let named = PathBuf::from(&inputs.setup_file);
        let beside = self.file.parent().map(|folder| folder.join(&named));
        let found = std::iter::once(named.clone())
            .chain(beside)
            .find(|path| path.is_file());
        found.ok_or_else(|| {
            Failure::input(anyhow::anyhow!(
                "{}: the setup it was solved with, {}, is not found (from here or beside \
                 the result): give it with --setup",
                self.file.display(),
                named.display()
            ))
        })
    }

    /// The content hash of the setup it was solved with (after the solve's options).
    pub fn setup_hash(&self) -> Option<&str> {
        self.read.inputs.as_ref().map(|i| i.setup_hash.as_str())
    }

    /// What simulated the cable in its motion tests (`None`: none ran).
    pub fn engine(&self) -> Option<EngineKind> {
        self.read.motion_test.as_ref().map(|m| m.engine)
    }
}
