//! Waypoint files (TOML): what the trajectory generator reads.

use super::{MotionError, Profile};
use crate::input::line_of;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A parsed and checked waypoint file (format: see the [module](super) docs). Joint values
/// stay in file units (degrees, millimetres for prismatic joints) until
/// [`WaypointFile::generate`] meets the robot.
#[derive(Debug, Clone, PartialEq)]
pub struct WaypointFile {
    /// The file it was read from (for messages and the CSV comment).
    pub source: PathBuf,
    /// Free text carried into the generated CSV's comment.
    pub description: Option<String>,
    /// The robot's URDF, resolved against the waypoint file's folder.
    pub robot_urdf: PathBuf,
    /// Sample rate of the generated motion (Hz).
    pub sample_rate_hz: f64,
    /// Fraction (0, 1] of each joint's URDF speed limit that moves may use.
    pub speed_scale: f64,
    /// Velocity profile of every move.
    pub profile: Profile,
    /// Acceleration limits of the joints.
    pub acceleration: Acceleration,
    /// The waypoints, in the order they are visited (at least one).
    pub waypoints: Vec<Waypoint>,
}

/// How the joints' acceleration limits are given.
#[derive(Debug, Clone, PartialEq)]
pub enum Acceleration {
    /// Every joint reaches its (scaled) speed limit in this time (s): `a_j = v_j / t`.
    TimeToFullSpeed {
        /// The time from rest to full speed (s).
        seconds: f64,
    },
    /// One limit per joint in joint-vector order: deg/s² (mm/s² for prismatic joints).
    PerJoint {
        /// The limits in file units.
        values_deg_s2: Vec<f64>,
        /// Line of the list in the file.
        line: usize,
    },
}

/// A pose the robot moves to and rests at.
#[derive(Debug, Clone, PartialEq)]
pub struct Waypoint {
    /// The `name` key, or `waypoint <n>` (1-based) without one.
    pub name: String,
    /// One value per actuated joint, joint-vector order: degrees (mm for prismatic joints).
    pub joints_deg: Vec<f64>,
    /// Rest at the waypoint before moving on (s).
    pub dwell_s: f64,
    /// Line of `joints_deg` in the file.
    pub line: usize,
}

/// The file's keys, as written (units in the names).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    description: Option<String>,
    robot: String,
    sample_rate_hz: Spanned<f64>,
    speed_scale: Spanned<f64>,
    profile: Profile,
    time_to_full_speed_s: Option<Spanned<f64>>,
    acceleration_deg_s2: Option<Spanned<Vec<f64>>>,
    waypoint: Spanned<Vec<RawWaypoint>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWaypoint {
    name: Option<String>,
    joints_deg: Spanned<Vec<f64>>,
    dwell_s: Option<Spanned<f64>>,
}

/// Checks values of one file, locating problems by byte offset.
struct Checker<'a> {
    text: &'a str,
    source: &'a Path,
}

impl Checker<'_> {
    fn error(&self, offset: usize, problem: impl Into<String>) -> MotionError {
        MotionError::at(self.source, line_of(self.text, offset), problem)
    }

    /// A finite number within `ok`, described by `rule` otherwise.
    fn number(
        &self,
        key: &str,
        value: &Spanned<f64>,
        ok: impl Fn(f64) -> bool,
        rule: &str,
    ) -> Result<f64, MotionError> {
        let v = *value.get_ref();
        if v.is_finite() && ok(v) {
            Ok(v)
        } else {
            Err(self.error(value.span().start, format!("`{key}` = {v} must be {rule}")))
        }
    }

    /// A list of finite numbers, each within `ok`.
    fn list(
        &self,
        key: &str,
        values: &Spanned<Vec<f64>>,
        ok: impl Fn(f64) -> bool,
        rule: &str,
    ) -> Result<Vec<f64>, MotionError> {
        let bad = values
            .get_ref()
            .iter()
            .position(|&v| !(v.is_finite() && ok(v)));
        match bad {
            None => Ok(values.get_ref().clone()),
            Some(i) => Err(self.error(
                values.span().start,
                format!(
                    "`{key}` item {} = {} must be {rule}",
                    i + 1,
                    values.get_ref()[i]
                ),
            )),
        }
    }
}

impl WaypointFile {
    /// Reads and checks a waypoint file (everything that can be checked without the robot).
    pub fn from_file(path: impl AsRef<Path>) -> Result<WaypointFile, MotionError> {
        let path = path.as_ref();
        let text = crate::input::read_text(path, crate::input::WAYPOINTS)
            .map_err(|e| MotionError::in_file(path, e))?;
        WaypointFile::from_toml_str(&text, path)
    }

    /// Parses and checks a waypoint file's text; `source` names it in messages and anchors
    /// the relative robot path.
    pub fn from_toml_str(text: &str, source: &Path) -> Result<WaypointFile, MotionError> {
        let raw: RawFile = toml::from_str(text).map_err(|e| MotionError {
            file: Some(source.to_path_buf()),
            line: e.span().map(|s| line_of(text, s.start)),
            problem: e.message().to_string(),
        })?;
        let check = Checker { text, source };
        let positive = |v: f64| v > 0.0;
        let acceleration = match (&raw.time_to_full_speed_s, &raw.acceleration_deg_s2) {
            (Some(t), None) => Acceleration::TimeToFullSpeed {
                seconds: check.number("time_to_full_speed_s", t, positive, "a number > 0")?,
            },
            (None, Some(list)) => Acceleration::PerJoint {
                values_deg_s2: check.list("acceleration_deg_s2", list, positive, "> 0")?,
                line: line_of(text, list.span().start),
            },
            _ => {
                return Err(MotionError::in_file(
                    source,
                    "give exactly one of `time_to_full_speed_s` (s) and `acceleration_deg_s2` \
                     (one per joint)",
                ));
            }
        };
        if raw.waypoint.get_ref().is_empty() {
            return Err(check.error(raw.waypoint.span().start, "no `[[waypoint]]`"));
        }
        let waypoints = raw
            .waypoint
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, w)| check.waypoint(i, w))
            .collect::<Result<_, _>>()?;
        let folder = source.parent().unwrap_or(Path::new(""));
        Ok(WaypointFile {
            source: source.to_path_buf(),
            description: raw.description,
            robot_urdf: folder.join(&raw.robot),
            sample_rate_hz: check.number("sample_rate_hz", &raw.sample_rate_hz, positive, "> 0")?,
            speed_scale: check.number(
                "speed_scale",
                &raw.speed_scale,
                |v| v > 0.0 && v <= 1.0,
                "in (0, 1]",
            )?,
            profile: raw.profile,
            acceleration,
            waypoints,
        })
    }
}

impl Checker<'_> {
    fn waypoint(&self, index: usize, raw: &RawWaypoint) -> Result<Waypoint, MotionError> {
        let name = raw
            .name
            .clone()
            .unwrap_or_else(|| format!("waypoint {}", index + 1));
        let here = |mut e: MotionError| {
            e.problem = format!("waypoint {} (`{name}`): {}", index + 1, e.problem);
            e
        };
        let joints_deg = self
            .list("joints_deg", &raw.joints_deg, |_| true, "a finite number")
            .map_err(here)?;
        let dwell_s = match &raw.dwell_s {
            Some(d) => self
                .number("dwell_s", d, |v| v >= 0.0, "a number ≥ 0")
                .map_err(here)?,
            None => 0.0,
        };
        Ok(Waypoint {
            name,
            joints_deg,
            dwell_s,
            line: line_of(self.text, raw.joints_deg.span().start),
        })
    }
}
