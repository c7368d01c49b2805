//! The report assembled from the stages' results: names, counts and the explanation.

use super::super::diagnosis::diagnose;
use super::super::life::path_life;
use super::super::options::{LifeGoal, SolveOptions};
use super::super::search::{MotionSearch, Tried};
use super::data::*;
use super::margins::margins;
use crate::attachment::{ConnectMethod, Evaluator, SegmentPoses, SegmentSets, TestPose};
use crate::chain::ChainSearch;
use crate::json::tidy;
use crate::life::estimate::CableLife;
use crate::motion::{Cell, Motion};
use crate::motion_test::{MotionTestReport, PieceWorst, Worst};
use crate::mounting::mounting_plan;
use crate::path::CablePath;
use crate::setup::Setup;
use std::collections::{BTreeMap, BTreeSet};

/// What the stages of a solve leave for its report.
pub(in crate::solve) struct Stages<'s> {
    pub setup: &'s Setup,
    pub cell: &'s Cell,
    pub options: &'s SolveOptions,
    pub evaluator: &'s Evaluator<'s>,
    pub poses: &'s SegmentPoses,
    pub sets: &'s [SegmentSets],
    pub search: &'s ChainSearch,
    pub outcome: MotionSearch,
    pub timings: Timings,
}

impl SolveReport {
    /// Assembles the report from the stages' results.
    pub(in crate::solve) fn new(stages: Stages<'_>) -> SolveReport {
        let Stages {
            setup,
            cell,
            options,
            evaluator,
            poses,
            sets,
            search,
            outcome,
            timings,
        } = stages;
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let MotionSearch { tried, winner, .. } = &outcome;
        let winner = *winner;
        let best = winner.map(|w| tried[w].path.clone());
        let status = status(options, search, winner);
        let candidates = candidate_outcomes(tried, cell, pitch_mm);
        let static_sweep = sweep_summary(setup, cell, &outcome);
        let diagnosis = matches!(status, Status::NoChain | Status::NonePassedMotionTest)
            .then(|| diagnose(setup, cell, poses, sets, &outcome));
        let unsolved = unsolved(setup, status, &outcome);
        let closest = (unsolved.as_ref())
            .and_then(|u| u.closest.as_ref())
            .map(|c| c.candidate);
        // The one that passed (the winner), else the closest miss, else the last tried.
        let verdicts = tried.iter().map(Tried::passed);
        let shown = shown_index(verdicts, closest);
        let motion_test = shown.and_then(|k| tried[k].report().cloned());
        let runs = shown.map_or(&[][..], |k| tried[k].runs.as_slice());
        let shown_motion = shown.and_then(|k| tried[k].judged).unwrap_or(0);
        let motions = motion_verdicts(cell, runs);
        let binding = binding(setup, &motions);
        let life = life(setup, &motions);
        // For a cell, the words speak of every one of its motions.
        let explanation = match (status, options.life_goal) {
            (Status::Solved, Some(goal)) => life_goal_words(goal, &candidates, cell_words(cell)),
            _ => explanation(
                status,
                sets,
                &candidates,
                &outcome.stop,
                &static_sweep,
                unsolved.as_ref(),
                (setup, cell_words(cell)),
            ),
        };
        SolveReport {
            status,
            explanation,
            inputs: inputs(setup, cell, options),
            optimal: best.as_ref().map(|p| named_path(setup, p)),
            mounting: best.as_ref().map(|p| mounting_plan(setup, p)),
            thresholds: setup.thresholds,
            sub_segment_pitch_mm: pitch_mm,
            optimal_length_mm: best
                .as_ref()
                .map(|p| p.total_sub_segments() as f64 * pitch_mm),
            margins: best
                .as_ref()
                .map(|p| margins(evaluator, poses, p))
                .unwrap_or_default(),
            segments: segment_reports(setup, poses, sets, first(cell)),
            chains: search.chain_count().to_string(),
            candidates,
            static_sweep,
            motion_test,
            motions,
            shown_motion,
            binding,
            life,
            motion_test_requested: options.motion_test,
            motion_engine: options.engine,
            timings,
            diagnosis,
            unsolved,
            ranges: None,
            allowed_ranges: None,
        }
    }
}

