//! `cable-dict sites`: what a setup's search will try — every guide's candidate clamp
//! configurations (generated sites with their cable directions, or the written ones), the
//! number of candidate pieces per segment, and optionally a glTF scene of them all.

use super::{Failure, emit, print_json, tidy, write_glb};
use cable_dict::attachment::{ConnectMethod, CostEstimate, Evaluator, SegmentPoses};
use cable_dict::motion::Motion;
use cable_dict::report::scene::{GuideMark, PoseScene, SceneSpec};
use cable_dict::setup::{ConfigurationOrigin, Guide, GuideConfiguration, Setup};
use cable_dict::sites::{GeneratedSites, Site, reference_axes};
use nalgebra::{Point3, Unit, Vector3};
use serde::Serialize;
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
        print_json(&report(&setup)?)
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

/// `cable-dict sites --json`.
#[derive(Serialize)]
struct SitesReport {
    setup: String,
    /// The installation pose as written (deg; mm for prismatic joints), if any.
    install_joints_deg: Option<Vec<f64>>,
    guides: Vec<GuideReport>,
    segments: Vec<SegmentReport>,
    /// Why `solve` and `build` would refuse the catalogue, if they would.
    too_many: Option<String>,
}

#[derive(Serialize)]
struct GuideReport {
    name: String,
    link: String,
    /// `sites`, `configurations` or `fixed`.
    kind: &'static str,
    /// The search may leave this clamp out.
    optional: bool,
    /// The axes directions are measured from (generated sites only).
    reference: Option<ReferenceReport>,
    /// Every configuration the search tries, in index order.
    configurations: Vec<ConfigurationReport>,
    /// Every generated site, in site order.
    sites: Vec<SiteReport>,
}

#[derive(Serialize)]
struct ReferenceReport {
    /// Unit, link frame.
    axis: [f64; 3],
    /// Used where the normal is within 17° of `axis`.
    second_axis: [f64; 3],
    /// `long axis`, `disc axis`, `link z` or `setup`.
    rule: &'static str,
}

#[derive(Serialize)]
struct ConfigurationReport {
    index: usize,
    name: String,
    position_mm: [f64; 3],
    rpy_deg: [f64; 3],
    /// The guide frame's +z (unit, link frame).
    cable_direction: [f64; 3],
    /// `declared`, `generated` or `coincident`.
    origin: &'static str,
    /// The generated site (0-based), for generated configurations.
    site: Option<usize>,
    /// `guide/configuration` a coincident copy copies.
    copy_of: Option<String>,
}

#[derive(Serialize)]
struct SiteReport {
    /// 0-based, as `site` in the configurations.
    site: usize,
    /// The link whose collider the site stands on (the guide's link or one fixed to it).
    link: String,
    /// 0-based index of the collider in that link's `<collision>` list.
    collider: usize,
    /// Where the cable axis runs (link frame).
    position_mm: [f64; 3],
    surface_point_mm: [f64; 3],
    /// Outward surface normal (unit).
    normal: [f64; 3],
    /// The axis direction 0° is measured from (unit, link frame).
    reference_axis: [f64; 3],
    directions: Vec<DirectionReport>,
}

#[derive(Serialize)]
struct DirectionReport {
    angle_deg: f64,
    /// The cable direction (unit, link frame).
    direction: [f64; 3],
    /// Index of its configuration in the guide's list.
    configuration: usize,
    name: String,
}

#[derive(Serialize)]
struct SegmentReport {
    /// `C2`, or `C2–C3` for a span where optional clamps are left out.
    name: String,
    from: String,
    to: String,
    /// A span over optional guides rather than a declared segment.
    span: bool,
    lengths: usize,
    candidate_pieces: u64,
    real_cable_pieces: u64,
}

