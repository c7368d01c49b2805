//! `cable-dict solve` and `cable-dict critical-poses`: a setup and a motion → the optimal
//! cable path, or the poses each segment is tested at.

use super::args::{non_negative, setup_and_motions};
use super::output::{Failure, emit, print_json};
use super::provenance::open_verified;
use cable_dict::atomic_file::write_atomically;
use cable_dict::attachment::{ConnectMethod, IntraLinkCriterion, SegmentPoses};
use cable_dict::motion::{Cell, JointRanges, Motion};
use cable_dict::motion_test::EngineKind;
use cable_dict::report::{ReportError, check_report_folder, write_report};
use cable_dict::setup::Setup;
use cable_dict::solve::{
    DEFAULT_GRID_STEP_DEG, LifeGoal, ReportShapes, SearchKind, Solution, SolveError, SolveOptions,
    SolveReport, allowed_box, allowed_ranges, guide_names, solve_cell, solve_ranges,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The setup file (robot, cable, guide candidates, segment lengths, limits; see
    /// docs/setup-format.md). Optional with --dict (which embeds its setup); given with it,
    /// it must have the dictionary's robot, cable, gravity, limits and installation pose and
    /// take its intra-link clamps from the dictionary's places.
    /// Also accepted as the first file: `solve SETUP.toml MOTION.csv`.
    #[arg(long, value_name = "SETUP.toml")]
    setup: Option<PathBuf>,
    /// Answer the intra-link segments' pieces from this dictionary (cable-dict build): the
    /// same sets as solving them, faster; the pieces its margins cannot decide are solved.
    #[arg(long, value_name = "DICT.cdict")]
    dict: Option<PathBuf>,
    #[command(flatten)]
    trust: super::provenance::Trust,
    /// The motion CSV (see motions/README.md), after the setup when the setup is not given
    /// as --setup. Several motions (or a cell file naming them, docs/commands.md, "Cells"):
    /// one cable path that holds every limit over every one of them.
    #[arg(
        value_name = "[SETUP.toml] MOTION.csv|CELL.toml",
        num_args = 1..,
        required_unless_present = "ranges"
    )]
    files: Vec<PathBuf>,
    /// Design for axis ranges (a `[joints]` table, `name = [min_deg, max_deg]`; docs/commands.md,
    /// "Axis ranges"): the path must hold over stress motions that drive each ranged axis
    /// end to end at its URDF speed, alone and together (and over the motions given, if any).
    /// and every piece at a grid of the box's static poses (--grid-step-deg).
    #[arg(long, value_name = "RANGES.toml")]
    ranges: Option<PathBuf>,
    /// The step of the axis-range grid of --ranges (degrees; millimetres for a prismatic
    /// joint): each piece is tested at the box's poses of the joints that shape it, this far
    /// apart.
    #[arg(long, value_name = "DEG", default_value_t = DEFAULT_GRID_STEP_DEG, requires = "ranges")]
    grid_step_deg: f64,
    /// How often each motion given runs per hour (a cell file's own `cycles_per_hour` comes
    /// first): the predicted life is then also given in hours and years (with a rated life
    /// or the conductors' offset in the cable file).
    #[arg(long, value_name = "N", value_parser = non_negative)]
    cycles_per_hour: Option<f64>,

    /// Also write the box --ranges answered (the box asked, or the narrowed one, with the
    /// stress motions' time to full speed it needed) as a ranges file, for `check --ranges`
    /// (replaced atomically).
    #[arg(long, value_name = "ANSWERED.toml", requires = "ranges")]
    write_ranges: Option<PathBuf>,
    /// Also find the range each axis allows the answer, the others anywhere in the box of
    /// --ranges (the box answered), else in the motions' extremes: scanned outward on a grid
    /// this far apart (degrees; mm), each end found to 1° (docs/commands.md, "Allowed
    /// ranges").
    #[arg(long, value_name = "STEP_DEG", num_args = 0..=1, default_missing_value = "10")]
    allowed_ranges: Option<f64>,
    /// Print the result as JSON instead of the summary.
    #[arg(long)]
    json: bool,
    /// Also write the result JSON to this file (replaced atomically).
    #[arg(short, long, value_name = "RESULT.json")]
    output: Option<PathBuf>,
    /// Also write a report folder: result.json, summary.md, plots (SVG), a 3D scene
    /// (scene.glb) and index.html to open in a browser.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// 1: one clamp per link (two guides on one link must then coincide, length 0); 2: as
    /// many clamps as the setup declares.
    #[arg(long, value_name = "1|2", value_parser = clap::value_parser!(u8).range(1..=2))]
    max_guides_per_link: Option<u8>,
    /// How the attachment test shapes a segment: `hermite` (Hermite curve + quasi-static
    /// solver) or `linear` (the paper's previous method: a straight cable dragged into place
    /// and relaxed in rapier3d; very slow).
    #[arg(long, value_enum, default_value_t = Connect::Hermite)]
    connect: Connect,
    /// Chains tried in the motion test, shortest first, before giving up.
    #[arg(long, value_name = "N", default_value_t = 50)]
    k_best: usize,
    /// Skip the motion test: report the shortest chain of robust cable pieces.
    #[arg(long)]
    no_motion_test: bool,
    /// Skip the static sweep of each candidate's cable pieces over every motion pose before its
    /// dynamic motion test (the paper's pipeline: critical poses, then dynamics only).
    #[arg(long)]
    no_static_sweep: bool,
    /// Do not learn from failed motion tests: without it, the pieces whose static shapes keep
    /// less inside a limit than their segment's cable swung past its static shapes in a
    /// failed test are set aside while other chains remain (the answer then says how much
    /// shorter a chain with them is); with it, chains go to the motion test strictly
    /// shortest first.
    #[arg(long)]
    no_learning: bool,
    /// Test every candidate cable piece before searching the chains (the paper's order),
    /// instead of only the pieces a chain shorter than the answer could use: the same path,
    /// slower; the reference the default search is checked against
    #[arg(long)]
    exhaustive: bool,
    /// What simulates the cable in the motion test: `implicit` (the statics' cable model
    /// integrated in time; at rest it is the static equilibrium) or `rigid-chain` (rapier3d
    /// rigid bodies, the paper's baseline; slower, and it drifts from the static shape for
    /// stiff cables).
    #[arg(long, value_enum, default_value_t = MotionEngine::Implicit)]
    motion_engine: MotionEngine,
    /// Where pieces between two clamps on one link are tested: `gravity-directions` (under
    /// every direction of gravity the motion produces in the link's frame, to 3°; what a
    /// dictionary answers) or `first-pose` (the paper's rule: one pose, the motion's first).
    #[arg(long, value_enum, default_value_t = IntraLink::GravityDirections)]
    intra_link: IntraLink,
    /// The shortest path that holds every limit and whose predicted life is at least N cycles
    /// (of the motion; of a round of the cell's motions). Needs a [rated_life] or
    /// conductor_offset_mm in the cable file.
    #[arg(long, value_name = "N", value_parser = non_negative, conflicts_with = "prefer")]
    min_life_cycles: Option<f64>,
    /// `life`: among the paths that hold every limit and are at most --within-mm longer than
    /// the shortest such path, the one with the longest predicted life.
    #[arg(long, value_enum, requires = "within_mm")]
    prefer: Option<Prefer>,
    /// How much longer than the shortest path that holds every limit a path --prefer life
    /// may be (mm).
    #[arg(long, value_name = "MM", value_parser = non_negative, requires = "prefer")]
    within_mm: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum)]
