//! What the scene of a cable path shows: the robot at a pose, the path's static equilibrium
//! there, its guides, the motion test as an animation, the critical poses as snapshots.

use super::scene::{
    CableLine, CableTint, GuideMark, PoseScene, SceneAnimation, SceneSpec, Snapshot,
};
use crate::attachment::{ConnectMethod, Evaluator};
use crate::motion::Motion;
use crate::motion_test::{MotionTestReport, SegmentNodes, ShapeFrame};
use crate::path::{CablePath, Pv};
use crate::pose::Pose;
use crate::robot::JointVectorError;
use crate::setup::Setup;
use crate::solve::{NearestMiss, SolveReport};
use crate::stress::contact::ContactError;
use nalgebra::{Point3, Vector3};

/// Snapshots per row of the grid they are laid out on behind the main robot.
const SNAPSHOTS_PER_ROW: usize = 5;

/// Why a scene could not be assembled.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// The robot's geometry cannot be used for the equilibria's clearance model.
    #[error(transparent)]
    Obstacles(#[from] ContactError),
    /// A joint vector does not fit the robot.
    #[error(transparent)]
    Kinematics(#[from] JointVectorError),
}

/// The static cable of `path` with the robot at `link_poses`: one centreline per segment
/// that has a cable, and for each segment without an equilibrium, why.
struct StaticCable {
    /// Centrelines of the segments that have one.
    lines: Vec<CableLine>,
    /// `C3: no equilibrium (…)` for the others.
    problems: Vec<String>,
}

/// The static equilibrium of every segment of `path` with the links at `link_poses`.
fn static_cable(evaluator: &Evaluator<'_>, path: &CablePath, link_poses: &[Pose]) -> StaticCable {
    let mut cable = StaticCable {
        lines: Vec::new(),
        problems: Vec::new(),
    };
    let setup = evaluator.setup();
    for (m, pv) in path.pieces() {
        match evaluator.equilibrium_nodes(m, &pv, link_poses) {
            Ok(nodes) if nodes.len() >= 2 => cable.lines.push(CableLine {
                name: setup.segment_name(m),
                nodes_m: nodes,
            }),
            Ok(_) => {}
            Err(why) => cable
                .problems
                .push(format!("{}: {why}", setup.segment_name(m))),
        }
    }
    cable
}

/// The clamps of `path`, each at the configuration the path uses.
pub fn guide_marks(setup: &Setup, path: &CablePath) -> Vec<GuideMark> {
    path.guides(setup)
        .zip(&path.configurations)
        .map(|(g, &c)| {
            let guide = &setup.guides[g];
            let configuration = &guide.configurations[c];
            GuideMark {
                name: format!("{} ({})", guide.name, configuration.name),
                clamp: guide.name.clone(),
                link: guide.link,
                pose_in_link: configuration.pose,
            }
        })
        .collect()
}

/// The scene of `path` with the robot at `joints` (rad / m): its static equilibrium there
/// (segments without one are left out; [`Evaluator::check_at`] says why).
pub fn pose_scene<'a>(
    setup: &'a Setup,
    path: &CablePath,
    joints: &[f64],
) -> Result<SceneSpec<'a>, ViewError> {
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
    let link_poses = setup.robot.link_poses(joints)?;
    let cable = static_cable(&evaluator, path, &link_poses).lines;
    Ok(still_scene(
        setup,
        Some(path),
        PoseScene { link_poses, cable },
    ))
}

/// A scene of `main` alone, with the guides of `path`.
fn still_scene<'a>(setup: &'a Setup, path: Option<&CablePath>, main: PoseScene) -> SceneSpec<'a> {
    SceneSpec {
        robot: &setup.robot,
        cable_radius_m: 0.5 * setup.cable.diameter_m,
        main,
        guides: path.map(|p| guide_marks(setup, p)).unwrap_or_default(),
        animation: None,
        snapshots: Vec::new(),
        tints: Vec::new(),
        installation: None,
    }
}