fn status(options: &SolveOptions, search: &ChainSearch, winner: Option<usize>) -> Status {
    match (search.shortest().is_some(), winner, options.motion_test) {
        (false, _, _) => Status::NoChain,
        (true, Some(_), true) => Status::Solved,
        (true, Some(_), false) => Status::Untested,
        (true, None, _) => Status::NonePassedMotionTest,
    }
}

/// What the answer's words speak of: `the motion`, or `every motion of the cell`.
fn cell_words(cell: &Cell) -> &'static str {
    match cell.len() {
        1 => "the motion",
        _ => "every motion of the cell",
    }
}

/// The answer's words under a life goal: what it is the shortest or longest-lived of.
fn life_goal_words(goal: LifeGoal, candidates: &[CandidateOutcome], over: &str) -> String {
    let weighed = candidates
        .iter()
        .filter(|c| c.life_cycles.is_some())
        .count();
    match goal {
        LifeGoal::AtLeast { cycles } => format!(
            "the shortest cable path that held every limit over {over} and is predicted to last \
             at least {cycles:.0} cycles; {} shorter or equally long ones did not ({} of them \
             for their life)",
            candidates.len() - 1,
            weighed - 1
        ),
        LifeGoal::Longest { within_mm } => format!(
            "the longest-lived of the {weighed} cable paths that held every limit over {over} \
             within {within_mm:.0} mm of the shortest such path"
        ),
    }
}

fn explanation(
    status: Status,
    sets: &[SegmentSets],
    candidates: &[CandidateOutcome],
    stop: &str,
    sweep: &SweepSummary,
    unsolved: Option<&Unsolved>,
    (setup, over): (&Setup, &str),
) -> String {
    match status {
        Status::Solved if sweep.shortest_untried_mm.is_some() => format!(
            "the shortest cable path that held every limit over {over} among the chains \
             whose pieces kept the swings learned from {} failed motion tests inside the \
             limits; a chain of {:.0} mm (or shorter) with {} pieces set aside was not tested (`solve \
             --no-learning` tests the chains strictly shortest first)",
            candidates.len() - 1,
            sweep.shortest_untried_mm.unwrap_or_default(),
            sweep.set_aside,
        ),
        Status::Solved => match candidates.len() {
            1 => format!("the shortest cable path, and it held every limit over {over}"),
            n => format!(
                "the shortest cable path that held every limit over {over}; {} shorter or \
                 equally long ones did not",
                n - 1
            ),
        },
        Status::Untested => {
            format!(
                "the shortest path of robust cable pieces; not simulated over {over} \
                 (--no-motion-test)"
            )
        }
        Status::NonePassedMotionTest if candidates.is_empty() => format!(
            "every chain of robust candidate pieces has a piece that fails the static sweep \
             over {over}{}",
            sweep_note(sweep)
        ),
        // Each candidate's failure is in `candidates` (and `solve -v`), the per-piece story
        // in the diagnosis: the reason stays one sentence.
        Status::NonePassedMotionTest => format!(
            "{}, and {stop}{}{}{}",
            match candidates.len() {
                1 => "1 path was tried".to_string(),
                n => format!("{n} paths were tried"),
            },
            sweep_note(sweep),
            closest_note(unsolved),
            untried_note(unsolved, candidates.len()),
        ),
        Status::NoChain => unsolved_reason(sets, setup),
    }
}

