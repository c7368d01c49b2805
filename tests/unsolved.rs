//! The ways a search ends without an answer, on the hand-written pick-and-place catalogue
//! (its short paths hang two loops into each other, docs/architecture.md "Self-contact"):
//! the whole cable at rest at the first pose against the motion test's first step, and a
//! spent budget's closest miss, shown chain, untried chain and relaxed limit against the
//! motion tests re-run one by one.

use cable_dict::motion::Motion;
use cable_dict::motion_test::{self, Constraint, MotionTestOptions, Violation};
use cable_dict::path::CablePath;
use cable_dict::setup::Setup;
use cable_dict::solve::{NamedPath, SolveOptions, Status, UnsolvedCase, named_path, solve};
use std::collections::BTreeSet;

const SETUP: &str = "robots/viper_s850/hand_written/pick_and_place.toml";
const MOTION: &str = "motions/viper_s850/pick_and_place.csv";

fn setup_and_motion() -> (Setup, Motion) {
    let root = crate::common::root();
    let setup = Setup::from_file(root.join(SETUP)).unwrap_or_else(|e| panic!("{e}"));
    let motion =
        Motion::from_csv_file(&setup.robot, root.join(MOTION)).unwrap_or_else(|e| panic!("{e}"));
    (setup, motion)
}

/// The motion test as the search runs it: stopped at the first violation.
fn first_violation_options() -> MotionTestOptions {
    MotionTestOptions {
        stop_at_first_violation: true,
        record_series: false,
        ..MotionTestOptions::default()
    }
}

