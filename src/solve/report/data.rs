//! What `solve` found, as data: the types of the result, named for people and scripts.

use super::super::box_check::PieceOverBox;
use super::super::certify::Certification;
use super::super::diagnosis::Diagnosis;
use super::super::options::SearchKind;
use crate::attachment::{ConnectMethod, Rejection};
use crate::motion_test::{Constraint, EngineKind, MotionTestReport};
use crate::mounting::MountingPlan;
use crate::path::CablePath;
use crate::robot::DisplayUnit;
use crate::setup::Thresholds;
use serde::Serialize;
use std::collections::BTreeMap;

/// How the run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// d* found: a chain that passed the motion test.
    Solved,
    /// Shortest chain found, motion test not run (`--no-motion-test`).
    Untested,
    /// No chain: some segment has no robust PV, or no robust PVs agree on shared guides (the
    /// paper's "None").
    NoChain,
    /// Chains exist, but none of the ones tried passed the motion test (the paper's
    /// "Unsolved").
    NonePassedMotionTest,
}

impl Status {
    /// The result JSON's `status`: `solved`, `untested` or `unsolved` (both ways of failing).
    pub fn word(self) -> &'static str {
        match self {
            Status::Solved => "solved",
            Status::Untested => "untested",
            Status::NoChain | Status::NonePassedMotionTest => "unsolved",
        }
    }

    /// For people, e.g. `unsolved: no path of robust cable pieces`.
    pub fn describe(self) -> &'static str {
        match self {
            Status::Solved => "solved",
            Status::Untested => "shortest cable path found, not simulated over the motion",
            Status::NoChain => "unsolved: no path of robust cable pieces",
            Status::NonePassedMotionTest => {
                "unsolved: no path tried held its limits over the motion"
            }
        }
    }
}

/// Wall-clock time of each stage (s); the result JSON's `timings_s`. The only part of the
/// report that changes from run to run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Timings {
    /// Critical and test poses.
    #[serde(rename = "critical_poses")]
    pub critical_poses_s: f64,
    /// Attachment test of every segment.
    #[serde(rename = "attachment")]
    pub attachment_s: f64,
    /// The part of it spent on the intra-link segments (the part a dictionary answers).
    #[serde(rename = "attachment_intra_link")]
    pub attachment_intra_link_s: f64,
    /// Chain search (dynamic programming and counting).
    #[serde(rename = "chain_search")]
    pub chain_s: f64,
    /// Static sweeps of the candidates' PVs over the motion.
    #[serde(rename = "static_sweep")]
    pub static_sweep_s: f64,
    /// Dynamic motion tests of every candidate tried (chain searches between them included).
    #[serde(rename = "motion_test")]
    pub motion_test_s: f64,
    /// Whole run.
    #[serde(rename = "total")]
    pub total_s: f64,
}

/// A cable path ([`CablePath`]) with the names of its pieces, clamps and links: the result
/// JSON's `ecpv` (the paper's term).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NamedPath {
    /// Piece by piece from the base end: declared segments, or spans where optional guides
    /// are left out.
    pub segments: Vec<PathSegment>,
    /// Every clamp the path mounts with its configuration, from the base end.
    pub guides: Vec<PathGuide>,
    /// The optional guides the path leaves out.
    pub left_out: Vec<String>,
}

/// One segment of a cable path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathSegment {
    /// `C1`, `C2`, …; `C2–C3` for a span over optional guides.
    pub name: String,
    /// Start guide.
    pub from_guide: String,
    /// End guide.
    pub to_guide: String,
    /// Link of the start guide.
    pub from_link: String,
    /// Link of the end guide.
    pub to_link: String,
    /// `inter-link` or `intra-link`.
    pub kind: &'static str,
    /// Length in sub-segments (0: the two guides are one clamp).
    pub sub_segments: usize,
    /// Natural length (mm).
    pub length_mm: f64,
}

/// One guide of a cable path: where its clamp goes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathGuide {
    /// `G1`, `G2`, …
    pub name: String,
    /// The link it is screwed onto.
    pub link: String,
    /// The configuration's name (`G2/…` when the guide coincides with G2: no clamp of its own).
    pub configuration: String,
    /// Position in the link frame (mm).
    pub xyz_mm: [f64; 3],
    /// URDF roll, pitch, yaw in the link frame (deg).
    pub rpy_deg: [f64; 3],
}

