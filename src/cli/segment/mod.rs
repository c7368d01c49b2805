//! `cable-dict segment`: one cable segment between two guide frames in free space.

mod obstacles;
mod report;

use super::args;
use super::output::{Failure, emit, print_json};
use cable_dict::cable::CableSpec;
use cable_dict::pose::Pose;
use cable_dict::report::scene::{CableLine, ClampPart, GuideMark, PoseScene, SceneSpec};
use cable_dict::robot::Robot;
use cable_dict::segment::{ConnectKind, PieceError, PieceRequest, SolverKind, connected};
use nalgebra::{Point3, Vector3};
use report::SegmentReport;
use serde::Serialize;
use std::path::{Path, PathBuf};

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
    /// Which shape to compute: `connected` (the start shape, no physics) or `converged` (the
    /// static equilibrium under gravity, started from the connected shape).
    #[arg(long, value_enum, default_value_t = Stage::Converged)]
    stage: Stage,
    /// Static solver of the converged stage.
    #[arg(long, value_enum, default_value_t = Solver::QuasiStatic)]
    solver: Solver,
    /// Whole turns of twist added at the end guide about the cable (right-handed about its
    /// +z axis; negative: the other way), beyond what the guide frames define — a frame fixes
    /// the twist only up to whole turns. Reached by turning the end guide in steps of at most
    /// 15°, each solved from the previous shape (quasi-static solver, converged stage).
    #[arg(long, value_name = "N", default_value_t = 0, allow_hyphen_values = true,
          value_parser = clap::value_parser!(i32).range(-MAX_TWIST_TURNS..=MAX_TWIST_TURNS))]
    twist_turns: i32,
    /// How the connected geometry is obtained: `hermite` (Hermite curve + rotation-minimizing
    /// frames) or `linear` (the paper's previous method: a straight cable dragged into the end
    /// guide by the physics engine; slow, for comparison).
    #[arg(long, value_enum, default_value_t = Connect::Hermite)]
    connect: Connect,
    /// A robot whose links are obstacles for the contact metric; the guide frames are then in
    /// its base frame. Needs --joints-deg.
    #[arg(long, value_name = "URDF", requires = "joints_deg")]
    robot: Option<PathBuf>,
    /// The robot's joint values for --robot, in `robot-info` order (deg; mm for prismatic).
    #[arg(long, value_name = "A,B,C,…", requires = "robot", allow_hyphen_values = true, value_parser = args::number_list_arg)]
    joints_deg: Option<args::NumberList>,
    /// Link the start guide is screwed to: the cable next to it (--clamp-zone-mm) is not
    /// checked against that link.
    #[arg(long, value_name = "LINK", requires = "robot")]
    start_link: Option<String>,
    /// Link the end guide is screwed to, as --start-link.
    #[arg(long, value_name = "LINK", requires = "robot")]
    end_link: Option<String>,
    /// Cable length next to a guide that is not checked against the guide's own link (mm).
    #[arg(long, value_name = "MM", default_value_t = 20.0)]
    clamp_zone_mm: f64,
    /// Contact threshold: a clearance below this is a violation (mm; 0 = no contact).
    #[arg(
        long,
        value_name = "MM",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    contact_threshold_mm: f64,
    /// Gravity in the world frame, gx,gy,gz (m/s²).
    #[arg(long, value_name = "GX,GY,GZ", default_value = "0,0,-9.81", allow_hyphen_values = true, value_parser = args::vector3)]
    gravity: Vector3<f64>,
    /// Print JSON: the connected stage (curve, alpha_m, nodes_mm, frames, metrics) and, for
    /// the converged stage, a `converged` object with its nodes, frames, metrics, iterations,
    /// residual and solve time.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "snake_case")]
