//! One PV at one robot pose: the guides' world poses, the connected geometry, the static
//! equilibrium and the three stress metrics against the setup's limits.

use super::TestPose;
use crate::geometry::{ConnectError, connect, reaches, sag_direction};
use crate::path::Pv;
use crate::pose::Pose;
use crate::rigid_chain::{
    ConvergenceWindow, DynamicsSettings, LinearConnect, SegmentShape, connect_linear, relax,
};
use crate::setup::{Setup, Thresholds};
use crate::statics::{FarEnd, RodParameters, SolverOptions, StaticSolver, continuation};
use crate::stress::contact::{
    ContactError, GuideEnd, Obstacles, min_clearance, min_clearance_to_links,
};
use crate::stress::{BendRadius, min_bend_radius, stretch};
use nalgebra::{Point3, Vector3};
use serde::Serialize;
use std::borrow::Borrow;
use std::ops::Range;

/// How the start shape of a segment is obtained, and which solver finds its equilibrium.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConnectMethod {
    /// Hermite curve + rotation-minimizing frames, then the quasi-static Newton solver.
    Hermite,
    /// The paper's previous method: a straight cable dragged into the end guide and relaxed
    /// in rapier3d (two orders of magnitude slower; for comparison).
    Linear,
}

/// The stress limit a PV violates first (in the order contact, stretch, bend), or why it
/// could not be evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rejection {
    /// The cable is shorter than the distance between its guides.
    TooShort,
    /// The connected geometry or the static solver failed (reported, not fatal).
    Diverged,
    /// Clearance to the robot below the contact threshold.
    Contact,
    /// Centreline length / natural length above the stretch threshold.
    Stretch,
    /// Bend radius below the minimum.
    Bend,
}

impl Rejection {
    /// Every kind, in report order.
    pub const ALL: [Rejection; 5] = [
        Rejection::TooShort,
        Rejection::Diverged,
        Rejection::Contact,
        Rejection::Stretch,
        Rejection::Bend,
    ];

    /// Short name for people.
    pub fn name(self) -> &'static str {
        match self {
            Rejection::TooShort => "too short",
            Rejection::Diverged => "solver failed",
            Rejection::Contact => "contact",
            Rejection::Stretch => "stretch",
            Rejection::Bend => "bend radius",
        }
    }
}

/// How a PV failed the attachment test: which limit, how far past it, where on the cable and
/// at which test pose — what a diagnosis of "no path" ranks its nearest misses by.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Miss {
    /// The first limit violated.
    pub rejection: Rejection,
    /// How far past the limit, relative to it: contact, the clearance deficit over the
    /// cable's diameter; stretch (and a cable too short for its clamps), the excess stretch
    /// over the allowed excess; bend, the radius deficit over the minimum radius. Infinite
    /// when nothing was measured (a failed solve, a verdict read from a dictionary).
    pub severity: f64,
    /// The measured value: clearance (m), stretch ratio, or bend radius (m); NaN when not
    /// measured.
    pub value: f64,
    /// Index of the test pose where it failed first.
    pub pose: usize,
    /// Where along the piece (m of cable from its start clamp); NaN for the whole piece.
    pub at_m: f64,
}

impl Miss {
    /// A verdict without measurements (e.g. from a dictionary).
    pub fn unmeasured(rejection: Rejection) -> Miss {
        Miss {
            rejection,
            severity: f64::INFINITY,
            value: f64::NAN,
            pose: 0,
            at_m: f64::NAN,
        }
    }

    /// The miss of a limit a lookup found violated at test pose `pose`, from the looked-up
    /// margins `[clearance mm, stretch, curvature 1/m]` (unmeasured without them). The
    /// place on the cable is not known.
    pub fn looked_up(
        setup: &Setup,
        rejection: Rejection,
        margins: Option<[f64; 3]>,
        pose: usize,
    ) -> Miss {
        let limits = &setup.thresholds;
        let unmeasured = Miss {
            pose,
            ..Miss::unmeasured(rejection)
        };
        let Some([clearance_mm, stretch, curvature]) = margins else {
            return unmeasured;
        };
        let (severity, value) = match rejection {
            Rejection::Contact => (
                -clearance_mm * 1e-3 / setup.cable.diameter_m,
                limits.contact_clearance_m + clearance_mm * 1e-3,
            ),
            Rejection::Stretch => {
                let value = limits.stretch - stretch;
                (
                    (value - 1.0) / (limits.stretch - 1.0).max(1e-12) - 1.0,
                    value,
                )
            }
            Rejection::Bend => {
                let limit = limits.static_min_bend_radius_m();
                let radius = 1.0 / (1.0 / limit - curvature);
                ((limit - radius) / limit, radius)
            }
            Rejection::TooShort | Rejection::Diverged => return unmeasured,
        };
        Miss {
            rejection,
            severity: severity.max(0.0),
            value,
            pose,
            at_m: f64::NAN,
        }
    }

