//! `cable-dict build`, `info`, `verify` and `merge`: dictionaries from the command line.

use super::output::{Failure, emit, print_json};
use super::provenance;
use super::provenance::open_verified;
use cable_dict::dictionary::{
    BuildOptions, DEFAULT_DIRECTION_COUNT, Dictionary, Info, RECOMPUTE_TOLERANCE_UNITS,
    RecomputeChoice, UNDECIDED_SAMPLE_DIRECTIONS, build, merge, merge_signed_by, write_dictionary,
};
use cable_dict::provenance::TrustedKeys;
use cable_dict::setup::Setup;
use cable_dict::text_table::{Align, TextTable};
use std::collections::hash_map::RandomState;
use std::fmt::Write as _;
use std::hash::{BuildHasher, Hasher};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub struct BuildArgs {
    /// The setup whose clamp places to store: every pair of places on each link with two or
    /// more (from all its guides on that link), at its intra-link segments' lengths.
    #[command(flatten)]
    setup: super::args::SetupArg,
    /// The dictionary (or shard) to write; replaced atomically.
    #[arg(short, long, value_name = "DICT.cdict")]
    output: PathBuf,
    /// Gravity directions sampled on the sphere (docs/dictionaries.md, "Direction count": why
    /// 32).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_DIRECTION_COUNT)]
    directions: usize,
    /// Worker threads (default: one per core). The bytes do not depend on it.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Build only shard i of n (0-based, e.g. 0/4 … 3/4), for `cable-dict merge`.
    #[arg(long, value_name = "i/n", value_parser = shard_arg)]
    shard: Option<(u32, u32)>,
}

/// Parses `i/n`.
fn shard_arg(text: &str) -> Result<(u32, u32), String> {
    let (i, n) = text
        .split_once('/')
        .ok_or_else(|| format!("'{text}' is not i/n (e.g. 0/4)"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| format!("'{s}' in '{text}' is not a whole number"))
    };
    let (i, n) = (parse(i)?, parse(n)?);
    if n == 0 || i >= n {
        return Err(format!(
            "shard {i}/{n}: the index counts from 0 to n − 1 and n is at least 1"
        ));
    }
    Ok((i, n))
}

pub fn run_build(args: BuildArgs) -> Result<(), Failure> {
    let path = args
        .setup
        .path()
        .map_err(|e| Failure::input(anyhow::anyhow!(e)))?;
    let setup = Setup::from_file(path).map_err(Failure::input)?;
    let options = BuildOptions {
        directions: args.directions,
        shard: args.shard,
    };
    let clock = Instant::now();
    let built = match args.threads {
        None => build(&setup, &options),
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Failure::input(anyhow::anyhow!("--threads {threads}: {e}")))?
            .install(|| build(&setup, &options)),
    }
    .map_err(|problem| Failure::input(anyhow::anyhow!("{}: {problem}", path.display())))?;
    write_dictionary(&args.output, &built).map_err(Failure::input)?;
    let mut text = format!(
        "wrote {}: {} cable pieces × {} gravity directions in {:.1} s",
        args.output.display(),
        built.pvs.len(),
        built.directions.len(),
        clock.elapsed().as_secs_f64()
    );
    if let Some(shard) = built.header.shard {
        let _ = write!(
            text,
            " (shard {}/{}: pieces {} to {} of {})",
            shard.index, shard.count, shard.first_pv, shard.end_pv, built.header.pv_total
        );
    }
    for e in &built.header.links {
        let _ = write!(
            text,
            "; {} ({} clamp places): {} pieces hold the limits at every direction, {} robust",
            e.link,
            e.clamps.len(),
            e.d1_all,
            e.d2_all
        );
    }
    emit(&(text + "\n"))
}

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// The dictionary.
    dict: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Look the signers up in these public keys (see `verify`).
    #[arg(long, value_name = "FILE")]
    trusted_keys: Option<PathBuf>,
}

pub fn run_info(args: InfoArgs) -> Result<(), Failure> {
    let dictionary = Dictionary::open(&args.dict).map_err(Failure::input)?;
    let mut info = Info::of(&dictionary);
    // A signature that does not hold is shown, not an error: `info` describes what is there.
    match provenance::check(&dictionary, args.trusted_keys.as_deref(), false) {
        Ok(provenance) => info.provenance = Some(provenance),
        Err(failure) => info.signature_problem = Some(format!("{:#}", failure.error)),
    }
    if args.json {
        return print_json(&info);
    }
    emit(&describe(&info))
}

