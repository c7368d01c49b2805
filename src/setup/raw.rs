//! The setup file's keys as written (units in the names), before validation.

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};
use std::fmt;
use toml::Spanned;

/// The whole file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSetup {
    pub robot: Spanned<String>,
    pub cable: Spanned<String>,
    pub gravity_m_s2: Spanned<[f64; 3]>,
    pub max_guides_per_link: Spanned<usize>,
    #[serde(default)]
    pub install_joints_deg: Option<Spanned<Vec<f64>>>,
    pub thresholds: RawThresholds,
    pub robustness: RawRobustness,
    pub guides: Spanned<Vec<Spanned<RawGuide>>>,
    pub segments: Spanned<Vec<Spanned<RawSegment>>>,
    #[serde(default)]
    pub bodies: Option<Spanned<Vec<Spanned<RawBody>>>>,
    #[serde(default)]
    pub pendant_angles: Option<Spanned<std::collections::BTreeMap<String, Spanned<RawPendant>>>>,
}

/// One `[pendant_angles]` entry: how the robot's pendant shows a joint's angle.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPendant {
    pub sign: Spanned<f64>,
    pub offset_deg: Spanned<f64>,
}

/// One `[[bodies]]` entry: a shape a link carries (see `bodies.rs`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    pub name: Spanned<String>,
    pub link: Spanned<String>,
    pub position_mm: Spanned<[f64; 3]>,
    pub rpy_deg: Spanned<[f64; 3]>,
    #[serde(default)]
    pub box_mm: Option<Spanned<[f64; 3]>>,
    #[serde(default)]
    pub cylinder_mm: Option<Spanned<RawCylinder>>,
    #[serde(default)]
    pub sphere_radius_mm: Option<Spanned<f64>>,
    #[serde(default)]
    pub mesh: Option<Spanned<String>>,
    #[serde(default)]
    pub mesh_scale: Option<Spanned<[f64; 3]>>,
}

/// `cylinder_mm = { radius, length }` (axis along the body's z).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCylinder {
    pub radius: f64,
    pub length: f64,
}

/// `[thresholds]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawThresholds {
    pub contact_clearance_mm: Spanned<f64>,
    pub stretch: Spanned<f64>,
    pub min_bend_radius_mm: Spanned<BendRadiusSetting>,
    pub clamp_zone_mm: Spanned<f64>,
    #[serde(default)]
    pub static_bend_margin_mm: Option<Spanned<f64>>,
    #[serde(default)]
    pub flexing_curvature_change_per_m: Option<Spanned<f64>>,
}

/// `[robustness]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRobustness {
    pub delta_s: Spanned<usize>,
    pub range: Spanned<usize>,
}

/// One `[[guides]]` entry: exactly one of `configurations`, `fixed` and `sites`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGuide {
    pub name: Spanned<String>,
    pub link: Spanned<String>,
    pub configurations: Option<Spanned<Vec<Spanned<RawConfiguration>>>>,
    pub fixed: Option<Spanned<RawConfiguration>>,
    pub sites: Option<Spanned<RawSites>>,
    /// The search may leave this clamp out.
    pub optional: Option<Spanned<bool>>,
    /// How it holds the cable: `"rigid"` (when absent), `"rotating"`, `"swivel"`, or a list
    /// of those the search may choose from; checked in `guides.rs`.
    #[serde(default)]
    pub kind: Option<Spanned<toml::Value>>,
    /// A swivel's cone: the half-angle its direction may turn within (deg).
    #[serde(default)]
    pub cone_deg: Option<Spanned<f64>>,
    /// A sliding guide's Coulomb friction coefficient on the cable (0 allowed).
    #[serde(default)]
    pub friction_coefficient: Option<Spanned<f64>>,
    /// A retraction's spring force at zero travel (N).
    #[serde(default)]
    pub preload_n: Option<Spanned<f64>>,
    /// A retraction's spring rate (N per mm of cable pulled out).
    #[serde(default)]
    pub rate_n_per_mm: Option<Spanned<f64>>,
    /// A retraction's travel: the most cable it gives out (mm).
    #[serde(default)]
    pub travel_mm: Option<Spanned<f64>>,
    /// A retraction's inlet: the guide the stored cable comes from (the previous guide).
    #[serde(default)]
    pub stored_from: Option<Spanned<String>>,
}

/// `sites = { spacing_mm, clamp_height_mm, directions_deg, region, reference_axis }`: a site
/// generator.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSites {
    pub spacing_mm: Spanned<f64>,
    pub clamp_height_mm: Spanned<f64>,
    pub directions_deg: Spanned<Vec<f64>>,
    #[serde(default)]
    pub region: Option<Spanned<RawRegion>>,
    /// `"x" | "y" | "z" | [x, y, z]`, checked in `sites.rs`.
    #[serde(default)]
    pub reference_axis: Option<Spanned<toml::Value>>,
}

/// `region = { min_mm, max_mm }` (a box) or `region = { z_mm = [low, high] }` (link frame).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRegion {
    #[serde(default)]
    pub min_mm: Option<[f64; 3]>,
    #[serde(default)]
    pub max_mm: Option<[f64; 3]>,
    #[serde(default)]
    pub z_mm: Option<[f64; 2]>,
}

/// One guide configuration: a pose in the guide's link frame.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawConfiguration {
    pub name: Spanned<String>,
    pub position_mm: Spanned<[f64; 3]>,
    pub rpy_deg: Spanned<[f64; 3]>,
}

/// One `[[segments]]` entry.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSegment {
    pub from: Spanned<String>,
    pub to: Spanned<String>,
    pub lengths: RawLengths,
}

/// `lengths = { min, max, step, allow_zero }`, in sub-segments.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLengths {
    pub min: Spanned<usize>,
    pub max: Spanned<usize>,
    pub step: Spanned<usize>,
    pub allow_zero: Spanned<bool>,
}

/// `min_bend_radius_mm`: a number of millimetres, or the word `"cable"`.
pub(super) enum BendRadiusSetting {
    /// An explicit radius (mm), not yet checked.
    Millimetres(f64),
    /// Any string; only `"cable"` is accepted later, with a located message.
    Word(String),
}

impl<'de> Deserialize<'de> for BendRadiusSetting {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BendRadiusVisitor)
    }
}

struct BendRadiusVisitor;

impl Visitor<'_> for BendRadiusVisitor {
    type Value = BendRadiusSetting;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a radius in millimetres or the string \"cable\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
        Ok(BendRadiusSetting::Millimetres(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
        Ok(BendRadiusSetting::Millimetres(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
        Ok(BendRadiusSetting::Millimetres(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        Ok(BendRadiusSetting::Word(v.to_string()))
    }
}
