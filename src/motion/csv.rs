//! Motion CSV: reading with located errors, and writing (degrees / millimetres, atomically).

use super::units::ColumnUnit;
use super::{Motion, MotionError};
use crate::atomic_file::write_atomically;
use crate::robot::Robot;
use std::borrow::Cow;
use std::fmt::Write as _;
use std::path::Path;

/// Slack (rad or m) on the joint limits, as in [`Robot::check_limits`].
const LIMIT_TOLERANCE: f64 = 1e-9;

/// One joint column of the header.
struct Column {
    /// The header text, e.g. `joint_2_deg`.
    header: String,
    /// Joint-vector index.
    joint: usize,
    unit: ColumnUnit,
}

/// The reader's position in the file, for messages.
struct Cursor<'a> {
    file: &'a Path,
    line: usize,
}

impl Cursor<'_> {
    fn error(&self, problem: impl Into<String>) -> MotionError {
        MotionError::at(self.file, self.line, problem)
    }
}

impl Motion {
    /// Reads and validates a motion CSV for `robot` (format: see the [module](super) docs).
    pub fn from_csv_file(robot: &Robot, path: impl AsRef<Path>) -> Result<Motion, MotionError> {
        let path = path.as_ref();
        let text = crate::input::read_text(path, crate::input::MOTION)
            .map_err(|e| MotionError::in_file(path, e))?;
        Motion::from_csv_str(robot, &text, path)
    }

    /// Parses and validates a motion CSV's text; `source` names it in messages.
    pub fn from_csv_str(robot: &Robot, text: &str, source: &Path) -> Result<Motion, MotionError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, line)| (i + 1, line.trim()))
            .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'));
        let Some((header_line, header)) = lines.next() else {
            return Err(MotionError::in_file(
                source,
                "no header line (expected `time_s,<URDF joint name>_deg,…`)",
            ));
        };
        let cursor = Cursor {
            file: source,
            line: header_line,
        };
        let columns = parse_header(robot, header, &cursor)?;
        let (mut times_s, mut samples) = (Vec::new(), Vec::new());
        let mut previous: Option<(f64, usize)> = None;
        for (line, row) in lines {
            let cursor = Cursor { file: source, line };
            let (time_s, sample) = parse_row(robot, &columns, row, &cursor)?;
            if let Some((before, before_line)) = previous
                && time_s <= before
            {
                return Err(cursor.error(format!(
                    "time {time_s} s is not after the previous sample's {before} s (line \
                     {before_line}); times must strictly increase"
                )));
            }
            previous = Some((time_s, line));
            times_s.push(time_s);
            samples.push(sample);
        }
        if times_s.is_empty() {
            return Err(cursor.error("the header is not followed by any sample"));
        }
        if let Some(warning) = radians_under_degrees(&columns, &samples) {
            log::warn!("{}: {warning}", source.display());
        }
        Motion::new(robot, times_s, samples).map_err(|e| e.located(source, None))
    }

    /// The motion as CSV text: `comment` as `# ` lines, the header, one row per sample; rotary
    /// joints in degrees, prismatic ones in millimetres, every number in the shortest form
    /// that reads back to the same value.
    pub fn to_csv(&self, comment: &str) -> String {
        let mut out = String::new();
        for line in comment.lines() {
            out.push('#');
            if !line.is_empty() {
                out.push(' ');
                out.push_str(line);
            }
            out.push('\n');
        }
        let units: Vec<ColumnUnit> = self
            .rotary()
            .iter()
            .map(|&r| ColumnUnit::display(r))
            .collect();
        out.push_str("time_s");
        for (name, unit) in self.joint_names().iter().zip(&units) {
            let _ = write!(out, ",{name}_{}", unit.suffix());
        }
        out.push('\n');
        for (time_s, sample) in self.times_s().iter().zip(self.samples()) {
            let _ = write!(out, "{time_s}");
            for (value, unit) in sample.iter().zip(&units) {
                let _ = write!(out, ",{}", unit.exact_value(*value));
            }
            out.push('\n');
        }
        out
    }

    /// Writes [`Motion::to_csv`] to `path` atomically (temporary file in the same folder,
    /// fsync, rename).
    pub fn write_csv(&self, path: impl AsRef<Path>, comment: &str) -> Result<(), MotionError> {
        let path = path.as_ref();
        write_atomically(path, self.to_csv(comment).as_bytes())
            .map_err(|e| MotionError::in_file(path, format!("cannot write the motion: {e}")))
    }
}

