//! What a setup's search will try, as data: every guide with its configurations and
//! generated sites, every segment with its candidate counts (`cable-dict sites --json`; the
//! format: docs/commands.md, "cable-dict sites").

use super::{ConfigurationOrigin, Guide, GuideConfiguration, Setup};
use crate::json::tidy;
use crate::sites::{GeneratedSites, Site, reference_axes};
use nalgebra::{Point3, Unit, Vector3};
use serde::Serialize;

/// What a setup's search will try (`cable-dict sites --json`): every guide with its clamp
/// configurations and, for generated ones, every site; every segment's candidate counts.
#[derive(Serialize)]
pub struct Catalogue {
    /// The setup file as given.
    pub setup: String,
    /// The installation pose as written (deg; mm for prismatic joints), if any.
    pub install_joints_deg: Option<Vec<f64>>,
    /// Every guide, in the setup's order.
    pub guides: Vec<GuideEntry>,
    /// Every segment, spans included.
    pub segments: Vec<SegmentEntry>,
    /// Why `solve` and `build` would refuse the catalogue, if they would.
    pub too_many: Option<String>,
}

/// One guide: its link, kind, and every configuration (and site) the search tries.
#[derive(Serialize)]
pub struct GuideEntry {
    /// Its name.
    pub name: String,
    /// The link it is mounted on.
    pub link: String,
    /// `sites`, `configurations` or `fixed`.
    pub kind: &'static str,
    /// The search may leave this clamp out.
    pub optional: bool,
    /// The axes directions are measured from (generated sites only).
    pub reference: Option<ReferenceAxes>,
    /// Every configuration the search tries, in index order.
    pub configurations: Vec<ConfigurationEntry>,
    /// Every generated site, in site order.
    pub sites: Vec<SiteEntry>,
}

/// The axes a generator measures cable directions from.
#[derive(Serialize)]
pub struct ReferenceAxes {
    /// Unit, link frame.
    pub axis: [f64; 3],
    /// Used where the normal is within 17° of `axis`.
    pub second_axis: [f64; 3],
    /// `long axis`, `disc axis`, `link z` or `setup`.
    pub rule: &'static str,
}

/// One clamp configuration a guide offers.
#[derive(Serialize)]
pub struct ConfigurationEntry {
    /// Its index in the guide's list.
    pub index: usize,
    /// Its name.
    pub name: String,
    /// Where the cable's axis runs (link frame).
    pub position_mm: [f64; 3],
    /// The frame's orientation (URDF roll, pitch, yaw).
    pub rpy_deg: [f64; 3],
    /// The guide frame's +z (unit, link frame).
    pub cable_direction: [f64; 3],
    /// `declared`, `generated` or `coincident`.
    pub origin: &'static str,
    /// The generated site (0-based), for generated configurations.
    pub site: Option<usize>,
    /// `guide/configuration` a coincident copy copies.
    pub copy_of: Option<String>,
}

/// One generated site: where on which collider, and its cable directions.
#[derive(Serialize)]
pub struct SiteEntry {
    /// 0-based, as `site` in the configurations.
    pub site: usize,
    /// The link whose collider the site stands on (the guide's link or one fixed to it).
    pub link: String,
    /// 0-based index of the collider in that link's `<collision>` list.
    pub collider: usize,
    /// Where the cable axis runs (link frame).
    pub position_mm: [f64; 3],
    /// The nearest point of the surface (link frame).
    pub surface_point_mm: [f64; 3],
    /// Outward surface normal (unit).
    pub normal: [f64; 3],
    /// The axis direction 0° is measured from (unit, link frame).
    pub reference_axis: [f64; 3],
    /// The cable directions tried at this site.
    pub directions: Vec<DirectionEntry>,
}

/// One cable direction at a site.
#[derive(Serialize)]
pub struct DirectionEntry {
    /// Its angle from the reference axis around the normal.
    pub angle_deg: f64,
    /// The cable direction (unit, link frame).
    pub direction: [f64; 3],
    /// Index of its configuration in the guide's list.
    pub configuration: usize,
    /// Its name.
    pub name: String,
}

/// One segment (or span) and its candidate counts.
#[derive(Serialize)]
pub struct SegmentEntry {
    /// `C2`, or `C2–C3` for a span where optional clamps are left out.
    pub name: String,
    /// The guide it starts at.
    pub from: String,
    /// The guide it ends at.
    pub to: String,
    /// A span over optional guides rather than a declared segment.
    pub span: bool,
    /// Candidate lengths.
    pub lengths: usize,
    /// Candidate pieces (lengths × configuration pairs).
    pub candidate_pieces: u64,
    /// Those a real cable can make (admissible).
    pub real_cable_pieces: u64,
}

impl Catalogue {
    /// The catalogue of `setup`, with `too_many` (why `solve` and `build` would refuse it)
    /// as the caller's size check says.
    pub fn of(setup: &Setup, too_many: Option<String>) -> Catalogue {
        let guides = setup
            .guides
            .iter()
            .map(|guide| guide_report(setup, guide, guide.generated.as_ref()))
            .collect();
        let segments = (0..setup.segment_count())
            .map(|m| {
                let (a, b) = setup.segment_guides(m);
                SegmentEntry {
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
        Catalogue {
            setup: setup.source.display().to_string(),
            install_joints_deg: setup.installation.as_ref().map(|installation| {
                let robot = &setup.robot;
                (installation.joints.iter().enumerate())
                    .map(|(i, v)| tidy(v * robot.actuated_joint(i).kind.display_unit().0))
                    .collect()
            }),
            guides,
            segments,
            too_many,
        }
    }
}

fn guide_report(setup: &Setup, guide: &Guide, generated: Option<&GeneratedSites>) -> GuideEntry {
    let configurations = guide
        .configurations
        .iter()
        .enumerate()
        .map(|(index, c)| configuration_report(setup, index, c))
        .collect();
    let (kind, reference, sites) = match generated {
        Some(generated) => {
            let axes = reference_axes(&setup.robot, guide.link, generated.spec.reference_axis);
            let reference = ReferenceAxes {
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
    GuideEntry {
        name: guide.name.clone(),
        link: setup.robot.links[guide.link].name.clone(),
        kind,
        optional: guide.optional,
        reference,
        configurations,
        sites,
    }
}

fn configuration_report(setup: &Setup, index: usize, c: &GuideConfiguration) -> ConfigurationEntry {
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
    ConfigurationEntry {
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
) -> SiteEntry {
    let configurations = (guide.configurations.iter().enumerate()).filter(
        |(_, c)| matches!(c.origin, ConfigurationOrigin::Generated { site, .. } if site == k),
    );
    let directions = configurations
        .zip(directions_rad)
        .map(|((index, c), angle)| DirectionEntry {
            angle_deg: tidy(angle.to_degrees()),
            direction: vector(&(c.pose.rotation * Vector3::z())),
            configuration: index,
            name: c.name.clone(),
        })
        .collect();
    SiteEntry {
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
