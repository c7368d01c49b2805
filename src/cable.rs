//! The physical specification of a cable, read from a TOML file.
//!
//! The discrete cable model is a chain of rigid sub-segments of pitch `l_ss` joined by a
//! bending spring `kb` and a torsion spring `kt` (N·m/rad per joint), so the continuum
//! stiffnesses are `EI = kb·l_ss` and `GJ = kt·l_ss`. File keys carry their units
//! (`diameter_mm`, `bending_stiffness_nm_per_rad`, …); [`CableSpec`] holds SI values.

use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A cable's datasheet values in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct CableSpec {
    /// Display name.
    pub name: String,
    /// Outer diameter (m).
    pub diameter_m: f64,
    /// Mass per unit length (kg/m).
    pub mass_per_length_kg_m: f64,
    /// Bending spring per joint of the discrete model, `kb` (N·m/rad).
    pub bending_stiffness_nm_per_rad: f64,
    /// Torsion spring per joint of the discrete model, `kt` (N·m/rad).
    pub torsion_stiffness_nm_per_rad: f64,
    /// Smallest allowed bend radius (m).
    pub min_bend_radius_m: f64,
    /// Length of one rigid sub-segment, `l_ss` (m).
    pub sub_segment_pitch_m: f64,
    /// Axial stiffness `EA` (N): the force that would double a sub-segment's length. The
    /// model's sub-segments are nearly rigid; this finite value makes stretch measurable.
    pub axial_stiffness_n: f64,
}

impl CableSpec {
    /// Continuum bending stiffness `EI = kb · l_ss` (N·m²).
    pub fn bending_rigidity_nm2(&self) -> f64 {
        self.bending_stiffness_nm_per_rad * self.sub_segment_pitch_m
    }

    /// Continuum torsional stiffness `GJ = kt · l_ss` (N·m²).
    pub fn torsional_rigidity_nm2(&self) -> f64 {
        self.torsion_stiffness_nm_per_rad * self.sub_segment_pitch_m
    }

    /// Reads and validates a cable file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<CableSpec, CableError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| CableError {
            file: path.to_path_buf(),
            line: None,
            problem: format!("cannot read the cable file: {e}"),
        })?;
        Self::from_toml_str(&text, path)
    }

    /// Parses and validates a cable file's text; `source` names it in messages.
    ///
    /// Every key is required, unknown keys are refused (a typo must not fall back to a
    /// default), and every number must be finite and positive.
    pub fn from_toml_str(text: &str, source: &Path) -> Result<CableSpec, CableError> {
        let raw: RawCable = toml::from_str(text).map_err(|e| CableError {
            file: source.to_path_buf(),
            line: e.span().map(|s| line_of(text, s.start)),
            problem: e.message().to_string(),
        })?;
        let positive = |field: &'static str, value: &Spanned<f64>| -> Result<f64, CableError> {
            let v = *value.get_ref();
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(CableError {
                    file: source.to_path_buf(),
                    line: Some(line_of(text, value.span().start)),
                    problem: format!("`{field}` = {v} must be a finite number > 0"),
                })
            }
        };
        Ok(CableSpec {
            name: raw.name,
            diameter_m: positive("diameter_mm", &raw.diameter_mm)? * 1e-3,
            mass_per_length_kg_m: positive("mass_per_length_kg_m", &raw.mass_per_length_kg_m)?,
            bending_stiffness_nm_per_rad: positive(
                "bending_stiffness_nm_per_rad",
                &raw.bending_stiffness_nm_per_rad,
            )?,
            torsion_stiffness_nm_per_rad: positive(
                "torsion_stiffness_nm_per_rad",
                &raw.torsion_stiffness_nm_per_rad,
            )?,
            min_bend_radius_m: positive("min_bend_radius_mm", &raw.min_bend_radius_mm)? * 1e-3,
            sub_segment_pitch_m: positive("sub_segment_pitch_mm", &raw.sub_segment_pitch_mm)?
                * 1e-3,
            axial_stiffness_n: positive("axial_stiffness_n", &raw.axial_stiffness_n)?,
        })
    }
}

/// The file's keys, as written (units in the names).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCable {
    name: String,
    diameter_mm: Spanned<f64>,
    mass_per_length_kg_m: Spanned<f64>,
    bending_stiffness_nm_per_rad: Spanned<f64>,
    torsion_stiffness_nm_per_rad: Spanned<f64>,
    min_bend_radius_mm: Spanned<f64>,
    sub_segment_pitch_mm: Spanned<f64>,
    axial_stiffness_n: Spanned<f64>,
}

/// 1-based line number of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
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
