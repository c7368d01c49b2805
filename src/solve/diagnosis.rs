//! "No path" as a diagnosis: for each segment that blocks the search, the candidate pieces
//! that came closest (which limit, by how much, at which pose, where on the cable) and what
//! would help — a longer or shorter length window, other clamp sites or cable directions, a
//! smaller joint range, or a slower joint between two times of the motion.

use super::search::MotionSearch;
use crate::attachment::{Miss, Rejection, SegmentPoses, SegmentSets};
use crate::motion::{Cell, Motion};
use crate::motion_test::{Constraint, Violation};
use crate::path::CablePath;
use crate::setup::Setup;
use serde::Serialize;
use std::collections::BTreeMap;

/// Why no path was found, segment by segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diagnosis {
    /// The segments that block the search, base end first.
    pub segments: Vec<SegmentDiagnosis>,
}

/// One blocking segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentDiagnosis {
    /// `C3`.
    pub segment: String,
    /// Its start guide, `G3`: where the places on the cable are measured from.
    pub from_guide: String,
    /// What blocks, for people.
    pub problem: String,
    /// The candidate pieces that came closest, least severe first (attachment test).
    pub nearest_misses: Vec<NearestMiss>,
    /// The test poses that rejected most of its candidate pieces, most first, at most
    /// [`REJECTING_POSES`] (attachment test; empty when chains reached the motion test).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rejecting_poses: Vec<RejectingPose>,
    /// How the chains tried failed in this segment, first ones first (motion test and its
    /// static sweep).
    pub failures: Vec<String>,
    /// What would help, most specific first.
    pub suggestions: Vec<String>,
}

/// Rejecting poses kept per blocking segment.
pub const REJECTING_POSES: usize = 10;

/// A test pose where candidate pieces of a segment failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RejectingPose {
    /// The pose.
    #[serde(flatten)]
    pub at: DiagnosedPose,
    /// Candidate pieces rejected there.
    pub pieces: usize,
}

/// A test pose a diagnosis names: a moment of a motion, or a pose of an axis-range grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiagnosedPose {
    /// Which motion of a cell (absent for the first, and for a single motion).
    #[serde(skip_serializing_if = "crate::json::is_zero")]
    pub motion: usize,
    /// Time in the motion (s).
    pub time_s: f64,
    /// Why that pose was tested (e.g. `joint_5 max`).
    pub pose: String,
    /// The pose is one of an axis-range grid's (`time_s` its number), not a moment of a
    /// motion.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub grid: bool,
}

impl DiagnosedPose {
    fn of(pose: &crate::attachment::TestPose) -> DiagnosedPose {
        DiagnosedPose {
            motion: pose.motion,
            time_s: pose.time_s,
            pose: pose.reason.clone(),
            grid: pose.grid,
        }
    }

    /// Where in the motion: `at t = 4.15 s (joint_5 max)`, or on an axis-range grid `at
    /// axis-range grid: pose 227 (joint_5 48.1 deg, …)`.
    pub fn when(&self) -> String {
        match self.grid {
            true => format!("at {}", self.pose),
            false => format!("at t = {:.2} s ({})", self.time_s, self.pose),
        }
    }
}

/// A candidate piece that failed one limit, and how.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NearestMiss {
    /// Start clamp configuration.
    pub from_configuration: String,
    /// End clamp configuration.
    pub to_configuration: String,
    /// Cable length (mm).
    pub length_mm: f64,
    /// The limit it violated.
    pub limit: Rejection,
    /// What was measured: clearance or bend radius (mm), or the stretch ratio (for a piece
    /// too short, the stretch it would need: the clamps' distance over its length).
    pub value: f64,
    /// The limit's value, in the same unit.
    pub limit_value: f64,
    /// Where it failed first.
    #[serde(flatten)]
    pub at: DiagnosedPose,
    /// Where on the piece: cable length from its start clamp (mm); `None` for the whole
    /// piece.
    pub from_start_clamp_mm: Option<f64>,
}

