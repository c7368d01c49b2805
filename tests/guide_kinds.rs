//! Clamps that are not rigid (setup key `kind`): the rotating clamp and the swivel at the
//! cable's end, on the one-joint spindle of `tests/common/spindle.rs`, against closed forms,
//! and the search's choice among the kinds a guide offers.
//!
//! A straight cable hangs 0.4 m along the spindle's axis from a clamp on the base to one on
//! the spindle. Turning the spindle by θ twists it by θ/L when both clamps are rigid; a
//! rotating clamp on the spindle lets it turn about its own axis, so it does not twist at all
//! — in the attachment test, the static sweep and the motion test alike.

use crate::common::spindle::{cable_text, motion_test, spindle_setup_file, turning};
use cable_dict::attachment::{ConnectMethod, Evaluator, MotionSweep};
use cable_dict::path::Pv;
use cable_dict::setup::{GuideKind, Setup};
use cable_dict::solve::{SolveOptions, Status, solve};
use std::path::Path;

/// The straight hanging cable with `end_keys` in the spindle clamp's table and a torsion
/// limit of `limit` deg/m.
fn hanging(dir: &Path, end_keys: &str, limit: f64) -> Setup {
    let down = [180.0, 0.0, 0.0];
    let path = spindle_setup_file(
        dir,
        ("base", [0.0, 0.0, 400.0], down),
        ("spindle", [0.0, 0.0, 0.0], down),
        40,
        // One bend radius, loose: only the twist decides here.
        &cable_text(20.0, 20.0, limit),
        end_keys,
    );
    Setup::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Turned by 90°, a rigid clamp twists the cable by 225 °/m (refused by a 200 °/m limit);
/// a rotating one leaves it untwisted and within the limit, in every stage.
#[test]
fn a_rotating_clamp_at_the_cable_end_takes_no_twist_in_any_stage() {
    let dir = tempfile::tempdir().unwrap();
    let motion = |setup: &Setup| turning(setup, 90.0, 1.0);
    for (keys, twisted) in [("", true), ("kind = \"rotating\"\n", false)] {
        let setup = hanging(dir.path(), keys, 200.0);
        assert_eq!(
            setup.guides[1].configurations[0].kind,
            if twisted {
                GuideKind::Rigid
            } else {
                GuideKind::Rotating
            }
        );
        let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).unwrap();
        let links = setup.robot.link_poses(&[90f64.to_radians()]).unwrap();
        let check = evaluator.check_at(0, &Pv::new(40, 0, 0), &links);
        let twist = check.metrics.expect("an equilibrium").twist_deg_per_m;
        let closed_form = if twisted { 225.0 } else { 0.0 };
        assert!(
            (twist.abs() - closed_form).abs() < 1e-6 * 225.0,
            "{keys}: {twist}"
        );
        assert_eq!(check.passed(), !twisted, "{keys}: {:?}", check.detail);

        let motion = motion(&setup);
        let mut sweep = MotionSweep::new(&evaluator, &motion).unwrap();
        assert_eq!(
            sweep.check(0, &Pv::new(40, 0, 0)).is_some(),
            twisted,
            "{keys}"
        );
        let report = motion_test(&setup, 40, &motion);
        let worst = report.worst_twist.as_ref().map_or(0.0, |w| w.value);
        assert!(
            (worst - closed_form).abs() < 1e-3 * 225.0,
            "{keys}: {worst}"
        );
        assert_eq!(report.passed, !twisted, "{keys}: {}", report.summary());
    }
}

