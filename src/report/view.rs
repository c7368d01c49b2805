//! The report page's interactive 3D view: the files that make it (the vendored
//! `@google/model-viewer` web component with its licences, our `view.js`, and `view-data.js`
//! holding the scene and the clamp labels' tracks) and the page markup that hosts it.
//!
//! The scene is the report's main scene without the critical-pose copies: the robot and the
//! cable at the motion's start, animated over the motion test. A page opened from `file://`
//! may not read its neighbours, so the `.glb` travels as base64 inside `view-data.js`, a
//! plain script; everything else is in the folder, nothing is fetched from a network.

use super::error::ReportError;
use super::scene::{
    COLOUR_VARIANTS, CableTint, ClampPart, DamageLevel, GuideMark, INSTALLATION_ANIMATION,
    SceneAnimation, SceneSpec, to_glb,
};
use super::views::{TIGHT_SHARE, other_motion_animation};
use super::worst::{limit_words, smallest_margin};
use crate::escape::html as escape;
use crate::motion_test::MotionTestReport;
use crate::mounting::mounting_plan;
use crate::pose::Pose;
use crate::setup::Setup;
use crate::solve::{MotionVerdict, SolveReport};
use base64::Engine as _;
use nalgebra::Point3;
use serde::Serialize;
use std::borrow::Cow;

/// `@google/model-viewer` 4.4.0, `dist/model-viewer-umd.min.js` from npm (a classic script:
/// module scripts do not load from `file://`).
const MODEL_VIEWER_JS: &[u8] = include_bytes!("../../assets/viewer/model-viewer.min.js");
/// Its licence and those of the libraries it bundles (three.js, lit).
const MODEL_VIEWER_LICENSES: &[u8] = include_bytes!("../../assets/viewer/LICENSES.txt");
/// The controls: play, pause, the time slider, the worst moment, the clamp labels.
const VIEW_JS: &[u8] = include_bytes!("../../assets/viewer/view.js");

/// One file of the view: name, what it is (for the summary's file list) and bytes.
pub struct ViewFile {
    /// File name in the report folder.
    pub name: &'static str,
    /// What it is.
    pub what: &'static str,
    /// Its content (the vendored files borrowed, not copied).
    pub bytes: Cow<'static, [u8]>,
}

/// What `view.js` reads from `view-data.js` (`window.cableDictView`).
#[derive(Serialize)]
struct ViewData {
    /// The scene, a `.glb` in base64.
    glb_base64: String,
    /// The name of the one-keyframe animation holding the installation pose; `None` when
    /// the scene has none.
    installation: Option<&'static str>,
    /// One label per physical clamp.
    clamps: Vec<ClampLabel>,
    /// The motion tests the view plays, the one the report shows first; a cell's other
    /// motions after it, in the cell's order (the page offers a choice when there are
    /// several).
    clips: Vec<Clip>,
}

/// A clamp label, and where it is at the installation pose.
#[derive(Serialize)]
struct ClampLabel {
    /// `G2 = G3`, `G4 (gripper connector)`.
    label: String,
    /// Its position at the installation pose (glTF frame, m, y up); `None` without one.
    installation_m: Option<[f64; 3]>,
}

/// One motion test as the view plays it.
#[derive(Serialize)]
struct Clip {
    /// The motion's name and verdict, for the choice (`pick_and_place: holds`).
    label: String,
    /// The animation's name; `None` when there is nothing to animate.
    animation: Option<String>,
    /// Keyframe times (s from the start of the animation); one 0 without animation.
    times_s: Vec<f64>,
    /// Per clamp label, its position at each keyframe (glTF frame, m, y up).
    positions_m: Vec<Vec<[f64; 3]>>,
    /// The moment to jump to; `None` without a motion test.
    worst: Option<WorstMoment>,
    /// When the motion ends (s from the animation's start): the test runs on, the motion's
    /// last pose held, so that the cable settles.
    motion_end_s: Option<f64>,
}