    /// The miss of a failed `check` at test pose `pose`; `None` when it passed.
    fn of(
        check: &Check,
        setup: &Setup,
        pose: usize,
        guides: &(Pose, Pose),
        sub_segments: usize,
    ) -> Option<Miss> {
        let rejection = check.rejection?;
        let limits = &setup.thresholds;
        let pitch = setup.cable.sub_segment_pitch_m;
        let excess = |stretch: f64| (stretch - 1.0) / (limits.stretch - 1.0).max(1e-12) - 1.0;
        let measured = |severity: f64, value: f64, at_m: f64| Miss {
            rejection,
            severity: severity.max(0.0),
            value,
            pose,
            at_m,
        };
        Some(match (rejection, check.metrics) {
            (Rejection::TooShort, _) => {
                let distance = (guides.1.translation.vector - guides.0.translation.vector).norm();
                let stretch = distance / (sub_segments as f64 * pitch);
                measured(excess(stretch), stretch, f64::NAN)
            }
            (Rejection::Contact, Some(m)) => {
                let clearance = m.clearance_m.unwrap_or(f64::NAN);
                let deficit = limits.contact_clearance_m - clearance;
                let at = m
                    .clearance_sub_segment
                    .map_or(f64::NAN, |k| (k as f64 + 0.5) * pitch);
                measured(deficit / setup.cable.diameter_m, clearance, at)
            }
            (Rejection::Stretch, Some(m)) => measured(excess(m.stretch), m.stretch, f64::NAN),
            (Rejection::Bend, Some(m)) => {
                let limit = limits.static_min_bend_radius_m();
                let at = m.min_bend_node as f64 * pitch;
                measured(
                    (limit - m.min_bend_radius_m) / limit,
                    m.min_bend_radius_m,
                    at,
                )
            }
            _ => Miss {
                pose,
                ..Miss::unmeasured(rejection)
            },
        })
    }
}

/// The stress metrics of one equilibrium shape.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Lowest signed clearance to the robot (m), clamp zones excluded; `None` when nothing
    /// was checked.
    pub clearance_m: Option<f64>,
    /// Link of the lowest clearance (index into `robot.links`).
    pub clearance_link: Option<usize>,
    /// Sub-segment of the lowest clearance.
    pub clearance_sub_segment: Option<usize>,
    /// Centreline length / natural length.
    pub stretch: f64,
    /// Smallest bend radius (m); infinite for a straight cable.
    pub min_bend_radius_m: f64,
    /// Node of the smallest bend radius (0 = start guide).
    pub min_bend_node: usize,
}

/// How far an equilibrium is from each limit, positive when the limit holds: what a
/// dictionary stores per PV and direction ([`crate::dictionary::format::MarginRecord`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Margins {
    /// Clearance − contact limit (mm); infinite when no clearance was measured.
    pub clearance_mm: f64,
    /// Stretch limit − stretch.
    pub stretch: f64,
    /// 1/(minimum bend radius) − 1/(bend radius) (1/m): curvature, so that a straight cable
    /// has a finite margin and the value changes smoothly with the shape.
    pub curvature_per_m: f64,
}

impl Margins {
    /// The margins of `metrics` against `limits` (the static bend radius, margin included).
    pub fn of(metrics: &Metrics, limits: &Thresholds) -> Margins {
        Margins {
            clearance_mm: metrics
                .clearance_m
                .map_or(f64::INFINITY, |c| (c - limits.contact_clearance_m) * 1e3),
            stretch: limits.stretch - metrics.stretch,
            curvature_per_m: 1.0 / limits.static_min_bend_radius_m()
                - 1.0 / metrics.min_bend_radius_m,
        }
    }

    /// `[clearance_mm, stretch, curvature_per_m]`.
    pub fn to_array(self) -> [f64; 3] {
        [self.clearance_mm, self.stretch, self.curvature_per_m]
    }

    /// The limit `[clearance, stretch, curvature]` margins violate first, in the order of
    /// [`Evaluator::check`] (contact, stretch, bend); `None` when all are non-negative.
    pub fn first_violation(margins: [f64; 3]) -> Option<Rejection> {
        let kinds = [Rejection::Contact, Rejection::Stretch, Rejection::Bend];
        kinds
            .into_iter()
            .zip(margins)
            .find(|(_, m)| *m < 0.0)
            .map(|(k, _)| k)
    }
}

/// The outcome of one PV at one pose.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The metrics, when an equilibrium was found (and the segment has a cable).
    pub metrics: Option<Metrics>,
    /// The first violated limit, `None` when all three hold.
    pub rejection: Option<Rejection>,
    /// Why, for people (only for a rejection).
    pub detail: Option<String>,
}

impl Check {
    fn pass(metrics: Option<Metrics>) -> Check {
        Check {
            metrics,
            rejection: None,
            detail: None,
        }
    }

