//! Parameter vectors and cable paths in the paper's notation, as indices into a
//! [`Setup`](crate::setup::Setup).
//!
//! A *PV* of segment `C_m` is `(S_m, P_m, P_(m+1))`: a length in sub-segments and one
//! candidate configuration of each of its two guides. A *cable path* (the paper's ECPV) is
//! every segment's length and every guide's configuration; its PVs agree on shared guides by
//! construction.

use crate::setup::Setup;

/// A parameter vector of one segment: length and the configurations of its two guides.
///
/// The derived order (length, then start, then end configuration) is the deterministic
/// tie-break wherever PVs are ranked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct Pv {
    /// Length S in sub-segments (0: the two guides coincide, intra-link segments only).
    pub sub_segments: usize,
    /// Index into the start guide's `configurations`.
    pub start: usize,
    /// Index into the end guide's `configurations`.
    pub end: usize,
}

impl Pv {
    /// The PV of `sub_segments` between configurations `start` and `end`.
    pub const fn new(sub_segments: usize, start: usize, end: usize) -> Pv {
        Pv {
            sub_segments,
            start,
            end,
        }
    }
}

/// A whole cable path (ECPV): the pieces of cable from the base end, each a segment of the
/// setup (a declared segment `C_m` from guide `m` to `m + 1`, or a span over optional guides,
/// see [`Setup::segments`](crate::setup::Setup::segments)), its length, and the
/// configuration of every clamp the path mounts.
///
/// A path through every guide has `segments = [0, 1, …, M − 1]` and one configuration per
/// guide; a path that leaves optional guides out has fewer pieces and clamps.
#[derive(
    Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct CablePath {
    /// Per piece, from the base end: its index into the setup's segments (empty in results
    /// written before paths could leave clamps out: then one per guide pair).
    #[serde(default)]
    pub segments: Vec<usize>,
    /// Length of every piece in sub-segments, from the base end.
    pub lengths: Vec<usize>,
    /// Configuration index of every clamp, from the base end: each piece's start guide, then
    /// the last piece's end guide (one more than there are pieces).
    pub configurations: Vec<usize>,
}

impl CablePath {
    /// The path through every guide: segment `m` from guide `m` to `m + 1`, of `lengths[m]`,
    /// with `configurations[g]` at guide `g`.
    pub fn through_every_guide(lengths: Vec<usize>, configurations: Vec<usize>) -> CablePath {
        CablePath {
            segments: (0..lengths.len()).collect(),
            lengths,
            configurations,
        }
    }

    /// The path through every guide made of one PV per segment, `None` when the PVs do not
    /// agree on a shared guide (or there are none).
    pub fn from_pvs(pvs: &[Pv]) -> Option<CablePath> {
        let pieces: Vec<(usize, Pv)> = pvs.iter().copied().enumerate().collect();
        CablePath::from_pieces(&pieces)
    }

    /// The path made of `(segment, PV)` pieces in order, `None` when consecutive PVs do not
    /// agree on their shared clamp (or there are none). Whether consecutive segments share a
    /// guide is the caller's to know (the chain search builds only such sequences).
    pub fn from_pieces(pieces: &[(usize, Pv)]) -> Option<CablePath> {
        let first = pieces.first()?;
        if pieces
            .windows(2)
            .any(|pair| pair[0].1.end != pair[1].1.start)
        {
            return None;
        }
        Some(CablePath {
            segments: pieces.iter().map(|&(m, _)| m).collect(),
            lengths: pieces.iter().map(|(_, pv)| pv.sub_segments).collect(),
            configurations: std::iter::once(first.1.start)
                .chain(pieces.iter().map(|(_, pv)| pv.end))
                .collect(),
        })
    }

    /// Number of pieces.
    pub fn segment_count(&self) -> usize {
        self.lengths.len()
    }

    /// The PV of piece `i` (its segment is `segments[i]`).
    pub fn pv(&self, i: usize) -> Pv {
        Pv {
            sub_segments: self.lengths[i],
            start: self.configurations[i],
            end: self.configurations[i + 1],
        }
    }

    /// The `(segment, PV)` of every piece, from the base end.
    pub fn pieces(&self) -> impl Iterator<Item = (usize, Pv)> + '_ {
        (0..self.segment_count()).map(|i| (self.segments[i], self.pv(i)))
    }

    /// Total length in sub-segments.
    pub fn total_sub_segments(&self) -> usize {
        self.lengths.iter().sum()
    }
}

/// Why a cable path does not fit a setup.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PathError {
    /// No piece at all.
    #[error("the cable path has no piece of cable")]
    Empty,
    /// The lists do not have one entry per piece (one more configuration).
    #[error(
        "the cable path has {pieces} segments, {lengths} lengths and {configurations} \
         configurations: one length per segment and one configuration per clamp (one more) \
         are needed"
    )]
    Counts {
        /// Entries of `segments`.
        pieces: usize,
        /// Entries of `lengths`.
        lengths: usize,
        /// Entries of `configurations`.
        configurations: usize,
    },
    /// A segment index beyond the setup's segments.
    #[error("piece {piece}: segment {segment} does not exist, the setup has {count}")]
    SegmentIndex {
        /// Position in the path.
        piece: usize,
        /// The index given.
        segment: usize,
        /// Segments (declared and spans) of the setup.
        count: usize,
    },
    /// The pieces do not run from the first guide to the last, each from where the previous
    /// one ended.
    #[error("{0}")]
    Route(String),
    /// A configuration index beyond the guide's candidate list.
    #[error(
        "guide {name} (path.configurations[{clamp}]): configuration index {index} is out of \
         range, the guide has {count} configurations"
    )]
    ConfigurationIndex {
        /// Position of the clamp in the path.
        clamp: usize,
        /// The guide's name.
        name: String,
        /// The index given.
        index: usize,
        /// Number of configurations of the guide.
        count: usize,
    },
    /// S = 0 between clamps that are different places, or S > 0 between clamps that are one.
    #[error("segment {name} (path.lengths[{piece}] = {sub_segments}): {problem}")]
    Inadmissible {
        /// Position in the path.
        piece: usize,
        /// The segment's name (`C2`, or `C2–C3` for a span).
        name: String,
        /// Its length in sub-segments.
        sub_segments: usize,
        /// What is wrong.
        problem: String,
    },
}

