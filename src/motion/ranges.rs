//! Axis ranges: the box of joint values a dress pack must allow, as vendors print it ("J4
//! ±170°, J6 ±240°"), and the stress motions that drive each ranged axis across it.
//!
//! # Ranges file (TOML)
//!
//! ```toml
//! time_to_full_speed_s = 0.3   # optional: how fast the stress motions accelerate (default 0.3)
//!
//! [joints]                     # deg (mm for prismatic joints); unnamed joints: URDF limits
//! joint_4 = [-170.0, 190.0]
//! joint_6 = [-240.0, 240.0]
//! ```
//!
//! Every named joint must be an actuated joint of the robot, its range inside the URDF
//! limits with min < max; a continuous joint (no URDF limits) must be named. Errors name the
//! file, the line and the joint.

use super::{Acceleration, Cell, CellMotion, MotionError, Profile, Waypoint, WaypointFile};
use crate::input::line_of;
use crate::robot::Robot;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// How fast the stress motions reach full speed when the file does not say (s): industrial
/// arms reach their rated joint speeds in a few tenths of a second.
pub const DEFAULT_TIME_TO_FULL_SPEED_S: f64 = 0.3;

/// The rest at each end of a stress motion's stroke (s): the loop swings out after the
/// stop, and the motion test sees it.
pub const STROKE_END_DWELL_S: f64 = 1.0;

/// The longest stroke a stress motion may take (s): a URDF speed limit so low that crossing
/// the range takes longer is refused rather than sampled.
pub const MAX_STROKE_S: f64 = 600.0;

/// The box of joint values, one interval per actuated joint (rad or m, joint-vector order).
#[derive(Debug, Clone, PartialEq)]
pub struct JointRanges {
    /// The file it was read from (`None`: built in memory).
    pub source: Option<PathBuf>,
    /// Per actuated joint, `[min, max]` (rad / m).
    pub ranges: Vec<[f64; 2]>,
    /// Per actuated joint: named in the file (a ranged axis), not the URDF's.
    pub named: Vec<bool>,
    /// The stress motions' time from rest to full speed (s).
    pub time_to_full_speed_s: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRanges {
    time_to_full_speed_s: Option<Spanned<f64>>,
    joints: Spanned<BTreeMap<String, Spanned<Vec<f64>>>>,
}

impl JointRanges {
    /// The URDF limits of every joint (none named); `None` when a joint has no limits.
    pub fn urdf(robot: &Robot) -> Option<JointRanges> {
        let ranges = (0..robot.dof())
            .map(|j| robot.actuated_joint(j).limits.map(|l| [l.lower, l.upper]))
            .collect::<Option<Vec<_>>>()?;
        Some(JointRanges {
            source: None,
            named: vec![false; ranges.len()],
            ranges,
            time_to_full_speed_s: DEFAULT_TIME_TO_FULL_SPEED_S,
        })
    }

    /// The least box holding every sample of `cell`'s motions (each joint between its least
    /// and greatest value over them; none named): the box a mounting found for motions is
    /// asked about when no ranges are given. `None` for a cell without samples.
    pub fn spanned(cell: &Cell) -> Option<JointRanges> {
        let mut samples = (cell.motions.iter()).flat_map(|m| m.motion.samples());
        let first = samples.next()?;
        let mut ranges: Vec<[f64; 2]> = first.iter().map(|&v| [v, v]).collect();
        for sample in samples {
            for (range, &v) in ranges.iter_mut().zip(sample) {
                *range = [range[0].min(v), range[1].max(v)];
            }
        }
        Some(JointRanges {
            source: None,
            named: vec![false; ranges.len()],
            ranges,
            time_to_full_speed_s: DEFAULT_TIME_TO_FULL_SPEED_S,
        })
    }

