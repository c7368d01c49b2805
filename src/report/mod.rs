//! The report folder of a solve: what an engineer opens instead of reading JSON.
//!
//! [`write_report`] writes the folder as a whole (built next to it, then renamed into its
//! place: a reader never sees half an old report and half a new one):
//!
//! - `result.json`: the result JSON, as `solve --json` prints it;
//! - `summary.md`: the path, set sizes, margins, motion test, timings, inputs and hashes;
//! - `joints.svg`: the motion's joint angles with the critical poses marked ([`plots`]);
//! - `stress.svg`: the shown candidate's clearance, stretch and bend radius over its motion
//!   test against the limits (when a motion test ran);
//! - `sets.svg`: |D0|, |D'0|, |D1|, |D2| per segment;
//! - `scene.glb`: robot, cable, guides, critical poses and the motion test's animation
//!   ([`scene`], assembled by [`views`]);
//! - `pose-1.svg` …, `worst-moment.svg`, `nearest-miss.svg`: the cable on the robot, front,
//!   side and top, drawn from the same scene ([`pictures`]);
//! - `index.html`: the summary, the pictures and the plots on one page needing nothing but
//!   the folder.

mod error;
mod hashes;
mod install;
mod page;
pub mod pictures;
pub mod plots;
pub mod scene;
mod summary;
pub mod text;
mod view;
pub mod views;
mod worst;

pub use error::ReportError;
pub use hashes::{Hashed, input_hashes};

use crate::atomic_file::FolderReplacement;
use crate::motion::Motion;
use crate::setup::Setup;
use crate::solve::{ReportShapes, SolveReport};
use std::path::{Path, PathBuf};

/// Writes the report folder `dir` of `report`, which solved `motions` (one per
/// `report.motions`, in order: its 3D view animates each motion test) with `setup` as
/// solved ([`Solution::setup`](crate::solve::Solution::setup)), drawing the cable in the
/// `shapes` solved for it ([`ReportShapes::of`]): created, or replaced as a whole when it
/// holds only what a report writes ([`is_report_file`]). Returns the files written,
/// `index.html` last.
pub fn write_report(
    dir: &Path,
    setup: &Setup,
    motions: &[&Motion],
    report: &SolveReport,
    shapes: &ReportShapes,
) -> Result<Vec<PathBuf>, ReportError> {
    if motions.len() != report.motions.len().max(1) {
        return Err(ReportError::Scene(format!(
            "{} motions given for a report of {}",
            motions.len(),
            report.motions.len()
        )));
    }
    let motion = motions[report.shown_motion.min(motions.len() - 1)];
    let write_error = |error| ReportError::Write {
        path: dir.to_path_buf(),
        error,
    };
    let staging = FolderReplacement::begin(dir, is_report_file).map_err(write_error)?;
    let mut folder = Folder {
        dir,
        staging: staging.path(),
        written: Vec::new(),
        described: Vec::new(),
    };
    let json = crate::json::to_pretty_string(report)? + "\n";
    folder.put(
        "result.json",
        "the result JSON (as `solve --json`)",
        json.as_bytes(),
    )?;
    let plots = write_plots(&mut folder, setup, motion, report)?;
    let (spec, problems) = views::solve_scene(setup, motions, report, shapes)
        .map_err(|e| ReportError::Scene(e.to_string()))?;
    let notes = write_scene(&mut folder, &spec, problems)?;
    for file in view::view_files(setup, report, &spec)? {
        folder.put(file.name, file.what, &file.bytes)?;
    }
    let pictures = pictures::pictures(setup, report, &spec);
    for picture in &pictures {
        folder.put(&picture.file, &picture.what, picture.svg.as_bytes())?;
    }
    let dials = (report.allowed_ranges.as_ref()).and_then(pictures::dials_svg);
    if let Some(dials) = &dials {
        folder.put(
            "allowed-ranges.svg",
            "a dial per axis: its limits, the range the cable allows it, the range asked within",
            dials.as_bytes(),
        )?;
    }
    if let Some(plan) = &report.mounting {
        let picture = pictures::installation_picture(setup, report, &spec);
        if let Some(picture) = &picture {
            folder.put(&picture.file, &picture.what, picture.svg.as_bytes())?;
        }
        let sheet = install::Sheet {
            plan,
            title: title_block(setup, report),
            picture: picture.as_ref(),
            allowed: (report.allowed_ranges.as_ref()).filter(|_| dials.is_some()),
            loads: report
                .motion_test
                .as_ref()
                .map(|test| text::load_rows(test, Some(plan)))
                .unwrap_or_default(),
        };
        folder.put(
            "install.svg",
            "the installation sheet's strip: the cable laid out straight with each clamp's mark",
            install::install_svg(plan, &scene::CableTint::Plain.css()).as_bytes(),
        )?;
        folder.put(
            "install.html",
            "the installation sheet, one printed A4 landscape page: every clamp's place and mark",
            install::install_html(&sheet).as_bytes(),
        )?;
    }
    let described: Vec<(&str, &str)> = folder
        .described
        .iter()
        .map(|(file, what)| (file.as_str(), what.as_str()))
        .collect();
    let summary =
        summary::summary_markdown(report, &input_hashes(setup, report), &described, &notes);
    folder.put("summary.md", "this summary as Markdown", summary.as_bytes())?;
    let title = format!("cable-dict: {}", report.status.describe());
    let sections = [
        page::Section {
            heading: "The cable on the robot",
            intro: PICTURES_INTRO,
            figures: pictures
                .iter()
                .map(|p| (p.file.as_str(), p.caption.as_str()))
                .collect(),
        },
        page::Section {
            heading: "Installation sheet",
            intro: "Where each clamp grips the cable; the printable sheet, one A4 page with \
                    the arm at the installation pose and every clamp's place, is install.html \
                    in this folder.",
            figures: report
                .mounting
                .as_ref()
                .map(|_| {
                    vec![(
                        "install.svg",
                        "Each clamp's mark: cable length from the end at the tool",
                    )]
                })
                .unwrap_or_default(),
        },
        page::Section {
            heading: "Allowed ranges",
            intro: "How far each axis may turn with the others anywhere in the box named in the \
                    summary before a piece of the cable breaks a limit: jog each axis to its \
                    ends as the last check of the mounting.",
            figures: match dials {
                Some(_) => vec![("allowed-ranges.svg", "The range each axis allows")],
                None => Vec::new(),
            },
        },
        page::Section {
            heading: "Plots",
            intro: "",
            figures: plots,
        },
    ];
    let page = page::index_html(&title, &summary, &sections, &view::view_html());
    folder.put("index.html", "this page", page.as_bytes())?;
    let written = folder.written;
    staging.commit().map_err(write_error)?;
    Ok(written)
}

