//! Pictures of the cable on the robot for the report page: front, side and top views
//! (orthographic, world frame, one scale for all) of the robot's collision shapes, the
//! cable and its clamps, at each critical pose, at the worst moment of the motion test and,
//! when no candidate path exists, at the nearest miss.
//!
//! Everything drawn comes from the scene [`super::views::solve_scene`] assembles for `scene.glb`
//! (the same colliders, tessellated the same way, the same cable nodes, the same clamps), so
//! the pictures cannot disagree with the 3D scene or the physics. Plain SVG, no script: the
//! page stays a folder that works offline.

mod dials;
mod projection;
mod svg;

pub use dials::dials_svg;

use super::scene::{self, CableTint, PoseScene, SceneSpec};
use super::worst::{limit_words, smallest_margin};
use crate::mounting::{MountingPlan, mounting_plan};
use crate::setup::Setup;
use crate::solve::{CriticalPose, critical_poses, first_nearest_miss};
use crate::solve::{SolveReport, Status};
use nalgebra::Point3;
use svg::{CablePiece, Drawing, Layout, picture_svg};

/// One picture of the report folder.
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// File name in the report folder, e.g. `pose-2.svg`.
    pub file: String,
    /// What it shows, one line for the summary's list of files.
    pub what: String,
    /// The caption under it on the page, in plain words.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// The pictures of a solve, drawn from `spec`, the scene [`super::views::solve_scene`] assembled
/// for `report` with `setup`: one per critical pose (`pose-1.svg` …), one at the worst
/// moment of the motion test when the test kept the cable's shapes (`worst-moment.svg`),
/// and one of the nearest miss when there is no candidate path (`nearest-miss.svg`).
pub fn pictures(setup: &Setup, report: &SolveReport, spec: &SceneSpec<'_>) -> Vec<Picture> {
    let plan = report
        .shown_candidate()
        .map(|c| mounting_plan(setup, &c.path));
    let names = Names {
        setup,
        plan: plan.as_ref(),
    };
    let mut moments = critical_pose_moments(report, spec, &names);
    moments.extend(worst_moment(setup, report, spec, &names));
    moments.extend(nearest_miss_moment(setup, report, spec));
    let drawings: Vec<Drawing> = moments.iter().map(|m| drawing(spec, m, &names)).collect();
    let layouts = Layout::for_each(&drawings, 2e3 * spec.cable_radius_m);
    moments
        .into_iter()
        .zip(drawings.iter().zip(&layouts))
        .map(|(moment, (drawing, layout))| Picture {
            file: moment.file,
            what: moment.what,
            caption: moment.caption,
            svg: picture_svg(drawing, layout),
        })
        .collect()
}

/// The robot and the cable at the installation pose, for the installation sheet
/// (`installation-pose.svg`): front, side and top, the clamps numbered as the sheet numbers
/// them. `None` without an installation pose in the setup or a shown path.
pub fn installation_picture(
    setup: &Setup,
    report: &SolveReport,
    spec: &SceneSpec<'_>,
) -> Option<Picture> {
    let scene = spec.installation.as_ref()?;
    let plan = report
        .shown_candidate()
        .map(|c| mounting_plan(setup, &c.path))?;
    let names = Names {
        setup,
        plan: Some(&plan),
    };
    let moment = Moment {
        file: "installation-pose.svg".into(),
        heading: "The robot at the installation pose, the cable laid untwisted".into(),
        what: "the robot and the cable at the installation pose, front, side and top, for \
               the installation sheet"
            .into(),
        caption: String::new(),
        scene,
        marker_m: None,
    };
    let drawing = drawing(spec, &moment, &names);
    // The in-a-row layout has no corner for the legend: the caption says what it would.
    let colours: Vec<String> = drawing
        .cable_legend
        .iter()
        .map(|tint| format!("{} {}", tint.colour_word(), tint.legend()))
        .collect();
    let caption = format!(
        "The robot at the installation pose with the cable as laid there, clamps numbered as \
         in the table; {}.",
        colours.join("; ")
    );
    let layout = Layout::in_a_row(&drawing, 2e3 * spec.cable_radius_m, SHEET_LABEL_PX);
    Some(Picture {
        svg: picture_svg(&drawing, &layout),
        file: moment.file,
        what: moment.what,
        caption,
    })
}