enum Stage {
    /// Hermite curve + rotation-minimizing frames (no physics).
    Connected,
    /// Static equilibrium under gravity, clamped at both guides.
    Converged,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
enum Solver {
    /// Newton's method on the cable's potential energy (0.04–0.14 ms for 250–500 mm;
    /// docs/physics.md, "Cable physics").
    QuasiStatic,
    /// Damped rigid-body relaxation in rapier3d (the paper's baseline; 14–66 ms for 250–500
    /// mm, 340–470× slower).
    Rapier,
}

impl Solver {
    /// For people: `quasi-static`, `rapier rigid-chain`.
    fn describe(self) -> &'static str {
        match self {
            Solver::QuasiStatic => "quasi-static",
            Solver::Rapier => "rapier rigid-chain",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum)]
enum Connect {
    /// Hermite curve + rotation-minimizing frames.
    Hermite,
    /// A straight cable dragged into the end guide by the physics engine.
    Linear,
}

/// Most whole turns `--twist-turns` takes: beyond a few turns every real cable has writhed
/// into loops long before (and each turn costs 24 solves or more).
const MAX_TWIST_TURNS: i64 = 100;

pub fn run(args: Args) -> Result<(), Failure> {
    run_with_scene(args, None)
}

/// `segment`, and with `scene_file` also its scene (`export-scene segment`).
pub fn run_with_scene(args: Args, scene_file: Option<&Path>) -> Result<(), Failure> {
    if args.twist_turns != 0
        && (args.stage != Stage::Converged || args.solver != Solver::QuasiStatic)
    {
        return Err(Failure::input(anyhow::anyhow!(
            "--twist-turns turns the end guide of the static equilibrium: it needs --stage \
             converged and --solver quasi-static"
        )));
    }
    let cable = CableSpec::from_file(&args.cable).map_err(Failure::input)?;
    let sub_segments =
        sub_segment_count(args.length_mm, cable.sub_segment_pitch_m).map_err(Failure::input)?;
    let scene = obstacles::Scene::from_args(&args, &cable)?;
    let request = PieceRequest {
        start: args.start,
        end: args.end,
        gravity_m_s2: args.gravity,
        connect: match args.connect {
            Connect::Hermite => ConnectKind::Hermite,
            Connect::Linear => ConnectKind::Linear,
        },
        solver: match args.solver {
            Solver::QuasiStatic => SolverKind::QuasiStatic,
            Solver::Rapier => SolverKind::Rapier,
        },
        twist_turns: args.twist_turns,
    };
    let failure = |e: PieceError| match e {
        PieceError::Input(_) => Failure::input(e),
        PieceError::NoShape(_) => Failure::unsolved(e),
    };
    let connected = connected(&cable, &request, sub_segments).map_err(failure)?;
    let mut report = SegmentReport::new(&cable, &args, sub_segments, &connected, scene.as_ref())?;
    let mut nodes = &connected.nodes;
    let converged;
    if args.stage == Stage::Converged {
        converged =
            cable_dict::segment::converged(&cable, &request, &connected).map_err(failure)?;
        report.add_converged(&cable, &args, &converged, scene.as_ref())?;
        nodes = &converged.nodes;
    }
    if let Some(file) = scene_file {
        write_scene(file, &args, &cable, nodes, scene.as_ref())?;
    }
    if args.json {
        print_json(&report)
    } else {
        emit(&report.to_string())
    }
}

/// The segment's scene: its shape, its two guides, and the robot when there is one (the
/// guide frames are in its base frame, else in a robot-less world).
fn write_scene(
    file: &Path,
    args: &Args,
    cable: &CableSpec,
    nodes: &[Point3<f64>],
    scene: Option<&obstacles::Scene>,
) -> Result<(), Failure> {
    let world = Robot::world_only();
    let (robot, link_poses) = match scene {
        Some(scene) => (scene.robot(), scene.link_poses().to_vec()),
        None => (&world, vec![Pose::identity()]),
    };
    let base = link_poses[0];
    let guide = |name: &str, frame: &Pose| GuideMark {
        name: name.into(),
        clamp: name.into(),
        link: 0,
        pose_in_link: base.inverse() * frame,
        part: ClampPart::Rigid,
    };
    let spec = SceneSpec {
        robot,
        cable_radius_m: 0.5 * cable.diameter_m,
        main: PoseScene {
            link_poses,
            cable: vec![CableLine {
                name: "segment".into(),
                nodes_m: nodes.to_vec(),
            }],
        },
        guides: vec![
            guide("start guide", &args.start),
            guide("end guide", &args.end),
        ],
        animation: None,
        other_motions: Vec::new(),
        snapshots: Vec::new(),
        tints: Vec::new(),
        damage: Vec::new(),
        installation: None,
    };
    super::output::write_glb(file, &spec)
}

/// The number of sub-segments in `length_mm`, refusing lengths that are not a whole number.
fn sub_segment_count(length_mm: f64, pitch_m: f64) -> anyhow::Result<usize> {
    match args::whole_sub_segments(length_mm, pitch_m) {
        Some(count) if count >= 1 => Ok(count),
        _ => anyhow::bail!(
            "--length-mm {length_mm}: must be a positive whole number of {} mm sub-segments (the cable's sub_segment_pitch_mm)",
            pitch_m * 1e3
        ),
    }
}