impl NearestMiss {
    /// One line for people: `"…" → "…", 420 mm: bend radius 46.2 mm < 48.0 mm at t =
    /// 4.15 s (joint_5 max), 320 mm of cable from G3`.
    pub fn describe(&self, from_guide: &str) -> String {
        let what = match self.limit {
            Rejection::TooShort => format!(
                "too short: its clamps are {:.0} mm apart",
                self.length_mm * self.value
            ),
            Rejection::Stretch => format!("stretch {:.4} > {:.4}", self.value, self.limit_value),
            limit => format!(
                "{} {:.2} mm < {:.2} mm ({} short)",
                match limit {
                    Rejection::Contact => "clearance",
                    Rejection::SelfContact => "clearance to itself",
                    _ => "bend radius",
                },
                self.value,
                self.limit_value,
                shortfall(self.limit_value - self.value)
            ),
        };
        let place = self
            .from_start_clamp_mm
            .map(|mm| format!(", {mm:.0} mm of cable from {from_guide}"))
            .unwrap_or_default();
        format!(
            "\"{}\" → \"{}\", {:.0} mm: {what} {}{place}",
            self.from_configuration,
            self.to_configuration,
            self.length_mm,
            self.at.when()
        )
    }
}

/// A shortfall given in mm, to two decimals, or in µm below 0.01 mm (so that a miss by a
/// hair does not read "0.00 mm short").
fn shortfall(mm: f64) -> String {
    if mm >= 0.01 {
        format!("{mm:.2} mm")
    } else {
        format!("{:.2} µm", mm * 1e3)
    }
}

impl std::fmt::Display for Diagnosis {
    /// One line per blocking segment, then its nearest misses, failures and suggestions,
    /// indented.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for d in &self.segments {
            writeln!(f, "{}: {}", d.segment, d.problem)?;
            for miss in &d.nearest_misses {
                writeln!(f, "  nearest miss: {}", miss.describe(&d.from_guide))?;
            }
            for at in d.rejecting_poses.iter().take(3) {
                let pieces = match at.pieces {
                    1 => "1 piece".to_string(),
                    n => format!("{n} pieces"),
                };
                writeln!(f, "  failed {pieces} {}", at.at.when())?;
            }
            for failure in &d.failures {
                writeln!(f, "  failed: {failure}")?;
            }
            for suggestion in &d.suggestions {
                writeln!(f, "  would help: {suggestion}")?;
            }
        }
        Ok(())
    }
}

/// The diagnosis of an unsolved search: the segments without a robust candidate piece, or,
/// when chains were found but failed the motion test, the segments they failed in.
pub(super) fn diagnose(
    setup: &Setup,
    cell: &Cell,
    poses: &SegmentPoses,
    sets: &[SegmentSets],
    outcome: &MotionSearch,
) -> Diagnosis {
    let blocking: Vec<usize> = (0..sets.len())
        .filter(|&m| sets[m].d2.is_empty() && setup.has_candidates(m))
        .collect();
    let mut segments: Vec<SegmentDiagnosis> = if !blocking.is_empty() {
        blocking
            .into_iter()
            .map(|m| attachment_diagnosis(setup, poses, &sets[m], m))
            .collect()
    } else {
        motion_diagnosis(setup, cell, outcome)
    };
    if segments.is_empty() {
        segments = disagreements(setup, sets);
    }
    Diagnosis { segments }
}

/// Where every segment has robust pieces but no chain joins them: per clamp between two
/// pieces, the placements the robust pieces before it end in and those after it start
/// from, when no placement has both.
fn disagreements(setup: &Setup, sets: &[SegmentSets]) -> Vec<SegmentDiagnosis> {
    let placements = |g: usize, ends: &mut dyn Iterator<Item = usize>| {
        let mut used: Vec<usize> = ends.collect();
        used.sort_unstable();
        used.dedup();
        let names: Vec<&str> = (used.iter())
            .map(|&c| setup.guides[g].configurations[c].name.as_str())
            .collect();
        (used, names)
    };
    (1..setup.guides.len() - 1)
        .filter_map(|g| {
            let (before, before_names) = placements(
                g,
                &mut setup
                    .segments_into(g)
                    .flat_map(|m| sets[m].d2.iter().map(|pv| pv.end)),
            );
            let (after, after_names) = placements(
                g,
                &mut setup
                    .segments_from(g)
                    .flat_map(|m| sets[m].d2.iter().map(|pv| pv.start)),
            );
            if before.is_empty() || after.is_empty() || before.iter().any(|c| after.contains(c)) {
                return None;
            }
            let m = setup.segments_from(g).find(|&m| setup.has_candidates(m))?;
            let guide = &setup.guides[g].name;
            Some(SegmentDiagnosis {
                segment: setup.segment_name(m),
                from_guide: guide.clone(),
                problem: format!(
                    "the robust pieces before {guide} end in its placements {}, those after it \
                     start from {}: none in common",
                    before_names.join(", "),
                    after_names.join(", ")
                ),
                nearest_misses: Vec::new(),
                rejecting_poses: Vec::new(),
                failures: Vec::new(),
                suggestions: vec![format!(
                    "offer {guide} more placements, or lengths that reach the ones the other side \
                     uses"
                )],
            })
        })
        .collect()
}