/// A clamp that may be rigid or rotating (`kind = ["rigid", "rotating"]`) under the straight
/// cable turned by 90° (225 °/m of twist with rigid clamps; no length error tolerated, since
/// a taut cable's shorter neighbours do not reach): the search takes the rotating one where
/// the rigid one twists the cable past its limit, and the rigid one — the simpler part —
/// where both hold.
#[test]
fn the_search_chooses_the_simplest_kind_that_holds() {
    let dir = tempfile::tempdir().unwrap();
    let keys = "kind = [\"rotating\", \"rigid\"]\n";
    for (limit, expected) in [(200.0, GuideKind::Rotating), (300.0, GuideKind::Rigid)] {
        let taut = hanging(dir.path(), keys, limit);
        let text = std::fs::read_to_string(&taut.source).unwrap();
        std::fs::write(&taut.source, text.replace("range = 2", "range = 0")).unwrap();
        let setup = Setup::from_file(&taut.source).unwrap_or_else(|e| panic!("{e}"));
        let kinds: Vec<GuideKind> = setup.guides[1]
            .configurations
            .iter()
            .map(|c| c.kind)
            .collect();
        assert_eq!(kinds, [GuideKind::Rigid, GuideKind::Rotating]);
        let motion = turning(&setup, 90.0, 1.0);
        let report = solve(&setup, &motion, &SolveOptions::default()).unwrap();
        assert_eq!(report.status, Status::Solved, "{}", report.explanation);
        let path = &report.shown_candidate().expect("an answer").path;
        let end = path.configurations[1];
        assert_eq!(
            setup.guides[1].configurations[end].kind, expected,
            "limit {limit}"
        );
    }
}

/// Every wrong `kind` is refused naming the file, the line and the key.
#[test]
fn wrong_kinds_are_refused_with_the_key_and_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let down = [180.0, 0.0, 0.0];
    for (keys, says) in [
        ("kind = \"sliding\"\n", "needs friction_coefficient"),
        (
            "kind = \"sliding\"\nfriction_coefficient = -0.1\n",
            "in [0, 2]",
        ),
        (
            "kind = \"sliding\"\nfriction_coefficient = 0.1\n",
            "is the last guide: a sliding guide sits between two clamps",
        ),
        ("friction_coefficient = 0.1\n", "offers no sliding"),
        (
            "kind = [\"rigid\", \"sliding\"]\nfriction_coefficient = 0.1\n",
            "offer it alone",
        ),
        ("kind = \"retraction\"\n", "needs preload_n"),
        (
            "kind = \"retraction\"\npreload_n = 1.0\nrate_n_per_mm = 0.01\ntravel_mm = 0.0\n\
             stored_from = \"G1\"\n",
            "(0, 5000]",
        ),
        (
            "kind = \"retraction\"\npreload_n = 1.0\nrate_n_per_mm = 0.01\ntravel_mm = 100.0\n",
            "needs stored_from",
        ),
        ("travel_mm = 100.0\n", "offers no retraction"),
        (
            "kind = \"ball\"\n",
            "a kind is \"rigid\", \"rotating\", \"swivel\", \"sliding\" or",
        ),
        ("kind = 3\n", "a kind is"),
        ("kind = []\n", "an empty list"),
        ("kind = [\"rigid\", \"rigid\"]\n", "named twice"),
        ("kind = \"swivel\"\n", "needs cone_deg"),
        ("kind = \"swivel\"\ncone_deg = 0.0\n", "(0, 180]"),
        ("kind = \"swivel\"\ncone_deg = 200.0\n", "(0, 180]"),
        ("cone_deg = 20.0\n", "offers no swivel (kind = \"swivel\")"),
        ("kind = \"rotating\"\ncone_deg = 20.0\n", "offers no swivel"),
    ] {
        let path = spindle_setup_file(
            dir.path(),
            ("base", [0.0, 0.0, 400.0], down),
            ("spindle", [0.0, 0.0, 0.0], down),
            40,
            &cable_text(40.0, 80.0, 360.0),
            keys,
        );
        let error = Setup::from_file(&path).expect_err(keys).to_string();
        assert!(error.contains(says), "{keys}: {error}");
        assert!(
            error.contains("setup.toml") && error.contains("guides[1]"),
            "{error}"
        );
    }
}

