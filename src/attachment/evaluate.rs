//! One PV at one robot pose: the guides' world poses, the connected geometry, the static
//! equilibrium and the three stress metrics against the setup's limits.

use super::poses::TestPose;
use super::verdict::{Check, Metrics, Miss, Rejection, verdict};
use crate::path::Pv;
use crate::pose::Pose;
use crate::setup::{Setup, Thresholds};
use crate::statics::{Holds, RodParameters, SolverOptions, StaticSolver};
use crate::stress::contact::{
    ContactError, GuideEnd, Obstacles, min_clearance, min_clearance_to_links,
};
use crate::stress::{CurvatureRange, curvatures_per_m};
use nalgebra::{Point3, Vector3};
use serde::Serialize;
use std::borrow::Borrow;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};

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

/// Everything a PV evaluation needs besides the PV and the pose, prepared once per run.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    pub(super) setup: &'a Setup,
    obstacles: Obstacles,
    pub(super) rod: RodParameters,
    pub(super) solver: SolverOptions,
    pub(super) method: ConnectMethod,
    /// Every link at the identity: the frame of an intra-link segment's own link.
    link_frame_poses: Vec<Pose>,
    /// Newton solves (relaxations for the linear method) started, per segment.
    static_solves: StaticSolves,
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
            static_solves: StaticSolves::new(setup.segment_count()),
        })
    }

    /// Static solves (Newton's, or the baseline's relaxations) this evaluator has started for
    /// segment `m` so far: the machine-independent measure of its work.
    pub fn static_solves(&self, m: usize) -> usize {
        self.static_solves
            .0
            .get(m)
            .map_or(0, |n| n.load(Ordering::Relaxed))
    }

    pub(super) fn count_static_solve(&self, m: usize) {
        if let Some(n) = self.static_solves.0.get(m) {
            n.fetch_add(1, Ordering::Relaxed);
        }
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
    /// blocks of [`CONTINUATION_BLOCK`](super::CONTINUATION_BLOCK)), every length measured
    /// (none skipped). `Err` with
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
            (m, self.holds(m, (start, end))),
            (&declared, &turns),
            &scene,
            lengths.iter().copied(),
            |length, _, check, _| {
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
        let scene = Scene {
            link_poses,
            gravity_m_s2: self.rod.gravity_m_s2,
            clearance_link: None,
        };
        self.equilibrium(m, pv, &(start, end), &scene)
            .map(|solved| solved.nodes)
            .map_err(|check| check.detail.unwrap_or_else(|| "no equilibrium".into()))
    }

    fn check_in(&self, m: usize, pv: &Pv, scene: &Scene<'_>) -> Check {
        if pv.sub_segments == 0 {
            return Check::pass(None);
        }
        let (start, end) =
            self.setup
                .clamp_poses(scene.link_poses, m, pv.sub_segments, (pv.start, pv.end));
        match self.equilibrium(m, pv, &(start, end), scene) {
            Ok(solved) => self.judge(m, &(start, end), &solved, scene),
            Err(check) => check,
        }
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
    /// The lengths are continued in fixed blocks ([`CONTINUATION_BLOCK`]): in each block that
    /// holds a length still open, every length from the block's start up to the longest open
    /// one, also lengths not asked for and those that failed at an earlier pose. A length's
    /// verdict then depends only on the poses, its clamps and its length — not on which other
    /// lengths are asked for, nor in which order or batches — so a search that asks for a
    /// few lengths at a time gets the verdicts of one that asks for all, and a dictionary's
    /// build ([`Evaluator::link_frame_metrics`]) lands a piece with two equilibria (a loop
    /// that can hang on either side of its link) on the same one as `solve --setup`.
    ///
    /// [`continuation::change_length`]: crate::statics::continuation::change_length
    /// [`continuation::extrapolate_length`]: crate::statics::continuation::extrapolate_length
    /// [`CONTINUATION_BLOCK`]: super::CONTINUATION_BLOCK
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
        let turns = ClampTurns::new(self.setup, m, (start, end), lengths);
        let piece = (m, self.holds(m, (start, end)));
        // Per length, per motion: how its shapes flex (only where a flexing radius applies).
        type AtPose = (usize, (Pose, Pose));
        let mut flexing: Vec<BTreeMap<usize, FlexWatch<AtPose>>> = match self.watches_flexing(m) {
            true => vec![BTreeMap::new(); lengths.len()],
            false => Vec::new(),
        };
        for (p, pose) in poses.iter().enumerate() {
            let open_lengths: Vec<usize> = (0..lengths.len())
                .filter(|&i| open(&verdicts, i))
                .map(|i| lengths[i])
                .collect();
            if open_lengths.is_empty() {
                break;
            }
            let pose = pose.borrow();
            let (scene, declared) = self.at_pose(m, (start, end), pose);
            self.continue_lengths(
                &mut solver,
                piece,
                (&declared, &turns),
                &scene,
                open_lengths.into_iter(),
                |length, guides, check, solved| {
                    if let Ok(i) = lengths.binary_search(&length)
                        && open(&verdicts, i)
                    {
                        verdicts[i] = Miss::of(check, self.setup, p, guides, length);
                        if let (None, Some(watches), Some(solved)) =
                            (verdicts[i], flexing.get_mut(i), solved)
                        {
                            let watch = watches.entry(pose.motion).or_default();
                            watch.take(solved, guides, check, || (p, *guides));
                        }
                    }
                },
            );
        }
        // A piece that held at every pose and flexes between two poses of a motion keeps the
        // flexing radius at its tightest one (as the static sweep holds it).
        for (i, watches) in flexing.into_iter().enumerate() {
            if !open(&verdicts, i) {
                continue;
            }
            let failure = (watches.into_values()).find_map(|w| self.flexing_failure(w));
            if let Some(((p, guides), check)) = failure {
                verdicts[i] = Miss::of(&check, self.setup, p, &guides, lengths[i]);
            }
        }
        verdicts
    }

    /// How the clamps of segment `m`'s piece between configurations `pair` hold it.
    pub(super) fn holds(&self, m: usize, pair: (usize, usize)) -> Holds {
        Holds::of(self.setup.piece_kinds(m, pair))
    }

    /// Whether the attachment test holds segment `m`'s pieces to the flexing bend radius
    /// over its test poses: an inter-link segment (its clamps move apart and together over a
    /// motion) of a cable with a flexing radius above the fixed one. An intra-link piece is
    /// tested as a dictionary stores it, one pose at a time; the static sweep holds it.
    pub fn watches_flexing(&self, m: usize) -> bool {
        let limits = &self.setup.thresholds;
        !self.setup.is_intra_link(m) && limits.flexing_bend_radius_m() > limits.min_bend_radius_m
    }

    /// The first pose of `poses` (in their order) where PV `pv` of segment `m` violates a
    /// limit, with its check (`None` when it holds them all), and the least bend radius and
    /// clearance met on the way. A piece whose curvature changes somewhere by more than the
    /// setup's flexing amount over the poses must keep the flexing bend radius: when it does
    /// not, it fails at the pose of its tightest bend. With `stop_below`, it stops as soon as a least value is
    /// below that one's (the least can only fall further: the caller's verdict is known). Each pose's equilibrium starts
    /// from the previous poses', carried along by the guides' motion and extrapolated
    /// ([`follow_guides_extrapolated`](crate::statics::continuation::follow_guides_extrapolated)):
    /// the quasi-static cable moved slowly
    /// through the poses, on the branch it started on.
    pub fn sweep<'p>(
        &self,
        m: usize,
        pv: &Pv,
        poses: &'p [TestPose],
        stop_below: Option<&SweptLeast>,
    ) -> Swept<'p> {
        let mut swept = Swept {
            failure: None,
            least: SweptLeast::NONE,
            stopped_below: false,
        };
        if pv.sub_segments == 0 {
            return swept;
        }
        let mut solver = StaticSolver::default();
        // The last two poses' solutions and guides, the last first.
        let mut earlier: Vec<(Solved, (Pose, Pose))> = Vec::with_capacity(3);
        let turn = self
            .setup
            .end_clamp_turn(m, pv.sub_segments, (pv.start, pv.end));
        let mut flexing: FlexWatch<&TestPose> = FlexWatch::default();
        let piece = (m, self.holds(m, (pv.start, pv.end)));
        for pose in poses {
            let (scene, declared) = self.at_pose(m, (pv.start, pv.end), pose);
            let guides = (declared.0, declared.1 * turn);
            let warm = Warm::Poses(&earlier);
            let check =
                match self.solve_warm(&mut solver, piece, &guides, pv.sub_segments, &scene, warm) {
                    Ok(solved) => {
                        let check = self.judge(m, &guides, &solved, &scene);
                        flexing.take(&solved, &guides, &check, || pose);
                        earlier.insert(0, (solved, guides));
                        earlier.truncate(2);
                        check
                    }
                    Err(check) => {
                        earlier.clear();
                        check
                    }
                };
            if let Some(metrics) = &check.metrics {
                swept.least.take(metrics);
            }
            if !check.passed() {
                swept.failure = Some((pose, check));
                return swept;
            }
            if stop_below.is_some_and(|stop| swept.least.below(stop)) {
                swept.stopped_below = true;
                return swept;
            }
        }
        swept.least.flexes = flexing.flexes(&self.setup.thresholds);
        swept.failure = self.flexing_failure(flexing);
        swept
    }

    /// The failure of a piece that flexes over one motion's poses (`watch`) with its tightest
    /// static shape below the flexing bend radius, where that shape was; `None` when it does
    /// not flex or keeps that radius.
    fn flexing_failure<At>(&self, watch: FlexWatch<At>) -> Option<(At, Check)> {
        let limits = &self.setup.thresholds;
        let (change, node) = watch.range.largest_change();
        let flexes = watch.flexes(limits);
        let (at, tightest) = watch.tightest?;
        let metrics = tightest.metrics?;
        let limit = limits.bend_radius_for(true, true);
        if !flexes || metrics.min_bend_radius_m >= limit {
            return None;
        }
        let detail = format!(
            "bend radius {:.1} mm at node {} of a flexing piece (its curvature changes by \
             {change:.1} 1/m at node {node}; flexing limit {:.1} mm{})",
            metrics.min_bend_radius_m * 1e3,
            metrics.min_bend_node,
            limit * 1e3,
            super::verdict::static_margin_note(limits)
        );
        Some((at, Check::fail(Rejection::Bend, detail, Some(metrics))))
    }

    /// The distance between the clamps of configurations `pair` of segment `m` at `pose`
    /// (m): what the shortest cable between them must reach.
    pub fn clamp_distance_m(&self, m: usize, pair: (usize, usize), pose: &TestPose) -> f64 {
        let (_, (start, end)) = self.at_pose(m, pair, pose);
        (end.translation.vector - start.translation.vector).norm()
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

    /// The equilibrium of PV `pv` of segment `m` between its clamp poses `guides` in `scene`
    /// (solved from the connected geometry), or the failed check.
    fn equilibrium(
        &self,
        m: usize,
        pv: &Pv,
        guides: &(Pose, Pose),
        scene: &Scene<'_>,
    ) -> Result<Solved, Check> {
        let mut solver = StaticSolver::default();
        self.solve_warm(
            &mut solver,
            (m, self.holds(m, (pv.start, pv.end))),
            guides,
            pv.sub_segments,
            scene,
            Warm::Length(&[]),
        )
    }

    /// The metrics of an equilibrium `solved` between `(start, end)` against the limits.
    pub(super) fn judge(
        &self,
        m: usize,
        (start, end): &(Pose, Pose),
        solved: &Solved,
        scene: &Scene<'_>,
    ) -> Check {
        let setup = self.setup;
        let nodes = &solved.nodes;
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
        // The stored margin is the lower of the clearances to the robot and to itself: an
        // approach to itself farther than the robot's clearance changes nothing.
        let limit = setup.thresholds.contact_clearance_m;
        let within = clearance.as_ref().map_or(f64::INFINITY, |c| {
            (c.clearance_m - limit).max(0.0) + setup.cable.diameter_m
        });
        let start = solved.from.as_ref().unwrap_or(start);
        let metrics = Metrics::of_shape(
            &setup.cable,
            (nodes, solved.pitch_m),
            (start, end),
            clearance.as_ref(),
            within,
            solved.twist_rad,
        );
        verdict(setup, metrics)
    }
}

