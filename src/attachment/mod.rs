//! The attachment test: which PVs of each segment hold all three stress limits
//! at every pose that matters, and which of those are robust to a length error.
//!
//! Per segment `C_m`, in the paper's notation:
//!
//! - **D0**: the admissible PVs (S, P_m, P_(m+1)) of the setup ([`Setup::is_admissible`]).
//! - **D'0** (adjacency): for an inter-link segment, the PVs of D0 whose guide shared with an
//!   intra-link neighbour is used by some PV in that neighbour's D2. Intra-link segments are
//!   tested first, so their D'0 is their D0.
//! - **D1**: the PVs of D'0 whose static equilibrium keeps the clearance, stretch and bend
//!   radius limits at every test pose ([`SegmentPoses`]). A zero-length PV (one clamp) has no
//!   cable and passes.
//! - **D2** (robustness): the PVs of D1 whose guides, with every length `S ± k·ΔS`,
//!   `k = 1…R`, pass the same test. Lengths beyond the candidate range are evaluated for this
//!   purpose (they are not candidates themselves), so a PV at the end of its range is judged
//!   by physics, not by the range. A length below one sub-segment cannot be built: a PV that
//!   would need one is not robust. Zero-length PVs are robust (there is no cable to cut
//!   wrong).
//!
//! Every (guides, length) pair is evaluated once, in parallel with rayon; results are
//! collected in a fixed order, so the sets do not depend on the thread count. A failed
//! solve rejects that PV (counted as "solver failed") and the run goes on.
//!
//! Two drivers share the evaluation: [`attachment_test`] decides every candidate (the
//! paper's order, `solve --exhaustive`), [`LazyAttachment`] only those a chain shorter than
//! a bound can use (`solve`'s default; docs/architecture.md, "Lazy attachment test"). The
//! modules: the sets a test decides (`sets`), verdicts and margins (`verdict`), one piece at
//! one pose (`evaluate`), warm starts and continuation over lengths (`continuation`), the
//! rapier baseline (`baseline`), test poses (`poses`), jobs of pieces evaluated in parallel
//! (`jobs`), the two drivers (`exhaustive`, `lazy`), a dictionary's answers (`lookup`), the
//! static sweep (`sweep`), cost estimates (`estimate`), verdicts kept between solves
//! (`memory`). This file only hands their names on.

mod baseline;
mod continuation;
mod estimate;
mod evaluate;
mod exhaustive;
mod jobs;
mod lazy;
mod lookup;
mod memory;
mod poses;
mod sets;
mod sweep;
mod through;
mod verdict;

pub use continuation::CONTINUATION_BLOCK;
pub use estimate::{CostEstimate, SAMPLE_PAIRS, SAMPLE_POSES};
pub use evaluate::{ConnectMethod, Evaluator, Swept, SweptLeast};
pub use exhaustive::{attachment_test, attachment_test_with};
pub use lazy::LazyAttachment;
pub use lookup::{IntraLinkAnswer, LookupAnswer};
pub use memory::{Learnt, VerdictMemory};
pub use poses::{GRAVITY_RESOLUTION_DEG, IntraLinkCriterion, SegmentPoses, TestPose};
pub use sets::{
    LookedUp, MAX_CANDIDATE_PIECES, NEAREST_MISSES, SegmentSets, admissible_pvs, check_size,
    needed_pvs, robust_neighbours,
};
pub use sweep::{MotionSweep, SweepFailure};
pub use verdict::{Check, MARGIN_COUNT, MarginValues, Margins, Metrics, Miss, Rejection};
