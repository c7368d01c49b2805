//! `cable-dict calibrate`: a cable file from bench measurements (module
//! [`cable_dict::calibrate`]).

use super::output::{Failure, emit, tidy};
use cable_dict::atomic_file::write_atomically;
use cable_dict::cable::{CableSpec, DEFAULT_AXIAL_STIFFNESS_N, DEFAULT_SUB_SEGMENT_PITCH_M};
use cable_dict::calibrate::{CantileverTest, TipMeasurement, torsion_stiffness};
use std::path::PathBuf;

/// Standard gravity (m/s²).
const STANDARD_GRAVITY: f64 = 9.80665;

#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("tip").required(true).args(["droop_mm", "end_angle_deg"])))]
#[command(group(clap::ArgGroup::new("torsion").required(true).args(["torsion_ratio", "twist_angle_deg"])))]
pub struct Args {
    /// Name of the cable in the file.
    #[arg(long)]
    name: String,
    /// Outer diameter (mm).
    #[arg(long, value_name = "MM")]
    diameter_mm: f64,
    /// Mass per length (kg/m): weigh a measured length.
    #[arg(long, value_name = "KG_M")]
    mass_per_length_kg_m: f64,
    /// Smallest allowed bend radius (mm), from the datasheet.
    #[arg(long, value_name = "MM")]
    min_bend_radius_mm: f64,
    /// Bending test: free length of the cable clamped horizontally, from the clamp's edge
    /// to the end (mm).
    #[arg(long, value_name = "MM")]
    length_mm: f64,
    /// Bending test: how far the free end hangs below the clamp (mm).
    #[arg(long, value_name = "MM")]
    droop_mm: Option<f64>,
    /// Bending test, instead of the droop: the angle of the cable at its free end below the
    /// horizontal (degrees).
    #[arg(long, value_name = "DEG")]
    end_angle_deg: Option<f64>,
    /// Torsion: GJ as this multiple of EI (when no twist test was made; see cables/README.md
    /// for measured cables, 0.8–1.9).
    #[arg(long, value_name = "RATIO")]
    torsion_ratio: Option<f64>,
    /// Twist test: the angle the free end turns under the torque (degrees).
    #[arg(long, value_name = "DEG", requires_all = ["twist_length_mm", "twist_torque_nm"])]
    twist_angle_deg: Option<f64>,
    /// Twist test: length between the clamp and the twisted end (mm).
    #[arg(long, value_name = "MM")]
    twist_length_mm: Option<f64>,
    /// Twist test: the torque on the free end (N·m; a weight m on a lever arm a: m·g·a).
    #[arg(long, value_name = "NM")]
    twist_torque_nm: Option<f64>,
    /// Gravitational acceleration where the bending test was made (m/s²).
    #[arg(long, value_name = "M_S2", default_value_t = STANDARD_GRAVITY)]
    gravity_m_s2: f64,
    /// Also write the cable file here (replaced atomically).
    #[arg(short, long, value_name = "CABLE.toml")]
    output: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let test = CantileverTest {
        length_m: args.length_mm * 1e-3,
        mass_per_length_kg_m: args.mass_per_length_kg_m,
        gravity_m_s2: args.gravity_m_s2,
        tip: match (args.droop_mm, args.end_angle_deg) {
            (Some(droop), _) => TipMeasurement::Droop(droop * 1e-3),
            (None, Some(angle)) => TipMeasurement::EndAngle(angle.to_radians()),
            (None, None) => unreachable_tip()?,
        },
    };
    let (ei, shape) = test.bending_stiffness().map_err(Failure::input)?;
    let (gj, torsion_source) = match (args.torsion_ratio, args.twist_angle_deg) {
        (Some(ratio), _) => {
            if !(ratio.is_finite() && ratio > 0.0) {
                return Err(Failure::input(anyhow::anyhow!(
                    "--torsion-ratio {ratio} must be a finite number > 0"
                )));
            }
            (ratio * ei, format!("GJ = {ratio} × EI (stated ratio)"))
        }
        (None, Some(angle)) => {
            let length = args.twist_length_mm.unwrap_or(f64::NAN) * 1e-3;
            let torque = args.twist_torque_nm.unwrap_or(f64::NAN);
            let gj =
                torsion_stiffness(length, torque, angle.to_radians()).map_err(Failure::input)?;
            (
                gj,
                format!(
                    "twist test: {torque} N·m over {} mm turns the end by {angle}°: GJ = T·L/φ",
                    length * 1e3
                ),
            )
        }
        (None, None) => unreachable_tip()?,
    };
    let cable = CableSpec {
        name: args.name,
        diameter_m: args.diameter_mm * 1e-3,
        mass_per_length_kg_m: args.mass_per_length_kg_m,
        bending_stiffness_n_m2: ei,
        torsion_stiffness_n_m2: gj,
        min_bend_radius_m: args.min_bend_radius_mm * 1e-3,
        datasheet: Default::default(),
        sub_segment_pitch_m: DEFAULT_SUB_SEGMENT_PITCH_M,
        axial_stiffness_n: DEFAULT_AXIAL_STIFFNESS_N,
        tool_end_allowance_m: None,
        base_end_allowance_m: None,
        part_number: None,
    };
    let measured = match test.tip {
        // As typed: 18 mm, not the 18.000000000000004 of the unit conversions.
        TipMeasurement::Droop(droop) => format!("droops {} mm", tidy(droop * 1e3)),
        TipMeasurement::EndAngle(angle) => {
            format!("ends {}° below the horizontal", tidy(angle.to_degrees()))
        }
    };
    let header = format!(
        "Written by `cable-dict calibrate`.\n\
         Bending test: {} mm clamped horizontally, {} kg/m, g = {} m/s², {measured}.\n\
         Heavy elastica: wL³/EI = {:.6}, end angle {:.3}°, droop {:.2} mm.\n\
         Torsion: {torsion_source}.",
        args.length_mm,
        args.mass_per_length_kg_m,
        args.gravity_m_s2,
        shape.load_parameter,
        shape.end_angle_rad.to_degrees(),
        shape.droop_over_length * args.length_mm,
    );
    // The values go through the cable file's own reader: what is printed is what loads.
    let text = cable.to_toml(&header);
    let written = CableSpec::from_toml_str(&text, std::path::Path::new("(calibrated cable)"))
        .map_err(Failure::input)?;
    written.log_plausibility_warnings(std::path::Path::new("the calibrated cable"));
    if let Some(path) = &args.output {
        write_atomically(path, text.as_bytes())
            .map_err(|e| Failure::input(anyhow::anyhow!("cannot write {}: {e}", path.display())))?;
    }
    emit(&text)
}

/// Clap's argument groups make one of each measurement required.
fn unreachable_tip<T>() -> Result<T, Failure> {
    Err(Failure::input(anyhow::anyhow!(
        "give the bending test's --droop-mm or --end-angle-deg, and --torsion-ratio or the \
         twist test"
    )))
}
