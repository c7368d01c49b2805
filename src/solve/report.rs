//! The result of [`solve`](super::solve): serializable (the result JSON) and printable (the
//! human summary).

use super::certify::Certification;
use super::diagnosis::{Diagnosis, diagnose};
use super::{MotionSearch, SearchKind, SolveOptions, Tried};
use crate::attachment::{
    ConnectMethod, Evaluator, Metrics, Rejection, SegmentPoses, SegmentSets, TestPose,
};
use crate::chain::ChainSearch;
use crate::motion::Motion;
use crate::motion_test::{EngineKind, MotionTestReport, Worst};
use crate::path::CablePath;
use crate::setup::Setup;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt;

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

    /// For people, e.g. `unsolved: no chain of robust cable pieces`.
    pub fn describe(self) -> &'static str {
        match self {
            Status::Solved => "solved",
            Status::Untested => "shortest chain found, not motion-tested",
            Status::NoChain => "unsolved: no chain of robust cable pieces",
            Status::NonePassedMotionTest => "unsolved: no chain tried passed the motion test",
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

/// A cable path as built: the paper's ECPV, with names.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ecpv {
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
    /// Motion sample.
    pub sample: usize,
    /// Time (s).
    pub time_s: f64,
    /// Joint values (deg for rotary joints, mm for prismatic ones).
    pub joints: Vec<f64>,
    /// Why.
    pub reason: String,
}

/// One chain tried in the motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CandidateOutcome {
    /// 1 for the shortest chain.
    pub rank: usize,
    /// Total natural length (mm).
    pub total_length_mm: f64,
    /// The path.
    pub path: CablePath,
    /// Passed the motion test; `None` when not tested.
    pub passed: Option<bool>,
    /// Why it failed.
    pub failure: Option<String>,
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

/// Everything `solve` found. Serializes as the result JSON (README, "Result JSON"): the names
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
    pub optimal: Option<Ecpv>,
    /// Its total length (mm).
    pub optimal_length_mm: Option<f64>,
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
    /// `None` when none was run.
    pub motion_test: Option<MotionTestReport>,
    /// The motion test was asked for.
    pub motion_test_requested: bool,
    /// What simulated the cable in the motion tests.
    pub motion_engine: EngineKind,
    /// Stage timings (s).
    pub timings: Timings,
    /// Why there is no path, and what would help; `None` when solved.
    pub diagnosis: Option<Diagnosis>,
}

impl SolveReport {
    /// Assembles the report from the stages' results.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        setup: &Setup,
        motion: &Motion,
        options: &SolveOptions,
        evaluator: &Evaluator<'_>,
        poses: &SegmentPoses,
        sets: &[SegmentSets],
        search: &ChainSearch,
        outcome: MotionSearch,
        timings: Timings,
    ) -> SolveReport {
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let MotionSearch { tried, winner, .. } = &outcome;
        let winner = *winner;
        let best = winner.map(|w| tried[w].0.clone());
        let status = status(options, search, winner);
        let candidates = candidate_outcomes(tried, pitch_mm);
        let static_sweep = sweep_summary(setup, &outcome);
        let motion_test = match winner {
            Some(w) => tried[w].1.clone(),
            None => tried.last().and_then(|(_, report)| report.clone()),
        };
        let diagnosis = matches!(status, Status::NoChain | Status::NonePassedMotionTest)
            .then(|| diagnose(setup, motion, poses, sets, &outcome));
        SolveReport {
            status,
            explanation: explanation(
                status,
                sets,
                &candidates,
                &outcome.stop,
                &static_sweep,
                setup,
            ),
            inputs: inputs(setup, motion, options),
            optimal: best.as_ref().map(|p| ecpv(setup, p)),
            optimal_length_mm: best
                .as_ref()
                .map(|p| p.total_sub_segments() as f64 * pitch_mm),
            margins: best
                .as_ref()
                .map(|p| margins(evaluator, poses, p))
                .unwrap_or_default(),
            segments: segment_reports(setup, poses, sets, motion),
            chains: search.chain_count().to_string(),
            candidates,
            static_sweep,
            motion_test,
            motion_test_requested: options.motion_test,
            motion_engine: options.engine,
            timings,
            diagnosis,
        }
    }
}