/// A piece's static shapes over the poses of one motion as far as flexing goes: how the
/// curvature at each joint ranged, and its tightest shape with where it was (`At`).
#[derive(Debug, Clone)]
struct FlexWatch<At> {
    range: CurvatureRange,
    tightest: Option<(At, Check)>,
}

impl<At> Default for FlexWatch<At> {
    fn default() -> Self {
        FlexWatch {
            range: CurvatureRange::default(),
            tightest: None,
        }
    }
}

impl<At> FlexWatch<At> {
    /// Takes in one more equilibrium `solved` between `guides`, judged `check`; `at` says
    /// where it is, kept when it is the tightest so far.
    fn take(
        &mut self,
        solved: &Solved,
        guides: &(Pose, Pose),
        check: &Check,
        at: impl FnOnce() -> At,
    ) {
        let axis = |pose: &Pose| pose.rotation * Vector3::z();
        let start = solved.from.as_ref().unwrap_or(&guides.0);
        let (nodes, pitch) = (&solved.nodes, solved.pitch_m);
        let curvatures = curvatures_per_m(nodes, &axis(start), &axis(&guides.1), pitch);
        self.range.take(&curvatures);
        let radius = |c: &Check| c.metrics.map_or(f64::INFINITY, |m| m.min_bend_radius_m);
        if self
            .tightest
            .as_ref()
            .is_none_or(|(_, t)| radius(check) < radius(t))
        {
            self.tightest = Some((at(), check.clone()));
        }
    }

