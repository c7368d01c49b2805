//! A cable never passes through itself in an answer: `segment` reports a twisted cable that
//! crosses itself as such, and the motion test refuses the hand-written pick-and-place
//! catalogue's short paths, whose two long loops hang into each other — checked here against
//! the shapes themselves by brute-force sampling, not through the tool's own metric.

use crate::common;

use cable_dict::attachment::Rejection;
use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve};
use nalgebra::Point3;
use serde_json::Value;

/// The smallest distance between points of the polyline `a` and points of `b`, sampled 20
/// times per sub-segment: an upper bound of the true distance, within a tenth of a pitch.
fn sampled_distance(a: &[Point3<f64>], b: &[Point3<f64>]) -> f64 {
    let samples = |line: &[Point3<f64>]| -> Vec<Point3<f64>> {
        line.windows(2)
            .flat_map(|w| (0..20).map(move |k| w[0] + (w[1] - w[0]) * (k as f64 / 20.0)))
            .collect()
    };
    let (a, b) = (samples(a), samples(b));
    a.iter()
        .flat_map(|p| b.iter().map(move |q| (p - q).norm()))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn the_catalogue_s_short_paths_touch_themselves_and_are_not_reported() {
    let root = crate::common::root();
    let setup = Setup::from_file(root.join("robots/viper_s850/hand_written/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(
        &setup.robot,
        root.join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let options = SolveOptions {
        k_best: 12,
        ..SolveOptions::default()
    };
    let report = solve(&setup, &motion, &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        report.status,
        Status::NonePassedMotionTest,
        "{}",
        report.explanation
    );
    // The attachment test refuses loops between the two link_4 clamps that touch themselves.
    let touching_pieces: usize = report
        .segments
        .iter()
        .filter_map(|s| s.rejections.get(&Rejection::SelfContact))
        .sum();
    assert!(touching_pieces > 0, "no piece refused as touching itself");
    let failures: Vec<&str> = report
        .candidates
        .iter()
        .filter_map(|c| c.failure.as_deref())
        .collect();
    let touching = failures
        .iter()
        .filter(|f| f.contains("self-contact"))
        .count();
    assert!(touching >= failures.len() / 2, "{failures:#?}");

    // The last motion test stopped at its violation: its final shape shows it.
    let test = report.motion_test.as_ref().expect("a motion test ran");
    let violation = test.first_violation.as_ref().expect("it failed");
    if !violation.constraint.to_string().contains("self") {
        return; // a chain that failed on another limit: nothing to check against
    }
    let shape: Vec<Vec<Point3<f64>>> = test
        .final_shape
        .iter()
        .map(|s| {
            s.nodes_m
                .iter()
                .map(|p| Point3::new(p[0], p[1], p[2]))
                .collect()
        })
        .collect();
    let closest = shape
        .iter()
        .enumerate()
        .flat_map(|(i, a)| {
            shape
                .iter()
                .skip(i + 1)
                .map(move |b| sampled_distance(a, b))
        })
        .fold(f64::INFINITY, f64::min);
    // Two different pieces, far apart along the cable, closer than the cable is thick.
    assert!(
        closest < setup.cable.diameter_m,
        "the pieces are {:.2} mm apart",
        closest * 1e3
    );
}

fn segment(extra: &[&str]) -> Value {
    let mut args = vec![
        "segment",
        "--cable",
        "cables/smc_le_cp_3.toml",
        "--json",
        "--start",
        "0,0,0,0,90,0",
    ];
    args.extend_from_slice(extra);
    let output = common::run(&args);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("JSON")
}

/// A taut straight cable takes a whole turn as pure twist: 360°, and no part of it comes
/// back toward another. Between clamps 100 mm apart in weak gravity, a 300 mm cable turned three times
/// relieves its twist by passing through itself; `segment` says so, from which angle on.
#[test]
fn segment_twist_turns_reach_whole_turns_and_report_a_cable_through_itself() {
    let taut = segment(&[
        "--end",
        "200,0,0,0,90,0",
        "--length-mm",
        "200",
        "--gravity",
        "0,0,0",
        "--twist-turns",
        "1",
    ]);
    let converged = &taut["converged"];
    let twist = converged["twist_deg"].as_f64().expect("twist");
    assert!((twist - 360.0).abs() < 1e-6, "{twist}");
    assert_eq!(converged["twist_turns"], 1);
    assert_eq!(converged["self_contact_from_deg"], Value::Null);
    // Straight, twisted or not, no part of it comes back toward another: no approach at all.
    assert_eq!(converged["metrics"]["self_contact"], Value::Null);

    let looped = segment(&[
        "--end",
        "100,0,0,0,90,0",
        "--length-mm",
        "300",
        "--gravity",
        "0,0,-0.5",
        "--twist-turns=-3",
    ]);
    let converged = &looped["converged"];
    let from = converged["self_contact_from_deg"]
        .as_f64()
        .expect("it crossed");
    assert!((-1080.0..0.0).contains(&from), "{from}");
    let itself = &converged["metrics"]["self_contact"];
    assert_eq!(itself["violation"], true, "{itself}");
    assert!(itself["min_clearance_mm"].as_f64().expect("mm") < 0.0);
}