/// A static stress margin of one segment of d* at its binding test pose (attachment test).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margin {
    /// `C1`, `C2`, …
    pub segment: String,
    /// `contact`, `stretch` or `bend_radius`.
    pub constraint: &'static str,
    /// The value at the binding pose (m for contact and bend radius, 1 for stretch).
    pub value: f64,
    /// The limit, same unit.
    pub threshold: f64,
    /// Distance to the limit, positive when it holds (same unit).
    pub margin: f64,
    /// The binding test pose: sample, time and why it is a test pose.
    pub sample: usize,
    /// Time of the pose (s).
    pub time_s: f64,
    /// Why the pose was tested.
    pub reason: String,
}

/// The attachment-test results of one segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentReport {
    /// `C1`, `C2`, …
    pub segment: String,
    /// Start guide.
    pub from_guide: String,
    /// End guide.
    pub to_guide: String,
    /// `inter-link` or `intra-link`.
    pub kind: &'static str,
    /// Joints between the two links (inter-link segments).
    pub traversed_joints: Vec<String>,
    /// The test poses (sample, time, reason).
    pub test_poses: Vec<PoseSummary>,
    /// |D0|.
    pub d0: usize,
    /// |D'0|.
    pub d0_pruned: usize,
    /// |D1|.
    pub d1: usize,
    /// |D2|.
    pub d2: usize,
    /// Rejected PVs of D'0 by first violated limit.
    pub rejections: BTreeMap<Rejection, usize>,
    /// (guides, length) combinations evaluated, robustness lengths included.
    pub evaluations: usize,
    /// Static solves (Newton's) the attachment test started for this segment, at every test
    /// pose: the machine-independent measure of its work.
    pub static_solves: usize,
}

/// A test pose, without its link poses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoseSummary {
    /// Which motion of a cell (absent for the first, and for a single motion).
    #[serde(skip_serializing_if = "crate::json::is_zero")]
    pub motion: usize,
    /// Motion sample.
    pub sample: usize,
    /// Time (s).
    pub time_s: f64,
    /// Joint values (deg for rotary joints, mm for prismatic ones).
    pub joints: Vec<f64>,
    /// Why.
    pub reason: String,
}

/// One chain tried in the motion test (read back from a result JSON by `export-scene`).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct CandidateOutcome {
    /// 1 for the shortest chain.
    pub rank: usize,
    /// Total natural length (mm).
    pub total_length_mm: f64,
    /// The path.
    pub path: CablePath,
    /// Passed the motion test; `None` when not tested.
    pub passed: Option<bool>,
    /// Why it failed (a limit), or why it held every limit and is not the answer (a life
    /// goal).
    pub failure: Option<String>,
    /// Its predicted life in cycles, when a life goal asked for it and it held every limit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub life_cycles: Option<f64>,
    /// For a cell: the motion it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub motion: Option<String>,
}

/// What the static sweep in front of the motion test did (result JSON `static_sweep`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSummary {
    /// Distinct motion poses each PV was solved at (0: the sweep did not run).
    pub poses: usize,
    /// PVs swept.
    pub pvs_swept: usize,
    /// PVs dropped, in the order found.
    pub rejected: Vec<SweepRejection>,
    /// How far the cable swung past its static shapes in the failed motion tests, per
    /// segment (the smallest over the clamp pairs measured), in segment order.
    pub learned_swings: Vec<LearnedSwing>,
    /// Clamp pairs one of whose loops swung into another part of the cable in a motion
    /// test: their other lengths are set aside too.
    pub touching_pairs: usize,
    /// Pieces set aside because their static shapes kept a learned swing not inside a
    /// limit, or their clamp pair's loop touched the cable (docs/architecture.md, "Learning
    /// from failed motion tests").
    pub set_aside: usize,
    /// The pieces set aside came back: no chain was left without them and the search went
    /// on without learned margins, or a chain passed and they came back to find the shortest
    /// untried chain (`shortest_untried_mm`).
    pub set_aside_restored: bool,
    /// The answer passed with pieces set aside: the length of the shortest chain with them
    /// of the pieces decided (mm), when shorter than the answer. It was not motion-tested;
    /// a shorter one of pieces the search did not decide may exist.
    pub shortest_untried_mm: Option<f64>,
}

