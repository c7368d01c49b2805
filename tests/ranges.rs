//! Axis ranges: a design for a box of joint values (`solve --ranges`), checked by an
//! independent method on a grid four times finer than the search's, and with the motion
//! whose joints stay inside the box.

use crate::common::root;
use cable_dict::motion::{Cell, JointRanges, Motion};
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, check_box, check_mounting, solve_ranges};

/// The bundled pick-and-place's own box (each joint's least and greatest value over the
/// motion), joints 4 and 5 ranged (their stress motions run): the design's path must hold
/// at every pose of a grid at a quarter of the search's step, each piece solved cold by
/// [`check_box`] (not the search's continuation over lengths, nor its grid), and over the
/// motion itself, which stays inside the box.
#[test]
fn a_range_design_holds_on_a_four_times_finer_grid_and_over_a_motion_inside_its_box() {
    let setup = Setup::from_file(root().join("robots/viper_s850/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let robot = &setup.robot;
    let motion = Motion::from_csv_file(robot, root().join("motions/viper_s850/pick_and_place.csv"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut ranges = JointRanges::urdf(robot).expect("the Viper's joints have limits");
    for (j, range) in ranges.ranges.iter_mut().enumerate() {
        let series = motion.joint_series(j).expect("a joint");
        let lo = series.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = series.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        *range = [lo, hi];
    }
    for name in ["joint_4", "joint_5"] {
        ranges.named[robot.actuated_index(name).expect(name)] = true;
    }
    assert!(ranges.contains(&motion.samples()[0]));
    let step_deg = 10.0;
    let options = SolveOptions::default();
    let (solution, _) = solve_ranges(&setup, &ranges, None, step_deg, &options, None)
        .unwrap_or_else(|e| panic!("{e}"));
    let report = &solution.report;
    assert_eq!(report.status, Status::Solved, "{}", report.explanation);
    let design = report.ranges.as_ref().expect("the design's ranges");
    assert_eq!(
        design.asked, design.answered,
        "no narrowing for the motion's own box"
    );
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