/// A segment none of whose candidate pieces is robust.
fn attachment_diagnosis(
    setup: &Setup,
    poses: &SegmentPoses,
    sets: &SegmentSets,
    m: usize,
) -> SegmentDiagnosis {
    let (a, b) = setup.segment_guides(m);
    let problem = if sets.d1 == 0 {
        format!(
            "none of its {} candidate pieces holds every limit at its test poses{}",
            sets.d0_pruned,
            pruning_note(setup, m, sets)
        )
    } else {
        let r = setup.robustness;
        format!(
            "{} candidate pieces hold every limit, but none keeps them when its length is off \
             by up to ±{:.0} mm (the robust length window)",
            sets.d1,
            (r.delta_s * r.range) as f64 * setup.cable.sub_segment_pitch_m * 1e3
        )
    };
    let nearest_misses: Vec<NearestMiss> = sets
        .nearest_misses
        .iter()
        .map(|(pv, miss)| {
            let pose = &poses.poses[m][miss.pose];
            nearest_miss(
                setup,
                (a, pv.start),
                (b, pv.end),
                pv.sub_segments,
                miss,
                pose,
            )
        })
        .collect();
    let suggestions = attachment_suggestions(setup, m, sets, &nearest_misses);
    let mut rejecting: Vec<(usize, usize)> = (sets.rejected_at.iter())
        .map(|(&p, &pieces)| (p, pieces))
        .collect();
    rejecting.sort_by_key(|&(p, pieces)| (std::cmp::Reverse(pieces), p));
    let rejecting_poses = (rejecting.into_iter().take(REJECTING_POSES))
        .filter_map(|(p, pieces)| {
            let pose = poses.poses[m].get(p)?;
            Some(RejectingPose {
                at: DiagnosedPose::of(pose),
                pieces,
            })
        })
        .collect();
    SegmentDiagnosis {
        segment: setup.segment_name(m),
        from_guide: setup.guides[a].name.clone(),
        problem,
        nearest_misses,
        rejecting_poses,
        failures: Vec::new(),
        suggestions,
    }
}

/// `" (of 693680: …)"` when its neighbours' robust pieces left only some of its candidates —
/// the clamp configurations it shares with them.
fn pruning_note(setup: &Setup, m: usize, sets: &SegmentSets) -> String {
    if sets.d0_pruned == sets.d0 {
        return String::new();
    }
    // The neighbours tested before it (intra-link segments first, then the others in order),
    // whose robust pieces pruned it.
    let (a, b) = setup.segment_guides(m);
    let neighbours: Vec<String> = setup
        .segments_into(a)
        .chain(setup.segments_from(b))
        .filter(|&n| setup.is_intra_link(n) || n < m)
        .map(|n| setup.segment_name(n))
        .collect();
    format!(
        " (of {}: only those on the clamp configurations the robust pieces of {} use; widen \
         {} too)",
        sets.d0,
        neighbours.join(" and "),
        if neighbours.len() > 1 {
            "their windows or sites"
        } else {
            "its window or sites"
        }
    )
}