/// `; the closest, 1620 mm, missed …`: the path tried that came closest to passing and how
/// far a limit would have to move for it; nothing without one.
fn closest_note(unsolved: Option<&Unsolved>) -> String {
    let Some(closest) = unsolved.and_then(|u| u.closest.as_ref()) else {
        return String::new();
    };
    let what = closest.limit_words();
    let by = match closest.relax_by_mm {
        v if v < 0.01 => "less than 0.01 mm".to_string(),
        v => format!("{v:.2} mm"),
    };
    format!(
        "; the closest path tried ({:.0} mm) missed by {by} of {what} in {} ({:.3} mm against \
         {:.1} mm): a limit relaxed by that much removes this failure (the motion test stops \
         at a path's first failure: later ones were not simulated)",
        closest.length_mm, closest.segment, closest.value_mm, closest.limit_mm,
    )
}

/// `; the 50 paths tried used 12 clamp placements; the shortest chain not tested is …`: what
/// a spent budget left, and how to test it; nothing when the budget was not spent.
fn untried_note(unsolved: Option<&Unsolved>, tried: usize) -> String {
    let Some(unsolved) = unsolved.filter(|u| u.case == UnsolvedCase::BudgetSpent) else {
        return String::new();
    };
    let placements = match unsolved.placements_tried {
        1 => "one clamp placement (lengths apart)".to_string(),
        n => format!("{n} clamp placements"),
    };
    let next = match &unsolved.next_untried {
        Some(next) => format!(
            "; the shortest chain not tested is {:.0} mm, {} (`--k-best {}` tests further)",
            next.length_mm,
            if next.new_placement {
                "with clamp places none of them used"
            } else {
                "another length of a placement tried"
            },
            2 * tried
        ),
        None => String::new(),
    };
    format!("; the paths tried used {placements}{next}")
}

/// Which way the search ended without an answer, and the path tried that came closest;
/// `None` when solved (or not motion-tested).
fn unsolved(setup: &Setup, status: Status, outcome: &MotionSearch) -> Option<Unsolved> {
    let case = match status {
        Status::NoChain => UnsolvedCase::NoChain,
        Status::NonePassedMotionTest if outcome.budget_spent => UnsolvedCase::BudgetSpent,
        Status::NonePassedMotionTest => UnsolvedCase::AllChainsFailed,
        Status::Solved | Status::Untested => return None,
    };
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    // Bend radius and clearance misses, in mm, least first (the first one tried on ties).
    let misses = (outcome.tried.iter().enumerate()).filter_map(|(k, tried)| {
        let (path, v) = (&tried.path, tried.report()?.first_violation.as_ref()?);
        v.missed_by_m().map(|missed_m| ClosestMiss {
            candidate: k,
            length_mm: path.total_sub_segments() as f64 * pitch_mm,
            segment: v.segment_name.clone(),
            limit: v.constraint,
            value_mm: tidy(v.value * 1e3),
            limit_mm: tidy(v.threshold * 1e3),
            relax_by_mm: tidy(missed_m * 1e3),
        })
    });
    let closest = misses.min_by(|a, b| a.relax_by_mm.total_cmp(&b.relax_by_mm));
    let placement = |p: &CablePath| (p.segments.clone(), p.configurations.clone());
    let placements: BTreeSet<_> = outcome.tried.iter().map(|t| placement(&t.path)).collect();
    let next_untried = outcome.next_untried.as_ref().map(|path| UntriedChain {
        length_mm: path.total_sub_segments() as f64 * pitch_mm,
        path: named_path(setup, path),
        new_placement: !placements.contains(&placement(path)),
    });
    Some(Unsolved {
        case,
        closest,
        placements_tried: placements.len(),
        next_untried,
    })
}

/// `; the static sweep over the motion dropped N cable pieces (C1 n1, …)`, or nothing when it
/// dropped none.
fn sweep_note(sweep: &SweepSummary) -> String {
    if sweep.rejected.is_empty() {
        return String::new();
    }
    format!(
        "; the static sweep over the motion dropped {} cable pieces ({})",
        sweep.rejected.len(),
        dropped_per_segment(sweep)
    )
}

