//! `cable-dict segment`: one cable segment between two guide frames in free space.

use super::{Failure, args, emit, print_json};
use cable_dict::cable::CableSpec;
use cable_dict::geometry::{ConnectError, ConnectedGeometry, CurveFamily, connect};
use cable_dict::pose::{Pose, matrix_rows};
use cable_dict::stress::{BendRadius, min_bend_radius, stretch};
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Cable specification file (e.g. cables/smc_le_cp_3.toml).
    #[arg(long, value_name = "CABLE.toml")]
    cable: PathBuf,
    /// Natural cable length between the two guides (mm); a whole number of sub-segments.
    #[arg(long, value_name = "L")]
    length_mm: f64,
    /// Start guide frame in the world frame: x,y,z (mm), roll,pitch,yaw (deg, URDF convention
    /// R = Rz(yaw)·Ry(pitch)·Rx(roll)); its +z axis is the cable direction leaving the guide.
    #[arg(long, value_name = "X,Y,Z,R,P,Y", allow_hyphen_values = true, value_parser = args::guide_frame)]
    start: Pose,
    /// End guide frame, as --start; its +z axis is the cable direction arriving at the guide.
    #[arg(long, value_name = "X,Y,Z,R,P,Y", allow_hyphen_values = true, value_parser = args::guide_frame)]
    end: Pose,
    /// Which shape to compute: `connected` is the Hermite curve with rotation-minimizing frames.
    #[arg(long, value_enum, default_value_t = Stage::Connected)]
    stage: Stage,
    /// Print JSON: stage, alpha_m, length_mm, nodes_mm, frames, metrics.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum, Serialize)]
#[serde(rename_all = "snake_case")]
enum Stage {
    /// Hermite curve + rotation-minimizing frames (no physics).
    Connected,
}

#[derive(Serialize)]
struct SegmentReport {
    stage: Stage,
    cable: String,
    /// `hermite` (the paper's curve) or `bowed` (slack taken by a bow towards -z).
    curve: &'static str,
    alpha_m: f64,
    /// Bow height of the `bowed` curve (m); 0 for `hermite`.
    bow_m: f64,
    length_mm: f64,
    sub_segments: usize,
    pitch_mm: f64,
    twist_correction_deg: f64,
    /// S+1 nodes from the start guide to the end guide inclusive.
    nodes_mm: Vec<[f64; 3]>,
    /// Node frames, row-major rotations (columns: normal, binormal, tangent).
    frames: Vec<[[f64; 3]; 3]>,
    metrics: Metrics,
}

#[derive(Serialize)]
struct Metrics {
    /// `null` for a straight cable (infinite radius).
    min_bend_radius_mm: Option<f64>,
    min_bend_radius_node: usize,
    cable_min_bend_radius_mm: f64,
    stretch: f64,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let cable = CableSpec::from_file(&args.cable).map_err(Failure::input)?;
    let sub_segments =
        sub_segment_count(args.length_mm, cable.sub_segment_pitch_m).map_err(Failure::input)?;
    let geometry = connect(
        &args.start,
        &args.end,
        sub_segments,
        cable.sub_segment_pitch_m,
        &-nalgebra::Vector3::z_axis(),
    )
    .map_err(|e| match e {
        ConnectError::InvalidInput { .. } => Failure::input(e),
        ConnectError::TooShort { .. } | ConnectError::NoSolution { .. } => Failure::unsolved(e),
    })?;
    let report = SegmentReport::of(args.stage, &cable, &args, &geometry);
    if args.json {
        print_json(&report)
    } else {
        emit(&report.to_string())
    }
}

/// The number of sub-segments in `length_mm`, refusing lengths that are not a whole number.
fn sub_segment_count(length_mm: f64, pitch_m: f64) -> anyhow::Result<usize> {
    let pitch_mm = pitch_m * 1e3;
    let count = (length_mm / pitch_mm).round();
    if !(length_mm.is_finite() && count >= 1.0 && (count * pitch_mm - length_mm).abs() < 1e-6) {
        anyhow::bail!(
            "--length-mm {length_mm}: must be a positive whole number of {pitch_mm} mm sub-segments (the cable's sub_segment_pitch_mm)"
        );
    }
    Ok(count as usize)
}

impl SegmentReport {
    fn of(stage: Stage, cable: &CableSpec, args: &Args, geometry: &ConnectedGeometry) -> Self {
        let z = |pose: &Pose| pose.rotation * nalgebra::Vector3::z();
        let bend: BendRadius = min_bend_radius(
            &geometry.nodes,
            &z(&args.start),
            &z(&args.end),
            geometry.pitch_m,
        );
        SegmentReport {
            stage,
            cable: cable.name.clone(),
            curve: match geometry.curve {
                CurveFamily::Hermite => "hermite",
                CurveFamily::Bowed => "bowed",
            },
            alpha_m: geometry.alpha_m,
            bow_m: geometry.bow_m,
            length_mm: geometry.natural_length_m() * 1e3,
            sub_segments: geometry.sub_segment_count(),
            pitch_mm: geometry.pitch_m * 1e3,
            twist_correction_deg: geometry.twist_correction_rad.to_degrees(),
            nodes_mm: geometry
                .nodes
                .iter()
                .map(|p| (p.coords * 1e3).into())
                .collect(),
            frames: geometry.frames.iter().map(matrix_rows).collect(),
            metrics: Metrics {
                min_bend_radius_mm: bend.radius_m.is_finite().then_some(bend.radius_m * 1e3),
                min_bend_radius_node: bend.node,
                cable_min_bend_radius_mm: cable.min_bend_radius_m * 1e3,
                stretch: stretch(&geometry.nodes, geometry.natural_length_m()),
            },
        }
    }
}

impl fmt::Display for SegmentReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = &self.metrics;
        writeln!(
            f,
            "{:?} geometry of {}: {} mm = {} sub-segments of {} mm",
            self.stage, self.cable, self.length_mm, self.sub_segments, self.pitch_mm
        )?;
        writeln!(f, "  curve             {}", self.curve)?;
        writeln!(f, "  alpha             {:.6} m", self.alpha_m)?;
        if self.bow_m != 0.0 {
            writeln!(f, "  bow               {:.6} m", self.bow_m)?;
        }
        writeln!(f, "  twist correction  {:.3}°", self.twist_correction_deg)?;
        match m.min_bend_radius_mm {
            Some(r) => {
                let verdict = if r >= m.cable_min_bend_radius_mm {
                    "ok"
                } else {
                    "TOO TIGHT"
                };
                writeln!(
                    f,
                    "  min bend radius   {r:.1} mm at node {} (cable minimum {:.1} mm: {verdict})",
                    m.min_bend_radius_node, m.cable_min_bend_radius_mm
                )?;
            }
            None => writeln!(f, "  min bend radius   ∞ (straight)")?,
        }
        writeln!(f, "  stretch           {:.6}", m.stretch)?;
        writeln!(f, "  nodes (mm):")?;
        for (i, p) in self.nodes_mm.iter().enumerate() {
            writeln!(f, "    {i:>4}  {:>9.3} {:>9.3} {:>9.3}", p[0], p[1], p[2])?;
        }
        Ok(())
    }
}