fn nearest_miss(
    setup: &Setup,
    (a, ca): (usize, usize),
    (b, cb): (usize, usize),
    sub_segments: usize,
    miss: &Miss,
    pose: &crate::attachment::TestPose,
) -> NearestMiss {
    let limits = &setup.thresholds;
    let (value, limit_value) = match miss.rejection {
        Rejection::Contact => (miss.value * 1e3, limits.contact_clearance_m * 1e3),
        Rejection::SelfContact => (miss.value * 1e3, 0.0),
        Rejection::Bend => (miss.value * 1e3, limits.static_min_bend_radius_m() * 1e3),
        _ => (miss.value, limits.stretch),
    };
    NearestMiss {
        from_configuration: setup.guides[a].configurations[ca].name.clone(),
        to_configuration: setup.guides[b].configurations[cb].name.clone(),
        length_mm: sub_segments as f64 * setup.cable.sub_segment_pitch_m * 1e3,
        limit: miss.rejection,
        value,
        limit_value,
        at: DiagnosedPose::of(pose),
        from_start_clamp_mm: miss.at_m.is_finite().then_some(miss.at_m * 1e3),
    }
}

fn attachment_suggestions(
    setup: &Setup,
    m: usize,
    sets: &SegmentSets,
    misses: &[NearestMiss],
) -> Vec<String> {
    let mut out = Vec::new();
    let Some(nearest) = misses.first() else {
        out.push(
            "no candidate piece could be measured: check that its clamps' configurations can \
             be reached by a cable of the segment's lengths"
                .into(),
        );
        return out;
    };
    let range = setup.segments[m].range;
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let (min_mm, max_mm) = (range.min as f64 * pitch_mm, range.max as f64 * pitch_mm);
    if nearest.length_mm >= max_mm {
        let needs = match nearest.limit {
            // Its clamps' distance, in whole sub-segments: it must reach before it can hold.
            Rejection::TooShort => Some(format!(
                "needs at least {:.0} mm to reach between its clamps",
                (max_mm * nearest.value / pitch_mm).ceil() * pitch_mm
            )),
            Rejection::Stretch => Some(format!(
                "needs about {:.0} mm",
                max_mm * nearest.value / nearest.limit_value
            )),
            _ => None,
        };
        if let Some(needs) = needs {
            out.push(format!(
                "a longer length window: the nearest miss is {max_mm:.0} mm long, the \
                 window's maximum, and {needs} ({})",
                window_keys(setup, m, "max")
            ));
        }
    }
    let slack = matches!(
        nearest.limit,
        Rejection::Bend | Rejection::Contact | Rejection::SelfContact
    );
    if slack && nearest.length_mm <= min_mm && range.min > 1 {
        out.push(format!(
            "a shorter length window: the nearest miss is {min_mm:.0} mm long, the window's \
             minimum ({})",
            window_keys(setup, m, "min")
        ));
    }
    if sets.d1 > 0 {
        out.push(format!(
            "a smaller robust length window ([robustness] range = {}, ΔS = {})",
            setup.robustness.range, setup.robustness.delta_s
        ));
    }
    if slack && !nearest.at.pose.is_empty() {
        out.push(format!(
            "it fails {}: a smaller range of that joint in the motion, or clamps that keep \
             the cable clear there",
            nearest.at.when()
        ));
    }
    let (a, b) = setup.segment_guides(m);
    out.push(format!(
        "other clamp sites or cable directions for {} or {} (near \"{}\" and \"{}\"): more \
         directions_deg, a finer spacing_mm, or a bracket (a larger clamp_height_mm)",
        setup.guides[a].name,
        setup.guides[b].name,
        nearest.from_configuration,
        nearest.to_configuration
    ));
    out
}

