//! Parameter vectors and cable paths in the paper's notation, as indices into a
//! [`Setup`](crate::setup::Setup).
//!
//! A *PV* of segment `C_m` is `(S_m, P_m, P_(m+1))`: a length in sub-segments and one
//! candidate configuration of each of its two guides. A *cable path* (the paper's ECPV) is
//! every segment's length and every guide's configuration; its PVs agree on shared guides by
//! construction.

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

/// A whole cable path (ECPV): `lengths[m]` for segment `C_m`, `configurations[g]` for guide
/// `G_g` (one more than there are segments).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct CablePath {
    /// Length of every segment in sub-segments, from the base end.
    pub lengths: Vec<usize>,
    /// Configuration index of every guide, from the base end.
    pub configurations: Vec<usize>,
}

impl CablePath {
    /// The path made of one PV per segment, `None` when the PVs do not agree on a shared
    /// guide (or there are none).
    pub fn from_pvs(pvs: &[Pv]) -> Option<CablePath> {
        let first = pvs.first()?;
        let mut configurations = vec![first.start];
        for pair in pvs.windows(2) {
            if pair[0].end != pair[1].start {
                return None;
            }
        }
        configurations.extend(pvs.iter().map(|pv| pv.end));
        Some(CablePath {
            lengths: pvs.iter().map(|pv| pv.sub_segments).collect(),
            configurations,
        })
    }

    /// Number of segments.
    pub fn segment_count(&self) -> usize {
        self.lengths.len()
    }

    /// The PV of segment `m`.
    pub fn pv(&self, m: usize) -> Pv {
        Pv {
            sub_segments: self.lengths[m],
            start: self.configurations[m],
            end: self.configurations[m + 1],
        }
    }

    /// Total length in sub-segments.
    pub fn total_sub_segments(&self) -> usize {
        self.lengths.iter().sum()
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
        assert_eq!(path.total_sub_segments(), 7);
        assert_eq!(path.pv(1), c);
    }
}