/// Font size of the clamp labels in the installation sheet's picture (px of a 960 px wide
/// picture printed about 190 mm wide: about 9 pt).
const SHEET_LABEL_PX: f64 = 18.0;

/// One instant to draw and the words that go with it.
struct Moment<'s> {
    file: String,
    heading: String,
    what: String,
    caption: String,
    /// The robot and the cable then.
    scene: &'s PoseScene,
    /// Where to ring in red (world frame, m).
    marker_m: Option<Point3<f64>>,
}

/// The fitter's names of the shown candidate's clamps and pieces (the search's when it has
/// no mounting plan).
struct Names<'a> {
    setup: &'a Setup,
    plan: Option<&'a MountingPlan>,
}

impl Names<'_> {
    /// `1`, `gripper connector`: the physical clamp guide `guide` belongs to.
    fn clamp(&self, guide: &str) -> String {
        self.plan
            .and_then(|plan| plan.clamp_of_guide(guide))
            .map_or_else(|| guide.to_string(), |clamp| clamp.short_name())
    }

    /// `piece 1 → 2`, `clamp 2` (a 0 mm piece inside it), or `cable piece C3`.
    fn piece(&self, segment: usize) -> String {
        let name = self.setup.segment_name(segment);
        self.plan
            .and_then(|plan| plan.place_on_cable(&name, None))
            .map(|words| {
                words
                    .trim_start_matches("on ")
                    .trim_start_matches("at ")
                    .to_string()
            })
            .unwrap_or_else(|| format!("cable piece {name}"))
    }
}

/// What is drawn of `moment`, in millimetres.
fn drawing(spec: &SceneSpec<'_>, moment: &Moment<'_>, names: &Names<'_>) -> Drawing {
    let mm = |p: &Point3<f64>| p * 1e3;
    let scene = moment.scene;
    let colliders = scene::collider_points(spec.robot, &scene.link_poses)
        .into_iter()
        .map(|c| c.points_m.iter().map(mm).collect())
        .collect();
    let cable: Vec<CablePiece> = scene
        .cable
        .iter()
        .map(|line| CablePiece {
            name: line.name.clone(),
            nodes: line.nodes_m.iter().map(mm).collect(),
            colour: spec.tint_of(&line.name).css(),
        })
        .collect();
    let cable_legend: Vec<CableTint> = CableTint::ALL
        .into_iter()
        .filter(|&tint| {
            scene
                .cable
                .iter()
                .any(|line| spec.tint_of(&line.name) == tint)
        })
        .collect();
    // One dot per physical clamp: guides joined by a 0 mm piece share a place and a name.
    let mut clamps: Vec<(String, Point3<f64>)> = Vec::new();
    for mark in &spec.guides {
        let Some(link_pose) = scene.link_poses.get(mark.link) else {
            continue;
        };
        let name = names.clamp(&mark.clamp);
        if clamps.iter().any(|(n, _)| *n == name) {
            continue;
        }
        let at = link_pose * mark.pose_in_link;
        clamps.push((name, mm(&Point3::from(at.translation.vector))));
    }
    Drawing {
        heading: moment.heading.clone(),
        colliders,
        cable,
        clamps,
        cable_legend,
        marker: moment.marker_m.as_ref().map(mm),
    }
}