/// The worst moment of the motion test.
#[derive(Serialize)]
struct WorstMoment {
    /// Time from the animation's start (s).
    time_s: f64,
    /// For people: `smallest margin: bend radius 63.6 mm (limit 48.0 mm) on piece 1 → 2 at
    /// t = 4.91 s`, or what failed.
    what: String,
    /// Where on the cable (glTF frame, m, y up), for the camera and the red ring; `None` when
    /// the place is not known.
    spot_m: Option<[f64; 3]>,
    /// The camera's orbit to look at the spot from outside the arm: azimuth and polar angle
    /// (deg, model-viewer's), distance (m).
    orbit: Option<[f64; 3]>,
}

/// The view's files for the scene `spec` of `report` (solved with `setup`).
pub fn view_files(
    setup: &Setup,
    report: &SolveReport,
    spec: &SceneSpec<'_>,
) -> Result<Vec<ViewFile>, ReportError> {
    let mut main_only = spec.clone();
    main_only.snapshots.clear();
    let glb = to_glb(&main_only).map_err(|e| ReportError::Scene(e.to_string()))?;
    let marks = clamp_marks(setup, report, spec);
    let shown = report.motions.get(report.shown_motion);
    let mut clips = vec![clip(
        setup,
        report,
        spec,
        &marks,
        spec.animation.as_ref(),
        shown,
        report.motion_test.as_ref(),
    )];
    for animation in &spec.other_motions {
        let verdict =
            (report.motions.iter()).find(|m| other_motion_animation(&m.name) == animation.name);
        let test = verdict.and_then(|m| m.motion_test.as_ref());
        clips.push(clip(
            setup,
            report,
            spec,
            &marks,
            Some(animation),
            verdict,
            test,
        ));
    }
    let data = ViewData {
        glb_base64: base64::engine::general_purpose::STANDARD.encode(glb),
        installation: spec.installation.as_ref().map(|_| INSTALLATION_ANIMATION),
        clamps: (marks.iter())
            .map(|(label, mark)| ClampLabel {
                // Shown as text by the page: what would reorder or hide text written out.
                label: crate::escape::terminal(label).into_owned(),
                installation_m: spec
                    .installation
                    .as_ref()
                    .map(|i| gltf_point(&i.link_poses, mark)),
            })
            .collect(),
        clips,
    };
    let script = format!(
        "// The 3D view's scene and clamp labels, written by cable-dict; read by view.js.\n\
         window.cableDictView = {};\n",
        serde_json::to_string(&data)?
    );
    Ok(vec![
        ViewFile {
            name: "model-viewer.min.js",
            what: "the 3D view's web component (@google/model-viewer 4.4.0, Apache-2.0)",
            bytes: Cow::Borrowed(MODEL_VIEWER_JS),
        },
        ViewFile {
            name: "model-viewer-licenses.txt",
            what: "the licences of model-viewer and the libraries it bundles",
            bytes: Cow::Borrowed(MODEL_VIEWER_LICENSES),
        },
        ViewFile {
            name: "view.js",
            what: "the 3D view's controls",
            bytes: Cow::Borrowed(VIEW_JS),
        },
        ViewFile {
            name: "view-data.js",
            what: "the 3D view's scene and clamp labels",
            bytes: Cow::Owned(script.into_bytes()),
        },
    ])
}

/// One motion test as the view plays it: `animation` (none: the still main scene), the
/// motion's verdict and its `test`.
fn clip(
    setup: &Setup,
    report: &SolveReport,
    spec: &SceneSpec<'_>,
    marks: &[(String, &GuideMark)],
    animation: Option<&SceneAnimation>,
    verdict: Option<&MotionVerdict>,
    test: Option<&MotionTestReport>,
) -> Clip {
    let frames: Vec<&[Pose]> = match animation {
        Some(animation) => (animation.frames.iter())
            .map(|f| f.link_poses.as_slice())
            .collect(),
        None => vec![spec.main.link_poses.as_slice()],
    };
    Clip {
        label: verdict.map_or_else(String::new, |m| {
            format!("{}: {}", m.name, m.verdict().replace('_', " "))
        }),
        animation: animation.map(|a| a.name.clone()),
        times_s: animation.map_or_else(|| vec![0.0], |a| a.times_s.clone()),
        positions_m: (marks.iter())
            .map(|(_, mark)| frames.iter().map(|poses| gltf_point(poses, mark)).collect())
            .collect(),
        worst: test.and_then(|test| worst_moment(setup, report, test)),
        // The animation starts at the motion's start.
        motion_end_s: test
            .filter(|_| animation.is_some())
            .map(|t| t.motion_duration_s),
    }
}

