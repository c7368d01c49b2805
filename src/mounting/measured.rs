//! A cable as the fitter mounted it, measured on the robot the way the installation sheet
//! gives it — each clamp by its link, its place (along the link's line from the feature the
//! sheet names, the angle around it) and the cable mark it grips — read back into the path
//! of a setup that it is: the inverse of [`super::mounting_plan`], so that `check` can judge
//! an installed cable, not only a result file.
//!
//! # Mounting file (TOML)
//!
//! ```toml
//! setup = "../robots/viper_s850/pick_and_place.toml"   # optional, relative to this file
//!
//! [[clamps]]                # from the base side to the tool, as mounted
//! link = "link_3"
//! along_mm = 173            # as the sheet measures it (from the seam, a joint axis, …)
//! around_deg = 329          # clockwise from the side the sheet names
//! mark_mm = 620             # the cable mark the clamp grips
//! # optional: off_axis_mm, cable_to_axis_deg, cable_turn ("clockwise", "anticlockwise",
//! # "outward", "inward") where several cable directions share a place
//!
//! [[clamps]]
//! fitting = "turret connector"   # a fitting the setup fixes, with its mark, when the
//! mark_mm = 1450                 # cable starts there (the one at the tool end is mark 0)
//! ```
//!
//! Each clamp is matched to the setup's nearest clamp place on that link within a tolerance
//! (distance along the line, arc around it, difference off it), and the pieces between
//! clamps are the differences of their marks, rounded to the cable model's pitch.

use super::{LinkPlace, Turn, installation_link_poses, link_place};
use crate::path::CablePath;
use crate::setup::Setup;
use serde::Deserialize;
use std::fmt;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A clamp's cable direction within this angle (deg) of the one measured is the same.
pub const DIRECTION_WITHIN_DEG: f64 = 15.0;

/// The most clamps one mounting file may list.
pub const MAX_MEASURED_CLAMPS: usize = 256;

/// A mounting file that cannot be read, or that does not fit its setup: where and what.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct MeasuredError {
    /// The mounting file.
    pub file: PathBuf,
    /// 1-based line, when the problem has one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
}

impl fmt::Display for MeasuredError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.file.display(), self.problem),
            None => write!(f, "{}: {}", self.file.display(), self.problem),
        }
    }
}

/// One entry of a mounting file.
#[derive(Debug, Clone, PartialEq)]
pub enum MeasuredEntry {
    /// A clamp the fitter mounted and measured.
    Clamp {
        /// Its link's name.
        link: String,
        /// Along the link's line from the sheet's feature (mm); `None` where the sheet
        /// measures nothing along.
        along_mm: Option<f64>,
        /// Around the line (deg).
        around_deg: f64,
        /// Off the line to the cable's axis (mm), when measured.
        off_axis_mm: Option<f64>,
        /// The cable's angle to the line (deg), when measured.
        cable_to_axis_deg: Option<f64>,
        /// Which way the cable leans around the line, when measured.
        cable_turn: Option<Turn>,
    },
    /// A fitting the setup fixes (a connector), by its name.
    Fitting {
        /// Its name (the fixed configuration's or the guide's).
        name: String,
    },
}

/// An entry with its mark and line.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// What was mounted.
    pub entry: MeasuredEntry,
    /// The cable mark it grips (mm from the cable's end at the tool).
    pub mark_mm: f64,
    /// 1-based line of the entry in the file.
    pub line: usize,
}

/// A mounting file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredMounting {
    /// The file.
    pub source: PathBuf,
    /// The setup it names, resolved against its folder.
    pub setup: Option<PathBuf>,
    /// Its entries from the base side.
    pub entries: Vec<Measured>,
}

/// How one entry was read against the setup.
#[derive(Debug, Clone, PartialEq)]
pub struct Matched {
    /// 1-based line of the entry.
    pub line: usize,
    /// The setup's guides it stands for (two or more: joined by 0 mm pieces).
    pub guides: Vec<String>,
    /// The setup's name of the place taken.
    pub configuration: String,
    /// Between the place measured and the place taken (mm): along, around (as an arc) and
    /// off the line together.
    pub distance_mm: f64,
}

/// One physical clamp read: its (guide, configuration) pairs, its mark (mm) and its line in
/// the file (`None`: the tool's fitting, added).
type Group = (Vec<(usize, usize)>, f64, Option<usize>);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    setup: Option<String>,
    clamps: Spanned<Vec<Spanned<RawClamp>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawClamp {
    link: Option<String>,
    fitting: Option<String>,
    along_mm: Option<f64>,
    around_deg: Option<f64>,
    off_axis_mm: Option<f64>,
    cable_to_axis_deg: Option<f64>,
    cable_turn: Option<Turn>,
    mark_mm: f64,
}

