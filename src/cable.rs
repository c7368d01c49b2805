//! The physical specification of a cable, read from a TOML file.
//!
//! A cable is described by continuum quantities an engineer can measure or find in a
//! datasheet: the bending stiffness `EI` and the torsional stiffness `GJ` (N·m²), the mass
//! per length, the diameter and the minimum bend radius. The cable model (module
//! [`statics`](crate::statics)) discretizes it into rigid sub-segments of a pitch `l`
//! (`sub_segment_pitch_mm`, a discretization setting, 10 mm by default) joined by a
//! bending spring `kb = EI / l` and a torsion spring `kt = GJ / l` per joint.
//!
//! The reference paper gives its cables as those per-joint springs
//! (`bending_stiffness_nm_per_rad`, `torsion_stiffness_nm_per_rad`, N·m/rad at its 10 mm
//! pitch). Such a file is still read: `EI = kb · l` and `GJ = kt · l` with the file's own
//! `sub_segment_pitch_mm`, which it must then state. File keys carry their units;
//! [`CableSpec`] holds SI values.
//!
//! [`CableSpec::plausibility_warnings`] says when the numbers describe no real cable (a
//! density no cable material reaches, a torsion-to-bending ratio far outside measured
//! cables): the values are still used, but the user is told.

use crate::input::line_of;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Sub-segment pitch (m) when the cable file does not set one: the reference paper's.
pub const DEFAULT_SUB_SEGMENT_PITCH_M: f64 = 0.010;

/// The sub-segment pitches a cable file may state (mm): finer than 1 mm resolves nothing a
/// robot cable's shape has and makes a metre of cable 1000 sub-segments; coarser than 100 mm
/// cannot bend around a link.
pub const SUB_SEGMENT_PITCH_RANGE_MM: std::ops::RangeInclusive<f64> = 1.0..=100.0;

/// Axial stiffness `EA` (N) of the model when the cable file does not set one. Not a
/// material value: a real cable's copper makes it 10⁵–10⁶ N. It only has to make the
/// sub-segments nearly rigid (a hanging metre of a 0.3 kg/m cable strains by < 3e-4) while
/// keeping the Newton systems well conditioned, so that "stretch" measures the geometry
/// (guides too far apart), not the material.
pub const DEFAULT_AXIAL_STIFFNESS_N: f64 = 1.0e4;

/// Bulk densities (kg/m³) a cable can have: from polymer-only cables (about 900, e.g.
/// all-dielectric fibre cables) to cables that are mostly copper (copper is 8960; a thin-
/// insulated power conductor reaches about 5000). Outside this range the mass or the
/// diameter is wrong.
pub const PLAUSIBLE_DENSITY_KG_M3: (f64, f64) = (700.0, 6000.0);

/// Ratios `GJ / EI` seen in cables: an isotropic rod has `1/(1 + ν)` = 0.67–0.77, stranded
/// and cabled cores slip in bending more than in torsion and measure 0.8–1.9 (see
/// cables/README.md); a braided shield may raise it further. Far outside, a value was
/// probably entered in the wrong unit or convention.
pub const PLAUSIBLE_TORSION_TO_BENDING: (f64, f64) = (0.3, 5.0);

/// Longest part number a cable file may give (characters).
pub const MAX_PART_NUMBER_CHARS: usize = 100;

