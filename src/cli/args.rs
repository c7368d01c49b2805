//! Parsers for compound command-line values.

use cable_dict::pose::{Pose, pose_from_mm_deg};
use std::path::{Path, PathBuf};

/// A comma-separated list of finite numbers given as one argument.
#[derive(Debug, Clone)]
pub struct NumberList(pub Vec<f64>);

/// Parses `a,b,c,…` as one [`NumberList`] argument.
pub fn number_list_arg(text: &str) -> Result<NumberList, String> {
    number_list(text).map(NumberList)
}

/// Parses `a,b,c,…` into numbers, naming the bad item.
/// A finite number ≥ 0 (a rate, a count per hour).
pub fn non_negative(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        Ok(v) => Err(format!("{v} must be a finite number ≥ 0")),
        Err(e) => Err(format!("`{text}` is not a number: {e}")),
    }
}

pub fn number_list(text: &str) -> Result<Vec<f64>, String> {
    text.split(',')
        .enumerate()
        .map(|(i, item)| {
            let item = item.trim();
            let value: f64 = item
                .parse()
                .map_err(|_| format!("item {} ('{item}') is not a number", i + 1))?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(format!("item {} ('{item}') is not a finite number", i + 1))
            }
        })
        .collect()
}

/// The number of sub-segments of `pitch_m` in `length_mm`, when it is a finite, whole,
/// non-negative number of them (within 1e-6 mm).
pub fn whole_sub_segments(length_mm: f64, pitch_m: f64) -> Option<usize> {
    let pitch_mm = pitch_m * 1e3;
    let count = (length_mm / pitch_mm).round();
    (length_mm.is_finite() && count >= 0.0 && (count * pitch_mm - length_mm).abs() < 1e-6)
        .then_some(count as usize)
}

/// Parses a vector `x,y,z`.
pub fn vector3(text: &str) -> Result<nalgebra::Vector3<f64>, String> {
    let values = number_list(text)?;
    let [x, y, z] = values[..] else {
        return Err(format!(
            "expected 3 comma-separated numbers x,y,z, got {}",
            values.len()
        ));
    };
    Ok(nalgebra::Vector3::new(x, y, z))
}

/// Parses a guide frame `x,y,z,roll,pitch,yaw` (mm, deg; URDF roll–pitch–yaw).
pub fn guide_frame(text: &str) -> Result<Pose, String> {
    let values = number_list(text)?;
    let [x, y, z, roll, pitch, yaw] = values[..] else {
        return Err(format!(
            "expected 6 comma-separated numbers x,y,z,roll,pitch,yaw (mm, deg), got {}",
            values.len()
        ));
    };
    Ok(pose_from_mm_deg([x, y, z], [roll, pitch, yaw]))
}

/// The setup of a command that takes no other file: `cable-dict sites SETUP.toml` or, as
/// `solve` takes it, `cable-dict sites --setup SETUP.toml`.
#[derive(Debug, clap::Args)]
pub struct SetupArg {
    /// The setup file (see docs/setup-format.md); `--setup SETUP.toml` says the same.
    #[arg(value_name = "SETUP.toml", required_unless_present = "setup_option")]
    setup: Option<PathBuf>,
    /// The setup file, as `solve` takes it.
    #[arg(
        long = "setup",
        id = "setup_option",
        value_name = "SETUP.toml",
        conflicts_with = "setup"
    )]
    setup_option: Option<PathBuf>,
}

impl SetupArg {
    /// The setup's path, however it was given.
    pub fn path(&self) -> Result<&Path, String> {
        self.setup
            .as_deref()
            .or(self.setup_option.as_deref())
            .ok_or_else(|| "give the setup file: SETUP.toml or --setup SETUP.toml".into())
    }
}

