//! The result JSON: [`SolveReport`] serialized under the documented field names.

use super::super::diagnosis::Diagnosis;
use super::data::*;
use crate::motion_test::{
    ClampLoadPeak, ClampTurn, EngineKind, GuideSlide, MotionTestReport, PieceTwist, PieceWorst,
    Worst,
};
use serde::Serialize;

#[derive(Serialize)]
struct MotionTestJson<'a> {
    engine: EngineKind,
    candidates_tried: usize,
    #[serde(flatten)]
    test: TestJson<'a>,
}

/// One motion test's verdict and worst values.
#[derive(Serialize)]
struct TestJson<'a> {
    passed: Option<bool>,
    failure: Option<&'a str>,
    /// Largest contact force outside the clamp zones (N); 0 when the cable never touched.
    max_contact: Option<f64>,
    min_clearance_mm: Option<f64>,
    max_stretch: Option<f64>,
    min_bend_radius_mm: Option<f64>,
    /// The closest approach of the cable to itself (centreline distance − diameter, mm);
    /// `None` when no part of it comes back toward another.
    min_self_clearance_mm: Option<f64>,
    /// Largest twist per length of a piece (deg/m), relative to the cable as installed;
    /// `None` where the engine does not model twist.
    max_twist_deg_per_m: Option<f64>,
    worst_clearance: Option<&'a Worst>,
    worst_stretch: Option<&'a Worst>,
    worst_bend_radius: Option<&'a Worst>,
    worst_contact_force: Option<&'a Worst>,
    worst_self_clearance: Option<&'a Worst>,
    worst_twist: Option<&'a Worst>,
    /// Per piece, its largest twist over the motion (deg and deg/m), relative to the cable
    /// as installed.
    twists: Option<&'a [PieceTwist]>,
    /// Per clamp, the largest force and moment the cable puts on it.
    clamp_loads: Option<&'a [ClampLoadPeak]>,
    /// Per rotating clamp between two pieces, the largest turn of the cable in it.
    clamp_turns: Option<&'a [ClampTurn]>,
    /// Per sliding guide and retraction outlet, how far the cable slid through it.
    slides: Option<&'a [GuideSlide]>,
    simulated_s: Option<f64>,
    wall_time_s: Option<f64>,
}

/// One motion of a cell: its name and verdict, and the path's motion test over it.
#[derive(Serialize)]
struct MotionJson<'a> {
    name: &'a str,
    file: Option<&'a str>,
    cycles_per_hour: Option<f64>,
    duration_s: f64,
    /// `holds`, `fails` or `not_run`; `static` for an axis-range grid.
    verdict: &'static str,
    /// An axis-range grid: its number of static poses.
    #[serde(skip_serializing_if = "Option::is_none")]
    grid_poses: Option<usize>,
    #[serde(flatten)]
    test: TestJson<'a>,
    /// Per piece, its own worst values over this motion.
    pieces: Option<&'a [PieceWorst]>,
}

impl<'a> MotionJson<'a> {
    fn new(verdict: &'a MotionVerdict) -> Self {
        let test = verdict.motion_test.as_ref();
        MotionJson {
            name: &verdict.name,
            file: verdict.file.as_deref(),
            cycles_per_hour: verdict.cycles_per_hour,
            duration_s: verdict.duration_s,
            verdict: verdict.verdict(),
            grid_poses: verdict.grid_poses,
            test: TestJson::new(test),
            pieces: test.map(|t| t.pieces.as_slice()),
        }
    }
}