/// A swivel clamp between two pieces has one place and is its guide's only kind: offered
/// beside a rigid clamp, or on a guide with sites, it is refused naming the guide; a
/// rotating clamp at the cable's end loads, and the setup's content hash changes with it.
#[test]
fn a_kind_between_two_pieces_is_refused_and_one_at_the_end_changes_the_hash() {
    let root = crate::common::root();
    let source = root.join("robots/viper_s850/pick_and_place.toml");
    let text = crate::common::bundled_setup_text();
    let with = |guide: &str, keys: &str| {
        let line = format!("name = \"{guide}\"\n");
        assert!(text.contains(&line));
        text.replacen(&line, &format!("{line}{keys}"), 1)
    };
    for (keys, says) in [
        (
            "kind = [\"rigid\", \"swivel\"]\ncone_deg = 20.0\n",
            "G2 is between two pieces of cable: a swivel clamp there is its only kind",
        ),
        (
            "kind = \"swivel\"\ncone_deg = 20.0\n",
            "places: a swivel guide has one",
        ),
    ] {
        let error = Setup::from_toml_str(&with("G2", keys), &source)
            .expect_err("refused")
            .to_string();
        assert!(
            error.contains("guides[1].kind") && error.contains(says),
            "{error}"
        );
    }
    let plain = Setup::from_toml_str(&text, &source).unwrap();
    let end = Setup::from_toml_str(&with("G4", "kind = \"rotating\"\n"), &source).unwrap();
    assert_eq!(end.guides[3].kinds, [GuideKind::Rotating]);
    assert_ne!(plain.content_hash, end.content_hash);
}

/// A straight cable down the spindle's axis through a middle clamp on the base: 0.3 m from
/// the top clamp to the middle one, 0.3 m on to the spindle. Turning the spindle by θ with a
/// rigid middle clamp twists only the lower piece, by θ over 0.3 m; a rotating middle clamp
/// lets the cable turn in it until both pieces carry the same torque: each twisted by θ/2,
/// θ over the whole 0.6 m (closed form), the cable turned by θ/2 in the clamp, in the motion
/// test.
#[test]
fn a_rotating_clamp_between_two_pieces_shares_the_twist_by_their_lengths() {
    let dir = tempfile::tempdir().unwrap();
    let down = [180.0, 0.0, 0.0];
    let cable = cable_text(20.0, 20.0, 1e4);
    // Writes the robot and the cable file next to the setup.
    spindle_setup_file(
        dir.path(),
        ("base", [0.0, 0.0, 600.0], down),
        ("spindle", [0.0, 0.0, 0.0], down),
        60,
        &cable,
        "",
    );
    let guide = |name: &str, link: &str, z: f64, keys: &str| {
        format!(
            "[[guides]]\nname = \"{name}\"\nlink = \"{link}\"\n{keys}configurations = [\n  \
             {{ name = \"only\", position_mm = [0.0, 0.0, {z:?}], rpy_deg = {down:?} }},\n]\n"
        )
    };
    let segment = |from: &str, to: &str| {
        format!(
            "[[segments]]\nfrom = \"{from}\"\nto = \"{to}\"\n\
             lengths = {{ min = 30, max = 30, step = 1, allow_zero = false }}\n"
        )
    };
    let turned_by_deg = 90.0;
    for (middle, lower_per_m, upper_per_m) in [
        ("", turned_by_deg / 0.3, 0.0),
        (
            "kind = \"rotating\"\n",
            turned_by_deg / 0.6,
            turned_by_deg / 0.6,
        ),
    ] {
        let text = format!(
            "robot = \"spindle.urdf\"\ncable = \"cable.toml\"\ngravity_m_s2 = [0.0, 0.0, -9.81]\n\
             max_guides_per_link = 2\ninstall_joints_deg = [0.0]\n\n{}\n{}\n{}\n{}\n{}\n{}",
            crate::common::limits("\"cable\""),
            guide("G1", "base", 600.0, ""),
            guide("G2", "base", 300.0, middle),
            guide("G3", "spindle", 0.0, ""),
            segment("G1", "G2"),
            segment("G2", "G3"),
        );
        let path = dir.path().join("three.toml");
        std::fs::write(&path, text).unwrap();
        let setup = Setup::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
        let motion = turning(&setup, turned_by_deg, 1.0);
        let path = cable_dict::path::CablePath::through_every_guide(vec![30, 30], vec![0, 0, 0]);
        let options = cable_dict::motion_test::MotionTestOptions::default();
        let report = cable_dict::motion_test::run(&setup, &path, &motion, &options).unwrap();
        let twist = |piece: usize| {
            let twists = &report.twists[piece];
            twists.twist_deg_per_m.abs()
        };
        // The rotating clamp took half the turn off the lower piece: θ/2 turned in it.
        let turned: Vec<f64> = report
            .clamp_turns
            .iter()
            .map(|t| t.largest_turn_deg.abs())
            .collect();
        match middle.is_empty() {
            true => assert!(turned.is_empty(), "{turned:?}"),
            false => assert!(
                turned.len() == 1 && (turned[0] - turned_by_deg / 2.0).abs() < 0.1,
                "{turned:?}"
            ),
        }
        for (piece, closed_form) in [(0, upper_per_m), (1, lower_per_m)] {
            assert!(
                (twist(piece) - closed_form).abs() < 2e-3 * lower_per_m,
                "{middle} piece {piece}: {} °/m against {closed_form}",
                twist(piece)
            );
        }
    }
}

