//! `cable-dict export-scene`: a glTF scene of one candidate, for looking at what the solver
//! rejected — a whole cable path at a pose, or one `segment`.

use super::fk::joint_vector_si;
use super::output::{Failure, emit, write_glb};
use super::result_file::ResultFile;
use super::{args, segment};
use cable_dict::attachment::{ConnectMethod, Evaluator};
use cable_dict::motion::Motion;
use cable_dict::path::CablePath;
use cable_dict::report::views::pose_scene;
use cable_dict::setup::Setup;
use cable_dict::solve::path_shape;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    what: What,
}

#[derive(Debug, clap::Subcommand)]
enum What {
    /// A whole cable path of a setup with the robot at one pose: each cable piece's
    /// static equilibrium, and whether it holds the limits there.
    Path(PathArgs),
    /// One segment, as `cable-dict segment` computes it (same options).
    Segment(Box<SegmentSceneArgs>),
}

#[derive(Debug, clap::Args)]
struct PathArgs {
    /// The setup file.
    #[arg(long, value_name = "SETUP.toml")]
    setup: PathBuf,
    /// Take the path from a result JSON (`solve --json` / `-o` / report's result.json).
    #[arg(long, value_name = "RESULT.json", conflicts_with_all = ["lengths_mm", "configurations"])]
    result: Option<PathBuf>,
    /// With --result: the candidate of that rank (1 = shortest tried); default: the one
    /// that passed, else the closest miss, else the last one tried.
    #[arg(long, value_name = "RANK", requires = "result")]
    candidate: Option<usize>,
    /// The path's piece lengths from the base end (mm): one per segment, or one per span
    /// where optional guides are left out.
    #[arg(long, value_name = "L1,L2,…", requires = "configurations", allow_hyphen_values = true, value_parser = args::number_list_arg)]
    lengths_mm: Option<args::NumberList>,
    /// The path's guide configurations by name, G1 first (comma-separated); `-` for an
    /// optional guide the path leaves out.
    #[arg(
        long,
        value_name = "NAME,NAME,…",
        requires = "lengths_mm",
        value_delimiter = ','
    )]
    configurations: Option<Vec<String>>,
    /// The robot pose, one value per joint (deg; mm for prismatic joints).
    #[arg(long, value_name = "A,B,C,…", allow_hyphen_values = true, value_parser = args::number_list_arg, conflicts_with = "motion")]
    joints_deg: Option<args::NumberList>,
    /// Take the pose from this motion CSV at --time-s.
    #[arg(long, value_name = "MOTION.csv")]
    motion: Option<PathBuf>,
    /// Time in the motion (s; between samples the joints are interpolated).
    #[arg(long, value_name = "T", requires = "motion")]
    time_s: Option<f64>,
    /// The scene file to write (replaced atomically).
    #[arg(short, long, value_name = "SCENE.glb")]
    output: PathBuf,
}

#[derive(Debug, clap::Args)]
struct SegmentSceneArgs {
    #[command(flatten)]
    segment: segment::Args,
    /// The scene file to write (replaced atomically).
    #[arg(short, long, value_name = "SCENE.glb")]
    output: PathBuf,
}

pub fn run(args: Args) -> Result<(), Failure> {
    match args.what {
        What::Path(args) => run_path(args),
        What::Segment(args) => segment::run_with_scene(args.segment, Some(&args.output)),
    }
}

fn run_path(args: PathArgs) -> Result<(), Failure> {
    let setup = Setup::from_file(&args.setup).map_err(Failure::input)?;
    let (path, motion_test) = chosen_path(&args, &setup)?;
    let joints = chosen_pose(&args, &setup)?;
    let shape = path_shape(&setup, &path, &joints).map_err(Failure::input)?;
    let spec = pose_scene(&setup, &path, &shape);
    write_glb(&args.output, &spec)?;
    let checks = path_checks(&setup, &path, &spec.main.link_poses)?;
    emit(&(motion_test.map_or(String::new(), |m| m + "\n") + &checks))
}

/// Writes `spec` as a `.glb` file; an unwritable file is a bad argument.
/// The path of --result or of --lengths-mm / --configurations, checked against the setup,
/// and (from a result) what the motion test said of it.
fn chosen_path(args: &PathArgs, setup: &Setup) -> Result<(CablePath, Option<String>), Failure> {
    let (path, motion_test) = match (&args.result, &args.lengths_mm, &args.configurations) {
        (Some(file), _, _) => {
            let chosen = ResultFile::read(file)?.chosen(args.candidate)?;
            (chosen.path, Some(chosen.motion_test))
        }
        (None, Some(lengths), Some(names)) => (path_from_names(setup, &lengths.0, names)?, None),
        _ => {
            return Err(Failure::input(anyhow::anyhow!(
                "give --result, or --lengths-mm with --configurations"
            )));
        }
    };
    check_path(setup, &path)?;
    Ok((path, motion_test))
}

