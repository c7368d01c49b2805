//! `cable-dict sites`: what a setup's search will try — every guide's candidate clamp
//! configurations (generated sites with their cable directions, or the written ones), the
//! number of candidate pieces per segment, and optionally a glTF scene of them all.

use super::{Failure, emit, print_json, write_glb};
use cable_dict::attachment::{ConnectMethod, CostEstimate, Evaluator, SegmentPoses};
use cable_dict::motion::Motion;
use cable_dict::report::scene::{GuideMark, PoseScene, SceneSpec};
use cable_dict::setup::{Catalogue, ConfigurationOrigin, Guide, Setup};
use nalgebra::Vector3;
use std::fmt::Write as _;
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
            tints: Vec::new(),
            installation: None,
        };
        write_glb(output, &spec)?;
    }
    if args.json {
        let too_many = cable_dict::attachment::check_size(&setup)
            .err()
            .map(|e| e.to_string());
        print_json(&Catalogue::of(&setup, too_many))
    } else {
        let mut out = listing(&setup, args.all);
        out.push_str(&cost_line(&setup));
        emit(&out)
    }
}

/// What testing every candidate piece costs on this machine, measured on a sample at the
/// installation pose (all joints at 0 without one); empty when that pose cannot be used.
fn cost_line(setup: &Setup) -> String {
    let joints = match &setup.installation {
        Some(installation) => installation.joints.clone(),
        None => vec![0.0; setup.robot.dof()],
    };
    let estimate = Motion::new(&setup.robot, vec![0.0, 1.0], vec![joints.clone(), joints])
        .ok()
        .and_then(|motion| SegmentPoses::new(setup, &motion).ok())
        .and_then(|poses| {
            let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).ok()?;
            Some(CostEstimate::measure(&evaluator, &poses))
        });
    let Some(estimate) = estimate else {
        return String::new();
    };
    format!(
        "\ntesting every candidate piece at one pose (the installation pose) takes {}; \
         `solve` tests only the pieces a chain shorter than the answer can use, and each motion \
         has its own test poses\n",
        estimate.describe(rayon::current_num_threads())
    )
}

/// A marker per configuration of every guide.
fn marks(setup: &Setup) -> Vec<GuideMark> {
    setup
        .guides
        .iter()
        .flat_map(|guide| {
            guide.configurations.iter().map(|c| GuideMark {
                name: format!("{} ({})", guide.name, c.name),
                clamp: guide.name.clone(),
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
            "  {:<6} {}→{}  {} lengths × {} × {} = {} ({} describe a real cable)",
            setup.segment_name(m),
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
        "\n{}{} on {link}: {} configuration{}{}{}",
        guide.name,
        if guide.optional {
            " (optional: the search may leave it out)"
        } else {
            ""
        },
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
