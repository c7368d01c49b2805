//! The cable's static shapes at the poses a solve's report shows: the motion's first pose,
//! the installation pose, every critical pose and, without an answer, where the nearest miss
//! failed. The equilibria are solved here, with the search's cable model, so that the report
//! only draws what it is given.

use super::diagnosis::NearestMiss;
use super::report::SolveReport;
use crate::attachment::{ConnectMethod, Evaluator};
use crate::motion::Motion;
use crate::path::{CablePath, Pv};
use crate::pose::Pose;
use crate::robot::JointVectorError;
use crate::setup::Setup;
use crate::stress::contact::ContactError;
use nalgebra::Point3;
use std::collections::BTreeMap;

/// Why the shapes could not be solved.
#[derive(Debug, thiserror::Error)]
pub enum ShapeError {
    /// The robot's geometry cannot be used for the equilibria's clearance model.
    #[error(transparent)]
    Obstacles(#[from] ContactError),
    /// A joint vector does not fit the robot.
    #[error(transparent)]
    Kinematics(#[from] JointVectorError),
    /// No motion, or a pose of a motion that was not given.
    #[error("the report's poses name a motion not given")]
    NoMotion,
}

/// One segment's static centreline.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeLine {
    /// The segment's name (`C3`), or `C3 nearest miss`.
    pub name: String,
    /// Node positions (world frame, m), from the start clamp to the end clamp.
    pub nodes_m: Vec<Point3<f64>>,
}

/// The robot at one pose with the static cable of a path there.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseShape {
    /// World pose of every link.
    pub link_poses: Vec<Pose>,
    /// The segments that have an equilibrium there.
    pub lines: Vec<ShapeLine>,
    /// `C3: no equilibrium (…)` for the segments that have none.
    pub problems: Vec<String>,
}

/// A critical pose of the inter-link segments: one motion sample, with every segment and
/// reason that chose it.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalPose {
    /// Which motion of a cell (0 for a single motion).
    pub motion: usize,
    /// Index of the motion sample.
    pub sample: usize,
    /// Time of the sample in the motion (s).
    pub time_s: f64,
    /// `(segment, reason)` pairs, e.g. `("C1", "joint_1 max")`, segments in path order.
    pub reasons: Vec<(String, String)>,
}

/// The shapes a solve's report shows (of its shown candidate; the robot alone without one).
#[derive(Debug, Clone, PartialEq)]
pub struct ReportShapes {
    /// At the motion's first sample.
    pub first: PoseShape,
    /// At the installation pose, when the setup states one and there is a candidate.
    pub installation: Option<PoseShape>,
    /// At each critical pose, in [`critical_poses`]' order.
    pub critical: Vec<PoseShape>,
    /// Without a candidate: the robot where the diagnosis's first nearest miss failed, with
    /// that piece (named `C1 nearest miss`).
    pub nearest_miss: Option<PoseShape>,
}

impl ReportShapes {
    /// Solves the shapes of `report`'s shown candidate for `setup` over `motions` (one per
    /// `report.motions`, in order; the first and the nearest miss's at the shown one's
    /// poses, each critical pose at its own motion's).
    pub fn of(
        setup: &Setup,
        motions: &[&Motion],
        report: &SolveReport,
    ) -> Result<ReportShapes, ShapeError> {
        let Some(&motion) = motions.get(report.shown_motion).or(motions.first()) else {
            return Err(ShapeError::NoMotion);
        };
        let path = report.shown_candidate().map(|c| &c.path);
        let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
        let at = |joints: &[f64]| -> Result<PoseShape, ShapeError> {
            let link_poses = setup.robot.link_poses(joints)?;
            Ok(match path {
                Some(path) => static_shape(&evaluator, path, link_poses),
                None => PoseShape {
                    link_poses,
                    lines: Vec::new(),
                    problems: Vec::new(),
                },
            })
        };
        let nearest_miss = match path {
            Some(_) => None,
            None => nearest_miss_shape(&evaluator, motions, report).transpose()?,
        };
        let installation = match (path, &setup.installation) {
            (Some(path), Some(installation)) => Some(static_shape(
                &evaluator,
                path,
                installation.link_poses.clone(),
            )),
            _ => None,
        };
        let sample = |pose: &CriticalPose| {
            let motion = motions.get(pose.motion).ok_or(ShapeError::NoMotion)?;
            motion
                .samples()
                .get(pose.sample)
                .ok_or(ShapeError::NoMotion)
        };
        let critical = critical_poses(report)
            .iter()
            .map(|pose| at(sample(pose)?))
            .collect::<Result<_, _>>()?;
        Ok(ReportShapes {
            first: at(&motion.samples()[0])?,
            installation,
            critical,
            nearest_miss,
        })
    }
}

