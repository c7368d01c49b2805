//! `.cdict` dictionary files as they are found on disk: a valid file opens, verifies and is
//! described by `info --json`; every kind of damage (truncation, wrong magic, another format
//! version, a flipped byte in the preamble, the section table or any of the four sections, a
//! header that contradicts its setup hash) is refused with its own [`Problem`] variant and a
//! message naming the file (and the section); shards that do not make one dictionary are
//! refused by `merge`, shards that do merge give the single build's bytes; a shard is refused
//! where a whole dictionary is needed. Resealed forgeries (valid checksums) that would change
//! answers are refused by `verify` (a header that is not what a build of its embedded setup
//! writes, overlapping sections, an embedded URDF nested 100 000 deep) or caught by
//! `verify --recompute` (forged margins, an altered setup with its hash patched). The
//! binary's exit code for all of these is 2.

use crate::common;

use cable_dict::dictionary::format::{self, SectionKind};
use cable_dict::dictionary::{
    BuildOptions, Built, Dictionary, DictionaryError, Problem, build, merge, merge_signed_by,
    write_dictionary,
};
use cable_dict::setup::Setup;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

const SETUP: &str = "tests/data/dict_setup.toml";
const MOTION: &str = "motions/viper_s850/pick_and_place.csv";
const DIRECTIONS: usize = 8;

/// The fixture setup built with `directions` (whole, or one shard `(i, n)`).
fn fixture(setup: &Setup, directions: usize, shard: Option<(u32, u32)>) -> Built {
    let options = BuildOptions { directions, shard };
    build(setup, &options).expect("the fixture builds")
}

/// The fixture setup and its whole dictionary with [`DIRECTIONS`], built once per process.
fn whole() -> &'static (Setup, Built) {
    static WHOLE: OnceLock<(Setup, Built)> = OnceLock::new();
    WHOLE.get_or_init(|| {
        let setup =
            Setup::from_file(crate::common::root().join(SETUP)).expect("the fixture setup loads");
        let built = fixture(&setup, DIRECTIONS, None);
        (setup, built)
    })
}

/// (kind code, byte range) of each section-table entry, read from the bytes themselves.
fn sections(bytes: &[u8]) -> Vec<(u32, Range<usize>)> {
    let word = |at: usize, n: usize| {
        let mut le = [0u8; 8];
        le[..n].copy_from_slice(&bytes[at..at + n]);
        u64::from_le_bytes(le) as usize
    };
    (0..4)
        .map(|i| {
            let entry = format::PREAMBLE_LEN + i * format::TABLE_ENTRY_LEN;
            let offset = word(entry + 8, 8);
            (word(entry, 4) as u32, offset..offset + word(entry + 16, 8))
        })
        .collect()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("written");
    path
}

/// The message names the file (and, for a checksum, the place).
fn assert_names(error: &DictionaryError, path: &Path, place: &str) {
    let message = error.to_string();
    assert_eq!(error.path, path, "{message}");
    assert!(message.contains(&path.display().to_string()), "{message}");
    assert!(message.contains(place), "{message}");
}

fn open_error(path: &Path) -> DictionaryError {
    Dictionary::open(path).expect_err("the damaged file is refused")
}

