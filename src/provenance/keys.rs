//! Ed25519 keys as one-line text files: `TAG ed25519 HEX NAME`, where NAME is how the key's
//! owner calls itself (a team, a person). Text so that a public key can be pasted into a
//! mail or a repository and a trusted-keys file assembled with `cat`.

use super::{ProvenanceError, content_lines, hex, unhex};
use crate::input::{self, FileKind};
use ed25519_dalek::{Signature, Signer as _, SigningKey, VerifyingKey};
use std::path::{Path, PathBuf};

/// First word of a secret key line.
const SECRET_TAG: &str = "cable-dict-secret-key";
/// First word of a public key line.
const PUBLIC_TAG: &str = "cable-dict-public-key";
/// The only algorithm.
const ALGORITHM: &str = "ed25519";
/// Longest signer name (characters).
pub const MAX_NAME_CHARS: usize = 100;

/// Key files are one line; trusted-keys files a few hundred.
const KEY_FILE: FileKind = FileKind {
    what: "key file",
    limit_bytes: 1 << 20,
};

/// A signing key and the name it signs with. Kept in a file only its owner can read.
pub struct SecretKey {
    signing: SigningKey,
    name: String,
}

/// A public key and the name its owner gave it (or, in a trusted-keys file, the name the
/// team knows it by).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PublicKey {
    key: VerifyingKey,
    name: String,
}

/// The public keys a team accepts signatures from.
#[derive(Debug, Clone)]
pub struct TrustedKeys {
    file: PathBuf,
    keys: Vec<PublicKey>,
}

impl SecretKey {
    /// A new key from the operating system's random source.
    pub fn generate(name: &str) -> Result<SecretKey, String> {
        check_name(name)?;
        let mut seed = [0u8; 32];
        getrandom::fill(&mut seed).map_err(|e| format!("no random numbers for a key: {e}"))?;
        Ok(Self::from_seed(seed, name))
    }

    /// The key of a 32-byte seed (tests and reproducible examples only: a seed anyone knows
    /// signs for anyone).
    pub fn from_seed(seed: [u8; 32], name: &str) -> SecretKey {
        SecretKey {
            signing: SigningKey::from_bytes(&seed),
            name: name.to_string(),
        }
    }

    /// Reads a key written by [`SecretKey::to_text`]; on Unix the file must not be readable
    /// by others.
    pub fn read(path: &Path) -> Result<SecretKey, ProvenanceError> {
        check_private(path)?;
        let text = read(path)?;
        let mut lines = content_lines(&text);
        let Some((line, content)) = lines.next() else {
            return Err(ProvenanceError::new(path, None, "holds no key"));
        };
        if let Some((extra, _)) = lines.next() {
            return Err(ProvenanceError::new(
                path,
                Some(extra),
                "a second key; a secret key file holds one",
            ));
        }
        let (seed, name) = parse_line(content, SECRET_TAG)
            .map_err(|problem| ProvenanceError::new(path, Some(line), problem))?;
        Ok(Self::from_seed(seed, &name))
    }

    /// The file text: a comment and the key line.
    pub fn to_text(&self) -> String {
        format!(
            "# cable-dict secret key: it signs dictionaries as \"{}\". Keep it private.\n\
             {SECRET_TAG} {ALGORITHM} {} {}\n",
            self.name,
            hex(&self.signing.to_bytes()),
            self.name
        )
    }

    /// The public half, to hand to those who check the signatures.
    pub fn public(&self) -> PublicKey {
        PublicKey {
            key: self.signing.verifying_key(),
            name: self.name.clone(),
        }
    }

    /// The name it signs with.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The signature of `message`.
    pub(super) fn sign(&self, message: &[u8]) -> Signature {
        self.signing.sign(message)
    }
}

impl PublicKey {
    /// The key of 32 bytes, refused when they are not a usable Ed25519 point.
    pub(super) fn from_bytes(bytes: [u8; 32], name: String) -> Result<PublicKey, String> {
        let key = VerifyingKey::from_bytes(&bytes)
            .map_err(|_| "the public key is not a point of the Ed25519 curve".to_string())?;
        if key.is_weak() {
            return Err(
                "the public key is a weak (small-order) key that anyone can sign for; \
                        it is refused"
                    .into(),
            );
        }
        Ok(PublicKey { key, name })
    }

