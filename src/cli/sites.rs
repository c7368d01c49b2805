//! `cable-dict sites`: what a setup's search will try — every guide's candidate clamp
//! configurations (generated sites with their cable directions, or the written ones), the
//! number of candidate pieces per segment, and optionally a glTF scene of them all.

use super::output::{Failure, emit, print_json, write_glb};
use cable_dict::attachment::CostEstimate;
use cable_dict::report::text::catalogue_listing;
use cable_dict::report::views::sites_scene;
use cable_dict::setup::{Catalogue, Setup};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    setup: super::args::SetupArg,
    /// Also write a glTF scene: the robot at the installation pose (else all joints at 0)
    /// with a marker per candidate clamp configuration (+z along the cable).
    #[arg(long, value_name = "SCENE.glb")]
    gltf: Option<PathBuf>,
    /// Print every configuration, not only the sites.
    #[arg(long)]
    all: bool,
    /// Print JSON: every guide with its configurations and, for generated ones, every site
    /// (link, collider, position, surface point, normal, reference axis, directions; the
    /// format: docs/commands.md, "cable-dict sites").
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let path = args
        .setup
        .path()
        .map_err(|e| Failure::input(anyhow::anyhow!(e)))?;
    let setup = Setup::from_file(path).map_err(Failure::input)?;
    if let Some(output) = &args.gltf {
        let spec = sites_scene(&setup).map_err(Failure::input)?;
        write_glb(output, &spec)?;
    }
    if args.json {
        let too_many = cable_dict::attachment::check_size(&setup)
            .err()
            .map(|e| e.to_string());
        print_json(&Catalogue::of(&setup, too_many))
    } else {
        // Beyond what solve accepts, the listing says so and nothing is timed.
        let estimate = (cable_dict::attachment::check_size(&setup).is_ok())
            .then(|| CostEstimate::at_reference_pose(&setup))
            .flatten();
        emit(&catalogue_listing(&setup, args.all, estimate.as_ref()))
    }
}
