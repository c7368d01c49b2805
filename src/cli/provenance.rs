//! `cable-dict keygen` and `sign`, and the trust options of the commands that read
//! dictionaries (`--trusted-keys`, `--require-signature`).

use super::output::{Failure, emit};
use cable_dict::atomic_file::write_new;
use cable_dict::dictionary::Dictionary;
use cable_dict::provenance::{Provenance, SecretKey, TrustedKeys};
use std::path::{Path, PathBuf};

#[derive(Debug, clap::Args)]
pub struct KeygenArgs {
    /// Who signs with the key (a team or a person): shown with every signature it makes.
    #[arg(long)]
    name: String,
    /// Writes PREFIX.key (the secret key, readable by you only) and PREFIX.pub (the public
    /// key, for the trusted-keys files of those who use your dictionaries). Neither may exist.
    #[arg(short, long, value_name = "PREFIX")]
    output: PathBuf,
}

pub fn run_keygen(args: KeygenArgs) -> Result<(), Failure> {
    let key = SecretKey::generate(&args.name)
        .map_err(|e| Failure::input(anyhow::anyhow!("--name: {e}")))?;
    let secret = with_extension(&args.output, "key");
    let public = with_extension(&args.output, "pub");
    if public.exists() {
        return Err(Failure::input(anyhow::anyhow!(
            "{} exists; choose another --output or remove it",
            public.display()
        )));
    }
    write_new(&secret, key.to_text().as_bytes(), 0o600).map_err(|e| {
        Failure::input(anyhow::anyhow!(
            "cannot write the secret key {}: {e} (an existing key is never replaced)",
            secret.display()
        ))
    })?;
    write_new(&public, key.public().to_line().as_bytes(), 0o644)
        .map_err(|e| Failure::input(anyhow::anyhow!("cannot write {}: {e}", public.display())))?;
    emit(&format!(
        "wrote {} (secret: keep it, never share it) and {} (public key {}: give it to those \
         who use your dictionaries, for their --trusted-keys file)\n",
        secret.display(),
        public.display(),
        key.public().fingerprint()
    ))
}

/// `PREFIX.ext`, keeping any dots in PREFIX.
fn with_extension(prefix: &Path, extension: &str) -> PathBuf {
    let mut name = prefix.as_os_str().to_os_string();
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

#[derive(Debug, clap::Args)]
pub struct SignArgs {
    /// The dictionary (or shard) to sign: verified first; it is not changed, the signature
    /// goes to DICT.cdict.sig beside it (other signers' lines are kept).
    dict: PathBuf,
    /// The secret key (cable-dict keygen).
    #[arg(long, value_name = "KEY.key")]
    key: PathBuf,
}

pub fn run_sign(args: SignArgs) -> Result<(), Failure> {
    let key = SecretKey::read(&args.key).map_err(Failure::input)?;
    let dictionary = open_verified(&args.dict)?;
    let provenance = dictionary.sign(&key).map_err(Failure::input)?;
    emit(&format!(
        "{}: {} ({})\n",
        args.dict.display(),
        provenance.describe(),
        provenance.signature_file.unwrap_or_default()
    ))
}

/// Which signers a command accepts.
#[derive(Debug, clap::Args)]
pub struct Trust {
    /// The public keys whose signatures you accept: the lines of the .pub files of
    /// cable-dict keygen, one per line. The dictionary's signers are looked up in it.
    #[arg(long, value_name = "FILE")]
    trusted_keys: Option<PathBuf>,
    /// Refuse a dictionary that a key in --trusted-keys has not signed.
    #[arg(long, requires = "trusted_keys")]
    require_signature: bool,
}

impl Trust {
    /// True when a trust option is on the command line.
    pub fn is_given(&self) -> bool {
        self.trusted_keys.is_some() || self.require_signature
    }

    /// The provenance of `dictionary`: every signature beside it must hold; with
    /// `--require-signature`, a trusted key must have signed it.
    pub fn check(&self, dictionary: &Dictionary) -> Result<Provenance, Failure> {
        check(
            dictionary,
            self.trusted_keys.as_deref(),
            self.require_signature,
        )
    }
}

/// [`Trust::check`] with the keys file and the requirement given separately (`merge` and
/// `info` have their own flags).
pub fn check(
    dictionary: &Dictionary,
    trusted_keys: Option<&Path>,
    require: bool,
) -> Result<Provenance, Failure> {
    let trusted = trusted_keys
        .map(TrustedKeys::read)
        .transpose()
        .map_err(Failure::input)?;
    let provenance = dictionary
        .provenance(trusted.as_ref())
        .map_err(Failure::input)?;
    if require {
        provenance
            .require_trusted(dictionary.path())
            .map_err(Failure::input)?;
    }
    Ok(provenance)
}

/// Reads a dictionary into memory and checks every byte of it (milliseconds for the bundled
/// ones): a damaged file is refused before it can decide anything, and the bytes checked —
/// its signatures too — are the bytes the run reads, whatever happens to the file meanwhile.
pub(super) fn open_verified(path: &Path) -> Result<Dictionary, Failure> {
    let dictionary = Dictionary::read(path).map_err(Failure::input)?;
    dictionary.verify().map_err(Failure::input)?;
    Ok(dictionary)
}