/// The result JSON's `motion_test`: the run of d* (or of the last candidate tried).
#[derive(Serialize)]
struct MotionTestJson<'a> {
    engine: EngineKind,
    candidates_tried: usize,
    passed: Option<bool>,
    failure: Option<&'a str>,
    /// Largest contact force outside the clamp zones (N); 0 when the cable never touched.
    max_contact: Option<f64>,
    min_clearance_mm: Option<f64>,
    max_stretch: Option<f64>,
    min_bend_radius_mm: Option<f64>,
    worst_clearance: Option<&'a Worst>,
    worst_stretch: Option<&'a Worst>,
    worst_bend_radius: Option<&'a Worst>,
    worst_contact_force: Option<&'a Worst>,
    simulated_s: Option<f64>,
    wall_time_s: Option<f64>,
}

impl<'a> MotionTestJson<'a> {
    fn new(
        engine: EngineKind,
        candidates_tried: usize,
        report: Option<&'a MotionTestReport>,
    ) -> Self {
        let mm = |w: &Option<Worst>| w.as_ref().map(|w| w.value * 1e3);
        Self {
            engine,
            candidates_tried,
            passed: report.map(|r| r.passed),
            failure: report
                .and_then(|r| r.failure.as_ref())
                .map(|f| f.reason.as_str()),
            max_contact: report.map(|r| r.worst_contact_force.as_ref().map_or(0.0, |w| w.value)),
            min_clearance_mm: report.and_then(|r| mm(&r.worst_clearance)),
            max_stretch: report
                .and_then(|r| r.worst_stretch.as_ref())
                .map(|w| w.value),
            min_bend_radius_mm: report.and_then(|r| mm(&r.worst_bend)),
            worst_clearance: report.and_then(|r| r.worst_clearance.as_ref()),
            worst_stretch: report.and_then(|r| r.worst_stretch.as_ref()),
            worst_bend_radius: report.and_then(|r| r.worst_bend.as_ref()),
            worst_contact_force: report.and_then(|r| r.worst_contact_force.as_ref()),
            simulated_s: report.map(|r| r.simulated_s),
            wall_time_s: report.map(|r| r.wall_time_s),
        }
    }
}

/// The result JSON, field names as documented.
#[derive(Serialize)]
struct ResultJson<'a> {
    status: &'static str,
    outcome: Status,
    method: &'a str,
    total_length_mm: Option<f64>,
    ecpv: Option<&'a Ecpv>,
    sets: &'a [SegmentReport],
    chains: &'a str,
    motion_test: Option<MotionTestJson<'a>>,
    candidates: &'a [CandidateOutcome],
    static_sweep: &'a SweepSummary,
    margins: &'a [Margin],
    reason: Option<&'a str>,
    diagnosis: Option<&'a Diagnosis>,
    inputs: &'a Inputs,
    timings_s: &'a Timings,
}

impl Serialize for SolveReport {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        ResultJson {
            status: self.status.word(),
            outcome: self.status,
            method: &self.inputs.method,
            total_length_mm: self.optimal_length_mm,
            ecpv: self.optimal.as_ref(),
            sets: &self.segments,
            chains: &self.chains,
            motion_test: self.motion_test_requested.then(|| {
                MotionTestJson::new(
                    self.motion_engine,
                    self.candidates.len(),
                    self.motion_test.as_ref(),
                )
            }),
            candidates: &self.candidates,
            static_sweep: &self.static_sweep,
            margins: &self.margins,
            reason: (self.status != Status::Solved).then_some(self.explanation.as_str()),
            diagnosis: self.diagnosis.as_ref(),
            inputs: &self.inputs,
            timings_s: &self.timings,
        }
        .serialize(serializer)
    }
}

fn status(options: &SolveOptions, search: &ChainSearch, winner: Option<usize>) -> Status {
    match (search.shortest().is_some(), winner, options.motion_test) {
        (false, _, _) => Status::NoChain,
        (true, Some(_), true) => Status::Solved,
        (true, Some(_), false) => Status::Untested,
        (true, None, _) => Status::NonePassedMotionTest,
    }
}