#[test]
fn a_valid_file_opens_verifies_and_info_reports_the_build() {
    let (setup, built) = whole();
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("dict.cdict");
    write_dictionary(&path, built).expect("written");
    let bytes = std::fs::read(&path).expect("read back");
    assert_eq!(bytes, built.to_bytes().expect("encodes"));

    let dictionary = Dictionary::open(&path).expect("opens");
    dictionary.verify().expect("verifies");
    assert_eq!(dictionary.directions().len(), DIRECTIONS);
    assert_eq!(
        dictionary.setup().expect("setup").content_hash,
        setup.content_hash
    );

    let output = common::run(&["info", path.to_str().expect("utf-8"), "--json"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    let info: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(info["directions"], DIRECTIONS);
    assert!(info["shard"].is_null());
    // One catalogue per link with two or more distinct places, counted here from the
    // positions and angles as written (coincident copies are the same place).
    let mut places: std::collections::BTreeMap<String, std::collections::BTreeSet<String>> =
        Default::default();
    for guide in &setup.guides {
        let link = setup.robot.links[guide.body].name.clone();
        for c in &guide.configurations {
            let written = format!("{:?} {:?}", c.position_mm, c.rpy_deg);
            places.entry(link.clone()).or_default().insert(written);
        }
    }
    places.retain(|_, written| written.len() >= 2);
    let links = info["links"].as_array().expect("links");
    assert_eq!(links.len(), places.len(), "{links:?}");
    for (entry, (link, written)) in links.iter().zip(&places) {
        assert_eq!(entry["link"], link.as_str());
        assert_eq!(entry["clamps"], written.len());
    }
    assert!(links.iter().any(|s| s["link"] == "link_4"), "{links:?}");
}

#[test]
fn a_truncated_file_is_not_a_dictionary_or_has_the_wrong_length() {
    let bytes = whole().1.to_bytes().expect("encodes");
    let dir = tempfile::tempdir().expect("temp dir");
    for cut in [0, 10, 63, 64, 100, bytes.len() - 1] {
        let path = write(dir.path(), &format!("cut{cut}.cdict"), &bytes[..cut]);
        let error = open_error(&path);
        if cut < format::PREAMBLE_LEN {
            assert!(
                matches!(error.problem, Problem::NotADictionary(_)),
                "{cut}: {error}"
            );
        } else {
            assert!(
                matches!(
                    error.problem,
                    Problem::Length { expected, actual }
                        if expected == bytes.len() as u64 && actual == cut as u64
                ),
                "{cut}: {error}"
            );
        }
        assert_names(&error, &path, "");
    }
}

#[test]
fn a_wrong_magic_is_not_a_dictionary() {
    let mut bytes = whole().1.to_bytes().expect("encodes");
    bytes[0] ^= 0x01;
    let dir = tempfile::tempdir().expect("temp dir");
    let path = write(dir.path(), "magic.cdict", &bytes);
    let error = open_error(&path);
    assert!(
        matches!(error.problem, Problem::NotADictionary(_)),
        "{error}"
    );
    assert_names(&error, &path, "magic");
}

#[test]
fn a_future_old_or_unknown_version_is_refused_as_such() {
    let bytes = whole().1.to_bytes().expect("encodes");
    let dir = tempfile::tempdir().expect("temp dir");
    for version in [5u32, 3, 2, 1, 0] {
        let mut altered = bytes.clone();
        altered[8..12].copy_from_slice(&version.to_le_bytes());
        let path = write(dir.path(), &format!("v{version}.cdict"), &altered);
        let error = open_error(&path);
        match version {
            5 => {
                assert!(
                    matches!(
                        error.problem,
                        Problem::FutureVersion {
                            found: 5,
                            supported: 4
                        }
                    ),
                    "{error}"
                );
                assert_names(&error, &path, "newer");
            }
            // Versions 1 (verdicts), 2 (one block per segment) and 3 (no twist margin) are
            // refused with the command that rebuilds them.
            1..=3 => {
                assert!(
                    matches!(error.problem, Problem::OldVersion { found } if found == version),
                    "{error}"
                );
                assert_names(&error, &path, "cable-dict build");
            }
            _ => {
                assert!(
                    matches!(
                        error.problem,
                        Problem::UnknownVersion {
                            found: 0,
                            supported: 4
                        }
                    ),
                    "{error}"
                );
                assert_names(&error, &path, "version 0");
            }
        }
    }
}

#[test]
fn a_flipped_byte_is_caught_by_the_checksum_of_its_place() {
    let bytes = whole().1.to_bytes().expect("encodes");
    let dir = tempfile::tempdir().expect("temp dir");
    let flipped = |name: &str, at: usize| {
        let mut altered = bytes.clone();
        altered[at] ^= 0x01;
        write(dir.path(), name, &altered)
    };
    let is_checksum = |problem: &Problem, expected: &str| {
        matches!(problem, Problem::Checksum { place, stored, computed }
            if place == expected && stored != computed)
    };

    // The preamble's reserved bytes and the section table are checked by open().
    for (name, at, place) in [
        ("preamble.cdict", 45, "preamble"),
        ("table.cdict", format::PREAMBLE_LEN + 8, "section table"),
    ] {
        let path = flipped(name, at);
        let error = open_error(&path);
        assert!(is_checksum(&error.problem, place), "{error}");
        assert_names(&error, &path, place);
    }

    // Each section, in the middle: the header by open(), the bulk sections by verify().
    let table = sections(&bytes);
    let kinds: Vec<u32> = table.iter().map(|(kind, _)| *kind).collect();
    assert_eq!(kinds, SectionKind::ALL.map(|k| k as u32));
    for ((_, range), kind) in table.into_iter().zip(SectionKind::ALL) {
        assert!(!range.is_empty(), "section '{}' is empty", kind.name());
        let path = flipped(
            &format!("{}.cdict", kind.name()),
            range.start + range.len() / 2,
        );
        let place = format!("section '{}'", kind.name());
        let error = match kind {
            SectionKind::Header => open_error(&path),
            _ => Dictionary::open(&path)
                .expect("the bulk sections are not read by open")
                .verify()
                .expect_err("verify reads every byte"),
        };
        assert!(is_checksum(&error.problem, &place), "{error}");
        assert_names(&error, &path, &place);
    }
}

#[test]
fn a_header_whose_setup_does_not_match_its_hash_is_refused_by_verify_setup_and_solve() {
    let built = &whole().1;
    let mut header = built.header.clone();
    let original = "stretch = 1.02";
    assert!(header.setup.text.contains(original));
    header.setup.text = header.setup.text.replace(original, "stretch = 1.03");
    let bytes =
        format::encode(&header, &built.directions, &built.pvs, &built.results).expect("encodes");
    let dir = tempfile::tempdir().expect("temp dir");
    let path = write(dir.path(), "altered.cdict", &bytes);

    let dictionary = Dictionary::open(&path).expect("the checksums are valid");
    for error in [
        dictionary
            .verify()
            .expect_err("verify loads the embedded setup"),
        dictionary.setup().expect_err("the hash does not match"),
    ] {
        assert!(
            matches!(error.problem, Problem::SetupHash { stored, computed }
                if stored == built.header.setup_hash && computed != stored),
            "{error}"
        );
        assert_names(&error, &path, "hash");
    }

    let output = common::run(&["solve", "--dict", path.to_str().expect("utf-8"), MOTION]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("altered.cdict"), "{stderr}");
}

/// Writes each shard under `dir` as `shard{i}of{n}-{tag}.cdict`.
fn write_shards(dir: &Path, tag: &str, shards: &[&Built]) -> Vec<PathBuf> {
    shards
        .iter()
        .map(|built| {
            let range = built.header.shard.expect("a shard");
            let name = format!("shard{}of{}-{tag}.cdict", range.index, range.count);
            let path = dir.join(name);
            write_dictionary(&path, built).expect("written");
            path
        })
        .collect()
}

fn merge_error(paths: &[PathBuf], culprit: &Path, words: &str) {
    let error = merge(paths).expect_err("the shards do not make one dictionary");
    assert!(matches!(error.problem, Problem::Merge(_)), "{error}");
    assert_names(&error, culprit, words);
}

#[test]
fn shards_of_different_direction_sets_do_not_merge() {
    let setup = &whole().0;
    let dir = tempfile::tempdir().expect("temp dir");
    let first = fixture(setup, DIRECTIONS, Some((0, 2)));
    let second = fixture(setup, DIRECTIONS + 4, Some((1, 2)));
    let paths = write_shards(dir.path(), "mixed", &[&first, &second]);
    merge_error(&paths, &paths[1], "direction");
}

#[test]
fn overlapping_missing_and_whole_files_do_not_merge() {
    let (setup, whole) = whole();
    let dir = tempfile::tempdir().expect("temp dir");
    let halves = [
        fixture(setup, DIRECTIONS, Some((0, 2))),
        fixture(setup, DIRECTIONS, Some((1, 2))),
    ];
    let halves = write_shards(dir.path(), "half", &[&halves[0], &halves[1]]);
    let thirds = [
        fixture(setup, DIRECTIONS, Some((0, 3))),
        fixture(setup, DIRECTIONS, Some((2, 3))),
    ];
    let thirds = write_shards(dir.path(), "third", &[&thirds[0], &thirds[1]]);
    let whole_path = dir.path().join("whole.cdict");
    write_dictionary(&whole_path, whole).expect("written");

    // The halves alone do merge: the failures below come from what was added or left out.
    merge(&halves).expect("the halves merge");
    let twice = [halves[0].clone(), halves[0].clone(), halves[1].clone()];
    merge_error(&twice, &halves[0], "overlap");
    merge_error(&thirds, &thirds[1], "missing");
    merge_error(
        &[halves[0].clone(), whole_path.clone()],
        &whole_path,
        "whole dictionary",
    );
}

#[test]
fn shards_of_another_setup_do_not_merge() {
    let setup = &whole().0;
    let dir = tempfile::tempdir().expect("temp dir");
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read_to_string(Path::new(root).join(SETUP))
        .expect("fixture setup")
        .replace("../../robots", &format!("{root}/robots"))
        .replace("../../cables", &format!("{root}/cables"))
        .replace("stretch = 1.02", "stretch = 1.03");
    let other_path = write(dir.path(), "other_setup.toml", text.as_bytes());
    let other = Setup::from_file(&other_path).expect("the modified setup loads");
    assert_ne!(other.thresholds.stretch, setup.thresholds.stretch);

    let first = fixture(setup, DIRECTIONS, Some((0, 2)));
    let second = fixture(&other, DIRECTIONS, Some((1, 2)));
    let paths = write_shards(dir.path(), "setups", &[&first, &second]);
    merge_error(&paths, &paths[1], "another setup");
}

#[test]
fn shards_given_out_of_order_merge_to_the_single_builds_bytes() {
    let (setup, whole) = whole();
    let dir = tempfile::tempdir().expect("temp dir");
    let thirds: Vec<Built> = [1, 0, 2]
        .map(|i| fixture(setup, DIRECTIONS, Some((i, 3))))
        .into();
    let paths = write_shards(dir.path(), "all", &thirds.iter().collect::<Vec<_>>());
    let merged = merge(&paths).expect("the shards merge");
    assert_eq!(
        merged.to_bytes().expect("encodes"),
        whole.to_bytes().expect("encodes")
    );
}

#[test]
fn merge_requiring_signatures_refuses_unsigned_and_untrusted_shards() {
    use cable_dict::provenance::{SecretKey, TrustedKeys};
    let (setup, whole) = whole();
    let dir = tempfile::tempdir().expect("temp dir");
    let halves = [
        fixture(setup, DIRECTIONS, Some((0, 2))),
        fixture(setup, DIRECTIONS, Some((1, 2))),
    ];
    let paths = write_shards(dir.path(), "signed", &[&halves[0], &halves[1]]);
    let (builder, stranger) = (
        SecretKey::from_seed([5; 32], "shard builder"),
        SecretKey::from_seed([6; 32], "stranger"),
    );
    let trusted =
        TrustedKeys::parse(&builder.public().to_line(), Path::new("keys")).expect("the key parses");
    let sign = |path: &Path, key: &SecretKey| {
        Dictionary::open(path)
            .expect("opens")
            .sign(key)
            .expect("signs");
    };
    let refused = |culprit: &Path, words: &str| {
        let error = merge_signed_by(&paths, &trusted).expect_err("a shard is not trusted");
        assert!(matches!(error.problem, Problem::Provenance(_)), "{error}");
        assert_names(&error, culprit, words);
    };
    sign(&paths[0], &builder);
    refused(&paths[1], "unsigned");
    sign(&paths[1], &stranger);
    refused(&paths[1], "not in keys");
    sign(&paths[1], &builder);
    let merged = merge_signed_by(&paths, &trusted).expect("both shards are signed by the builder");
    assert_eq!(
        merged.to_bytes().expect("encodes"),
        whole.to_bytes().expect("encodes")
    );
}

#[test]
fn a_shard_is_not_a_whole_dictionary() {
    let setup = &whole().0;
    let dir = tempfile::tempdir().expect("temp dir");
    let shard = fixture(setup, DIRECTIONS, Some((1, 2)));
    let path = write_shards(dir.path(), "solo", &[&shard]).remove(0);

    let dictionary = Dictionary::open(&path).expect("a shard opens");
    dictionary.verify().expect("and verifies");
    let error = dictionary
        .setup()
        .expect_err("a shard has no whole setup to solve with");
    assert!(
        matches!(error.problem, Problem::Shard { index: 1, count: 2 }),
        "{error}"
    );
    assert_names(&error, &path, "merge");

    let output = common::run(&["solve", "--dict", path.to_str().expect("utf-8"), MOTION]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("shard1of2-solo.cdict"), "{stderr}");
}

#[test]
fn the_binary_refuses_damaged_files_with_exit_code_2() {
    let bytes = whole().1.to_bytes().expect("encodes");
    let dir = tempfile::tempdir().expect("temp dir");
    let results = sections(&bytes)[SectionKind::Results as usize - 1]
        .1
        .clone();
    let mut damaged = bytes.clone();
    damaged[results.start + results.len() / 2] ^= 0x01;
    let damaged = write(dir.path(), "damaged.cdict", &damaged);
    let truncated = write(dir.path(), "truncated.cdict", &bytes[..bytes.len() / 2]);
    let intact = write(dir.path(), "intact.cdict", &bytes);

    let run = |args: &[&str]| {
        let output = common::run(args);
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        (output.status.code(), stderr)
    };
    let (code, stderr) = run(&["verify", intact.to_str().expect("utf-8")]);
    assert_eq!(code, Some(0), "{stderr}");
    let (code, stderr) = run(&["verify", damaged.to_str().expect("utf-8")]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("damaged.cdict") && stderr.contains("results"),
        "{stderr}"
    );
    let (code, stderr) = run(&["info", truncated.to_str().expect("utf-8")]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("truncated.cdict"), "{stderr}");
}

/// A forged header with more clamps on a link than a PV record can index (so that its grid,
/// lengths × clamps², would be out of reach of the records) is refused before anything is
/// multiplied (an earlier layout's count overflowed 64 bits: it panicked in debug builds).
#[test]
fn a_header_with_more_clamps_than_a_record_indexes_is_refused() {
    let built = &whole().1;
    let mut header = built.header.clone();
    let link = &mut header.links[0];
    link.lengths = vec![1, 2];
    let clamp = link.clamps[0].clone();
    link.clamps = vec![clamp; usize::from(u16::MAX) + 1];
    header.pv_total = 2 * (1u64 << 32);
    header.shard = Some(format::ShardRange {
        index: 0,
        count: 1,
        first_pv: 0,
        end_pv: 1,
    });
    let n = built.directions.len();
    let bytes = format::encode(
        &header,
        &built.directions,
        &built.pvs[..1],
        &built.results[..n],
    )
    .expect("encodes");
    let problem = cable_dict::dictionary::check_bytes(&bytes).expect_err("refused");
    assert!(
        matches!(&problem, Problem::Header(detail) if detail.contains("65536 clamps, not 2 to 65535")),
        "{problem}"
    );
}

/// An output path that cannot be written is a bad argument: exit code 2, the path named, and
/// nothing left behind.
#[test]
fn an_unwritable_output_is_refused_with_exit_code_2() {
    let dir = tempfile::tempdir().expect("temp dir");
    let target = dir.path().join("missing-folder").join("out.cdict");
    let target = target.to_str().expect("utf-8");
    let output = common::run(&["build", SETUP, "-o", target, "--directions", "8", "-q"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("out.cdict"), "{stderr}");
    assert!(!dir.path().join("missing-folder").exists());
}

/// `solve --dict` with a setup of other limits is refused (exit 2) with one message that
/// names the dictionary and the difference — once, not repeated by each error layer that
/// wraps it (it was printed three times).
#[test]
fn a_setup_with_other_limits_is_refused_once_by_the_command() {
    let built = &whole().1;
    let dir = tempfile::tempdir().expect("temp dir");
    let dict = dir.path().join("dict.cdict");
    write_dictionary(&dict, built).expect("written");
    let root = crate::common::root();
    let text = std::fs::read_to_string(root.join(SETUP)).expect("fixture");
    let robot = root.join("robots/viper_s850/viper_s850.urdf");
    let cable = root.join("cables/smc_le_cp_3_paper.toml");
    let edited = text
        .replace(
            "../../robots/viper_s850/viper_s850.urdf",
            &robot.display().to_string(),
        )
        .replace(
            "../../cables/smc_le_cp_3_paper.toml",
            &cable.display().to_string(),
        )
        .replace("stretch = 1.02", "stretch = 1.03");
    let setup = write(dir.path(), "stiffer.toml", edited.as_bytes());
    let output = common::run(&[
        "solve",
        "--dict",
        dict.to_str().expect("utf-8"),
        "--setup",
        setup.to_str().expect("utf-8"),
        MOTION,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.matches("other limits").count(), 1, "{stderr}");
    assert!(stderr.contains("dict.cdict"), "{stderr}");
}

/// `bytes` with every checksum recomputed: what a forger does after editing a file.
fn reseal(bytes: &mut [u8]) {
    use xxhash_rust::xxh3::xxh3_64;
    let word = |bytes: &[u8], at: usize| {
        u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")) as usize
    };
    let table = format::PREAMBLE_LEN..format::PREAMBLE_LEN + 4 * format::TABLE_ENTRY_LEN;
    for i in 0..4 {
        let entry = table.start + i * format::TABLE_ENTRY_LEN;
        let (offset, len) = (word(bytes, entry + 8), word(bytes, entry + 16));
        let sum = xxh3_64(&bytes[offset..offset + len]);
        bytes[entry + 24..entry + 32].copy_from_slice(&sum.to_le_bytes());
    }
    let sum = xxh3_64(&bytes[table]);
    bytes[32..40].copy_from_slice(&sum.to_le_bytes());
    let sum = xxh3_64(&bytes[..56]);
    bytes[56..64].copy_from_slice(&sum.to_le_bytes());
}

/// The fixture re-encoded after `forge` edited its parts (checksums valid).
fn forged(forge: impl Fn(&mut Built)) -> Vec<u8> {
    let mut built = whole().1.clone();
    forge(&mut built);
    built.to_bytes().expect("encodes")
}

/// Headers a forger can reseal that would change what `solve --dict` answers:
/// each opens (its checksums are valid) and each is refused by `verify`, naming the part.
#[test]
fn resealed_headers_that_would_change_answers_are_refused_by_verify() {
    let nan = f64::NAN;
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "no directions (every piece would pass)",
            forged(|b| {
                b.header.directions.count = 0;
                b.directions.clear();
                b.results.clear();
            }),
            "0 gravity directions",
        ),
        (
            "NaN covering radius",
            forged(|b| b.header.directions.covering_radius_rad = nan),
            "the covering radius",
        ),
        (
            "infinite covering radius",
            forged(|b| b.header.directions.covering_radius_rad = f64::INFINITY),
            "the covering radius",
        ),
        (
            "zero covering radius",
            forged(|b| b.header.directions.covering_radius_rad = 0.0),
            "the covering radius",
        ),
        (
            "negated directions",
            forged(|b| b.directions.iter_mut().flatten().for_each(|x| *x = -*x)),
            "not the Fibonacci sample of 8 directions",
        ),
        (
            "NaN direction",
            forged(|b| b.directions[3][0] = nan),
            "not the Fibonacci sample of 8 directions",
        ),
        (
            "header gravity unlike the setup's",
            forged(|b| b.header.directions.gravity_m_s2 = 1.62),
            "the gravity",
        ),
        (
            "other solver settings",
            forged(|b| b.header.solver.max_iterations += 1),
            "the solver settings",
        ),
        (
            "a clamp moved",
            forged(|b| b.header.links[0].clamps[0].position_m[2] += 0.01),
            "the catalogue of link",
        ),
        (
            "an error bound lowered",
            forged(|b| b.header.links[0].margin_error = [0.0; 4]),
            "error bounds",
        ),
        (
            "a setup name with folders and an ANSI sequence",
            forged(|b| b.header.setup.file_name = "../\u{1b}[31mevil.toml".into()),
            "not a plain file name",
        ),
        (
            "a mesh the URDF does not use",
            forged(|b| {
                b.header.setup.meshes.push(cable_dict::robot::MeshFile {
                    uri: "payload.stl".into(),
                    bytes: vec![0; 84],
                })
            }),
            "the embedded mesh `payload.stl` is not a mesh the embedded URDF uses",
        ),
    ];
    let dir = tempfile::tempdir().expect("temp dir");
    for (i, (case, bytes, words)) in cases.iter().enumerate() {
        let path = write(dir.path(), &format!("forged{i}.cdict"), bytes);
        let dictionary = Dictionary::open(&path).expect("its checksums are valid");
        let error = dictionary.verify().expect_err(case);
        assert!(error.to_string().contains(words), "{case}: {error}");
        assert_names(&error, &path, words);
    }
}

#[test]
fn overlapping_sections_and_foreign_bytes_resealed_are_refused_on_open() {
    let bytes = whole().1.to_bytes().expect("encodes");
    let table = sections(&bytes);
    let (directions, pvs) = (table[1].1.clone(), table[2].1.clone());
    let entry = |i: usize| format::PREAMBLE_LEN + i * format::TABLE_ENTRY_LEN;
    let mut overlapping = bytes.clone();
    // The PV section pointed at the directions' bytes (as long as they last).
    let start = (directions.start as u64).to_le_bytes();
    overlapping[entry(2) + 8..entry(2) + 16].copy_from_slice(&start);
    let len = (pvs.len().min(directions.len()) / 16 * 16) as u64;
    overlapping[entry(2) + 16..entry(2) + 24].copy_from_slice(&len.to_le_bytes());
    let mut reserved = bytes.clone();
    reserved[44] = 1;
    let mut trailing = bytes.clone();
    trailing.extend_from_slice(&[0; 16]);
    let file_len = (trailing.len() as u64).to_le_bytes();
    trailing[16..24].copy_from_slice(&file_len);
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, mut bytes, words) in [
        ("overlapping", overlapping, "sections overlap"),
        ("reserved", reserved, "reserved bytes 40..56"),
        ("trailing", trailing, "16 bytes follow the last section"),
    ] {
        reseal(&mut bytes);
        let path = write(dir.path(), &format!("{name}.cdict"), &bytes);
        let error = open_error(&path);
        assert!(error.to_string().contains(words), "{name}: {error}");
    }
}

#[test]
fn an_embedded_urdf_nested_100_000_deep_is_refused_by_verify_without_overflow() {
    let depth = 100_000;
    let bytes = forged(|b| {
        b.header.setup.robot_text = format!(
            "<robot name=\"r\">\n{}{}</robot>\n",
            "<link>".repeat(depth),
            "</link>".repeat(depth)
        )
    });
    let dir = tempfile::tempdir().expect("temp dir");
    let path = write(dir.path(), "deep.cdict", &bytes);
    let dictionary = Dictionary::open(&path).expect("its checksums are valid");
    let error = dictionary
        .verify()
        .expect_err("the embedded URDF is refused");
    assert!(
        error.to_string().contains("nested more than 64 deep"),
        "{error}"
    );
    // `info` describes the header without loading the setup; it must not crash either.
    let output = common::run(&["info", path.to_str().expect("utf-8")]);
    assert_eq!(output.status.code(), Some(0), "killed by a signal?");
    let path = path.to_str().expect("utf-8");
    for args in [vec!["verify", path], vec!["solve", "--dict", path, MOTION]] {
        let output = common::run(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("nested more than 64 deep"),
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn shards_without_directions_are_refused_by_merge_without_a_panic() {
    let setup = &whole().0;
    let dir = tempfile::tempdir().expect("temp dir");
    let paths: Vec<PathBuf> = (0..2)
        .map(|i| {
            let mut shard = fixture(setup, DIRECTIONS, Some((i, 2)));
            shard.header.directions.count = 0;
            shard.directions.clear();
            shard.results.clear();
            let path = dir.path().join(format!("empty{i}.cdict"));
            std::fs::write(&path, shard.to_bytes().expect("encodes")).expect("written");
            path
        })
        .collect();
    let error = merge(&paths).expect_err("a shard without directions does not verify");
    assert!(
        error.to_string().contains("0 gravity directions"),
        "{error}"
    );
}

/// The index of a measured record of the fixture with a negative stored margin at some
/// direction: a piece the exact test rejects.
fn a_failing_piece(built: &Built) -> usize {
    let n = built.directions.len();
    (0..built.pvs.len())
        .find(|&k| {
            let record = &built.pvs[k];
            record.sub_segments > 0
                && !record.has(format::PvRecord::TOO_SHORT)
                && built.results[k * n..(k + 1) * n]
                    .iter()
                    .any(|r| r.values().is_some_and(|v| v.iter().any(|&m| m < -0.1)))
        })
        .expect("the fixture has a failing piece")
}

/// `verify --recompute` catches what no checksum can: margins forged to pass, and an
/// embedded setup altered with its hash patched (a bend limit, so every stored margin is
/// stale) — naming the first disagreeing record; the genuine file agrees everywhere.
#[test]
fn recomputation_catches_forged_margins_and_an_altered_setup() {
    let (setup, built) = whole();
    let k = a_failing_piece(built);
    let n = built.directions.len();
    let pass = format::MarginRecord::quantize(Some([5.0, 0.01, 1.0, 100.0]));
    let margins = forged(|b| {
        b.results[k * n..(k + 1) * n].fill(pass);
        // A careful forger also sets the flags and counts the forged margins imply.
        b.derive_flags(&setup.robustness);
    });
    let altered_text = setup.text.replace("stretch = 1.02", "stretch = 1.05");
    assert_ne!(altered_text, setup.text);
    let altered = Setup::from_texts(
        &altered_text,
        Path::new(&built.header.setup.file_name),
        &setup.robot_text,
        &setup.cable_text,
        &setup.robot.mesh_files,
    )
    .expect("the altered setup loads");
    let patched = forged(|b| {
        b.header.setup.text = altered_text.clone();
        b.header.setup_hash = altered.content_hash;
    });
    let dir = tempfile::tempdir().expect("temp dir");
    let genuine = write(
        dir.path(),
        "genuine.cdict",
        &built.to_bytes().expect("encodes"),
    );
    let margins = write(dir.path(), "margins.cdict", &margins);
    let patched = write(dir.path(), "patched.cdict", &patched);
    let all = cable_dict::dictionary::RecomputeChoice::All;
    let recompute = |path: &Path| {
        let dictionary = Dictionary::open(path).expect("opens");
        dictionary
            .verify()
            .expect("every byte and the header check out");
        dictionary.recompute(all).expect("recomputes")
    };
    let genuine_result = recompute(&genuine);
    assert_eq!(genuine_result.disagreement, None);
    assert_eq!(genuine_result.checked, genuine_result.measured);
    let forged_margins = recompute(&margins).disagreement.expect("caught");
    let record = built.header.stored_pvs().start + k as u64;
    assert_eq!(forged_margins.record, record, "{forged_margins}");
    assert!(
        forged_margins.what.contains("stored +5"),
        "{forged_margins}"
    );
    let stale = recompute(&patched).disagreement.expect("caught");
    assert!(stale.what.contains("stretch margin"), "{stale}");

    let output = common::run(&[
        "verify",
        margins.to_str().expect("utf-8"),
        "--recompute",
        "all",
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("margins.cdict: a stored cable piece is not what the embedded setup gives (forged, stale or computed differently): PV record {record} ")),
        "{stderr}"
    );
}

/// Record flags a forger can reseal, with the header's counts made to agree: a failing
/// candidate promoted to D1 and D2 (what `info` counts), a measured record made
/// inadmissible with its margins cleared (out of `verify --recompute`'s draw), and one made
/// "too short" though its clamps are within its length. Each opens and is refused by
/// `verify`, naming the record and the flags.
#[test]
fn resealed_flags_that_contradict_the_setup_or_the_margins_are_refused_by_verify() {
    use format::PvRecord;
    let (_, built) = whole();
    let n = built.directions.len();
    let stored = built.header.stored_pvs().start;
    let records = &built.pvs;
    let failing = (0..records.len())
        .find(|&k| {
            let r = &records[k];
            r.has(PvRecord::CANDIDATE)
                && !r.has(PvRecord::D1_ALL)
                && !r.has(PvRecord::TOO_SHORT)
                && r.sub_segments > 0
        })
        .expect("the fixture has a failing candidate");
    let measured = (0..records.len())
        .find(|&k| {
            let r = &records[k];
            r.has(PvRecord::ADMISSIBLE)
                && !r.has(PvRecord::D1_ALL)
                && r.sub_segments > 0
                && r.error_factor == [0; 4]
                && built.results[k * n..(k + 1) * n]
                    .iter()
                    .any(|row| row.values().is_some())
        })
        .expect("the fixture has a measured record without an error factor");
    let cases = [
        (
            failing,
            "0x000f",
            forged(|b| {
                let slot = usize::from(b.pvs[failing].link);
                b.pvs[failing].flags |= PvRecord::D1_ALL | PvRecord::D2_ALL;
                b.header.links[slot].d1_all += 1;
                b.header.links[slot].d2_all += 1;
            }),
        ),
        (
            measured,
            "ADMISSIBLE",
            forged(|b| {
                b.pvs[measured].flags &= !(PvRecord::ADMISSIBLE | PvRecord::CANDIDATE);
                b.results[measured * n..(measured + 1) * n].fill(format::MarginRecord::UNMEASURED);
            }),
        ),
        (
            // "Too short" for clamps it reaches: out of every chain and of the draw.
            measured,
            "TOO_SHORT",
            forged(|b| {
                b.pvs[measured].flags |= PvRecord::TOO_SHORT;
                b.pvs[measured].error_factor = [0; 4];
                b.results[measured * n..(measured + 1) * n].fill(format::MarginRecord::UNMEASURED);
            }),
        ),
    ];
    let dir = tempfile::tempdir().expect("temp dir");
    for (i, (k, flags, bytes)) in cases.iter().enumerate() {
        let path = write(dir.path(), &format!("flags{i}.cdict"), bytes);
        let dictionary = Dictionary::open(&path).expect("its checksums are valid");
        let error = dictionary.verify().expect_err(flags).to_string();
        let record = format!("PV record {}", stored + *k as u64);
        assert!(error.contains(&record), "{error}");
        assert!(error.contains(&format!("flags {flags}")), "{error}");
    }
}

/// A dictionary's verdicts are of the Hermite connected geometry it was built with: `solve
/// --dict … --connect linear` would test its other segments another way and answer neither
/// method's path, so it is refused naming the file and its geometry.
#[test]
fn a_dictionary_is_not_used_with_another_connected_geometry() {
    let dict = "dictionaries/viper_s850_pick_and_place.cdict";
    let output = common::run(&["solve", "--dict", dict, MOTION, "--connect", "linear"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(dict) && stderr.contains("built with the hermite connected geometry"),
        "{stderr}"
    );
}