/// The guide mark of every physical clamp of the shown candidate, labelled as the mounting
/// plan names it (guides joined by a 0 mm piece are one clamp; a fitting carries its name),
/// then of every sliding guide and retraction outlet the cable runs through (`sliding guide
/// S`).
fn clamp_marks<'s>(
    setup: &Setup,
    report: &SolveReport,
    spec: &'s SceneSpec<'_>,
) -> Vec<(String, &'s GuideMark)> {
    let Some(shown) = report.shown_candidate() else {
        return Vec::new();
    };
    let plan = mounting_plan(setup, &shown.path);
    let mark = |guide: &str| spec.guides.iter().find(|m| m.clamp == guide);
    let clamps =
        (plan.clamps.iter()).filter_map(|clamp| Some((clamp.name(), mark(&clamp.guides[0])?)));
    let parts =
        (plan.sliding_parts.iter()).filter_map(|part| Some((part.name(), mark(&part.guide)?)));
    clamps.chain(parts).collect()
}

/// Where `mark` is with the links at `poses`, in the glTF frame: the scene's root turns the
/// robot's z up into glTF's y up.
fn gltf_point(poses: &[Pose], mark: &GuideMark) -> [f64; 3] {
    let p = poses[mark.link] * mark.pose_in_link * Point3::origin();
    [p.x, p.z, -p.y]
}

/// The report's worst moment of the motion test ([`smallest_margin`]), from the
/// animation's start, with where it is and a camera looking at it from outside the arm.
fn worst_moment(
    setup: &Setup,
    report: &SolveReport,
    test: &MotionTestReport,
) -> Option<WorstMoment> {
    let start = test.shapes.first().map_or(0.0, |f| f.time_s);
    let worst = smallest_margin(test, &setup.thresholds, setup.cable.diameter_m)?;
    let verdict = if worst.violated {
        "failed"
    } else {
        "smallest margin"
    };
    let piece = setup.segment_name(worst.segment);
    let plan = report
        .shown_candidate()
        .map(|c| mounting_plan(setup, &c.path));
    let place = plan
        .as_ref()
        .and_then(|plan| plan.place_on_cable(&piece, None))
        .unwrap_or_else(|| format!("on cable piece {piece}"));
    // The scene's root turns the robot's z up into glTF's y up.
    let spot_m = worst.position_m.map(|[x, y, z]| [x, z, -y]);
    Some(WorstMoment {
        time_s: worst.time_s - start,
        what: format!(
            "{verdict}: {} {place} at t = {:.2} s",
            limit_words(worst.constraint, worst.value, worst.limit),
            worst.time_s
        ),
        orbit: spot_m.map(outside_orbit),
        spot_m,
    })
}

/// Distance of the camera from the worst spot (m).
const WORST_CAMERA_M: f64 = 0.9;
/// Polar angle the worst spot is seen at (deg from straight above).
const WORST_POLAR_DEG: f64 = 65.0;

/// A camera orbit around `spot` (glTF frame) that looks at it from outside the arm: from the
/// side away from the robot's base axis (glTF y), a little from above.
fn outside_orbit(spot: [f64; 3]) -> [f64; 3] {
    let [x, _, z] = spot;
    // model-viewer's azimuth θ is measured about +y from +z toward +x.
    let azimuth = if x.hypot(z) > 1e-6 {
        x.atan2(z).to_degrees()
    } else {
        0.0
    };
    [azimuth, WORST_POLAR_DEG, WORST_CAMERA_M]
}