    fn fail(rejection: Rejection, detail: String, metrics: Option<Metrics>) -> Check {
        Check {
            metrics,
            rejection: Some(rejection),
            detail: Some(detail),
        }
    }

    /// True when all three limits hold.
    pub fn passed(&self) -> bool {
        self.rejection.is_none()
    }
}

/// Everything a PV evaluation needs besides the PV and the pose, prepared once per run.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    setup: &'a Setup,
    obstacles: Obstacles,
    rod: RodParameters,
    solver: SolverOptions,
    method: ConnectMethod,
    /// Every link at the identity: the frame of an intra-link segment's own link.
    link_frame_poses: Vec<Pose>,
}

impl<'a> Evaluator<'a> {
    /// Prepares the robot's obstacles and the cable model of `setup`.
    pub fn new(setup: &'a Setup, method: ConnectMethod) -> Result<Evaluator<'a>, ContactError> {
        Ok(Evaluator {
            setup,
            obstacles: Obstacles::from_robot(&setup.robot)?,
            rod: RodParameters::new(&setup.cable, setup.gravity_m_s2),
            solver: SolverOptions::STRESS_CHECK,
            method,
            link_frame_poses: vec![Pose::identity(); setup.robot.links.len()],
        })
    }

    /// The setup this evaluator checks against.
    pub fn setup(&self) -> &'a Setup {
        self.setup
    }

    /// Checks PV `pv` of segment `m` at `pose`. A zero-length PV (coincident guides) has no
    /// cable and passes.
    pub fn check(&self, m: usize, pv: &Pv, pose: &TestPose) -> Check {
        self.check_in(m, pv, &self.scene_at(pose))
    }

    /// Where a PV is solved at `pose`: in the world frame, or — for a pose that measures
    /// clearance against one link, an intra-link segment's — in that link's frame with
    /// gravity turned into it. The physics is the same; the arithmetic is then exactly a
    /// dictionary build's ([`Evaluator::link_frame_metrics`]), so that the two cannot part on
    /// rounding where a piece has two equilibria close together.
    fn scene_at<'s>(&'s self, pose: &'s TestPose) -> Scene<'s> {
        match pose.clearance_link {
            Some(link) => {
                let down = pose.gravity_in_link(link, &self.rod.gravity_m_s2);
                self.link_frame_scene(link, &down)
            }
            None => Scene {
                link_poses: &pose.link_poses,
                gravity_m_s2: self.rod.gravity_m_s2,
                clearance_link: None,
            },
        }
    }

