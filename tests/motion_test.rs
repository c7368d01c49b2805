//! The motion test (`cable_dict::motion_test`) against references computed here, another
//! way: the quasi-static equilibrium and the exact clearance of each segment at the poses
//! that matter, guide distances from forward kinematics, step counts from the time step,
//! a second run (determinism, early stop), and scans of the recorded series.
//!
//! Run in release (`cargo test --release --test motion_test`): the physics is stepped with
//! substeps of 1/3840 s. `realistic_pick_and_place_run` (ignored) runs the fixture setup on the bundled
//! pick-and-place motion in full and prints the reports.

use crate::common::{self, root};
use cable_dict::geometry::connect;
use cable_dict::motion::Motion;
use cable_dict::motion_test::{
    Constraint, Engine, FailureCause, MotionTestError, MotionTestOptions, MotionTestReport, run,
};
use cable_dict::path::CablePath;
use cable_dict::pose::Pose;
use cable_dict::rigid_chain::DynamicsSettings;
use cable_dict::robot::Robot;
use cable_dict::setup::Setup;
use cable_dict::statics::{Equilibrium, FarEnd, RodParameters, SolverOptions, solve_segment};
use cable_dict::stress::{Clearance, GuideEnd, Obstacles, min_bend_radius, min_clearance, stretch};
use nalgebra::{Point3, Vector3};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The many-configuration fixture setup (tests/data/motion_test_setup.toml) on the bundled
/// robot and cable; the tests pick guide configurations by name.
fn fixture_setup() -> Setup {
    Setup::from_file(root().join("tests/data/motion_test_setup.toml")).unwrap()
}

