//! The signature file beside a dictionary, `DICT.cdict.sig`: one line per signer,
//! `cable-dict-signature v1 ed25519 KEY SIGNATURE FILE-SHA512 FILE-BYTES NAME`. Each signs a
//! short statement — the dictionary's length, its SHA-512 and the signer's name — so a line
//! copied to another file, or a name changed, no longer verifies.

use super::keys::{check_name, next_word};
use super::record::{Provenance, Signer, signature_path};
use super::{ProvenanceError, PublicKey, SecretKey, TrustedKeys, content_lines, hex, unhex};
use crate::atomic_file::write_atomically;
use crate::input::{self, FileKind};
use ed25519_dalek::Signature;
use sha2::{Digest, Sha512};
use std::path::Path;

/// First word of a signature line.
const TAG: &str = "cable-dict-signature";
/// Version of the signed statement.
const VERSION: &str = "v1";
/// Largest signature file read (bytes).
pub const SIGNATURE_FILE_LIMIT: u64 = 1 << 20;
/// Most signers of one dictionary.
pub const MAX_SIGNATURES: usize = 64;

const SIGNATURE_FILE: FileKind = FileKind {
    what: "signature file",
    limit_bytes: SIGNATURE_FILE_LIMIT,
};

/// Checks the signatures of the dictionary at `dictionary`, whose bytes are `bytes`: every
/// line of its signature file must sign exactly these bytes (a stale or forged line is an
/// error, not skipped); the signers are looked up in `trusted`. No signature file: unsigned.
pub fn check(
    dictionary: &Path,
    bytes: &[u8],
    trusted: Option<&TrustedKeys>,
) -> Result<Provenance, ProvenanceError> {
    let file = signature_path(dictionary);
    let trusted_keys = trusted.map(|t| t.file().display().to_string());
    let Some(lines) = read_lines(&file)? else {
        return Ok(Provenance {
            trusted_keys,
            ..Provenance::default()
        });
    };
    if lines.is_empty() {
        return Err(ProvenanceError::new(
            &file,
            None,
            "holds no signature: remove it, or sign the dictionary (cable-dict sign)",
        ));
    }
    let signed = Signed::of(bytes);
    let signers = lines
        .iter()
        .map(|(line, entry)| {
            entry
                .check(&signed, dictionary)
                .map_err(|problem| ProvenanceError::new(&file, Some(*line), problem))?;
            Ok(entry.signer(trusted))
        })
        .collect::<Result<Vec<_>, ProvenanceError>>()?;
    Ok(Provenance {
        signature_file: Some(file.display().to_string()),
        signers,
        trusted_keys,
    })
}

/// Signs the dictionary at `dictionary` (bytes `bytes`) with `key`: its line is added to the
/// signature file, or replaces the key's earlier line; the other signers' lines must still
/// hold. The file is replaced atomically.
pub fn sign(
    dictionary: &Path,
    bytes: &[u8],
    key: &SecretKey,
) -> Result<Provenance, ProvenanceError> {
    let file = signature_path(dictionary);
    let signed = Signed::of(bytes);
    let public = key.public();
    let mut lines: Vec<Entry> = Vec::new();
    for (line, entry) in read_lines(&file)?.unwrap_or_default() {
        entry.check(&signed, dictionary).map_err(|problem| {
            let advice = " — remove the signature file to sign the new dictionary afresh";
            ProvenanceError::new(&file, Some(line), problem + advice)
        })?;
        if entry.key.key() != public.key() {
            lines.push(entry);
        }
    }
    lines.push(Entry::new(key, &signed));
    if lines.len() > MAX_SIGNATURES {
        return Err(ProvenanceError::new(
            &file,
            None,
            format!("would hold more than {MAX_SIGNATURES} signatures"),
        ));
    }
    let mut text = "# cable-dict signatures of the dictionary beside this file, one line per \
                    signer (cable-dict verify --trusted-keys FILE checks them)\n"
        .to_string();
    for entry in &lines {
        text.push_str(&entry.to_line());
    }
    write_atomically(&file, text.as_bytes())
        .map_err(|e| ProvenanceError::new(&file, None, format!("cannot write: {e}")))?;
    // Every line was checked above or just signed: no second pass over the file.
    Ok(Provenance {
        signature_file: Some(file.display().to_string()),
        signers: lines.iter().map(|entry| entry.signer(None)).collect(),
        trusted_keys: None,
    })
}