    /// Whether the curvature changed somewhere by more than `limits`' flexing amount.
    fn flexes(&self, limits: &Thresholds) -> bool {
        self.range.largest_change().0 > limits.flexing_curvature_change_per_m
    }
}

/// A counter per segment, shared by the threads of a run.
#[derive(Debug)]
struct StaticSolves(Vec<AtomicUsize>);

impl StaticSolves {
    fn new(segments: usize) -> StaticSolves {
        StaticSolves((0..segments).map(|_| AtomicUsize::new(0)).collect())
    }
}

impl Clone for StaticSolves {
    fn clone(&self) -> StaticSolves {
        StaticSolves(
            self.0
                .iter()
                .map(|n| AtomicUsize::new(n.load(Ordering::Relaxed)))
                .collect(),
        )
    }
}

/// Where a PV is checked: the links' poses, gravity in the same frame, and the one link
/// that counts for clearance (`None`: all).
pub(super) struct Scene<'p> {
    pub(super) link_poses: &'p [Pose],
    pub(super) gravity_m_s2: Vector3<f64>,
    pub(super) clearance_link: Option<usize>,
}

/// The end clamp's installed-twist turn of every length up to the longest a pair's chains
/// visit, computed once per pair of clamps (it does not depend on the pose).
pub(super) struct ClampTurns {
    pair: (usize, usize),
    turns: Vec<Pose>,
}

