//! `cable-dict sites`: what a setup's search will try — every guide's candidate clamp
//! configurations (generated sites with their cable directions, or the written ones), the
//! number of candidate pieces per segment, and optionally a glTF scene of them all.

use super::scene::write_scene;
use super::{Failure, emit};
use cable_dict::report::scene::{GuideMark, PoseScene, SceneSpec};
use cable_dict::setup::{ConfigurationOrigin, Guide, Setup};
use nalgebra::Vector3;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The setup file.
    #[arg(value_name = "SETUP.toml")]
    setup: PathBuf,
    /// Also write a glTF scene: the robot at the installation pose (else all joints at 0)
    /// with a marker per candidate clamp configuration (+z along the cable).
    #[arg(long, value_name = "SCENE.glb")]
    gltf: Option<PathBuf>,
    /// Print every configuration, not only the sites.
    #[arg(long)]
    all: bool,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let setup = Setup::from_file(&args.setup).map_err(Failure::input)?;
    if let Some(output) = &args.gltf {
        let joints = match &setup.installation {
            Some(installation) => installation.joints.clone(),
            None => vec![0.0; setup.robot.dof()],
        };
        let link_poses = setup.robot.link_poses(&joints).map_err(Failure::input)?;
        let spec = SceneSpec {
            robot: &setup.robot,
            cable_radius_m: 0.5 * setup.cable.diameter_m,
            main: PoseScene {
                link_poses,
                cable: Vec::new(),
            },
            guides: marks(&setup),
            animation: None,
            snapshots: Vec::new(),
        };
        write_scene(output, &spec)?;
    }
    emit(&listing(&setup, args.all))
}

/// A marker per configuration of every guide.
fn marks(setup: &Setup) -> Vec<GuideMark> {
    setup
        .guides
        .iter()
        .flat_map(|guide| {
            guide.configurations.iter().map(|c| GuideMark {
                name: format!("{} ({})", guide.name, c.name),
                link: guide.link,
                pose_in_link: c.pose,
            })
        })
        .collect()
}

fn listing(setup: &Setup, all: bool) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "setup {}", setup.source.display());
    match &setup.installation {
        Some(installation) => {
            let joints: Vec<String> = installation
                .joints
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let (scale, unit) = setup.robot.actuated_joint(i).kind.display_unit();
                    format!("{:.1} {unit}", v * scale)
                })
                .collect();
            let _ = writeln!(
                out,
                "cable installed untwisted at [{}]: clamp twist references derived from the route",
                joints.join(", ")
            );
        }
        None => {
            let _ = writeln!(
                out,
                "clamp twist references: the configurations' written +x axes"
            );
        }
    }
    for guide in &setup.guides {
        guide_listing(&mut out, setup, guide, all);
    }
    let _ = writeln!(
        out,
        "\ncandidate pieces (length × start × end configuration)"
    );
    if let Err(too_many) = cable_dict::attachment::check_size(setup) {
        let _ = writeln!(out, "  too many for solve and build: {too_many}");
    }
    for m in 0..setup.segment_count() {
        let (a, b) = setup.segment_guides(m);
        let _ = writeln!(
            out,
            "  C{}  {}→{}  {} lengths × {} × {} = {} ({} describe a real cable)",
            m + 1,
            setup.guides[a].name,
            setup.guides[b].name,
            setup.segments[m].lengths.len(),
            setup.guides[a].configurations.len(),
            setup.guides[b].configurations.len(),
            setup.pv_count(m),
            setup.admissible_pv_count(m),
        );
    }
    out
}

fn guide_listing(out: &mut String, setup: &Setup, guide: &Guide, all: bool) {
    let link = &setup.robot.links[guide.link].name;
    let own = |c: &&cable_dict::setup::GuideConfiguration| {
        !matches!(c.origin, ConfigurationOrigin::Coincident { .. })
    };
    let copies = guide.configurations.len() - guide.configurations.iter().filter(own).count();
    let sites = site_count(guide);
    let _ = writeln!(
        out,
        "\n{} on {link}: {} configuration{}{}{}",
        guide.name,
        guide.configurations.len(),
        if guide.configurations.len() == 1 {
            ""
        } else {
            "s"
        },
        match sites {
            0 => String::new(),
            n => format!(" at {n} generated sites"),
        },
        match copies {
            0 => String::new(),
            n => format!(" ({n} shared with the neighbouring guide: one clamp for both)"),
        },
    );
    let mut last_site = None;
    for c in guide.configurations.iter().filter(own) {
        let site = match c.origin {
            ConfigurationOrigin::Generated { site, .. } => Some(site),
            _ => None,
        };
        if !all && site.is_some() && site == last_site {
            continue;
        }
        last_site = site;
        let normal = c.pose.rotation * Vector3::x();
        let along = c.pose.rotation * Vector3::z();
        let p = c.position_mm;
        let _ = match (site, all) {
            (Some(k), false) => writeln!(
                out,
                "  {:<10} at ({:7.1}, {:7.1}, {:7.1}) mm, surface normal ({:5.2}, {:5.2}, {:5.2})",
                format!("site {}", k + 1),
                p[0],
                p[1],
                p[2],
                normal.x,
                normal.y,
                normal.z
            ),
            _ => writeln!(
                out,
                "  {:<34} at ({:7.1}, {:7.1}, {:7.1}) mm, cable along ({:5.2}, {:5.2}, {:5.2})",
                c.name, p[0], p[1], p[2], along.x, along.y, along.z
            ),
        };
    }
}

/// Number of distinct generated sites of a guide.
fn site_count(guide: &Guide) -> usize {
    let mut sites: Vec<usize> = guide
        .configurations
        .iter()
        .filter_map(|c| match c.origin {
            ConfigurationOrigin::Generated { site, .. } => Some(site),
            _ => None,
        })
        .collect();
    sites.dedup();
    sites.len()
}