/// The bundled dress pack (`robots/viper_s850/dress_pack.toml`): a retraction on the upper
/// arm, a sliding ring on the forearm. Its mistakes are refused naming the key and the reason:
/// too little cable stored for the travel (with the count it needs), a stored length that is
/// a window, a piece through the ring longer than a piece may be, an inlet that is not the
/// guide before the outlet, a sliding guide next to an optional clamp, two places for a
/// sliding guide.
#[test]
fn a_dress_pack_with_sliding_parts_is_checked_when_loaded() {
    let root = crate::common::root();
    let source = root.join("robots/viper_s850/dress_pack.toml");
    let text = std::fs::read_to_string(&source).unwrap();
    let loaded = Setup::from_toml_str(&text, &source).unwrap_or_else(|e| panic!("{e}"));
    // The pieces through the outlet and the ring are spans; the segments beside them have
    // no lengths of their own.
    let through: Vec<(String, Option<usize>)> = (0..loaded.segments.len())
        .filter(|&m| loaded.has_candidates(m))
        .map(|m| (loaded.segment_name(m), loaded.segments[m].through))
        .collect();
    assert_eq!(
        through,
        [
            ("C1–C2".to_string(), Some(1)),
            ("C3–C4".to_string(), Some(3))
        ]
    );
    // The span through the retraction: the stored 40 plus the free 10…70.
    assert_eq!(loaded.segments[4].lengths.first(), Some(&50));
    assert_eq!(loaded.segments[4].lengths.last(), Some(&110));
    let stored = "lengths = { min = 40, max = 40, step = 1, allow_zero = false }";
    assert!(text.contains(stored));
    for (from, to, says) in [
        (
            stored,
            "lengths = { min = 30, max = 30, step = 1, allow_zero = false }",
            "cannot give out the 150 mm of travel beyond their 240 mm straight run: at least 39",
        ),
        (
            stored,
            "lengths = { min = 40, max = 50, step = 1, allow_zero = false }",
            "one length (min = max, no allow_zero)",
        ),
        (
            "lengths = { min = 15, max = 70, step = 1, allow_zero = false }",
            "lengths = { min = 15, max = 9990, step = 1, allow_zero = false }",
            "from G3 through S to G5 could be 10050 sub-segments long",
        ),
        (
            "stored_from = \"G1\"",
            "stored_from = \"G3\"",
            "the guide before R is G1",
        ),
        (
            "name = \"G3\"\n",
            "name = \"G3\"\noptional = true\n",
            "R is next to G3, which is optional",
        ),
        (
            "fixed = { name = \"forearm ring\", position_mm = [80.0, 0.0, 172.5], rpy_deg = [0.0, 0.0, 0.0] }",
            "configurations = [\n  { name = \"a\", position_mm = [80.0, 0.0, 172.5], rpy_deg = [0.0, 0.0, 0.0] },\n  \
             { name = \"b\", position_mm = [80.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 0.0] },\n]",
            "S has 2 places",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let changed = text.replacen(from, to, 1);
        let error = Setup::from_toml_str(&changed, &source)
            .expect_err(to)
            .to_string();
        assert!(error.contains(says), "{to}: {error}");
        assert!(error.contains("dress_pack.toml:"), "{error}");
    }
}

/// Beside a swivel clamp between two pieces (or any guide the cable runs through) no piece
/// may be 0 mm: `allow_zero` there is refused, naming the key and the guide, not ignored.
#[test]
fn no_zero_length_beside_a_swivel_between_two_pieces() {
    let source = crate::common::root().join("robots/viper_s850/swivel_forearm.toml");
    let text = std::fs::read_to_string(&source).unwrap();
    let zero = text.replacen("allow_zero = false", "allow_zero = true", 1);
    assert_ne!(zero, text);
    let error = Setup::from_toml_str(&zero, &source)
        .expect_err("refused")
        .to_string();
    assert!(
        error.contains("segments[0].lengths.allow_zero")
            && error.contains("the cable runs on through G2"),
        "{error}"
    );
}

/// A swivel clamp between two pieces makes them one piece of the search (a span through it;
/// the declared pieces either side have no candidates), held where the two length windows
/// share the spare length in proportion to their widths, each within its window: checked
/// against that rule by hand on the bundled forearm swivel with its first window narrowed to
/// 200–400 mm (widths 20 and 60 sub-segments).
#[test]
fn a_swivel_between_two_pieces_holds_the_span_where_the_windows_share_the_spare_length() {
    let source = crate::common::root().join("robots/viper_s850/swivel_forearm.toml");
    let text = std::fs::read_to_string(&source).unwrap();
    let narrowed = text.replacen(
        "lengths = { min = 20, max = 80, step = 1, allow_zero = false }",
        "lengths = { min = 20, max = 40, step = 1, allow_zero = false }",
        1,
    );
    assert_ne!(narrowed, text);
    let setup = Setup::from_toml_str(&narrowed, &source).unwrap_or_else(|e| panic!("{e}"));
    assert!(!setup.has_candidates(0) && !setup.has_candidates(1));
    let span = (0..setup.segment_count())
        .find(|&m| setup.segments[m].through == Some(1))
        .expect("the span through the swivel");
    assert_eq!(setup.segment_guides(span), (0, 2));
    assert_eq!(setup.segments[span].lengths.first(), Some(&40));
    assert_eq!(setup.segments[span].lengths.last(), Some(&120));
    assert!(
        setup.slide_of(span).is_none(),
        "a swivel is no sliding guide"
    );
    assert!(
        !setup.segment_is_rigid(span),
        "no dictionary answers for it"
    );
    // (S, before): the spare S − 40 shared 20 : 60, rounded half up.
    for (sub_segments, before) in [(40, 20), (100, 35), (102, 36), (120, 40)] {
        let split = setup.swivel_of(span, sub_segments).expect("a swivel");
        assert_eq!(
            (split.guide, split.before),
            (1, before),
            "S = {sub_segments}"
        );
        assert!((split.cone_rad - 30f64.to_radians()).abs() < 1e-12);
    }
}

/// Advice on a piece through a swivel names the keys of the declared pieces it sums: the
/// forearm swivel with both windows one length each, the rigid answer's 280 + 340 mm, which
/// is too short for some of its clamp pairs.
#[test]
fn advice_on_a_piece_through_a_swivel_names_the_windows_it_sums() {
    let root = crate::common::root();
    let dir = tempfile::tempdir().unwrap();
    let text = crate::common::viper_setup_text("swivel_forearm.toml")
        .replacen("min = 20, max = 80", "min = 28, max = 28", 1)
        .replacen("min = 20, max = 80", "min = 34, max = 34", 1);
    let setup = dir.path().join("fixed.toml");
    std::fs::write(&setup, text).unwrap();
    let motion = root.join("motions/viper_s850/pick_and_place.csv");
    let output = crate::common::run(&[
        "solve",
        "--setup",
        setup.to_str().unwrap(),
        motion.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.starts_with("unsolved"), "{stdout}");
    assert!(
        stdout.contains("(segments[0].lengths.max or segments[1].lengths.max)"),
        "{stdout}"
    );
}
