//! The result JSON: [`SolveReport`] serialized under the documented field names.

use super::super::diagnosis::Diagnosis;
use super::data::*;
use crate::motion_test::{ClampLoadPeak, EngineKind, MotionTestReport, PieceTwist, Worst};
use serde::Serialize;

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
    /// The closest approach of the cable to itself (centreline distance − diameter, mm);
    /// `None` when no part of it comes back toward another.
    min_self_clearance_mm: Option<f64>,
    worst_clearance: Option<&'a Worst>,
    worst_stretch: Option<&'a Worst>,
    worst_bend_radius: Option<&'a Worst>,
    worst_contact_force: Option<&'a Worst>,
    worst_self_clearance: Option<&'a Worst>,
    /// Per piece, its largest twist over the motion (deg and deg/m), relative to the cable
    /// as installed.
    twists: Option<&'a [PieceTwist]>,
    /// Per clamp, the largest force and moment the cable puts on it.
    clamp_loads: Option<&'a [ClampLoadPeak]>,
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
            min_self_clearance_mm: report.and_then(|r| mm(&r.worst_self_clearance)),
            worst_clearance: report.and_then(|r| r.worst_clearance.as_ref()),
            worst_stretch: report.and_then(|r| r.worst_stretch.as_ref()),
            worst_bend_radius: report.and_then(|r| r.worst_bend.as_ref()),
            worst_contact_force: report.and_then(|r| r.worst_contact_force.as_ref()),
            worst_self_clearance: report.and_then(|r| r.worst_self_clearance.as_ref()),
            twists: report.map(|r| r.twists.as_slice()),
            clamp_loads: report.map(|r| r.clamp_loads.as_slice()),
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
    candidates: &'a [CandidateOutcome],
    static_sweep: &'a SweepSummary,
    margins: &'a [Margin],
    reason: Option<&'a str>,
    diagnosis: Option<&'a Diagnosis>,
    unsolved: Option<&'a Unsolved>,
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
            unsolved: self.unsolved.as_ref(),
            inputs: &self.inputs,
            timings_s: &self.timings,
        }
        .serialize(serializer)
    }
}
