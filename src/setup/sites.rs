//! `sites = {…}`: a guide whose candidate configurations are generated on its link's
//! collision surfaces (see [`crate::sites`]).

use super::error::Source;
use super::raw::{RawRegion, RawSites};
use super::{ConfigurationOrigin, GuideConfiguration, Installation, SetupError};
use crate::robot::Robot;
use crate::sites::{GeneratedSites, MIN_SPACING_M, Region, Site, SiteSpec, generate, site_frame};
use crate::stress::contact::Obstacles;
use nalgebra::{Point3, Unit, Vector3};
use std::cell::OnceCell;
use toml::Spanned;

/// Most cable directions per site.
const MAX_DIRECTIONS: usize = 36;

/// Most clamp configurations all of a setup's site generators together may give, estimated
/// from their links' surface areas before any site is made. Each generator has its own
/// limits ([`crate::sites::MAX_SURFACE_POINTS`], [`MAX_DIRECTIONS`]); eight of them within
/// theirs made 29 million configurations and 3.5 GB. A configuration takes about 200 bytes,
/// so this keeps a setup's catalogue near 200 MB.
pub(super) const MAX_GENERATED_CONFIGURATIONS: f64 = 1.0e6;

/// One site generator of a setup, as the total bound sees it: `guides[g]` on `link`.
pub(super) struct GeneratorEstimate {
    pub guide: usize,
    pub link: usize,
    pub spacing_mm: f64,
    pub directions: usize,
}

/// Refuses site generators that together would give more than
/// [`MAX_GENERATED_CONFIGURATIONS`] configurations, before any of them runs: the figure, the
/// limit and the largest generators in the message.
pub(super) fn check_generated_total(
    src: Source,
    span: std::ops::Range<usize>,
    robot: &Robot,
    generators: &[GeneratorEstimate],
) -> Result<(), SetupError> {
    let mut estimates: Vec<(f64, &GeneratorEstimate)> = generators
        .iter()
        .map(|e| {
            let points = crate::sites::estimated_surface_points(robot, e.link, e.spacing_mm * 1e-3);
            (points * e.directions as f64, e)
        })
        .collect();
    let total: f64 = estimates.iter().map(|(n, _)| n).sum();
    if total <= MAX_GENERATED_CONFIGURATIONS {
        return Ok(());
    }
    estimates.sort_by(|a, b| b.0.total_cmp(&a.0));
    let largest: Vec<String> = estimates
        .iter()
        .take(3)
        .map(|(n, e)| {
            format!(
                "guides[{}] on {}: about {n:.0} ({} mm spacing × {} directions)",
                e.guide, robot.links[e.link].name, e.spacing_mm, e.directions
            )
        })
        .collect();
    Err(src.error(
        span,
        "guides",
        format!(
            "the site generators would give about {total:.0} clamp configurations together, \
             at most {MAX_GENERATED_CONFIGURATIONS:.0}; the largest: {}. Raise spacing_mm, \
             give fewer directions_deg, or a region",
            largest.join("; ")
        ),
    ))
}

/// What generating sites needs besides the generator itself: the cable radius, the
/// installation pose and, built on first use, the robot's collision geometry (which the
/// check of written clamps shares, so that loading a setup builds it once).
pub(super) struct SiteContext<'a> {
    pub cable_radius_m: f64,
    pub installation: Option<&'a Installation>,
    obstacles: OnceCell<Result<Obstacles, String>>,
}

impl<'a> SiteContext<'a> {
    pub fn new(cable_radius_m: f64, installation: Option<&'a Installation>) -> Self {
        Self {
            cable_radius_m,
            installation,
            obstacles: OnceCell::new(),
        }
    }

    /// The robot's collision geometry, built on first use; the error says why it cannot be.
    pub fn obstacles(&self, robot: &Robot) -> Result<&Obstacles, &String> {
        self.obstacles
            .get_or_init(|| Obstacles::from_robot(robot).map_err(|e| e.to_string()))
            .as_ref()
    }