/// What ties the installation sheet to its job: robot, cable, motion, setup, its hash, the
/// date.
fn title_block(setup: &Setup, report: &SolveReport) -> install::TitleBlock {
    let cable = &setup.cable;
    install::TitleBlock {
        robot: format!("{} ({})", setup.robot.name, setup.robot_path.display()),
        cable: match &cable.part_number {
            Some(part) => format!("{}, part number {part}", cable.name),
            None => cable.name.clone(),
        },
        motion: report.shown_motion_file().unwrap_or("(none)").to_string(),
        setup: report.inputs.setup_file.clone(),
        setup_hash: report.inputs.setup_hash.clone(),
        date: sheet_date(),
    }
}

/// The date the sheet is made, `YYYY-MM-DD` (UTC): from `SOURCE_DATE_EPOCH` (seconds) when
/// it is set, so that a report can be made again byte for byte, else today.
fn sheet_date() -> String {
    let seconds = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|v| v.trim().parse::<i64>().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs() as i64)
        });
    let (year, month, day) = civil_date(seconds.div_euclid(86_400));
    format!("{year:04}-{month:02}-{day:02}")
}

/// The proleptic Gregorian date of `days` since 1970-01-01 (H. Hinnant's `civil_from_days`).
fn civil_date(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

/// `Ok` when [`write_report`] will be able to put its folder at `dir` (checked before a
/// solve, so that a typo does not cost the whole run).
pub fn check_report_folder(dir: &Path) -> Result<(), ReportError> {
    FolderReplacement::check(dir, is_report_file).map_err(|error| ReportError::Write {
        path: dir.to_path_buf(),
        error,
    })
}

/// The files a report folder may hold (what [`write_report`] writes, by extension): an
/// existing folder holding anything else is not replaced.
pub fn is_report_file(name: &str) -> bool {
    [".json", ".md", ".html", ".svg", ".glb", ".js", ".txt"]
        .iter()
        .any(|extension| name.ends_with(extension))
}

/// The folder being written, and what is in it so far.
struct Folder<'a> {
    /// Where the folder will be.
    dir: &'a Path,
    /// Where it is written.
    staging: &'a Path,
    written: Vec<PathBuf>,
    /// `(file, what it shows)` for the summary's list.
    described: Vec<(String, String)>,
}

impl Folder<'_> {
    fn put(&mut self, file: &str, what: &str, bytes: &[u8]) -> Result<(), ReportError> {
        std::fs::write(self.staging.join(file), bytes).map_err(|error| ReportError::Write {
            path: self.dir.join(file),
            error,
        })?;
        self.written.push(self.dir.join(file));
        self.described.push((file.into(), what.into()));
        Ok(())
    }
}

/// What the pictures on the page are, said once above them.
const PICTURES_INTRO: &str = "The robot's collision shapes (grey), the cable (orange) and its \
     clamps (blue), seen from the front, the side and the top, at one scale in the robot's \
     base frame (mm): the shapes the physics checks, at each pose the path was tested at.";