fn pick_and_place(setup: &Setup) -> Motion {
    Motion::from_csv_file(
        &setup.robot,
        root().join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap()
}

/// The motion's first `end_s` seconds (its samples up to then).
fn truncated(setup: &Setup, motion: &Motion, end_s: f64) -> Motion {
    let keep = motion.times_s().iter().filter(|&&t| t <= end_s).count();
    Motion::new(
        &setup.robot,
        motion.times_s()[..keep].to_vec(),
        motion.samples()[..keep].to_vec(),
    )
    .unwrap()
}

/// `motion` played `factor` times faster.
fn sped_up(setup: &Setup, motion: &Motion, factor: f64) -> Motion {
    let times = motion.times_s().iter().map(|t| t / factor).collect();
    Motion::new(&setup.robot, times, motion.samples().to_vec()).unwrap()
}

/// The motion test of `path` with the setup's own options (a valid input: unwrapped).
fn run_as_set_up(setup: &Setup, path: &CablePath, motion: &Motion) -> MotionTestReport {
    run(setup, path, motion, &MotionTestOptions::default()).unwrap()
}

/// The robot resting at `joints` for `duration_s`.
fn hold(setup: &Setup, joints: &[f64], duration_s: f64) -> Motion {
    Motion::new(
        &setup.robot,
        vec![0.0, duration_s],
        vec![joints.to_vec(), joints.to_vec()],
    )
    .unwrap()
}

/// A setup on the bundled robot and cable with the given guides and one segment; the
/// minimum bend radius is `min_bend_mm`.
fn custom_setup(guides: &str, lengths: &str, min_bend_mm: f64) -> Setup {
    let limits = common::limits(&format!("{min_bend_mm:.1}"));
    let text = format!(
        r#"robot = "viper_s850.urdf"
cable = "../../cables/smc_le_cp_3_paper.toml"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 2

{limits}
{guides}

[[segments]]
from = "A"
to = "B"
lengths = {lengths}
"#
    );
    let source: PathBuf = root().join("robots/viper_s850/motion-test-custom.toml");
    Setup::from_toml_str(&text, &source).unwrap()
}

/// Two guides 140 mm apart on the right side of the forearm tube (link_4), both along it;
/// S = 0 allowed, so B also gets A's pose as a coincident copy (configuration 1).
fn forearm_setup() -> Setup {
    custom_setup(
        r#"[[guides]]
name = "A"
link = "link_4"
configurations = [{ name = "right z60", position_mm = [0.0, -72.0, 60.0], rpy_deg = [0.0, 0.0, -90.0] }]

[[guides]]
name = "B"
link = "link_4"
configurations = [{ name = "right z200", position_mm = [0.0, -72.0, 200.0], rpy_deg = [0.0, 0.0, -90.0] }]"#,
        "{ min = 15, max = 30, step = 1, allow_zero = true }",
        5.0,
    )
}

/// The fixture setup's G1 "J4 housing right" (link_3) and G2 "forearm right z120" (link_4)
/// as a one-segment setup across joint 4.
fn across_joint_4_setup() -> Setup {
    custom_setup(
        r#"[[guides]]
name = "A"
link = "link_3"
configurations = [{ name = "J4 housing right", position_mm = [-90.0, -82.0, 100.0], rpy_deg = [0.0, 0.0, -90.0] }]

[[guides]]
name = "B"
link = "link_4"
configurations = [{ name = "forearm right z120", position_mm = [0.0, -72.0, 120.0], rpy_deg = [0.0, 0.0, -90.0] }]"#,
        "{ min = 10, max = 40, step = 1, allow_zero = false }",
        5.0,
    )
}

/// Index of the configuration of guide `g` named `name`.
fn configuration(setup: &Setup, g: usize, name: &str) -> usize {
    setup.guides[g]
        .configuration_index(name)
        .unwrap_or_else(|| panic!("{} has no configuration {name}", setup.guides[g].name))
}

/// Reference: one segment's guide poses from forward kinematics and the configuration poses.
fn guide_poses(setup: &Setup, joints: &[f64], m: usize, (i, j): (usize, usize)) -> (Pose, Pose) {
    let links = setup.robot.link_poses(joints).unwrap();
    let pose =
        |g: usize, c: usize| links[setup.guides[g].link] * setup.guides[g].configurations[c].pose;
    (pose(m, i), pose(m + 1, j))
}

/// Reference: the equilibrium of segment `m` with `s` sub-segments at `joints`, computed
/// directly (default, tighter solver tolerance) and its exact clearance to the robot with
/// the setup's clamp zones.
fn reference(
    setup: &Setup,
    joints: &[f64],
    m: usize,
    s: usize,
    configurations: (usize, usize),
) -> (Equilibrium, Clearance, (Pose, Pose)) {
    let (a, b) = guide_poses(setup, joints, m, configurations);
    let pitch = setup.cable.sub_segment_pitch_m;
    let start = connect(&a, &b, s, pitch, &-Vector3::z_axis()).unwrap();
    let options = SolverOptions {
        max_iterations: 500,
        ..SolverOptions::default()
    };
    let params = RodParameters::new(&setup.cable, setup.gravity_m_s2);
    let equilibrium = solve_segment(
        &params,
        &a,
        &FarEnd::Clamped(b),
        &start.nodes,
        Some(start.twist_correction_rad),
        &options,
    )
    .unwrap();
    let zone = |end, g: usize| setup.clamp_zone(end, setup.guides[g].link);
    let links = setup.robot.link_poses(joints).unwrap();
    let clearance = min_clearance(
        &Obstacles::from_robot(&setup.robot).unwrap(),
        &links,
        &equilibrium.nodes,
        0.5 * setup.cable.diameter_m,
        &[zone(GuideEnd::Start, m), zone(GuideEnd::End, m + 1)],
    )
    .unwrap()
    .unwrap();
    (equilibrium, clearance, (a, b))
}

fn steps_for(duration_s: f64, dt: f64) -> usize {
    // Whole steps covering the duration (the durations used here are whole multiples of
    // 1/240 s or not close to one).
    (duration_s / dt - 1e-9).ceil() as usize
}

/// (a) With the robot at rest, the simulated cable stays at the quasi-static equilibrium:
/// its shape, stretch and bend radius as the stress functions give on the equilibrium, and
/// the initial clearance as the exact query on it. The implicit engine minimizes the
/// statics' own energy, so it stays there to a micrometre; the rigid chain (the paper's
/// baseline, at the paper's stiffness) within 1 mm and 2 % of the bend radius.
#[test]
fn a_cable_held_still_stays_at_its_static_equilibrium() {
    let setup = forearm_setup();
    let q0 = pick_and_place(&fixture_setup()).samples()[0].clone();
    let motion = hold(&setup, &q0, 1.0);
    let path = CablePath::through_every_guide(vec![16], vec![0, 0]);
    let (equilibrium, clearance, (a, b)) = reference(&setup, &q0, 0, 16, (0, 0));
    let pitch = setup.cable.sub_segment_pitch_m;
    let reference_stretch = stretch(&equilibrium.nodes, 16.0 * pitch);
    let axis = |p: &Pose| p.rotation * Vector3::z();
    let reference_bend = min_bend_radius(&equilibrium.nodes, &axis(&a), &axis(&b), pitch);
    // The reference passes with margin, so the run must too.
    assert!(clearance.clearance_m > 5e-3, "{clearance:?}");
    assert!(reference_bend.radius_m > 2.0 * setup.thresholds.min_bend_radius_m);
    let engines = [
        // (engine, shape m, stretch, bend radius (relative))
        (MotionTestOptions::default(), 1e-6, 1e-6, 1e-4),
        (
            MotionTestOptions::new(Engine::RigidChain(DynamicsSettings::motion(
                setup.gravity_m_s2,
            ))),
            1e-3,
            2e-3,
            0.02,
        ),
    ];
    for (options, shape_tolerance, stretch_tolerance, bend_tolerance) in engines {
        let report = run(&setup, &path, &motion, &options).unwrap();
        assert!(report.passed, "{}", report.summary());
        let dt = options.time_step_s();
        assert_eq!(report.steps, steps_for(1.0, dt) + steps_for(0.5, dt));
        let final_nodes: Vec<Point3<f64>> = report.final_shape[0]
            .nodes_m
            .iter()
            .map(|p| Point3::new(p[0], p[1], p[2]))
            .collect();
        let offset = final_nodes
            .iter()
            .zip(&equilibrium.nodes)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        let last = report.series.last().unwrap();
        // Recomputed from the final nodes and the reference guide axes: the report's value.
        let final_bend = min_bend_radius(&final_nodes, &axis(&a), &axis(&b), pitch);
        assert!((final_bend.radius_m - last.min_bend_radius_m).abs() < 1e-9);
        eprintln!(
            "held still ({:?}): final shape within {:.6} mm of the equilibrium; stretch {:.6} vs {:.6}; bend {:.3} mm at node {} vs {:.3} mm at node {}",
            options.engine.kind(),
            offset * 1e3,
            last.max_stretch,
            reference_stretch,
            final_bend.radius_m * 1e3,
            final_bend.node,
            reference_bend.radius_m * 1e3,
            reference_bend.node
        );
        assert!(offset < shape_tolerance, "{offset} m");
        assert!((last.max_stretch - reference_stretch).abs() < stretch_tolerance);
        assert_eq!(final_bend.node, reference_bend.node);
        assert!(
            (final_bend.radius_m / reference_bend.radius_m - 1.0).abs() < bend_tolerance,
            "{final_bend:?} vs {reference_bend:?}"
        );
        let initial = report.series[0].min_clearance_m.unwrap();
        assert!((initial - clearance.clearance_m).abs() < 1e-6);
        assert_eq!(report.series[0].time_s, 0.0);
    }
}

/// (a') A guide whose clamp zone lies inside its own link (tests/data/small_setup.toml with G2
/// "left z250" moved into the wrist box of link_4, and a 40 mm clamp zone that reaches out of
/// it): the stress checks leave the zone out, so must the rigid chain's simulated contacts —
/// the cable held still stays at its equilibrium's clearance (it used to be pushed 8 mm into
/// the forearm within one step by the box pressing on the zone).
#[test]
fn a_clamp_zone_inside_its_guides_link_does_not_push_the_cable() {
    let path = root().join("tests/data/small_setup.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("[0.0, 80.0, 250.0]", "[0.0, 72.0, 250.0]")
        .replace("clamp_zone_mm = 20.0", "clamp_zone_mm = 40.0");
    let setup = Setup::from_toml_str(&text, &path).unwrap();
    let q0 = pick_and_place(&setup).samples()[0].clone();
    let path = CablePath::through_every_guide(vec![30], vec![0, 0]);
    let (_, clearance, _) = reference(&setup, &q0, 0, 30, (0, 0));
    assert!(clearance.clearance_m > 3e-3, "{clearance:?}");
    let rigid = MotionTestOptions::new(Engine::RigidChain(DynamicsSettings::motion(
        setup.gravity_m_s2,
    )));
    let report = run(&setup, &path, &hold(&setup, &q0, 0.2), &rigid).unwrap();
    assert!(report.passed, "{}", report.summary());
    assert!(report.worst_contact_force.is_none(), "{}", report.summary());
    let worst = report.worst_clearance.unwrap().value;
    assert!(
        (worst - clearance.clearance_m).abs() < 0.5e-3,
        "{worst} vs {clearance:?}"
    );
}

/// (b) A segment shorter than its guides' distance at the first pose is a failed candidate
/// (not an error) whose stretch is the distance over the natural length; the merged S = 0
/// segments do not shift the reported segment index.
#[test]
fn a_segment_shorter_than_its_guides_distance_fails_as_too_short() {
    let setup = fixture_setup();
    let motion = pick_and_place(&setup);
    let g3 = configuration(&setup, 2, "G2/forearm back z60");
    let g4 = configuration(&setup, 3, "G5/gripper connector");
    let path = CablePath::through_every_guide(vec![40, 0, 8, 0], vec![0, 0, g3, g4, 0]);
    let report = run_as_set_up(&setup, &path, &motion);

    let (a, b) = guide_poses(&setup, &motion.samples()[0], 2, (g3, g4));
    let distance = (b.translation.vector - a.translation.vector).norm();
    let required = distance / (8.0 * setup.cable.sub_segment_pitch_m);
    assert!(required > setup.thresholds.stretch, "{required}");
    assert!(!report.passed);
    let failure = report.failure.as_ref().unwrap();
    assert_eq!(failure.cause, FailureCause::TooShort, "{}", failure.reason);
    assert!(failure.reason.contains("C3"), "{}", failure.reason);
    let worst = report.worst_stretch.as_ref().unwrap();
    assert_eq!(worst.segment, 2);
    assert!((worst.value - required).abs() < 1e-9 * required);
    let violation = report.first_violation.as_ref().unwrap();
    assert_eq!(
        (violation.constraint, violation.segment),
        (Constraint::Stretch, 2)
    );
    assert_eq!(violation.threshold, setup.thresholds.stretch);
    assert_eq!((report.steps, report.final_shape.len()), (0, 0));
}

/// (c) A segment whose equilibrium runs through the forearm is reported as a contact of
/// that segment (C3, behind two merged S = 0 segments), with the exact clearance of the
/// reference; the other segment, clear in the reference, is not blamed. The rigid chain also
/// feels the forearm push the cable: a contact force on C3.
#[test]
fn a_segment_through_the_forearm_fails_with_contact() {
    let mut setup = fixture_setup();
    // The fixture guides bend every cable below 48 mm somewhere: only contact is under test.
    setup.thresholds.min_bend_radius_m = 1e-3;
    let q0 = pick_and_place(&setup).samples()[0].clone();
    let (g1, g2) = (
        configuration(&setup, 0, "J4 housing right"),
        configuration(&setup, 1, "forearm back z120"),
    );
    let g3 = configuration(&setup, 2, "G2/forearm back z120");
    let g4 = configuration(&setup, 3, "G5/gripper connector");
    let path = CablePath::through_every_guide(vec![20, 0, 50, 0], vec![g1, g2, g3, g4, 0]);
    let (_, clear, _) = reference(&setup, &q0, 0, 20, (g1, g2));
    let (_, hit, _) = reference(&setup, &q0, 2, 50, (g3, g4));
    assert!(clear.clearance_m > 2e-3, "C1 {clear:?}");
    assert!(hit.clearance_m < -0.02, "C3 {hit:?}");
    let engines = [
        Engine::Implicit(Default::default()),
        Engine::RigidChain(DynamicsSettings::motion(setup.gravity_m_s2)),
    ];
    for engine in engines {
        let options = MotionTestOptions {
            settle_tail_s: 0.0,
            ..MotionTestOptions::new(engine)
        };
        let report = run(&setup, &path, &hold(&setup, &q0, 0.1), &options).unwrap();
        assert!(!report.passed);
        let violation = report.first_violation.as_ref().unwrap();
        assert_eq!(violation.constraint, Constraint::Contact, "{violation}");
        assert_eq!((violation.segment, violation.time_s), (2, 0.0));
        assert!((violation.value - hit.clearance_m).abs() < 1e-6);
        let link = &setup.robot.links[hit.link].name;
        assert_eq!(violation.place.link.as_ref(), Some(link));
        assert_eq!(report.worst_clearance.as_ref().unwrap().segment, 2);
        eprintln!("through the forearm: {}", report.summary());
        match options.engine {
            Engine::RigidChain(_) => {
                let force = report.worst_contact_force.as_ref().unwrap();
                assert_eq!(force.segment, 2, "{}", report.summary());
            }
            Engine::Implicit(_) => assert!(report.worst_contact_force.is_none()),
        }
    }
}

/// (c') A contact that only arises during the motion: joint 4 turns by −120° in 1.2 s,
/// from a pose where the equilibrium is clear to one where it runs through a link. The run
/// fails on a contact of that segment during the motion; stopping at the first violation
/// finds the same violation as the full run, after exactly the steps up to it.
#[test]
fn a_contact_during_the_motion_is_found_and_early_stop_agrees_with_the_full_run() {
    let setup = across_joint_4_setup();
    let q0 = pick_and_place(&fixture_setup()).samples()[0].clone();
    let mut q1 = q0.clone();
    q1[3] -= 120f64.to_radians();
    let motion = Motion::new(&setup.robot, vec![0.0, 1.2], vec![q0.clone(), q1.clone()]).unwrap();
    let path = CablePath::through_every_guide(vec![20], vec![0, 0]);
    let (_, before, _) = reference(&setup, &q0, 0, 20, (0, 0));
    let (_, after, _) = reference(&setup, &q1, 0, 20, (0, 0));
    assert!(before.clearance_m > 5e-3 && after.clearance_m < -5e-3);

    let full_options = MotionTestOptions::default();
    let full = run(&setup, &path, &motion, &full_options).unwrap();
    let stop_options = MotionTestOptions {
        stop_at_first_violation: true,
        ..full_options.clone()
    };
    let stopped = run(&setup, &path, &motion, &stop_options).unwrap();

    eprintln!("joint 4 −120°: {}", full.summary());
    assert!(!full.passed && !stopped.passed);
    let violation = full.first_violation.as_ref().unwrap();
    assert!(
        matches!(
            violation.constraint,
            Constraint::Contact | Constraint::ContactForce
        ),
        "{violation}"
    );
    assert_eq!(violation.segment, 0);
    assert!(
        violation.time_s > 0.0 && violation.time_s <= 1.2 + 0.5,
        "{violation}"
    );
    assert_eq!(stopped.first_violation.as_ref(), Some(violation));
    let dt = full_options.time_step_s();
    assert_eq!(stopped.steps, (violation.time_s / dt).round() as usize);
    assert_eq!(full.steps, steps_for(1.2, dt) + steps_for(0.5, dt));
    assert!(stopped.steps < full.steps);
    assert_eq!(stopped.series[..], full.series[..stopped.series.len()]);
}

/// (d) Input that does not fit the setup is an error naming what is wrong.
#[test]
fn input_that_does_not_fit_the_setup_is_an_error() {
    let setup = fixture_setup();
    let motion = hold(&setup, &pick_and_place(&setup).samples()[0], 0.1);
    let options = MotionTestOptions::default();
    let good = CablePath::through_every_guide(vec![20, 20, 30, 20], vec![6, 5, 3, 2, 0]);
    let message =
        |path: &CablePath, options: &MotionTestOptions| match run(&setup, path, &motion, options) {
            Err(e) => e.to_string(),
            Ok(report) => panic!("accepted: {}", report.summary()),
        };
    let short = CablePath {
        lengths: vec![20, 20, 30],
        ..good.clone()
    };
    assert!(message(&short, &options).contains("4 segments, 3 lengths and 5 configurations"));
    let few = CablePath {
        configurations: vec![6, 5, 3, 2],
        ..good.clone()
    };
    assert!(message(&few, &options).contains("4 segments, 4 lengths and 4 configurations"));
    let beyond = CablePath {
        configurations: vec![6, 99, 3, 2, 0],
        ..good.clone()
    };
    let text = message(&beyond, &options);
    assert!(text.contains("G2") && text.contains("index 99"), "{text}");
    let zero = CablePath {
        lengths: vec![20, 0, 30, 20],
        ..good.clone()
    };
    let text = message(&zero, &options);
    assert!(text.contains("C2") && text.contains("length 0"), "{text}");
    let g3 = configuration(&setup, 2, "G2/forearm right z120");
    let looped = CablePath {
        configurations: vec![6, 5, g3, 2, 0],
        ..good.clone()
    };
    assert!(message(&looped, &options).contains("coincide"));
    let negative_tail = MotionTestOptions {
        settle_tail_s: -1.0,
        ..options.clone()
    };
    assert!(message(&good, &negative_tail).contains("settle_tail_s"));
    let moon = MotionTestOptions::new(Engine::RigidChain(DynamicsSettings::motion(Vector3::new(
        0.0, 0.0, -1.62,
    ))));
    assert!(message(&good, &moon).contains("gravity"));

    // Every segment S = 0: no cable.
    let forearm = forearm_setup();
    let nothing = CablePath::through_every_guide(vec![0], vec![0, 1]);
    let forearm_motion = hold(&forearm, &pick_and_place(&setup).samples()[0], 0.1);
    let result = run(
        &forearm,
        &nothing,
        &forearm_motion,
        &MotionTestOptions::default(),
    );
    assert!(
        matches!(result, Err(MotionTestError::NoCable)),
        "{result:?}"
    );

    // A motion of another robot.
    let other = Robot::from_urdf_str(
        r#"<robot name="one"><link name="a"/><link name="b"/>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"#,
        Path::new("one.urdf"),
    )
    .unwrap();
    let alien = Motion::new(&other, vec![0.0], vec![vec![0.0]]).unwrap();
    let result = run(&setup, &good, &alien, &options);
    assert!(
        matches!(result, Err(MotionTestError::MotionJoints { .. })),
        "{result:?}"
    );
}

/// The first 1.5 s of the bundled pick-and-place (down to the pick) played three times faster,
/// with a whole four-segment cable (90 sub-segments), run once for the tests below. The limits
/// are set so that the first violation comes during the run: a 2 mm clearance margin, a 12 mm
/// bend radius.
fn shared_run() -> &'static (
    Setup,
    CablePath,
    Motion,
    MotionTestOptions,
    MotionTestReport,
) {
    static RUN: OnceLock<(
        Setup,
        CablePath,
        Motion,
        MotionTestOptions,
        MotionTestReport,
    )> = OnceLock::new();
    RUN.get_or_init(|| {
        let mut setup = fixture_setup();
        setup.thresholds.contact_clearance_m = 2e-3;
        setup.thresholds.min_bend_radius_m = 12e-3;
        let motion = sped_up(
            &setup,
            &truncated(&setup, &pick_and_place(&setup), 1.5),
            3.0,
        );
        let path = CablePath::through_every_guide(vec![20, 20, 30, 20], vec![6, 5, 3, 2, 0]);
        let options = MotionTestOptions {
            settle_tail_s: 0.1,
            ..MotionTestOptions::default()
        };
        let report = run(&setup, &path, &motion, &options).unwrap();
        eprintln!("shared run: {}", report.summary());
        (setup, path, motion, options, report)
    })
}

/// The report as JSON without the wall-clock time.
fn json_without_wall_time(report: &MotionTestReport) -> serde_json::Value {
    let mut value = serde_json::to_value(report).unwrap();
    value.as_object_mut().unwrap().remove("wall_time_s");
    value
}

/// (e) The same inputs give the same report, bit for bit (but the wall time).
#[test]
fn runs_are_deterministic() {
    let (setup, path, motion, options, first) = shared_run();
    let second = run(setup, path, motion, options).unwrap();
    assert_eq!(
        json_without_wall_time(first),
        json_without_wall_time(&second)
    );
    assert!(first.steps > 100);
}

/// (f) The worst values are the extremes of the recorded series, and the first violation is
/// the first instant of the series beyond a limit.
#[test]
fn worst_values_and_first_violation_match_the_series() {
    let (setup, _, _, _, report) = shared_run();
    let series = &report.series;
    assert_eq!(series.len(), report.steps + 1);
    let max_stretch = series.iter().map(|p| p.max_stretch).fold(0.0, f64::max);
    assert_eq!(report.worst_stretch.as_ref().unwrap().value, max_stretch);
    let min_bend = series
        .iter()
        .map(|p| p.min_bend_radius_m)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(report.worst_bend.as_ref().unwrap().value, min_bend);
    let min_clearance = series
        .iter()
        .filter_map(|p| p.min_clearance_m)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(
        report.worst_clearance.as_ref().unwrap().value,
        min_clearance
    );
    let max_force = series
        .iter()
        .map(|p| p.max_contact_force_n)
        .fold(0.0, f64::max);
    assert_eq!(
        report.worst_contact_force.as_ref().map_or(0.0, |w| w.value),
        max_force
    );
    for worst in [
        &report.worst_stretch,
        &report.worst_bend,
        &report.worst_clearance,
    ] {
        let worst = worst.as_ref().unwrap();
        assert!(series.iter().any(|p| p.time_s == worst.time_s));
    }

    let t = setup.thresholds;
    let violated = |p: &cable_dict::motion_test::SeriesPoint| {
        p.min_clearance_m.is_some_and(|c| c < t.contact_clearance_m)
            || p.max_contact_force_n > 0.0
            || p.max_stretch > t.stretch
            || p.min_bend_radius_m < t.min_bend_radius_m
    };
    let first = series.iter().find(|p| violated(p)).map(|p| p.time_s);
    assert!(first.is_some_and(|t| t > 0.0), "{first:?}");
    assert_eq!(report.first_violation.as_ref().map(|v| v.time_s), first);
    assert_eq!(report.passed, first.is_none());
}

/// The bundled pick-and-place motion in full (11.1 s + 0.5 s tail) with three paths: the
/// mid-range lengths and first configurations (107 sub-segments), a 145-sub-segment path
/// whose segments are clear of the robot in a static check at sampled poses, and the same
/// guides with 190 sub-segments; prints the reports and the cost.
#[test]
#[ignore = "about 30 s in release; run with --ignored to measure"]
fn realistic_pick_and_place_run() {
    let setup = fixture_setup();
    let motion = pick_and_place(&setup);
    let paths = [
        ([32, 16, 39, 20], [0, 0, 0, 0, 0]),
        ([60, 20, 30, 35], [6, 5, 3, 4, 0]),
        ([60, 25, 70, 35], [6, 5, 3, 4, 0]),
    ];
    for (lengths, configurations) in paths {
        let path = CablePath::through_every_guide(lengths.to_vec(), configurations.to_vec());
        let report = run_as_set_up(&setup, &path, &motion);
        println!(
            "{lengths:?} {configurations:?} ({} sub-segments):\n{}\n",
            path.total_sub_segments(),
            report.summary()
        );
    }
}

/// The clearance moves smoothly when the robot does: between two steps it cannot change by
/// more than the largest displacement of a cable node plus the largest displacement of a
/// link's material near the cable (the clearance is 1-Lipschitz in both), a bound computed
/// here from the simulated shapes and the links' poses. A clamp zone measured along the
/// cable's current shape broke this: it gained and lost a sub-segment as the cable breathed,
/// and the clearance jumped by a millimetre every few steps on the bundled pick-and-place.
///
/// The cable: 300 mm across joint 4 with the realistic SMC cable, from a clamp 12 mm off the
/// J4 housing (link_3) whose cable runs along the housing, so that the sub-segment right after
/// the clamp zone is the nearest to the robot; the first 3 s of the bundled pick-and-place.
#[test]
fn the_clearance_moves_smoothly_with_the_robot() {
    let head = r#"robot = "viper_s850.urdf"
cable = "../../cables/smc_le_cp_3.toml"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 1
"#;
    let text = head.to_string()
        + &common::limits("\"cable\"")
        + r#"
[[guides]]
name = "A"
link = "link_3"
configurations = [{ name = "J4 housing", position_mm = [-156.3, 48.2, 71.2], rpy_deg = [0.0, 0.0, 144.0] }]

[[guides]]
name = "B"
link = "link_4"
configurations = [{ name = "forearm", position_mm = [22.2, 68.5, 191.7], rpy_deg = [90.0, 0.0, 72.0] }]

[[segments]]
from = "A"
to = "B"
lengths = { min = 30, max = 30, step = 1, allow_zero = false }
"#;
    let source = root().join("robots/viper_s850/motion-test-smooth.toml");
    let setup = Setup::from_toml_str(&text, &source).unwrap();
    let motion = truncated(&setup, &pick_and_place(&setup), 3.0);
    let path = CablePath::through_every_guide(vec![30], vec![0, 0]);
    let options = MotionTestOptions {
        record_series: true,
        shape_interval_s: Some(MotionTestOptions::default().time_step_s()),
        settle_tail_s: 0.0,
        ..MotionTestOptions::default()
    };
    let report = run(&setup, &path, &motion, &options).unwrap();
    let frames = &report.shapes;
    assert!(frames.len() > 500, "{} frames", frames.len());
    let clearance_at = |t: f64| {
        report
            .series
            .iter()
            .find(|p| (p.time_s - t).abs() < 1e-9)
            .and_then(|p| p.min_clearance_m)
            .unwrap()
    };
    let nodes = |frame: &cable_dict::motion_test::ShapeFrame| -> Vec<Point3<f64>> {
        frame
            .segments
            .iter()
            .flat_map(|s| s.nodes_m.iter().map(|p| Point3::from(*p)))
            .collect()
    };
    let mut largest_ratio: f64 = 0.0;
    for pair in frames.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        let (na, nb) = (nodes(a), nodes(b));
        let moved_nodes = na
            .iter()
            .zip(&nb)
            .map(|(p, q)| (q - p).norm())
            .fold(0.0, f64::max);
        let (ca, cb) = (clearance_at(a.time_s), clearance_at(b.time_s));
        let poses_a = setup.robot.link_poses(&motion.joints_at(a.time_s)).unwrap();
        let poses_b = setup.robot.link_poses(&motion.joints_at(b.time_s)).unwrap();
        // Link material within reach of the cable: the points where the cable's nodes are,
        // widened by the clearance and the sub-segment (a nearest point is no farther).
        let reach = ca.abs().max(cb.abs()) + setup.cable.diameter_m + 0.01;
        let moved_links = poses_a
            .iter()
            .zip(&poses_b)
            .map(|(pa, pb)| {
                let relative = pb * pa.inverse();
                let turn = relative.rotation.angle();
                na.iter()
                    .map(|p| (relative * p - p).norm() + turn * reach)
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let bound = moved_nodes + moved_links;
        assert!(
            (cb - ca).abs() <= bound + 1e-9,
            "t = {:.4} → {:.4} s: clearance {:.4} → {:.4} mm, more than the {:.4} mm the cable \
             and the links moved",
            a.time_s,
            b.time_s,
            ca * 1e3,
            cb * 1e3,
            bound * 1e3
        );
        if bound > 0.0 {
            largest_ratio = largest_ratio.max((cb - ca).abs() / bound);
        }
    }
    eprintln!("largest clearance change / bound: {largest_ratio:.3}");
}