/// Degrees a `_deg` column's values stay within when they are radians: 2π.
const RADIANS_LOOK_DEG: f64 = std::f64::consts::TAU;

/// A warning when every `_deg` column stays within ±[`RADIANS_LOOK_DEG`] and one of them
/// moves: radians under degree headers read so (every joint then moves a few degrees at
/// most), and a whole motion that small is rare. `samples` hold SI values (rad).
fn radians_under_degrees(columns: &[Column], samples: &[Vec<f64>]) -> Option<String> {
    let degrees: Vec<&Column> = columns
        .iter()
        .filter(|c| c.unit == ColumnUnit::Deg)
        .collect();
    let value_deg = |c: &Column, sample: &Vec<f64>| sample[c.joint].to_degrees();
    let within = degrees.iter().all(|c| {
        samples
            .iter()
            .all(|s| value_deg(c, s).abs() <= RADIANS_LOOK_DEG + 1e-9)
    });
    let moves = degrees.iter().any(|c| {
        samples
            .iter()
            .any(|s| value_deg(c, s) != samples.first().map_or(0.0, |f| value_deg(c, f)))
    });
    (!degrees.is_empty() && within && moves).then(|| {
        format!(
            "every joint angle stays within ±{RADIANS_LOOK_DEG:.2}°, as radians would: the \
             columns say degrees ({}); if the values are radians, head the columns `_rad`",
            degrees
                .iter()
                .map(|c| crate::escape::terminal(&c.header))
                .collect::<Vec<_>>()
                .join(", ")
        )
    })
}

/// `time_s` then one column per actuated joint, each exactly once.
fn parse_header(robot: &Robot, header: &str, at: &Cursor) -> Result<Vec<Column>, MotionError> {
    let mut fields = header.split(',').map(str::trim);
    match fields.next() {
        Some("time_s") => {}
        other => {
            return Err(at.error(format!(
                "column 1 is `{}`; the first column must be `time_s`",
                clipped(other.unwrap_or_default())
            )));
        }
    }
    let mut owner: Vec<Option<usize>> = vec![None; robot.dof()];
    let mut columns = Vec::new();
    for (i, field) in fields.enumerate() {
        let number = i + 2;
        let column = parse_column(robot, field, number, at)?;
        if let Some(first) = owner[column.joint] {
            return Err(at.error(format!(
                "column {number} `{field}`: joint `{}` already has column {first}",
                robot.actuated_joint(column.joint).name
            )));
        }
        owner[column.joint] = Some(number);
        columns.push(column);
    }
    let missing: Vec<&str> = (0..robot.dof())
        .filter(|&j| owner[j].is_none())
        .map(|j| robot.actuated_joint(j).name.as_str())
        .collect();
    if !missing.is_empty() {
        return Err(at.error(format!(
            "no column for joint(s) {}; every actuated joint needs one",
            missing.join(", ")
        )));
    }
    Ok(columns)
}