fn describe(info: &Info) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{}: cable-dict dictionary, format v{}, physics v{}, {} bytes{}",
        info.file,
        info.format_version,
        info.physics_version,
        info.file_bytes,
        info.shard
            .as_ref()
            .map(|s| format!(", shard {s} ({} of {} PVs)", info.pv_records, info.pv_total))
            .unwrap_or_default()
    );
    if let Some(provenance) = &info.provenance {
        let _ = writeln!(text, "{}", provenance.describe());
    }
    if let Some(problem) = &info.signature_problem {
        let _ = writeln!(text, "the signature does not hold: {problem}");
    }
    let _ = writeln!(
        text,
        "setup {} (hash {}): robot {}, cable {}",
        info.setup_file, info.setup_hash, info.robot, info.cable
    );
    let _ = writeln!(
        text,
        "{} gravity directions ({}, at most {:.2}° from any direction); {}",
        info.directions, info.direction_method, info.covering_radius_deg, info.solver
    );
    if info.mesh_files > 0 {
        let _ = writeln!(
            text,
            "{} mesh files embedded with the URDF",
            info.mesh_files
        );
    }
    let _ = write!(text, "\n{}", link_table(info));
    let _ = writeln!(
        text,
        "\nhold, robust: pieces that hold the limits (D1), and robustly (D2), at every stored \
         direction. error factor: the piece's largest interpolation error per unit of \
         neighbour spread × 1.5, measured leaving each direction out and at {} probe \
         directions. undecided: lookups of candidate pieces the margins cannot decide, solved \
         exactly instead (over {UNDECIDED_SAMPLE_DIRECTIONS} gravity directions spread over \
         the sphere).",
        info.probes
    );
    text
}

/// One row per link's clamp catalogue, columns as wide as their cells.
fn link_table(info: &Info) -> TextTable {
    use Align::{Left, Right};
    let mut table = TextTable::new(
        2,
        &[
            ("link", Left),
            ("clamp places", Right),
            ("lengths (S)", Right),
            ("pieces", Right),
            ("candidates", Right),
            ("hold", Right),
            ("robust", Right),
            ("error factor", Right),
            ("undecided", Right),
        ],
    );
    for s in &info.links {
        // One factor per piece serves all three margins (a branch change moves the whole shape).
        table.row(vec![
            s.link.clone(),
            s.clamps.to_string(),
            format!("{} to {} ({})", s.lengths[0], s.lengths[1], s.length_count),
            s.pvs.to_string(),
            s.candidates.to_string(),
            s.d1_all.to_string(),
            s.d2_all.to_string(),
            format!("{:.3}", s.margin_error[0]),
            s.undecided_share
                .map_or("-".to_string(), |u| format!("{:.1} %", 100.0 * u)),
        ]);
    }
    table
}

#[derive(Debug, clap::Args)]
pub struct VerifyArgs {
    /// The dictionary (or shard).
    dict: PathBuf,
    /// Also re-solve this many stored cable pieces, drawn at random, from the embedded setup
    /// and compare them with the file ("all": every piece, as long as the build). Run it on
    /// a dictionary from another team, machine or cable-dict version.
    #[arg(long, value_name = "N|all", value_parser = recompute_arg)]
    recompute: Option<Recount>,
    /// Seed of the random draw (default: a fresh one, printed so the draw can be repeated).
    #[arg(long, requires = "recompute")]
    seed: Option<u64>,
    #[command(flatten)]
    trust: provenance::Trust,
}

/// `--recompute N` or `--recompute all`.
#[derive(Debug, Clone, Copy)]
enum Recount {
    Some(usize),
    All,
}

fn recompute_arg(text: &str) -> Result<Recount, String> {
    match text {
        "all" => Ok(Recount::All),
        n => n
            .parse::<usize>()
            .ok()
            .filter(|&n| n > 0)
            .map(Recount::Some)
            .ok_or_else(|| format!("`{n}`: give a number of pieces (≥ 1) or `all`")),
    }
}