/// What a signature covers: the dictionary's length and SHA-512.
#[derive(Clone, Copy)]
struct Signed {
    bytes: u64,
    sha512: [u8; 64],
}

impl Signed {
    fn of(bytes: &[u8]) -> Signed {
        Signed {
            bytes: bytes.len() as u64,
            sha512: Sha512::digest(bytes).into(),
        }
    }

    /// The statement a signer signs.
    fn statement(&self, signer: &str) -> Vec<u8> {
        format!(
            "cable-dict signature {VERSION}\nfile-bytes {}\nfile-sha512 {}\nsigner {signer}\n",
            self.bytes,
            hex(&self.sha512)
        )
        .into_bytes()
    }
}

/// One line of a signature file.
struct Entry {
    /// The signer's key, under the name it signed with.
    key: PublicKey,
    signature: Signature,
    signed: Signed,
}

impl Entry {
    fn new(key: &SecretKey, signed: &Signed) -> Entry {
        Entry {
            key: key.public(),
            signature: key.sign(&signed.statement(key.name())),
            signed: *signed,
        }
    }

    fn to_line(&self) -> String {
        format!(
            "{TAG} {VERSION} ed25519 {} {} {} {} {}\n",
            self.key.hex(),
            hex(&self.signature.to_bytes()),
            hex(&self.signed.sha512),
            self.signed.bytes,
            self.key.name()
        )
    }

    fn parse(line: &str) -> Result<Entry, String> {
        let (tag, rest) = next_word(line);
        let (version, rest) = next_word(rest);
        if tag != TAG || version != VERSION {
            return Err(format!(
                "starts with '{tag} {version}', not '{TAG} {VERSION}' (a signature file of a \
                 newer cable-dict, or not a signature file)"
            ));
        }
        let (algorithm, rest) = next_word(rest);
        if algorithm != "ed25519" {
            return Err(format!("the algorithm is '{algorithm}', not 'ed25519'"));
        }
        let (key, rest) = next_word(rest);
        let (signature, rest) = next_word(rest);
        let (sha512, rest) = next_word(rest);
        let (length, name) = next_word(rest);
        let digits = |what: &str, text: &str, n: usize| {
            format!("the {what} '{text}' is not {n} hexadecimal digits")
        };
        let key = unhex::<32>(key).ok_or_else(|| digits("key", key, 64))?;
        let signature =
            unhex::<64>(signature).ok_or_else(|| digits("signature", signature, 128))?;
        let sha512 = unhex::<64>(sha512).ok_or_else(|| digits("SHA-512", sha512, 128))?;
        // One way to write a length, as `sign` writes it: digits, no sign, no leading zero.
        let canonical = length.bytes().all(|b| b.is_ascii_digit())
            && (length == "0" || !length.starts_with('0'));
        let bytes = (length.parse::<u64>().ok())
            .filter(|_| canonical)
            .ok_or_else(|| {
                format!("the file length '{length}' is not a whole number as `sign` writes it")
            })?;
        check_name(name)?;
        Ok(Entry {
            key: PublicKey::from_bytes(key, name.to_string())?,
            signature: Signature::from_bytes(&signature),
            signed: Signed { bytes, sha512 },
        })
    }

    /// The line signs `signed` (the dictionary at `dictionary`) and its signature holds.
    fn check(&self, signed: &Signed, dictionary: &Path) -> Result<(), String> {
        if self.signed.bytes != signed.bytes || self.signed.sha512 != signed.sha512 {
            return Err(format!(
                "'{}' signed another file ({} bytes, SHA-512 {}…) than {} ({} bytes, SHA-512 \
                 {}…): the dictionary changed after it was signed",
                self.key.name(),
                self.signed.bytes,
                &hex(&self.signed.sha512)[..16],
                dictionary.display(),
                signed.bytes,
                &hex(&signed.sha512)[..16]
            ));
        }
        self.key
            .key()
            .verify_strict(&signed.statement(self.key.name()), &self.signature)
            .map_err(|_| {
                format!(
                    "the signature of '{}' (key {}) does not verify: the line was altered or \
                     forged",
                    self.key.name(),
                    self.key.fingerprint()
                )
            })
    }

