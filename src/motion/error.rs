//! The one error type of the motion module: where (file, line) and what.

use std::path::{Path, PathBuf};

/// A motion or waypoint file that cannot be used, or motion data that does not fit its robot.
///
/// Displayed as `file:line: problem`; the problem text names the column, joint or waypoint
/// where one is at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{problem}", location(file.as_deref(), *line))]
pub struct MotionError {
    /// The file at fault; `None` for in-memory data.
    pub file: Option<PathBuf>,
    /// 1-based line in that file, when the problem has one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
}

impl MotionError {
    /// A problem at a known line of a file.
    pub(crate) fn at(file: &Path, line: usize, problem: impl Into<String>) -> Self {
        MotionError {
            file: Some(file.to_path_buf()),
            line: Some(line),
            problem: problem.into(),
        }
    }

    /// A problem with a file as a whole.
    pub(crate) fn in_file(file: &Path, problem: impl Into<String>) -> Self {
        MotionError {
            file: Some(file.to_path_buf()),
            line: None,
            problem: problem.into(),
        }
    }

    /// A problem with in-memory data.
    pub(crate) fn data(problem: impl Into<String>) -> Self {
        MotionError {
            file: None,
            line: None,
            problem: problem.into(),
        }
    }

    /// The same problem, located in `file` (at `line` when given) if it had no file yet.
    pub(crate) fn located(mut self, file: &Path, line: Option<usize>) -> Self {
        if self.file.is_none() {
            self.file = Some(file.to_path_buf());
            self.line = line;
        }
        self
    }
}

/// `file:line: `, `file: ` or nothing.
fn location(file: Option<&Path>, line: Option<usize>) -> String {
    match (file, line) {
        (Some(file), Some(line)) => format!("{}:{line}: ", file.display()),
        (Some(file), None) => format!("{}: ", file.display()),
        (None, _) => String::new(),
    }
}