enum Prefer {
    /// The longest predicted life within --within-mm of the shortest path.
    Life,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum)]
enum IntraLink {
    /// Every gravity direction of the motion in the link's frame.
    GravityDirections,
    /// The motion's first pose only.
    FirstPose,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum)]
enum MotionEngine {
    /// BDF2 on the energy of the static solver.
    Implicit,
    /// rapier3d rigid sub-segments and joint springs.
    RigidChain,
}

#[derive(Debug, Clone, Copy, PartialEq, clap::ValueEnum)]
enum Connect {
    /// Hermite curve + rotation-minimizing frames, then the quasi-static solver.
    Hermite,
    /// A straight cable dragged into the end guide and relaxed by the physics engine.
    Linear,
}

/// Runs `solve`; with `verbose` (`-v`) the printed summary carries the search's details.
pub fn run(args: Args, verbose: bool) -> Result<(), Failure> {
    if let Some(dir) = &args.report {
        check_report_folder(dir).map_err(Failure::input)?;
    }
    let dictionary = args.dict.as_deref().map(open_verified).transpose()?;
    let provenance = match &dictionary {
        Some(dictionary) => {
            let provenance = args.trust.check(dictionary)?;
            if !provenance.is_trusted() {
                // Accepted: every piece an answer takes from the file is solved again.
                log::warn!("{}: {}", dictionary.path().display(), provenance.describe());
            }
            Some(provenance)
        }
        None if args.trust.is_given() => {
            return Err(Failure::input(anyhow::anyhow!(
                "--trusted-keys and --require-signature check a dictionary: give --dict"
            )));
        }
        None => None,
    };
    let (setup_path, motion_paths) = match (&args.ranges, args.files.as_slice()) {
        (Some(_), []) => (args.setup.as_deref(), &[][..]),
        _ => setup_and_motions(
            args.setup.as_deref(),
            &args.files,
            Some(dictionary.is_some()),
        )
        .map_err(|e| Failure::input(anyhow::anyhow!(e)))?,
    };
    let setup = match (setup_path, &dictionary) {
        (Some(path), _) => Setup::from_file(path).map_err(Failure::input)?,
        (None, Some(dictionary)) => dictionary.setup().map_err(Failure::input)?,
        (None, None) => {
            return Err(Failure::input(anyhow::anyhow!(
                "give the setup (--setup SETUP.toml) or a dictionary (--dict)"
            )));
        }
    };
    let options = SolveOptions {
        method: match args.connect {
            Connect::Hermite => ConnectMethod::Hermite,
            Connect::Linear => ConnectMethod::Linear,
        },
        max_guides_per_link: args.max_guides_per_link.map(usize::from),
        k_best: args.k_best,
        motion_test: !args.no_motion_test,
        static_sweep: !args.no_static_sweep,
        learn: !args.no_learning,
        search: if args.exhaustive {
            SearchKind::Exhaustive
        } else {
            SearchKind::Lazy
        },
        shape_interval_s: args.report.is_some().then_some(SCENE_FRAME_INTERVAL_S),
        engine: match args.motion_engine {
            MotionEngine::Implicit => EngineKind::Implicit,
            MotionEngine::RigidChain => EngineKind::RigidChain,
        },
        intra_link: match args.intra_link {
            IntraLink::GravityDirections => IntraLinkCriterion::GravityDirections,
            IntraLink::FirstPose => IntraLinkCriterion::FirstPose,
        },
        diagnose: true,
        life_goal: match (args.min_life_cycles, args.prefer, args.within_mm) {
            (Some(cycles), _, _) => Some(LifeGoal::AtLeast { cycles }),
            (None, Some(Prefer::Life), Some(within_mm)) => Some(LifeGoal::Longest { within_mm }),
            _ => None,
        },
    };
    let given = (!motion_paths.is_empty())
        .then(|| Cell::from_files(&setup.robot, motion_paths))
        .transpose()
        .map_err(Failure::input)?
        .map(|cell| cell.running(args.cycles_per_hour));
    let failure = |e: SolveError| match e {
        SolveError::Options(_)
        | SolveError::Setup(_)
        | SolveError::Motion(_)
        | SolveError::Obstacles(_)
        | SolveError::Dictionary(_) => Failure::input(e),
        SolveError::Chain(_) | SolveError::MotionTest(_) => Failure::unsolved(e),
    };
    let (mut solution, cell, within) = match (&args.ranges, given) {
        (Some(ranges), given) => {
            let asked = JointRanges::from_file(&setup.robot, ranges).map_err(Failure::input)?;
            let step = args.grid_step_deg;
            let (solution, cell, answered) = solve_ranges(
                &setup,
                &asked,
                given.as_ref(),
                step,
                &options,
                dictionary.as_ref(),
            )
            .map_err(failure)?;
            let narrowed = answered != asked;
            if let Some(path) = &args.write_ranges {
                let comment = format!(
                    "The box `cable-dict solve --ranges {}` answered on {} ({}).\n\
                     Check a mounting over it: cable-dict check RESULT.json --ranges {}",
                    ranges.display(),
                    setup.source.display(),
                    match (answered.ranges == asked.ranges, narrowed) {
                        (false, _) => "narrowed: the box asked has no path".to_string(),
                        (true, true) => format!(
                            "the box asked, at a gentler acceleration: full speed in {} s, not {} s",
                            answered.time_to_full_speed_s, asked.time_to_full_speed_s
                        ),
                        (true, false) => "the box asked".to_string(),
                    },
                    path.display()
                );
                write_atomically(path, answered.to_toml(&setup.robot, &comment).as_bytes())
                    .map_err(|e| {
                        Failure::input(anyhow::anyhow!("cannot write {}: {e}", path.display()))
                    })?;
            }
            (
                solution,
                cell,
                allowed_box(Some((&answered, narrowed)), None),
            )
        }
        (None, Some(cell)) => {
            let solution =
                solve_cell(&setup, &cell, &options, dictionary.as_ref()).map_err(failure)?;
            let within = allowed_box(None, Some(&cell));
            (solution, cell, within)
        }
        (None, None) => return Err(Failure::input(anyhow::anyhow!("give the motion"))),
    };
    if let (Some(step), Some((box_, words)), Some(path)) =
        (args.allowed_ranges, &within, solution.answer())
    {
        let allowed =
            allowed_ranges(&solution.setup, path, box_, words, step, &options).map_err(failure)?;
        solution.report.allowed_ranges = Some(allowed);
    }
    let Solution {
        mut report,
        setup: solved,
    } = solution;
    if let Some(used) = &mut report.inputs.dictionary {
        used.provenance = provenance;
    }
    if let Some(path) = &args.output {
        let text = cable_dict::json::to_pretty_string(&report)
            .map_err(|e| Failure::unsolved(anyhow::anyhow!("cannot encode the result: {e}")))?;
        write_atomically(path, (text + "\n").as_bytes())
            .map_err(|e| Failure::input(anyhow::anyhow!("cannot write {}: {e}", path.display())))?;
    }
    if let Some(dir) = &args.report {
        let motions: Vec<&Motion> = cell.motions().collect();
        write_report_folder(dir, &solved, &motions, &report)?;
    }
    if args.json {
        print_json(&report)?;
    } else {
        // `-v`: the search's details as well.
        emit(&match verbose {
            true => format!("{report:#}"),
            false => report.to_string(),
        })?;
    }
    // "No cable path" is an answer, not a failure: exit 0 like "solved" (the status says which).
    Ok(())
}

