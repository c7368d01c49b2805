//! `verify --recompute`: re-solving stored pieces from the embedded setup and comparing them
//! with the file. Checksums prove that the bytes are the ones written; only recomputation
//! shows that the margins in them are what this version's physics gives for the embedded
//! setup — not forged, not stale, not from a machine that computes differently.

use super::build::{DirectionSample, Pair, Piece, solve_lengths};
use super::catalogue::link_catalogues;
use super::derive::{catalogue_lengths, probe_count, pv_at};
use super::directions::probe_directions;
use super::error::{DictionaryError, Problem};
use super::format::{MARGIN_UNITS, MarginRecord, PvRecord};
use super::reader::Dictionary;
use crate::attachment::{ConnectMethod, Evaluator, MARGIN_COUNT};
use crate::progress;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt;

/// Which stored pieces to re-solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecomputeChoice {
    /// `count` pieces drawn at random (without repetition) with `seed`.
    Random {
        /// How many (all of them when the file holds fewer).
        count: usize,
        /// The draw's seed: the same seed draws the same pieces.
        seed: u64,
    },
    /// Every measured piece: as long as the build.
    All,
}

/// Stored and recomputed values may differ by this many fixed-point units per margin
/// (0.01 mm, 1e-5, 0.002 1/m) and error-factor steps (1/16): what a different rounding
/// order on another machine can change, far below what would change a verdict.
pub const RECOMPUTE_TOLERANCE_UNITS: i32 = 1;

/// The outcome of a recomputation.
#[derive(Debug, Clone, PartialEq)]
pub struct Recomputed {
    /// Pieces re-solved.
    pub checked: usize,
    /// Measured pieces in the file (those a choice draws from).
    pub measured: usize,
    /// The first re-solved piece (in record order) whose stored values disagree.
    pub disagreement: Option<Disagreement>,
}

/// A stored piece that does not match its recomputation.
#[derive(Debug, Clone, PartialEq)]
pub struct Disagreement {
    /// Global PV index of the record.
    pub record: u64,
    /// The link of its catalogue.
    pub link: String,
    /// Its start and end clamp places.
    pub clamps: (String, String),
    /// Its length (sub-segments).
    pub sub_segments: usize,
    /// What differs, stored against recomputed.
    pub what: String,
}

impl fmt::Display for Disagreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "PV record {} (link {}, clamps \"{}\" → \"{}\", S = {}): {}",
            self.record, self.link, self.clamps.0, self.clamps.1, self.sub_segments, self.what
        )
    }
}

impl Dictionary {
    /// Verifies the file ([`Dictionary::verify`]), then re-solves the pieces `choice`
    /// names from the embedded setup and compares them with the stored ones within
    /// [`RECOMPUTE_TOLERANCE_UNITS`].
    pub fn recompute(&self, choice: RecomputeChoice) -> Result<Recomputed, DictionaryError> {
        self.verify()?;
        let error = |problem| DictionaryError::new(self.path(), problem);
        let header = self.header();
        let setup = self.embedded().map_err(error)?;
        let (_, candidate_lengths) = catalogue_lengths(setup);
        let catalogues = link_catalogues(setup, &candidate_lengths);
        let evaluators = catalogues
            .iter()
            .map(|c| Evaluator::new(&c.setup, ConnectMethod::Hermite))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| error(Problem::Build(e.to_string())))?;
        let first = header.stored_pvs().start;
        let measured: Vec<u64> = (first..)
            .zip(self.pv_records())
            .filter(|(_, r)| r.has(PvRecord::ADMISSIBLE) && r.sub_segments > 0)
            .map(|(g, _)| g)
            .collect();
        let chosen = choose(&measured, choice);
        let mut pairs: BTreeMap<(usize, usize, usize), Vec<(u64, usize)>> = BTreeMap::new();
        for &g in &chosen {
            let (slot, pv) = pv_at(header, g);
            pairs
                .entry((slot, pv.start, pv.end))
                .or_default()
                .push((g, pv.sub_segments));
        }
        let count = header.directions.count as usize;
        let sample = DirectionSample::new(
            self.directions().to_vec(),
            probe_directions(probe_count(count)),
        );
        progress::begin("recompute", pairs.len() as u64);
        let found: Vec<Option<Disagreement>> = pairs
            .par_iter()
            .map(|(&(slot, start, end), lengths)| {
                let pair = Pair { slot, start, end };
                let pieces = solve_lengths(&evaluators[slot], &pair, lengths, &sample);
                progress::advance(1);
                pieces.iter().find_map(|(g, piece)| self.compare(*g, piece))
            })
            .collect();
        progress::end();
        let disagreement = found.into_iter().flatten().min_by_key(|d| d.record);
        Ok(Recomputed {
            checked: chosen.len(),
            measured: measured.len(),
            disagreement,
        })
    }

    /// `Some` naming the first difference between record `g` and its recomputed `piece`.
    fn compare(&self, g: u64, piece: &Piece) -> Option<Disagreement> {
        let header = self.header();
        let k = (g - header.stored_pvs().start) as usize;
        let record = self.pv_records()[k];
        let n = self.directions().len();
        let stored_rows = &self.results()[k * n..(k + 1) * n];
        let what = match &piece.rows {
            None if !record.has(PvRecord::TOO_SHORT) => {
                Some("stored as reaching between its clamps, recomputed too short".to_string())
            }
            Some(_) if record.has(PvRecord::TOO_SHORT) => {
                Some("stored as too short for its clamps, recomputed reaching".to_string())
            }
            None => None,
            Some(rows) => first_row_difference(self.directions(), stored_rows, rows)
                .or_else(|| factor_difference(record.error_factor, piece.error_factor)),
        }?;
        let (slot, pv) = pv_at(header, g);
        let entry = &header.links[slot];
        Some(Disagreement {
            record: g,
            link: entry.link.clone(),
            clamps: (
                entry.clamps[pv.start].name.clone(),
                entry.clamps[pv.end].name.clone(),
            ),
            sub_segments: pv.sub_segments,
            what,
        })
    }
}