impl MeasuredMounting {
    /// Whether `path` reads as a mounting file (a `.toml` with `[[clamps]]`).
    pub fn is_mounting_file(path: &Path) -> bool {
        crate::input::is_toml_with(path, crate::input::SETUP, "[[clamps]]")
    }

    /// Reads and checks a mounting file (what can be checked without its setup).
    pub fn from_file(path: &Path) -> Result<MeasuredMounting, MeasuredError> {
        let error = |line: Option<usize>, problem: String| MeasuredError {
            file: path.to_path_buf(),
            line,
            problem,
        };
        let text =
            crate::input::read_text(path, crate::input::SETUP).map_err(|e| error(None, e))?;
        let line_of = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
        let raw: RawFile = toml::from_str(&text).map_err(|e| {
            let line = e.span().map(|s| line_of(s.start));
            error(
                line,
                format!("{} (a mounting file lists `[[clamps]]`)", e.message()),
            )
        })?;
        let list = raw.clamps.get_ref();
        if list.is_empty() || list.len() > MAX_MEASURED_CLAMPS {
            return Err(error(
                Some(line_of(raw.clamps.span().start)),
                format!("{} clamps: give 1 to {MAX_MEASURED_CLAMPS}", list.len()),
            ));
        }
        let mut entries = Vec::with_capacity(list.len());
        for clamp in list {
            let line = line_of(clamp.span().start);
            let c = clamp.get_ref();
            let finite = [
                ("mark_mm", Some(c.mark_mm)),
                ("along_mm", c.along_mm),
                ("around_deg", c.around_deg),
                ("off_axis_mm", c.off_axis_mm),
                ("cable_to_axis_deg", c.cable_to_axis_deg),
            ];
            if let Some((key, Some(v))) = finite
                .iter()
                .find(|(_, v)| v.is_some_and(|v| !v.is_finite()))
            {
                return Err(error(Some(line), format!("`{key}` = {v} is not a number")));
            }
            if c.mark_mm < 0.0 {
                return Err(error(
                    Some(line),
                    format!("`mark_mm` = {} must be ≥ 0", c.mark_mm),
                ));
            }
            let entry = match (&c.link, &c.fitting, c.around_deg) {
                (Some(link), None, Some(around_deg)) => MeasuredEntry::Clamp {
                    link: link.clone(),
                    along_mm: c.along_mm,
                    around_deg,
                    off_axis_mm: c.off_axis_mm,
                    cable_to_axis_deg: c.cable_to_axis_deg,
                    cable_turn: c.cable_turn,
                },
                (None, Some(name), _) => MeasuredEntry::Fitting { name: name.clone() },
                _ => {
                    return Err(error(
                        Some(line),
                        "give a clamp's `link` and `around_deg` (and `along_mm` where the \
                         sheet measures along), or a `fitting`'s name"
                            .into(),
                    ));
                }
            };
            entries.push(Measured {
                entry,
                mark_mm: c.mark_mm,
                line,
            });
        }
        let folder = path.parent().unwrap_or(Path::new(""));
        Ok(MeasuredMounting {
            source: path.to_path_buf(),
            setup: raw.setup.map(|s| folder.join(s)),
            entries,
        })
    }