fn explanation(
    status: Status,
    sets: &[SegmentSets],
    candidates: &[CandidateOutcome],
    stop: &str,
    sweep: &SweepSummary,
    setup: &Setup,
) -> String {
    match status {
        Status::Solved => match candidates.len() {
            1 => "the shortest chain, and it passed the motion test".into(),
            n => format!(
                "the shortest chain that passed the motion test, after {} shorter or equally \
                 long ones failed it",
                n - 1
            ),
        },
        Status::Untested => {
            "the shortest chain of robust cable pieces; the motion test was not run".into()
        }
        Status::NonePassedMotionTest if candidates.is_empty() => format!(
            "every chain of robust candidate pieces has a piece that fails the static sweep \
             over the motion{}",
            sweep_note(sweep)
        ),
        Status::NonePassedMotionTest => {
            let reasons: Vec<String> = candidates
                .iter()
                .map(|c| {
                    format!(
                        "#{}: {}",
                        c.rank,
                        c.failure.as_deref().unwrap_or("not tested")
                    )
                })
                .collect();
            format!(
                "none of the {} chains tried passed the motion test, and {stop}{} — {}",
                candidates.len(),
                sweep_note(sweep),
                reasons.join("; ")
            )
        }
        Status::NoChain => unsolved_reason(sets, setup),
    }
}

/// `; the static sweep over the motion dropped N cable pieces (C1 n1, …)`, or nothing when it
/// dropped none.
fn sweep_note(sweep: &SweepSummary) -> String {
    if sweep.rejected.is_empty() {
        return String::new();
    }
    format!(
        "; the static sweep over the motion dropped {} cable pieces ({})",
        sweep.rejected.len(),
        dropped_per_segment(sweep)
    )
}

/// `C1 n1, C2 n2`: cable pieces the sweep dropped per segment.
fn dropped_per_segment(sweep: &SweepSummary) -> String {
    let mut per_segment: BTreeMap<&str, usize> = BTreeMap::new();
    for r in &sweep.rejected {
        *per_segment.entry(r.segment.as_str()).or_insert(0) += 1;
    }
    let counts: Vec<String> = per_segment
        .iter()
        .map(|(segment, n)| format!("{segment} {n}"))
        .collect();
    counts.join(", ")
}

/// The sweep's counts and dropped PVs, with names.
fn sweep_summary(setup: &Setup, outcome: &MotionSearch) -> SweepSummary {
    let rejected = outcome
        .dropped
        .iter()
        .map(|(m, pv, failure)| {
            let (a, b) = setup.segment_guides(*m);
            SweepRejection {
                segment: setup.segment_name(*m),
                sub_segments: pv.sub_segments,
                from_configuration: setup.guides[a].configurations[pv.start].name.clone(),
                to_configuration: setup.guides[b].configurations[pv.end].name.clone(),
                rejection: failure.rejection,
                sample: failure.sample,
                time_s: failure.time_s,
                detail: failure.detail.clone(),
            }
        })
        .collect();
    SweepSummary {
        poses: outcome.sweep_poses,
        pvs_swept: outcome.swept,
        rejected,
    }
}

/// Which segment has no robust PV and what rejected its candidates most.
fn unsolved_reason(sets: &[SegmentSets], setup: &Setup) -> String {
    let empty: Vec<String> = sets
        .iter()
        .enumerate()
        .filter(|(_, s)| s.d2.is_empty())
        .map(|(m, s)| {
            let worst = s
                .rejections
                .iter()
                .max_by_key(|(_, count)| **count)
                .map(|(r, count)| format!("most rejected by {} ({count})", r.name()))
                .unwrap_or_else(|| "no candidate left after adjacency pruning".into());
            let (a, b) = setup.segment_guides(m);
            format!(
                "{} ({} → {}) has no robust cable piece: {} hold the limits, {worst}",
                setup.segment_name(m),
                setup.guides[a].name,
                setup.guides[b].name,
                s.d1
            )
        })
        .collect();
    if empty.is_empty() {
        "every segment has robust cable pieces, but none agree on their shared clamps".into()
    } else {
        empty.join("; ")
    }
}

fn inputs(setup: &Setup, motion: &Motion, options: &SolveOptions) -> Inputs {
    let method = match (options.method, options.max_guides_per_link) {
        (ConnectMethod::Linear, _) => "previous method",
        (ConnectMethod::Hermite, Some(1)) => "one clamp per link",
        (ConnectMethod::Hermite, _) if setup.max_guides_per_link == 1 => "one clamp per link",
        (ConnectMethod::Hermite, _) => "up to two clamps per link",
    };
    Inputs {
        setup_file: setup.source.display().to_string(),
        setup_hash: setup.content_hash_hex(),
        robot_file: setup.robot_path.display().to_string(),
        cable_file: setup.cable_path.display().to_string(),
        cable: setup.cable.name.clone(),
        motion_file: None,
        motion_duration_s: motion.duration_s(),
        motion_samples: motion.len(),
        method: method.into(),
        connect: options.method,
        search: options.search,
        dictionary: None,
    }
}