/// How far one segment's cable swung past its static shapes in a failed motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LearnedSwing {
    /// `C1`, `C2`, …
    pub segment: String,
    /// Bend radius lost to the swing (mm); `None`: no bend-radius failure measured.
    pub bend_radius_mm: Option<f64>,
    /// Clearance to the robot lost to the swing (mm); `None`: no contact failure measured.
    pub clearance_mm: Option<f64>,
}

/// A PV the static sweep dropped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRejection {
    /// `C1`, `C2`, …
    pub segment: String,
    /// Length in sub-segments.
    pub sub_segments: usize,
    /// Start guide's configuration name.
    pub from_configuration: String,
    /// End guide's configuration name.
    pub to_configuration: String,
    /// The limit violated first.
    pub rejection: Rejection,
    /// The motion of a cell whose sweep dropped it (`None` for a single motion).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub motion: Option<String>,
    /// Motion sample and time (s) of the first pose that fails.
    pub sample: usize,
    /// Time of that pose (s).
    pub time_s: f64,
    /// Why, for people.
    pub detail: String,
}

/// The inputs, named and hashed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Inputs {
    /// Setup file.
    pub setup_file: String,
    /// Content hash of the setup as used (after method restrictions).
    pub setup_hash: String,
    /// Robot URDF.
    pub robot_file: String,
    /// Cable file and name.
    pub cable_file: String,
    /// Cable name.
    pub cable: String,
    /// Motion file, filled in by the caller who read it.
    pub motion_file: Option<String>,
    /// Motion duration (s).
    pub motion_duration_s: f64,
    /// Motion samples.
    pub motion_samples: usize,
    /// `method 1`, `method 2` or `previous method` (linear connect).
    pub method: String,
    /// `hermite` or `linear`.
    pub connect: ConnectMethod,
    /// `lazy` (the pieces the search needs) or `exhaustive` (every candidate first).
    pub search: SearchKind,
    /// The dictionary the intra-link sets came from (`None`: tested at their poses).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dictionary: Option<DictionaryUse>,
    /// The limits the answer was held to, and what the cable file left out.
    pub limits: LimitsUsed,
}

/// The bend radii and the torsion limit an answer was held to, and which datasheet values
/// the cable file does not state (each then said, not invented).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LimitsUsed {
    /// The radius every piece keeps (fixed installation), mm.
    pub min_bend_radius_fixed_mm: f64,
    /// The radius a flexing piece keeps, mm (the fixed one when the file states none).
    pub min_bend_radius_flexing_mm: f64,
    /// A piece flexes when its curvature changes by more than this somewhere (1/m).
    pub flexing_curvature_change_per_m: f64,
    /// The largest twist per length (deg/m); `None`: the cable file states none.
    pub torsion_limit_deg_per_m: Option<f64>,
    /// What the cable file does not state, in words.
    pub not_stated: Vec<&'static str>,
}

impl LimitsUsed {
    /// The limits of `setup`.
    pub fn of(setup: &crate::setup::Setup) -> LimitsUsed {
        let t = &setup.thresholds;
        LimitsUsed {
            min_bend_radius_fixed_mm: t.min_bend_radius_m * 1e3,
            min_bend_radius_flexing_mm: t.flexing_bend_radius_m() * 1e3,
            flexing_curvature_change_per_m: t.flexing_curvature_change_per_m,
            torsion_limit_deg_per_m: t.torsion_limit_deg_per_m,
            not_stated: setup.cable.datasheet.missing(),
        }
    }
}

/// How a dictionary answered for the intra-link segments.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DictionaryUse {
    /// The dictionary file.
    pub file: String,
    /// Gravity directions it stores.
    pub directions: u32,
    /// Largest angle from any direction to a stored one (deg).
    pub covering_radius_deg: f64,
    /// Per intra-link segment: what the lookup decided.
    pub segments: Vec<DictionarySegmentUse>,
    /// The exact checks of the pieces the offered chains took from the file.
    pub certification: Certification,
    /// Who signed the file, as the command line checked it; `None`: not checked (a library
    /// caller's business, [`crate::dictionary::Dictionary::provenance`]).
    pub provenance: Option<crate::provenance::Provenance>,
}

/// How a dictionary answered for one intra-link segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DictionarySegmentUse {
    /// `C2`, …
    pub segment: String,
    /// Distinct gravity directions of the motion in the segment's link frame.
    pub gravity_directions: usize,
    /// Pieces that held or failed by the lookup alone, and those solved exactly.
    pub pieces: crate::attachment::LookedUp,
}