/// `C1 n1, C2 n2`: cable pieces the sweep dropped per segment.
pub fn dropped_per_segment(sweep: &SweepSummary) -> String {
    let mut per_segment: BTreeMap<&str, usize> = BTreeMap::new();
    for r in &sweep.rejected {
        *per_segment.entry(r.segment.as_str()).or_insert(0) += 1;
    }
    let counts: Vec<String> = per_segment
        .iter()
        .map(|(segment, n)| format!("{segment} {n}"))
        .collect();
    let mut per_motion: BTreeMap<&str, usize> = BTreeMap::new();
    for motion in sweep.rejected.iter().filter_map(|r| r.motion.as_deref()) {
        *per_motion.entry(motion).or_insert(0) += 1;
    }
    let by_motion: Vec<String> = (per_motion.iter())
        .map(|(motion, n)| format!("{motion} {n}"))
        .collect();
    match by_motion.is_empty() {
        true => counts.join(", "),
        false => format!("{}; by motion: {}", counts.join(", "), by_motion.join(", ")),
    }
}

/// The sweep's counts and dropped PVs, with names.
fn sweep_summary(setup: &Setup, cell: &Cell, outcome: &MotionSearch) -> SweepSummary {
    let rejected = outcome
        .dropped
        .iter()
        .map(|(m, pv, failure)| {
            let (a, b) = setup.segment_guides(*m);
            SweepRejection {
                segment: setup.segment_name(*m),
                sub_segments: pv.sub_segments,
                from_configuration: setup.guides[a].configurations[pv.start].name.clone(),
                to_configuration: setup.guides[b].configurations[pv.end].name.clone(),
                rejection: failure.rejection,
                motion: (cell.len() > 1).then(|| cell.motions[failure.motion].name.clone()),
                sample: failure.sample,
                time_s: failure.time_s,
                detail: failure.detail.clone(),
            }
        })
        .collect();
    let mm = |v: Option<f64>| v.map(|v| tidy(v * 1e3));
    let learned_swings = (outcome.learned.by_segment())
        .map(|(m, swing)| LearnedSwing {
            segment: setup.segment_name(m),
            bend_radius_mm: mm(swing.bend_radius_m),
            clearance_mm: mm(swing.clearance_m),
        })
        .collect();
    SweepSummary {
        poses: outcome.sweep_poses,
        pvs_swept: outcome.swept,
        rejected,
        learned_swings,
        touching_pairs: outcome.learned.touched_pairs(),
        set_aside: outcome.set_aside.len(),
        set_aside_restored: outcome.set_aside_restored,
        shortest_untried_mm: (outcome.shortest_untried)
            .map(|s| tidy(s as f64 * setup.cable.sub_segment_pitch_m * 1e3)),
    }
}

/// Which segment has no robust PV and what rejected its candidates most.
fn unsolved_reason(sets: &[SegmentSets], setup: &Setup) -> String {
    let empty: Vec<String> = sets
        .iter()
        .enumerate()
        // The segments on either side of a sliding guide are never pieces alone.
        .filter(|(m, s)| s.d2.is_empty() && setup.has_candidates(*m))
        .map(|(m, s)| {
            let worst = s
                .rejections
                .iter()
                .max_by_key(|(_, count)| **count)
                .map(|(r, count)| format!("most rejected by {} ({count})", r.name()))
                .unwrap_or_else(|| "no candidate left after adjacency pruning".into());
            let (a, b) = setup.segment_guides(m);
            format!(
                "{} ({} → {}) has no robust cable piece: {} hold the limits, {worst}",
                setup.segment_name(m),
                setup.guides[a].name,
                setup.guides[b].name,
                s.d1
            )
        })
        .collect();
    if empty.is_empty() {
        "every segment has robust cable pieces, but none agree on their shared clamps".into()
    } else {
        empty.join("; ")
    }
}

/// Every motion of `cell` with its run of the path shown (`runs`, one per motion, or empty).
pub(in crate::solve) fn motion_verdicts(
    cell: &Cell,
    runs: &[Option<MotionTestReport>],
) -> Vec<MotionVerdict> {
    (cell.motions.iter().enumerate())
        .map(|(i, m)| MotionVerdict {
            name: m.name.clone(),
            file: m.file.as_ref().map(|f| f.display().to_string()),
            cycles_per_hour: m.cycles_per_hour,
            duration_s: m.motion.duration_s(),
            motion_test: runs.get(i).cloned().flatten(),
            grid_poses: m.grid.as_ref().map(|_| m.motion.samples().len()),
        })
        .collect()
}

