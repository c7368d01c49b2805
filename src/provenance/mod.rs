//! Who vouches for a dictionary: Ed25519 signatures kept beside it, checked against the keys
//! a team trusts (docs/architecture.md, "Provenance").
//!
//! A dictionary holds the results of hours of solving; whoever hands one over could have
//! written any margins into it. The certification of `solve --dict` re-solves every stored
//! piece an answer takes, so a forged file cannot make a path break a limit; a signature says
//! in addition who built the file, so that a forged one is refused before it is used and
//! cannot hide a shorter path.
//!
//! - [`SecretKey`], [`PublicKey`]: one-line text files written by `cable-dict keygen`.
//! - [`TrustedKeys`]: the public keys a team accepts, one per line (like `authorized_keys`).
//! - [`sign`], [`check`]: the signature file `DICT.cdict.sig`, one line per signer. A
//!   signature covers the SHA-512 of the whole dictionary and the signer's name; the
//!   dictionary's bytes stay what `build` and `merge` write, and several teams can sign one
//!   file.

//!
//! The keys and signatures need the `signatures` feature (ed25519-dalek, sha2, getrandom);
//! what a check found ([`Provenance`]) does not, so reports and dictionaries carry it in any
//! build.

#[cfg(feature = "signatures")]
mod keys;
mod record;
#[cfg(feature = "signatures")]
mod signature;

#[cfg(feature = "signatures")]
pub use keys::{MAX_NAME_CHARS, PublicKey, SecretKey, TrustedKeys};
pub use record::{Provenance, Signer, signature_path};
#[cfg(feature = "signatures")]
pub use signature::{MAX_SIGNATURES, SIGNATURE_FILE_LIMIT, check, check_text, sign};

use std::path::{Path, PathBuf};

/// A key, signature or trusted-keys file that cannot be used, or a signature that does not
/// hold: the file, the line when one is to blame, and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {problem}", file.display(), line.map(|l| format!(": line {l}")).unwrap_or_default())]
pub struct ProvenanceError {
    /// The file to blame.
    pub file: PathBuf,
    /// Its 1-based line, when one line is to blame.
    pub line: Option<usize>,
    /// What is wrong, and what to do.
    pub problem: String,
}

impl ProvenanceError {
    fn new(file: &Path, line: Option<usize>, problem: impl Into<String>) -> Self {
        ProvenanceError {
            file: file.to_path_buf(),
            line,
            problem: problem.into(),
        }
    }
}

#[cfg(feature = "signatures")]
/// Lower-case hexadecimal digits of `bytes`.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(feature = "signatures")]
/// The `N` bytes written as `2 N` hexadecimal digits in `text`; `None` for anything else.
fn unhex<const N: usize>(text: &str) -> Option<[u8; N]> {
    if text.len() != 2 * N || !text.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let mut out = [0u8; N];
    for (k, byte) in out.iter_mut().enumerate() {
        *byte = u8::from_str_radix(&text[2 * k..2 * k + 2], 16).ok()?;
    }
    Some(out)
}

#[cfg(feature = "signatures")]
/// The lines of a text file that carry content, numbered from 1: blank lines and `#` comments
/// are skipped, and a byte-order mark before the first.
fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    // A byte-order mark some editors write first is not content.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    text.lines()
        .enumerate()
        .map(|(i, line)| (i + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'))
}

#[cfg(feature = "signatures")]
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_round_trips_and_refuses_what_is_not_hex() {
        let bytes = [0u8, 1, 0xab, 0xff];
        assert_eq!(hex(&bytes), "0001abff");
        assert_eq!(unhex::<4>("0001abff"), Some(bytes));
        assert_eq!(unhex::<4>("0001ABFF"), Some(bytes));
        assert_eq!(unhex::<4>("0001abf"), None);
        assert_eq!(unhex::<4>("0001abfg"), None);
        assert_eq!(
            unhex::<2>("+1ab"),
            None,
            "from_str_radix accepts a sign; we do not"
        );
        assert_eq!(unhex::<2>("é1a"), None);
    }
}
