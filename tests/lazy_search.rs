//! The lazy search (the default) against the exhaustive one (`--exhaustive`, every candidate
//! piece tested before the chains are searched): the same path, the same candidates tried in
//! the same order, on every bundled motion and on a site-generated setup of a second robot
//! (the UR5's STL meshes); and the invariant behind it, checked against the exhaustive sets
//! with a dynamic program of the test's own: after widening to a bound, the lazy test knows
//! exactly the chains of robust pieces no longer than the bound.

use cable_dict::attachment::{
    ConnectMethod, Evaluator, LazyAttachment, SegmentPoses, attachment_test,
};
use cable_dict::motion::{Motion, WaypointFile};
use cable_dict::path::Pv;
use cable_dict::setup::Setup;
use cable_dict::solve::{SearchKind, SolveOptions, SolveReport, solve};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn setup(path: &str) -> Setup {
    Setup::from_file(root(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn motion(setup: &Setup, csv: &str) -> Motion {
    Motion::from_csv_file(&setup.robot, root(csv)).unwrap_or_else(|e| panic!("{csv}: {e}"))
}

fn solved(setup: &Setup, motion: &Motion, search: SearchKind) -> SolveReport {
    let options = SolveOptions {
        search,
        ..SolveOptions::default()
    };
    solve(setup, motion, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// Both searches on one setup and motion: same status, path and candidates tried; the lazy
/// one tests fewer pieces.
fn same_answer(setup: &Setup, motion: &Motion, name: &str) {
    let lazy = solved(setup, motion, SearchKind::Lazy);
    let exhaustive = solved(setup, motion, SearchKind::Exhaustive);
    assert_eq!(lazy.status, exhaustive.status, "{name}");
    assert_eq!(lazy.optimal, exhaustive.optimal, "{name}");
    let tried = |r: &SolveReport| -> Vec<_> {
        r.candidates
            .iter()
            .map(|c| (c.path.clone(), c.passed, c.failure.clone()))
            .collect()
    };
    assert_eq!(tried(&lazy), tried(&exhaustive), "{name}");
    let evaluated = |r: &SolveReport| r.segments.iter().map(|s| s.evaluations).sum::<usize>();
    assert!(
        evaluated(&lazy) < evaluated(&exhaustive),
        "{name}: {} vs {}",
        evaluated(&lazy),
        evaluated(&exhaustive)
    );
}

#[test]
fn both_searches_find_the_same_path_on_every_bundled_motion() {
    let robot_level = setup("robots/viper_s850/pick_and_place.toml");
    for name in [
        "pick_and_place",
        "palletizing",
        "machine_tending",
        "screw_driving",
    ] {
        let csv = format!("motions/viper_s850/{name}.csv");
        same_answer(&robot_level, &motion(&robot_level, &csv), name);
    }
    let inspection = setup("robots/viper_s850/inspection.toml");
    let csv = "motions/viper_s850/inspection.csv";
    same_answer(&inspection, &motion(&inspection, csv), "inspection");
}

#[test]
fn both_searches_find_the_same_path_on_a_second_robot() {
    let ur5 = setup("tests/data/ur5/sites_setup.toml");
    let waypoints = WaypointFile::from_file(root("tests/data/ur5/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion = waypoints
        .generate(&ur5.robot)
        .unwrap_or_else(|e| panic!("{e}"))
        .motion;
    same_answer(&ur5, &motion, "UR5");
}

/// The bundled robot-level setup with narrower length windows, so that the exhaustive sets
/// are quick to compute.
fn narrow_setup() -> Setup {
    let path = root("robots/viper_s850/pick_and_place.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let text = text
        .replace(
            "lengths = { min = 20, max = 80, step = 1, allow_zero = false }",
            "lengths = { min = 22, max = 40, step = 1, allow_zero = false }",
        )
        .replace(
            "lengths = { min = 10, max = 40, step = 1, allow_zero = true }",
            "lengths = { min = 10, max = 16, step = 1, allow_zero = true }",
        );
    Setup::from_toml_str(&text, &path).unwrap_or_else(|e| panic!("{e}"))
}

/// The pieces of `d2` (per segment, segment `m` from guide `m` to `m + 1`) that lie on a
/// chain of `d2` no longer than `bound`: a shortest prefix and suffix per configuration by
/// relaxation over the guides, written here independently of the library's chain search.
fn on_chains_up_to(setup: &Setup, d2: &[Vec<Pv>], bound: usize) -> Vec<BTreeSet<Pv>> {
    let counts: Vec<usize> = setup
        .guides
        .iter()
        .map(|g| g.configurations.len())
        .collect();
    let guides = counts.len();
    let mut before: Vec<Vec<usize>> = counts.iter().map(|&n| vec![usize::MAX; n]).collect();
    let mut after = before.clone();
    before[0].fill(0);
    after[guides - 1].fill(0);
    for (m, pieces) in d2.iter().enumerate() {
        for pv in pieces {
            let head = before[m][pv.start];
            if head != usize::MAX {
                let slot = &mut before[m + 1][pv.end];
                *slot = (*slot).min(head + pv.sub_segments);
            }
        }
    }
    for (m, pieces) in d2.iter().enumerate().rev() {
        for pv in pieces {
            let tail = after[m + 1][pv.end];
            if tail != usize::MAX {
                let slot = &mut after[m][pv.start];
                *slot = (*slot).min(tail + pv.sub_segments);
            }
        }
    }
    d2.iter()
        .enumerate()
        .map(|(m, pieces)| {
            pieces
                .iter()
                .filter(|pv| {
                    let (head, tail) = (before[m][pv.start], after[m + 1][pv.end]);
                    head != usize::MAX
                        && tail != usize::MAX
                        && head + pv.sub_segments + tail <= bound
                })
                .copied()
                .collect()
        })
        .collect()
}

#[test]
fn after_widening_the_lazy_test_knows_every_chain_up_to_its_bound() {
    let setup = narrow_setup();
    let motion = motion(&setup, "motions/viper_s850/pick_and_place.csv");
    assert!(setup.segment_count() == 3 && setup.guides.len() == 4);
    let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
    let evaluator =
        Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
    let exhaustive: Vec<Vec<Pv>> = attachment_test(&evaluator, &poses)
        .into_iter()
        .map(|s| s.d2)
        .collect();
    let mut lazy = LazyAttachment::new(&evaluator, &poses, None);
    let first = lazy.lower_bound().expect("a chain can exist");
    let on_any_chain = on_chains_up_to(&setup, &exhaustive, usize::MAX);
    assert!(
        on_any_chain.iter().all(|pieces| !pieces.is_empty()),
        "the narrow setup has chains"
    );
    for bound in [first, first + 3, first + 8, first + 16] {
        lazy.widen_to(bound);
        let known = lazy.robust();
        let expected = on_chains_up_to(&setup, &exhaustive, bound);
        let found = on_chains_up_to(&setup, &known, bound);
        assert_eq!(found, expected, "bound {bound}");
        for (m, pieces) in known.iter().enumerate() {
            for pv in pieces {
                assert!(
                    exhaustive[m].contains(pv) || !found[m].contains(pv),
                    "bound {bound}: C{} {pv:?} robust only in the lazy test",
                    m + 1
                );
            }
        }
        // In one round from nothing, the same chains: verdicts do not depend on batches.
        let mut fresh = LazyAttachment::new(&evaluator, &poses, None);
        fresh.widen_to(bound);
        assert_eq!(on_chains_up_to(&setup, &fresh.robust(), bound), expected);
    }
}