impl ClampTurns {
    /// The turns of `pair` of segment `m` for the lengths 1 ..= the longest of `lengths`
    /// (ascending).
    pub(super) fn new(
        setup: &Setup,
        m: usize,
        pair: (usize, usize),
        lengths: &[usize],
    ) -> ClampTurns {
        let last = lengths.last().copied().unwrap_or(0);
        ClampTurns {
            pair,
            turns: (1..=last)
                .map(|s| setup.end_clamp_turn(m, s, pair))
                .collect(),
        }
    }

    /// The turn of `length` (computed on the spot outside the precomputed range).
    pub(super) fn at(&self, setup: &Setup, m: usize, length: usize) -> Pose {
        match length.checked_sub(1).and_then(|k| self.turns.get(k)) {
            Some(turn) => *turn,
            None => setup.end_clamp_turn(m, length, self.pair),
        }
    }
}

/// A solved segment: its nodes, its total twist, and (when solved from it) the connected
/// geometry it started from, for the next length's start shape.
pub(super) struct Solved {
    pub(super) nodes: Vec<Point3<f64>>,
    pub(super) connected: Vec<Point3<f64>>,
    pub(super) twist_rad: f64,
    /// The cable length between two of its nodes (m): the setup's pitch, but for the free
    /// piece out of a retraction, whose length changes with the travel.
    pub(super) pitch_m: f64,
    /// Where its nodes start when not at the segment's start clamp: a retraction's outlet
    /// (the cable stored in the unit behind it is not free).
    pub(super) from: Option<Pose>,
    /// Through a sliding guide or out of a retraction: the split or travel (m).
    pub(super) slid_m: Option<f64>,
}

