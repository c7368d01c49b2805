//! Axis ranges: a design for a box of joint values (`solve --ranges`), checked by an
//! independent method on a grid four times finer than the search's, and with the motion
//! whose joints stay inside the box; the ranges a mounting allows, checked on a finer grid.

use crate::common::root;
use cable_dict::motion::{Cell, JointRanges, Motion};
use cable_dict::setup::Setup;
use cable_dict::solve::{
    RangeEnd, STRESS_MOTION_RATE_HZ, SolveOptions, Status, allowed_box, allowed_ranges, check_box,
    check_mounting, solve_cell, solve_ranges,
};

/// The robot-level pick-and-place setup and the bundled pick-and-place motion.
fn pick_and_place() -> (Setup, Motion) {
    let setup = Setup::from_file(root().join("robots/viper_s850/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(
        &setup.robot,
        root().join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    (setup, motion)
}

/// The bundled pick-and-place's own box (each joint's least and greatest value over the
/// motion), joints 4 and 5 ranged (their stress motions run): the design's path must hold
/// at every pose of a grid at a quarter of the search's step, each piece solved cold by
/// [`check_box`] (not the search's continuation over lengths, nor its grid), and over the
/// motion itself, which stays inside the box.
#[test]
fn a_range_design_holds_on_a_four_times_finer_grid_and_over_a_motion_inside_its_box() {
    let (setup, motion) = pick_and_place();
    let robot = &setup.robot;
    let mut ranges = JointRanges::spanned(&Cell::single(motion.clone(), None)).expect("a box");
    for name in ["joint_4", "joint_5"] {
        ranges.named[robot.actuated_index(name).expect(name)] = true;
    }
    assert!(ranges.contains(&motion.samples()[0]));
    let step_deg = 10.0;
    let options = SolveOptions::default();
    let (solution, _, answered) = solve_ranges(&setup, &ranges, None, step_deg, &options, None)
        .unwrap_or_else(|e| panic!("{e}"));
    let report = &solution.report;
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    let design = report.ranges.as_ref().expect("the design's ranges");
    assert_eq!(
        design.asked, design.answered,
        "no narrowing for the motion's own box"
    );
    assert_eq!(answered, ranges);
    let path = &report.candidates.last().expect("the answer").path;

    let finer = check_box(&solution.setup, path, &ranges, step_deg / 4.0, 200_000)
        .unwrap_or_else(|e| panic!("{e}"));
    let t = &solution.setup.thresholds;
    for piece in &finer.pieces {
        assert!(piece.poses > 0, "{}", piece.segment);
        assert!(
            piece.failure.is_none(),
            "{} fails on the finer grid: {:?}",
            piece.segment,
            piece.failure
        );
        assert!(piece.least_bend_radius_mm >= t.min_bend_radius_m * 1e3 - 1e-9);
        assert!(
            piece
                .least_clearance_mm
                .is_none_or(|c| c >= t.contact_clearance_m * 1e3)
        );
    }
    assert!(finer.holds());
    // The reference can fail: joint 5 over its whole URDF range folds the wrist onto the
    // cable, outside the design's box.
    let mut wide = ranges.clone();
    let j5 = robot.actuated_index("joint_5").expect("joint_5");
    let limits = robot.actuated_joint(j5).limits.expect("limits");
    wide.ranges[j5] = [limits.lower, limits.upper];
    let over_wide = check_box(&solution.setup, path, &wide, step_deg, 200_000)
        .unwrap_or_else(|e| panic!("{e}"));
    let failure = (over_wide.pieces.iter())
        .find_map(|p| p.failure.as_ref())
        .expect("the wide box fails");
    let (_, at_deg) = (failure.joints.iter())
        .find(|(name, _)| name == "joint_5")
        .expect("joint 5 shapes the failing piece");
    let inner = ranges.ranges[j5].map(f64::to_degrees);
    assert!(
        *at_deg < inner[0] || *at_deg > inner[1],
        "it fails outside the design's box: {failure:?}"
    );

    let inside = check_mounting(&solution.setup, path, &Cell::single(motion, None), &options)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(inside.holds(), "{:?}", inside.motions[0].motion_test);
}

/// The pick-and-place motion's own box with all six axes named (the bundled ranges file):
/// chains that hold every static pose of the box fail a stress motion at the acceleration
/// asked, so the design answers the whole box at half the acceleration, not a narrower box.
/// The independent reference is the motion test of the answer over the stress motions
/// themselves (no search): at the answered ramp every one holds, at the asked ramp one fails
/// — the gentler ramp was needed. (`k_best` 3 caps the motion tests of each box: what the
/// test checks is the ramp, not the search's budget.)
#[test]
fn a_box_whose_axes_fail_at_speed_is_answered_with_a_gentler_ramp_the_stress_motions_confirm() {
    let (setup, _) = pick_and_place();
    let robot = &setup.robot;
    let ranges = JointRanges::from_file(
        robot,
        &root().join("motions/viper_s850/pick_and_place_box.toml"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let options = SolveOptions {
        k_best: 3,
        ..SolveOptions::default()
    };
    let (solution, _, answered) =
        solve_ranges(&setup, &ranges, None, 10.0, &options, None).unwrap_or_else(|e| panic!("{e}"));
    let report = &solution.report;
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    let design = report.ranges.as_ref().expect("the design's ranges");
    assert_eq!(design.asked, design.answered, "the ranges are kept");
    assert_eq!(answered.ranges, ranges.ranges);
    let slower = answered.time_to_full_speed_s;
    assert!(slower > ranges.time_to_full_speed_s, "{slower}");
    assert_eq!(design.time_to_full_speed_answered_s, slower);
    assert_eq!(
        design.time_to_full_speed_asked_s,
        ranges.time_to_full_speed_s
    );
    let path = solution.answer().expect("the answer passed");

    let stress = |r: &JointRanges| {
        let cell = r
            .stress_motions(robot, STRESS_MOTION_RATE_HZ)
            .unwrap_or_else(|e| panic!("{e}"));
        check_mounting(&solution.setup, path, &cell, &SolveOptions::default())
            .unwrap_or_else(|e| panic!("{e}"))
    };
    // The answered box as `solve --write-ranges` writes it, read back as `check --ranges`
    // reads it: the stress motions the check runs are the answer's.
    let written = std::env::temp_dir().join(format!("answered-{}.toml", std::process::id()));
    std::fs::write(&written, answered.to_toml(robot, "answered")).unwrap_or_else(|e| panic!("{e}"));
    let read = JointRanges::from_file(robot, &written).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(read.time_to_full_speed_s, slower);
    let at_answer = stress(&read);
    assert!(at_answer.holds(), "{:?}", at_answer.motions);
    let at_asked = stress(&ranges);
    assert!(!at_asked.holds(), "the asked acceleration must fail");
}

/// The ranges the bundled pick-and-place answer allows, each axis alone with the others
/// anywhere in the motion's extremes, scanned on a 10° grid: the vertical first axis shapes
/// no piece and keeps its URDF limits; every other axis's allowed range holds on the
/// independent box check at half the step (values the scan never solved), and each end that
/// a piece's failure sets lies beyond the range within the resolution.
#[test]
fn the_ranges_a_mounting_allows_hold_on_a_finer_grid_and_end_where_a_piece_fails() {
    let (setup, motion) = pick_and_place();
    let robot = &setup.robot;
    let options = SolveOptions::default();
    let cell = Cell::single(motion, None);
    let solution = solve_cell(&setup, &cell, &options, None).unwrap_or_else(|e| panic!("{e}"));
    let path = solution.answer().expect("the bundled answer passes");
    let (within, words) = allowed_box(None, Some(&cell)).expect("a box");
    let step_deg = 10.0;
    let allowed = allowed_ranges(&solution.setup, path, &within, &words, step_deg, &options)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(allowed.box_failure.is_none(), "{:?}", allowed.box_failure);
    assert_eq!(allowed.axes.len(), robot.dof());

    let j1 = &allowed.axes[0];
    let limits = robot.actuated_joint(0).limits.expect("limits");
    assert!(j1.shapes.is_empty(), "{:?}", j1.shapes);
    assert_eq!(
        j1.allowed,
        [
            limits.lower.to_degrees().round(),
            limits.upper.to_degrees().round()
        ]
    );
    assert_eq!((&j1.below, &j1.above), (&RangeEnd::Limit, &RangeEnd::Limit));

    let mut widened = 0;
    for (j, axis) in allowed.axes.iter().enumerate().skip(1) {
        // The allowed range holds the asked range, and lies in the limits.
        let limits = robot
            .actuated_joint(j)
            .limits
            .expect("limits")
            .lower
            .to_degrees()
            ..=robot
                .actuated_joint(j)
                .limits
                .expect("limits")
                .upper
                .to_degrees();
        assert!(axis.allowed[0] <= axis.within[0] && axis.allowed[1] >= axis.within[1]);
        assert!(limits.contains(&axis.allowed[0]) && limits.contains(&axis.allowed[1]));
        for (end, side) in [(&axis.below, 0), (&axis.above, 1)] {
            if let RangeEnd::Fails { at, .. } = end {
                let beyond = if side == 0 {
                    axis.allowed[0] - at
                } else {
                    at - axis.allowed[1]
                };
                assert!(
                    beyond > 0.0 && beyond <= 2.0 * allowed.resolution_deg + 1e-9,
                    "{}: fails at {at}, allows {:?}",
                    axis.joint,
                    axis.allowed
                );
            }
        }
        if axis.allowed == axis.within {
            continue;
        }
        widened += 1;
        let mut wider = within.clone();
        wider.ranges[j] = axis.allowed.map(f64::to_radians);
        let finer = check_box(&solution.setup, path, &wider, step_deg / 2.0, 200_000)
            .unwrap_or_else(|e| panic!("{e}"));
        for piece in &finer.pieces {
            assert!(
                piece.failure.is_none(),
                "{} {:?}: {} fails at half the step: {:?}",
                axis.joint,
                axis.allowed,
                piece.segment,
                piece.failure
            );
        }
    }
    assert!(widened >= 3, "{allowed:?}");
}

/// The pick-and-place motion's box with joint 5 widened to 100° has no path. The design
/// narrows joint 5 from the end where the closest pieces failed, keeping the other end, and
/// answers a narrower box — inside the one asked, the other joints untouched — whose path
/// holds on the independent check at a quarter of the search's step.
#[test]
fn a_box_without_a_path_is_narrowed_from_its_failing_end_and_holds_on_a_finer_grid() {
    let (setup, motion) = pick_and_place();
    let robot = &setup.robot;
    let mut asked = JointRanges::spanned(&Cell::single(motion, None)).expect("a box");
    let j5 = robot.actuated_index("joint_5").expect("joint_5");
    asked.ranges[j5][1] = 100f64.to_radians();
    asked.named[j5] = true;
    // A coarse grid (the check below is at a quarter of it): the narrowing is what is tested.
    let step_deg = 20.0;
    let options = SolveOptions::default();
    let (solution, _, answered) = solve_ranges(&setup, &asked, None, step_deg, &options, None)
        .unwrap_or_else(|e| panic!("{e}"));
    let report = &solution.report;
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    let design = report.ranges.as_ref().expect("the design's ranges");
    assert!(!design.tried.is_empty(), "the box asked has no path");
    let failures = &design.failures[0];
    assert_eq!(failures.joint, "joint_5");
    let [lo, hi] = answered.ranges[j5];
    let [a, b] = asked.ranges[j5];
    assert!(
        a <= lo && hi <= b && hi - lo < b - a,
        "{:?}",
        answered.ranges[j5]
    );
    match failures.kept_end() {
        Some(0) => assert_eq!(lo, a, "the lower end is kept"),
        Some(_) => assert_eq!(hi, b, "the upper end is kept"),
        None => panic!("the closest misses fell evenly: {failures:?}"),
    }
    for j in (0..robot.dof()).filter(|&j| j != j5) {
        assert_eq!(answered.ranges[j], asked.ranges[j]);
    }
    let path = solution.answer().expect("the answer passed");
    let finer = check_box(&solution.setup, path, &answered, step_deg / 4.0, 200_000)
        .unwrap_or_else(|e| panic!("{e}"));
    for piece in &finer.pieces {
        assert!(
            piece.failure.is_none(),
            "{}: {:?}",
            piece.segment,
            piece.failure
        );
    }
}
