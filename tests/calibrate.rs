//! `cable-dict calibrate` against an independent solution of the heavy elastica
//! (`reference::elastica`, multiple shooting written from the continuum equations): the
//! droop or end angle the reference computes for a known EI gives that EI back; the printed
//! cable file loads and reproduces the bench test in the project's own statics; bad
//! measurements are refused by name.

use crate::common;
use crate::reference;

use cable_dict::cable::CableSpec;
use cable_dict::calibrate::{CantileverTest, TipMeasurement, torsion_stiffness};
use cable_dict::pose::pose_from_xyz_rpy;
use cable_dict::statics::{FarEnd, Holds, RodParameters, SolverOptions, solve_segment};
use common::run;
use nalgebra::{Point3, Vector3};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

const G: f64 = 9.81;
const RHO: f64 = 0.26;

/// Droop (m, > 0 downwards) and end angle (rad below the horizontal) of the reference heavy
/// cantilever clamped horizontally.
fn reference_tip(length: f64, ei: f64) -> (f64, f64) {
    let shape = reference::elastica::solve_cantilever(length, ei, RHO * G, 0.0)
        .unwrap_or_else(|e| panic!("reference: {e}"));
    let [_, z, angle] = shape.end_pose();
    (-z, -angle)
}

/// From the paper's floppy cable (droops ~90 % of the length) to a stiff one (0.1 %), both
/// measurements recover the reference's EI to 1e-6.
#[test]
fn the_measured_tip_gives_back_the_reference_bending_stiffness() {
    for (length, ei) in [
        (0.1, 5.1e-4),
        (0.3, 6e-3),
        (0.5, 6e-3),
        (0.2, 6e-2),
        (0.4, 2.5e-3),
    ] {
        let (droop, angle) = reference_tip(length, ei);
        for tip in [
            TipMeasurement::Droop(droop),
            TipMeasurement::EndAngle(angle),
        ] {
            let test = CantileverTest {
                length_m: length,
                mass_per_length_kg_m: RHO,
                gravity_m_s2: G,
                tip,
            };
            let (found, shape) = test.bending_stiffness().unwrap_or_else(|e| panic!("{e}"));
            eprintln!(
                "L {length} m, EI {ei}: droop {:.3} mm, end angle {:.3}° → EI {found:.9e}",
                droop * 1e3,
                angle.to_degrees()
            );
            assert!((found / ei - 1.0).abs() < 1e-6, "{tip:?}: {found} vs {ei}");
            assert!((shape.droop_over_length * length - droop).abs() < 1e-9);
        }
    }
}

/// The bench test of a calibrated cable, repeated with the project's discrete cable model
/// (a 300 mm cantilever of 30 sub-segments): the same droop within the model's
/// discretization error (0.5 %).
#[test]
fn the_calibrated_cable_droops_as_measured_in_the_discrete_model() {
    let (length, droop) = (0.3, 0.045);
    let test = CantileverTest {
        length_m: length,
        mass_per_length_kg_m: RHO,
        gravity_m_s2: G,
        tip: TipMeasurement::Droop(droop),
    };
    let (ei, _) = test.bending_stiffness().unwrap();
    let params = RodParameters {
        pitch_m: 0.01,
        bending_stiffness_n_m2: ei,
        torsion_stiffness_n_m2: 1.3 * ei,
        axial_stiffness_n: 1e6,
        mass_per_length_kg_m: RHO,
        gravity_m_s2: Vector3::new(0.0, 0.0, -G),
        holds: Holds::RIGID,
    };
    let clamp = pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0]);
    let straight: Vec<Point3<f64>> = (0..=30)
        .map(|k| Point3::new(0.01 * k as f64, 0.0, 0.0))
        .collect();
    let options = SolverOptions {
        force_tolerance_n: 1e-7,
        max_iterations: 200,
    };
    let shape = solve_segment(&params, &clamp, &FarEnd::Free, &straight, None, &options).unwrap();
    let model_droop = -shape.nodes[30].z;
    assert!(
        (model_droop / droop - 1.0).abs() < 5e-3,
        "model {model_droop} vs measured {droop}"
    );
}

/// `GJ = T·L/φ`: 0.05 N·m over 0.5 m turning the end by 90° is 0.05·0.5/(π/2).
#[test]
fn a_twist_test_gives_torque_times_length_over_angle() {
    let gj = torsion_stiffness(0.5, 0.05, FRAC_PI_2).unwrap();
    assert!((gj - 0.025 / FRAC_PI_2).abs() < 1e-15);
    assert!(torsion_stiffness(0.5, 0.0, 1.0).is_err());
}

/// The command line of a bench cable, the measurements left out.
const CABLE_ARGS: [&str; 11] = [
    "calibrate",
    "--name",
    "bench cable",
    "--diameter-mm",
    "8",
    "--mass-per-length-kg-m",
    "0.26",
    "--min-bend-radius-mm",
    "48",
    "--length-mm",
    "300",
];

/// The command prints a cable file that loads to the calibrated values (EI from the
/// reference's droop, GJ from the twist test) and writes the same text with `-o`.
#[test]
fn the_command_prints_a_cable_file_that_loads() {
    let (droop, _) = reference_tip(0.3, 6e-3);
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("cable.toml");
    let droop_mm = format!("{}", droop * 1e3);
    let out_arg = out.to_str().expect("utf-8");
    let output = run(&[
        &CABLE_ARGS[..],
        &[
            "--droop-mm",
            &droop_mm,
            "--gravity-m-s2",
            "9.81",
            "--twist-angle-deg",
            "90",
            "--twist-length-mm",
            "500",
            "--twist-torque-nm",
            "0.02",
            "-o",
            out_arg,
        ],
    ]
    .concat());
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8(output.stdout).expect("utf-8");
    assert_eq!(std::fs::read_to_string(&out).expect("written"), text);
    let cable = CableSpec::from_toml_str(&text, Path::new("printed")).expect("loads");
    assert_eq!(cable.name, "bench cable");
    assert!((cable.diameter_m - 0.008).abs() < 1e-12);
    // Six significant digits are printed.
    assert!(
        (cable.bending_stiffness_n_m2 / 6e-3 - 1.0).abs() < 1e-5,
        "{text}"
    );
    assert!((cable.torsion_stiffness_n_m2 / (0.02 * 0.5 / FRAC_PI_2) - 1.0).abs() < 1e-5);
    assert!((cable.min_bend_radius_m - 0.048).abs() < 1e-12);
}

/// Impossible measurements and missing ones exit with 2 and say what is wrong.
#[test]
fn bad_measurements_are_refused_by_name() {
    let base = CABLE_ARGS;
    let refused = |extra: &[&str], expected: &str| {
        let output = run(&[&base[..], extra].concat());
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(stderr.contains(expected), "{extra:?}: {stderr}");
    };
    refused(
        &["--droop-mm", "310", "--torsion-ratio", "1.3"],
        "droop of 310 mm",
    );
    refused(
        &["--end-angle-deg", "95", "--torsion-ratio", "1.3"],
        "end angle of 95",
    );
    refused(
        &["--droop-mm=-5", "--torsion-ratio", "1.3"],
        "droop of -5 mm",
    );
    refused(
        &["--droop-mm", "20", "--torsion-ratio", "0"],
        "--torsion-ratio 0",
    );
    refused(&["--droop-mm", "20"], "--torsion-ratio");
    refused(&["--torsion-ratio", "1.3"], "--droop-mm");
    refused(
        &[
            "--droop-mm",
            "20",
            "--twist-angle-deg",
            "30",
            "--twist-length-mm",
            "500",
        ],
        "--twist-torque-nm",
    );
}