/// One joint column header: `<URDF joint name>_<unit>`.
fn parse_column(
    robot: &Robot,
    field: &str,
    number: usize,
    at: &Cursor,
) -> Result<Column, MotionError> {
    let shown = clipped(field);
    let parsed = field
        .rsplit_once('_')
        .and_then(|(name, suffix)| Some((name, ColumnUnit::from_suffix(suffix)?)));
    let Some((name, unit)) = parsed else {
        return Err(at.error(format!(
            "column {number} `{shown}`: a joint column is named `<URDF joint name>_deg` or \
             `_rad` (`_mm` or `_m` for prismatic joints)"
        )));
    };
    let Some(joint) = robot.actuated_index(name) else {
        let problem = if robot.joints.iter().any(|j| j.name == name) {
            format!("joint `{name}` is fixed or a mimic joint and takes no column")
        } else {
            let known: Vec<&str> = (0..robot.dof())
                .map(|j| robot.actuated_joint(j).name.as_str())
                .collect();
            format!(
                "robot `{}` has no joint `{}` (its actuated joints: {})",
                robot.name,
                clipped(name),
                known.join(", ")
            )
        };
        return Err(at.error(format!("column {number} `{shown}`: {problem}")));
    };
    let rotary = robot.actuated_joint(joint).kind.is_rotary();
    if unit.is_rotary() != rotary {
        let (kind, units) = match rotary {
            true => ("rotary", "_deg or _rad"),
            false => ("prismatic", "_mm or _m"),
        };
        return Err(at.error(format!(
            "column {number} `{shown}`: joint `{name}` is {kind}; use {units}"
        )));
    }
    Ok(Column {
        header: field.to_string(),
        joint,
        unit,
    })
}

/// `field` for a message: whole when short, else its start and its length, so that a
/// malformed line of 100 MB is not echoed into the error.
fn clipped(field: &str) -> Cow<'_, str> {
    const SHOWN_CHARS: usize = 40;
    match field.char_indices().nth(SHOWN_CHARS) {
        None => Cow::Borrowed(field),
        Some((end, _)) => Cow::Owned(format!("{}… ({} bytes)", &field[..end], field.len())),
    }
}

/// One data row: the time (s) and the joint vector (SI), checked against the limits.
fn parse_row(
    robot: &Robot,
    columns: &[Column],
    row: &str,
    at: &Cursor,
) -> Result<(f64, Vec<f64>), MotionError> {
    // At most one field more than expected is split off: a line of 10⁸ commas is refused
    // without a list of 10⁸ fields.
    let fields: Vec<&str> = row.splitn(columns.len() + 2, ',').map(str::trim).collect();
    if fields.len() != columns.len() + 1 {
        let count = match fields.len() > columns.len() + 1 {
            true => format!("more than {}", columns.len() + 1),
            false => fields.len().to_string(),
        };
        return Err(at.error(format!(
            "{count} values, but the header has {} columns",
            columns.len() + 1
        )));
    }
    let time_s = parse_number(fields[0], 1, "time_s", at)?;
    let mut sample = vec![0.0; robot.dof()];
    for (i, (column, field)) in columns.iter().zip(&fields[1..]).enumerate() {
        let value = parse_number(field, i + 2, &column.header, at)?;
        check_limit(robot, column, value, i + 2, at)?;
        sample[column.joint] = column.unit.to_si(value);
    }
    robot
        .check_limits(&sample)
        .map_err(|e| at.error(e.to_string()))?;
    Ok((time_s, sample))
}

/// A finite number, or an error naming the column.
fn parse_number(field: &str, number: usize, header: &str, at: &Cursor) -> Result<f64, MotionError> {
    let field_shown = clipped(field);
    match field.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        Ok(_) => Err(at.error(format!(
            "column {number} ({header}): `{field_shown}` is not a finite number"
        ))),
        Err(_) => Err(at.error(format!(
            "column {number} ({header}): `{field_shown}` is not a number"
        ))),
    }
}

/// The joint's URDF limits, stated in the column's unit when violated.
fn check_limit(
    robot: &Robot,
    column: &Column,
    value: f64,
    number: usize,
    at: &Cursor,
) -> Result<(), MotionError> {
    let joint = robot.actuated_joint(column.joint);
    let Some(limits) = joint.limits else {
        return Ok(());
    };
    let si = column.unit.to_si(value);
    if si >= limits.lower - LIMIT_TOLERANCE && si <= limits.upper + LIMIT_TOLERANCE {
        return Ok(());
    }
    let show = |v: f64| (column.unit.in_unit(v) * 1e9).round() / 1e9 + 0.0;
    Err(at.error(format!(
        "column {number} ({}): {value} {unit} is outside the limits of `{}`, [{}, {}] {unit}",
        column.header,
        joint.name,
        show(limits.lower),
        show(limits.upper),
        unit = column.unit.suffix(),
    )))
}
