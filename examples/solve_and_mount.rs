//! Solves a setup for a motion with the library and prints where to mount each clamp.
//!
//! ```sh
//! cargo run --release --example solve_and_mount -- \
//!     robots/viper_s850/pick_and_place.toml motions/viper_s850/pick_and_place.csv
//! ```

use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve};
use std::error::Error;
use std::io::Write;

fn main() -> Result<(), Box<dyn Error>> {
    let mut out = std::io::stdout().lock();
    let mut args = std::env::args().skip(1);
    let (Some(setup_file), Some(motion_file)) = (args.next(), args.next()) else {
        return Err("usage: solve_and_mount SETUP.toml MOTION.csv".into());
    };
    let setup = Setup::from_file(&setup_file)?;
    let motion = Motion::from_csv_file(&setup.robot, &motion_file)?;
    let report = solve(&setup, &motion, &SolveOptions::default())?;
    let Some(plan) = report
        .mounting
        .as_ref()
        .filter(|_| report.status == Status::Solved)
    else {
        writeln!(
            out,
            "no cable path held every limit over the motion ({:?})",
            report.status
        )?;
        return Ok(());
    };
    writeln!(
        out,
        "{:.0} mm of cable between the first clamp and the last",
        plan.length_mm
    )?;
    for clamp in &plan.clamps {
        writeln!(
            out,
            "{} on {}, mark {:.0} mm",
            clamp.name(),
            clamp.link,
            clamp.mark_mm
        )?;
        if let Some(place) = &clamp.place {
            writeln!(out, "    {}", place.describe())?;
        }
    }
    Ok(())
}