pub fn run_verify(args: VerifyArgs) -> Result<(), Failure> {
    let dictionary = open_verified(&args.dict)?;
    let provenance = args.trust.check(&dictionary)?;
    let mut out = format!(
        "{}: ok ({} bytes; every section checksum and {} piece records × {} directions verified; \
         the header is what a build of the embedded setup writes)\n{}\n",
        args.dict.display(),
        dictionary.file_len(),
        dictionary.pv_records().len(),
        dictionary.directions().len(),
        provenance.describe()
    );
    if let Some(recount) = args.recompute {
        let seed = args
            .seed
            .unwrap_or_else(|| RandomState::new().build_hasher().finish());
        let choice = match recount {
            Recount::All => RecomputeChoice::All,
            Recount::Some(count) => RecomputeChoice::Random { count, seed },
        };
        let recomputed = dictionary.recompute(choice).map_err(Failure::input)?;
        let drawn = match recount {
            Recount::All => "every piece".to_string(),
            Recount::Some(_) => format!("drawn with --seed {seed}"),
        };
        if let Some(disagreement) = recomputed.disagreement {
            return Err(Failure::input(anyhow::anyhow!(
                "{}: a stored cable piece is not what the embedded setup gives (forged, stale \
                 or computed differently): {disagreement}; re-solved {} of the {} measured \
                 pieces, {drawn}",
                args.dict.display(),
                recomputed.checked,
                recomputed.measured
            )));
        }
        out.push_str(&format!(
            "re-solved {} of the {} measured cable pieces ({drawn}; the other records are \
             zero-length, not admissible or too short to solve): all agree with the file \
             within {RECOMPUTE_TOLERANCE_UNITS} stored unit\n",
            recomputed.checked, recomputed.measured
        ));
    }
    emit(&out)
}

#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The shards, in any order (cable-dict build --shard i/n).
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// The whole dictionary to write; replaced atomically.
    #[arg(short, long, value_name = "DICT.cdict")]
    output: PathBuf,
    /// Public keys whose signatures you accept (see `verify`).
    #[arg(long, value_name = "FILE", requires = "require_signatures")]
    trusted_keys: Option<PathBuf>,
    /// Refuse shards that a key in --trusted-keys has not signed (each shard's signature
    /// must hold). The merged file is unsigned: sign it in turn.
    #[arg(long, requires = "trusted_keys")]
    require_signatures: bool,
}

pub fn run_merge(args: MergeArgs) -> Result<(), Failure> {
    let trusted = args
        .trusted_keys
        .as_deref()
        .map(TrustedKeys::read)
        .transpose()
        .map_err(Failure::input)?;
    let built = match &trusted {
        Some(trusted) => merge_signed_by(&args.shards, trusted),
        None => merge(&args.shards),
    }
    .map_err(Failure::input)?;
    write_dictionary(&args.output, &built).map_err(Failure::input)?;
    emit(&format!(
        "wrote {}: {} shards merged, {} cable pieces × {} gravity directions\n",
        args.output.display(),
        args.shards.len(),
        built.pvs.len(),
        built.directions.len()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use cable_dict::dictionary::LinkInfo;

    fn link(name: &str, clamps: usize) -> LinkInfo {
        LinkInfo {
            link: name.into(),
            lengths: [0, 37],
            length_count: 38,
            clamps,
            pvs: 38 * (clamps * clamps) as u64,
            candidates: 12_345,
            d1_all: 7,
            d2_all: 0,
            margin_error: [15.9375; 4],
            undecided_share: Some(0.017),
        }
    }

    /// Long vendor link names do not shift the columns after them: every right-aligned
    /// column ends at the same character in every line, the title's included.
    #[test]
    fn the_link_table_keeps_its_columns_with_long_names() {
        let info = Info {
            file: "x.cdict".into(),
            file_bytes: 0,
            format_version: 3,
            physics_version: 6,
            setup_file: "s.toml".into(),
            setup_hash: "0".into(),
            robot: "r".into(),
            cable: "c".into(),
            directions: 32,
            direction_method: "fibonacci".into(),
            probes: 16,
            covering_radius_deg: 20.0,
            solver: "hermite".into(),
            shard: None,
            pv_total: 0,
            pv_records: 0,
            mesh_files: 0,
            links: vec![link("l3", 7), link("kr6r900sixx_link_4_with_flange", 123)],
            provenance: None,
            signature_problem: None,
        };
        let text = link_table(&info).to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        let ends = |line: &str, cell: &str| line.find(cell).map(|at| at + cell.len());
        let title_end = ends(lines[0], "clamp places").expect("title");
        assert_eq!(ends(lines[1], " 7 "), Some(title_end + 1), "{text}");
        assert_eq!(ends(lines[2], " 123 "), Some(title_end + 1), "{text}");
        let undecided = ends(lines[0], "undecided").expect("title");
        assert!(
            lines[1..]
                .iter()
                .all(|l| l.ends_with("1.7 %") && l.len() == undecided)
        );
    }
}