/// A cable's physical values and its discretization, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct CableSpec {
    /// Display name.
    pub name: String,
    /// Outer diameter (m).
    pub diameter_m: f64,
    /// Mass per unit length (kg/m).
    pub mass_per_length_kg_m: f64,
    /// Bending stiffness `EI` (N·m²).
    pub bending_stiffness_n_m2: f64,
    /// Torsional stiffness `GJ` (N·m²).
    pub torsion_stiffness_n_m2: f64,
    /// Smallest bend radius of a fixed installation (m): what every piece must keep, the
    /// datasheet's `min_bend_radius_fixed_mm` (or the single `min_bend_radius_mm` of older
    /// files).
    pub min_bend_radius_m: f64,
    /// What the datasheet states beyond the fixed bend radius: the flexing radius, the
    /// torsion limit, a rated life and where the conductors lie. Each `None` when not stated.
    pub datasheet: Datasheet,
    /// Length of one rigid sub-segment of the model, `l` (m): a discretization setting.
    pub sub_segment_pitch_m: f64,
    /// Axial stiffness `EA` of the model (N); see [`DEFAULT_AXIAL_STIFFNESS_N`].
    pub axial_stiffness_n: f64,
    /// Cable to cut beyond the last clamp, into the connector at the tool (m); `None` when
    /// the file does not say. Not part of the physics (nor of a setup's hash).
    pub tool_end_allowance_m: Option<f64>,
    /// Cable to cut before the first clamp, to the base or the controller (m); `None` when
    /// the file does not say.
    pub base_end_allowance_m: Option<f64>,
    /// The maker's part number, for the installation sheet; `None` when the file does not
    /// say. Not part of the physics.
    pub part_number: Option<String>,
}

impl CableSpec {
    /// Bending spring per joint of the discrete model, `kb = EI / l` (N·m/rad).
    pub fn bending_stiffness_nm_per_rad(&self) -> f64 {
        self.bending_stiffness_n_m2 / self.sub_segment_pitch_m
    }

    /// Torsion spring per joint of the discrete model, `kt = GJ / l` (N·m/rad).
    pub fn torsion_stiffness_nm_per_rad(&self) -> f64 {
        self.torsion_stiffness_n_m2 / self.sub_segment_pitch_m
    }

    /// Bulk density (kg/m³): mass per length over the cross-section's area.
    pub fn density_kg_m3(&self) -> f64 {
        self.mass_per_length_kg_m / (0.25 * std::f64::consts::PI * self.diameter_m.powi(2))
    }