    /// The path of `setup` this mounting is: each clamp the nearest place of the guides on
    /// its link within `tolerance_mm`, in the setup's guide order; optional guides nobody
    /// measured left out; the fitting at the tool end (mark 0) added when not listed.
    pub fn path(
        &self,
        setup: &Setup,
        tolerance_mm: f64,
    ) -> Result<(CablePath, Vec<Matched>), MeasuredError> {
        let error = |line: Option<usize>, problem: String| MeasuredError {
            file: self.source.clone(),
            line,
            problem,
        };
        let link_poses = installation_link_poses(setup);
        let place = |g: usize, c: usize| -> Option<LinkPlace> {
            let guide = &setup.guides[g];
            let pose = guide.link_in_body * guide.configurations[c].pose;
            link_place(&setup.robot, guide.body, &pose, &link_poses)
        };
        let link_name = |g: usize| setup.robot.links[setup.guides[g].link].name.as_str();
        let mut groups: Vec<Group> = Vec::new();
        let mut matched = Vec::new();
        let mut next = 0;
        for (k, measured) in self.entries.iter().enumerate() {
            let line = Some(measured.line);
            let found = (next..setup.guides.len()).find_map(|g| {
                let best = match &measured.entry {
                    MeasuredEntry::Fitting { name } => {
                        let guide = &setup.guides[g];
                        let named = guide.name == *name || guide.configurations[0].name == *name;
                        (guide.fixed && named).then_some((0, 0.0))
                    }
                    MeasuredEntry::Clamp { link, .. } if link_name(g) != link => None,
                    MeasuredEntry::Clamp { .. } => (0..setup.guides[g].configurations.len())
                        .filter_map(|c| Some((c, distance_mm(&measured.entry, &place(g, c)?)?)))
                        .filter(|&(_, d)| d <= tolerance_mm)
                        .min_by(|a, b| a.1.total_cmp(&b.1)),
                };
                best.map(|(c, d)| (g, c, d))
            });
            let Some((g, c, distance)) = found else {
                return Err(error(
                    line,
                    self.nothing_near(setup, k, next, tolerance_mm, &place),
                ));
            };
            // A guide the cable slides through is no clamp: nobody measures a mark there.
            let measured_there = |s: usize| {
                let guide = &setup.guides[s];
                !guide.optional && !guide.kinds.iter().any(|k| k.slides())
            };
            if let Some(skipped) = (next..g).find(|&s| measured_there(s)) {
                return Err(error(
                    line,
                    format!(
                        "{} ({}) is not optional, and no clamp before this one was measured \
                         on it",
                        setup.guides[skipped].name,
                        link_name(skipped)
                    ),
                ));
            }
            let mut group = vec![(g, c)];
            // The guides right after it on the same link that coincide with it, unless the
            // next clamp measured is on that link: one clamp, 0 mm pieces between them.
            let next_on_same_link = match self.entries.get(k + 1).map(|e| &e.entry) {
                Some(MeasuredEntry::Clamp { link, .. }) => link == link_name(g),
                _ => false,
            };
            let mut last = g;
            while !next_on_same_link && last + 1 < setup.guides.len() {
                let h = last + 1;
                let Some(copy) = coincident(setup, h, g, c) else {
                    break;
                };
                group.push((h, copy));
                last = h;
            }
            matched.push(Matched {
                line: measured.line,
                guides: group
                    .iter()
                    .map(|&(g, _)| setup.guides[g].name.clone())
                    .collect(),
                configuration: setup.guides[g].configurations[c].name.clone(),
                distance_mm: distance,
            });
            groups.push((group, measured.mark_mm, line));
            next = last + 1;
        }
        // Guides after the last one measured: optional ones left out, the tool's fitting
        // mounted at mark 0.
        for g in next..setup.guides.len() {
            let guide = &setup.guides[g];
            let slides = guide.kinds.iter().any(|k| k.slides());
            match (guide.fixed, guide.optional || slides) {
                (true, _) if g + 1 == setup.guides.len() => groups.push((vec![(g, 0)], 0.0, None)),
                (_, true) => {}
                _ => {
                    return Err(error(
                        None,
                        format!(
                            "no clamp measured on {} ({}): it is not optional",
                            guide.name,
                            link_name(g)
                        ),
                    ));
                }
            }
        }
        self.assemble(setup, &groups, matched)
    }

    /// The path of physical clamps `groups` (guides, mark, line) of `setup`.
    fn assemble(
        &self,
        setup: &Setup,
        groups: &[Group],
        matched: Vec<Matched>,
    ) -> Result<(CablePath, Vec<Matched>), MeasuredError> {
        let error = |line: Option<usize>, problem: String| MeasuredError {
            file: self.source.clone(),
            line,
            problem,
        };
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let mut mounted: Vec<(usize, usize)> = Vec::new();
        let mut lengths = Vec::new();
        for (i, (group, mark_mm, line)) in groups.iter().enumerate() {
            if let Some((_, before_mm, _)) = i.checked_sub(1).map(|p| &groups[p]) {
                let piece_mm = before_mm - mark_mm;
                if piece_mm < pitch_mm / 2.0 {
                    return Err(error(
                        *line,
                        format!(
                            "mark {mark_mm} mm after mark {before_mm} mm: marks fall from the \
                             base side toward the tool (the cable's end there is mark 0)"
                        ),
                    ));
                }
                lengths.push((piece_mm / pitch_mm).round() as usize);
            }
            for (j, &guide) in group.iter().enumerate() {
                if j > 0 {
                    lengths.push(0);
                }
                mounted.push(guide);
            }
        }
        // A swivel clamp between two pieces: its two pieces are one of the search's, held at
        // the mark the setup's windows give.
        let mut i = 1;
        while i + 1 < mounted.len() {
            let g = mounted[i].0;
            let (before, total) = (lengths[i - 1], lengths[i - 1] + lengths[i]);
            let split = (0..setup.segment_count())
                .find(|&m| setup.segments[m].through == Some(g))
                .and_then(|m| setup.swivel_of(m, total));
            let Some(judged) = split.map(|split| split.before) else {
                i += 1;
                continue;
            };
            if judged != before {
                let measured = groups.iter().find(|(group, ..)| group[0].0 == g);
                let mark_mm = measured.map_or(0.0, |g| g.1);
                return Err(error(
                    measured.and_then(|g| g.2),
                    format!(
                        "{} is a swivel clamp with {} mm of cable before it, but the search \
                         judged the {} mm through it with {} mm before it (the setup's length \
                         windows share the spare length): mount it at mark {} mm",
                        setup.guides[g].name,
                        before as f64 * pitch_mm,
                        total as f64 * pitch_mm,
                        judged as f64 * pitch_mm,
                        mark_mm + (before as f64 - judged as f64) * pitch_mm
                    ),
                ));
            }
            mounted.remove(i);
            lengths[i - 1] = total;
            lengths.remove(i);
        }
        let mut segments = Vec::with_capacity(mounted.len().saturating_sub(1));
        for pair in mounted.windows(2) {
            let ends = (pair[0].0, pair[1].0);
            let m = (0..setup.segment_count()).find(|&m| setup.segment_guides(m) == ends);
            let m = m.ok_or_else(|| {
                let names = (&setup.guides[ends.0].name, &setup.guides[ends.1].name);
                error(
                    None,
                    format!("the setup has no piece from {} to {}", names.0, names.1),
                )
            })?;
            segments.push(m);
        }
        let path = CablePath {
            segments,
            lengths,
            configurations: mounted.iter().map(|&(_, c)| c).collect(),
        };
        path.check(setup)
            .map_err(|e| error(None, format!("the mounting does not fit the setup: {e}")))?;
        Ok((path, matched))
    }