    /// The line of a public key file (and of a trusted-keys file).
    pub fn to_line(&self) -> String {
        format!("{PUBLIC_TAG} {ALGORITHM} {} {}\n", self.hex(), self.name)
    }

    /// Whether `other` is the same key, whatever either's name.
    pub fn same_key(&self, other: &PublicKey) -> bool {
        self.key == other.key
    }

    /// The key in full: 64 hexadecimal digits.
    pub fn hex(&self) -> String {
        hex(self.key.as_bytes())
    }

    /// A short form for messages: `ed25519:` and the first 16 hexadecimal digits.
    pub fn fingerprint(&self) -> String {
        format!("{ALGORITHM}:{}", &self.hex()[..16])
    }

    /// The name of the key's owner.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The Ed25519 key.
    pub(super) fn key(&self) -> &VerifyingKey {
        &self.key
    }
}

impl TrustedKeys {
    /// Reads a trusted-keys file: public key lines ([`PublicKey::to_line`]), blank lines and
    /// `#` comments; at least one key, each once.
    pub fn read(path: &Path) -> Result<TrustedKeys, ProvenanceError> {
        let text = read(path)?;
        Self::parse(&text, path)
    }

    /// [`TrustedKeys::read`] on text already read from `file`.
    pub fn parse(text: &str, file: &Path) -> Result<TrustedKeys, ProvenanceError> {
        let mut keys: Vec<(usize, PublicKey)> = Vec::new();
        for (line, content) in content_lines(text) {
            let at = |problem: String| ProvenanceError::new(file, Some(line), problem);
            if content.starts_with(SECRET_TAG) {
                return Err(at(
                    "a secret key; a trusted-keys file holds public keys (the \
                               .pub file keygen writes)"
                        .into(),
                ));
            }
            let (bytes, name) = parse_line(content, PUBLIC_TAG).map_err(at)?;
            let key = PublicKey::from_bytes(bytes, name).map_err(at)?;
            if let Some((first, _)) = keys.iter().find(|(_, k)| k.same_key(&key)) {
                return Err(at(format!("the key of line {first} again")));
            }
            keys.push((line, key));
        }
        if keys.is_empty() {
            return Err(ProvenanceError::new(
                file,
                None,
                "holds no public key: add the lines of the .pub files to trust",
            ));
        }
        Ok(TrustedKeys {
            file: file.to_path_buf(),
            keys: keys.into_iter().map(|(_, key)| key).collect(),
        })
    }

    /// The file the keys were read from.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The trusted key equal to `key`.
    pub fn find(&self, key: &PublicKey) -> Option<&PublicKey> {
        self.keys.iter().find(|k| k.key == key.key)
    }
}

/// `TAG ed25519 HEX NAME` → the 32 key bytes and the name.
fn parse_line(line: &str, tag: &str) -> Result<([u8; 32], String), String> {
    let (first, rest) = next_word(line);
    if first != tag {
        return Err(format!("starts with '{first}', not '{tag}'"));
    }
    let (algorithm, rest) = next_word(rest);
    if algorithm != ALGORITHM {
        return Err(format!(
            "the algorithm is '{algorithm}', not '{ALGORITHM}' (the only one)"
        ));
    }
    let (digits, name) = next_word(rest);
    let bytes = unhex::<32>(digits)
        .ok_or_else(|| format!("'{digits}' is not a key of 64 hexadecimal digits"))?;
    check_name(name)?;
    Ok((bytes, name.to_string()))
}

/// The first whitespace-separated word of `text` and the trimmed rest.
pub(super) fn next_word(text: &str) -> (&str, &str) {
    let text = text.trim_start();
    match text.split_once(char::is_whitespace) {
        Some((word, rest)) => (word, rest.trim()),
        None => (text, ""),
    }
}

/// Punctuation a signer name may hold besides letters, digits and spaces: nothing that
/// quotes, separates or brackets in a verdict (a name is printed inside one).
pub const NAME_PUNCTUATION: &str = "-_.,@+&/:#";