    /// The sites of a generator, and its configurations: every site in every direction, in
    /// site order.
    pub fn configurations(
        &self,
        src: Source,
        robot: &Robot,
        link: usize,
        key: &str,
        raw: &Spanned<RawSites>,
    ) -> Result<(GeneratedSites, Vec<GuideConfiguration>), SetupError> {
        let generated = self.sites(src, robot, link, key, raw)?;
        let line = src.line_of(raw.span().start);
        let directions = &generated.spec.directions_rad;
        let configurations = generated
            .sites
            .iter()
            .enumerate()
            .flat_map(|(k, site)| {
                directions
                    .iter()
                    .map(move |&angle| configuration(site, k, angle, line))
            })
            .collect();
        Ok((generated, configurations))
    }

    /// The sites of a generator and the spec they were made with.
    fn sites(
        &self,
        src: Source,
        robot: &Robot,
        link: usize,
        key: &str,
        raw: &Spanned<RawSites>,
    ) -> Result<GeneratedSites, SetupError> {
        let fail = |problem: String| src.error(raw.span(), key, problem);
        let installation = self.installation.ok_or_else(|| {
            fail(
                "generated sites need `install_joints_deg = [...]` at the top of the setup: \
                 the robot pose at which the cable is installed untwisted, from which the \
                 clamps' twist references are derived"
                    .into(),
            )
        })?;
        let spec = spec(src, key, raw.get_ref())?;
        let obstacles = self.obstacles(robot).map_err(|e| fail(e.clone()))?;
        let sites = generate(
            robot,
            obstacles,
            link,
            &spec,
            self.cable_radius_m,
            &installation.link_poses,
        )
        .map_err(|e| fail(e.to_string()))?;
        Ok(GeneratedSites { spec, sites })
    }
}

/// The configuration of site `k` (0-based) in the direction `angle` (rad), named
/// `site <k + 1> [x y z] <angle>°` (mm, deg, rounded).
fn configuration(site: &Site, k: usize, angle: f64, line: usize) -> GuideConfiguration {
    let pose = site_frame(site, angle);
    // + 0.0 writes −0 as 0, in the numbers and in the rounded name.
    let position_mm = [site.position.x, site.position.y, site.position.z].map(|v| v * 1e3 + 0.0);
    let (r, p, y) = pose.rotation.euler_angles();
    let rounded = position_mm.map(|v| v.round() + 0.0);
    GuideConfiguration {
        name: format!(
            "site {} [{} {} {}] {}°",
            k + 1,
            rounded[0],
            rounded[1],
            rounded[2],
            angle.to_degrees().round() + 0.0
        ),
        pose,
        position_mm,
        rpy_deg: [r, p, y].map(f64::to_degrees),
        origin: ConfigurationOrigin::Generated { line, site: k },
        kind: super::GuideKind::Rigid,
    }
}

fn spec(src: Source, key: &str, raw: &RawSites) -> Result<SiteSpec, SetupError> {
    let spacing = *raw.spacing_mm.get_ref();
    if !(spacing.is_finite() && spacing * 1e-3 >= MIN_SPACING_M) {
        return Err(src.error(
            raw.spacing_mm.span(),
            format!("{key}.spacing_mm"),
            format!(
                "{spacing} must be a finite number ≥ {} mm",
                MIN_SPACING_M * 1e3
            ),
        ));
    }
    let height = *raw.clamp_height_mm.get_ref();
    if !(height.is_finite() && height >= 0.0) {
        return Err(src.error(
            raw.clamp_height_mm.span(),
            format!("{key}.clamp_height_mm"),
            format!("{height} must be a finite number ≥ 0"),
        ));
    }
    Ok(SiteSpec {
        spacing_m: spacing * 1e-3,
        clamp_height_m: height * 1e-3,
        directions_rad: directions(src, key, &raw.directions_deg)?,
        region: match &raw.region {
            Some(region) => self::region(src, key, region)?,
            None => Region::Everywhere,
        },
        reference_axis: match &raw.reference_axis {
            Some(axis) => Some(reference_axis(src, key, axis)?),
            None => None,
        },
    })
}