/// The predicted life of the path the motions were run with ([`path_life`]).
pub(in crate::solve) fn life(setup: &Setup, motions: &[MotionVerdict]) -> Option<CableLife> {
    path_life(
        setup,
        motions
            .iter()
            .map(|m| (m.cycles_per_hour, m.motion_test.as_ref())),
    )
}

/// Per piece of the path the motions were run with, the motion with its smallest bend
/// radius and the one with its lowest clearance (first motion on ties); none for a single
/// motion, which binds everything.
pub(in crate::solve) fn binding(setup: &Setup, motions: &[MotionVerdict]) -> Vec<PieceBinding> {
    if motions.len() < 2 {
        return Vec::new();
    }
    let t = &setup.thresholds;
    let pieces = (motions.iter())
        .filter_map(|m| m.motion_test.as_ref())
        .flat_map(|test| test.pieces.iter().map(|p| p.segment));
    let segments: BTreeSet<usize> = pieces.collect();
    let least = |m: usize, worst: fn(&PieceWorst) -> Option<&Worst>, limit_m: f64| {
        let each = motions.iter().filter_map(|verdict| {
            let test = verdict.motion_test.as_ref()?;
            let piece = test.pieces.iter().find(|p| p.segment == m)?;
            Some((verdict, worst(piece)?))
        });
        let (verdict, w) = each.min_by(|a, b| a.1.value.total_cmp(&b.1.value))?;
        Some(BindingMotion {
            motion: verdict.name.clone(),
            value_mm: tidy(w.value * 1e3),
            limit_mm: tidy(limit_m * 1e3),
            time_s: w.time_s,
        })
    };
    (segments.into_iter())
        .map(|m| PieceBinding {
            segment: setup.segment_name(m),
            bend_radius: least(m, |p| p.worst_bend.as_ref(), t.min_bend_radius_m),
            clearance: least(m, |p| p.worst_clearance.as_ref(), t.contact_clearance_m),
        })
        .collect()
}

/// The first motion of `cell`: its joint names and units are every motion's.
fn first(cell: &Cell) -> &Motion {
    &cell.motions[0].motion
}

fn inputs(setup: &Setup, cell: &Cell, options: &SolveOptions) -> Inputs {
    let motion = first(cell);
    let method = match (options.method, options.max_guides_per_link) {
        (ConnectMethod::Linear, _) => "previous method",
        (ConnectMethod::Hermite, Some(1)) => "one clamp per link",
        (ConnectMethod::Hermite, _) if setup.max_guides_per_link == 1 => "one clamp per link",
        (ConnectMethod::Hermite, _) => "up to two clamps per link",
    };
    Inputs {
        setup_file: setup.source.display().to_string(),
        setup_hash: setup.content_hash_hex(),
        robot_file: setup.robot_path.display().to_string(),
        cable_file: setup.cable_path.display().to_string(),
        cable: setup.cable.name.clone(),
        motion_file: (cell.motions[0].file.as_ref()).map(|f| f.display().to_string()),
        motion_duration_s: motion.duration_s(),
        motion_samples: motion.len(),
        method: method.into(),
        connect: options.method,
        search: options.search,
        dictionary: None,
        limits: LimitsUsed::of(setup),
    }
}

fn candidate_outcomes(tried: &[Tried], cell: &Cell, pitch_mm: f64) -> Vec<CandidateOutcome> {
    tried
        .iter()
        .enumerate()
        .map(|(i, tried)| CandidateOutcome {
            rank: i + 1,
            total_length_mm: tried.path.total_sub_segments() as f64 * pitch_mm,
            path: tried.path.clone(),
            passed: tried.passed(),
            failure: tried.short_lived.clone().or_else(|| {
                (tried.report())
                    .and_then(|r| r.failure.as_ref())
                    .map(|f| f.reason.clone())
            }),
            life_cycles: tried.life_cycles,
            motion: match (cell.len(), tried.report().map(|r| r.passed)) {
                (2.., Some(false)) => tried.judged.map(|i| cell.motions[i].name.clone()),
                _ => None,
            },
        })
        .collect()
}