    /// What makes these values implausible for a real cable, one sentence each (empty when
    /// nothing does): a density outside [`PLAUSIBLE_DENSITY_KG_M3`], a `GJ / EI` outside
    /// [`PLAUSIBLE_TORSION_TO_BENDING`].
    pub fn plausibility_warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        let density = self.density_kg_m3();
        let (low, high) = PLAUSIBLE_DENSITY_KG_M3;
        if !(low..=high).contains(&density) {
            warnings.push(format!(
                "{}: a mass of {} kg/m in a {} mm diameter is a density of {density:.0} kg/m³; \
                 cables lie between {low:.0} and {high:.0} (copper alone is 8960): check the \
                 mass per length and the diameter",
                self.name,
                self.mass_per_length_kg_m,
                self.diameter_m * 1e3
            ));
        }
        let ratio = self.torsion_stiffness_n_m2 / self.bending_stiffness_n_m2;
        let (low, high) = PLAUSIBLE_TORSION_TO_BENDING;
        if !(low..=high).contains(&ratio) {
            warnings.push(format!(
                "{}: torsional over bending stiffness GJ/EI = {ratio:.2}; measured cables lie \
                 between about {low} and {high} (an isotropic rod: 0.67–0.77): check both \
                 values and their units (N·m², or N·m/rad per joint)",
                self.name
            ));
        }
        warnings
    }

    /// Reads and validates a cable file; logs its [plausibility
    /// warnings](CableSpec::plausibility_warnings), naming the file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<CableSpec, CableError> {
        let path = path.as_ref();
        let text =
            crate::input::read_text(path, crate::input::CABLE).map_err(|problem| CableError {
                file: path.to_path_buf(),
                line: None,
                problem,
            })?;
        let spec = Self::from_toml_str(&text, path)?;
        spec.log_plausibility_warnings(path);
        Ok(spec)
    }

    /// Logs each of [`CableSpec::plausibility_warnings`] as a warning naming `source`: for
    /// the places that load a cable to use it (a cable file, a setup's cable).
    pub fn log_plausibility_warnings(&self, source: &Path) {
        for warning in self.plausibility_warnings() {
            log::warn!("{}: {warning}", source.display());
        }
    }

    /// Parses and validates a cable file's text; `source` names it in messages.
    ///
    /// Unknown keys are refused (a typo must not fall back to a default), every number must
    /// be finite and positive, and each stiffness must be given exactly once: as `EI`/`GJ`
    /// (N·m²) or as the paper's per-joint spring (N·m/rad, which needs the file's
    /// `sub_segment_pitch_mm`).
    pub fn from_toml_str(text: &str, source: &Path) -> Result<CableSpec, CableError> {
        let raw: RawCable = toml::from_str(text).map_err(|e| CableError {
            file: source.to_path_buf(),
            line: e.span().map(|s| line_of(text, s.start)),
            problem: e.message().to_string(),
        })?;
        let file = FileValues { text, source };
        let pitch_m = match &raw.sub_segment_pitch_mm {
            Some(value) => file.pitch_mm(value)? * 1e-3,
            None => DEFAULT_SUB_SEGMENT_PITCH_M,
        };
        let stiffness = |continuum, per_joint, names| {
            file.stiffness(
                continuum,
                per_joint,
                raw.sub_segment_pitch_mm.is_some(),
                pitch_m,
                names,
            )
        };
        Ok(CableSpec {
            bending_stiffness_n_m2: stiffness(
                &raw.bending_stiffness_n_m2,
                &raw.bending_stiffness_nm_per_rad,
                ["bending_stiffness_n_m2", "bending_stiffness_nm_per_rad"],
            )?,
            torsion_stiffness_n_m2: stiffness(
                &raw.torsion_stiffness_n_m2,
                &raw.torsion_stiffness_nm_per_rad,
                ["torsion_stiffness_n_m2", "torsion_stiffness_nm_per_rad"],
            )?,
            diameter_m: file.positive("diameter_mm", &raw.diameter_mm)? * 1e-3,
            mass_per_length_kg_m: file
                .positive("mass_per_length_kg_m", &raw.mass_per_length_kg_m)?,
            min_bend_radius_m: file.fixed_bend_radius_mm(&raw)? * 1e-3,
            datasheet: file.datasheet(&raw)?,
            sub_segment_pitch_m: pitch_m,
            axial_stiffness_n: match &raw.axial_stiffness_n {
                Some(value) => file.positive("axial_stiffness_n", value)?,
                None => DEFAULT_AXIAL_STIFFNESS_N,
            },
            tool_end_allowance_m: file
                .allowance("tool_end_allowance_mm", &raw.tool_end_allowance_mm)?,
            base_end_allowance_m: file
                .allowance("base_end_allowance_mm", &raw.base_end_allowance_mm)?,
            part_number: file.part_number(&raw.part_number)?,
            name: raw.name,
        })
    }

    /// The cable file of these values (continuum keys, SI units with the unit in the key),
    /// with `header` as its leading comment lines: what `cable-dict calibrate` prints.
    pub fn to_toml(&self, header: &str) -> String {
        let mut text = String::new();
        for line in header.lines() {
            text.push_str(&format!("# {line}\n").replace("# \n", "#\n"));
        }
        let value = |v: f64| format!("{:e}", significant(v));
        text.push_str(&format!(
            "name = {}\n\
             diameter_mm = {}\n\
             mass_per_length_kg_m = {}\n\
             bending_stiffness_n_m2 = {}   # EI\n\
             torsion_stiffness_n_m2 = {}   # GJ\n\
             min_bend_radius_fixed_mm = {}\n\
             sub_segment_pitch_mm = {}     # discretization of the model\n",
            toml::Value::String(self.name.clone()),
            significant(self.diameter_m * 1e3),
            significant(self.mass_per_length_kg_m),
            value(self.bending_stiffness_n_m2),
            value(self.torsion_stiffness_n_m2),
            significant(self.min_bend_radius_m * 1e3),
            significant(self.sub_segment_pitch_m * 1e3),
        ));
        text.push_str(&self.datasheet.to_toml());
        text
    }
}