fn candidate_outcomes(tried: &[Tried], pitch_mm: f64) -> Vec<CandidateOutcome> {
    tried
        .iter()
        .enumerate()
        .map(|(i, (path, report))| CandidateOutcome {
            rank: i + 1,
            total_length_mm: path.total_sub_segments() as f64 * pitch_mm,
            path: path.clone(),
            passed: report.as_ref().map(|r| r.passed),
            failure: report
                .as_ref()
                .and_then(|r| r.failure.as_ref())
                .map(|f| f.reason.clone()),
        })
        .collect()
}

/// Names of segment `m`'s two guides and of their links.
pub fn guide_names(setup: &Setup, m: usize) -> ([String; 2], [String; 2]) {
    let (a, b) = setup.segment_guides(m);
    let link = |g: usize| setup.robot.links[setup.guides[g].link].name.clone();
    (
        [setup.guides[a].name.clone(), setup.guides[b].name.clone()],
        [link(a), link(b)],
    )
}

/// `inter-link` or `intra-link`: the result JSON's `kind` of segment `m`.
fn segment_kind(setup: &Setup, m: usize) -> &'static str {
    if setup.is_intra_link(m) {
        "intra-link"
    } else {
        "inter-link"
    }
}

/// The path with names: piece by piece, and every mounted clamp's configuration.
pub fn ecpv(setup: &Setup, path: &CablePath) -> Ecpv {
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let segments = path
        .pieces()
        .map(|(m, pv)| {
            let sub_segments = pv.sub_segments;
            let ([from_guide, to_guide], [from_link, to_link]) = guide_names(setup, m);
            PathSegment {
                name: setup.segment_name(m),
                from_guide,
                to_guide,
                from_link,
                to_link,
                kind: segment_kind(setup, m),
                sub_segments,
                length_mm: sub_segments as f64 * pitch_mm,
            }
        })
        .collect();
    let mounted: Vec<usize> = path.guides(setup).collect();
    let guides = mounted
        .iter()
        .zip(&path.configurations)
        .map(|(&g, &c)| {
            let guide = &setup.guides[g];
            let configuration = &guide.configurations[c];
            PathGuide {
                name: guide.name.clone(),
                link: setup.robot.links[guide.link].name.clone(),
                configuration: configuration.name.clone(),
                xyz_mm: configuration.position_mm,
                rpy_deg: configuration.rpy_deg,
            }
        })
        .collect();
    let left_out = (0..setup.guides.len())
        .filter(|g| !mounted.contains(g))
        .map(|g| setup.guides[g].name.clone())
        .collect();
    Ecpv {
        segments,
        guides,
        left_out,
    }
}

fn segment_reports(
    setup: &Setup,
    poses: &SegmentPoses,
    sets: &[SegmentSets],
    motion: &Motion,
) -> Vec<SegmentReport> {
    sets.iter()
        .enumerate()
        .map(|(m, s)| {
            let ([from_guide, to_guide], _) = guide_names(setup, m);
            SegmentReport {
                segment: setup.segment_name(m),
                from_guide,
                to_guide,
                kind: segment_kind(setup, m),
                traversed_joints: poses.traversed[m]
                    .iter()
                    .map(|&j| motion.joint_names()[j].clone())
                    .collect(),
                test_poses: poses.poses[m]
                    .iter()
                    .map(|p| pose_summary(p, motion))
                    .collect(),
                d0: s.d0,
                d0_pruned: s.d0_pruned,
                d1: s.d1,
                d2: s.d2.len(),
                rejections: s.rejections.clone(),
                evaluations: s.evaluations,
                static_solves: s.static_solves,
            }
        })
        .collect()
}

/// A test pose in the motion's display units (deg / mm).
pub fn pose_summary(pose: &TestPose, motion: &Motion) -> PoseSummary {
    let joints = pose
        .joints
        .iter()
        .zip(motion.rotary())
        .map(|(v, &rotary)| if rotary { v.to_degrees() } else { v * 1e3 })
        .collect();
    PoseSummary {
        sample: pose.sample,
        time_s: pose.time_s,
        joints,
        reason: pose.reason.clone(),
    }
}