/// Everything `solve` found. Serializes as the result JSON (docs/commands.md, "Result JSON"): the names
/// there are stable, scripts depend on them.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveReport {
    /// How the run ended.
    pub status: Status,
    /// Why, for people.
    pub explanation: String,
    /// The inputs.
    pub inputs: Inputs,
    /// The optimal path d* (or d̂ when untested).
    pub optimal: Option<NamedPath>,
    /// Its total length (mm).
    pub optimal_length_mm: Option<f64>,
    /// How to mount it: physical clamps, their places and the cable marks.
    pub mounting: Option<MountingPlan>,
    /// The limits the path was held to (quoted by the summaries).
    pub thresholds: Thresholds,
    /// The cable model's sub-segment length (mm): places along a piece are counted in it.
    pub sub_segment_pitch_mm: f64,
    /// Static margins of every segment of the optimal path at its binding test pose.
    pub margins: Vec<Margin>,
    /// Per segment: test poses and set sizes.
    pub segments: Vec<SegmentReport>,
    /// |D3|: chains of robust PVs that agree on every shared guide (a decimal string: it can
    /// exceed 2⁶⁴).
    pub chains: String,
    /// The chains tried in the motion test, in the order tried (non-decreasing length).
    pub candidates: Vec<CandidateOutcome>,
    /// The static sweep in front of the motion test.
    pub static_sweep: SweepSummary,
    /// Motion test of the optimal path, or of the last candidate tried when none passed;
    /// `None` when none was run. For a cell: the motion the path is judged by (the one it
    /// failed, else the first).
    pub motion_test: Option<MotionTestReport>,
    /// Every motion of the cell (one for a single motion) with the motion test of the path
    /// shown, in the order given (result JSON `motions`).
    pub motions: Vec<MotionVerdict>,
    /// The index in `motions` of the motion `motion_test` is over (0 for a single motion):
    /// what a report animates.
    pub shown_motion: usize,
    /// For a cell of several motions, per piece of the path shown, the motion that comes
    /// closest to each limit (result JSON `binding`; empty for a single motion).
    pub binding: Vec<PieceBinding>,
    /// The predicted life of the path shown (result JSON `life`); `None` without a rated
    /// life in the cable file or a motion test of every motion.
    pub life: Option<crate::life::estimate::CableLife>,
    /// The motion test was asked for.
    pub motion_test_requested: bool,
    /// What simulated the cable in the motion tests.
    pub motion_engine: EngineKind,
    /// Stage timings (s).
    pub timings: Timings,
    /// Why there is no path, and what would help; `None` when solved.
    pub diagnosis: Option<Diagnosis>,
    /// Which of the three ways the search ended without an answer, and the path tried that
    /// came closest to passing; `None` when solved.
    pub unsolved: Option<Unsolved>,
    /// A design for axis ranges: the box asked for, the box answered (narrowed when the one
    /// asked has no path) and the boxes tried on the way.
    pub ranges: Option<RangeDesign>,
    /// The ranges the path shown allows per axis (`solve --allowed-ranges`).
    pub allowed_ranges: Option<AllowedRanges>,
}

/// One motion of a cell, and how the path shown fared over it.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionVerdict {
    /// Its name (`pick_and_place`, or the cell file's `name`).
    pub name: String,
    /// Its motion CSV.
    pub file: Option<String>,
    /// How many times an hour it runs, when the cell file says.
    pub cycles_per_hour: Option<f64>,
    /// Duration (s).
    pub duration_s: f64,
    /// The motion test of the path shown over it; `None` when it was not run (an earlier
    /// motion failed, or no motion test, or an axis-range grid).
    pub motion_test: Option<MotionTestReport>,
    /// `Some(poses)`: an axis-range grid of that many static poses, each piece tested at its
    /// own by the attachment test (never simulated).
    pub grid_poses: Option<usize>,
}

impl MotionVerdict {
    /// `holds`, `fails` or `not_run`: the motion's verdict in the result JSON.
    pub fn verdict(&self) -> &'static str {
        match &self.motion_test {
            None if self.grid_poses.is_some() => "static",
            Some(test) if test.passed => "holds",
            Some(_) => "fails",
            None => "not_run",
        }
    }
}