/// The path of lengths (mm) and configuration names.
fn path_from_names(
    setup: &Setup,
    lengths_mm: &[f64],
    names: &[String],
) -> Result<CablePath, Failure> {
    let pitch_m = setup.cable.sub_segment_pitch_m;
    let lengths = lengths_mm
        .iter()
        .map(|&mm| {
            args::whole_sub_segments(mm, pitch_m).ok_or_else(|| {
                Failure::input(anyhow::anyhow!(
                    "--lengths-mm {mm}: not a whole number of {} mm sub-segments",
                    pitch_m * 1e3
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if names.len() != setup.guides.len() {
        return Err(Failure::input(anyhow::anyhow!(
            "--configurations: {} names for the {} guides of {} (`-` for a guide left out)",
            names.len(),
            setup.guides.len(),
            setup.source.display()
        )));
    }
    let mut mounted: Vec<(usize, usize)> = Vec::new();
    for (g, (guide, name)) in setup.guides.iter().zip(names).enumerate() {
        if name == "-" {
            if !guide.optional {
                return Err(Failure::input(anyhow::anyhow!(
                    "--configurations: {} is not optional, it needs a configuration",
                    guide.name
                )));
            }
            continue;
        }
        let c = guide.configuration_index(name).ok_or_else(|| {
            let known: Vec<&str> = guide
                .configurations
                .iter()
                .map(|c| c.name.as_str())
                .collect();
            Failure::input(anyhow::anyhow!(
                "--configurations: {} has no configuration '{name}' (it has {})",
                guide.name,
                known.join(", ")
            ))
        })?;
        mounted.push((g, c));
    }
    let segments = mounted
        .windows(2)
        .map(|pair| {
            let ends = (pair[0].0, pair[1].0);
            (0..setup.segment_count())
                .find(|&m| setup.segment_guides(m) == ends)
                .ok_or_else(|| {
                    Failure::input(anyhow::anyhow!(
                        "--configurations: no segment joins {} and {}",
                        setup.guides[ends.0].name,
                        setup.guides[ends.1].name
                    ))
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(CablePath {
        segments,
        lengths,
        configurations: mounted.into_iter().map(|(_, c)| c).collect(),
    })
}

/// Refuses a path whose counts or indices do not fit the setup.
fn check_path(setup: &Setup, path: &CablePath) -> Result<(), Failure> {
    path.check(setup).map_err(|e| {
        Failure::input(anyhow::anyhow!(
            "the path does not fit {}: {e}",
            setup.source.display()
        ))
    })
}

/// The joint vector (rad / m) of --joints-deg or of --motion at --time-s (its first sample
/// by default).
fn chosen_pose(args: &PathArgs, setup: &Setup) -> Result<Vec<f64>, Failure> {
    let robot = &setup.robot;
    let joints = match (&args.joints_deg, &args.motion) {
        (Some(values), _) => joint_vector_si(robot, &values.0),
        (None, Some(file)) => {
            let motion = Motion::from_csv_file(robot, file).map_err(Failure::input)?;
            let t = args.time_s.unwrap_or(motion.times_s()[0]);
            if !t.is_finite() {
                return Err(Failure::input(anyhow::anyhow!("--time-s {t}: not a time")));
            }
            motion.joints_at(t)
        }
        (None, None) => {
            return Err(Failure::input(anyhow::anyhow!(
                "give the pose: --joints-deg, or --motion (with --time-s)"
            )));
        }
    };
    robot
        .check_limits(&joints)
        .map_err(|e| Failure::input(anyhow::anyhow!("the pose: {e}")))?;
    Ok(joints)
}

/// One line per segment: the attachment test's verdict on its piece at this pose (static
/// equilibrium; the motion test is another matter).
fn path_checks(
    setup: &Setup,
    path: &CablePath,
    link_poses: &[cable_dict::pose::Pose],
) -> Result<String, Failure> {
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite).map_err(Failure::input)?;
    let mut text = String::new();
    for (i, (m, pv)) in path.pieces().enumerate() {
        let check = evaluator.check_at(m, &pv, link_poses);
        let verdict = match (&check.rejection, &check.detail) {
            (None, _) => "holds the limits at this pose".to_string(),
            (Some(r), Some(detail)) => format!("{}: {detail}", r.name()),
            (Some(r), None) => r.name().to_string(),
        };
        let metrics = check.metrics.map_or(String::new(), |x| {
            let clearance = x
                .clearance_m
                .map_or("-".into(), |c| format!("{:.1} mm", c * 1e3));
            format!(
                " (clearance {clearance}, stretch {:.4}, bend radius {:.1} mm)",
                x.stretch,
                x.min_bend_radius_m * 1e3
            )
        });
        let _ = writeln!(
            text,
            "{} {:.0} mm: {verdict}{metrics}",
            setup.segment_name(m),
            path.lengths[i] as f64 * setup.cable.sub_segment_pitch_m * 1e3
        );
    }
    Ok(text)
}
