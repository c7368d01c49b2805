//! The simulated cable of a path: its non-zero segments (declared ones, and spans where
//! optional clamps are left out), with the guides of every S = 0 segment merged into one
//! clamp.

use super::MotionTestError;
use crate::motion::Motion;
use crate::path::CablePath;
use crate::pose::Pose;
use crate::setup::{Setup, SwivelSplit, turn_about_axis};
use crate::statics::{Hold, Holds, RodParameters};
use crate::stress::{ClampZone, GuideEnd};

/// One simulated segment: a segment of the setup (declared, or a span over optional guides)
/// with S > 0.
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
    /// How its clamps hold it.
    pub holds: Holds,
    /// The sliding guide or retraction outlet it runs through, if any (index into the
    /// setup's guides): followed quasi-statically, its split carried step to step.
    pub through: Option<usize>,
    /// The swivel clamp between two pieces it runs through, if any, and where it holds the
    /// cable ([`Setup::swivel_of`]): simulated as one piece held there.
    pub swivel: Option<SwivelSplit>,
}

impl PlannedSegment {
    /// The cable model `params` held as this piece's clamps hold it.
    pub fn rod(&self, params: &RodParameters) -> RodParameters {
        RodParameters {
            holds: self.holds,
            ..*params
        }
    }
}

/// The simulated cable: its segments in order, consecutive ones sharing a clamp.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plan {
    pub segments: Vec<PlannedSegment>,
    /// Per simulated clamp, its turn about the cable axis from the declared configuration
    /// (rad): the installed cable's twist references carried from the first clamp along the
    /// whole cable (see [`Setup::clamp_poses`]), so every piece is untwisted at installation.
    pub clamp_turns_rad: Vec<f64>,
    /// Per simulated clamp, whether it is a rotating clamp between two pieces: the cable's
    /// turn in it is shared by both, and follows from their torques balancing
    /// ([`Plan::balance_turns`]).
    pub shared_turn: Vec<bool>,
}

impl Plan {
    /// Checks `path` against `setup` ([`CablePath::check`]) and drops its S = 0 segments:
    /// their two guides coincide, so the segments on either side share that clamp.
    pub fn new(setup: &Setup, path: &CablePath) -> Result<Plan, MotionTestError> {
        path.check(setup)?;
        let mut segments = Vec::new();
        for (m, pv) in path.pieces().filter(|(_, pv)| pv.sub_segments > 0) {
            let (a, b) = setup.segment_guides(m);
            segments.push(PlannedSegment {
                setup_index: m,
                sub_segments: pv.sub_segments,
                start: (a, pv.start),
                end: (b, pv.end),
                holds: Holds::of(setup.piece_kinds(m, (pv.start, pv.end))),
                through: setup.segments[m].through,
                swivel: setup.swivel_of(m, pv.sub_segments),
            });
        }
        if segments.is_empty() {
            return Err(MotionTestError::NoCable);
        }
        // A rotating clamp between two pieces holds each of them rigidly at the turn the
        // cable has in it, which the simulation balances.
        let count = segments.len();
        let mut shared_turn = vec![false; count + 1];
        for i in 1..count {
            if segments[i].holds.start == Hold::Rotating {
                shared_turn[i] = true;
                segments[i - 1].holds.end = Hold::Rigid;
                segments[i].holds.start = Hold::Rigid;
            }
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
            shared_turn,
        })
    }

    /// Whether a rotating clamp between two pieces shares the cable's turn between them.
    pub fn shares_turns(&self) -> bool {
        self.shared_turn.contains(&true)
    }

    /// Turns each rotating clamp between two pieces of `guides` (the clamp poses) by the
    /// cable's turn in it, `turns_rad` (one per clamp; 0 elsewhere).
    pub fn turned(&self, guides: &mut [Pose], turns_rad: &[f64]) {
        for ((guide, &shared), &turn) in guides.iter_mut().zip(&self.shared_turn).zip(turns_rad) {
            if shared {
                *guide *= turn_about_axis(turn);
            }
        }
    }

    /// One step of the torque balance at every rotating clamp between two pieces: the
    /// pieces' twists `twists_rad` (Ψ over each, relative to its clamps as turned by
    /// `turns_rad`) change by `δ` and `−δ` when the cable turns by `δ` more in the clamp, and
    /// carry equal torques `GJ Ψ / L` when `(Ψ_a + δ)/S_a = (Ψ_b − δ)/S_b`: each clamp's turn
    /// moves by that `δ`, and the twists with it (the twist being uniform along a piece,
    /// exactly; the shapes, which the twist bends a little, follow at the next solve).
    pub fn balance_turns(&self, turns_rad: &mut [f64], twists_rad: &mut [f64]) {
        for i in (1..self.segments.len()).filter(|&i| self.shared_turn[i]) {
            let (a, b) = (&self.segments[i - 1], &self.segments[i]);
            let (ka, kb) = (1.0 / a.sub_segments as f64, 1.0 / b.sub_segments as f64);
            let delta = (kb * twists_rad[i] - ka * twists_rad[i - 1]) / (ka + kb);
            turns_rad[i] += delta;
            twists_rad[i - 1] += delta;
            twists_rad[i] -= delta;
        }
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

    /// Clamp zones of every simulated segment: the setup's clamp zone at each end is not
    /// checked against the link its guide is screwed onto, nor against the link that one is
    /// fixed to (a guide on a fixed child frame such as a flange sits on the parent's
    /// collider).
    pub fn clamp_zones(&self, setup: &Setup) -> Vec<Vec<ClampZone>> {
        let zones = |g: usize, end: GuideEnd| {
            let guide = &setup.guides[g];
            let mut links = vec![guide.link];
            if guide.body != guide.link {
                links.push(guide.body);
            }
            links
                .into_iter()
                .map(move |link| setup.clamp_zone(end, link))
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
