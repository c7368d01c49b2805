//! The programs of a robot cell: the motions one installed cable must survive, each with how
//! often it runs.
//!
//! # Cell file (TOML)
//!
//! ```toml
//! description = "Viper cell 3: every program"   # optional
//!
//! [[motions]]
//! file = "../motions/viper_s850/pick_and_place.csv"   # a motion CSV, relative to this file
//! name = "pick and place"                              # optional, default: the file's stem
//! cycles_per_hour = 240                                # optional, ≥ 0
//! ```
//!
//! Unknown keys are refused; names must be distinct; at most [`MAX_CELL_MOTIONS`] motions.
//! Every motion is read for the cell's robot ([`Motion::from_csv_file`]): errors name the
//! motion file, line and column as for a single motion.

use super::{Motion, MotionError, RangeGrid};
use crate::input::line_of;
use crate::robot::Robot;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The most motions one cell may name: every motion of a cell costs a motion test of every
/// chain that passes the ones before it.
pub const MAX_CELL_MOTIONS: usize = 64;

/// One motion of a cell.
#[derive(Debug, Clone)]
pub struct CellMotion {
    /// How people call it (`pick and place`): the cell file's `name`, else the file's stem.
    pub name: String,
    /// The motion CSV it was read from (`None`: built in memory).
    pub file: Option<PathBuf>,
    /// How many times an hour it runs, when stated.
    pub cycles_per_hour: Option<f64>,
    /// The motion.
    pub motion: Motion,
    /// `Some`: not a motion in time but an axis-range box's grid of static poses
    /// ([`JointRanges::grid`](super::JointRanges::grid)), each piece tested at its own;
    /// never simulated.
    pub grid: Option<RangeGrid>,
}

/// The motions one cable must survive, in the order given.
#[derive(Debug, Clone)]
pub struct Cell {
    /// The cell file (`None`: motions given one by one).
    pub source: Option<PathBuf>,
    /// Its `description`, when given.
    pub description: Option<String>,
    /// At least one motion.
    pub motions: Vec<CellMotion>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCell {
    description: Option<String>,
    motions: Spanned<Vec<RawMotion>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    file: String,
    name: Option<String>,
    cycles_per_hour: Option<Spanned<f64>>,
}

impl Cell {
    /// The axis-range grid among the cell's motions (a range design's), if any.
    pub fn grid(&self) -> Option<&RangeGrid> {
        self.motions.iter().find_map(|m| m.grid.as_ref())
    }

    /// Whether `path` reads as a cell file: a `.toml` with a `[[motions]]` table (a setup or
    /// a waypoint file has none).
    pub fn is_cell_file(path: &Path) -> bool {
        crate::input::is_toml_with(path, crate::input::WAYPOINTS, "[[motions]]")
    }

    /// `text` said of motion `i`, as people read it: prefixed with the motion's name
    /// (`palletizing: bend radius …`) when the cell has several motions, as it is otherwise.
    pub fn label(&self, i: usize, text: &str) -> String {
        match (self.len(), self.motions.get(i)) {
            (2.., Some(motion)) => format!("{}: {text}", motion.name),
            _ => text.to_string(),
        }
    }

    /// The cell with `cycles_per_hour` for each motion that states none (unchanged for
    /// `None`).
    pub fn running(mut self, cycles_per_hour: Option<f64>) -> Cell {
        for motion in &mut self.motions {
            motion.cycles_per_hour = motion.cycles_per_hour.or(cycles_per_hour);
        }
        self
    }

    /// A cell of one motion, named after its file (or `motion`).
    pub fn single(motion: Motion, file: Option<&Path>) -> Cell {
        Cell {
            source: None,
            description: None,
            motions: vec![CellMotion {
                name: file.map_or("motion".to_string(), stem),
                file: file.map(Path::to_path_buf),
                cycles_per_hour: None,
                motion,
                grid: None,
            }],
        }
    }

    /// The motions read from `files` for `robot`, in order: motion CSVs, and cell files
    /// (`.toml`, their motions in place). Errors name the file at fault.
    pub fn from_files(robot: &Robot, files: &[PathBuf]) -> Result<Cell, MotionError> {
        let mut cell = Cell {
            source: None,
            description: None,
            motions: Vec::new(),
        };
        for file in files {
            let is_cell = file.extension().is_some_and(|e| e == "toml");
            if is_cell {
                let read = Cell::from_file(robot, file)?;
                if files.len() == 1 {
                    return Ok(read);
                }
                cell.motions.extend(read.motions);
            } else {
                let motion = Motion::from_csv_file(robot, file)?;
                cell.motions
                    .extend(Cell::single(motion, Some(file)).motions);
            }
        }
        cell.checked(files.first().map(PathBuf::as_path))
    }

