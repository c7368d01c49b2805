//! The cable dynamics (`cable_dict::dynamics`) against references computed another way:
//! the static equilibrium (a cable at rest stays there), the closed-form vibrations of the
//! continuous Euler–Bernoulli cantilever and of the hanging chain
//! (`reference::vibration`), and the time integrator's order of convergence.

use crate::reference;

use cable_dict::dynamics::{IntegratorSettings, SegmentDynamics};
use cable_dict::pose::{Pose, pose_from_xyz_rpy};
use cable_dict::statics::{FarEnd, Holds, RodParameters, SolverOptions, solve_segment};
use nalgebra::{Point3, Vector3};
use reference::vibration;
use std::f64::consts::FRAC_PI_2;

const PITCH: f64 = 0.01;
const RHO: f64 = 0.26;

fn rod(ei: f64, gravity: f64) -> RodParameters {
    RodParameters {
        pitch_m: PITCH,
        bending_stiffness_n_m2: ei,
        torsion_stiffness_n_m2: 1.3 * ei,
        axial_stiffness_n: 1e6,
        mass_per_length_kg_m: RHO,
        gravity_m_s2: Vector3::new(0.0, 0.0, -gravity),
        holds: Holds::RIGID,
    }
}

/// A clamp at the origin whose +z axis (the cable's direction) is world +x.
fn along_x() -> Pose {
    pose_from_xyz_rpy([0.0; 3], [0.0, FRAC_PI_2, 0.0])
}

/// A clamp at the origin whose +z axis is world −z (the cable hangs from it).
fn hanging() -> Pose {
    pose_from_xyz_rpy([0.0; 3], [0.0, std::f64::consts::PI, 0.0])
}

/// Nodes one pitch apart whose direction turns by `angle(s)` from `direction` towards
/// `across` (s the arc length of each sub-segment's midpoint): an exact-length polyline.
fn polyline(
    sub_segments: usize,
    direction: Vector3<f64>,
    across: Vector3<f64>,
    angle: impl Fn(f64) -> f64,
) -> Vec<Point3<f64>> {
    let mut nodes = vec![Point3::origin()];
    for k in 0..sub_segments {
        let a = angle((k as f64 + 0.5) * PITCH);
        let last = nodes[k];
        nodes.push(last + PITCH * (a.cos() * direction + a.sin() * across));
    }
    nodes
}

/// Times of the downward zero crossings of `signal` (linear interpolation).
fn downward_crossings(times: &[f64], signal: &[f64]) -> Vec<f64> {
    (1..signal.len())
        .filter(|&i| signal[i - 1] > 0.0 && signal[i] <= 0.0)
        .map(|i| {
            let f = signal[i - 1] / (signal[i - 1] - signal[i]);
            times[i - 1] + f * (times[i] - times[i - 1])
        })
        .collect()
}