    /// Reads a ranges file for `robot`.
    pub fn from_file(robot: &Robot, path: &Path) -> Result<JointRanges, MotionError> {
        let text = crate::input::read_text(path, crate::input::WAYPOINTS)
            .map_err(|e| MotionError::in_file(path, e))?;
        let at =
            |offset: usize, problem: String| MotionError::at(path, line_of(&text, offset), problem);
        let raw: RawRanges = toml::from_str(&text).map_err(|e| MotionError {
            file: Some(path.to_path_buf()),
            line: e.span().map(|s| line_of(&text, s.start)),
            problem: format!(
                "{} (a ranges file has `[joints]`, one `name = [min, max]` each)",
                e.message()
            ),
        })?;
        let time_to_full_speed_s = match &raw.time_to_full_speed_s {
            Some(t) if !(t.get_ref().is_finite() && *t.get_ref() > 0.0) => {
                return Err(at(
                    t.span().start,
                    format!("`time_to_full_speed_s` = {} must be > 0", t.get_ref()),
                ));
            }
            Some(t) => *t.get_ref(),
            None => DEFAULT_TIME_TO_FULL_SPEED_S,
        };
        let mut ranges: Vec<Option<[f64; 2]>> = (0..robot.dof())
            .map(|j| robot.actuated_joint(j).limits.map(|l| [l.lower, l.upper]))
            .collect();
        let mut named = vec![false; robot.dof()];
        for (name, values) in raw.joints.get_ref() {
            let offset = values.span().start;
            let j = robot.actuated_index(name).ok_or_else(|| {
                let known: Vec<&str> = (0..robot.dof())
                    .map(|j| robot.actuated_joint(j).name.as_str())
                    .collect();
                at(
                    offset,
                    format!(
                        "`{name}` is not an actuated joint of the robot (it has {})",
                        known.join(", ")
                    ),
                )
            })?;
            let joint = robot.actuated_joint(j);
            let (scale, unit) = match joint.kind.is_rotary() {
                true => (1f64.to_radians(), "°"),
                false => (1e-3, " mm"),
            };
            let [min, max] = values.get_ref()[..] else {
                return Err(at(
                    offset,
                    format!(
                        "`{name}`: give [min, max], got {} numbers",
                        values.get_ref().len()
                    ),
                ));
            };
            if !(min.is_finite() && max.is_finite() && min < max) {
                return Err(at(
                    offset,
                    format!("`{name}` = [{min}, {max}]: give finite numbers, min < max"),
                ));
            }
            let range = [min * scale, max * scale];
            if let Some(limits) = joint.limits {
                let slack = 1e-9;
                if range[0] < limits.lower - slack || range[1] > limits.upper + slack {
                    return Err(at(
                        offset,
                        format!(
                            "`{name}` = [{min}, {max}] goes beyond the URDF limits [{:.1}, {:.1}]{unit}",
                            limits.lower / scale,
                            limits.upper / scale
                        ),
                    ));
                }
            }
            ranges[j] = Some(range);
            named[j] = true;
        }
        let ranges = (ranges.into_iter().enumerate())
            .map(|(j, r)| {
                r.ok_or_else(|| {
                    MotionError::in_file(
                        path,
                        format!(
                            "`{}` has no URDF limits (a continuous joint): name its range under [joints]",
                            robot.actuated_joint(j).name
                        ),
                    )
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        if !named.iter().any(|&n| n) {
            return Err(at(
                raw.joints.span().start,
                "no joint named under [joints]".into(),
            ));
        }
        Ok(JointRanges {
            source: Some(path.to_path_buf()),
            ranges,
            named,
            time_to_full_speed_s,
        })
    }

    /// The box as a ranges file (the format [`JointRanges::from_file`] reads): its named
    /// joints in degrees (mm), the stress motions' time to full speed, after `comment` (each
    /// line as a TOML comment). What a design answered, written for `check --ranges` and for
    /// the next design.
    pub fn to_toml(&self, robot: &Robot, comment: &str) -> String {
        // Control characters (a file name may carry them) have no place in a TOML comment.
        let line = |l: &str| -> String {
            let shown: String = (l.chars())
                .map(|c| if c.is_control() { '?' } else { c })
                .collect();
            format!("# {shown}\n")
        };
        let mut text: String = comment.lines().map(line).collect();
        text += &format!(
            "time_to_full_speed_s = {}\n\n[joints]\n",
            self.time_to_full_speed_s
        );
        for (j, [min, max]) in self.ranges.iter().enumerate() {
            if !self.named[j] {
                continue;
            }
            let joint = robot.actuated_joint(j);
            let scale = match joint.kind.is_rotary() {
                true => 1f64.to_degrees(),
                false => 1e3,
            };
            // Names as TOML keys: bare when they can be, else quoted as JSON quotes them.
            let bare =
                (joint.name.bytes()).all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
            let key = match bare && !joint.name.is_empty() {
                true => joint.name.clone(),
                false => serde_json::to_string(&joint.name).unwrap_or_default(),
            };
            // To a millionth of a degree (mm), inward — never wider than the box but by what
            // converting units loses (≤ 1e-9°).
            let tidy = |v: f64, inward: fn(f64) -> f64| {
                let millionths = v * scale * 1e6;
                match (millionths - millionths.round()).abs() < 1e-3 {
                    true => millionths.round() / 1e6,
                    false => inward(millionths) / 1e6,
                }
            };
            let (min, max) = (tidy(*min, f64::ceil), tidy(*max, f64::floor));
            text += &format!("{key} = [{min}, {max}]\n");
        }
        text
    }

    /// The middle of the box (rad / m).
    pub fn centre(&self) -> Vec<f64> {
        self.ranges.iter().map(|[a, b]| 0.5 * (a + b)).collect()
    }

    /// The box with joint `j`'s range narrowed to `keep` (0–1) of its width, about its middle
    /// (`kept_end` `None`) or from one end, the other kept (`Some(0)` keeps the minimum,
    /// `Some(1)` the maximum); its ends rounded inward to 0.1° (0.1 mm for a prismatic joint;
    /// `rotary`) so that the range printed is the range solved.
    pub fn narrowed(
        &self,
        j: usize,
        keep: f64,
        kept_end: Option<usize>,
        rotary: bool,
    ) -> JointRanges {
        let mut narrowed = self.clone();
        let [a, b] = self.ranges[j];
        let width = (b - a) * keep.clamp(0.0, 1.0);
        let (lo, hi) = match kept_end {
            Some(0) => (a, a + width),
            Some(_) => (b - width, b),
            None => (0.5 * (a + b - width), 0.5 * (a + b + width)),
        };
        let unit = match rotary {
            true => 0.1f64.to_radians(),
            false => 1e-4,
        };
        let (lo, hi) = (lo / unit, hi / unit);
        let (lo, hi) = match (lo.ceil(), hi.floor()) {
            (lo, hi) if lo < hi => (lo, hi),
            _ => (lo, hi),
        };
        narrowed.ranges[j] = [lo * unit, hi * unit];
        narrowed
    }

    /// Whether `joints` (rad / m) lie in the box (1e-9 slack).
    pub fn contains(&self, joints: &[f64]) -> bool {
        (joints.iter().zip(&self.ranges)).all(|(v, [a, b])| *v >= a - 1e-9 && *v <= b + 1e-9)
    }

    /// The stress motions, sampled at `sample_rate_hz`: each ranged axis alone from its
    /// minimum to its maximum and back at its URDF speed limit, the other joints at the box's
    /// middle; then every ranged axis together; a rest of [`STROKE_END_DWELL_S`] at each end.
    pub fn stress_motions(&self, robot: &Robot, sample_rate_hz: f64) -> Result<Cell, MotionError> {
        let ranged: Vec<usize> = (0..self.ranges.len()).filter(|&j| self.named[j]).collect();
        for &j in &ranged {
            let joint = robot.actuated_joint(j);
            let speed = joint.limits.and_then(|l| l.velocity).unwrap_or(0.0);
            let stroke_s = (self.ranges[j][1] - self.ranges[j][0]) / speed;
            if stroke_s.is_nan() || stroke_s > MAX_STROKE_S {
                return Err(MotionError::data(format!(
                    "`{}`: at its URDF speed limit ({speed}) its range takes {stroke_s:.0} s to \
                     cross, more than {MAX_STROKE_S} s",
                    joint.name
                )));
            }
        }
        let centre = self.centre();
        let deg = |j: usize, v: f64| match robot.actuated_joint(j).kind.is_rotary() {
            true => v.to_degrees(),
            false => v * 1e3,
        };
        let pose = |ends: &[(usize, usize)]| -> Vec<f64> {
            let mut joints = centre.clone();
            for &(j, end) in ends {
                joints[j] = self.ranges[j][end];
            }
            (0..joints.len()).map(|j| deg(j, joints[j])).collect()
        };
        let stroke = |name: String, joints: &[usize]| -> Result<CellMotion, MotionError> {
            let at = |end: usize| joints.iter().map(|&j| (j, end)).collect::<Vec<_>>();
            let waypoint = |name: &str, end: usize| Waypoint {
                name: name.into(),
                joints_deg: pose(&at(end)),
                dwell_s: STROKE_END_DWELL_S,
                line: 0,
            };
            let file = WaypointFile {
                source: self
                    .source
                    .clone()
                    .unwrap_or_else(|| PathBuf::from("ranges")),
                description: None,
                robot_urdf: robot.source.clone(),
                sample_rate_hz,
                speed_scale: 1.0,
                profile: Profile::Trapezoidal,
                acceleration: Acceleration::TimeToFullSpeed {
                    seconds: self.time_to_full_speed_s,
                },
                waypoints: vec![
                    waypoint("min", 0),
                    waypoint("max", 1),
                    waypoint("min again", 0),
                ],
            };
            Ok(CellMotion {
                name,
                file: None,
                cycles_per_hour: None,
                motion: file.generate(robot)?.motion,
                grid: None,
            })
        };
        let mut motions = Vec::with_capacity(ranged.len() + 1);
        for &j in &ranged {
            motions.push(stroke(
                format!("{} end to end", robot.actuated_joint(j).name),
                &[j],
            )?);
        }
        if ranged.len() > 1 {
            motions.push(stroke("every ranged axis together".into(), &ranged)?);
        }
        Ok(Cell {
            source: self.source.clone(),
            description: Some("the stress motions of the axis ranges".into()),
            motions,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::narrow_pick_and_place;

    fn write(name: &str, text: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("cable-dict-ranges-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
        path
    }

    #[test]
    fn a_box_written_as_a_ranges_file_reads_back_as_the_same_box_never_wider() {
        let (setup, _) = narrow_pick_and_place();
        let robot = &setup.robot;
        let asked = write(
            "asked.toml",
            "time_to_full_speed_s = 0.3\n[joints]\njoint_4 = [0, 48.8]\njoint_5 = [-62.9, 57.3]\n",
        );
        let asked = JointRanges::from_file(robot, &asked).unwrap_or_else(|e| panic!("{e}"));
        let j5 = robot.actuated_index("joint_5").expect("joint_5");
        // As a design answers: one axis narrowed from its upper end, a gentler ramp.
        let answered = JointRanges {
            time_to_full_speed_s: 1.2,
            ..asked.narrowed(j5, 0.5, Some(0), true)
        };
        let text = answered.to_toml(robot, "answered\nsecond \r line\u{7}");
        assert!(text.starts_with("# answered\n# second ? line?\n"), "{text}");
        let read = JointRanges::from_file(robot, &write("answered.toml", &text))
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(read.named, answered.named);
        assert_eq!(read.time_to_full_speed_s, 1.2);
        // Joint 5 narrowed to -62.9…-2.9°: the 0.1° grid the narrowing rounds to.
        assert!(
            (read.ranges[j5][1].to_degrees() - -2.9).abs() < 1e-6,
            "{text}"
        );
        for (j, ([a, b], [c, d])) in read.ranges.iter().zip(&answered.ranges).enumerate() {
            assert!(
                a >= &(c - 1e-11) && b <= &(d + 1e-11),
                "joint {j}: {a}…{b} wider than {c}…{d}"
            );
            assert!((a - c).abs() < 1e-7 && (b - d).abs() < 1e-7, "joint {j}");
        }
    }

    #[test]
    fn a_ranges_file_names_joints_within_their_limits_and_refuses_the_rest() {
        let (setup, _) = narrow_pick_and_place();
        let robot = &setup.robot;
        let good = write(
            "good.toml",
            "[joints]\njoint_4 = [-170, 170]\njoint_6 = [-240.0, 240.0]\n",
        );
        let ranges = JointRanges::from_file(robot, &good).unwrap_or_else(|e| panic!("{e}"));
        let j4 = robot.actuated_index("joint_4").expect("joint_4");
        assert_eq!(
            ranges.ranges[j4],
            [-170f64.to_radians(), 170f64.to_radians()]
        );
        assert_eq!(ranges.named.iter().filter(|&&n| n).count(), 2);
        let j1 = robot.actuated_index("joint_1").expect("joint_1");
        let limits = robot.actuated_joint(j1).limits.expect("limits");
        assert_eq!(ranges.ranges[j1], [limits.lower, limits.upper]);
        let cases = [
            ("[joints]\njoint_9 = [0, 1]\n", "not an actuated joint"),
            ("[joints]\njoint_4 = [10, -10]\n", "min < max"),
            ("[joints]\njoint_4 = [0, 1, 2]\n", "got 3 numbers"),
            ("[joints]\njoint_4 = [-400, 0]\n", "beyond the URDF limits"),
            (
                "time_to_full_speed_s = 0\n[joints]\njoint_4 = [0, 1]\n",
                "must be > 0",
            ),
            ("[joints]\n", "no joint named"),
            ("[joint]\njoint_4 = [0, 1]\n", "unknown field"),
        ];
        for (i, (text, expected)) in cases.iter().enumerate() {
            let file = write(&format!("bad{i}.toml"), text);
            let error = JointRanges::from_file(robot, &file)
                .expect_err(text)
                .to_string();
            assert!(
                error.contains(expected) && error.contains(&format!("bad{i}.toml")),
                "{text}: {error}"
            );
        }
    }

    /// A URDF speed limit so low that a stroke would take hours is refused before a sample
    /// is made.
    #[test]
    fn a_stroke_longer_than_the_bound_is_refused() {
        let (setup, _) = narrow_pick_and_place();
        let mut robot = setup.robot.clone();
        let j4 = robot.actuated_index("joint_4").expect("joint_4");
        let joint = robot.actuated[j4];
        if let Some(limits) = robot.joints[joint].limits.as_mut() {
            limits.velocity = Some(1e-4);
        }
        let file = write("slow.toml", "[joints]\njoint_4 = [-90, 90]\n");
        let ranges = JointRanges::from_file(&robot, &file).unwrap_or_else(|e| panic!("{e}"));
        let error = ranges
            .stress_motions(&robot, 100.0)
            .expect_err("refused")
            .to_string();
        assert!(
            error.contains("joint_4") && error.contains("more than 600 s"),
            "{error}"
        );
    }

    /// Each stress motion drives its axes from the box's minimum to its maximum and back at
    /// the URDF speed limit, everything else at the middle; a trapezoidal move of distance d
    /// at speed v reaching it in t takes d / v + t (d ≥ v t).
    #[test]
    fn the_stress_motions_cross_the_box_at_the_urdf_speed() {
        let (setup, _) = narrow_pick_and_place();
        let robot = &setup.robot;
        let file = write(
            "stress.toml",
            "[joints]\njoint_4 = [-90, 90]\njoint_6 = [-180, 180]\n",
        );
        let ranges = JointRanges::from_file(robot, &file).unwrap_or_else(|e| panic!("{e}"));
        let cell = ranges
            .stress_motions(robot, 100.0)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(cell.len(), 3);
        let centre = ranges.centre();
        let t = ranges.time_to_full_speed_s;
        for (motion, axes) in
            cell.motions
                .iter()
                .zip([vec!["joint_4"], vec!["joint_6"], vec!["joint_4", "joint_6"]])
        {
            let m = &motion.motion;
            let axes: Vec<usize> = axes
                .iter()
                .map(|a| robot.actuated_index(a).expect("axis"))
                .collect();
            for (j, middle) in centre.iter().enumerate() {
                let series = m.joint_series(j).expect("joint");
                let (lo, hi) = series
                    .iter()
                    .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
                if axes.contains(&j) {
                    assert!(
                        (lo - ranges.ranges[j][0]).abs() < 1e-9
                            && (hi - ranges.ranges[j][1]).abs() < 1e-9,
                        "{}",
                        motion.name
                    );
                } else {
                    assert!(
                        (lo - middle).abs() < 1e-9 && (hi - middle).abs() < 1e-9,
                        "{}",
                        motion.name
                    );
                }
            }
            // The slowest axis sets the move's time; the others are scaled to it.
            let move_s = axes
                .iter()
                .map(|&j| {
                    let v = robot
                        .actuated_joint(j)
                        .limits
                        .and_then(|l| l.velocity)
                        .expect("speed");
                    let d = ranges.ranges[j][1] - ranges.ranges[j][0];
                    assert!(d >= v * t);
                    d / v + t
                })
                .fold(0.0, f64::max);
            let expected_s = 3.0 * STROKE_END_DWELL_S + 2.0 * move_s;
            assert!(expected_s < MAX_STROKE_S);
            assert!(
                (m.duration_s() - expected_s).abs() < 0.011,
                "{}: {} s against {expected_s} s",
                motion.name,
                m.duration_s()
            );
        }
    }
}
