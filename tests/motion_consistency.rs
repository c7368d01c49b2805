//! The motion test and the statics are one cable model (issue: a still robot's cable *is*
//! its static equilibrium). References computed another way: each segment's static
//! equilibrium solved directly from its connected geometry, and the static sweep's worst
//! values from independent solves at every motion sample.
//!
//! - At rest, on both bundled setups, for 1×, 10×, 30× and 100× the paper's stiffness: from
//!   the first step on, every node within 0.5 mm and every segment's bend radius within 1 % of
//!   the static equilibrium.
//! - In slow motion: as the bundled pick-and-place motion is played 4×, 10× and 20× slower,
//!   the motion test's worst bend radius and clearance approach the static sweep's.

use cable_dict::attachment::{ConnectMethod, Evaluator};
use cable_dict::geometry::{connect, sag_direction};
use cable_dict::motion::Motion;
use cable_dict::motion_test::{MotionTestOptions, MotionTestReport, run};
use cable_dict::path::CablePath;
use cable_dict::pose::Pose;
use cable_dict::setup::Setup;
use cable_dict::statics::{FarEnd, RodParameters, SolverOptions, solve_segment};
use cable_dict::stress::min_bend_radius;
use nalgebra::{Point3, Vector3};

fn bundled(name: &str) -> Setup {
    let root = crate::common::root();
    Setup::from_file(root.join("robots/viper_s850/hand_written").join(name))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn motion(setup: &Setup, name: &str) -> Motion {
    let root = crate::common::root();
    Motion::from_csv_file(&setup.robot, root.join("motions/viper_s850").join(name))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The setup with the paper's cable (Table 3: `EI = kb·l`, `GJ = kt·l`) scaled by `scale`.
fn with_paper_stiffness(setup: &Setup, cable_file: &str, scale: f64) -> Setup {
    let root = crate::common::root();
    let paper = cable_dict::cable::CableSpec::from_file(root.join("cables").join(cable_file))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut scaled = setup.clone();
    scaled.cable.bending_stiffness_n_m2 = scale * paper.bending_stiffness_n_m2;
    scaled.cable.torsion_stiffness_n_m2 = scale * paper.torsion_stiffness_n_m2;
    scaled
}

/// Segment `m`'s equilibrium at `link_poses`, solved directly (tight tolerance) from its
/// connected geometry, with its clamps as the attachment test turns them, piece by piece.
fn equilibrium(
    setup: &Setup,
    link_poses: &[Pose],
    path: &CablePath,
    m: usize,
) -> (Vec<Point3<f64>>, Pose, Pose) {
    let pv = path.pv(m);
    let (start, end) = setup.clamp_poses(link_poses, m, pv.sub_segments, (pv.start, pv.end));
    let pitch = setup.cable.sub_segment_pitch_m;
    let connected = connect(
        &start,
        &end,
        pv.sub_segments,
        pitch,
        &sag_direction(&setup.gravity_m_s2),
    )
    .unwrap_or_else(|e| panic!("C{}: {e}", m + 1));
    let params = RodParameters::new(&setup.cable, setup.gravity_m_s2);
    let options = SolverOptions {
        force_tolerance_n: 1e-8,
        max_iterations: 500,
    };
    let solved = solve_segment(
        &params,
        &start,
        &FarEnd::Clamped(end),
        &connected.nodes,
        Some(connected.twist_correction_rad),
        &options,
    )
    .unwrap_or_else(|e| panic!("C{}: {e}", m + 1));
    (solved.nodes, start, end)
}

/// The robot resting at the motion's first pose for `duration_s`.
fn at_rest(setup: &Setup, motion: &Motion, duration_s: f64) -> Motion {
    let q0 = motion.samples()[0].clone();
    Motion::new(&setup.robot, vec![0.0, duration_s], vec![q0.clone(), q0]).unwrap()
}

/// A mid-range path of each bundled setup: every segment with cable (its guides' first
/// configurations), lengths inside the candidate ranges.
fn paths() -> [(&'static str, &'static str, &'static str, CablePath); 2] {
    [
        (
            "pick_and_place.toml",
            "pick_and_place.csv",
            "smc_le_cp_3_paper.toml",
            CablePath::through_every_guide(vec![60, 24, 48, 22], vec![0, 0, 0, 0, 0]),
        ),
        (
            "inspection.toml",
            "inspection.csv",
            "gev_c6hf_paper.toml",
            CablePath::through_every_guide(vec![32, 16, 39, 20], vec![0, 0, 0, 0, 0]),
        ),
    ]
}

#[test]
fn a_still_robot_keeps_the_static_equilibrium_for_any_real_stiffness() {
    for (setup_file, motion_file, paper_cable, path) in paths() {
        let bundled = bundled(setup_file);
        let moving = motion(&bundled, motion_file);
        for scale in [1.0, 10.0, 30.0, 100.0] {
            let setup = with_paper_stiffness(&bundled, paper_cable, scale);
            let still = at_rest(&setup, &moving, 0.5);
            let options = MotionTestOptions {
                settle_tail_s: 0.0,
                shape_interval_s: Some(1e-6),
                ..MotionTestOptions::default()
            };
            let report = run(&setup, &path, &still, &options).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                report.failure.as_ref().is_none_or(
                    |f| f.reason.contains("bend radius") || f.reason.contains("contact")
                ),
                "{setup_file} ×{scale}: {}",
                report.summary()
            );
            let links = setup.robot.link_poses(&still.samples()[0]).unwrap();
            let references: Vec<_> = (0..setup.segment_count())
                .map(|m| equilibrium(&setup, &links, &path, m))
                .collect();
            let (offset, bend) = worst_deviation(&setup, &report, &references);
            eprintln!(
                "{setup_file} ×{scale:>3}: {} frames, nodes within {:.2e} mm, bend radius within {:.2e} of the static equilibrium",
                report.shapes.len(),
                offset * 1e3,
                bend
            );
            assert_eq!(report.shapes.len(), report.steps + 1);
            assert!(offset < 0.5e-3, "{setup_file} ×{scale}: {offset} m");
            assert!(bend < 0.01, "{setup_file} ×{scale}: {bend}");
        }
    }
}

/// With derived twist references (the robot-level pick-and-place setup), the whole cable the
/// motion test clamps — its clamps turned one after another from the first — rests in the
/// static equilibria of its pieces between the clamps as the attachment test turns them, each
/// piece on its own: a mistake in carrying the turns along the cable would twist the second
/// piece. The path is the setup's answer on pick and place (C2 at S = 0).
#[test]
fn a_still_robot_keeps_the_installed_cables_equilibrium() {
    let root = crate::common::root();
    let setup = Setup::from_file(root.join("robots/viper_s850/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let index = |g: usize, name: &str| {
        setup.guides[g]
            .configuration_index(name)
            .unwrap_or_else(|| panic!("no {name}"))
    };
    let path = CablePath::through_every_guide(
        vec![28, 0, 34],
        vec![
            index(0, "site 9 [-156 48 71] 90°"),
            index(1, "site 10 [22 68 173] 90°"),
            index(2, "site 10 [22 68 173] 90°"),
            0,
        ],
    );
    let still = at_rest(&setup, &motion(&setup, "pick_and_place.csv"), 0.3);
    let options = MotionTestOptions {
        settle_tail_s: 0.0,
        shape_interval_s: Some(1e-6),
        ..MotionTestOptions::default()
    };
    let report = run(&setup, &path, &still, &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.passed, "{}", report.summary());
    let links = setup.robot.link_poses(&still.samples()[0]).unwrap();
    let turned: Vec<f64> = [0, 2]
        .iter()
        .map(|&m| {
            setup.installed_twist_rad(
                m,
                path.lengths[m],
                (path.configurations[m], path.configurations[m + 1]),
            )
        })
        .collect();
    assert!(
        turned.iter().all(|t| t.abs() > 1e-3),
        "{turned:?}: nothing turned"
    );
    let references: Vec<_> = (0..setup.segment_count())
        .map(|m| match path.lengths[m] {
            0 => (Vec::new(), Pose::identity(), Pose::identity()),
            _ => equilibrium(&setup, &links, &path, m),
        })
        .collect();
    let (offset, bend) = worst_deviation(&setup, &report, &references);
    assert!(offset < 1e-6, "{offset} m");
    assert!(bend < 1e-6, "{bend}");
}

/// The largest node distance (m) and relative bend-radius difference between every kept
/// frame of `report` and the reference equilibria (segments with cable, in order).
fn worst_deviation(
    setup: &Setup,
    report: &MotionTestReport,
    references: &[(Vec<Point3<f64>>, Pose, Pose)],
) -> (f64, f64) {
    let pitch = setup.cable.sub_segment_pitch_m;
    let axis = |pose: &Pose| pose.rotation * Vector3::z();
    let (mut offset, mut bend) = (0.0_f64, 0.0_f64);
    for frame in &report.shapes {
        for segment in &frame.segments {
            let (nodes, start, end) = &references[segment.segment];
            let simulated: Vec<Point3<f64>> = segment
                .nodes_m
                .iter()
                .map(|p| Point3::new(p[0], p[1], p[2]))
                .collect();
            for (a, b) in simulated.iter().zip(nodes) {
                offset = offset.max((a - b).norm());
            }
            let radius =
                |n: &[Point3<f64>]| min_bend_radius(n, &axis(start), &axis(end), pitch).radius_m;
            bend = bend.max((radius(&simulated) / radius(nodes) - 1.0).abs());
        }
    }
    (offset, bend)
}

/// Worst bend radius and clearance of `path` over every sample of `motion`, each sample's
/// equilibrium solved from its connected geometry (the attachment test's check, no
/// continuation).
fn static_worst(setup: &Setup, motion: &Motion, path: &CablePath) -> (f64, f64) {
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).unwrap();
    let (mut bend, mut clearance) = (f64::INFINITY, f64::INFINITY);
    for joints in motion.samples() {
        let links = setup.robot.link_poses(joints).unwrap();
        for m in 0..setup.segment_count() {
            let pv = path.pv(m);
            if pv.sub_segments == 0 {
                continue;
            }
            let metrics = evaluator
                .check_at(m, &pv, &links)
                .metrics
                .expect("an equilibrium");
            bend = bend.min(metrics.min_bend_radius_m);
            clearance = clearance.min(metrics.clearance_m.unwrap_or(f64::INFINITY));
        }
    }
    (bend, clearance)
}

/// The first 2.3 s of the bundled pick-and-place (down to the pick and up again) played
/// `slower` times slower.
fn slowed(setup: &Setup, slower: f64) -> Motion {
    let full = motion(setup, "pick_and_place.csv");
    let keep = full.times_s().iter().filter(|&&t| t <= 2.3).count();
    let times = full.times_s()[..keep].iter().map(|t| t * slower).collect();
    Motion::new(&setup.robot, times, full.samples()[..keep].to_vec()).unwrap()
}

#[test]
fn in_slow_motion_the_motion_test_converges_to_the_static_sweep() {
    let (_, _, paper_cable, path) = paths()[0].clone();
    let bundled = bundled("pick_and_place.toml");
    for (cable, setup) in [
        ("realistic", bundled.clone()),
        ("paper ×1", with_paper_stiffness(&bundled, paper_cable, 1.0)),
    ] {
        let (static_bend, static_clearance) = static_worst(&setup, &slowed(&setup, 1.0), &path);
        let mut errors = Vec::new();
        for slower in [4.0, 10.0, 20.0] {
            let options = MotionTestOptions {
                settle_tail_s: 0.0,
                record_series: false,
                ..MotionTestOptions::default()
            };
            let report = run(&setup, &path, &slowed(&setup, slower), &options).unwrap();
            let worst =
                |w: &Option<cable_dict::motion_test::Worst>| w.as_ref().expect("worst").value;
            let bend = worst(&report.worst_bend);
            let clearance = worst(&report.worst_clearance);
            eprintln!(
                "{cable}, {slower}× slower: bend {:.3} mm (static {:.3}), clearance {:.3} mm (static {:.3})",
                bend * 1e3,
                static_bend * 1e3,
                clearance * 1e3,
                static_clearance * 1e3
            );
            errors.push((
                (bend / static_bend - 1.0).abs(),
                (clearance - static_clearance).abs(),
            ));
        }
        let (bend_error, clearance_error) = errors[errors.len() - 1];
        assert!(bend_error < 5e-3, "{cable}: {errors:?}");
        assert!(clearance_error < 0.1e-3, "{cable}: {errors:?}");
        // Closer as the motion slows: the inertial forces fall with the square of the speed.
        assert!(
            errors[0].0 >= bend_error && errors[0].1 >= clearance_error,
            "{cable}: {errors:?}"
        );
    }
}
