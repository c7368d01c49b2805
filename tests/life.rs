//! The cable's life (`cable_dict::life`) against independent references: rainflow counting
//! against the PyPI package `rainflow` 3.2.0 on the ASTM E1049 example and generated
//! histories (tests/data/rainflow, written by its generate.py), and the point-by-point
//! counter of a repeating history against counting the history turned to start at its
//! largest value.

use cable_dict::life::rainflow::{Counter, cycles, reversals};
use serde_json::Value;

fn reference() -> Value {
    let path = crate::common::root().join("tests/data/rainflow/reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).expect("reference")).expect("JSON")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn rainflow_counts_as_the_reference_package_does() {
    let reference = reference();
    let series = reference["series"].as_array().expect("series");
    assert!(series.len() >= 8);
    for s in series {
        let name = s["name"].as_str().expect("name");
        let values = floats(&s["values"]);
        let turning = reversals(&values);
        let expected_indices: Vec<usize> = s["reversals"]["indices"]
            .as_array()
            .expect("indices")
            .iter()
            .map(|i| i.as_u64().expect("index") as usize)
            .collect();
        let indices: Vec<usize> = turning.iter().map(|r| r.0).collect();
        assert_eq!(indices, expected_indices, "{name}: reversal indices");
        assert_eq!(
            turning.iter().map(|r| r.1).collect::<Vec<_>>(),
            floats(&s["reversals"]["values"]),
            "{name}: reversal values"
        );
        let expected = s["cycles"].as_array().expect("cycles");
        let counted = cycles(&values);
        assert_eq!(counted.len(), expected.len(), "{name}: number of cycles");
        for (k, (c, e)) in counted.iter().zip(expected).enumerate() {
            let f = |key: &str| e[key].as_f64().expect("number");
            assert!(
                close(c.range, f("range")) && close(c.mean, f("mean")) && c.count == f("count"),
                "{name} cycle {k}: {c:?} against {e}"
            );
            assert_eq!(
                (c.start, c.end),
                (f("i_start") as usize, f("i_end") as usize),
                "{name} cycle {k}"
            );
        }
    }
}

/// A repeating history counted point by point (closed cycles as they close, the rest as
/// the history repeated) gives the cycles of the same history turned to start and end at its
/// largest value and counted whole — range by range, and a damage sum of range⁴.
#[test]
fn a_repeating_history_counted_point_by_point_is_the_history_turned_to_its_peak() {
    let reference = reference();
    for s in reference["series"].as_array().expect("series") {
        let name = s["name"].as_str().expect("name");
        let values = floats(&s["values"]);
        if values.len() < 4 {
            continue;
        }
        let mut counter = Counter::default();
        let mut online: Vec<(f64, f64)> = Vec::new();
        for &v in &values {
            counter.push(v, |range| online.push((range, 1.0)));
        }
        counter.close_periodic(|range, count| online.push((range, count)));

        let top = (0..values.len())
            .max_by(|&i, &j| values[i].total_cmp(&values[j]))
            .expect("values");
        let mut turned = values[top..].to_vec();
        turned.extend_from_slice(&values[..=top]);
        let whole: Vec<(f64, f64)> = cycles(&turned).iter().map(|c| (c.range, c.count)).collect();

        let damage = |cs: &[(f64, f64)]| cs.iter().map(|(r, c)| c * r.powi(4)).sum::<f64>();
        let count = |cs: &[(f64, f64)]| cs.iter().map(|(_, c)| c).sum::<f64>();
        assert!(
            close(damage(&online), damage(&whole)),
            "{name}: {} against {}",
            damage(&online),
            damage(&whole)
        );
        assert!(close(count(&online), count(&whole)), "{name}");
        let mut a: Vec<(f64, f64)> = online.clone();
        let mut b = whole.clone();
        for list in [&mut a, &mut b] {
            list.sort_by(|x, y| x.0.total_cmp(&y.0));
        }
        let grouped = |list: &[(f64, f64)]| {
            let mut out: Vec<(f64, f64)> = Vec::new();
            for &(r, c) in list {
                match out.last_mut() {
                    Some(last) if close(last.0, r) => last.1 += c,
                    _ => out.push((r, c)),
                }
            }
            out
        };
        let (ga, gb) = (grouped(&a), grouped(&b));
        assert_eq!(ga.len(), gb.len(), "{name}: {ga:?} against {gb:?}");
        for (x, y) in ga.iter().zip(&gb) {
            assert!(
                close(x.0, y.0) && (x.1 - y.1).abs() < 1e-12,
                "{name}: {x:?} {y:?}"
            );
        }
    }
}

/// A straight cable hanging along the spindle's axis, turned to θ and back twice per
/// motion: its twist per length runs 0 → −θ/L → 0 twice, two cycles of range θ/L, and with a
/// rated life of N cycles at ±T (torsion only, exponent k) one motion does
/// 2 (θ/L / 2T)^k / N — and (θ₁/θ₂)^k as much at θ₁ as at θ₂. The cable stays straight.
#[test]
fn a_twisting_motion_does_the_damage_of_its_twist_cycles() {
    use crate::common::spindle::{cable_text, hanging_straight};
    use cable_dict::motion::Motion;
    use cable_dict::motion_test::{MotionTestOptions, run};
    use cable_dict::path::CablePath;
    let dir = tempfile::tempdir().unwrap();
    let (cycles, torsion, k, length_m) = (1e6, 360.0, 4.0, 0.4);
    let cable = cable_text(40.0, 80.0, 1e4)
        + &format!(
            "\n[rated_life]\ncycles = {cycles}\ntorsion_deg_per_m = {torsion}\nexponent = {k}\n"
        );
    let setup = hanging_straight(dir.path(), &cable);
    let damage_at = |turn_deg: f64| {
        let q = f64::to_radians(turn_deg);
        let times = vec![0.0, 1.0, 1.5, 2.5, 3.0, 4.0, 4.5, 5.5, 6.0];
        let joints = [0.0, q, q, 0.0, 0.0, q, q, 0.0, 0.0]
            .map(|j| vec![j])
            .to_vec();
        let motion = Motion::new(&setup.robot, times, joints).unwrap();
        let path = CablePath::through_every_guide(vec![40], vec![0, 0]);
        let report = run(&setup, &path, &motion, &MotionTestOptions::default()).unwrap();
        assert!(report.passed, "{}", report.summary());
        let straight = report
            .worst_bend
            .as_ref()
            .map_or(f64::INFINITY, |w| w.value);
        assert!(straight > 10.0, "bent to {straight} m");
        report.damage[0].damage.torsion
    };
    let closed_form =
        |turn_deg: f64| 2.0 * (turn_deg / length_m / (2.0 * torsion)).powf(k) / cycles;
    for turn in [60.0, 90.0] {
        let damage = damage_at(turn);
        assert!(
            (damage / closed_form(turn) - 1.0).abs() < 4e-3,
            "turned {turn}°: {damage} against {}",
            closed_form(turn)
        );
    }
    let ratio = damage_at(90.0) / damage_at(60.0);
    assert!((ratio / 1.5f64.powf(k) - 1.0).abs() < 4e-3, "{ratio}");
}

/// The bundled pick and place under the makers' rule with a rated life and ±10 mm length
/// errors ([`crate::common::ten_mm_setup_text`]): `--min-life-cycles` answers a path that lasts what was asked,
/// every shorter path tried having failed a limit or lived shorter, its life the one `check`
/// predicts again from its own motion test; `--prefer life` answers, within the window, the
/// longest-lived path it weighed, and lives at least as long as the shortest answer.
#[test]
fn a_life_goal_answers_a_path_that_lasts() {
    use cable_dict::motion::{Cell, Motion};
    use cable_dict::setup::Setup;
    use cable_dict::solve::{LifeGoal, SolveOptions, Status, check_mounting, solve};
    let root = crate::common::root();
    let text = crate::common::ten_mm_setup_text(true);
    let source = root.join("robots/viper_s850/pick_and_place.toml");
    let setup = Setup::from_toml_str(&text, &source).unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(
        &setup.robot,
        root.join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap();
    let run = |goal: Option<LifeGoal>| {
        let options = SolveOptions {
            life_goal: goal,
            ..SolveOptions::default()
        };
        let report = solve(&setup, &motion, &options).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(report.status, Status::Solved, "{}", report.explanation);
        report
    };
    let shortest = run(None);
    let life =
        |r: &cable_dict::solve::SolveReport| r.life.as_ref().expect("a life").cycles_to_failure;
    let (shortest_mm, shortest_life) = (shortest.optimal_length_mm.unwrap(), life(&shortest));

    let asked = 1.5 * shortest_life;
    let long = run(Some(LifeGoal::AtLeast { cycles: asked }));
    assert!(life(&long) >= asked, "{} < {asked}", life(&long));
    assert!(long.optimal_length_mm.unwrap() > shortest_mm);
    let answer = long.shown_candidate().expect("the answer");
    for c in long.candidates.iter().take_while(|c| c.rank < answer.rank) {
        assert_eq!(c.passed, Some(false), "{c:?}");
        assert!(c.life_cycles.is_none_or(|l| l < asked), "{c:?}");
    }
    let check = check_mounting(
        &setup,
        &answer.path,
        &Cell::single(motion.clone(), None),
        &SolveOptions::default(),
    )
    .unwrap();
    let again = check
        .life
        .as_ref()
        .expect("check predicts it")
        .cycles_to_failure;
    assert!(
        (again / life(&long) - 1.0).abs() < 1e-12,
        "{again} against {}",
        life(&long)
    );

    let within_mm = 100.0;
    let preferred = run(Some(LifeGoal::Longest { within_mm }));
    let weighed: Vec<f64> = preferred
        .candidates
        .iter()
        .filter_map(|c| c.life_cycles)
        .collect();
    assert!(weighed.len() >= 2, "{weighed:?}");
    assert!(
        weighed.iter().all(|&l| l <= life(&preferred)),
        "{weighed:?}"
    );
    assert!(life(&preferred) >= shortest_life);
    assert!(preferred.optimal_length_mm.unwrap() <= shortest_mm + within_mm + 1e-9);
}
