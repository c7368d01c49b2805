//! Signatures of shared dictionaries end to end: a file signed by a trusted key is accepted
//! and its signer named; a file changed after signing (even resealed so that every checksum
//! and `verify` pass), a signature line edited, copied to another file or made by an
//! unknown key is refused where a signature is required.

use crate::common;

use cable_dict::dictionary::{Dictionary, format};
use cable_dict::provenance::{SecretKey, TrustedKeys, signature_path};
use std::path::{Path, PathBuf};

const BUNDLED: &str = "dictionaries/viper_s850_pick_and_place.cdict";
const OTHER: &str = "dictionaries/viper_s850_inspection.cdict";
const MOTION: &str = "motions/viper_s850/pick_and_place.csv";

fn root(path: &str) -> PathBuf {
    crate::common::root().join(path)
}

/// A copy of a bundled dictionary in `dir`.
fn copy(dir: &Path, bundled: &str, name: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::copy(root(bundled), &path).expect("copied");
    path
}

fn team_a() -> SecretKey {
    SecretKey::from_seed([1; 32], "Team A")
}

fn trusted(keys: &[&SecretKey]) -> TrustedKeys {
    let text: String = keys.iter().map(|k| k.public().to_line()).collect();
    TrustedKeys::parse(&text, Path::new("trusted_keys")).expect("the keys parse")
}

/// Rewrites `path` with its first measured margin made more favourable and every checksum
/// recomputed: a forgery `open` and `verify` accept.
fn forge_resealed(path: &Path) {
    let bytes = resealed_forgery(path);
    std::fs::write(path, bytes).expect("written");
    let forged = Dictionary::open(path).expect("the forgery opens");
    forged
        .verify()
        .expect("the resealed forgery passes verify: only the signature can tell");
}

/// The bytes of `path` with its first measured margin made more favourable and every
/// checksum recomputed (the same length).
fn resealed_forgery(path: &Path) -> Vec<u8> {
    let dictionary = Dictionary::open(path).expect("opens");
    let mut results = dictionary.results().to_vec();
    let record = results
        .iter_mut()
        .find(|r| r.values().is_some())
        .expect("a measured margin");
    record.clearance = record.clearance.saturating_add(500);
    let bytes = format::encode(
        dictionary.header(),
        dictionary.directions(),
        dictionary.pv_records(),
        &results,
    )
    .expect("encodes");
    drop(dictionary);
    bytes
}

/// What `solve --dict` opens ([`Dictionary::read`], through the command line's check) holds
/// the bytes it checked: a signed file rewritten in place during a run — a resealed forgery
/// of the same length, over the same inode — changes nothing the run reads, and the
/// signature still holds for the bytes the run holds. The reference: a memory map of the
/// same file, opened at the same moment, reads the forgery.
#[test]
fn a_signed_file_changed_in_place_during_a_run_changes_nothing_the_run_reads() {
    use std::io::Write;
    let dir = tempfile::tempdir().expect("temp dir");
    let path = copy(dir.path(), BUNDLED, "shared.cdict");
    let a = team_a();
    let keys = trusted(&[&a]);
    Dictionary::open(&path)
        .expect("opens")
        .sign(&a)
        .expect("signs");
    let run = Dictionary::read(&path).expect("reads");
    let mapped = Dictionary::open(&path).expect("maps");
    (run.provenance(Some(&keys)).expect("holds"))
        .require_trusted(&path)
        .expect("Team A signed it");
    run.verify().expect("every byte checks");
    let checked = run.results().to_vec();

    let forgery = resealed_forgery(&path);
    assert_eq!(
        forgery.len(),
        std::fs::metadata(&path).expect("size").len() as usize
    );
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .open(&path)
        .expect("opens for writing in place");
    file.write_all(&forgery).expect("rewritten in place");
    drop(file);

    assert_ne!(mapped.results(), &checked[..], "a map reads the forgery");
    assert_eq!(run.results(), &checked[..], "the run reads what it checked");
    (run.provenance(Some(&keys))
        .expect("the signature holds for the bytes held"))
    .require_trusted(&path)
    .expect("still Team A's bytes");
    let now = Dictionary::read(&path).expect("the forgery opens");
    let refused = now
        .provenance(Some(&keys))
        .expect_err("a new run sees the change");
    assert!(
        refused.problem.contains("changed after it was signed"),
        "{refused}"
    );
}