/// Keyframe interval of the report scene's animation (s): 30 frames per second.
const SCENE_FRAME_INTERVAL_S: f64 = 1.0 / 30.0;

/// Writes the `--report` folder of `report`, solved with `solved`; an unwritable folder is a
/// bad argument.
fn write_report_folder(
    dir: &Path,
    solved: &Setup,
    motions: &[&Motion],
    report: &SolveReport,
) -> Result<(), Failure> {
    let clock = std::time::Instant::now();
    let shapes = ReportShapes::of(solved, motions, report).map_err(Failure::unsolved)?;
    let files = write_report(dir, solved, motions, report, &shapes).map_err(|e| match e {
        ReportError::Write { .. } => Failure::input(e),
        _ => Failure::unsolved(e),
    })?;
    log::info!(
        "report: {} files in {}, {:.2} s",
        files.len(),
        dir.display(),
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}

#[derive(Debug, clap::Args)]
pub struct CriticalArgs {
    /// The setup file; also accepted as the first file: `critical-poses SETUP.toml MOTION.csv`.
    #[arg(long, value_name = "SETUP.toml")]
    setup: Option<PathBuf>,
    /// The motion CSV, after the setup when the setup is not given as --setup; several
    /// motions (or a cell file): the poses of all of them, each tested once.
    #[arg(value_name = "[SETUP.toml] MOTION.csv|CELL.toml", num_args = 1.., required = true)]
    files: Vec<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(serde::Serialize)]
struct SegmentPosesJson {
    segment: String,
    guides: [String; 2],
    links: [String; 2],
    intra_link: bool,
    traversed_joints: Vec<String>,
    poses: Vec<cable_dict::solve::PoseSummary>,
}

pub fn run_critical(args: CriticalArgs) -> Result<(), Failure> {
    let usage = |e: String| Failure::input(anyhow::anyhow!(e));
    let (setup, motions) =
        setup_and_motions(args.setup.as_deref(), &args.files, None).map_err(usage)?;
    let setup = setup.ok_or_else(|| usage("give the setup: --setup SETUP.toml".into()))?;
    let setup = Setup::from_file(setup).map_err(Failure::input)?;
    let cell = Cell::from_files(&setup.robot, motions).map_err(Failure::input)?;
    let poses = SegmentPoses::for_cell(&setup, &cell, IntraLinkCriterion::default())
        .map_err(Failure::input)?;
    let motion = &cell.motions[0].motion;
    let segments: Vec<SegmentPosesJson> = (0..setup.segment_count())
        .map(|m| {
            let (guides, links) = guide_names(&setup, m);
            SegmentPosesJson {
                segment: setup.segment_name(m),
                guides,
                links,
                intra_link: setup.is_intra_link(m),
                traversed_joints: poses.traversed[m]
                    .iter()
                    .map(|&j| motion.joint_names()[j].clone())
                    .collect(),
                poses: poses.poses[m]
                    .iter()
                    .map(|p| cable_dict::solve::pose_summary(p, motion))
                    .collect(),
            }
        })
        .collect();
    if args.json {
        return print_json(&segments);
    }
    let mut text = String::new();
    for s in &segments {
        let kind = if s.intra_link {
            "intra-link: tested under each gravity direction of the motion in its link's frame"
                .to_string()
        } else {
            format!("traverses {}", s.traversed_joints.join(", "))
        };
        let _ = writeln!(
            text,
            "{} {}→{} ({}→{}), {kind}",
            s.segment, s.guides[0], s.guides[1], s.links[0], s.links[1]
        );
        for p in &s.poses {
            let joints: Vec<String> = p.joints.iter().map(|v| format!("{v:.1}")).collect();
            let _ = writeln!(
                text,
                "  t = {:>7.3} s  sample {:>5}  [{}]  {}",
                p.time_s,
                p.sample,
                joints.join(", "),
                p.reason
            );
        }
    }
    emit(&text)
}
