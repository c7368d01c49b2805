//! What a signature check found, kept apart from the cryptography so that a library built
//! without the `signatures` feature still reads and reports it: the signers of a dictionary,
//! whether a trusted key is among them, and where the signature file lies.

use super::ProvenanceError;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// One signer whose signature holds for the dictionary.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Signer {
    /// The name the signer gave its key: self-declared, only `trusted_as` is vouched for.
    pub name: String,
    /// The public key: `ed25519:` and 64 hexadecimal digits.
    pub key: String,
    /// The key's name in the trusted-keys file; `None` when the key is not in it (or no
    /// trusted keys were given).
    pub trusted_as: Option<String>,
}

/// Who signed a dictionary, and whether the signers are trusted.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize)]
pub struct Provenance {
    /// The signature file; `None`: the dictionary is unsigned.
    pub signature_file: Option<String>,
    /// Every signer, in the file's order (each signature verified).
    pub signers: Vec<Signer>,
    /// The trusted-keys file the signers were looked up in; `None`: not looked up.
    pub trusted_keys: Option<String>,
}

impl Provenance {
    /// True when at least one signature holds.
    pub fn is_signed(&self) -> bool {
        !self.signers.is_empty()
    }

    /// True when a signer's key is among the trusted keys.
    pub fn is_trusted(&self) -> bool {
        self.signers.iter().any(|s| s.trusted_as.is_some())
    }

    /// Refuses `dictionary` unless a trusted key signed it (`--require-signature`).
    pub fn require_trusted(&self, dictionary: &Path) -> Result<(), ProvenanceError> {
        if self.is_trusted() {
            return Ok(());
        }
        let keys = self
            .trusted_keys
            .as_deref()
            .unwrap_or("(no trusted keys given)");
        let problem = if self.is_signed() {
            format!(
                "signed only by keys that are not in {keys}: {}; add the signer's .pub line \
                 to the trusted keys if you trust it",
                self.signer_list()
            )
        } else {
            format!(
                "unsigned (no {}); a signature is required: have its builder run `cable-dict \
                 sign` with a key in {keys}",
                signature_path(dictionary).display()
            )
        };
        Err(ProvenanceError::new(dictionary, None, problem))
    }

    /// One sentence for people: unsigned, or who signed and whether they are trusted.
    pub fn describe(&self) -> String {
        if !self.is_signed() {
            return "unsigned: nothing says who built it (cable-dict sign; --require-signature \
                    refuses unsigned files)"
                .into();
        }
        // The verdict first: nothing a signer's name holds comes before it.
        let verdict = match (&self.trusted_keys, self.is_trusted()) {
            (None, _) => "not checked against trusted keys (--trusted-keys FILE)".to_string(),
            (Some(keys), true) => format!("trusted by {keys}"),
            (Some(keys), false) => format!("not trusted: no signer is in {keys}"),
        };
        format!("{verdict}; signed by {}", self.signer_list())
    }

    fn signer_list(&self) -> String {
        let one = |s: &Signer| {
            let short = &s.key[..s.key.len().min(24)];
            match &s.trusted_as {
                Some(known) if *known != s.name => {
                    format!("'{}' (key {short}…, trusted as '{known}')", s.name)
                }
                _ => format!("'{}' (key {short}…)", s.name),
            }
        };
        let list: Vec<String> = self.signers.iter().map(one).collect();
        list.join(", ")
    }
}

/// The signature file of `dictionary`: its path with `.sig` appended.
pub fn signature_path(dictionary: &Path) -> PathBuf {
    let mut name = dictionary.as_os_str().to_os_string();
    name.push(".sig");
    PathBuf::from(name)
}
