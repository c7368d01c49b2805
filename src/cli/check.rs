//! `cable-dict check`: an installed cable against motions, no search. Exit 0 when every
//! motion holds, 1 when one fails, 2 on invalid input: a gate for robot programs.

use super::args::non_negative;
use super::output::{Failure, emit, print_json};
use super::result_file::ResultFile;
use cable_dict::motion::{Cell, JointRanges};
use cable_dict::motion_test::EngineKind;
use cable_dict::mounting::MeasuredMounting;
use cable_dict::path::CablePath;
use cable_dict::setup::Setup;
use cable_dict::solve::{
    DEFAULT_GRID_STEP_DEG, SolveOptions, allowed_box, allowed_ranges, check_mounting, check_ranges,
};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The mounting: a result JSON (`solve --json`, `solve -o`, a report's result.json), its
    /// path that passed checked (else the closest miss, or --candidate); or a mounting file
    /// as the fitter measured the cable on the robot (`[[clamps]]` with link, place and mark;
    /// docs/commands.md, "check").
    #[arg(value_name = "RESULT.json|MOUNTING.toml")]
    mounting: PathBuf,
    /// The motions to check it against: motion CSVs, or cell files naming them.
    #[arg(value_name = "MOTION.csv|CELL.toml", num_args = 1.., required_unless_present = "ranges")]
    motions: Vec<PathBuf>,
    /// Check it over axis ranges (a ranges file as `solve --ranges` takes): each ranged axis
    /// end to end at its URDF speed, alone and together, and every piece at a grid of the
    /// box's poses (--grid-step-deg), solved one by one.
    #[arg(long, value_name = "RANGES.toml")]
    ranges: Option<PathBuf>,
    /// The step of --ranges' grid (degrees; millimetres for a prismatic joint). The default
    /// is a quarter of `solve --ranges`' step: an independent check of its answer.
    #[arg(long, value_name = "DEG", default_value_t = DEFAULT_GRID_STEP_DEG / 4.0, requires = "ranges")]
    grid_step_deg: f64,
    /// The setup the mounting was designed with; default: the one the result names (as
    /// written, else beside the result). Its content must be the one solved (same hash).
    #[arg(long, value_name = "SETUP.toml")]
    setup: Option<PathBuf>,
    /// Check the result's candidate of this rank (1 = the shortest tried) instead.
    #[arg(long, value_name = "RANK")]
    candidate: Option<usize>,
    /// A measured clamp is the setup's nearest clamp place on its link within this distance
    /// (mm: along, around as an arc, and off the link's line together).
    #[arg(long, value_name = "MM", default_value_t = 10.0)]
    tolerance_mm: f64,
    /// Also find the range each axis allows the mounting, the others anywhere in the box of
    /// --ranges, else in the motions' extremes: scanned outward on a grid this far apart
    /// (degrees; mm), each end found to 1° (docs/commands.md, "Allowed ranges").
    #[arg(long, value_name = "STEP_DEG", num_args = 0..=1, default_missing_value = "10")]
    allowed_ranges: Option<f64>,
    /// Print the verdicts as JSON (names as in the result JSON's `motions`).
    #[arg(long)]
    json: bool,
    /// How often each motion given runs per hour (a cell file's own `cycles_per_hour` comes
    /// first): the predicted life is then also given in hours and years (with a rated life
    /// or the conductors' offset in the cable file).
    #[arg(long, value_name = "N", value_parser = non_negative)]
    cycles_per_hour: Option<f64>,
}