/// The mean period of a signal from its downward zero crossings.
fn period(times: &[f64], signal: &[f64]) -> f64 {
    let crossings = downward_crossings(times, signal);
    assert!(crossings.len() >= 3, "too few oscillations: {crossings:?}");
    (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64
}

/// Runs `cable` for `duration_s` with fixed guides, recording `probe(nodes)` per step.
fn record(
    cable: &mut SegmentDynamics,
    settings: &IntegratorSettings,
    duration_s: f64,
    probe: impl Fn(&[Point3<f64>]) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    let steps = (duration_s / settings.time_step_s).round() as usize;
    let (start, end) = (cable.start(), cable.far_end());
    let mut times = vec![0.0];
    let mut values = vec![probe(&cable.nodes())];
    for k in 1..=steps {
        let report = cable
            .step(start, end, settings.time_step_s, settings)
            .unwrap_or_else(|e| panic!("step {k}: {e}"));
        assert_eq!(report.substeps, 1, "step {k} was retried");
        times.push(k as f64 * settings.time_step_s);
        values.push(probe(&cable.nodes()));
    }
    (times, values)
}

/// A cantilever along +x in the shape of its first mode, `tip_m` at the free end.
fn first_mode_cantilever(length: f64, tip_m: f64) -> Vec<Point3<f64>> {
    let sub_segments = (length / PITCH).round() as usize;
    let amplitude = tip_m / vibration::cantilever_mode(1, length, length);
    // The slope of the deflection w(x) = amplitude · φ(x), by central differences.
    let slope = |x: f64| {
        let h = 1e-6;
        amplitude
            * (vibration::cantilever_mode(1, length, x + h)
                - vibration::cantilever_mode(1, length, x - h))
            / (2.0 * h)
    };
    polyline(sub_segments, Vector3::x(), Vector3::z(), |s| {
        slope(s).atan()
    })
}

/// A cantilever released from its first mode's shape (1 mm tip deflection, no gravity)
/// vibrates at the Euler–Bernoulli frequency `(β₁L)² √(EI/ρL⁴)`: within 0.5 % for 25
/// sub-segments (measured 0.15 %), for a cable as stiff as the realistic presets and 10×
/// stiffer.
#[test]
fn a_cantilever_vibrates_at_the_euler_bernoulli_frequency() {
    let length = 0.25;
    for ei in [6e-3, 6e-2] {
        let params = rod(ei, 0.0);
        let nodes = first_mode_cantilever(length, 1e-3);
        let mut cable = SegmentDynamics::at_rest(&params, along_x(), FarEnd::Free, &nodes, 0.0)
            .unwrap_or_else(|e| panic!("{e}"));
        let omega = vibration::cantilever_omega(1, length, ei, RHO);
        let expected = std::f64::consts::TAU / omega;
        let settings = IntegratorSettings {
            time_step_s: expected / 400.0,
            ..IntegratorSettings::default()
        };
        let (times, tip) = record(&mut cable, &settings, 3.2 * expected, |n| n[n.len() - 1].z);
        let measured = period(&times, &tip);
        eprintln!("cantilever EI {ei}: period {measured:.6} s, Euler–Bernoulli {expected:.6} s");
        assert!(
            (measured / expected - 1.0).abs() < 0.005,
            "EI {ei}: period {measured:.5} s, Euler–Bernoulli {expected:.5} s"
        );
    }
}

/// A limp cable hanging from a clamp, released from the hanging chain's first mode shape
/// (2 mm at the free end), swings at `(j₀₁/2) √(g/L)`: within 0.5 % for 50 sub-segments
/// (measured 0.02 %).
#[test]
fn a_hanging_limp_cable_swings_at_the_hanging_chain_frequency() {
    let length = 0.5;
    let sub_segments = (length / PITCH).round() as usize;
    let g = 9.81;
    let params = rod(1e-7, g);
    let amplitude = 2e-3;
    // u(s) = amplitude · J0(j01 √(s/L)), s measured up from the free end; the node at arc
    // length a from the clamp is at s = L − a.
    let slope = |a: f64| {
        let h = 1e-7;
        let u = |a: f64| amplitude * vibration::hanging_chain_mode(1, length, length - a);
        (u(a + h) - u(a - h)) / (2.0 * h)
    };
    let nodes = polyline(sub_segments, -Vector3::z(), Vector3::x(), |a| {
        slope(a).atan()
    });
    let mut cable = SegmentDynamics::at_rest(&params, hanging(), FarEnd::Free, &nodes, 0.0)
        .unwrap_or_else(|e| panic!("{e}"));
    let omega = vibration::hanging_chain_omega(1, length, g);
    let expected = std::f64::consts::TAU / omega;
    let settings = IntegratorSettings {
        time_step_s: expected / 400.0,
        ..IntegratorSettings::default()
    };
    let (times, end) = record(&mut cable, &settings, 3.2 * expected, |n| n[n.len() - 1].x);
    let measured = period(&times, &end);
    eprintln!("hanging chain: period {measured:.6} s, closed form {expected:.6} s");
    assert!(
        (measured / expected - 1.0).abs() < 0.005,
        "period {measured:.5} s, hanging chain {expected:.5} s"
    );
}

/// A cable at rest at its static equilibrium stays there exactly: its nodes do not move by
/// more than a micrometre in a second, for a sagging span of 1×, 10× and 30× the paper's
/// stiffness.
#[test]
fn a_cable_at_its_static_equilibrium_stays_there() {
    let start = along_x();
    let end = pose_from_xyz_rpy([0.3, 0.0, -0.05], [0.0, 2.0, 0.0]);
    for scale in [1.0, 10.0, 30.0] {
        let params = rod(5.1e-4 * scale, 9.81);
        let guess = cable_dict::geometry::connect(&start, &end, 40, PITCH, &-Vector3::z_axis())
            .unwrap_or_else(|e| panic!("{e}"));
        let equilibrium = solve_segment(
            &params,
            &start,
            &FarEnd::Clamped(end),
            &guess.nodes,
            Some(guess.twist_correction_rad),
            &SolverOptions::STRESS_CHECK,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let mut cable = SegmentDynamics::at_rest(
            &params,
            start,
            FarEnd::Clamped(end),
            &equilibrium.nodes,
            equilibrium.twist_rad,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let settings = IntegratorSettings::default();
        let (_, drift) = record(&mut cable, &settings, 1.0, |nodes| {
            nodes
                .iter()
                .zip(&equilibrium.nodes)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max)
        });
        let worst = drift.iter().copied().fold(0.0, f64::max);
        eprintln!("stiffness ×{scale}: largest drift {worst:e} m");
        assert!(worst < 1e-6, "stiffness ×{scale}: moved {worst:e} m");
    }
}

/// BDF2 is second order: a rigid 200 mm sub-segment swinging on its clamp's bending spring
/// (a one-node cantilever: one slow mode, ω ≈ 7.6 rad/s, and the axial one, never excited)
/// is, after 0.3 s, closer to a run with 8× finer steps by a factor ≈ 4 each time the step
/// halves.
#[test]
fn the_time_integration_converges_with_order_two() {
    let params = RodParameters {
        pitch_m: 0.2,
        axial_stiffness_n: 1e4,
        ..rod(6e-3, 0.0)
    };
    let angle: f64 = 0.05;
    let nodes = [
        Point3::origin(),
        Point3::new(0.2 * angle.cos(), 0.0, 0.2 * angle.sin()),
    ];
    let tip_after = |step: f64| {
        let mut cable = SegmentDynamics::at_rest(&params, along_x(), FarEnd::Free, &nodes, 0.0)
            .unwrap_or_else(|e| panic!("{e}"));
        let settings = IntegratorSettings {
            time_step_s: step,
            solver: SolverOptions {
                force_tolerance_n: 1e-7,
                max_iterations: 100,
            },
            ..IntegratorSettings::default()
        };
        let (_, tip) = record(&mut cable, &settings, 0.3, |n| n[n.len() - 1].z);
        tip[tip.len() - 1]
    };
    let steps = [0.3 / 40.0, 0.3 / 80.0, 0.3 / 160.0];
    let reference = tip_after(0.3 / 1280.0);
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| (tip_after(h) - reference).abs())
        .collect();
    eprintln!("tip errors {errors:?}");
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!(
            (1.7..2.3).contains(&order),
            "errors {errors:?}: observed order {order:.2}"
        );
    }
}