/// The first direction whose stored margins differ from the recomputed ones by more than
/// the tolerance, described.
fn first_row_difference(
    directions: &[[f64; 3]],
    stored: &[MarginRecord],
    recomputed: &[MarginRecord],
) -> Option<String> {
    const NAMES: [&str; 3] = [
        "clearance margin (mm)",
        "stretch margin",
        "bend margin (1/m)",
    ];
    for (d, (s, r)) in stored.iter().zip(recomputed).enumerate() {
        let [x, y, z] = directions[d];
        let at = format!("gravity direction {d} ({x:.3}, {y:.3}, {z:.3})");
        let (sv, rv) = (
            [s.clearance, s.stretch, s.bend],
            [r.clearance, r.stretch, r.bend],
        );
        let show = |v: i16, k: usize| match v {
            MarginRecord::NOT_MEASURED => "no equilibrium".to_string(),
            v => format!("{:+}", f64::from(v) * MARGIN_UNITS[k]),
        };
        for k in 0..3 {
            let measured_differs =
                (sv[k] == MarginRecord::NOT_MEASURED) != (rv[k] == MarginRecord::NOT_MEASURED);
            if measured_differs
                || (i32::from(sv[k]) - i32::from(rv[k])).abs() > RECOMPUTE_TOLERANCE_UNITS
            {
                return Some(format!(
                    "at {at}, {} stored {}, recomputed {}",
                    NAMES[k],
                    show(sv[k], k),
                    show(rv[k], k)
                ));
            }
        }
    }
    None
}

fn factor_difference(stored: [u8; MARGIN_COUNT], recomputed: [u8; MARGIN_COUNT]) -> Option<String> {
    let differs = stored
        .iter()
        .zip(&recomputed)
        .any(|(&s, &r)| (i32::from(s) - i32::from(r)).abs() > RECOMPUTE_TOLERANCE_UNITS);
    differs.then(|| {
        format!(
            "interpolation error factors stored {:?}/16, recomputed {:?}/16",
            stored, recomputed
        )
    })
}

/// The records `choice` names among `measured` (ascending global indices), ascending.
fn choose(measured: &[u64], choice: RecomputeChoice) -> Vec<u64> {
    let (count, seed) = match choice {
        RecomputeChoice::All => return measured.to_vec(),
        RecomputeChoice::Random { count, seed } => (count, seed),
    };
    let mut pool = measured.to_vec();
    let count = count.min(pool.len());
    let mut state = seed;
    // A partial Fisher–Yates shuffle driven by SplitMix64: the first `count` are the draw.
    for i in 0..count {
        let j = i + (split_mix(&mut state) % (pool.len() - i) as u64) as usize;
        pool.swap(i, j);
    }
    pool.truncate(count);
    pool.sort_unstable();
    pool
}

/// SplitMix64 (Steele, Lea, Flood 2014): a small, well-mixed generator for the draw.
fn split_mix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_draw_is_distinct_sorted_and_repeatable() {
        let measured: Vec<u64> = (100..200).collect();
        let draw = |seed| choose(&measured, RecomputeChoice::Random { count: 10, seed });
        let a = draw(7);
        assert_eq!(a.len(), 10);
        assert!(a.windows(2).all(|w| w[0] < w[1]));
        assert!(a.iter().all(|g| measured.contains(g)));
        assert_eq!(a, draw(7));
        assert_ne!(a, draw(8));
        let all = choose(
            &measured,
            RecomputeChoice::Random {
                count: 500,
                seed: 1,
            },
        );
        assert_eq!(all, measured);
    }

    #[test]
    fn a_difference_of_one_unit_is_tolerated_and_of_two_named() {
        let directions = [[0.0, 0.0, -1.0]];
        let record = |bend| MarginRecord {
            clearance: 100,
            stretch: 10,
            bend,
            twist: 20,
        };
        assert_eq!(
            first_row_difference(&directions, &[record(50)], &[record(51)]),
            None
        );
        let named = first_row_difference(&directions, &[record(50)], &[record(-50)]);
        assert_eq!(
            named.as_deref(),
            Some(
                "at gravity direction 0 (0.000, 0.000, -1.000), bend margin (1/m) stored +0.1, \
                 recomputed -0.1"
            )
        );
        let unmeasured =
            first_row_difference(&directions, &[MarginRecord::UNMEASURED], &[record(0)]);
        assert!(unmeasured.is_some_and(|w| w.contains("stored no equilibrium")));
    }
}