    /// The scene of `link`'s frame with gravity along `down` (unit, in that frame), clearance
    /// against that link only.
    fn link_frame_scene(&self, link: usize, down: &Vector3<f64>) -> Scene<'_> {
        Scene {
            link_poses: &self.link_frame_poses,
            gravity_m_s2: down * self.rod.gravity_m_s2.norm(),
            clearance_link: Some(link),
        }
    }

    /// Checks PV `pv` of segment `m` with the links at `link_poses` (world frame).
    pub fn check_at(&self, m: usize, pv: &Pv, link_poses: &[Pose]) -> Check {
        let scene = Scene {
            link_poses,
            gravity_m_s2: self.rod.gravity_m_s2,
            clearance_link: None,
        };
        self.check_in(m, pv, &scene)
    }

    /// The metrics of the PVs `(S, start, end)` of intra-link segment `m`, one per length of
    /// `lengths` (sorted, > 0), in the link's frame under gravity along `down` (unit vector
    /// in that frame), clearance against the own link: the link-frame twin of
    /// [`Evaluator::first_rejections`] at one pose, lengths continued the same way (in
    /// blocks of [`CONTINUATION_BLOCK`]), every length measured (none skipped). `Err` with
    /// the rejection when there is no equilibrium (a cable too short for its clamps, a failed
    /// solve).
    pub fn link_frame_metrics(
        &self,
        m: usize,
        (start, end): (usize, usize),
        lengths: &[usize],
        down: &Vector3<f64>,
    ) -> Vec<Result<Metrics, Rejection>> {
        let setup = self.setup;
        let (a, b) = setup.segment_guides(m);
        let scene = self.link_frame_scene(setup.guides[a].body, down);
        let declared = (
            setup.guide_world_pose(scene.link_poses, a, start),
            setup.guide_world_pose(scene.link_poses, b, end),
        );
        let turns = ClampTurns::new(setup, m, (start, end), lengths);
        let mut solver = StaticSolver::default();
        let mut metrics = vec![Err(Rejection::Diverged); lengths.len()];
        self.continue_lengths(
            &mut solver,
            m,
            (&declared, &turns),
            &scene,
            lengths.iter().copied(),
            |length, _, check| {
                if let Ok(i) = lengths.binary_search(&length) {
                    metrics[i] = match (check.metrics, check.rejection) {
                        (Some(metrics), _) => Ok(metrics),
                        (None, rejection) => Err(rejection.unwrap_or(Rejection::Diverged)),
                    };
                }
            },
        );
        metrics
    }

    /// The equilibrium of PV `pv` of segment `m` with the links at `link_poses` under the
    /// setup's gravity: the shape the checks judge, for drawing it. Empty for a zero-length
    /// PV; `Err` with the reason when there is no equilibrium.
    pub fn equilibrium_nodes(
        &self,
        m: usize,
        pv: &Pv,
        link_poses: &[Pose],
    ) -> Result<Vec<Point3<f64>>, String> {
        if pv.sub_segments == 0 {
            return Ok(Vec::new());
        }
        let (start, end) =
            self.setup
                .clamp_poses(link_poses, m, pv.sub_segments, (pv.start, pv.end));
        self.equilibrium(&start, &end, pv.sub_segments, self.rod.gravity_m_s2)
            .map_err(|check| check.detail.unwrap_or_else(|| "no equilibrium".into()))
    }

    fn check_in(&self, m: usize, pv: &Pv, scene: &Scene<'_>) -> Check {
        if pv.sub_segments == 0 {
            return Check::pass(None);
        }
        let (start, end) =
            self.setup
                .clamp_poses(scene.link_poses, m, pv.sub_segments, (pv.start, pv.end));
        let nodes = match self.equilibrium(&start, &end, pv.sub_segments, scene.gravity_m_s2) {
            Ok(nodes) => nodes,
            Err(check) => return check,
        };
        self.judge(m, &start, &end, &nodes, pv.sub_segments, scene)
    }

    /// How each length of `lengths` (sorted, > 0) fails (its [`Miss`]; `None`: it holds) at
    /// the guide configurations `(start, end)` of segment `m`, over `poses` (stopping at a
    /// length's first failing pose): the verdicts of the PVs `(S, start, end)` that
    /// [`Evaluator::check`] gives pose by pose, solved with continuation — at each pose the
    /// lengths in increasing order, the first from the connected geometry, the second from
    /// the first's deviation from its connected geometry ([`continuation::change_length`]),
    /// the others extrapolated from the last two ([`continuation::extrapolate_length`]). The
    /// linear method relaxes every PV from scratch.
    ///
    /// For an intra-link segment the lengths are continued in fixed blocks
    /// ([`CONTINUATION_BLOCK`]): in each block that holds a length still open, every length
    /// from the block's start up to the longest open one, also lengths not asked for and
    /// those that failed at an earlier pose. A length's shape then depends only on the pose,
    /// its clamps and its length — not on which other lengths are asked for — exactly as in
    /// a dictionary's build ([`Evaluator::link_frame_metrics`]), so that a piece with two
    /// equilibria (a loop that can hang on either side of its link) lands on the same one
    /// in a dictionary built from any setup that offers its clamps.
    pub fn first_rejections<P: Borrow<TestPose>>(
        &self,
        m: usize,
        pair: (usize, usize),
        lengths: &[usize],
        poses: &[P],
    ) -> Vec<Option<Miss>> {
        self.first_rejections_of(m, pair, lengths, poses, &vec![true; lengths.len()])
    }

    /// [`Evaluator::first_rejections`] of the lengths marked in `wanted` only (`None` for the
    /// others); the unwanted ones are still solved where a longer wanted one's continuation
    /// needs them.
    pub fn first_rejections_of<P: Borrow<TestPose>>(
        &self,
        m: usize,
        (start, end): (usize, usize),
        lengths: &[usize],
        poses: &[P],
        wanted: &[bool],
    ) -> Vec<Option<Miss>> {
        let mut verdicts: Vec<Option<Miss>> = vec![None; lengths.len()];
        let mut solver = StaticSolver::default();
        let open = |verdicts: &[Option<Miss>], i: usize| wanted[i] && verdicts[i].is_none();
        if self.setup.is_intra_link(m) {
            let turns = ClampTurns::new(self.setup, m, (start, end), lengths);
            for (p, pose) in poses.iter().enumerate() {
                let (scene, declared) = self.at_pose(m, (start, end), pose.borrow());
                let open_lengths: Vec<usize> = (0..lengths.len())
                    .filter(|&i| open(&verdicts, i))
                    .map(|i| lengths[i])
                    .collect();
                self.continue_lengths(
                    &mut solver,
                    m,
                    (&declared, &turns),
                    &scene,
                    open_lengths.into_iter(),
                    |length, guides, check| {
                        if let Ok(i) = lengths.binary_search(&length)
                            && open(&verdicts, i)
                        {
                            verdicts[i] = Miss::of(check, self.setup, p, guides, length);
                        }
                    },
                );
            }
            return verdicts;
        }
        let turns: Vec<Pose> = lengths
            .iter()
            .map(|&s| self.setup.end_clamp_turn(m, s, (start, end)))
            .collect();
        for (p, pose) in poses.iter().enumerate() {
            let (scene, declared) = self.at_pose(m, (start, end), pose.borrow());
            // The last two solutions at this pose, the nearest first.
            let mut earlier: Vec<Solved> = Vec::with_capacity(3);
            for (i, (&length, turn)) in lengths.iter().zip(&turns).enumerate() {
                if !open(&verdicts, i) {
                    continue;
                }
                let guides = (declared.0, declared.1 * turn);
                let check = self.next_length(&mut solver, &mut earlier, m, &guides, length, &scene);
                verdicts[i] = Miss::of(&check, self.setup, p, &guides, length);
            }
        }
        verdicts
    }

    /// Solves the `wanted` lengths (ascending, > 0) between the `declared` clamp poses (the
    /// end clamp turned by `turns`) in `scene`, in the [`continuation_chains`] that cover
    /// them, each chain by continuation from the connected geometry at its first length, and
    /// hands every length solved (wanted or not), its clamp poses and its check to `visit`.
    fn continue_lengths(
        &self,
        solver: &mut StaticSolver,
        m: usize,
        (declared, turns): (&(Pose, Pose), &ClampTurns),
        scene: &Scene<'_>,
        wanted: impl Iterator<Item = usize>,
        mut visit: impl FnMut(usize, &(Pose, Pose), &Check),
    ) {
        let pitch = self.setup.cable.sub_segment_pitch_m;
        for chain in continuation_chains(wanted, reaching(declared, pitch)) {
            let mut earlier: Vec<Solved> = Vec::with_capacity(3);
            for length in chain {
                let guides = (declared.0, declared.1 * turns.at(self.setup, m, length));
                let check = self.next_length(solver, &mut earlier, m, &guides, length, scene);
                visit(length, &guides, &check);
            }
        }
    }

    /// The first pose of `poses` (in their order) where PV `pv` of segment `m` violates a
    /// limit, with its check; `None` when it holds them all. Each pose's equilibrium starts
    /// from the previous poses', carried along by the guides' motion and extrapolated
    /// ([`continuation::follow_guides_extrapolated`]): the quasi-static cable moved slowly
    /// through the poses, on the branch it started on.
    pub fn sweep<'p>(
        &self,
        m: usize,
        pv: &Pv,
        poses: &'p [TestPose],
    ) -> Option<(&'p TestPose, Check)> {
        if pv.sub_segments == 0 {
            return None;
        }
        let mut solver = StaticSolver::default();
        // The last two poses' solutions and guides, the last first.
        let mut earlier: Vec<(Solved, (Pose, Pose))> = Vec::with_capacity(3);
        let turn = self
            .setup
            .end_clamp_turn(m, pv.sub_segments, (pv.start, pv.end));
        for pose in poses {
            let (scene, declared) = self.at_pose(m, (pv.start, pv.end), pose);
            let guides = (declared.0, declared.1 * turn);
            let warm = Warm::Poses(&earlier);
            let check = match self.solve_warm(&mut solver, &guides, pv.sub_segments, &scene, warm) {
                Ok(solved) => {
                    let check = self.judge(
                        m,
                        &guides.0,
                        &guides.1,
                        &solved.nodes,
                        pv.sub_segments,
                        &scene,
                    );
                    earlier.insert(0, (solved, guides));
                    earlier.truncate(2);
                    check
                }
                Err(check) => {
                    earlier.clear();
                    check
                }
            };
            if !check.passed() {
                return Some((pose, check));
            }
        }
        None
    }

    /// Checks the next length of a continuation over lengths at one pose: solved from
    /// `earlier` (the last solutions, the nearest first), which it then joins; from the
    /// connected geometry when that fails.
    fn next_length(
        &self,
        solver: &mut StaticSolver,
        earlier: &mut Vec<Solved>,
        m: usize,
        guides: &(Pose, Pose),
        length: usize,
        scene: &Scene<'_>,
    ) -> Check {
        let mut solved = self.solve_warm(solver, guides, length, scene, Warm::Length(earlier));
        // A start shape carried over from other lengths can lead Newton astray where the
        // connected geometry would not: a failed warm solve is retried from it.
        let diverged = |r: &Result<Solved, Check>| {
            r.as_ref()
                .is_err_and(|c| c.rejection == Some(Rejection::Diverged))
        };
        if diverged(&solved) && !earlier.is_empty() {
            solved = self.solve_warm(solver, guides, length, scene, Warm::Length(&[]));
        }
        match solved {
            Ok(solved) => {
                let check = self.judge(m, &guides.0, &guides.1, &solved.nodes, length, scene);
                earlier.insert(0, solved);
                earlier.truncate(EXTRAPOLATION_POINTS);
                check
            }
            Err(check) => check,
        }
    }

    /// The scene of `pose` (all links, the setup's gravity) and the world poses of segment
    /// `m`'s guides in the configurations `(start, end)` as declared (the end clamp's twist
    /// reference not yet turned: it depends on the length, see [`Setup::clamp_poses`]).
    fn at_pose<'p>(
        &'p self,
        m: usize,
        (start, end): (usize, usize),
        pose: &'p TestPose,
    ) -> (Scene<'p>, (Pose, Pose)) {
        let (a, b) = self.setup.segment_guides(m);
        let scene = self.scene_at(pose);
        let guides = (
            self.setup.guide_world_pose(scene.link_poses, a, start),
            self.setup.guide_world_pose(scene.link_poses, b, end),
        );
        (scene, guides)
    }

    /// The equilibrium between `guides` with `sub_segments`, started from a neighbouring
    /// solution when `warm` has one (else from the connected geometry); the linear method
    /// always relaxes from scratch.
    fn solve_warm(
        &self,
        solver: &mut StaticSolver,
        guides: &(Pose, Pose),
        sub_segments: usize,
        scene: &Scene<'_>,
        warm: Warm<'_>,
    ) -> Result<Solved, Check> {
        if self.method == ConnectMethod::Linear {
            let nodes = self.relaxed(&guides.0, &guides.1, sub_segments, scene.gravity_m_s2)?;
            return Ok(Solved {
                nodes,
                connected: Vec::new(),
                twist_rad: 0.0,
            });
        }
        let pitch = self.setup.cable.sub_segment_pitch_m;
        let (start_nodes, connected, twist) = match warm {
            Warm::Poses([(last, at), (second, second_at), ..]) => {
                let nodes = continuation::follow_guides_extrapolated(
                    (&last.nodes, (&at.0, &at.1)),
                    (&second.nodes, (&second_at.0, &second_at.1)),
                    (&guides.0, &guides.1),
                    pitch,
                );
                (nodes, Vec::new(), last.twist_rad)
            }
            Warm::Poses([(last, at)]) => {
                let nodes = continuation::follow_guides(
                    &last.nodes,
                    (&at.0, &at.1),
                    (&guides.0, &guides.1),
                    pitch,
                );
                (nodes, Vec::new(), last.twist_rad)
            }
            Warm::Length(earlier @ [nearest, _, ..]) => {
                reaches(&guides.0, &guides.1, sub_segments, pitch).map_err(connect_failure)?;
                let shapes: Vec<&[Point3<f64>]> = earlier
                    .iter()
                    .map(|solved| solved.nodes.as_slice())
                    .collect();
                let nodes = continuation::extrapolate_length(&shapes, sub_segments, pitch);
                (nodes, Vec::new(), nearest.twist_rad)
            }
            Warm::Length(earlier) => {
                let sag = sag_direction(&scene.gravity_m_s2);
                let connected = connect(&guides.0, &guides.1, sub_segments, pitch, &sag)
                    .map_err(connect_failure)?;
                match earlier
                    .first()
                    .filter(|nearest| !nearest.connected.is_empty())
                {
                    Some(nearest) => {
                        let nodes = continuation::change_length(
                            &nearest.nodes,
                            &nearest.connected,
                            &connected.nodes,
                            pitch,
                        );
                        (nodes, connected.nodes, nearest.twist_rad)
                    }
                    None => (
                        connected.nodes.clone(),
                        connected.nodes,
                        connected.twist_correction_rad,
                    ),
                }
            }
            Warm::Poses([]) => {
                let sag = sag_direction(&scene.gravity_m_s2);
                let connected = connect(&guides.0, &guides.1, sub_segments, pitch, &sag)
                    .map_err(connect_failure)?;
                (connected.nodes, Vec::new(), connected.twist_correction_rad)
            }
        };
        let rod = RodParameters {
            gravity_m_s2: scene.gravity_m_s2,
            ..self.rod
        };
        let solved = solver
            .solve(
                &rod,
                &guides.0,
                &FarEnd::Clamped(guides.1),
                &start_nodes,
                Some(twist),
                &self.solver,
            )
            .map_err(|e| Check::fail(Rejection::Diverged, e.to_string(), None))?;
        Ok(Solved {
            nodes: solved.nodes,
            connected,
            twist_rad: solved.twist_rad,
        })
    }

    /// Equilibrium nodes between two guide poses, or the failed check.
    fn equilibrium(
        &self,
        start: &Pose,
        end: &Pose,
        sub_segments: usize,
        gravity_m_s2: Vector3<f64>,
    ) -> Result<Vec<Point3<f64>>, Check> {
        let scene = Scene {
            link_poses: &[],
            gravity_m_s2,
            clearance_link: None,
        };
        let mut solver = StaticSolver::default();
        self.solve_warm(
            &mut solver,
            &(*start, *end),
            sub_segments,
            &scene,
            Warm::Length(&[]),
        )
        .map(|solved| solved.nodes)
    }

    fn relaxed(
        &self,
        start: &Pose,
        end: &Pose,
        sub_segments: usize,
        gravity_m_s2: Vector3<f64>,
    ) -> Result<Vec<Point3<f64>>, Check> {
        let cable = &self.setup.cable;
        let settings = DynamicsSettings::relaxation(gravity_m_s2);
        if let Some(check) = too_short(start, end, sub_segments, cable.sub_segment_pitch_m) {
            return Err(check);
        }
        let diverged = |e: crate::rigid_chain::DynamicsError| {
            Check::fail(Rejection::Diverged, e.to_string(), None)
        };
        let linear = connect_linear(
            cable,
            start,
            end,
            sub_segments,
            &settings,
            &LinearConnect::default(),
        )
        .map_err(diverged)?;
        let shape = SegmentShape {
            start_guide: *start,
            end_guide: *end,
            nodes: &linear.nodes,
            frames: &linear.frames,
        };
        let relaxed =
            relax(cable, &shape, &settings, &ConvergenceWindow::default()).map_err(diverged)?;
        Ok(relaxed.nodes)
    }

    /// The three metrics of an equilibrium shape against the thresholds.
    fn judge(
        &self,
        m: usize,
        start: &Pose,
        end: &Pose,
        nodes: &[Point3<f64>],
        sub_segments: usize,
        scene: &Scene<'_>,
    ) -> Check {
        let setup = self.setup;
        let pitch = setup.cable.sub_segment_pitch_m;
        let (a, b) = setup.segment_guides(m);
        let zones = [
            setup.clamp_zone(GuideEnd::Start, setup.guides[a].link),
            setup.clamp_zone(GuideEnd::End, setup.guides[b].link),
        ];
        let radius = 0.5 * setup.cable.diameter_m;
        let clearance = match scene.clearance_link {
            None => min_clearance(&self.obstacles, scene.link_poses, nodes, radius, &zones),
            Some(link) => min_clearance_to_links(
                &self.obstacles,
                scene.link_poses,
                nodes,
                radius,
                &zones,
                std::slice::from_ref(&link),
            ),
        };
        let clearance = match clearance {
            Ok(clearance) => clearance,
            Err(e) => return Check::fail(Rejection::Diverged, e.to_string(), None),
        };
        let bend: BendRadius = min_bend_radius(
            nodes,
            &start.rotation.transform_vector(&Vector3::z()),
            &end.rotation.transform_vector(&Vector3::z()),
            pitch,
        );
        let metrics = Metrics {
            clearance_m: clearance.map(|c| c.clearance_m),
            clearance_link: clearance.map(|c| c.link),
            clearance_sub_segment: clearance.map(|c| c.sub_segment),
            stretch: stretch(nodes, sub_segments as f64 * pitch),
            min_bend_radius_m: bend.radius_m,
            min_bend_node: bend.node,
        };
        verdict(setup, metrics)
    }
}

