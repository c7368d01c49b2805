//! Answers no dictionary can bend: `solve --dict` solves exactly every piece a chain takes
//! from the file (the piece and its robustness neighbours) before the chain is offered. A
//! resealed forgery that makes every stored piece pass — robustness neighbours included —
//! yields the path the exact test finds, and each record it contradicts is reported; the
//! genuine file is contradicted nowhere.

use cable_dict::dictionary::{BuildOptions, Built, Dictionary, build, format, write_dictionary};
use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, SolveReport, solve, solve_with_dictionary};
use std::path::Path;

const SETUP: &str = "robots/viper_s850/hand_written/pick_and_place.toml";
const MOTION: &str = "motions/viper_s850/pick_and_place.csv";

/// The hand-written catalogue with its intra-link pieces made to have a length (no 0 mm
/// piece through one clamp), so that every chain takes pieces from the dictionary.
fn setup_and_motion() -> (Setup, Motion) {
    let root = crate::common::root();
    let folder = root.join(SETUP).parent().expect("a folder").to_path_buf();
    let text = std::fs::read_to_string(root.join(SETUP))
        .expect("the setup")
        .replace("allow_zero = true", "allow_zero = false");
    assert!(!text.contains("allow_zero = true"));
    let setup = Setup::from_toml_str(&text, &folder.join("pick_and_place_no_zero.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let motion =
        Motion::from_csv_file(&setup.robot, root.join(MOTION)).unwrap_or_else(|e| panic!("{e}"));
    (setup, motion)
}

/// `built` written to `dir/name` and solved with.
fn solved_with(
    dir: &Path,
    name: &str,
    built: &Built,
    setup: &Setup,
    motion: &Motion,
) -> SolveReport {
    let path = dir.join(name);
    write_dictionary(&path, built).unwrap_or_else(|e| panic!("{e}"));
    let dictionary = Dictionary::open(&path).unwrap_or_else(|e| panic!("{e}"));
    dictionary
        .verify()
        .unwrap_or_else(|e| panic!("{name}'s checksums are valid: {e}"));
    solve_with_dictionary(&dictionary, setup, motion, &options()).unwrap_or_else(|e| panic!("{e}"))
}

/// Certification is about the chains the attachment test offers: the shortest chain of
/// robust pieces the static sweep keeps is the answer compared (the catalogue's short
/// paths all fail the motion test, their two long loops touching each other).
fn options() -> SolveOptions {
    SolveOptions {
        motion_test: false,
        ..SolveOptions::default()
    }
}

#[test]
fn a_dictionary_forged_to_pass_every_piece_yields_the_exact_path() {
    let (setup, motion) = setup_and_motion();
    let exact = solve(&setup, &motion, &options()).unwrap_or_else(|e| panic!("{e}"));
    let exact_total_mm = exact
        .optimal_length_mm
        .expect("the hand-written setup has a path");
    let options = BuildOptions {
        directions: 8,
        shard: None,
    };
    let genuine = build(&setup, &options).unwrap_or_else(|e| panic!("{e}"));
    let mut forged = genuine.clone();
    let pass = format::MarginRecord::quantize(Some([5.0, 0.01, 1.0, 100.0]));
    for row in forged
        .results
        .iter_mut()
        .filter(|row| row.values().is_some())
    {
        *row = pass;
    }
    // A careful forger also sets the flags and counts the forged margins imply, so that
    // `verify` finds nothing to object to.
    forged.derive_flags(&setup.robustness);
    let dir = tempfile::tempdir().expect("temp dir");

    let from_genuine = solved_with(dir.path(), "genuine.cdict", &genuine, &setup, &motion);
    let certification = |report: &SolveReport| {
        report
            .inputs
            .dictionary
            .as_ref()
            .expect("a dictionary was used")
            .certification
            .clone()
    };
    assert_eq!(from_genuine.optimal, exact.optimal);
    let genuine_checks = certification(&from_genuine);
    assert!(genuine_checks.pieces_solved > 0);
    assert_eq!(genuine_checks.disagreements, Vec::new());

    let from_forged = solved_with(dir.path(), "forged.cdict", &forged, &setup, &motion);
    assert_eq!(
        from_forged.optimal, exact.optimal,
        "the forgery bent the path"
    );
    assert_eq!(from_forged.optimal_length_mm, exact.optimal_length_mm);
    let forged_checks = certification(&from_forged);
    assert!(
        !forged_checks.disagreements.is_empty(),
        "the forgery offered no shorter chain: the test shows nothing"
    );
    let summary = from_forged.to_string();
    assert!(summary.contains("records contradicted"), "{summary}");
    for disagreement in &forged_checks.disagreements {
        assert!(
            summary.contains(&disagreement.describe(&from_forged_file(dir.path()))),
            "{summary}"
        );
        let line = disagreement.describe("forged.cdict");
        assert!(line.contains(&disagreement.link), "{line}");
        assert!(line.contains("forged.cdict"), "{line}");
        assert!(disagreement.piece_length_mm <= exact_total_mm, "{line}");
    }
}

/// The dictionary file name a report shows for the forged file.
fn from_forged_file(dir: &Path) -> String {
    dir.join("forged.cdict").display().to_string()
}

/// Forgeries made to *fail*, resealed with the flags and counts they imply so that `verify`
/// passes: one holding record, only its robustness neighbour, every length of its clamp
/// pair, a whole link, every record, and two records' rows swapped. A piece the file rejects is solved all
/// the same — the lazy search decides only pieces a chain within its bound could use — so
/// each answers exactly what `--setup` answers, with the same sets, and the genuine file too.
#[test]
fn a_dictionary_forged_to_fail_hides_no_path() {
    let (setup, motion) = setup_and_motion();
    let exact = solve(&setup, &motion, &options()).unwrap_or_else(|e| panic!("{e}"));
    assert!(exact.optimal.is_some(), "the hand-written setup has a path");
    let genuine = build(
        &setup,
        &BuildOptions {
            directions: 8,
            shard: None,
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let n = genuine.directions.len();
    let fail = format::MarginRecord::quantize(Some([-5.0, 0.01, 1.0, 100.0]));
    let measured: Vec<usize> = (0..genuine.pvs.len())
        .filter(|&k| {
            genuine.results[k * n..(k + 1) * n]
                .iter()
                .any(|r| r.values().is_some())
        })
        .collect();
    let holding: Vec<usize> = (measured.iter().copied())
        .filter(|&k| genuine.pvs[k].has(format::PvRecord::D1_ALL))
        .collect();
    assert!(holding.len() > 2, "the file has holding pieces to forge");
    let forge = |which: &dyn Fn(usize) -> bool| {
        let mut forged = genuine.clone();
        for &k in measured.iter().filter(|&&k| which(k)) {
            forged.results[k * n..(k + 1) * n].fill(fail);
        }
        forged.derive_flags(&setup.robustness);
        forged
    };
    let first_link = genuine.pvs[holding[0]].link;
    let held = genuine.pvs[holding[0]];
    let same_pair = |k: usize| {
        let r = &genuine.pvs[k];
        (r.link, r.start, r.end) == (held.link, held.start, held.end)
    };
    // Its robustness neighbour one step longer (on no chain of its own: a forger's quiet
    // way to take the piece out of every chain).
    let delta_s = setup.robustness.delta_s as u32;
    let neighbour = (0..genuine.pvs.len())
        .find(|&k| same_pair(k) && genuine.pvs[k].sub_segments == held.sub_segments + delta_s)
        .expect("a robustness neighbour is stored");
    let mut swapped = genuine.clone();
    let (a, b) = (
        holding[0],
        *measured
            .iter()
            .find(|&&k| !holding.contains(&k))
            .expect("a failing piece"),
    );
    for d in 0..n {
        swapped.results.swap(a * n + d, b * n + d);
    }
    swapped.derive_flags(&setup.robustness);
    let cases = [
        ("genuine", genuine.clone()),
        ("one holding record", forge(&|k| k == holding[0])),
        ("its robustness neighbour only", forge(&|k| k == neighbour)),
        ("every length of its clamp pair", forge(&same_pair)),
        (
            "a whole link",
            forge(&|k| genuine.pvs[k].link == first_link),
        ),
        ("every record", forge(&|_| true)),
        ("two rows swapped", swapped),
    ];
    let dir = tempfile::tempdir().expect("temp dir");
    for (case, built) in &cases {
        let report = solved_with(
            dir.path(),
            &format!("{}.cdict", case.replace(' ', "_")),
            built,
            &setup,
            &motion,
        );
        assert_eq!(report.status, exact.status, "{case}");
        assert_eq!(
            report.optimal, exact.optimal,
            "{case}: the file bent the path"
        );
        for m in 0..setup.segment_count() {
            let (x, y) = (&exact.segments[m], &report.segments[m]);
            assert_eq!((x.d1, x.d2), (y.d1, y.d2), "{case}: C{}", m + 1);
        }
    }
}