#[test]
fn a_trusted_signer_is_named_and_a_file_changed_after_signing_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = copy(dir.path(), BUNDLED, "shared.cdict");
    let (a, mallory) = (team_a(), SecretKey::from_seed([2; 32], "Mallory"));
    let keys = trusted(&[&a]);

    let dictionary = Dictionary::open(&path).expect("opens");
    let unsigned = dictionary
        .provenance(Some(&keys))
        .expect("no signature file");
    assert!(!unsigned.is_signed());
    let refusal = unsigned.require_trusted(&path).expect_err("unsigned");
    assert!(refusal.problem.contains("unsigned"), "{refusal}");

    dictionary.sign(&a).expect("signs");
    dictionary.sign(&mallory).expect("a second signer");
    let signed = dictionary.provenance(Some(&keys)).expect("both hold");
    let names: Vec<_> = signed.signers.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Team A", "Mallory"]);
    assert_eq!(signed.signers[0].trusted_as.as_deref(), Some("Team A"));
    assert_eq!(
        signed.signers[0].key,
        format!("ed25519:{}", a.public().hex())
    );
    assert_eq!(signed.signers[1].trusted_as, None);
    signed.require_trusted(&path).expect("Team A is trusted");
    // Signing again with the same key replaces its line.
    dictionary.sign(&a).expect("signs again");
    assert_eq!(dictionary.provenance(None).expect("holds").signers.len(), 2);
    drop(dictionary);

    forge_resealed(&path);
    let error = Dictionary::open(&path)
        .expect("opens")
        .provenance(Some(&keys))
        .expect_err("the signatures are of the genuine bytes");
    assert_eq!(error.file, signature_path(&path));
    assert_eq!(error.line, Some(2), "{error}");
    assert!(
        error.problem.contains("changed after it was signed"),
        "{error}"
    );
}

#[test]
fn edited_copied_and_impostor_signatures_do_not_pass() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = copy(dir.path(), BUNDLED, "shared.cdict");
    let a = team_a();
    let keys = trusted(&[&a]);
    let dictionary = Dictionary::open(&path).expect("opens");
    dictionary.sign(&a).expect("signs");
    let sig = signature_path(&path);
    let genuine = std::fs::read_to_string(&sig).expect("the signature file");

    // The name is part of what is signed.
    std::fs::write(&sig, genuine.replace("Team A", "Team B")).expect("edited");
    let error = dictionary.provenance(Some(&keys)).expect_err("edited name");
    assert!(error.problem.contains("does not verify"), "{error}");

    // A line copied beside another dictionary signs the first one's bytes only.
    let other = copy(dir.path(), OTHER, "other.cdict");
    std::fs::write(signature_path(&other), &genuine).expect("copied");
    let error = Dictionary::open(&other)
        .expect("opens")
        .provenance(Some(&keys))
        .expect_err("copied line");
    assert!(error.problem.contains("signed another file"), "{error}");

    // An impostor's key under the trusted signer's name: valid, but not trusted.
    std::fs::remove_file(&sig).expect("removed");
    let impostor = SecretKey::from_seed([3; 32], "Team A");
    dictionary.sign(&impostor).expect("signs");
    let provenance = dictionary
        .provenance(Some(&keys))
        .expect("the signature holds");
    assert_eq!(provenance.signers[0].name, "Team A");
    assert_eq!(provenance.signers[0].trusted_as, None);
    let refusal = provenance.require_trusted(&path).expect_err("unknown key");
    assert!(refusal.problem.contains("not in trusted_keys"), "{refusal}");
}