    fn signer(&self, trusted: Option<&TrustedKeys>) -> Signer {
        Signer {
            name: self.key.name().to_string(),
            key: format!("ed25519:{}", self.key.hex()),
            trusted_as: trusted
                .and_then(|t| t.find(&self.key))
                .map(|k| k.name().to_string()),
        }
    }
}

/// The parsed lines of the signature file `file`, `None` when there is none.
fn read_lines(file: &Path) -> Result<Option<Vec<(usize, Entry)>>, ProvenanceError> {
    match std::fs::symlink_metadata(file) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        _ => {}
    }
    let text = input::read_text(file, SIGNATURE_FILE)
        .map_err(|problem| ProvenanceError::new(file, None, problem))?;
    let lines = parse_entries(&text)
        .map_err(|(line, problem)| ProvenanceError::new(file, Some(line), problem))?;
    Ok(Some(lines))
}

/// The signature lines of a signature file's text, numbered; the first bad line's number and
/// problem otherwise.
fn parse_entries(text: &str) -> Result<Vec<(usize, Entry)>, (usize, String)> {
    let mut lines: Vec<(usize, Entry)> = Vec::new();
    for (line, content) in content_lines(text) {
        if lines.len() == MAX_SIGNATURES {
            return Err((line, format!("more than {MAX_SIGNATURES} signatures")));
        }
        let entry = Entry::parse(content).map_err(|p| (line, p))?;
        // `sign` replaces a key's line: a key signing twice is a file put together by hand.
        if let Some((first, _)) = (lines.iter()).find(|(_, e)| e.key.same_key(&entry.key)) {
            return Err((
                line,
                format!("a second signature by the key of line {first}: one line per signer"),
            ));
        }
        lines.push((line, entry));
    }
    Ok(lines)
}

/// Parses `text` as a signature file and checks every line against `bytes`, as [`check`]
/// does, without the file system (for fuzzing).
pub fn check_text(text: &str, bytes: &[u8]) -> Result<usize, String> {
    let in_line = |(line, problem): (usize, String)| format!("line {line}: {problem}");
    let lines = parse_entries(text).map_err(in_line)?;
    let signed = Signed::of(bytes);
    for (line, entry) in &lines {
        entry
            .check(&signed, Path::new("the dictionary"))
            .map_err(|problem| in_line((*line, problem)))?;
    }
    Ok(lines.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fuzzing seed is a valid signature of the bytes `fuzz`, whose SHA-512 (Python's
    /// `hashlib`) it carries; one changed digit anywhere in the line makes it fail.
    #[test]
    fn the_fuzz_seed_signs_its_bytes_and_no_altered_copy_does() {
        let seed = include_str!("../../fuzz/seeds/check_signatures.sig");
        assert_eq!(check_text(seed, b"fuzz"), Ok(1));
        assert!(seed.contains(
            "2903a5143d708bd8b15a9bf4cbe448e856d543ca29241b8409917903eed365d58bd4130208d2b92a4\
             d27e32a267f95fd341f71dce6f2654b04ec6b20b1c952ef"
        ));
        assert!(check_text(seed, b"fuzz!").is_err());
        let line = seed.lines().nth(1).expect("the signature line");
        let start = line.find(" ed25519 ").expect("the key") + 9;
        for at in (start..line.len() - " 4 fuzz seed".len()).step_by(7) {
            let digit = line.as_bytes()[at];
            if !digit.is_ascii_hexdigit() {
                continue;
            }
            let other = if digit == b'0' { '1' } else { '0' };
            let altered = format!("{}{other}{}", &line[..at], &line[at + 1..]);
            assert!(
                check_text(&altered, b"fuzz").is_err(),
                "digit {at} altered passes"
            );
        }
    }
}