/// The exponent `k` of a rated life extended to other amplitudes, `N = N_rated · (a /
/// a_rated)^(−k)`, when the cable file's `[rated_life]` states none: 1/0.12, the elastic line
/// of Manson's universal slopes, where cable ratings (10⁶–10⁷ cycles) lie
/// ([`crate::life::curve`]; docs/physics.md, "Life").
pub const DEFAULT_LIFE_EXPONENT: f64 = 1.0 / 0.12;

/// What a cable datasheet states besides the fixed bend radius; each `None` when the file
/// does not say (nothing is invented: the summary says what is missing).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Datasheet {
    /// Smallest bend radius in continuous flexing (m), ≥ the fixed one: what a piece whose
    /// shape changes over the motion must keep.
    pub min_bend_radius_flexing_m: Option<f64>,
    /// Largest twist per length (deg/m, a magnitude: the datasheet's ±value).
    pub torsion_limit_deg_per_m: Option<f64>,
    /// The datasheet's rated life.
    pub rated_life: Option<RatedLife>,
    /// Distance of the outermost conductor's centre from the cable's axis (m): bending
    /// strain is curvature times this.
    pub conductor_offset_m: Option<f64>,
}

/// A datasheet's rated life: the cable lasted `cycles` flexing cycles from straight to
/// `bend_radius_m` and back, twisted between ±`torsion_deg_per_m` in each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatedLife {
    /// Cycles to failure at the rated point.
    pub cycles: f64,
    /// Bend radius of the rated flexing (m); `None`: the rating is for torsion alone.
    pub bend_radius_m: Option<f64>,
    /// Twist per length of the rated torsion, ± (deg/m); `None`: the rating is for bending
    /// alone.
    pub torsion_deg_per_m: Option<f64>,
    /// The exponent `k` extending the rated point to other amplitudes (see
    /// [`DEFAULT_LIFE_EXPONENT`]).
    pub exponent: f64,
    /// Whether the file stated the exponent (else [`DEFAULT_LIFE_EXPONENT`]).
    pub exponent_stated: bool,
}

impl Datasheet {
    /// The file lines of these values (empty for an empty datasheet): what
    /// [`CableSpec::to_toml`] appends.
    fn to_toml(&self) -> String {
        let mut text = String::new();
        let mm = |v: f64| significant(v * 1e3);
        if let Some(r) = self.min_bend_radius_flexing_m {
            text.push_str(&format!("min_bend_radius_flexing_mm = {}\n", mm(r)));
        }
        if let Some(t) = self.torsion_limit_deg_per_m {
            text.push_str(&format!("torsion_limit_deg_per_m = {}\n", significant(t)));
        }
        if let Some(offset) = self.conductor_offset_m {
            text.push_str(&format!("conductor_offset_mm = {}\n", mm(offset)));
        }
        if let Some(life) = &self.rated_life {
            text.push_str(&format!(
                "\n[rated_life]\ncycles = {}\n",
                significant(life.cycles)
            ));
            if let Some(r) = life.bend_radius_m {
                text.push_str(&format!("bend_radius_mm = {}\n", mm(r)));
            }
            if let Some(t) = life.torsion_deg_per_m {
                text.push_str(&format!("torsion_deg_per_m = {}\n", significant(t)));
            }
            if life.exponent_stated {
                text.push_str(&format!("exponent = {}\n", significant(life.exponent)));
            }
        }
        text
    }

    /// Whether a life can be predicted: a rated life, or the conductors' offset for
    /// copper's strain–life line ([`crate::life::curve::LifeCurve::of`]).
    pub fn predicts_life(&self) -> bool {
        self.rated_life.is_some() || self.conductor_offset_m.is_some()
    }