/// A limit's name, threshold, value in the metrics, and sign (+1: the value must stay above
/// the threshold, −1: below).
type LimitOf = (&'static str, f64, fn(&Metrics) -> Option<f64>, f64);

/// The smallest margin of each limit over the test poses, for every segment with a cable.
fn margins(evaluator: &Evaluator<'_>, poses: &SegmentPoses, path: &CablePath) -> Vec<Margin> {
    let setup = evaluator.setup();
    let limits = &setup.thresholds;
    let mut margins = Vec::new();
    for (m, pv) in path.pieces() {
        let checked: Vec<(&TestPose, Metrics)> = poses.poses[m]
            .iter()
            .filter_map(|pose| Some((pose, evaluator.check(m, &pv, pose).metrics?)))
            .collect();
        let limits_of: [LimitOf; 3] = [
            (
                "contact",
                limits.contact_clearance_m,
                |x| x.clearance_m,
                1.0,
            ),
            ("stretch", limits.stretch, |x| Some(x.stretch), -1.0),
            (
                "bend_radius",
                limits.min_bend_radius_m,
                |x| Some(x.min_bend_radius_m).filter(|r| r.is_finite()),
                1.0,
            ),
        ];
        for (constraint, threshold, value_of, sign) in limits_of {
            let binding = checked
                .iter()
                .filter_map(|(pose, metrics)| {
                    value_of(metrics).map(|v| (pose, v, sign * (v - threshold)))
                })
                .min_by(|a, b| a.2.total_cmp(&b.2));
            if let Some((pose, value, margin)) = binding {
                margins.push(Margin {
                    segment: setup.segment_name(m),
                    constraint,
                    value,
                    threshold,
                    margin,
                    sample: pose.sample,
                    time_s: pose.time_s,
                    reason: pose.reason.clone(),
                });
            }
        }
    }
    margins
}

impl fmt::Display for SolveReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.inputs;
        writeln!(f, "{} — {}", self.status.describe(), self.explanation)?;
        writeln!(
            f,
            "setup {} (hash {}), cable {}, {}, motion {}{:.2} s, {} samples",
            i.setup_file,
            i.setup_hash,
            i.cable,
            i.method,
            i.motion_file
                .as_deref()
                .map(|m| format!("{m}, "))
                .unwrap_or_default(),
            i.motion_duration_s,
            i.motion_samples
        )?;
        if let Some(d) = &i.dictionary {
            writeln!(
                f,
                "intra-link pieces from dictionary {} ({} stored gravity directions, at most \
                 {:.1}° from any direction)",
                d.file, d.directions, d.covering_radius_deg,
            )?;
            for s in &d.segments {
                let p = &s.pieces;
                writeln!(
                    f,
                    "  {}: {} gravity directions of the motion; {} pieces hold, {} fail by the \
                     stored margins, {} too close to a limit were solved ({} of them failed)",
                    s.segment, s.gravity_directions, p.holds, p.fails, p.solved, p.solved_failed
                )?;
            }
            let c = &d.certification;
            match (c.pieces_solved, c.disagreements.len()) {
                (0, _) => writeln!(f, "  certified: the chains offered took no stored piece")?,
                (n, k) => writeln!(
                    f,
                    "  certified: the stored pieces the chains offered and their robustness \
                     neighbours solved exactly ({n} pieces); {}",
                    match k {
                        0 => "the file agrees".to_string(),
                        1 => "1 record contradicted".to_string(),
                        k => format!("{k} records contradicted"),
                    }
                )?,
            }
            for disagreement in &c.disagreements {
                writeln!(f, "  {}", disagreement.describe(&d.file))?;
            }
            if let Some(provenance) = &d.provenance {
                writeln!(f, "  {}", provenance.describe())?;
            }
        }
        if let (Some(path), Some(total)) = (&self.optimal, self.optimal_length_mm) {
            writeln!(f, "\ncable path — total {total:.0} mm")?;
            write_path(f, path)?;
        }
        write_sets(f, &self.segments, &self.chains)?;
        write_margins(f, &self.margins)?;
        let sweep = &self.static_sweep;
        if sweep.poses > 0 {
            let per_segment = dropped_per_segment(sweep);
            let per_segment = if per_segment.is_empty() {
                per_segment
            } else {
                format!(" ({per_segment})")
            };
            writeln!(
                f,
                "\nstatic sweep: {} cable pieces solved at {} motion poses, {} dropped{per_segment}",
                sweep.pvs_swept,
                sweep.poses,
                sweep.rejected.len(),
            )?;
        }
        if let Some(report) = &self.motion_test {
            writeln!(
                f,
                "\nmotion test ({} engine): {}",
                self.motion_engine,
                report.summary()
            )?;
        }
        if let Some(diagnosis) = &self.diagnosis {
            writeln!(f, "\nwhy there is no path")?;
            for line in diagnosis.to_string().lines() {
                writeln!(f, "  {line}")?;
            }
        }
        let t = &self.timings;
        writeln!(
            f,
            "\ntimings: critical poses {:.3} s, attachment {:.2} s, chain search {:.3} s, static sweep {:.2} s, motion test {:.2} s, total {:.2} s",
            t.critical_poses_s,
            t.attachment_s,
            t.chain_s,
            t.static_sweep_s,
            t.motion_test_s,
            t.total_s
        )
    }
}