/// The three plots; returns `(file, caption)` of each for the page.
fn write_plots(
    folder: &mut Folder<'_>,
    setup: &Setup,
    motion: &Motion,
    report: &SolveReport,
) -> Result<Vec<(&'static str, &'static str)>, ReportError> {
    let plot = |file: &'static str| move |source| ReportError::Plot { file, source };
    let mut figures = Vec::new();
    let mut add = |folder: &mut Folder<'_>, file, caption, svg: String| {
        figures.push((file, caption));
        folder.put(file, caption, svg.as_bytes())
    };
    let motion_name = report.shown_motion_file().unwrap_or("the motion");
    let title = format!("Joint angles of {motion_name} and the critical poses");
    // The critical poses of the motion drawn (a cell's others are other motions' samples).
    let mut segments = report.segments.clone();
    for segment in &mut segments {
        segment
            .test_poses
            .retain(|p| p.motion == report.shown_motion);
    }
    let svg = plots::joints_svg(motion, &segments, &title).map_err(plot("joints.svg"))?;
    add(
        folder,
        "joints.svg",
        "joint angles over the motion, critical poses marked",
        svg,
    )?;
    if let Some(test) = report.motion_test.as_ref().filter(|t| !t.series.is_empty()) {
        let title = stress_title(report);
        let names = plot_names(setup, report, test);
        let svg = plots::stress_svg(test, &setup.thresholds, &title, &names)
            .map_err(plot("stress.svg"))?;
        add(
            folder,
            "stress.svg",
            "clearance, stretch and bend radius over the motion test",
            svg,
        )?;
    }
    if let (Some(life), Some(test)) = (&report.life, &report.motion_test) {
        let names = plot_names(setup, report, test);
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let title = "Damage per cycle along the cable";
        let svg = plots::life_svg(life, pitch_mm, title, &names).map_err(plot("life.svg"))?;
        add(
            folder,
            "life.svg",
            "damage one cycle of the motion does along the cable, and where it fails first",
            svg,
        )?;
    }
    if !report.segments.is_empty() {
        let svg =
            plots::sets_svg(&report.segments, "Set sizes per segment").map_err(plot("sets.svg"))?;
        add(
            folder,
            "sets.svg",
            "cable pieces per segment: candidates, after pruning, holding the limits, robust",
            svg,
        )?;
    }
    Ok(figures)
}

/// The fitter's names of the shown candidate's pieces and clamps, for the motion test's plot.
fn plot_names(
    setup: &Setup,
    report: &SolveReport,
    test: &crate::motion_test::MotionTestReport,
) -> plots::PlotNames {
    let Some(plan) = report
        .shown_candidate()
        .map(|c| crate::mounting::mounting_plan(setup, &c.path))
    else {
        return plots::PlotNames::default();
    };
    let pieces = (0..setup.segments.len())
        .map(|m| setup.segment_name(m))
        .filter_map(|name| {
            let words = plan.place_on_cable(&name, None)?;
            let words = words.trim_start_matches("on ").trim_start_matches("at ");
            Some((name, words.to_string()))
        })
        .collect();
    let clamps = plan
        .clamps
        .iter()
        .flat_map(|c| c.guides.iter().map(move |g| (g.clone(), c.name())))
        .collect();
    let failure = test
        .failure
        .as_ref()
        .map(|_| text::verdict_words(&report.limits(), test, Some(&plan)));
    plots::PlotNames {
        pieces,
        clamps,
        failure: failure.map(|f| f.trim_start_matches("failed: ").to_string()),
    }
}

/// `Motion test of d* (1380 mm)` or `Motion test of candidate 3 (1420 mm), which failed`.
fn stress_title(report: &SolveReport) -> String {
    match report.shown_candidate() {
        Some(c) if c.passed == Some(true) => {
            format!(
                "Motion test of the path that passed it ({:.0} mm)",
                c.total_length_mm
            )
        }
        Some(c) => format!(
            "Motion test of candidate {} ({:.0} mm), which failed",
            c.rank, c.total_length_mm
        ),
        None => "Motion test".into(),
    }
}

/// `scene.glb` of `spec`; returns the notes for the summary: the `problems` of
/// [`views::solve_scene`] (segments drawn without a cable).
fn write_scene(
    folder: &mut Folder<'_>,
    spec: &scene::SceneSpec<'_>,
    problems: Vec<String>,
) -> Result<Vec<String>, ReportError> {
    let bytes = scene::to_glb(spec).map_err(|e| ReportError::Scene(e.to_string()))?;
    let what = if spec.animation.is_some() {
        "3D scene: robot, cable, guides, critical poses, motion-test animation (glTF 2.0)"
    } else {
        "3D scene: robot, cable, guides, critical poses (glTF 2.0)"
    };
    folder.put("scene.glb", what, &bytes)?;
    Ok(problems
        .into_iter()
        .map(|p| format!("not drawn in the scene (no static equilibrium): {p}"))
        .collect())
}