/// The static cable of `path` with the robot at `joints` (rad / m): its equilibrium there
/// (segments without one are named in [`PoseShape::problems`]).
pub fn path_shape(
    setup: &Setup,
    path: &CablePath,
    joints: &[f64],
) -> Result<PoseShape, ShapeError> {
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
    let link_poses = setup.robot.link_poses(joints)?;
    Ok(static_shape(&evaluator, path, link_poses))
}

/// The static equilibrium of every segment of `path` with the links at `link_poses`.
fn static_shape(evaluator: &Evaluator<'_>, path: &CablePath, link_poses: Vec<Pose>) -> PoseShape {
    let mut shape = PoseShape {
        lines: Vec::new(),
        problems: Vec::new(),
        link_poses,
    };
    let setup = evaluator.setup();
    for (m, pv) in path.pieces() {
        match evaluator.equilibrium_nodes(m, &pv, &shape.link_poses) {
            Ok(nodes) if nodes.len() >= 2 => shape.lines.push(ShapeLine {
                name: setup.segment_name(m),
                nodes_m: nodes,
            }),
            Ok(_) => {}
            Err(why) => (shape.problems).push(format!("{}: {why}", setup.segment_name(m))),
        }
    }
    shape
}

/// The robot where the diagnosis's first nearest miss failed, with that piece's static
/// equilibrium (no cable when it has none); `None` without a nearest miss.
fn nearest_miss_shape(
    evaluator: &Evaluator<'_>,
    motions: &[&Motion],
    report: &SolveReport,
) -> Option<Result<PoseShape, ShapeError>> {
    let setup = evaluator.setup();
    let (m, _, miss) = first_nearest_miss(report)?;
    let Some(motion) = motions.get(miss.at.motion) else {
        return Some(Err(ShapeError::NoMotion));
    };
    let (a, b) = setup.segment_guides(m);
    let index = |g: usize, name: &str| setup.guides[g].configuration_index(name);
    let pv = Pv {
        sub_segments: (miss.length_mm / (setup.cable.sub_segment_pitch_m * 1e3)).round() as usize,
        start: index(a, &miss.from_configuration)?,
        end: index(b, &miss.to_configuration)?,
    };
    let link_poses = match setup.robot.link_poses(&motion.joints_at(miss.at.time_s)) {
        Ok(link_poses) => link_poses,
        Err(e) => return Some(Err(e.into())),
    };
    let line = (evaluator.equilibrium_nodes(m, &pv, &link_poses).ok())
        .filter(|nodes| nodes.len() >= 2)
        .map(|nodes| ShapeLine {
            name: format!("{} nearest miss", setup.segment_name(m)),
            nodes_m: nodes,
        });
    Some(Ok(PoseShape {
        link_poses,
        lines: line.into_iter().collect(),
        problems: Vec::new(),
    }))
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

/// The inter-link segments' critical poses, one per motion sample, in (motion, sample) order.
pub fn critical_poses(report: &SolveReport) -> Vec<CriticalPose> {
    let mut by_sample: BTreeMap<(usize, usize), CriticalPose> = BTreeMap::new();
    for segment in report.segments.iter().filter(|s| s.kind == "inter-link") {
        for pose in &segment.test_poses {
            by_sample
                .entry((pose.motion, pose.sample))
                .or_insert_with(|| CriticalPose {
                    motion: pose.motion,
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
