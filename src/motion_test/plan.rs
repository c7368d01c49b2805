//! The simulated cable of a path: its non-zero segments, with the guides of every S = 0
//! segment merged into one clamp.

use super::MotionTestError;
use crate::motion::Motion;
use crate::path::CablePath;
use crate::pose::Pose;
use crate::setup::{Setup, turn_about_axis};
use crate::stress::{ClampZone, GuideEnd};

/// One simulated segment: a segment of the setup with S > 0.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PlannedSegment {
    /// Index into the setup's segments.
    pub setup_index: usize,
    /// Length S (sub-segments, > 0).
    pub sub_segments: usize,
    /// Start guide: (index into the setup's guides, configuration).
    pub start: (usize, usize),
    /// End guide: (index into the setup's guides, configuration).
    pub end: (usize, usize),
}

/// The simulated cable: its segments in order, consecutive ones sharing a clamp.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plan {
    pub segments: Vec<PlannedSegment>,
    /// Per simulated clamp, its turn about the cable axis from the declared configuration
    /// (rad): the installed cable's twist references carried from the first clamp along the
    /// whole cable (see [`Setup::clamp_poses`]), so every piece is untwisted at installation.
    pub clamp_turns_rad: Vec<f64>,
}

impl Plan {
    /// Checks `path` against `setup` and drops its S = 0 segments: their two guides coincide,
    /// so the segments on either side share that clamp.
    pub fn new(setup: &Setup, path: &CablePath) -> Result<Plan, MotionTestError> {
        check_counts(setup, path)?;
        let mut segments = Vec::new();
        for m in 0..setup.segment_count() {
            check_admissible(setup, path, m)?;
            let sub_segments = path.lengths[m];
            if sub_segments > 0 {
                segments.push(PlannedSegment {
                    setup_index: m,
                    sub_segments,
                    start: (m, path.configurations[m]),
                    end: (m + 1, path.configurations[m + 1]),
                });
            }
        }
        if segments.is_empty() {
            return Err(MotionTestError::NoCable);
        }
        // A start clamp turned by β turns the untwisted cable's arrival by β too.
        let mut clamp_turns_rad = vec![0.0];
        for s in &segments {
            let installed =
                setup.installed_twist_rad(s.setup_index, s.sub_segments, (s.start.1, s.end.1));
            let previous = clamp_turns_rad.last().copied().unwrap_or(0.0);
            clamp_turns_rad.push(previous - installed);
        }
        Ok(Plan {
            segments,
            clamp_turns_rad,
        })
    }

    /// World poses of the simulated guides (segments + 1), from the link poses. A shared
    /// clamp takes the pose of the earlier segment's end guide (the coincident guides agree
    /// within 1e-9 m / rad).
    pub fn guide_poses(&self, setup: &Setup, link_poses: &[Pose]) -> Vec<Pose> {
        let pose = |(g, c): (usize, usize)| setup.guide_world_pose(link_poses, g, c);
        let first = pose(self.segments[0].start);
        std::iter::once(first)
            .chain(self.segments.iter().map(|s| pose(s.end)))
            .zip(&self.clamp_turns_rad)
            .map(|(declared, &turn)| declared * turn_about_axis(turn))
            .collect()
    }

    /// Clamp zones of every simulated segment: `length_m` of cable at each end is not checked
    /// against the link its guide is screwed onto, nor against the link that one is fixed to
    /// (a guide on a fixed child frame such as a flange sits on the parent's collider).
    pub fn clamp_zones(&self, setup: &Setup, length_m: f64) -> Vec<Vec<ClampZone>> {
        let zones = |g: usize, end: GuideEnd| {
            let guide = &setup.guides[g];
            let mut links = vec![guide.link];
            if guide.body != guide.link {
                links.push(guide.body);
            }
            links.into_iter().map(move |link| ClampZone {
                end,
                link,
                length_m,
            })
        };
        self.segments
            .iter()
            .map(|s| {
                zones(s.start.0, GuideEnd::Start)
                    .chain(zones(s.end.0, GuideEnd::End))
                    .collect()
            })
            .collect()
    }
}

/// One length per segment, one configuration per guide, each in range.
fn check_counts(setup: &Setup, path: &CablePath) -> Result<(), MotionTestError> {
    if path.lengths.len() != setup.segment_count() {
        return Err(MotionTestError::SegmentCount {
            expected: setup.segment_count(),
            got: path.lengths.len(),
        });
    }
    if path.configurations.len() != setup.guides.len() {
        return Err(MotionTestError::GuideCount {
            expected: setup.guides.len(),
            got: path.configurations.len(),
        });
    }
    for (g, (&index, guide)) in path.configurations.iter().zip(&setup.guides).enumerate() {
        if index >= guide.configurations.len() {
            return Err(MotionTestError::ConfigurationIndex {
                guide: g,
                name: guide.name.clone(),
                index,
                count: guide.configurations.len(),
            });
        }
    }
    Ok(())
}

/// S = 0 exactly when the segment's two configurations are one place
/// ([`Setup::is_admissible`]). Lengths outside the segment's candidate list are accepted:
/// the simulation does not need them to be candidates.
fn check_admissible(setup: &Setup, path: &CablePath, m: usize) -> Result<(), MotionTestError> {
    let pv = path.pv(m);
    if setup.is_admissible(m, pv.sub_segments, pv.start, pv.end) {
        return Ok(());
    }
    let (a, b) = setup.segment_guides(m);
    let names = format!(
        "{} \"{}\" and {} \"{}\"",
        setup.guides[a].name,
        setup.guides[a].configurations[pv.start].name,
        setup.guides[b].name,
        setup.guides[b].configurations[pv.end].name
    );
    let problem = if pv.sub_segments == 0 {
        format!("length 0 needs coincident guides, but {names} are different places")
    } else {
        format!("{names} coincide (one clamp), so the length must be 0")
    };
    Err(MotionTestError::Inadmissible {
        segment: m,
        sub_segments: pv.sub_segments,
        problem,
    })
}

/// The motion must drive the setup's robot: same actuated joints, same order.
pub(super) fn check_motion(setup: &Setup, motion: &Motion) -> Result<(), MotionTestError> {
    let robot = &setup.robot;
    let names: Vec<&str> = (0..robot.dof())
        .map(|j| robot.actuated_joint(j).name.as_str())
        .collect();
    if motion
        .joint_names()
        .iter()
        .map(String::as_str)
        .ne(names.iter().copied())
    {
        return Err(MotionTestError::MotionJoints {
            motion: motion.joint_names().join(", "),
            robot: names.join(", "),
        });
    }
    Ok(())
}