/// The setup and the motions of `solve` and `critical-poses`, from `--setup` and the files
/// after the options: `--setup SETUP.toml MOTION.csv…` or `SETUP.toml MOTION.csv…`, a motion
/// being a motion CSV or a cell file. `dictionary` says whether the command takes `--dict`
/// and whether it was given (a dictionary embeds a setup: then the motions alone will do,
/// the first file taken for the setup only when it is neither a CSV nor a cell file). The
/// errors say what to give.
pub fn setup_and_motions<'a>(
    option: Option<&'a Path>,
    files: &'a [PathBuf],
    dictionary: Option<bool>,
) -> Result<(Option<&'a Path>, &'a [PathBuf]), String> {
    match (option, files) {
        (_, []) => Err("give the motion: MOTION.csv (or a cell file, CELL.toml)".into()),
        (Some(setup), motions) => match motions.iter().find(|m| is_setup_like(m)) {
            Some(file) => Err(format!(
                "{} is a setup, not a motion: give the setup once, as --setup SETUP.toml or as \
                 the first file",
                file.display()
            )),
            None => Ok((Some(setup), motions)),
        },
        (None, [first, rest @ ..])
            if dictionary == Some(true) && (rest.is_empty() || is_motion_file(first)) =>
        {
            Ok((None, files))
        }
        (None, [setup, motions @ ..]) if !motions.is_empty() => Ok((Some(setup), motions)),
        (None, [motion, ..]) => Err(format!(
            "no setup for the motion {}: give it first (SETUP.toml {0}) or as --setup \
             SETUP.toml{}",
            motion.display(),
            match dictionary {
                Some(_) => ", or give a dictionary with --dict",
                None => "",
            }
        )),
    }
}

/// A `.toml` with `[[guides]]`: a setup where a motion belongs.
fn is_setup_like(path: &Path) -> bool {
    cable_dict::input::is_toml_with(path, cable_dict::input::SETUP, "[[guides]]")
}

/// A motion CSV or a cell file (`[[motions]]`), not a setup.
fn is_motion_file(path: &Path) -> bool {
    let csv = path.extension().is_some_and(|e| e == "csv");
    csv || cable_dict::motion::Cell::is_cell_file(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guide_frame_reads_mm_and_degrees() {
        let pose = guide_frame("100, -50, 20, 0, 90, 0").unwrap();
        let z = pose.rotation * nalgebra::Vector3::z();
        assert!((z - nalgebra::Vector3::x()).norm() < 1e-15);
        assert!((pose.translation.vector.x - 0.1).abs() < 1e-15);
    }

    #[test]
    fn bad_lists_name_the_item() {
        assert!(guide_frame("1,2,3").unwrap_err().contains("got 3"));
        assert!(number_list("1,x,3").unwrap_err().contains("item 2"));
        assert!(number_list("1,nan").unwrap_err().contains("finite"));
    }

    #[test]
    fn the_setup_is_taken_as_an_option_or_as_the_first_file() {
        let (setup, motion) = (PathBuf::from("s.toml"), PathBuf::from("m.csv"));
        let both = [setup.clone(), motion.clone()];
        let one = [motion.clone()];
        let given = Ok((Some(setup.as_path()), &one[..]));
        assert_eq!(setup_and_motions(Some(&setup), &one, None), given);
        assert_eq!(setup_and_motions(None, &both, Some(false)), given);
        assert_eq!(setup_and_motions(None, &both, Some(true)), given);
        let embedded = Ok((None, &one[..]));
        assert_eq!(setup_and_motions(None, &one, Some(true)), embedded);
        let two = [motion.clone(), PathBuf::from("n.csv")];
        assert_eq!(
            setup_and_motions(None, &two, Some(true)),
            Ok((None, &two[..]))
        );
        assert_eq!(
            setup_and_motions(Some(&setup), &two, None),
            Ok((Some(setup.as_path()), &two[..]))
        );
        let missing = setup_and_motions(None, &one, Some(false)).unwrap_err();
        assert!(
            missing.contains("--setup") && missing.contains("--dict"),
            "{missing}"
        );
        // A command without --dict does not offer it.
        let missing = setup_and_motions(None, &one, None).unwrap_err();
        assert!(
            missing.contains("--setup") && !missing.contains("--dict"),
            "{missing}"
        );
        assert!(setup_and_motions(Some(&setup), &[], None).is_err());
    }
}