/// One moment per critical pose, with the scene's snapshot of it.
fn critical_pose_moments<'s>(
    report: &SolveReport,
    spec: &'s SceneSpec<'_>,
    names: &Names<'_>,
) -> Vec<Moment<'s>> {
    let poses = critical_poses(report);
    let count = poses.len();
    let path = path_words(report);
    poses
        .iter()
        .zip(&spec.snapshots)
        .enumerate()
        .map(|(i, (pose, snapshot))| {
            let n = i + 1;
            let shape = static_shape_words(report, &snapshot.scene, names);
            Moment {
                file: format!("pose-{n}.svg"),
                heading: format!("Critical pose {n} of {count}, t = {:.2} s", pose.time_s),
                what: format!(
                    "the robot and the cable at critical pose {n} (t = {:.2} s), front, side and top",
                    pose.time_s
                ),
                caption: format!(
                    "Critical pose {n} of {count}, t = {:.2} s, tested for {}. {shape} {path}",
                    pose.time_s,
                    reasons_words(pose, names)
                )
                .trim_end()
                .to_string(),
                scene: &snapshot.scene,
                marker_m: None,
            }
        })
        .collect()
}

/// `piece 1 → 2: joint_4 max; piece 2 → gripper connector: joint_6 min`.
fn reasons_words(pose: &CriticalPose, names: &Names<'_>) -> String {
    let reasons: Vec<String> = pose
        .reasons
        .iter()
        .map(|(piece, reason)| {
            let segment =
                (0..names.setup.segments.len()).find(|&m| names.setup.segment_name(m) == *piece);
            let name = segment.map_or_else(|| format!("cable piece {piece}"), |m| names.piece(m));
            format!("{name}: {reason}")
        })
        .collect();
    reasons.join("; ")
}

/// What a critical pose's cable is, and which pieces have no static shape there.
fn static_shape_words(report: &SolveReport, scene: &PoseScene, names: &Names<'_>) -> String {
    let Some(shown) = report.shown_candidate() else {
        return "No candidate path, so only the robot is drawn.".into();
    };
    let missing: Vec<String> = shown
        .path
        .pieces()
        .filter(|(m, pv)| {
            let name = names.setup.segment_name(*m);
            pv.sub_segments > 0 && !scene.cable.iter().any(|line| line.name == name)
        })
        .map(|(m, _)| names.piece(m))
        .collect();
    let mut words = "The cable is drawn in its static shape at this pose.".to_string();
    if !missing.is_empty() {
        words += &format!(
            " No static shape found for {}: not drawn.",
            missing.join(", ")
        );
    }
    words
}

/// Which path the pictures show, and whether it is a working one.
fn path_words(report: &SolveReport) -> String {
    let Some(c) = report.shown_candidate() else {
        return String::new();
    };
    let length = c.total_length_mm;
    match c.passed {
        Some(true) => format!(
            "Path drawn: the shortest path that passed the motion test, {length:.0} mm of cable."
        ),
        None => format!(
            "Path drawn: the shortest candidate path, {length:.0} mm of cable, not tested over \
             the motion."
        ),
        Some(false) => {
            let which = match report.unsolved.as_ref().and_then(|u| u.closest.as_ref()) {
                Some(closest) => format!(
                    "the path tried that missed a limit by least ({:.2} mm of {} in {})",
                    closest.relax_by_mm,
                    closest.limit_words(),
                    closest.segment
                ),
                None => "the last one tried".to_string(),
            };
            format!(
                "Path drawn: candidate {} ({length:.0} mm of cable), {which}. It failed the \
                 motion test: this is the nearest miss, not a working path.",
                c.rank
            )
        }
    }
}