/// Runs `check`: `Ok` when every motion holds; a failing motion is exit code 1.
pub fn run(args: Args) -> Result<(), Failure> {
    let (setup, path, read) = match MeasuredMounting::is_mounting_file(&args.mounting) {
        true => measured(&args)?,
        false => from_result(&args)?,
    };
    let given = (!args.motions.is_empty())
        .then(|| Cell::from_files(&setup.robot, &args.motions))
        .transpose()
        .map_err(Failure::input)?
        .map(|cell| cell.running(args.cycles_per_hour));
    let options = SolveOptions {
        engine: read.engine,
        ..SolveOptions::default()
    };
    let ranges = (args.ranges.as_ref())
        .map(|file| JointRanges::from_file(&setup.robot, file))
        .transpose()
        .map_err(Failure::input)?;
    let within = allowed_box(ranges.as_ref().map(|r| (r, false)), given.as_ref());
    let mut check = match (ranges, given) {
        (Some(ranges), given) => {
            let step = args.grid_step_deg;
            check_ranges(&setup, &path, &ranges, given, step, &options)
        }
        (None, Some(cell)) => check_mounting(&setup, &path, &cell, &options),
        (None, None) => return Err(Failure::input(anyhow::anyhow!("give the motions"))),
    }
    .map_err(Failure::input)?;
    if let (Some(step), Some((box_, words))) = (args.allowed_ranges, &within) {
        let allowed =
            allowed_ranges(&setup, &path, box_, words, step, &options).map_err(Failure::input)?;
        check.allowed_ranges = Some(allowed);
    }
    if args.json {
        print_json(&check)?;
    } else {
        emit(&(read.words + &check.to_string()))?;
    }
    match check.holds() {
        true => Ok(()),
        false => Err(Failure::unsolved(anyhow::anyhow!(
            "the mounting of {} fails a motion",
            args.mounting.display()
        ))),
    }
}

/// What the check says of how it read the mounting, and the engine to simulate with.
struct Read {
    words: String,
    engine: EngineKind,
}

/// The setup and path of a result JSON.
fn from_result(args: &Args) -> Result<(Setup, CablePath, Read), Failure> {
    let result = ResultFile::read(&args.mounting)?;
    let chosen = result.chosen(args.candidate)?;
    let setup_file = match &args.setup {
        Some(file) => file.clone(),
        None => result.setup_file()?,
    };
    let given = Setup::from_file(&setup_file).map_err(Failure::input)?;
    let setup = solved_setup(given, result.setup_hash(), &args.mounting)?;
    let read = Read {
        words: format!("{}: {}\n", args.mounting.display(), chosen.motion_test),
        engine: result.engine().unwrap_or(EngineKind::Implicit),
    };
    Ok((setup, chosen.path, read))
}

/// The setup and path of a mounting file, each clamp matched to the setup's places.
fn measured(args: &Args) -> Result<(Setup, CablePath, Read), Failure> {
    if args.candidate.is_some() {
        return Err(Failure::input(anyhow::anyhow!(
            "--candidate picks a path of a result JSON; {} is a mounting file",
            args.mounting.display()
        )));
    }
    if !(args.tolerance_mm.is_finite() && args.tolerance_mm >= 0.0) {
        return Err(Failure::input(anyhow::anyhow!(
            "--tolerance-mm {}: give a distance ≥ 0",
            args.tolerance_mm
        )));
    }
    let mounting = MeasuredMounting::from_file(&args.mounting).map_err(Failure::input)?;
    let setup_file = args
        .setup
        .clone()
        .or(mounting.setup.clone())
        .ok_or_else(|| {
            Failure::input(anyhow::anyhow!(
                "{}: it names no setup (`setup = …`): give it with --setup",
                args.mounting.display()
            ))
        })?;
    let setup = Setup::from_file(&setup_file).map_err(Failure::input)?;
    let (path, matched) = mounting
        .path(&setup, args.tolerance_mm)
        .map_err(Failure::input)?;
    let mut words = format!(
        "{} read against {}:\n",
        args.mounting.display(),
        setup_file.display()
    );
    for m in &matched {
        words.push_str(&format!(
            "  line {}: {} at `{}`, {:.1} mm from the place measured\n",
            m.line,
            m.guides.join(" = "),
            m.configuration,
            m.distance_mm
        ));
    }
    let read = Read {
        words,
        engine: EngineKind::Implicit,
    };
    Ok((setup, path, read))
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