/// Which motion of a cell comes closest to each limit on one piece of the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceBinding {
    /// `C2`.
    pub segment: String,
    /// The motion with the piece's smallest bend radius, and that radius.
    pub bend_radius: Option<BindingMotion>,
    /// The motion with the piece's lowest clearance to the robot, and that clearance.
    pub clearance: Option<BindingMotion>,
}

/// The motion that binds one limit of a piece.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BindingMotion {
    /// The motion's name.
    pub motion: String,
    /// Its worst value on the piece (mm).
    pub value_mm: f64,
    /// The limit (mm).
    pub limit_mm: f64,
    /// When in that motion (s).
    pub time_s: f64,
}

/// How a search without an answer ended (result JSON `unsolved`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unsolved {
    /// Which case.
    pub case: UnsolvedCase,
    /// The path tried that missed a limit by the least (bend radius or clearance, in mm);
    /// `None` when no path reached the motion test, or none failed by a measurable amount.
    pub closest: Option<ClosestMiss>,
    /// How many different clamp placements (which clamps, where: the path without its
    /// lengths) the paths tried used.
    pub placements_tried: usize,
    /// When the budget was spent: the shortest chain left untested.
    pub next_untried: Option<UntriedChain>,
}

/// The shortest chain a spent budget left untested.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UntriedChain {
    /// Its total length (mm).
    pub length_mm: f64,
    /// Its clamps and pieces.
    pub path: NamedPath,
    /// Its clamp placement is none of the paths tried: a different family, not another
    /// length of one tried.
    pub new_placement: bool,
}

/// The three ways a search ends without an answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum UnsolvedCase {
    /// No chain of robust pieces exists within the length windows and clamp sites: the
    /// attachment test rules every one out (the diagnosis says why, segment by segment).
    NoChain,
    /// Every chain of robust pieces was tried (or contains a piece that failed): none
    /// exists that holds the limits over the motion.
    AllChainsFailed,
    /// The budget of motion tests ran out with chains untried: a path may exist.
    BudgetSpent,
}

/// The path tried that came closest to passing the motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosestMiss {
    /// Its index in `candidates`.
    pub candidate: usize,
    /// Its total length (mm).
    pub length_mm: f64,
    /// The segment that failed (`C3`).
    pub segment: String,
    /// The limit it missed: `bend_radius` or `contact`.
    pub limit: Constraint,
    /// What the motion test measured (mm).
    pub value_mm: f64,
    /// The limit (mm).
    pub limit_mm: f64,
    /// By how much the limit would have to be relaxed for this failure to go (mm).
    pub relax_by_mm: f64,
}

impl ClosestMiss {
    /// `bend radius`, `flexing bend radius` or `clearance`: the limit it missed, in words.
    pub fn limit_words(&self) -> &'static str {
        match self.limit {
            Constraint::BendRadius => "bend radius",
            Constraint::FlexingBendRadius => "flexing bend radius",
            _ => "clearance",
        }
    }
}

impl SolveReport {
    /// The file of the motion `motion_test` is over (for a cell, `motions[shown_motion]`'s).
    pub fn shown_motion_file(&self) -> Option<&str> {
        match self.motions.get(self.shown_motion) {
            Some(m) => m.file.as_deref(),
            None => self.inputs.motion_file.as_deref(),
        }
    }

    /// The candidate a report shows: the one that passed the motion test, the untested
    /// shortest one, or when none passed the closest miss (`unsolved.closest`), else the
    /// last one tried — the one whose motion test the report keeps. `None` when there is no
    /// candidate.
    pub fn shown_candidate(&self) -> Option<&CandidateOutcome> {
        let verdicts = self.candidates.iter().map(|c| c.passed);
        let closest = (self.unsolved.as_ref())
            .and_then(|u| u.closest.as_ref())
            .map(|c| c.candidate);
        shown_index(verdicts, closest).map(|i| &self.candidates[i])
    }
}

/// The index of the candidate to show among candidates with these motion-test verdicts
/// (`Some(true)` passed, `None` untested), in the order tried: the first that passed, else
/// `closest` (the closest miss, when it is one of them), else the last. The one rule for
/// [`SolveReport::shown_candidate`] and for readers of a result JSON's `candidates` and
/// `unsolved.closest.candidate`.
pub fn shown_index(
    verdicts: impl ExactSizeIterator<Item = Option<bool>>,
    closest: Option<usize>,
) -> Option<usize> {
    let count = verdicts.len();
    let mut verdicts = verdicts;
    verdicts
        .position(|passed| passed == Some(true))
        .or(closest.filter(|&k| k < count))
        .or(count.checked_sub(1))
}