/// The view's markup for the page: the component, its controls, the colours' legend and the
/// scripts.
pub fn view_html() -> String {
    let swatch_of = |css: String, legend: &str| {
        format!(
            "<span class=\"swatch\" style=\"background:{css}\"></span>{}",
            escape(legend)
        )
    };
    let swatch = |tint: CableTint| swatch_of(tint.css(), tint.legend());
    let damage_swatch = |level: DamageLevel| swatch_of(level.css(), level.legend());
    let part_swatch = |part: ClampPart| swatch_of(part.css(), part.legend());
    format!(
        "<section id=\"view-section\">\n<h2>3D view</h2>\n\
<p>Drag to turn, scroll to zoom. The robot's collision shapes, the cable and its numbered clamps \
over the motion test; play it, or drag the slider to any moment (the red tick is the worst one); \
<i>Worst moment</i> turns the camera to it and rings the spot on the cable in red; \
<i>Installation pose</i> shows the robot where the cable is laid untwisted, with its shape there. \
The test runs on after the motion ends, its last pose held, so that the cable comes to rest: the \
time under the slider says where the motion ends. For a cell of several motions, the list before \
the buttons picks the motion played.</p>\n\
<p class=\"view-legend\">{} (closer to the robot or to itself than one cable diameter, or within \
{:.0} % of the bend-radius or stretch limit) {} {} <span class=\"swatch ring\"></span>the worst \
spot. Clamp markers: {} {} {} {} {}</p>\n\
<p class=\"view-legend\" id=\"view-damage-legend\" hidden>Damage per cycle (the predicted life's \
Miner sum per round, along the cable): {} {} {} {}</p>\n\
<model-viewer id=\"view\" camera-controls camera-orbit=\"-40deg 70deg auto\" animation-crossfade-duration=\"0\" loading=\"eager\" interaction-prompt=\"none\" shadow-intensity=\"0\" \
exposure=\"0.6\" alt=\"the robot and the cable in 3D\"></model-viewer>\n\
<div class=\"view-controls\"><select id=\"view-motion\" aria-label=\"motion\" hidden></select>\
<select id=\"view-colour\" aria-label=\"colour the cable by\" hidden><option value=\"{}\">colour: margins</option>\
<option value=\"{}\">colour: damage per cycle</option></select>\
<button id=\"view-install\" type=\"button\">Installation pose</button>\
<button id=\"view-play\" type=\"button\">Play</button>\
<span class=\"view-track\"><input id=\"view-time\" type=\"range\" min=\"0\" max=\"0\" value=\"0\" \
aria-label=\"time\"><span id=\"view-worst-tick\"></span></span>\
<span id=\"view-readout\"></span></div>\n\
<p><button id=\"view-worst\" type=\"button\"></button></p>\n\
<script src=\"model-viewer.min.js\"></script>\n<script src=\"view-data.js\"></script>\n\
<script src=\"view.js\"></script>\n</section>\n",
        swatch(CableTint::Tight),
        100.0 * TIGHT_SHARE,
        swatch(CableTint::Ample),
        swatch(CableTint::Exceeded),
        part_swatch(ClampPart::Rigid),
        part_swatch(ClampPart::Rotating),
        part_swatch(ClampPart::Swivel),
        part_swatch(ClampPart::Sliding),
        part_swatch(ClampPart::Retraction),
        damage_swatch(DamageLevel::Worst),
        damage_swatch(DamageLevel::Raised),
        damage_swatch(DamageLevel::Low),
        damage_swatch(DamageLevel::Slight),
        COLOUR_VARIANTS[0],
        COLOUR_VARIANTS[1],
    )
}

/// The view's styling.
pub const VIEW_STYLE: &str = "model-viewer { width: 100%; height: 560px; background: #f4f6f8; }
.view-controls { display: flex; gap: 0.8em; align-items: center; margin: 0.4em 0; }
.view-track { position: relative; flex: 1; }
.view-track input { width: 100%; }
#view-worst-tick { position: absolute; top: -4px; width: 3px; height: 22px; background: #d00000; pointer-events: none; }
#view-install.active { background: #1c4fd8; color: white; }
.clamp-label { background: #1c4fd8; color: white; border-radius: 4px; padding: 1px 5px; font-size: 12px; pointer-events: none; }
.worst-ring { width: 34px; height: 34px; border: 3px solid #d00000; border-radius: 50%; pointer-events: none; }
.worst-ring[hidden] { display: none; }
.view-legend { font-size: 0.9em; }
.swatch { display: inline-block; width: 1.6em; height: 0.7em; margin: 0 0.3em 0 0.8em; vertical-align: middle; border-radius: 2px; }
.swatch.ring { width: 0.9em; height: 0.9em; border: 2px solid #d00000; border-radius: 50%; background: none; }
";