/// The neighbouring solution a solve starts from, if any.
pub(super) enum Warm<'a> {
    /// The same pose, shorter lengths, the nearest first (none: the connected geometry).
    Length(&'a [Solved]),
    /// The previous poses of a sweep and their guides, the last first (none: the connected
    /// geometry).
    Poses(&'a [(Solved, (Pose, Pose))]),
}

/// What sweeping one PV over a motion's poses found ([`Evaluator::sweep`]).
#[derive(Debug, Clone)]
pub struct Swept<'p> {
    /// The first pose where a limit is violated, with its check; `None`: none is.
    pub failure: Option<(&'p TestPose, Check)>,
    /// The least values met at the poses solved.
    pub least: SweptLeast,
    /// It stopped before the last pose, a least value below the one asked for: the poses
    /// after were not solved.
    pub stopped_below: bool,
}

/// The least bend radius and clearance of a PV's static shapes over the poses swept: what a
/// motion test's dynamic value is compared with to learn how far the cable swings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweptLeast {
    /// Smallest bend radius (m); infinite when straight everywhere (or not solved).
    pub bend_radius_m: f64,
    /// Lowest clearance to the robot (m); `None` when nothing was checked.
    pub clearance_m: Option<f64>,
    /// The piece flexed over the poses (its curvature changed somewhere by more than the
    /// setup's flexing amount): the flexing bend radius is its limit.
    pub flexes: bool,
}

impl SweptLeast {
    /// Nothing met yet: what a sweep starts from.
    pub const NONE: SweptLeast = SweptLeast {
        bend_radius_m: f64::INFINITY,
        clearance_m: None,
        flexes: false,
    };

    /// Whether a value is below `other`'s: the bend radius, or the clearance when both have
    /// one.
    pub fn below(&self, other: &SweptLeast) -> bool {
        let clearance = match (self.clearance_m, other.clearance_m) {
            (Some(mine), Some(theirs)) => mine < theirs,
            _ => false,
        };
        self.bend_radius_m < other.bend_radius_m || clearance
    }

    /// Takes the metrics of one more pose into account.
    fn take(&mut self, metrics: &Metrics) {
        self.bend_radius_m = self.bend_radius_m.min(metrics.min_bend_radius_m);
        if let Some(clearance) = metrics.clearance_m {
            self.clearance_m = Some(self.clearance_m.map_or(clearance, |c| c.min(clearance)));
        }
    }

    /// The least of both: over the poses of two sweeps (the motions of a cell; flexing in
    /// either).
    pub fn least_with(self, other: SweptLeast) -> SweptLeast {
        SweptLeast {
            flexes: self.flexes || other.flexes,
            bend_radius_m: self.bend_radius_m.min(other.bend_radius_m),
            clearance_m: match (self.clearance_m, other.clearance_m) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            },
        }
    }
}