fn report(setup: &Setup) -> Result<SitesReport, Failure> {
    let guides = setup
        .guides
        .iter()
        .map(|guide| guide_report(setup, guide, guide.generated.as_ref()))
        .collect();
    let segments = (0..setup.segment_count())
        .map(|m| {
            let (a, b) = setup.segment_guides(m);
            SegmentReport {
                name: setup.segment_name(m),
                from: setup.guides[a].name.clone(),
                to: setup.guides[b].name.clone(),
                span: m >= setup.declared_segments,
                lengths: setup.segments[m].lengths.len(),
                candidate_pieces: setup.pv_count(m) as u64,
                real_cable_pieces: setup.admissible_pv_count(m) as u64,
            }
        })
        .collect();
    Ok(SitesReport {
        setup: setup.source.display().to_string(),
        install_joints_deg: setup.installation.as_ref().map(|installation| {
            let robot = &setup.robot;
            (installation.joints.iter().enumerate())
                .map(|(i, v)| tidy(v * robot.actuated_joint(i).kind.display_unit().0))
                .collect()
        }),
        guides,
        segments,
        too_many: cable_dict::attachment::check_size(setup)
            .err()
            .map(|e| e.to_string()),
    })
}

fn guide_report(setup: &Setup, guide: &Guide, generated: Option<&GeneratedSites>) -> GuideReport {
    let configurations = guide
        .configurations
        .iter()
        .enumerate()
        .map(|(index, c)| configuration_report(setup, index, c))
        .collect();
    let (kind, reference, sites) = match generated {
        Some(generated) => {
            let axes = reference_axes(&setup.robot, guide.link, generated.spec.reference_axis);
            let reference = ReferenceReport {
                axis: unit(&axes.primary),
                second_axis: unit(&axes.second),
                rule: axes.rule.name(),
            };
            let directions = &generated.spec.directions_rad;
            let sites = (generated.sites.iter().enumerate())
                .map(|site| site_report(setup, guide, site, directions))
                .collect();
            ("sites", Some(reference), sites)
        }
        None if guide.fixed => ("fixed", None, Vec::new()),
        None => ("configurations", None, Vec::new()),
    };
    GuideReport {
        name: guide.name.clone(),
        link: setup.robot.links[guide.link].name.clone(),
        kind,
        optional: guide.optional,
        reference,
        configurations,
        sites,
    }
}

fn configuration_report(
    setup: &Setup,
    index: usize,
    c: &GuideConfiguration,
) -> ConfigurationReport {
    let (origin, site, copy_of) = match c.origin {
        ConfigurationOrigin::Declared { .. } => ("declared", None, None),
        ConfigurationOrigin::Generated { site, .. } => ("generated", Some(site), None),
        ConfigurationOrigin::Coincident {
            guide,
            configuration,
        } => {
            let original = &setup.guides[guide];
            let name = &original.configurations[configuration].name;
            (
                "coincident",
                None,
                Some(format!("{}/{name}", original.name)),
            )
        }
    };
    ConfigurationReport {
        index,
        name: c.name.clone(),
        position_mm: c.position_mm.map(tidy),
        rpy_deg: c.rpy_deg.map(tidy),
        cable_direction: vector(&(c.pose.rotation * Vector3::z())),
        origin,
        site,
        copy_of,
    }
}

fn site_report(
    setup: &Setup,
    guide: &Guide,
    (k, site): (usize, &Site),
    directions_rad: &[f64],
) -> SiteReport {
    let configurations = (guide.configurations.iter().enumerate()).filter(
        |(_, c)| matches!(c.origin, ConfigurationOrigin::Generated { site, .. } if site == k),
    );
    let directions = configurations
        .zip(directions_rad)
        .map(|((index, c), angle)| DirectionReport {
            angle_deg: tidy(angle.to_degrees()),
            direction: vector(&(c.pose.rotation * Vector3::z())),
            configuration: index,
            name: c.name.clone(),
        })
        .collect();
    SiteReport {
        site: k,
        link: setup.robot.links[site.link].name.clone(),
        collider: site.collider,
        position_mm: millimetres(&site.position),
        surface_point_mm: millimetres(&site.surface_point),
        normal: unit(&site.normal),
        reference_axis: unit(&site.reference_axis),
        directions,
    }
}

fn millimetres(p: &Point3<f64>) -> [f64; 3] {
    [p.x, p.y, p.z].map(|v| tidy(v * 1e3))
}

fn vector(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z].map(tidy)
}

fn unit(v: &Unit<Vector3<f64>>) -> [f64; 3] {
    vector(&v.into_inner())
}