/// The scene of a solve: the shown candidate at the motion's first pose, animated over its
/// motion test when one ran, with one snapshot per critical pose (the robot alone when there
/// is no candidate). The strings name the segments without a static equilibrium at a pose.
pub fn solve_scene<'a>(
    setup: &'a Setup,
    motion: &Motion,
    report: &SolveReport,
) -> Result<(SceneSpec<'a>, Vec<String>), ViewError> {
    let path = report.shown_candidate().map(|c| &c.path);
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
    let at = |joints: &[f64]| -> Result<(PoseScene, Vec<String>), ViewError> {
        let link_poses = setup.robot.link_poses(joints)?;
        let cable = path.map(|p| static_cable(&evaluator, p, &link_poses));
        let (lines, problems) = cable.map_or_else(Default::default, |c| (c.lines, c.problems));
        Ok((
            PoseScene {
                link_poses,
                cable: lines,
            },
            problems,
        ))
    };
    let (main, mut problems) = match (path, nearest_miss_scene(&evaluator, motion, report)) {
        (None, Some(miss)) => (miss?, Vec::new()),
        _ => at(&motion.samples()[0])?,
    };
    let mut spec = still_scene(setup, path, main);
    spec.tints = margin_tints(setup, report);
    if let Some(test) = &report.motion_test {
        spec.animation = motion_test_animation(setup, motion, test)?;
    }
    if let Some(animation) = &spec.animation {
        // The animated cable is the simulated one: it starts from the same equilibrium.
        spec.main = animation.frames[0].clone();
    }
    if let (Some(path), Some(installation)) = (path, &setup.installation) {
        let cable = static_cable(&evaluator, path, &installation.link_poses);
        let scene = PoseScene {
            link_poses: installation.link_poses.clone(),
            cable: cable.lines,
        };
        problems.extend(
            cable
                .problems
                .iter()
                .map(|p| format!("installation pose: {p}")),
        );
        // The view moves the main copy's pieces there: the same pieces must have a shape.
        if same_lines(&scene, &spec.main) {
            spec.installation = Some(scene);
        }
    }
    for (i, pose) in critical_poses(report).into_iter().enumerate() {
        let name = pose.scene_name(i + 1);
        let (scene, missing) = at(&motion.samples()[pose.sample])?;
        problems.extend(missing.into_iter().map(|p| format!("{name}: {p}")));
        spec.snapshots.push(Snapshot {
            name,
            scene,
            offset_m: Vector3::zeros(),
        });
    }
    lay_out_snapshots(&mut spec);
    Ok((spec, problems))
}

/// Whether two scenes have the same cable lines with the same node counts.
fn same_lines(a: &PoseScene, b: &PoseScene) -> bool {
    let shape = |scene: &PoseScene| -> Vec<(String, usize)> {
        let lines = scene.cable.iter();
        lines.map(|l| (l.name.clone(), l.nodes_m.len())).collect()
    };
    shape(a) == shape(b)
}

/// Share of a limit's allowance (bend radius, stretch beyond 1) within which a piece is
/// drawn as tight.
pub const TIGHT_SHARE: f64 = 0.2;