fn write_path(f: &mut fmt::Formatter<'_>, path: &Ecpv) -> fmt::Result {
    use crate::text_table::{Align, TextTable, decimal};
    let triple = |v: [f64; 3]| format!("({})", v.map(|x| decimal(x, 1)).join(", "));
    let mut pieces = TextTable::new(
        2,
        &[
            ("piece", Align::Left),
            ("clamps", Align::Left),
            ("links", Align::Left),
            ("kind", Align::Left),
            ("length", Align::Right),
        ],
    );
    for s in &path.segments {
        pieces.row(vec![
            s.name.clone(),
            format!("{}→{}", s.from_guide, s.to_guide),
            format!("{}→{}", s.from_link, s.to_link),
            s.kind.to_string(),
            format!("{:.0} mm", s.length_mm),
        ]);
    }
    let mut clamps = TextTable::new(
        2,
        &[
            ("clamp", Align::Left),
            ("link", Align::Left),
            ("placement", Align::Left),
            ("xyz (mm)", Align::Right),
            ("rpy (deg)", Align::Right),
        ],
    );
    for g in &path.guides {
        clamps.row(vec![
            g.name.clone(),
            g.link.clone(),
            g.configuration.clone(),
            triple(g.xyz_mm),
            triple(g.rpy_deg),
        ]);
    }
    write!(f, "{pieces}{clamps}")?;
    if !path.left_out.is_empty() {
        writeln!(f, "  left out (optional): {}", path.left_out.join(", "))?;
    }
    Ok(())
}

fn write_sets(f: &mut fmt::Formatter<'_>, segments: &[SegmentReport], chains: &str) -> fmt::Result {
    writeln!(
        f,
        "\ncable pieces  {:>10} {:>10} {:>10} {:>10}  rejected (first limit violated)",
        "candidates", "pruned", "hold", "robust"
    )?;
    for s in segments {
        let rejected: Vec<String> = s
            .rejections
            .iter()
            .map(|(r, n)| format!("{} {n}", r.name()))
            .collect();
        writeln!(
            f,
            "  {:<11} {:>10} {:>10} {:>10} {:>10}  {}",
            s.segment,
            s.d0,
            s.d0_pruned,
            s.d1,
            s.d2,
            rejected.join(", ")
        )?;
    }
    writeln!(f, "  chains of robust pieces through the clamps: {chains}")
}

fn write_margins(f: &mut fmt::Formatter<'_>, margins: &[Margin]) -> fmt::Result {
    if margins.is_empty() {
        return Ok(());
    }
    writeln!(f, "\nstatic margins at the binding test pose")?;
    for m in margins {
        // A stretch ratio to 1e-4, lengths to 0.1 mm.
        let (scale, digits, unit) = match m.constraint {
            "stretch" => (1.0, 4, ""),
            _ => (1e3, 1, " mm"),
        };
        let (value, threshold, margin) = (m.value * scale, m.threshold * scale, m.margin * scale);
        writeln!(
            f,
            "  {:<4} {:<12} {value:>8.digits$}{unit} (limit {threshold}{unit}, margin \
             {margin:+.digits$}{unit}) at t = {:.2} s ({})",
            m.segment,
            m.constraint.replace('_', " "),
            m.time_s,
            m.reason
        )?;
    }
    Ok(())
}