    /// What the datasheet leaves out that the checks would use, one phrase each (empty when
    /// nothing is missing): for the summary.
    pub fn missing(&self) -> Vec<&'static str> {
        let mut missing = Vec::new();
        if self.min_bend_radius_flexing_m.is_none() {
            missing.push("no flexing bend radius (flexing pieces keep the fixed one)");
        }
        if self.torsion_limit_deg_per_m.is_none() {
            missing.push("no torsion limit (twist reported, not limited)");
        }
        if self.rated_life.is_none() && self.conductor_offset_m.is_none() {
            missing.push("neither a rated life nor the conductors' offset (no life predicted)");
        }
        missing
    }
}

/// `v` rounded to 6 significant digits, so printed values carry no binary noise.
fn significant(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let scale = 10f64.powi(5 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

/// The file's keys, as written (units in the names).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCable {
    name: String,
    diameter_mm: Spanned<f64>,
    mass_per_length_kg_m: Spanned<f64>,
    bending_stiffness_n_m2: Option<Spanned<f64>>,
    torsion_stiffness_n_m2: Option<Spanned<f64>>,
    bending_stiffness_nm_per_rad: Option<Spanned<f64>>,
    torsion_stiffness_nm_per_rad: Option<Spanned<f64>>,
    min_bend_radius_mm: Option<Spanned<f64>>,
    min_bend_radius_fixed_mm: Option<Spanned<f64>>,
    min_bend_radius_flexing_mm: Option<Spanned<f64>>,
    torsion_limit_deg_per_m: Option<Spanned<f64>>,
    conductor_offset_mm: Option<Spanned<f64>>,
    rated_life: Option<Spanned<RawRatedLife>>,
    sub_segment_pitch_mm: Option<Spanned<f64>>,
    axial_stiffness_n: Option<Spanned<f64>>,
    tool_end_allowance_mm: Option<Spanned<f64>>,
    base_end_allowance_mm: Option<Spanned<f64>>,
    part_number: Option<Spanned<String>>,
}

/// `[rated_life]`: the datasheet's rated point.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRatedLife {
    cycles: Spanned<f64>,
    bend_radius_mm: Option<Spanned<f64>>,
    torsion_deg_per_m: Option<Spanned<f64>>,
    exponent: Option<Spanned<f64>>,
}

/// A cable file's text, for messages that name the line of a value.
struct FileValues<'a> {
    text: &'a str,
    source: &'a Path,
}

