//! The `cable-dict` command line: a thin layer over the `cable_dict` library.

mod cli;

use clap::Parser;
use std::process::ExitCode;

/// Exit code of a run stopped by Ctrl-C (128 + SIGINT, as shells report it).
const INTERRUPTED: i32 = 130;

fn main() -> ExitCode {
    // Ctrl-C stops any stage at once; what it leaves is the old outputs, whole, and no
    // temporary file (outputs are only ever written through temporaries).
    let stop = ctrlc::set_handler(|| {
        cable_dict::atomic_file::remove_temporaries();
        eprintln!("\ninterrupted: no output written");
        std::process::exit(INTERRUPTED);
    });
    if let Err(e) = stop {
        eprintln!("warning: Ctrl-C will not remove temporary files: {e}");
    }
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            let message = format!("{:#}", failure.error);
            eprintln!("error: {}", cable_dict::escape::terminal(&message));
            ExitCode::from(failure.code)
        }
    }
}