/// `reference_axis = "x" | "y" | "z" | [x, y, z]` (link frame; a vector need not be unit).
fn reference_axis(
    src: Source,
    key: &str,
    raw: &Spanned<toml::Value>,
) -> Result<Unit<Vector3<f64>>, SetupError> {
    let fail = || {
        src.error(
            raw.span(),
            format!("{key}.reference_axis"),
            format!(
                "{} is not an axis: give \"x\", \"y\", \"z\" or a non-zero [x, y, z] \
                 (link frame)",
                raw.get_ref()
            ),
        )
    };
    let number = |v: &toml::Value| match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    };
    let vector = match raw.get_ref() {
        toml::Value::String(name) => match name.as_str() {
            "x" => Vector3::x(),
            "y" => Vector3::y(),
            "z" => Vector3::z(),
            _ => return Err(fail()),
        },
        toml::Value::Array(items) if items.len() == 3 => {
            let values: Option<Vec<f64>> = items.iter().map(number).collect();
            Vector3::from_iterator(values.ok_or_else(fail)?)
        }
        _ => return Err(fail()),
    };
    let finite = vector.iter().all(|v| v.is_finite());
    finite
        .then(|| Unit::try_new(vector, 1e-12))
        .flatten()
        .ok_or_else(fail)
}

fn directions(src: Source, key: &str, raw: &Spanned<Vec<f64>>) -> Result<Vec<f64>, SetupError> {
    let fail = |problem: String| src.error(raw.span(), format!("{key}.directions_deg"), problem);
    let list = raw.get_ref();
    if list.is_empty() || list.len() > MAX_DIRECTIONS {
        return Err(fail(format!(
            "{} directions: give 1 to {MAX_DIRECTIONS} angles about the surface normal (deg)",
            list.len()
        )));
    }
    let mut seen: Vec<f64> = Vec::with_capacity(list.len());
    for &angle in list {
        if !angle.is_finite() {
            return Err(fail(format!("{angle} is not a finite angle")));
        }
        let wrapped = angle.rem_euclid(360.0);
        if let Some(twin) = seen.iter().position(|s| (s - wrapped).abs() < 1e-9) {
            return Err(fail(format!(
                "{angle}° is the same direction as {}° (angles are modulo 360°)",
                list[twin]
            )));
        }
        seen.push(wrapped);
    }
    Ok(list.iter().map(|a| a.to_radians()).collect())
}

fn region(src: Source, key: &str, raw: &Spanned<RawRegion>) -> Result<Region, SetupError> {
    let key = format!("{key}.region");
    let fail = |problem: &str| src.error(raw.span(), key.clone(), problem.to_string());
    let r = raw.get_ref();
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    match (r.min_mm, r.max_mm, r.z_mm) {
        (Some(min), Some(max), None) => {
            if !(finite(&min) && finite(&max) && (0..3).all(|k| min[k] < max[k])) {
                return Err(fail("min_mm must be finite and below max_mm on every axis"));
            }
            Ok(Region::Box {
                min_m: Point3::from(min.map(|v| v * 1e-3)),
                max_m: Point3::from(max.map(|v| v * 1e-3)),
            })
        }
        (None, None, Some([low, high])) => {
            if !(finite(&[low, high]) && low < high) {
                return Err(fail("z_mm = [low, high] must be finite with low < high"));
            }
            Ok(Region::AlongZ {
                min_m: low * 1e-3,
                max_m: high * 1e-3,
            })
        }
        _ => Err(fail(
            "give either `min_mm = [x, y, z], max_mm = [x, y, z]` (a box) or \
             `z_mm = [low, high]` (a range along the link's z axis), link frame",
        )),
    }
}
