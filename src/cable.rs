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
    /// Smallest allowed bend radius (m).
    pub min_bend_radius_m: f64,
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
            min_bend_radius_m: file.positive("min_bend_radius_mm", &raw.min_bend_radius_mm)? * 1e-3,
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
             min_bend_radius_mm = {}\n\
             sub_segment_pitch_mm = {}     # discretization of the model\n",
            toml::Value::String(self.name.clone()),
            significant(self.diameter_m * 1e3),
            significant(self.mass_per_length_kg_m),
            value(self.bending_stiffness_n_m2),
            value(self.torsion_stiffness_n_m2),
            significant(self.min_bend_radius_m * 1e3),
            significant(self.sub_segment_pitch_m * 1e3),
        ));
        text
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
    min_bend_radius_mm: Spanned<f64>,
    sub_segment_pitch_mm: Option<Spanned<f64>>,
    axial_stiffness_n: Option<Spanned<f64>>,
    tool_end_allowance_mm: Option<Spanned<f64>>,
    base_end_allowance_mm: Option<Spanned<f64>>,
    part_number: Option<Spanned<String>>,
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