/// Earlier lengths a start shape is extrapolated from: linearly through two. Measured on
/// the bundled pick-and-place attachment test, a quadratic through three took as many Newton
/// steps (3.16 per solve on average).
const EXTRAPOLATION_POINTS: usize = 2;

/// Intra-link lengths are continued in blocks of this many sub-segments, `[32k, 32k + 32)`,
/// each started from the connected geometry at its first length that reaches between the
/// clamps: a piece's equilibrium then depends on its clamps, its length and gravity only —
/// not on which other lengths are asked for — so a dictionary built from any setup that
/// offers the clamps stores the equilibrium `solve --setup` finds. Measured on the
/// robot-level pick-and-place attachment test (one run each, on-the-fly intra-link part):
/// blocks of 8 27.3 s, 16 27.6 s, 32 23.5 s; one chain from the shortest length asked for
/// (not history-free) 26.3 s. Nearly taut lengths are slow to solve: blocks of 64 from
/// length 1 made the design-space tests 15 % slower than blocks of 32.
pub const CONTINUATION_BLOCK: usize = 32;

/// The continuation chains covering the `wanted` lengths (ascending, > 0) between clamps
/// that the shortest cable of `reaching` sub-segments reaches: each shorter (too short)
/// length alone; then per block of [`CONTINUATION_BLOCK`] that holds one, every length from
/// the block's start (at least `reaching`) up to its longest wanted one.
fn continuation_chains(wanted: impl Iterator<Item = usize>, reaching: usize) -> Vec<Range<usize>> {
    let mut chains: Vec<Range<usize>> = Vec::new();
    for length in wanted {
        if length < reaching {
            chains.push(length..length + 1);
            continue;
        }
        let start = (length / CONTINUATION_BLOCK * CONTINUATION_BLOCK).max(reaching);
        match chains.last_mut() {
            Some(chain) if chain.start == start => chain.end = chain.end.max(length + 1),
            _ => chains.push(start..length + 1),
        }
    }
    chains
}

