//! What the scene of a cable path shows: the robot at a pose, the path's static equilibrium
//! there (solved by [`crate::solve::ReportShapes`]), its guides, the motion test as an
//! animation, the critical poses as snapshots.

use super::scene::{
    CableLine, CableTint, ClampPart, GuideMark, PoseScene, SceneAnimation, SceneSpec, Snapshot,
};
use crate::motion::Motion;
use crate::motion_test::{MotionTestReport, SegmentNodes, ShapeFrame};
use crate::path::CablePath;
use crate::robot::JointVectorError;
use crate::setup::{GuideKind, Setup};
use crate::solve::{CriticalPose, PoseShape, ReportShapes, SolveReport, critical_poses};
use nalgebra::{Point3, Vector3};

/// Snapshots per row of the grid they are laid out on behind the main robot.
const SNAPSHOTS_PER_ROW: usize = 5;

/// A marker at every configuration of every guide of `setup`: what `sites --gltf` shows.
fn configuration_marks(setup: &Setup) -> Vec<GuideMark> {
    let marks = (setup.guides.iter())
        .flat_map(|guide| (0..guide.configurations.len()).map(move |c| mark(guide, c)));
    marks.collect()
}

/// The marker of `guide` at its configuration `c`.
fn mark(guide: &crate::setup::Guide, c: usize) -> GuideMark {
    let configuration = &guide.configurations[c];
    GuideMark {
        name: format!("{} ({})", guide.name, configuration.name),
        clamp: guide.name.clone(),
        link: guide.link,
        pose_in_link: configuration.pose,
        part: match configuration.kind {
            GuideKind::Rigid => ClampPart::Rigid,
            GuideKind::Rotating => ClampPart::Rotating,
            GuideKind::Swivel { .. } => ClampPart::Swivel,
            GuideKind::Sliding { .. } => ClampPart::Sliding,
            GuideKind::Retraction { .. } => ClampPart::Retraction,
        },
    }
}

/// The clamps of `path`, each at the configuration the path uses, then the sliding guides
/// and retraction outlets its pieces run through.
pub fn guide_marks(setup: &Setup, path: &CablePath) -> Vec<GuideMark> {
    let clamps = (path.guides(setup))
        .zip(&path.configurations)
        .map(|(g, &c)| mark(&setup.guides[g], c));
    let through = (path.pieces())
        .filter_map(|(m, _)| setup.segments[m].through)
        .map(|g| mark(&setup.guides[g], 0));
    clamps.chain(through).collect()
}

/// The scene of `path` in its static `shape` at one pose ([`crate::solve::path_shape`]).
pub fn pose_scene<'a>(setup: &'a Setup, path: &CablePath, shape: &PoseShape) -> SceneSpec<'a> {
    still_scene(setup, Some(path), pose_of(shape))
}

/// The robot and cable lines of `shape`.
fn pose_of(shape: &PoseShape) -> PoseScene {
    let lines = shape.lines.iter().map(|line| CableLine {
        name: line.name.clone(),
        nodes_m: line.nodes_m.clone(),
    });
    PoseScene {
        link_poses: shape.link_poses.clone(),
        cable: lines.collect(),
    }
}

/// A scene of `main` alone, with the guides of `path`.
fn still_scene<'a>(setup: &'a Setup, path: Option<&CablePath>, main: PoseScene) -> SceneSpec<'a> {
    SceneSpec {
        robot: &setup.robot,
        cable_radius_m: 0.5 * setup.cable.diameter_m,
        main,
        guides: path.map(|p| guide_marks(setup, p)).unwrap_or_default(),
        animation: None,
        other_motions: Vec::new(),
        snapshots: Vec::new(),
        tints: Vec::new(),
        damage: Vec::new(),
        installation: None,
    }
}

/// The scene `sites --gltf` writes: the robot at its [`Setup::reference_joints`] with a
/// marker at every candidate clamp configuration.
pub fn sites_scene(setup: &Setup) -> Result<SceneSpec<'_>, JointVectorError> {
    let main = PoseScene {
        link_poses: setup.robot.link_poses(&setup.reference_joints())?,
        cable: Vec::new(),
    };
    let mut scene = still_scene(setup, None, main);
    scene.guides = configuration_marks(setup);
    Ok(scene)
}