/// The simulated cable at the kept shape nearest to the smallest margin of the motion test.
fn worst_moment<'s>(
    setup: &Setup,
    report: &SolveReport,
    spec: &'s SceneSpec<'_>,
    names: &Names<'_>,
) -> Option<Moment<'s>> {
    let test = report.motion_test.as_ref()?;
    let frames = &spec.animation.as_ref()?.frames;
    if frames.len() != test.shapes.len() {
        return None;
    }
    let worst = smallest_margin(test, &setup.thresholds, setup.cable.diameter_m)?;
    let (frame, shape) = test.shapes.iter().enumerate().min_by(|a, b| {
        let off = |s: &crate::motion_test::ShapeFrame| (s.time_s - worst.time_s).abs();
        off(a.1).total_cmp(&off(b.1))
    })?;
    let when = format!("t = {:.2} s", worst.time_s);
    let (heading, what) = if worst.violated {
        (
            format!("Where the motion test failed, {when}"),
            format!("The motion test failed at {when}:"),
        )
    } else {
        (
            format!("Worst moment of the motion test, {when}"),
            format!("Worst moment of the motion test, {when}: the smallest margin to a limit is"),
        )
    };
    let ring = if worst.position_m.is_some() {
        ", ringed in red"
    } else {
        ""
    };
    let drawn_at = if (shape.time_s - worst.time_s).abs() < 0.005 {
        "at that instant".to_string()
    } else {
        format!("at t = {:.2} s, the nearest kept shape", shape.time_s)
    };
    let caption = format!(
        "{what} {} on {}{ring}. The cable is drawn as simulated {drawn_at}. {}",
        limit_words(worst.constraint, worst.value, worst.limit),
        names.piece(worst.segment),
        path_words(report)
    )
    .trim_end()
    .to_string();
    Some(Moment {
        file: "worst-moment.svg".into(),
        heading,
        what: format!(
            "the robot and the cable at the worst moment of the motion test ({when}), front, \
             side and top"
        ),
        caption,
        scene: &frames[frame],
        marker_m: worst.position_m.map(Point3::from),
    })
}

/// Without a candidate path: the robot and the nearest miss's piece where it fails (the
/// scene's main view then), its failing place ringed.
fn nearest_miss_moment<'s>(
    setup: &Setup,
    report: &SolveReport,
    spec: &'s SceneSpec<'_>,
) -> Option<Moment<'s>> {
    if report.shown_candidate().is_some() || report.status != Status::NoChain {
        return None;
    }
    let (m, from_guide, miss) = first_nearest_miss(report)?;
    let piece = setup.segment_name(m);
    let line = spec.main.cable.first();
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let marker_m = line.zip(miss.from_start_clamp_mm).and_then(|(line, mm)| {
        let node = (mm / pitch_mm).round();
        (node >= 0.0)
            .then(|| line.nodes_m.get(node as usize).copied())
            .flatten()
    });
    let shape = if line.is_some() {
        "The piece is drawn in its static shape there, the other pieces are not drawn."
    } else {
        "The piece has no static shape there: only the robot is drawn."
    };
    Some(Moment {
        file: "nearest-miss.svg".into(),
        heading: format!(
            "No cable path: nearest miss of cable piece {piece}, t = {:.2} s",
            miss.at.time_s
        ),
        what: format!("the robot and the nearest miss of cable piece {piece}, front, side and top"),
        caption: format!(
            "No cable path was found. Cable piece {piece} comes closest with {}. {shape}",
            miss.describe(from_guide)
        ),
        scene: &spec.main,
        marker_m,
    })
}

#[cfg(test)]
mod tests {
    use super::projection::{View, outline};
    use super::*;
    use crate::robot::Robot;
    use std::f64::consts::FRAC_PI_2;
    use std::path::Path;

    /// A robot whose only collider is on its base, with the given `<collision>` geometry
    /// and origin (a bare link on a revolute joint makes it a robot).
    fn one_collider(geometry: &str, xyz: &str, rpy: &str) -> Robot {
        let urdf = format!(
            "<robot name=\"r\"><link name=\"base\"><collision><origin xyz=\"{xyz}\" \
             rpy=\"{rpy}\"/><geometry>{geometry}</geometry></collision></link>\
             <link name=\"tip\"/><joint name=\"j\" type=\"revolute\"><parent link=\"base\"/>\
             <child link=\"tip\"/><axis xyz=\"0 0 1\"/>\
             <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>"
        );
        Robot::from_urdf_str(&urdf, Path::new("test.urdf")).expect("a valid URDF")
    }

