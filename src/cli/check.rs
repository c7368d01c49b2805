//! `cable-dict check`: an installed cable against motions, no search. Exit 0 when every
//! motion holds, 1 when one fails, 2 on invalid input: a gate for robot programs.

use super::output::{Failure, emit, print_json};
use super::result_file::ResultFile;
use cable_dict::motion::Cell;
use cable_dict::motion_test::EngineKind;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, check_mounting};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The mounting: a result JSON (`solve --json`, `solve -o`, a report's result.json); its
    /// path that passed is checked (else the closest miss), or --candidate.
    #[arg(value_name = "RESULT.json")]
    mounting: PathBuf,
    /// The motions to check it against: motion CSVs, or cell files naming them.
    #[arg(value_name = "MOTION.csv|CELL.toml", num_args = 1.., required = true)]
    motions: Vec<PathBuf>,
    /// The setup the mounting was designed with; default: the one the result names (as
    /// written, else beside the result). Its content must be the one solved (same hash).
    #[arg(long, value_name = "SETUP.toml")]
    setup: Option<PathBuf>,
    /// Check the result's candidate of this rank (1 = the shortest tried) instead.
    #[arg(long, value_name = "RANK")]
    candidate: Option<usize>,
    /// Print the verdicts as JSON (names as in the result JSON's `motions`).
    #[arg(long)]
    json: bool,
}

/// Runs `check`: `Ok` when every motion holds; a failing motion is exit code 1.
pub fn run(args: Args) -> Result<(), Failure> {
    let result = ResultFile::read(&args.mounting)?;
    let chosen = result.chosen(args.candidate)?;
    let setup_file = match &args.setup {
        Some(file) => file.clone(),
        None => result.setup_file()?,
    };
    let given = Setup::from_file(&setup_file).map_err(Failure::input)?;
    let setup = solved_setup(given, result.setup_hash(), &args.mounting)?;
    let cell = Cell::from_files(&setup.robot, &args.motions).map_err(Failure::input)?;
    let options = SolveOptions {
        engine: result.engine().unwrap_or(EngineKind::Implicit),
        ..SolveOptions::default()
    };
    let check = check_mounting(&setup, &chosen.path, &cell, &options).map_err(Failure::input)?;
    log::info!("{}", chosen.motion_test);
    if args.json {
        print_json(&check)?;
    } else {
        emit(&check.to_string())?;
    }
    match check.holds() {
        true => Ok(()),
        false => Err(Failure::unsolved(anyhow::anyhow!(
            "the mounting of {} fails a motion",
            args.mounting.display()
        ))),
    }
}

/// The setup the result's indices refer to: `given` itself, or with one clamp per link
/// (`solve --max-guides-per-link 1`), whichever has the content hash the result names.
fn solved_setup(
    given: Setup,
    hash: Option<&str>,
    result: &std::path::Path,
) -> Result<Setup, Failure> {
    let Some(hash) = hash else {
        return Ok(given);
    };
    if given.content_hash_hex() == hash {
        return Ok(given);
    }
    if let Ok(one_per_link) = given.inter_link_only()
        && one_per_link.content_hash_hex() == hash
    {
        return Ok(one_per_link);
    }
    Err(Failure::input(anyhow::anyhow!(
        "{} was solved with another setup (content hash {hash}); {} has hash {}: its clamp \
         places may differ, so the mounting cannot be read against it",
        result.display(),
        given.source.display(),
        given.content_hash_hex()
    )))
}