/// The scene of a solve: the shown candidate at the motion's first pose, animated over its
/// motion test when one ran, with one snapshot per critical pose (the robot alone when there
/// is no candidate), drawn from the `shapes` solved for it. The strings name the segments
/// without a static equilibrium at a pose.
pub fn solve_scene<'a>(
    setup: &'a Setup,
    motions: &[&Motion],
    report: &SolveReport,
    shapes: &ReportShapes,
) -> Result<(SceneSpec<'a>, Vec<String>), JointVectorError> {
    let motion = motions[report.shown_motion.min(motions.len() - 1)];
    let path = report.shown_candidate().map(|c| &c.path);
    let (main, mut problems) = match (path, &shapes.nearest_miss) {
        (None, Some(miss)) => (pose_of(miss), Vec::new()),
        _ => (pose_of(&shapes.first), shapes.first.problems.clone()),
    };
    let mut spec = still_scene(setup, path, main);
    spec.tints = margin_tints(setup, report);
    spec.damage = damage_along(report, &spec.main);
    if let Some(test) = &report.motion_test {
        spec.animation = motion_test_animation(setup, motion, test)?;
    }
    // A cell's other motions, one animation each, when the one shown has one.
    if spec.animation.is_some() && motions.len() > 1 {
        for (i, (verdict, m)) in report.motions.iter().zip(motions).enumerate() {
            let Some(test) = verdict
                .motion_test
                .as_ref()
                .filter(|_| i != report.shown_motion)
            else {
                continue;
            };
            if let Some(mut animation) = motion_test_animation(setup, m, test)? {
                animation.name = other_motion_animation(&verdict.name);
                spec.other_motions.push(animation);
            }
        }
    }
    if let Some(animation) = &spec.animation {
        // The animated cable is the simulated one: it starts from the same equilibrium.
        spec.main = animation.frames[0].clone();
    }
    if let Some(installation) = &shapes.installation {
        let scene = pose_of(installation);
        let named = installation.problems.iter();
        problems.extend(named.map(|p| format!("installation pose: {p}")));
        // The view moves the main copy's pieces there: the same pieces must have a shape.
        if same_lines(&scene, &spec.main) {
            spec.installation = Some(scene);
        }
    }
    for (i, (pose, shape)) in critical_poses(report)
        .iter()
        .zip(&shapes.critical)
        .enumerate()
    {
        let name = scene_name(pose, i + 1);
        problems.extend(shape.problems.iter().map(|p| format!("{name}: {p}")));
        spec.snapshots.push(Snapshot {
            name,
            scene: pose_of(shape),
            offset_m: Vector3::zeros(),
        });
    }
    lay_out_snapshots(&mut spec);
    Ok((spec, problems))
}

/// The name of the animation of a cell's motion `name` other than the one shown.
pub fn other_motion_animation(name: &str) -> String {
    format!("motion test: {name}")
}

/// Whether two scenes have the same cable lines with the same node counts.
fn same_lines(a: &PoseScene, b: &PoseScene) -> bool {
    let shape = |scene: &PoseScene| -> Vec<(String, usize)> {
        let lines = scene.cable.iter();
        lines.map(|l| (l.name.clone(), l.nodes_m.len())).collect()
    };
    shape(a) == shape(b)
}

/// The damage per cycle at every node of each main cable line whose piece has a predicted
/// life: what the view's second colouring paints.
fn damage_along(report: &SolveReport, main: &PoseScene) -> Vec<(String, Vec<f64>)> {
    let Some(life) = &report.life else {
        return Vec::new();
    };
    let drawn = |name: &str, nodes: usize| {
        (main.cable.iter()).any(|line| line.name == name && line.nodes_m.len() == nodes)
    };
    (life.pieces.iter())
        .filter(|piece| drawn(&piece.segment_name, piece.damage_per_cycle.len()))
        .map(|piece| (piece.segment_name.clone(), piece.damage_per_cycle.clone()))
        .collect()
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

/// The motion test's kept shapes as keyframes (time from the motion's start), with the robot
/// at each frame's time; `None` with fewer than two frames.
fn motion_test_animation(
    setup: &Setup,
    motion: &Motion,
    test: &MotionTestReport,
) -> Result<Option<SceneAnimation>, JointVectorError> {
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
fn frame_scene(
    setup: &Setup,
    motion: &Motion,
    frame: &ShapeFrame,
) -> Result<PoseScene, JointVectorError> {
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

/// The scene's name of the `number`-th critical pose (from 1): `critical pose 2: C1 joint_1
/// max, C3 joint_1 max (t = 1.250 s)`.
fn scene_name(pose: &CriticalPose, number: usize) -> String {
    let why: Vec<String> = (pose.reasons.iter())
        .map(|(segment, reason)| format!("{segment} {reason}"))
        .collect();
    format!(
        "critical pose {number}: {} (t = {:.3} s)",
        why.join(", "),
        pose.time_s
    )
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
