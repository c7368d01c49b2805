//! The static motion sweep (`attachment::MotionSweep`, each pose started from the last
//! one's equilibrium) against a brute-force scan: every sample of the motion checked one
//! after the other with the attachment test's evaluator from the connected geometry.
//!
//! Run in release (`cargo test --release --test sweep`): a few PVs × 814 poses of static
//! solves.

use cable_dict::attachment::{
    ConnectMethod, Evaluator, MotionSweep, SegmentPoses, SweptLeast, TestPose,
};
use cable_dict::cable::CableSpec;
use cable_dict::motion::Motion;
use cable_dict::path::Pv;
use cable_dict::setup::Setup;

/// The bundled pick-and-place setup with the paper's floppy SMC cable, whose U-loop across
/// joint 4 bends below its limit between the critical poses (with the realistic preset,
/// only two C1 PVs of the whole catalogue do, by less than 0.05 mm of clearance).
fn bundled() -> (Setup, Motion) {
    let root = crate::common::root();
    let mut setup =
        Setup::from_file(root.join("robots/viper_s850/hand_written/pick_and_place.toml")).unwrap();
    setup.cable = CableSpec::from_file(root.join("cables/smc_le_cp_3_paper.toml")).unwrap();
    let motion = Motion::from_csv_file(
        &setup.robot,
        root.join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap();
    (setup, motion)
}

/// Motion sample `k` as a test pose.
fn sample_pose(setup: &Setup, motion: &Motion, k: usize) -> TestPose {
    let joints = motion.samples()[k].clone();
    TestPose {
        motion: 0,
        sample: k,
        time_s: motion.times_s()[k],
        grid: false,
        link_poses: setup.robot.link_poses(&joints).unwrap(),
        joints,
        reason: String::new(),
        clearance_link: None,
    }
}

/// The first sample, in time order, at which `pv` violates a limit.
fn brute_force(evaluator: &Evaluator<'_>, motion: &Motion, m: usize, pv: &Pv) -> Option<usize> {
    let setup = evaluator.setup();
    (0..motion.len()).find(|&k| {
        let check = evaluator.check(m, pv, &sample_pose(setup, motion, k));
        check.rejection.is_some()
    })
}

/// The sweep fails a PV at exactly the first sample a one-by-one scan fails it at (dwells
/// skipped: a repeated pose gives the same verdict), passes the others, and catches PVs the
/// critical poses let through — the reason it exists.
#[test]
fn the_sweep_agrees_with_a_scan_of_every_sample_and_catches_what_critical_poses_miss() {
    let (setup, motion) = bundled();
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).unwrap();
    let critical = SegmentPoses::new(&setup, &motion).unwrap();
    let mut sweep = MotionSweep::new(&evaluator, &motion).unwrap();

    let samples = motion.samples();
    let distinct = 1 + samples.windows(2).filter(|w| w[0] != w[1]).count();
    assert_eq!(sweep.pose_count(), distinct);
    assert!(distinct < motion.len(), "the motion has dwells");

    let cases = [
        (0, Pv::new(55, 1, 1)),
        (0, Pv::new(56, 4, 0)),
        (0, Pv::new(57, 3, 3)),
        (0, Pv::new(70, 1, 2)),
        (1, Pv::new(20, 0, 0)),
        (1, Pv::new(23, 0, 2)),
        (2, Pv::new(42, 1, 0)),
        (3, Pv::new(20, 0, 0)),
    ];
    let mut passed = 0;
    let mut missed_by_critical_poses = 0;
    for (m, candidate) in cases {
        let expected = brute_force(&evaluator, &motion, m, &candidate);
        let found = sweep.check(m, &candidate);
        assert_eq!(
            found.as_ref().map(|f| f.sample),
            expected,
            "C{} {candidate:?}: {found:?}",
            m + 1
        );
        if let Some(failure) = &found {
            assert_eq!(failure.time_s, motion.times_s()[failure.sample]);
            let at_critical = critical.poses[m]
                .iter()
                .any(|pose| !evaluator.check(m, &candidate, pose).passed());
            missed_by_critical_poses += usize::from(!at_critical);
        } else {
            passed += 1;
        }
    }
    assert_eq!(sweep.swept(), cases.len());
    assert!(passed > 0, "some case passes the whole motion");
    assert!(
        missed_by_critical_poses > 0,
        "some case passes its critical poses and fails between them"
    );
}

/// A sweep stopped as soon as a least value falls below a stop (how a piece the learned
/// swings will set aside is swept) ends below it, never past a failure the whole sweep
/// finds first; its least values are those of the whole sweep up to where it stopped, and a
/// check without a stop sweeps it again whole: the same verdict and least values as a sweep
/// never stopped.
#[test]
fn a_sweep_stopped_below_a_value_knows_the_least_so_far_and_is_swept_whole_when_asked_again() {
    let (setup, motion) = bundled();
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).unwrap();
    let cases = [
        (0, Pv::new(55, 1, 1)),
        (0, Pv::new(70, 1, 2)),
        (1, Pv::new(23, 0, 2)),
        (2, Pv::new(42, 1, 0)),
    ];
    let mut whole = MotionSweep::new(&evaluator, &motion).unwrap();
    let mut stopped_any = false;
    for (m, pv) in cases {
        let failure = whole.check(m, &pv);
        let least = whole.least(m, &pv).expect("swept");
        // A stop a little above the whole sweep's least bend radius: reached at some pose.
        let stop = SweptLeast {
            bend_radius_m: least.bend_radius_m + 1e-4,
            ..SweptLeast::NONE
        };
        let mut early = MotionSweep::new(&evaluator, &motion).unwrap();
        let found = early.check_until(&[(m, pv, Some(stop))]).pop().flatten();
        let partial = early.least(m, &pv).expect("swept");
        match (&failure, &found) {
            (Some(whole_failure), Some(early_failure)) => {
                assert_eq!(whole_failure.sample, early_failure.sample)
            }
            (_, None) => {
                stopped_any |= least.bend_radius_m.is_finite();
                assert!(
                    partial.below(&stop) || failure.is_some(),
                    "C{} {pv:?}",
                    m + 1
                );
                assert!(partial.bend_radius_m >= least.bend_radius_m);
            }
            (None, Some(_)) => panic!("C{} {pv:?}: a failure the whole sweep did not find", m + 1),
        }
        // Asked again without a stop: swept whole, as if never stopped.
        let again = early.check(m, &pv);
        assert_eq!(again.map(|f| f.sample), failure.as_ref().map(|f| f.sample));
        assert_eq!(early.least(m, &pv), Some(least), "C{} {pv:?}", m + 1);
    }
    assert!(stopped_any, "some case stopped early");
}