/// The shortest cable (sub-segments) that reaches between clamps at `guides`.
fn reaching(guides: &(Pose, Pose), pitch_m: f64) -> usize {
    let distance = (guides.1.translation.vector - guides.0.translation.vector).norm();
    (distance / pitch_m).ceil().max(1.0) as usize
}

/// The end clamp's installed-twist turn of every length up to the longest a pair's chains
/// visit, computed once per pair of clamps (it does not depend on the pose).
struct ClampTurns {
    pair: (usize, usize),
    turns: Vec<Pose>,
}

impl ClampTurns {
    /// The turns of `pair` of segment `m` for the lengths 1 ..= the longest of `lengths`
    /// (ascending).
    fn new(setup: &Setup, m: usize, pair: (usize, usize), lengths: &[usize]) -> ClampTurns {
        let last = lengths.last().copied().unwrap_or(0);
        ClampTurns {
            pair,
            turns: (1..=last)
                .map(|s| setup.end_clamp_turn(m, s, pair))
                .collect(),
        }
    }

    /// The turn of `length` (computed on the spot outside the precomputed range).
    fn at(&self, setup: &Setup, m: usize, length: usize) -> Pose {
        match length.checked_sub(1).and_then(|k| self.turns.get(k)) {
            Some(turn) => *turn,
            None => setup.end_clamp_turn(m, length, self.pair),
        }
    }
}

