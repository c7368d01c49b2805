//! `cable-dict merge`: shards of one build → the whole dictionary, byte for byte the one a
//! single build writes.

use super::build::Built;
use super::error::{DictionaryError, Problem};
use super::format::{Header, ShardRange};
use super::reader::{Dictionary, embedded_setup};
use crate::attachment::MARGIN_COUNT;
#[cfg(feature = "signatures")]
use crate::provenance::TrustedKeys;
use std::path::PathBuf;

/// Merges the shard files `paths` (any order). Each is verified; they must come from one
/// build (same header apart from the shard range, same shard count) and cover every PV
/// exactly once.
pub fn merge(paths: &[PathBuf]) -> Result<Built, DictionaryError> {
    merge_accepting(paths, |_| Ok(()))
}

/// [`merge`], and each shard must carry a signature by one of the `trusted` keys.
#[cfg(feature = "signatures")]
pub fn merge_signed_by(paths: &[PathBuf], trusted: &TrustedKeys) -> Result<Built, DictionaryError> {
    merge_accepting(paths, |shard| {
        shard
            .provenance(Some(trusted))?
            .require_trusted(shard.path())?;
        Ok(())
    })
}

/// [`merge`], each verified shard first passed to `accept`.
fn merge_accepting(
    paths: &[PathBuf],
    accept: impl Fn(&Dictionary) -> Result<(), DictionaryError>,
) -> Result<Built, DictionaryError> {
    let mut shards = Vec::with_capacity(paths.len());
    for path in paths {
        // Read into memory: the bytes verified and signed are the bytes merged.
        let dictionary = Dictionary::read(path)?;
        dictionary.verify()?;
        accept(&dictionary)?;
        let Some(range) = dictionary.header().shard else {
            return Err(merge_error(path, "a whole dictionary, not a shard".into()));
        };
        shards.push((range, dictionary));
    }
    shards.sort_by_key(|(range, _)| (range.first_pv, range.end_pv));
    let Some((_, first)) = shards.first() else {
        return Err(DictionaryError::new(
            "(no files)",
            Problem::Merge("no shards given".into()),
        ));
    };
    let common = unsharded(first.header());
    for (range, shard) in &shards {
        if let Some(difference) = difference(&common, &unsharded(shard.header())) {
            return Err(merge_error(
                shard.path(),
                format!(
                    "does not belong with {}: {difference}",
                    first.path().display()
                ),
            ));
        }
        let count = shards[0].0.count;
        if range.count != count {
            return Err(merge_error(
                shard.path(),
                format!(
                    "is shard {}/{}, the others are of {count}",
                    range.index, range.count
                ),
            ));
        }
    }
    check_tiling(&shards, common.pv_total)?;
    let mut common = common;
    merged_error_bounds(&mut common, &shards);
    let setup = embedded_setup(&common).map_err(|p| DictionaryError::new(first.path(), p))?;
    let mut built = Built {
        header: common,
        directions: first.directions().to_vec(),
        pvs: shards
            .iter()
            .flat_map(|(_, s)| s.pv_records().iter().copied())
            .collect(),
        results: shards
            .iter()
            .flat_map(|(_, s)| s.results().iter().copied())
            .collect(),
    };
    built.derive_flags(&setup.robustness);
    Ok(built)
}

/// The header as a whole dictionary's, before its D1/D2 counts and error bounds are known
/// (each shard measured the interpolation error of its own PVs).
fn unsharded(header: &Header) -> Header {
    let mut whole = Header {
        shard: None,
        ..header.clone()
    };
    for entry in &mut whole.links {
        entry.margin_error = [0.0; MARGIN_COUNT];
    }
    whole
}

/// The error bound of each link of the whole dictionary: the largest of the shards'.
fn merged_error_bounds(common: &mut Header, shards: &[(ShardRange, Dictionary)]) {
    for (slot, entry) in common.links.iter_mut().enumerate() {
        for (_, shard) in shards {
            let bounds = shard.header().links[slot].margin_error;
            for (merged, bound) in entry.margin_error.iter_mut().zip(bounds) {
                *merged = merged.max(bound);
            }
        }
    }
}

/// What differs between two shards' headers, for people; `None` when nothing does.
fn difference(a: &Header, b: &Header) -> Option<String> {
    if a == b {
        return None;
    }
    Some(if a.setup_hash != b.setup_hash {
        format!(
            "another setup (hash {:016x}, not {:016x})",
            b.setup_hash, a.setup_hash
        )
    } else if a.directions != b.directions {
        format!(
            "another direction set ({} directions, not {})",
            b.directions.count, a.directions.count
        )
    } else if a.physics_version != b.physics_version || a.solver != b.solver {
        "built by another cable-dict (physics version or solver settings differ)".into()
    } else {
        "the headers differ".into()
    })
}

/// The sorted shards cover `0..total` without gap or overlap.
fn check_tiling(shards: &[(ShardRange, Dictionary)], total: u64) -> Result<(), DictionaryError> {
    let mut next = 0;
    for (range, shard) in shards {
        if range.first_pv < next {
            return Err(merge_error(
                shard.path(),
                format!(
                    "shard {}/{} (PVs {}..{}) overlaps another shard",
                    range.index, range.count, range.first_pv, range.end_pv
                ),
            ));
        }
        if range.first_pv > next {
            return Err(merge_error(
                shard.path(),
                format!(
                    "PVs {next}..{} are missing before shard {}/{}: a shard was left out",
                    range.first_pv, range.index, range.count
                ),
            ));
        }
        next = range.end_pv;
    }
    if next != total {
        let path = shards
            .last()
            .map_or_else(PathBuf::new, |(_, s)| s.path().into());
        return Err(merge_error(
            &path,
            format!("PVs {next}..{total} are missing: a shard was left out"),
        ));
    }
    Ok(())
}

fn merge_error(path: &std::path::Path, detail: String) -> DictionaryError {
    DictionaryError::new(path, Problem::Merge(detail))
}