/// Names of segment `m`'s two guides and of their links.
pub fn guide_names(setup: &Setup, m: usize) -> ([String; 2], [String; 2]) {
    let (a, b) = setup.segment_guides(m);
    let link = |g: usize| setup.robot.links[setup.guides[g].link].name.clone();
    (
        [setup.guides[a].name.clone(), setup.guides[b].name.clone()],
        [link(a), link(b)],
    )
}

/// `inter-link` or `intra-link`: the result JSON's `kind` of segment `m`.
fn segment_kind(setup: &Setup, m: usize) -> &'static str {
    if setup.is_intra_link(m) {
        "intra-link"
    } else {
        "inter-link"
    }
}

/// The path with names: piece by piece, and every mounted clamp's configuration.
pub fn named_path(setup: &Setup, path: &CablePath) -> NamedPath {
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let segments = path
        .pieces()
        .map(|(m, pv)| {
            let sub_segments = pv.sub_segments;
            let ([from_guide, to_guide], [from_link, to_link]) = guide_names(setup, m);
            PathSegment {
                name: setup.segment_name(m),
                from_guide,
                to_guide,
                from_link,
                to_link,
                kind: segment_kind(setup, m),
                sub_segments,
                length_mm: sub_segments as f64 * pitch_mm,
            }
        })
        .collect();
    let mounted: Vec<usize> = path.guides(setup).collect();
    let guides = mounted
        .iter()
        .zip(&path.configurations)
        .map(|(&g, &c)| {
            let guide = &setup.guides[g];
            let configuration = &guide.configurations[c];
            PathGuide {
                name: guide.name.clone(),
                link: setup.robot.links[guide.link].name.clone(),
                configuration: configuration.name.clone(),
                xyz_mm: configuration.position_mm,
                rpy_deg: configuration.rpy_deg,
            }
        })
        .collect();
    let left_out = (0..setup.guides.len())
        .filter(|g| !mounted.contains(g))
        .map(|g| setup.guides[g].name.clone())
        .collect();
    NamedPath {
        segments,
        guides,
        left_out,
    }
}

fn segment_reports(
    setup: &Setup,
    poses: &SegmentPoses,
    sets: &[SegmentSets],
    motion: &Motion,
) -> Vec<SegmentReport> {
    sets.iter()
        .enumerate()
        .map(|(m, s)| {
            let ([from_guide, to_guide], _) = guide_names(setup, m);
            SegmentReport {
                segment: setup.segment_name(m),
                from_guide,
                to_guide,
                kind: segment_kind(setup, m),
                traversed_joints: poses.traversed[m]
                    .iter()
                    .map(|&j| motion.joint_names()[j].clone())
                    .collect(),
                test_poses: poses.poses[m]
                    .iter()
                    .map(|p| pose_summary(p, motion))
                    .collect(),
                d0: s.d0,
                d0_pruned: s.d0_pruned,
                d1: s.d1,
                d2: s.d2.len(),
                rejections: s.rejections.clone(),
                evaluations: s.evaluations,
                static_solves: s.static_solves,
            }
        })
        .collect()
}

/// A test pose in the motion's display units (deg / mm).
pub fn pose_summary(pose: &TestPose, motion: &Motion) -> PoseSummary {
    let joints = pose
        .joints
        .iter()
        .zip(motion.rotary())
        .map(|(v, &rotary)| if rotary { v.to_degrees() } else { v * 1e3 })
        .collect();
    PoseSummary {
        motion: pose.motion,
        sample: pose.sample,
        time_s: pose.time_s,
        joints,
        reason: pose.reason.clone(),
    }
}