    /// Reads a cell file and every motion it names, for `robot`.
    pub fn from_file(robot: &Robot, path: &Path) -> Result<Cell, MotionError> {
        let text = crate::input::read_text(path, crate::input::WAYPOINTS)
            .map_err(|e| MotionError::in_file(path, e))?;
        let raw: RawCell = toml::from_str(&text).map_err(|e| {
            let waypoints = text
                .lines()
                .any(|l| l.trim_start().starts_with("[[waypoint]]"));
            let problem = match waypoints {
                true => "this is a waypoint file, not a cell file: make its motion CSV with \
                         `cable-dict motion` and give that"
                    .to_string(),
                false => format!(
                    "{} (a cell file names `[[motions]]`, each with `file`)",
                    e.message()
                ),
            };
            MotionError {
                file: Some(path.to_path_buf()),
                line: e.span().map(|s| line_of(&text, s.start)),
                problem,
            }
        })?;
        let at =
            |offset: usize, problem: String| MotionError::at(path, line_of(&text, offset), problem);
        let list = raw.motions.get_ref();
        if list.is_empty() {
            return Err(at(raw.motions.span().start, "no `[[motions]]`".into()));
        }
        if list.len() > MAX_CELL_MOTIONS {
            return Err(at(
                raw.motions.span().start,
                format!("{} motions: at most {MAX_CELL_MOTIONS}", list.len()),
            ));
        }
        let folder = path.parent().unwrap_or(Path::new(""));
        let mut motions = Vec::with_capacity(list.len());
        for raw in list {
            let cycles_per_hour = match &raw.cycles_per_hour {
                Some(c) if !(c.get_ref().is_finite() && *c.get_ref() >= 0.0) => {
                    return Err(at(
                        c.span().start,
                        format!("`cycles_per_hour` = {} must be a number ≥ 0", c.get_ref()),
                    ));
                }
                c => c.as_ref().map(|c| *c.get_ref()),
            };
            let file = folder.join(&raw.file);
            let motion = Motion::from_csv_file(robot, &file)?;
            motions.push(CellMotion {
                name: raw.name.clone().unwrap_or_else(|| stem(&file)),
                file: Some(file),
                cycles_per_hour,
                motion,
                grid: None,
            });
        }
        Cell {
            source: Some(path.to_path_buf()),
            description: raw.description,
            motions,
        }
        .checked(Some(path))
    }

    /// The cell, refused when empty, too large or with two motions of one name.
    fn checked(self, source: Option<&Path>) -> Result<Cell, MotionError> {
        let problem = |p: String| match source {
            Some(file) => MotionError::in_file(file, p),
            None => MotionError::data(p),
        };
        if self.motions.is_empty() {
            return Err(problem("no motion".into()));
        }
        if self.motions.len() > MAX_CELL_MOTIONS {
            return Err(problem(format!(
                "{} motions: at most {MAX_CELL_MOTIONS} in one cell",
                self.motions.len()
            )));
        }
        for (i, a) in self.motions.iter().enumerate() {
            if let Some(b) = self.motions[..i].iter().find(|b| b.name == a.name) {
                return Err(problem(format!(
                    "two motions are called `{}` ({} and {}): give each a `name`",
                    a.name,
                    shown(&b.file),
                    shown(&a.file)
                )));
            }
        }
        Ok(self)
    }

    /// The motions, in order.
    pub fn motions(&self) -> impl ExactSizeIterator<Item = &Motion> {
        self.motions.iter().map(|m| &m.motion)
    }

    /// Number of motions.
    pub fn len(&self) -> usize {
        self.motions.len()
    }

    /// Never true for a checked cell.
    pub fn is_empty(&self) -> bool {
        self.motions.is_empty()
    }
}

/// The stem of `file` (`pick_and_place`), or its whole name.
fn stem(file: &Path) -> String {
    file.file_stem()
        .unwrap_or(file.as_os_str())
        .to_string_lossy()
        .into_owned()
}

fn shown(file: &Option<PathBuf>) -> String {
    file.as_ref()
        .map_or("in memory".into(), |f| f.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::narrow_pick_and_place;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
        path
    }

    #[test]
    fn a_cell_file_reads_its_motions_relative_to_itself_and_refuses_what_is_wrong() {
        let (setup, motion) = narrow_pick_and_place();
        let dir = std::env::temp_dir().join(format!("cable-dict-cell-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("m")).unwrap_or_else(|e| panic!("{e}"));
        write(&dir.join("m"), "a.csv", &motion.to_csv(""));
        let good = write(
            &dir,
            "good.toml",
            "[[motions]]\nfile = \"m/a.csv\"\ncycles_per_hour = 120\n\n\
             [[motions]]\nfile = \"m/a.csv\"\nname = \"again\"\n",
        );
        let cell = Cell::from_file(&setup.robot, &good).unwrap_or_else(|e| panic!("{e}"));
        let names: Vec<&str> = cell.motions.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["a", "again"]);
        assert_eq!(cell.motions[0].cycles_per_hour, Some(120.0));
        assert_eq!(cell.motions[1].motion.times_s(), motion.times_s());

        let cases = [
            (
                "[[motions]]\nfile = \"m/a.csv\"\n[[motions]]\nfile = \"m/a.csv\"\n",
                "two motions are called `a`",
            ),
            (
                "[[motions]]\nfile = \"m/a.csv\"\ncycles_per_hour = -1\n",
                ".toml:3: `cycles_per_hour` = -1 must be",
            ),
            (
                "[[motions]]\nfile = \"m/a.csv\"\nspeed = 1\n",
                "unknown field `speed`",
            ),
            ("motions = []\n", "no `[[motions]]`"),
            ("[[motions]]\nfile = \"m/missing.csv\"\n", "missing.csv"),
            (
                "robot = \"r.urdf\"\n[[waypoint]]\njoints_deg = [0]\n",
                "waypoint file",
            ),
        ];
        for (i, (text, expected)) in cases.iter().enumerate() {
            let bad = write(&dir, &format!("bad{i}.toml"), text);
            let error = Cell::from_file(&setup.robot, &bad)
                .expect_err(text)
                .to_string();
            assert!(error.contains(expected), "{text}: {error}");
            assert!(
                error.contains(&format!("bad{i}.toml")) || error.contains("missing.csv"),
                "{error}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