impl CablePath {
    /// Checks that the path fits `setup`: consistent counts, existing segments chained from
    /// the first guide to the last, configurations in range, and S = 0 exactly where the two
    /// clamps are one place ([`Setup::is_admissible`]). Lengths outside a segment's candidate
    /// list are accepted.
    pub fn check(&self, setup: &Setup) -> Result<(), PathError> {
        let pieces = self.segments.len();
        if pieces == 0 {
            return Err(PathError::Empty);
        }
        if self.lengths.len() != pieces || self.configurations.len() != pieces + 1 {
            return Err(PathError::Counts {
                pieces,
                lengths: self.lengths.len(),
                configurations: self.configurations.len(),
            });
        }
        self.check_route(setup)?;
        for (clamp, g) in self.guides(setup).enumerate() {
            let guide = &setup.guides[g];
            let index = self.configurations[clamp];
            if index >= guide.configurations.len() {
                return Err(PathError::ConfigurationIndex {
                    clamp,
                    name: guide.name.clone(),
                    index,
                    count: guide.configurations.len(),
                });
            }
        }
        (0..pieces).try_for_each(|i| self.check_admissible(setup, i))
    }

    /// The guide of every clamp of the path (call after [`CablePath::check`]).
    pub fn guides<'a>(&'a self, setup: &'a Setup) -> impl Iterator<Item = usize> + 'a {
        let first = self.segments.first().map(|&m| setup.segment_guides(m).0);
        first
            .into_iter()
            .chain(self.segments.iter().map(|&m| setup.segment_guides(m).1))
    }

    fn check_route(&self, setup: &Setup) -> Result<(), PathError> {
        let count = setup.segment_count();
        let beyond = self.segments.iter().enumerate().find(|&(_, &m)| m >= count);
        if let Some((piece, &segment)) = beyond {
            return Err(PathError::SegmentIndex {
                piece,
                segment,
                count,
            });
        }
        let guide_name = |g: usize| setup.guides[g].name.as_str();
        let (first, _) = setup.segment_guides(self.segments[0]);
        if first != 0 {
            return Err(PathError::Route(format!(
                "the cable path starts at {}, not at the first guide {}",
                guide_name(first),
                guide_name(0)
            )));
        }
        for (i, pair) in self.segments.windows(2).enumerate() {
            let (end, start) = (
                setup.segment_guides(pair[0]).1,
                setup.segment_guides(pair[1]).0,
            );
            if end != start {
                return Err(PathError::Route(format!(
                    "piece {i} ({}) ends at {} but piece {} ({}) starts at {}",
                    setup.segment_name(pair[0]),
                    guide_name(end),
                    i + 1,
                    setup.segment_name(pair[1]),
                    guide_name(start)
                )));
            }
        }
        let last = setup.guides.len() - 1;
        let (_, end) = setup.segment_guides(self.segments[self.segments.len() - 1]);
        if end != last {
            return Err(PathError::Route(format!(
                "the cable path ends at {}, not at the last guide {}",
                guide_name(end),
                guide_name(last)
            )));
        }
        Ok(())
    }

    fn check_admissible(&self, setup: &Setup, i: usize) -> Result<(), PathError> {
        let (m, pv) = (self.segments[i], self.pv(i));
        if setup.is_admissible(m, pv.sub_segments, pv.start, pv.end) {
            return Ok(());
        }
        let (a, b) = setup.segment_guides(m);
        let names = format!(
            "{} \"{}\" and {} \"{}\"",
            setup.guides[a].name,
            setup.guides[a].configurations[pv.start].name,
            setup.guides[b].name,
            setup.guides[b].configurations[pv.end].name
        );
        let problem = if pv.sub_segments == 0 {
            format!("length 0 needs coincident guides, but {names} are different places")
        } else {
            format!("{names} coincide (one clamp), so the length must be 0")
        };
        Err(PathError::Inadmissible {
            piece: i,
            name: setup.segment_name(m),
            sub_segments: pv.sub_segments,
            problem,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pvs_that_disagree_on_a_shared_guide_make_no_path() {
        let a = Pv {
            sub_segments: 3,
            start: 0,
            end: 1,
        };
        let b = Pv {
            sub_segments: 4,
            start: 2,
            end: 0,
        };
        assert_eq!(CablePath::from_pvs(&[a, b]), None);
        let c = Pv { start: 1, ..b };
        let path = CablePath::from_pvs(&[a, c]).unwrap();
        assert_eq!(path.configurations, vec![0, 1, 0]);
        assert_eq!(path.segments, vec![0, 1]);
        assert_eq!(path.total_sub_segments(), 7);
        assert_eq!(path.pv(1), c);
    }
}