/// What a design for axis ranges asked and answered.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RangeDesign {
    /// The ranges file.
    pub file: Option<String>,
    /// The axis-range grid's step (degrees; millimetres for a prismatic joint).
    pub grid_step_deg: f64,
    /// The ranges asked for, of the axes the file names.
    pub asked: Vec<AxisRange>,
    /// The stress motions' time from rest to full speed asked for (s).
    pub time_to_full_speed_asked_s: f64,
    /// The one answered: as asked, or longer when the axes' acceleration alone fails the
    /// box (s).
    pub time_to_full_speed_answered_s: f64,
    /// The ranges of the box answered: the ones asked, or narrower when those have no path.
    pub answered: Vec<AxisRange>,
    /// Per ranged axis, what its stress motion failed in the box asked (empty when that box
    /// has a path): the axes are narrowed in that order, most first.
    pub failures: Vec<AxisFailures>,
    /// The boxes tried to find which axis to narrow, in order (empty when the box asked has
    /// a path).
    pub tried: Vec<RangeProbe>,
}

/// What one ranged axis's stress motion (the axis end to end alone) failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisFailures {
    /// The joint's URDF name.
    pub joint: String,
    /// Chains whose motion test failed in it.
    pub motion_tests_failed: usize,
    /// Pieces its static sweep dropped.
    pub sweep_drops: usize,
    /// The candidate pieces of the segments that block the search (at the poses that
    /// rejected most of them, and the closest misses: the diagnosis's, at the grid's poses
    /// or the stress motions') that failed with this axis in the lower, and in the upper
    /// half of its range: the end to narrow it from.
    pub failed_in_half: [usize; 2],
}

impl AxisFailures {
    /// How much this axis is to blame, the most blamed narrowed first: the chains its
    /// stress motion failed and the pieces its sweep dropped, then by how many more of the
    /// pieces failed in one half of its range than in the other (failures spread evenly
    /// over an axis do not blame it).
    pub fn blame(&self) -> (usize, usize) {
        let [low, high] = self.failed_in_half;
        (
            self.motion_tests_failed + self.sweep_drops,
            low.abs_diff(high),
        )
    }

    /// The end of its range to keep when narrowing it (`Some(0)` the minimum, `Some(1)` the
    /// maximum): the one away from the half where more pieces failed; `None` (narrow about
    /// the middle) when they fell evenly.
    pub fn kept_end(&self) -> Option<usize> {
        match self.failed_in_half {
            [low, high] if low > high => Some(1),
            [low, high] if high > low => Some(0),
            _ => None,
        }
    }
}

impl RangeDesign {
    /// The axes whose answered range is narrower than asked.
    pub fn narrowed(&self) -> impl Iterator<Item = (&AxisRange, &AxisRange)> {
        (self.asked.iter().zip(&self.answered)).filter(|(a, b)| a != b)
    }
}

/// The ranges a mounting allows, per axis, with the others anywhere in a box.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllowedRanges {
    /// The box the other axes range over, for people (`the ranges of cell.toml`, `the
    /// motions' extremes`).
    pub within: String,
    /// The grid step of the other axes, and of the outward scan (degrees; mm).
    pub step_deg: f64,
    /// How close each end is to the first failing value (degrees; mm).
    pub resolution_deg: f64,
    /// When the mounting fails in the box itself: the first piece that does, and no axis is
    /// widened.
    pub box_failure: Option<PieceOverBox>,
    /// Per actuated joint, in joint-vector order (empty when the box fails).
    pub axes: Vec<AllowedAxis>,
    /// Wall time (s).
    pub wall_time_s: f64,
}

/// One axis's allowed range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllowedAxis {
    /// The joint's URDF name.
    pub joint: String,
    /// `deg` or `mm`.
    pub unit: DisplayUnit,
    /// Its URDF limits; `None` for a continuous joint.
    pub limits: Option<[f64; 2]>,
    /// Its range in the box.
    pub within: [f64; 2],
    /// The range it allows, ends rounded inward to the resolution (never inside `within`).
    pub allowed: [f64; 2],
    /// The pieces whose shape it changes (the others are not solved for it).
    pub shapes: Vec<String>,
    /// What ends the range below.
    pub below: RangeEnd,
    /// What ends it above.
    pub above: RangeEnd,
}

