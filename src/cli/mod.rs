//! Command-line interface: argument definitions and dispatch to one module per subcommand.

mod args;
mod calibrate;
mod check;
mod dictionary;
mod fk;
mod motion;
mod output;
mod progress_bars;
mod provenance;
mod result_file;
mod robot_info;
mod scene;
mod segment;
mod sites;
mod solve;

pub use output::Failure;

use clap::{Parser, Subcommand};

/// Finds the shortest safe external cable path for an industrial robot arm.
///
/// Units on the command line: millimetres and degrees. Exit codes: 0 success (`solve` also
/// when it finds no cable path: its status says so), 1 the input is valid but the command has
/// no answer (e.g. `segment` with a cable too short for its guides; `check` with a motion the
/// mounting fails), 2 invalid input.
#[derive(Debug, Parser)]
#[command(name = "cable-dict", version)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Stage logs on standard error: -v the stages and their timings, -vv details.
    #[arg(short, long, global = true, action = clap::ArgAction::Count)]
    verbose: u8,
    /// Nothing on standard error but errors: no progress bars, no logs.
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    quiet: bool,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List a robot's links, joints, limits and collision shapes.
    RobotInfo(robot_info::Args),
    /// Forward kinematics: the pose of every link for given joint angles.
    Fk(fk::Args),
    /// Shape and stress of one cable segment between two guide frames.
    Segment(Box<segment::Args>),
    /// Generate a sampled motion CSV from a waypoint file (trapezoidal or quintic moves).
    Motion(motion::Args),
    /// The poses of a motion at which each segment of a setup is tested.
    CriticalPoses(solve::CriticalArgs),
    /// The optimal cable path for a setup (or a dictionary) and a motion.
    Solve(Box<solve::Args>),
    /// Check an installed cable (a solve's result) against motions, no search: exit 0 when
    /// every motion holds, 1 when one fails, 2 on invalid input.
    Check(check::Args),
    /// Write a 3D scene (glTF .glb) of a cable path at a pose, or of one segment.
    ExportScene(scene::Args),
    /// List (or draw, glTF) the clamp sites and cable directions a setup's search will try.
    Sites(sites::Args),
    /// Precompute the cable pieces between a setup's clamp places on each link into a
    /// dictionary (or one shard of it).
    Build(dictionary::BuildArgs),
    /// Describe a dictionary: build parameters, setup, set sizes.
    Info(dictionary::InfoArgs),
    /// Check every checksum and record of a dictionary and that its header is what a build of
    /// its embedded setup writes; with --recompute, re-solve stored cable pieces and compare.
    Verify(dictionary::VerifyArgs),
    /// Merge the shards of a sharded build into one dictionary.
    Merge(dictionary::MergeArgs),
    /// Make an Ed25519 key pair to sign dictionaries with (PREFIX.key, PREFIX.pub).
    Keygen(provenance::KeygenArgs),
    /// Sign a dictionary: the signature goes to DICT.cdict.sig beside it.
    Sign(provenance::SignArgs),
    /// A cable file (EI, GJ) from bench measurements: the droop of a horizontal cantilever,
    /// a twist test or a stated GJ/EI.
    Calibrate(Box<calibrate::Args>),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> Result<(), Failure> {
    init_logging(cli.verbose, cli.quiet);
    progress_bars::install(cli.quiet);
    match cli.command {
        Command::RobotInfo(args) => robot_info::run(args),
        Command::Fk(args) => fk::run(args),
        Command::Segment(args) => segment::run(*args),
        Command::Motion(args) => motion::run(args),
        Command::CriticalPoses(args) => solve::run_critical(args),
        Command::Solve(args) => solve::run(*args, cli.verbose > 0),
        Command::Check(args) => check::run(args),
        Command::ExportScene(args) => scene::run(args),
        Command::Sites(args) => sites::run(args),
        Command::Build(args) => dictionary::run_build(args),
        Command::Info(args) => dictionary::run_info(args),
        Command::Verify(args) => dictionary::run_verify(args),
        Command::Merge(args) => dictionary::run_merge(args),
        Command::Keygen(args) => provenance::run_keygen(args),
        Command::Sign(args) => provenance::run_sign(args),
        Command::Calibrate(args) => calibrate::run(*args),
    }
}

/// Sends the library's `log` records to standard error: warnings by default, stage timings
/// (`info`) with `-v`, details (`debug`) with `-vv`, errors only with `--quiet`.
fn init_logging(verbose: u8, quiet: bool) {
    let level = match (quiet, verbose) {
        (true, _) => log::LevelFilter::Error,
        (false, 0) => log::LevelFilter::Warn,
        (false, 1) => log::LevelFilter::Info,
        (false, _) => log::LevelFilter::Debug,
    };
    let _ = env_logger::Builder::new()
        .filter_level(level)
        .format(|buf, record| {
            use std::io::Write;
            let message = record.args().to_string();
            writeln!(
                buf,
                "[{:<5}] {}",
                record.level(),
                cable_dict::escape::terminal(&message)
            )
        })
        .try_init();
}