/// Each piece of the shown candidate coloured by how close it came to a limit, at the test
/// poses and over the motion test: red when a limit is exceeded, amber when closer to the
/// robot or to itself than one cable diameter or within [`TIGHT_SHARE`] of the bend-radius
/// or stretch limit, green otherwise.
pub fn margin_tints(setup: &Setup, report: &SolveReport) -> Vec<(String, CableTint)> {
    let Some(shown) = report.shown_candidate() else {
        return Vec::new();
    };
    let t = &setup.thresholds;
    let diameter = setup.cable.diameter_m;
    // The margin below which a limit is tight.
    let tight_below = |constraint: &str| match constraint {
        "contact" => diameter,
        "bend_radius" => TIGHT_SHARE * t.min_bend_radius_m,
        _ => TIGHT_SHARE * (t.stretch - 1.0),
    };
    let mut tints: Vec<(String, CableTint)> = Vec::new();
    let mut worsen =
        |name: String, tint: CableTint| match tints.iter_mut().find(|(n, _)| *n == name) {
            Some((_, old)) => *old = (*old).max(tint),
            None => tints.push((name, tint)),
        };
    let classify = |margin: f64, tight: f64| match margin {
        m if m < 0.0 => CableTint::Exceeded,
        m if m < tight => CableTint::Tight,
        _ => CableTint::Ample,
    };
    // The answer's pieces are all judged; of a failed candidate only the failing one is.
    let is_answer = report.optimal.is_some() && shown.passed != Some(false);
    if is_answer {
        for (m, _) in shown.path.pieces() {
            worsen(setup.segment_name(m), CableTint::Ample);
        }
        for margin in &report.margins {
            let tint = classify(margin.margin, tight_below(margin.constraint));
            worsen(margin.segment.clone(), tint);
        }
    }
    if let Some(test) = &report.motion_test {
        let worsts = [
            (&test.worst_clearance, "contact", 1.0, t.contact_clearance_m),
            (&test.worst_self_clearance, "contact", 1.0, 0.0),
            (&test.worst_bend, "bend_radius", 1.0, t.min_bend_radius_m),
            (&test.worst_stretch, "stretch", -1.0, t.stretch),
        ];
        for (worst, constraint, sign, limit) in worsts {
            if let Some(w) = worst {
                let tint = classify(sign * (w.value - limit), tight_below(constraint));
                if is_answer || tint == CableTint::Exceeded {
                    worsen(setup.segment_name(w.segment), tint);
                }
            }
        }
    }
    tints
}

/// Without a candidate: the robot where the diagnosis's first nearest miss failed, with that
/// piece's static equilibrium (named `C1 nearest miss`); `None` without a nearest miss.
fn nearest_miss_scene(
    evaluator: &Evaluator<'_>,
    motion: &Motion,
    report: &SolveReport,
) -> Option<Result<PoseScene, ViewError>> {
    let setup = evaluator.setup();
    let (m, _, miss) = first_nearest_miss(report)?;
    let (a, b) = setup.segment_guides(m);
    let index = |g: usize, name: &str| setup.guides[g].configuration_index(name);
    let pv = Pv {
        sub_segments: (miss.length_mm / (setup.cable.sub_segment_pitch_m * 1e3)).round() as usize,
        start: index(a, &miss.from_configuration)?,
        end: index(b, &miss.to_configuration)?,
    };
    Some(piece_scene(evaluator, motion, m, &pv, miss.time_s))
}

/// The diagnosis's first nearest miss: its segment's index, its start guide (`G3`, where
/// places on the piece are measured from) and the miss; `None` without one.
pub fn first_nearest_miss(report: &SolveReport) -> Option<(usize, &str, &NearestMiss)> {
    report.diagnosis.as_ref()?.segments.iter().find_map(|d| {
        let m = report
            .segments
            .iter()
            .position(|s| s.segment == d.segment)?;
        Some((m, d.from_guide.as_str(), d.nearest_misses.first()?))
    })
}

/// The robot at `time_s` of the motion with the static equilibrium of PV `pv` of segment `m`
/// (no cable when it has none), named `C1 nearest miss`.
fn piece_scene(
    evaluator: &Evaluator<'_>,
    motion: &Motion,
    m: usize,
    pv: &Pv,
    time_s: f64,
) -> Result<PoseScene, ViewError> {
    let link_poses = evaluator
        .setup()
        .robot
        .link_poses(&motion.joints_at(time_s))?;
    let cable = evaluator
        .equilibrium_nodes(m, pv, &link_poses)
        .ok()
        .filter(|nodes| nodes.len() >= 2)
        .map(|nodes| CableLine {
            name: format!("{} nearest miss", evaluator.setup().segment_name(m)),
            nodes_m: nodes,
        });
    Ok(PoseScene {
        link_poses,
        cable: cable.into_iter().collect(),
    })
}