/// Chains were found, but every one tried failed the motion test (or its static sweep):
/// the segments they failed in, how, and — for a failure in the dynamic test — the joint that
/// moved fastest then, and between which times.
fn motion_diagnosis(setup: &Setup, cell: &Cell, outcome: &MotionSearch) -> Vec<SegmentDiagnosis> {
    let count = setup.segment_count();
    let mut dynamic: Vec<Vec<(String, f64)>> = vec![Vec::new(); count];
    let mut swept: Vec<Vec<(String, f64)>> = vec![Vec::new(); count];
    // Per segment, the motion of its first failure in a motion test.
    let mut first_motion: Vec<Option<usize>> = vec![None; count];
    // Per segment, the bend-radius or clearance failure missed by the least, with its path.
    let mut closest: Vec<Option<(&Violation, &CablePath)>> = vec![None; count];
    for tried in &outcome.tried {
        let (path, Some(report)) = (&tried.path, tried.report()) else {
            continue;
        };
        let (Some(failure), Some(violation)) = (&report.failure, &report.first_violation) else {
            continue;
        };
        if let Some(m) = failure.segment {
            let motion = tried.judged.unwrap_or(0);
            let reason = cell.label(motion, &failure.reason);
            dynamic[m].push((reason, violation.time_s));
            first_motion[m].get_or_insert(motion);
            if let Some(missed_m) = violation.missed_by_m()
                && closest[m].is_none_or(|(c, _)| c.missed_by_m().is_some_and(|c| missed_m < c))
            {
                closest[m] = Some((violation, path));
            }
        }
    }
    // Per segment and motion of a cell, how many pieces that motion's sweep dropped.
    let mut dropped_by: Vec<BTreeMap<&str, usize>> = vec![BTreeMap::new(); count];
    for (m, _, failure) in &outcome.dropped {
        if cell.len() > 1 {
            let name = cell.motions[failure.motion].name.as_str();
            *dropped_by[*m].entry(name).or_insert(0) += 1;
        }
        swept[*m].push((cell.label(failure.motion, &failure.detail), failure.time_s));
    }
    (0..count)
        .filter(|&m| !dynamic[m].is_empty() || !swept[m].is_empty())
        .map(|m| {
            let (a, b) = setup.segment_guides(m);
            let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
            let mut suggestions: Vec<String> = (closest[m].iter())
                .map(|(v, path)| relaxed_limit(v, path.total_sub_segments() as f64 * pitch_mm))
                .collect();
            let motion = &cell.motions[first_motion[m].unwrap_or(0)].motion;
            suggestions.extend((dynamic[m].first()).and_then(|&(_, t)| slower_joint(motion, t)));
            suggestions.push(format!(
                "other clamp sites or cable directions for {} or {} (more directions_deg, a \
                 finer spacing_mm, or a bracket: a larger clamp_height_mm)",
                setup.guides[a].name, setup.guides[b].name
            ));
            let described = |list: &[(String, f64)], test: &str| -> Vec<String> {
                list.iter()
                    .take(3)
                    .map(|(why, t)| format!("{test} at t = {t:.2} s: {why}"))
                    .collect()
            };
            let by: Vec<String> = (dropped_by[m].iter())
                .map(|(motion, n)| format!("{motion} {n}"))
                .collect();
            let by = match by.is_empty() {
                true => String::new(),
                false => format!(" (by motion: {})", by.join(", ")),
            };
            SegmentDiagnosis {
                segment: setup.segment_name(m),
                from_guide: setup.guides[a].name.clone(),
                rejecting_poses: Vec::new(),
                problem: match (dynamic[m].len(), swept[m].len()) {
                    (0, n) => format!(
                        "the static sweep over the motion dropped {n} of its candidate \
                         pieces{by}"
                    ),
                    (k, 0) => format!("{} here in the motion test", paths_failed(k)),
                    (k, n) => format!(
                        "{} here in the motion test, and the static sweep over the motion \
                         dropped {n} of its candidate pieces{by}",
                        paths_failed(k)
                    ),
                },
                nearest_misses: Vec::new(),
                failures: [
                    described(&dynamic[m], "motion test"),
                    described(&swept[m], "static sweep"),
                ]
                .concat(),
                suggestions,
            }
        })
        .collect()
}