#[test]
fn a_chain_touching_itself_at_rest_fails_the_motion_test_where_the_rest_check_says() {
    let (setup, motion) = setup_and_motion();
    // Without the static sweep (and its check at rest) the first chains go to the motion
    // test and touch themselves at its first step.
    let options = SolveOptions {
        static_sweep: false,
        learn: false,
        k_best: 12,
        ..SolveOptions::default()
    };
    let unswept = solve(&setup, &motion, &options).unwrap_or_else(|e| panic!("{e}"));
    let t0 = motion.times_s()[0];
    let at_rest: Vec<&CablePath> = (unswept.candidates.iter())
        .filter(|c| (c.failure.as_deref()).is_some_and(|f| f.contains("at t = 0.00 s")))
        .map(|c| &c.path)
        .collect();
    assert!(!at_rest.is_empty(), "{:#?}", unswept.candidates);
    for path in &at_rest {
        let full = motion_test::run(&setup, path, &motion, &first_violation_options())
            .unwrap_or_else(|e| panic!("{e}"));
        let rest = MotionTestOptions {
            first_pose_only: true,
            ..first_violation_options()
        };
        let rest = motion_test::run(&setup, path, &motion, &rest).unwrap_or_else(|e| panic!("{e}"));
        assert!(!full.passed && !rest.passed);
        assert_eq!(rest.failure, full.failure);
        assert_eq!(rest.first_violation, full.first_violation);
        let v = full.first_violation.as_ref().expect("a violation");
        assert_eq!((v.constraint, v.time_s), (Constraint::SelfContact, t0));
        assert_eq!(rest.steps, 0, "no step simulated at rest");
    }

    // With the sweep, no motion test is spent on a chain touching itself at rest: the
    // sweep drops the piece the motion test would have blamed, at the first pose.
    let swept = solve(
        &setup,
        &motion,
        &SolveOptions {
            static_sweep: true,
            ..options
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let rejected = &swept.static_sweep.rejected;
    assert!(
        rejected
            .iter()
            .any(|r| r.time_s == t0 && r.detail.contains("at rest"))
    );
    for c in &swept.candidates {
        let failure = c.failure.as_deref().unwrap_or_default();
        assert!(!failure.contains("at t = 0.00 s"), "{failure}");
    }
}

#[test]
fn a_spent_budget_names_its_closest_miss_its_placements_and_the_chain_left() {
    let (setup, motion) = setup_and_motion();
    // Strictly shortest first, so that the chain left is no shorter than those tried.
    let options = SolveOptions {
        k_best: 8,
        learn: false,
        ..SolveOptions::default()
    };
    let report = solve(&setup, &motion, &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.status, Status::NonePassedMotionTest);
    let unsolved = report.unsolved.as_ref().expect("unsolved");
    assert_eq!(
        unsolved.case,
        UnsolvedCase::BudgetSpent,
        "{}",
        report.explanation
    );
    assert_eq!(report.candidates.len(), options.k_best);

    // Every candidate's motion test again, one by one: the closest miss is the bend-radius
    // or clearance failure missed by the least.
    let violations: Vec<Option<Violation>> = (report.candidates.iter())
        .map(|c| {
            motion_test::run(&setup, &c.path, &motion, &first_violation_options())
                .unwrap_or_else(|e| panic!("{e}"))
                .first_violation
        })
        .collect();
    let miss = |v: &Violation| v.threshold - v.value;
    let (k, v) = (violations.iter().enumerate())
        .filter_map(|(k, v)| Some((k, v.as_ref()?)))
        .filter(|(_, v)| v.missed_by_m().is_some())
        .min_by(|a, b| miss(a.1).total_cmp(&miss(b.1)))
        .expect("a bend-radius or clearance failure among the paths tried");
    let closest = unsolved.closest.as_ref().expect("a closest miss");
    assert_eq!(closest.candidate, k);
    assert!((closest.relax_by_mm - miss(v) * 1e3).abs() < 1e-6);
    assert_eq!(closest.segment, v.segment_name);

    // The report shows that chain, with its own motion test.
    let shown = report.shown_candidate().expect("a chain shown");
    assert_eq!(shown.path, report.candidates[k].path);
    let kept = report
        .motion_test
        .as_ref()
        .expect("the shown chain's motion test");
    assert_eq!(kept.first_violation.as_ref(), Some(v));

    // Placements: the paths tried without their lengths.
    let placement = |p: &CablePath| (p.segments.clone(), p.configurations.clone());
    let placements: BTreeSet<_> = report
        .candidates
        .iter()
        .map(|c| placement(&c.path))
        .collect();
    assert_eq!(unsolved.placements_tried, placements.len());
    let next = unsolved.next_untried.as_ref().expect("chains were left");
    let longest_tried = (report.candidates.iter())
        .map(|c| c.total_length_mm)
        .fold(0.0, f64::max);
    assert!(
        next.length_mm >= longest_tried,
        "{} < {longest_tried}",
        next.length_mm
    );
    let mounted = |path: &NamedPath| -> Vec<(String, String)> {
        (path.guides.iter())
            .map(|g| (g.name.clone(), g.configuration.clone()))
            .collect()
    };
    let tried: BTreeSet<_> = (report.candidates.iter())
        .map(|c| mounted(&named_path(&setup, &c.path)))
        .collect();
    assert_eq!(next.new_placement, !tried.contains(&mounted(&next.path)));
    assert!(
        report
            .explanation
            .contains("the shortest chain not tested is")
    );

    // The limit the diagnosis offers for a bend-radius miss removes that failure: the same
    // chain under it does not fail there by its bend radius any more.
    assert_eq!(
        v.constraint,
        Constraint::BendRadius,
        "C3's 47.93 mm of 48 mm"
    );
    {
        let offered = (v.value * 1e4).floor() / 10.0; // mm, one decimal, rounded down
        let diagnosis = report.diagnosis.as_ref().expect("a diagnosis");
        let segment = (diagnosis.segments.iter())
            .find(|d| d.segment == v.segment_name)
            .expect("the segment is diagnosed");
        let wording = format!("a bend radius limit of {offered:.1} mm");
        assert!(
            segment
                .suggestions
                .first()
                .is_some_and(|s| s.starts_with(&wording)),
            "{:?}",
            segment.suggestions
        );
        let mut relaxed = setup.clone();
        relaxed.thresholds.min_bend_radius_m = offered * 1e-3;
        let again = motion_test::run(&relaxed, &shown.path, &motion, &first_violation_options())
            .unwrap_or_else(|e| panic!("{e}"));
        if let Some(w) = &again.first_violation {
            let same = w.constraint == Constraint::BendRadius
                && w.segment == v.segment
                && w.time_s <= v.time_s;
            assert!(!same, "{w:?}");
        }
    }
}