/// A solved segment: its nodes, its total twist, and (when solved from it) the connected
/// geometry it started from, for the next length's start shape.
struct Solved {
    nodes: Vec<Point3<f64>>,
    connected: Vec<Point3<f64>>,
    twist_rad: f64,
}

/// The neighbouring solution a solve starts from, if any.
enum Warm<'a> {
    /// The same pose, shorter lengths, the nearest first (none: the connected geometry).
    Length(&'a [Solved]),
    /// The previous poses of a sweep and their guides, the last first (none: the connected
    /// geometry).
    Poses(&'a [(Solved, (Pose, Pose))]),
}

/// Where a PV is checked: the links' poses, gravity in the same frame, and the one link
/// that counts for clearance (`None`: all).
struct Scene<'p> {
    link_poses: &'p [Pose],
    gravity_m_s2: Vector3<f64>,
    clearance_link: Option<usize>,
}

/// The first limit `metrics` violates, in the order contact, stretch, bend.
fn verdict(setup: &Setup, metrics: Metrics) -> Check {
    let limits = &setup.thresholds;
    if let (Some(clearance), Some(link)) = (metrics.clearance_m, metrics.clearance_link)
        && clearance < limits.contact_clearance_m
    {
        let detail = format!(
            "clearance {:.1} mm to {} (limit {:.1} mm)",
            clearance * 1e3,
            setup.robot.links[link].name,
            limits.contact_clearance_m * 1e3
        );
        return Check::fail(Rejection::Contact, detail, Some(metrics));
    }
    if metrics.stretch > limits.stretch {
        let detail = format!("stretch {:.4} (limit {})", metrics.stretch, limits.stretch);
        return Check::fail(Rejection::Stretch, detail, Some(metrics));
    }
    if metrics.min_bend_radius_m < limits.static_min_bend_radius_m() {
        let detail = format!(
            "bend radius {:.1} mm at node {} (limit {:.1} mm{})",
            metrics.min_bend_radius_m * 1e3,
            metrics.min_bend_node,
            limits.static_min_bend_radius_m() * 1e3,
            static_margin_note(limits)
        );
        return Check::fail(Rejection::Bend, detail, Some(metrics));
    }
    Check::pass(Some(metrics))
}

/// " incl. a 4.0 mm static margin" when the setup asks for one.
fn static_margin_note(limits: &Thresholds) -> String {
    if limits.static_bend_margin_m > 0.0 {
        format!(
            " incl. a {:.1} mm static margin",
            limits.static_bend_margin_m * 1e3
        )
    } else {
        String::new()
    }
}

fn connect_failure(error: ConnectError) -> Check {
    match error {
        ConnectError::TooShort { .. } => Check::fail(Rejection::TooShort, error.to_string(), None),
        _ => Check::fail(Rejection::Diverged, error.to_string(), None),
    }
}

/// The too-short check of [`connect`] for the linear method, which has no such test.
fn too_short(start: &Pose, end: &Pose, sub_segments: usize, pitch: f64) -> Option<Check> {
    let distance = (end.translation.vector - start.translation.vector).norm();
    let natural = sub_segments as f64 * pitch;
    (distance >= natural).then(|| {
        connect_failure(ConnectError::TooShort {
            distance_m: distance,
            natural_length_m: natural,
            required_stretch: distance / natural,
        })
    })
}