/// What lets the closest path of a segment past its bend-radius or clearance failure: the
/// limit relaxed by the amount it missed (the user weighs that against the cable's
/// datasheet), or for a clearance a higher clamp. Later failures of that path were not
/// simulated, so it is a failure removed, not a path promised.
fn relaxed_limit(violation: &Violation, length_mm: f64) -> String {
    let (value_mm, limit_mm) = (violation.value * 1e3, violation.threshold * 1e3);
    match violation.constraint {
        Constraint::BendRadius => format!(
            "a bend radius limit of {:.1} mm (min_bend_radius_mm under [thresholds], where the \
             cable's datasheet allows it): the closest path here ({length_mm:.0} mm) bent to \
             {value_mm:.2} mm against {limit_mm:.1} mm, and that removes this failure (`solve` \
             again tells whether it passes the rest of the motion)",
            (value_mm * 10.0).floor() / 10.0
        ),
        Constraint::FlexingBendRadius => format!(
            "a flexing bend radius of {:.1} mm (min_bend_radius_flexing_mm in the cable file, \
             where the cable's datasheet allows it): the closest path here ({length_mm:.0} mm) \
             flexed to {value_mm:.2} mm against {limit_mm:.1} mm, and that removes this failure \
             (`solve` again tells whether it passes the rest of the motion); or, where that \
             piece hardly moves, a larger flexing_curvature_change_per_m under [thresholds] \
             (the change of curvature from which a piece counts as flexing; its largest change \
             is in the JSON's motions[].pieces[])",
            (value_mm * 10.0).floor() / 10.0
        ),
        _ if value_mm >= 0.0 => format!(
            "a clearance limit of {:.2} mm (contact_clearance_mm under [thresholds]), or its \
             clamps on a bracket (a larger clamp_height_mm): the closest path here \
             ({length_mm:.0} mm) came within {value_mm:.2} mm of the arm against {limit_mm:.1} \
             mm, and that removes this failure (`solve` again tells whether it passes the rest \
             of the motion)",
            (value_mm * 100.0).floor() / 100.0
        ),
        // Touching is never a limit to relax.
        _ => format!(
            "its clamps on a bracket (a larger clamp_height_mm): the closest path here \
             ({length_mm:.0} mm) touched the arm, {:.2} mm into it",
            -value_mm
        ),
    }
}

/// "a slower joint_6 between …" when some rotary joint moves at `t_s`.
fn slower_joint(motion: &Motion, t_s: f64) -> Option<String> {
    let (joint, from, to, speed) = fastest_joint_move(motion, t_s)?;
    (speed >= 1.0).then(|| {
        format!(
            "a gentler move between t = {from:.2} s and {to:.2} s — lower accelerations \
             (acceleration_deg_s2 in the waypoint file) more than a lower speed_scale: a long \
             loop swings after every acceleration and keeps swinging; {joint}, the fastest \
             joint, moves at {speed:.0}°/s when the cable fails at t = {t_s:.2} s"
        )
    })
}

/// The rotary joint moving fastest at `t_s`, and the move it is in: from the last time
/// before `t_s` to the first after it at which that joint is at rest (below 1 % of its
/// peak speed). `(name, from, to, speed deg/s)`.
fn fastest_joint_move(motion: &Motion, t_s: f64) -> Option<(String, f64, f64, f64)> {
    let times = motion.times_s();
    let k = times.iter().position(|&t| t >= t_s)?.max(1);
    let speed = |j: usize, i: usize| {
        let s = motion.samples();
        let dt = times[i] - times[i - 1];
        ((s[i][j] - s[i - 1][j]) / dt).abs()
    };
    let joint = (0..motion.dof())
        .filter(|&j| motion.rotary()[j])
        .max_by(|&x, &y| speed(x, k).total_cmp(&speed(y, k)))?;
    let peak = motion.peak_speeds()[joint];
    let at_rest = |i: usize| speed(joint, i) <= 0.01 * peak;
    let from = (1..k)
        .rev()
        .find(|&i| at_rest(i))
        .map_or(times[0], |i| times[i]);
    let to = (k..times.len())
        .find(|&i| at_rest(i))
        .map_or(times[times.len() - 1], |i| times[i]);
    Some((
        motion.joint_names()[joint].clone(),
        from,
        to,
        speed(joint, k).to_degrees(),
    ))
}

/// `1 path failed` or `3 paths failed`.
fn paths_failed(count: usize) -> String {
    match count {
        1 => "1 path failed".into(),
        n => format!("{n} paths failed"),
    }
}

/// The setup keys of piece `m`'s length window's `end` (`min`, `max`): its own, or for a span
/// (over optional clamps, or through a sliding guide or swivel) those of the declared pieces
/// it sums — `segments[1].lengths.max or segments[2].lengths.max`.
fn window_keys(setup: &Setup, m: usize, end: &str) -> String {
    let (a, b) = setup.segment_guides(m);
    (a..b)
        .map(|d| format!("segments[{d}].lengths.{end}"))
        .collect::<Vec<_>>()
        .join(" or ")
}