/// A signer name: 1 to [`MAX_NAME_CHARS`] characters, each a letter, a digit, a space or
/// one of [`NAME_PUNCTUATION`] — so that no name can print another verdict ("…; trusted by
/// …") or turn text around (bidi controls are not letters).
pub(super) fn check_name(name: &str) -> Result<(), String> {
    if name.trim().is_empty() {
        return Err("no name after the key (who signs with it)".into());
    }
    if name.chars().count() > MAX_NAME_CHARS {
        return Err(format!(
            "the name is longer than {MAX_NAME_CHARS} characters"
        ));
    }
    if let Some(c) =
        (name.chars()).find(|&c| !(c.is_alphanumeric() || c == ' ' || NAME_PUNCTUATION.contains(c)))
    {
        return Err(format!(
            "the name holds {:?} (U+{:04X}): a name is letters, digits, spaces and {NAME_PUNCTUATION}",
            c.escape_default().to_string(),
            u32::from(c)
        ));
    }
    Ok(())
}

fn read(path: &Path) -> Result<String, ProvenanceError> {
    input::read_text(path, KEY_FILE).map_err(|problem| ProvenanceError::new(path, None, problem))
}

/// A secret key others can read is no longer secret: refused, as ssh does.
#[cfg(unix)]
fn check_private(path: &Path) -> Result<(), ProvenanceError> {
    use std::os::unix::fs::PermissionsExt;
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(()); // reading it names the problem
    };
    let mode = meta.permissions().mode() & 0o777;
    if mode & 0o077 != 0 {
        return Err(ProvenanceError::new(
            path,
            None,
            format!(
                "the secret key is readable by others (mode {mode:03o}); restrict it with \
                 `chmod 600`, and make a new key if others may have copied it"
            ),
        ));
    }
    Ok(())
}

#[cfg(not(unix))]
fn check_private(_path: &Path) -> Result<(), ProvenanceError> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RFC 8032, section 7.1, test 1: the public key of this secret key.
    #[test]
    fn the_public_key_is_the_rfc_8032_one() {
        let seed = unhex::<32>("9d61b19deffd5a60ba844af492ec2cc44449c5697b326919703bac031cae7f60")
            .unwrap();
        let key = SecretKey::from_seed(seed, "RFC 8032");
        assert_eq!(
            key.public().hex(),
            "d75a980182b10ab7d54bfed3c964073a0ee172f3daa62325af021a68f707511a"
        );
        let signature = key.sign(b"");
        assert_eq!(
            hex(&signature.to_bytes()),
            "e5564300c360ac729086e2cc806e828a84877f1eb8e5d974d873e065224901555fb8821590a33bacc61e39701cf9b46bd25bf5f0595bbe24655141438e7a100b"
        );
    }

    #[test]
    fn key_lines_round_trip_and_name_what_is_wrong() {
        let key = SecretKey::from_seed([7; 32], "Team A, line 3");
        let trusted =
            TrustedKeys::parse(&key.public().to_line(), Path::new("keys")).expect("one key");
        assert_eq!(
            trusted.find(&key.public()).map(PublicKey::name),
            Some("Team A, line 3")
        );
        let wrong = |text: &str| TrustedKeys::parse(text, Path::new("keys")).unwrap_err();
        let line = key.public().to_line();
        assert!(wrong("").problem.contains("no public key"));
        assert!(
            wrong(&format!("{line}{line}"))
                .problem
                .contains("line 1 again")
        );
        assert_eq!(wrong(&format!("# c\n\n{line}{line}")).line, Some(4));
        assert!(wrong(&key.to_text()).problem.contains("secret key"));
        assert!(
            wrong(&line.replace("ed25519", "rsa"))
                .problem
                .contains("algorithm")
        );
        assert!(
            wrong(&line.replace("Team A, line 3", ""))
                .problem
                .contains("no name")
        );
        assert!(
            wrong(&line.replace(&key.public().hex(), "abc"))
                .problem
                .contains("64 hex")
        );
        let mut identity = [0u8; 32];
        identity[0] = 1;
        let weak = format!("{PUBLIC_TAG} {ALGORITHM} {} x\n", hex(&identity));
        assert!(wrong(&weak).problem.contains("weak"), "{}", wrong(&weak));
        let long = line.replace("Team A, line 3", &"n".repeat(MAX_NAME_CHARS + 1));
        assert!(wrong(&long).problem.contains("longer"));
        assert!(
            wrong(&line.replace("line 3", "\u{1b}[31m"))
                .problem
                .contains("a name is letters, digits, spaces")
        );
    }
}