    /// Why entry `k` matched nothing from guide `from` on: the nearest place of its link.
    fn nothing_near(
        &self,
        setup: &Setup,
        k: usize,
        from: usize,
        tolerance_mm: f64,
        place: &dyn Fn(usize, usize) -> Option<LinkPlace>,
    ) -> String {
        let entry = &self.entries[k].entry;
        let link = match entry {
            MeasuredEntry::Clamp { link, .. } => link,
            MeasuredEntry::Fitting { name } => {
                return format!("the setup fixes no fitting `{name}` after the clamps before it");
            }
        };
        let on_link: Vec<usize> = (from..setup.guides.len())
            .filter(|&g| setup.robot.links[setup.guides[g].link].name == *link)
            .collect();
        if on_link.is_empty() {
            return format!("no clamp of the setup left on `{link}` after the clamps before it");
        }
        let nearest = (on_link.iter())
            .flat_map(|&g| (0..setup.guides[g].configurations.len()).map(move |c| (g, c)))
            .filter_map(|(g, c)| Some((g, c, distance_mm(entry, &place(g, c)?)?)))
            .min_by(|a, b| a.2.total_cmp(&b.2));
        match nearest {
            Some((g, c, d)) => format!(
                "nothing of the setup on {link} within {tolerance_mm} mm of the place measured \
                 (the nearest: {} `{}`, {d:.0} mm away)",
                setup.guides[g].name, setup.guides[g].configurations[c].name
            ),
            None => format!("no place of the setup on {link} can be measured as given"),
        }
    }
}

/// How far a measured clamp is from `place` (mm), `None` when its cable direction does not
/// match the one measured or the two cannot be compared (along measured on one only).
fn distance_mm(entry: &MeasuredEntry, place: &LinkPlace) -> Option<f64> {
    let MeasuredEntry::Clamp {
        along_mm,
        around_deg,
        off_axis_mm,
        cable_to_axis_deg,
        cable_turn,
        ..
    } = entry
    else {
        return None;
    };
    if let Some(angle) = cable_to_axis_deg
        && (angle - place.cable_to_axis_deg).abs() > DIRECTION_WITHIN_DEG
    {
        return None;
    }
    if cable_turn.is_some() && *cable_turn != place.cable_turn {
        return None;
    }
    let along = match (along_mm, place.along_mm) {
        (Some(a), Some(b)) => a - b,
        (None, None) => 0.0,
        _ => return None,
    };
    let turn = (around_deg - place.around_deg + 180.0).rem_euclid(360.0) - 180.0;
    let arc = turn.to_radians() * place.off_axis_mm;
    let off = off_axis_mm.map_or(0.0, |off| off - place.off_axis_mm);
    Some((along * along + arc * arc + off * off).sqrt())
}

/// The configuration of guide `h` that coincides with guide `g`'s `c` (same place and cable
/// direction), when `h` is on the same link.
fn coincident(setup: &Setup, h: usize, g: usize, c: usize) -> Option<usize> {
    let (a, b) = (&setup.guides[g], &setup.guides[h]);
    if a.body != b.body {
        return None;
    }
    let pose = a.link_in_body * a.configurations[c].pose;
    (0..b.configurations.len()).find(|&k| {
        let other = b.link_in_body * b.configurations[k].pose;
        let apart = (other.translation.vector - pose.translation.vector).norm();
        apart < 1e-6 && other.rotation.angle_to(&pose.rotation) < 1e-6
    })
}