impl FileValues<'_> {
    fn error(&self, line: Option<usize>, problem: String) -> CableError {
        CableError {
            file: self.source.to_path_buf(),
            line,
            problem,
        }
    }

    /// The file's `sub_segment_pitch_mm`, within [`SUB_SEGMENT_PITCH_RANGE_MM`].
    fn pitch_mm(&self, value: &Spanned<f64>) -> Result<f64, CableError> {
        let pitch = self.positive("sub_segment_pitch_mm", value)?;
        if SUB_SEGMENT_PITCH_RANGE_MM.contains(&pitch) {
            return Ok(pitch);
        }
        Err(self.error(
            Some(line_of(self.text, value.span().start)),
            format!(
                "`sub_segment_pitch_mm` = {pitch} is outside {} to {} mm (a piece may have at \
                 most 10 000 sub-segments; 10 mm is the default)",
                SUB_SEGMENT_PITCH_RANGE_MM.start(),
                SUB_SEGMENT_PITCH_RANGE_MM.end()
            ),
        ))
    }

    /// The fixed-installation bend radius (mm): `min_bend_radius_fixed_mm`, or the single
    /// `min_bend_radius_mm` of files written before datasheets had two; exactly one.
    fn fixed_bend_radius_mm(&self, raw: &RawCable) -> Result<f64, CableError> {
        match (&raw.min_bend_radius_fixed_mm, &raw.min_bend_radius_mm) {
            (Some(value), None) => self.positive("min_bend_radius_fixed_mm", value),
            (None, Some(value)) => self.positive("min_bend_radius_mm", value),
            (Some(_), Some(value)) => Err(self.error(
                Some(line_of(self.text, value.span().start)),
                "give either `min_bend_radius_fixed_mm` (with `min_bend_radius_flexing_mm` \
                 for flexing) or the older single `min_bend_radius_mm`, not both"
                    .into(),
            )),
            (None, None) => Err(self.error(
                None,
                "missing `min_bend_radius_fixed_mm` (the datasheet's bend radius for a fixed \
                 installation, mm; files before datasheets had two: `min_bend_radius_mm`)"
                    .into(),
            )),
        }
    }

    /// The datasheet values beyond the fixed radius, each checked: the flexing radius not
    /// below the fixed one, the conductors inside the cable, a rated point that states a
    /// radius or a torsion.
    fn datasheet(&self, raw: &RawCable) -> Result<Datasheet, CableError> {
        let optional = |key: &str, value: &Option<Spanned<f64>>| {
            value.as_ref().map(|v| self.positive(key, v)).transpose()
        };
        let at = |value: &Spanned<f64>| Some(line_of(self.text, value.span().start));
        let flexing = optional(
            "min_bend_radius_flexing_mm",
            &raw.min_bend_radius_flexing_mm,
        )?;
        let fixed = self.fixed_bend_radius_mm(raw)?;
        if let (Some(flexing), Some(value)) = (flexing, &raw.min_bend_radius_flexing_mm)
            && flexing < fixed
        {
            return Err(self.error(
                at(value),
                format!(
                    "`min_bend_radius_flexing_mm` = {flexing} is below the fixed-installation \
                     radius {fixed} mm: a cable that moves needs the larger radius"
                ),
            ));
        }
        let diameter = *raw.diameter_mm.get_ref();
        let offset = optional("conductor_offset_mm", &raw.conductor_offset_mm)?;
        if let (Some(offset), Some(value)) = (offset, &raw.conductor_offset_mm)
            && offset >= 0.5 * diameter
        {
            return Err(self.error(
                at(value),
                format!(
                    "`conductor_offset_mm` = {offset} is not inside the cable (its radius is \
                     {} mm)",
                    0.5 * diameter
                ),
            ));
        }
        let rated_life = match &raw.rated_life {
            Some(life) => Some(self.rated_life(life.get_ref(), life.span().start)?),
            None => None,
        };
        Ok(Datasheet {
            min_bend_radius_flexing_m: flexing.map(|r| r * 1e-3),
            torsion_limit_deg_per_m: optional(
                "torsion_limit_deg_per_m",
                &raw.torsion_limit_deg_per_m,
            )?,
            rated_life,
            conductor_offset_m: offset.map(|o| o * 1e-3),
        })
    }

    /// `[rated_life]`: at least one cycle, a radius or a torsion (or both), an exponent > 0.
    fn rated_life(&self, raw: &RawRatedLife, start: usize) -> Result<RatedLife, CableError> {
        let optional = |key: &str, value: &Option<Spanned<f64>>| {
            value.as_ref().map(|v| self.positive(key, v)).transpose()
        };
        let cycles = self.positive("rated_life.cycles", &raw.cycles)?;
        if cycles < 1.0 {
            return Err(self.error(
                Some(line_of(self.text, raw.cycles.span().start)),
                format!("`rated_life.cycles` = {cycles}: a rated life is at least one cycle"),
            ));
        }
        let bend_radius_mm = optional("rated_life.bend_radius_mm", &raw.bend_radius_mm)?;
        let torsion = optional("rated_life.torsion_deg_per_m", &raw.torsion_deg_per_m)?;
        if bend_radius_mm.is_none() && torsion.is_none() {
            return Err(self.error(
                Some(line_of(self.text, start)),
                "`[rated_life]` states neither `bend_radius_mm` nor `torsion_deg_per_m`: the \
                 cycles mean nothing without the conditions they were rated at"
                    .into(),
            ));
        }
        let exponent = optional("rated_life.exponent", &raw.exponent)?;
        Ok(RatedLife {
            cycles,
            bend_radius_m: bend_radius_mm.map(|r| r * 1e-3),
            torsion_deg_per_m: torsion,
            exponent: exponent.unwrap_or(DEFAULT_LIFE_EXPONENT),
            exponent_stated: exponent.is_some(),
        })
    }

    /// The optional part number: one line of at most [`MAX_PART_NUMBER_CHARS`] characters.
    fn part_number(&self, value: &Option<Spanned<String>>) -> Result<Option<String>, CableError> {
        let Some(value) = value else {
            return Ok(None);
        };
        let text = value.get_ref().trim();
        let problem = if text.is_empty() {
            Some("is empty (leave the key out when there is none)".to_string())
        } else if text.chars().count() > MAX_PART_NUMBER_CHARS {
            Some(format!("is longer than {MAX_PART_NUMBER_CHARS} characters"))
        } else if text.chars().any(char::is_control) {
            Some("holds a line break or another control character".to_string())
        } else {
            None
        };
        match problem {
            Some(problem) => Err(self.error(
                Some(line_of(self.text, value.span().start)),
                format!("`part_number` {problem}"),
            )),
            None => Ok(Some(text.to_string())),
        }
    }

    /// An optional cut allowance (mm in the file, m returned): finite and ≥ 0.
    fn allowance(
        &self,
        field: &str,
        value: &Option<Spanned<f64>>,
    ) -> Result<Option<f64>, CableError> {
        let Some(value) = value else {
            return Ok(None);
        };
        let v = *value.get_ref();
        if v.is_finite() && v >= 0.0 {
            return Ok(Some(v * 1e-3));
        }
        Err(self.error(
            Some(line_of(self.text, value.span().start)),
            format!("`{field}` = {v} must be a finite length ≥ 0 (mm)"),
        ))
    }

    fn positive(&self, field: &str, value: &Spanned<f64>) -> Result<f64, CableError> {
        let v = *value.get_ref();
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.error(
                Some(line_of(self.text, value.span().start)),
                format!("`{field}` = {v} must be a finite number > 0"),
            ))
        }
    }

    /// One stiffness (N·m²) from its continuum key or the paper's per-joint key, exactly one
    /// of them; the per-joint one needs the file's pitch.
    fn stiffness(
        &self,
        continuum: &Option<Spanned<f64>>,
        per_joint: &Option<Spanned<f64>>,
        pitch_written: bool,
        pitch_m: f64,
        [continuum_key, per_joint_key]: [&str; 2],
    ) -> Result<f64, CableError> {
        match (continuum, per_joint) {
            (Some(value), None) => self.positive(continuum_key, value),
            (None, Some(value)) if pitch_written => {
                Ok(self.positive(per_joint_key, value)? * pitch_m)
            }
            (None, Some(value)) => Err(self.error(
                Some(line_of(self.text, value.span().start)),
                format!(
                    "`{per_joint_key}` is a spring per joint of the model and means nothing \
                     without `sub_segment_pitch_mm`: add the pitch it was given for, or give \
                     `{continuum_key}` (EI or GJ in N·m²)"
                ),
            )),
            (Some(_), Some(value)) => Err(self.error(
                Some(line_of(self.text, value.span().start)),
                format!("give either `{continuum_key}` or `{per_joint_key}`, not both"),
            )),
            (None, None) => Err(self.error(
                None,
                format!("missing `{continuum_key}` (N·m²; or `{per_joint_key}` with the pitch)"),
            )),
        }
    }
}

/// A cable file that cannot be used: the file, the line when known, and the problem.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {problem}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct CableError {
    /// The cable file.
    pub file: PathBuf,
    /// 1-based line of the offending value, when known.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
}