fn stderr(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn the_command_line_signs_verifies_and_requires_signatures() {
    let dir = tempfile::tempdir().expect("temp dir");
    let prefix = dir.path().join("team-a");
    let prefix = prefix.to_str().expect("UTF-8");
    let keygen = common::run(&["keygen", "--name", "Team A", "-o", prefix]);
    assert!(keygen.status.success(), "{}", stderr(&keygen));
    let (secret, public) = (format!("{prefix}.key"), format!("{prefix}.pub"));
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&secret)
            .expect("key")
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o600, "the secret key is its owner's only");
    }
    let again = common::run(&["keygen", "--name", "Team A", "-o", prefix]);
    assert_eq!(
        again.status.code(),
        Some(2),
        "an existing key is never replaced"
    );

    let path = copy(dir.path(), BUNDLED, "shared.cdict");
    let dict = path.to_str().expect("UTF-8");
    let solve = |extra: &[&str]| {
        // The signature is what is tested: one motion test (the catalogue has no path for
        // this motion, and the default budget spends a minute finding so).
        let mut args = vec![
            "-q", "solve", "--dict", dict, MOTION, "--json", "--k-best", "1",
        ];
        args.extend_from_slice(extra);
        common::run(&args)
    };
    let required = ["--trusted-keys", public.as_str(), "--require-signature"];
    let refused = solve(&required);
    assert_eq!(refused.status.code(), Some(2));
    assert!(
        stderr(&refused).contains("unsigned"),
        "{}",
        stderr(&refused)
    );
    let no_keys = solve(&["--require-signature"]);
    assert_eq!(no_keys.status.code(), Some(2), "{}", stderr(&no_keys));

    let sign = common::run(&["sign", dict, "--key", &secret]);
    assert!(sign.status.success(), "{}", stderr(&sign));
    let verify = common::run(&["verify", dict, "--trusted-keys", &public]);
    let said = String::from_utf8_lossy(&verify.stdout);
    assert!(said.contains("signed by 'Team A'"), "{said}");
    // The verdict comes first: nothing a signer's name holds is printed before it.
    assert!(said.lines().any(|l| l.starts_with("trusted by ")), "{said}");

    let accepted = solve(&required);
    assert!(accepted.status.success(), "{}", stderr(&accepted));
    let json: serde_json::Value = serde_json::from_slice(&accepted.stdout).expect("JSON");
    let signer = &json["inputs"]["dictionary"]["provenance"]["signers"][0];
    assert_eq!(signer["trusted_as"], "Team A", "{signer}");
}

/// Names and fields with one reading: a signer name can only be letters, digits, spaces and
/// a little punctuation (no quote, semicolon, bracket or bidi control could print another
/// verdict), the verdict is printed before the names, a key file an editor began with a
/// byte-order mark reads, and a signature file holds one line per key with its length
/// written one way.
#[test]
fn names_and_fields_of_keys_and_signatures_have_one_reading() {
    for bad in [
        "Team A'; trusted by trusted; '",
        "QA (Munich)",
        "Eve\u{202e}reversed",
        "say \"hi\"",
    ] {
        let Err(refused) = SecretKey::generate(bad) else {
            panic!("{bad:?} accepted as a name")
        };
        assert!(
            refused.contains("a name is letters, digits, spaces"),
            "{refused}"
        );
    }
    SecretKey::generate("Équipe Zürich 4").expect("letters of any script");
    let a = team_a();
    let with_mark = format!("\u{feff}{}", a.public().to_line());
    let keys =
        TrustedKeys::parse(&with_mark, Path::new("trusted_keys")).expect("a BOM is no content");

    let dir = tempfile::tempdir().expect("temp dir");
    let path = copy(dir.path(), BUNDLED, "shared.cdict");
    let dictionary = Dictionary::open(&path).expect("opens");
    dictionary.sign(&a).expect("signs");
    let said = dictionary
        .provenance(Some(&keys))
        .expect("holds")
        .describe();
    assert!(
        said.starts_with("trusted by trusted_keys; signed by 'Team A'"),
        "{said}"
    );
    let sig = signature_path(&path);
    let genuine = std::fs::read_to_string(&sig).expect("the signature file");
    let line = (genuine.lines())
        .find(|l| l.starts_with("cable-dict-signature"))
        .expect("a signature line");

    std::fs::write(&sig, format!("{genuine}{line}\n")).expect("doubled");
    let error = dictionary
        .provenance(Some(&keys))
        .expect_err("one line per key");
    assert!(
        error
            .problem
            .contains("a second signature by the key of line"),
        "{error}"
    );

    let words: Vec<&str> = line.split_whitespace().collect();
    let length = words[6];
    for written in [format!("+{length}"), format!("0{length}")] {
        let edited = line.replacen(&format!(" {length} "), &format!(" {written} "), 1);
        std::fs::write(&sig, format!("{edited}\n")).expect("edited");
        let error = dictionary.provenance(Some(&keys)).expect_err(&written);
        assert!(
            error
                .problem
                .contains("is not a whole number as `sign` writes it"),
            "{error}"
        );
    }
}