impl<'a> TestJson<'a> {
    fn new(report: Option<&'a MotionTestReport>) -> Self {
        let mm = |w: &Option<Worst>| w.as_ref().map(|w| w.value * 1e3);
        Self {
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
            min_self_clearance_mm: report.and_then(|r| mm(&r.worst_self_clearance)),
            max_twist_deg_per_m: report.and_then(|r| r.worst_twist.as_ref().map(|w| w.value)),
            worst_clearance: report.and_then(|r| r.worst_clearance.as_ref()),
            worst_stretch: report.and_then(|r| r.worst_stretch.as_ref()),
            worst_bend_radius: report.and_then(|r| r.worst_bend.as_ref()),
            worst_contact_force: report.and_then(|r| r.worst_contact_force.as_ref()),
            worst_self_clearance: report.and_then(|r| r.worst_self_clearance.as_ref()),
            worst_twist: report.and_then(|r| r.worst_twist.as_ref()),
            twists: report.map(|r| r.twists.as_slice()),
            clamp_loads: report.map(|r| r.clamp_loads.as_slice()),
            clamp_turns: report.map(|r| r.clamp_turns.as_slice()),
            slides: report.map(|r| r.slides.as_slice()),
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
    ecpv: Option<&'a NamedPath>,
    mounting: Option<&'a crate::mounting::MountingPlan>,
    sets: &'a [SegmentReport],
    chains: &'a str,
    motion_test: Option<MotionTestJson<'a>>,
    motions: Vec<MotionJson<'a>>,
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    binding: &'a [PieceBinding],
    /// The predicted life (with a rated life in the cable file).
    life: Option<&'a crate::life::estimate::CableLife>,
    candidates: &'a [CandidateOutcome],
    static_sweep: &'a SweepSummary,
    margins: &'a [Margin],
    reason: Option<&'a str>,
    diagnosis: Option<&'a Diagnosis>,
    unsolved: Option<&'a Unsolved>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ranges: Option<&'a RangeDesign>,
    #[serde(skip_serializing_if = "Option::is_none")]
    allowed_ranges: Option<&'a AllowedRanges>,
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
            mounting: self.mounting.as_ref(),
            sets: &self.segments,
            chains: &self.chains,
            motion_test: self.motion_test_requested.then(|| MotionTestJson {
                engine: self.motion_engine,
                candidates_tried: self.candidates.len(),
                test: TestJson::new(self.motion_test.as_ref()),
            }),
            motions: self.motions.iter().map(MotionJson::new).collect(),
            binding: &self.binding,
            life: self.life.as_ref(),
            candidates: &self.candidates,
            static_sweep: &self.static_sweep,
            margins: &self.margins,
            reason: (self.status != Status::Solved).then_some(self.explanation.as_str()),
            diagnosis: self.diagnosis.as_ref(),
            unsolved: self.unsolved.as_ref(),
            ranges: self.ranges.as_ref(),
            allowed_ranges: self.allowed_ranges.as_ref(),
            inputs: &self.inputs,
            timings_s: &self.timings,
        }
        .serialize(serializer)
    }
}

/// The JSON `check --json` prints, named as the result JSON names the same things.
#[derive(Serialize)]
struct CheckJson<'a> {
    /// `holds` when every motion held every limit, else `fails`.
    verdict: &'static str,
    total_length_mm: f64,
    ecpv: &'a NamedPath,
    mounting: &'a crate::mounting::MountingPlan,
    motions: Vec<MotionJson<'a>>,
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    binding: &'a [PieceBinding],
    /// The predicted life (with a rated life in the cable file).
    life: Option<&'a crate::life::estimate::CableLife>,
    /// Over an axis-range box: every piece at a grid of its poses.
    #[serde(skip_serializing_if = "Option::is_none")]
    over_box: Option<&'a super::super::BoxCheck>,
    /// The ranges the mounting allows per axis (`check --allowed-ranges`).
    #[serde(skip_serializing_if = "Option::is_none")]
    allowed_ranges: Option<&'a AllowedRanges>,
    wall_time_s: f64,
}

impl Serialize for super::super::Check {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        CheckJson {
            verdict: if self.holds() { "holds" } else { "fails" },
            total_length_mm: self.length_mm,
            ecpv: &self.path,
            mounting: &self.mounting,
            motions: self.motions.iter().map(MotionJson::new).collect(),
            binding: &self.binding,
            life: self.life.as_ref(),
            over_box: self.over_box.as_ref(),
            allowed_ranges: self.allowed_ranges.as_ref(),
            wall_time_s: self.wall_time_s,
        }
        .serialize(serializer)
    }
}