/// The motion test's kept shapes as keyframes (time from the motion's start), with the robot
/// at each frame's time; `None` with fewer than two frames.
fn motion_test_animation(
    setup: &Setup,
    motion: &Motion,
    test: &MotionTestReport,
) -> Result<Option<SceneAnimation>, ViewError> {
    if test.shapes.len() < 2 {
        return Ok(None);
    }
    let start = test.shapes[0].time_s;
    let frames = test
        .shapes
        .iter()
        .map(|frame| frame_scene(setup, motion, frame))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Some(SceneAnimation {
        name: "motion test".into(),
        times_s: test.shapes.iter().map(|f| f.time_s - start).collect(),
        frames,
    }))
}

/// The robot and the simulated cable at one kept instant.
fn frame_scene(setup: &Setup, motion: &Motion, frame: &ShapeFrame) -> Result<PoseScene, ViewError> {
    Ok(PoseScene {
        link_poses: setup.robot.link_poses(&motion.joints_at(frame.time_s))?,
        cable: frame
            .segments
            .iter()
            .map(|s| simulated_line(setup, s))
            .collect(),
    })
}

fn simulated_line(setup: &Setup, segment: &SegmentNodes) -> CableLine {
    CableLine {
        name: setup.segment_name(segment.segment),
        nodes_m: segment.nodes_m.iter().map(|&p| Point3::from(p)).collect(),
    }
}

/// A critical pose of the inter-link segments: one motion sample, with every segment and
/// reason that chose it.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalPose {
    /// Index of the motion sample.
    pub sample: usize,
    /// Time of the sample in the motion (s).
    pub time_s: f64,
    /// `(segment, reason)` pairs, e.g. `("C1", "joint_1 max")`, segments in path order.
    pub reasons: Vec<(String, String)>,
}

impl CriticalPose {
    /// The scene's name of the `number`-th pose (from 1): `critical pose 2: C1 joint_1 max, C3
    /// joint_1 max (t = 1.250 s)`.
    fn scene_name(&self, number: usize) -> String {
        let why: Vec<String> = self
            .reasons
            .iter()
            .map(|(segment, reason)| format!("{segment} {reason}"))
            .collect();
        format!(
            "critical pose {number}: {} (t = {:.3} s)",
            why.join(", "),
            self.time_s
        )
    }
}

/// The inter-link segments' critical poses, one per motion sample, in sample order: the
/// scene's snapshots, in the same order.
pub fn critical_poses(report: &SolveReport) -> Vec<CriticalPose> {
    let mut by_sample: std::collections::BTreeMap<usize, CriticalPose> = Default::default();
    for segment in report.segments.iter().filter(|s| s.kind == "inter-link") {
        for pose in &segment.test_poses {
            by_sample
                .entry(pose.sample)
                .or_insert_with(|| CriticalPose {
                    sample: pose.sample,
                    time_s: pose.time_s,
                    reasons: Vec::new(),
                })
                .reasons
                .push((segment.segment.clone(), pose.reason.clone()));
        }
    }
    by_sample.into_values().collect()
}

/// Places the snapshots on a grid beside the main robot, far enough apart not to overlap.
fn lay_out_snapshots(spec: &mut SceneSpec<'_>) {
    let reach = std::iter::once(&spec.main)
        .chain(spec.snapshots.iter().map(|s| &s.scene))
        .flat_map(|scene| {
            let links = scene.link_poses.iter().map(|p| p.translation.vector);
            let cable = scene
                .cable
                .iter()
                .flat_map(|l| l.nodes_m.iter().map(|p| p.coords));
            links.chain(cable)
        })
        .map(|p| p.xy().norm())
        .fold(0.0, f64::max);
    // Robot colliders reach past the link origins: a margin of a few decimetres.
    let spacing = 2.0 * reach + 0.6;
    for (i, snapshot) in spec.snapshots.iter_mut().enumerate() {
        let (row, column) = (i / SNAPSHOTS_PER_ROW, i % SNAPSHOTS_PER_ROW);
        let centred = column as f64 - 0.5 * (SNAPSHOTS_PER_ROW - 1) as f64;
        snapshot.offset_m = Vector3::new(centred * spacing, (row + 1) as f64 * spacing, 0.0);
    }
}