    /// The outline of the robot's only collider with its link at `link_pose`, in mm,
    /// rounded to 0.1 mm and sorted.
    fn outline_mm(robot: &Robot, link_pose: crate::pose::Pose, view: View) -> Vec<[i64; 2]> {
        let colliders = scene::collider_points(robot, &vec![link_pose; robot.links.len()]);
        assert_eq!(colliders.len(), 1);
        let mm: Vec<Point3<f64>> = colliders[0].points_m.iter().map(|p| p * 1e3).collect();
        let mut corners: Vec<[i64; 2]> = outline(view, &mm)
            .into_iter()
            .map(|p| p.map(|v| (v * 10.0).round() as i64))
            .collect();
        corners.sort();
        corners
    }

    /// Corners of the axis-aligned rectangle `[r0, r1] × [u0, u1]` (mm) in tenths of a mm,
    /// sorted.
    fn rectangle(r: [f64; 2], u: [f64; 2]) -> Vec<[i64; 2]> {
        let tenths = |v: f64| (v * 10.0).round() as i64;
        let mut corners: Vec<[i64; 2]> = r
            .iter()
            .flat_map(|&x| u.iter().map(move |&y| [tenths(x), tenths(y)]))
            .collect();
        corners.sort();
        corners
    }

    #[test]
    fn a_turned_box_at_a_known_pose_projects_to_its_rectangles() {
        // 0.4 × 0.2 × 0.6 m box turned 90° about z in its link: it spans 0.2 m along x and
        // 0.4 m along y. The link frame sits at (1, 2, 3) m, the collider 0.1 m up in it.
        let robot = one_collider(
            "<box size=\"0.4 0.2 0.6\"/>",
            "0 0 0.1",
            &format!("0 0 {FRAC_PI_2}"),
        );
        let link = crate::pose::pose_from_xyz_rpy([1.0, 2.0, 3.0], [0.0; 3]);
        let (x, y, z) = ([900.0, 1100.0], [1800.0, 2200.0], [2800.0, 3400.0]);
        assert_eq!(outline_mm(&robot, link, View::Front), rectangle(x, z));
        assert_eq!(outline_mm(&robot, link, View::Side), rectangle(y, z));
        assert_eq!(outline_mm(&robot, link, View::Top), rectangle(x, y));
    }

    #[test]
    fn a_cylinder_along_x_is_a_rectangle_from_the_front_and_a_circle_from_the_side() {
        // Radius 50 mm, 300 mm long, its axis (z) turned onto x by a pitch of 90°, centred
        // at (0, 0, 500) mm.
        let robot = one_collider(
            "<cylinder radius=\"0.05\" length=\"0.3\"/>",
            "0 0 0.5",
            &format!("0 {FRAC_PI_2} 0"),
        );
        let link = crate::pose::Pose::identity();
        let front = outline_mm(&robot, link, View::Front);
        assert_eq!(front, rectangle([-150.0, 150.0], [450.0, 550.0]));
        let top = outline_mm(&robot, link, View::Top);
        assert_eq!(top, rectangle([-150.0, 150.0], [-50.0, 50.0]));
        // From the side, the end faces' rims: every corner 50 mm from the axis, and the
        // outline reaches the circle's extremes.
        let side = outline_mm(&robot, link, View::Side);
        assert!(side.len() >= 12, "{side:?}");
        for [y, z] in &side {
            let r = ((*y as f64).powi(2) + ((*z - 5000) as f64).powi(2)).sqrt() / 10.0;
            assert!((r - 50.0).abs() < 0.15, "{y}, {z}: {r} mm from the axis");
        }
        for extreme in [[-500, 5000], [500, 5000], [0, 4500], [0, 5500]] {
            assert!(side.contains(&extreme), "{extreme:?} not in {side:?}");
        }
    }
}