/// What ends an allowed range.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "end", rename_all = "snake_case")]
pub enum RangeEnd {
    /// The joint's URDF limit (a full turn each way for a continuous joint).
    Limit,
    /// A piece breaks a limit at `at` (deg; mm), within the resolution beyond the end.
    Fails {
        /// The axis value where it fails.
        at: f64,
        /// The piece (`C3`).
        piece: String,
        /// The joints that shape it there (name, deg or mm), the axis among them.
        joints: Vec<(String, f64)>,
        /// What fails, for people.
        reason: String,
    },
    /// Driven end to end at its URDF speed over the range statics allow, the cable fails:
    /// the range is shrunk until that motion holds.
    FullSpeed {
        /// The range statics allow (deg; mm), over which the stroke failed.
        statics: [f64; 2],
        /// The motion test's failure over it.
        reason: String,
    },
}

/// One axis's range, in the unit people give it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisRange {
    /// The joint's URDF name.
    pub joint: String,
    /// Its least value (deg, or mm for a prismatic joint).
    pub min: f64,
    /// Its greatest value.
    pub max: f64,
    /// `deg` or `mm`.
    pub unit: DisplayUnit,
}

impl AxisRange {
    /// `joint_5 -31.4…26.1°`.
    pub fn words(&self) -> String {
        let unit = self.unit.suffix();
        format!("{} {}…{}{unit}", self.joint, self.min, self.max)
    }
}

impl AllowedAxis {
    /// As a vendor prints it: `joint_4 -62…+118°`, `joint_6 ±240°` (whole units).
    pub fn words(&self) -> String {
        let unit = self.unit.suffix();
        let [lo, hi] = self.allowed;
        let signed = |v: f64| match v {
            v if v > 0.0 => format!("+{v:.0}"),
            v if v < 0.0 => format!("-{:.0}", -v),
            _ => "0".to_string(),
        };
        match lo == -hi && hi > 0.0 {
            true => format!("{} ±{hi:.0}{unit}", self.joint),
            false => format!("{} {}…{}{unit}", self.joint, signed(lo), signed(hi)),
        }
    }

    /// What ends the range at one side (`below`, `above`), for people; `piece` names a
    /// setup's piece (`C3`) as the mounting does.
    pub fn end_words(&self, end: &RangeEnd, piece: &dyn Fn(&str) -> String) -> String {
        let unit = self.unit.suffix();
        match end {
            RangeEnd::Limit if self.limits.is_some() => "its URDF limit".into(),
            RangeEnd::Limit => "a full turn (a continuous joint)".into(),
            RangeEnd::Fails {
                at,
                piece: segment,
                reason,
                ..
            } => format!("{} fails at {at:.1}{unit} ({reason})", piece(segment)),
            RangeEnd::FullSpeed { statics, reason } => format!(
                "statics allow {:.0}…{:.0}{unit}, but driven end to end over that at its URDF \
                 speed the cable fails ({reason}): shrunk until that stroke holds",
                statics[0], statics[1]
            ),
        }
    }
}

impl RangeProbe {
    /// `joint_5 20.6…31.4°: 620 mm`, `full speed in 0.6 s: 870 mm`, or `…: no path`.
    pub fn words(&self) -> String {
        let mut ranges: Vec<String> = self.narrowed.iter().map(AxisRange::words).collect();
        ranges.extend((self.time_to_full_speed_s).map(|t| format!("full speed in {t} s")));
        match self.length_mm {
            Some(mm) => format!("{}: {mm:.0} mm", ranges.join(", ")),
            None => format!("{}: no path", ranges.join(", ")),
        }
    }
}

/// One box tried while narrowing axis ranges.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RangeProbe {
    /// The axes narrowed in it (the others as asked).
    pub narrowed: Vec<AxisRange>,
    /// Its stress motions' time to full speed when not the one asked (s).
    pub time_to_full_speed_s: Option<f64>,
    /// Its shortest path's length (mm); `None`: no path.
    pub length_mm: Option<f64>,
    /// Wall time of its solve (s).
    pub time_s: f64,
}
