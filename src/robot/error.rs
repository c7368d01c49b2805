//! Errors of robot loading and of joint vectors.

use std::fmt;
use std::path::PathBuf;

/// A URDF that cannot be used, with the file, the place and the problem.
#[derive(Debug, thiserror::Error)]
#[error("{location}: {problem}")]
pub struct RobotError {
    location: Location,
    problem: String,
}

/// `file`, `file:line` or `file:line: <element name="…">`.
#[derive(Debug)]
struct Location {
    file: PathBuf,
    line: Option<usize>,
    element: Option<String>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(element) = &self.element {
            write!(f, ": {element}")?;
        }
        Ok(())
    }
}

impl RobotError {
    /// A problem with the file as a whole.
    pub(crate) fn file(file: impl Into<PathBuf>, problem: impl Into<String>) -> Self {
        RobotError {
            location: Location {
                file: file.into(),
                line: None,
                element: None,
            },
            problem: problem.into(),
        }
    }

    /// A problem at a known line.
    pub(crate) fn at_line(
        file: impl Into<PathBuf>,
        line: usize,
        problem: impl Into<String>,
    ) -> Self {
        RobotError {
            location: Location {
                file: file.into(),
                line: Some(line),
                element: None,
            },
            problem: problem.into(),
        }
    }

    /// A problem with one named element, located at `line` when it could be found.
    pub(crate) fn element(
        file: impl Into<PathBuf>,
        line: Option<usize>,
        element: String,
        problem: impl Into<String>,
    ) -> Self {
        RobotError {
            location: Location {
                file: file.into(),
                line,
                element: Some(element),
            },
            problem: problem.into(),
        }
    }

    /// The file the error is about.
    pub fn file_path(&self) -> &std::path::Path {
        &self.location.file
    }

    /// The 1-based line of the offending element, when known.
    pub fn line(&self) -> Option<usize> {
        self.location.line
    }
}

/// A joint vector that does not fit the robot.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JointVectorError {
    /// Wrong number of values.
    #[error("expected {expected} joint values ({names}), got {got}")]
    Length {
        /// Number of actuated joints.
        expected: usize,
        /// Number of values given.
        got: usize,
        /// The actuated joint names, comma-separated, in joint-vector order.
        names: String,
    },
    /// NaN or infinite value.
    #[error("joint '{joint}': value {value} is not a finite number")]
    NotFinite {
        /// Joint name.
        joint: String,
        /// The offending value.
        value: f64,
    },
    /// A value (or a mimic joint's derived value) beyond the joint's limits.
    #[error("joint '{joint}': {value} {unit} is outside its limits [{lower}, {upper}] {unit}")]
    OutOfLimits {
        /// Joint name.
        joint: String,
        /// Value in display units (deg for rotary, mm for prismatic joints).
        value: f64,
        /// Lower limit in display units.
        lower: f64,
        /// Upper limit in display units.
        upper: f64,
        /// Degrees or millimetres.
        unit: super::DisplayUnit,
    },
}
