//! Reading a setup file: parse, load the robot and the cable, validate, assemble.

use super::error::{Source, newline_offsets};
use super::raw::{BendRadiusSetting, RawRobustness, RawSetup, RawThresholds};
use super::sites::SiteContext;
use super::{
    BendRadiusSource, Installation, MAX_SUB_SEGMENTS, PendantAngle, Robustness, Setup, SetupError,
    Thresholds, bodies, coincide, guides, hash, segments,
};
use crate::cable::CableSpec;
use crate::input::{self, FileKind};
use crate::robot::{MeshFile, Robot};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use toml::Spanned;

pub(super) fn from_file(path: &Path) -> Result<Setup, SetupError> {
    let text = input::read_text(path, input::SETUP).map_err(|problem| SetupError {
        file: path.to_path_buf(),
        line: None,
        key: None,
        problem,
    })?;
    from_str(&text, path, None)
}

/// Loads a setup from its text; `given` holds the URDF and cable texts and the mesh files
/// when they are not to be read from the files the setup names.
pub(super) fn from_str(
    text: &str,
    path: &Path,
    given: Option<(&str, &str, &[MeshFile])>,
) -> Result<Setup, SetupError> {
    let newlines = newline_offsets(text);
    let src = Source {
        file: path,
        text,
        newlines: &newlines,
    };
    let raw: RawSetup = toml::from_str(text).map_err(|e| src.toml_error(&e))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let given_robot = given.map(|(urdf, _, meshes)| (urdf, meshes));
    let (robot_path, robot_text, mut robot) = load_robot(src, folder, &raw.robot, given_robot)?;
    if let Some(bodies) = &raw.bodies {
        bodies::attach(src, &mut robot, bodies, folder, given.map(|g| g.2))?;
    }
    let (cable_path, cable_text, cable) = load_cable(src, folder, &raw.cable, given.map(|g| g.1))?;
    let gravity_m_s2 = gravity(src, &raw.gravity_m_s2)?;
    let max_guides_per_link = at_least_one(src, &raw.max_guides_per_link, "max_guides_per_link")?;
    let thresholds = thresholds(src, &raw.thresholds, &cable)?;
    let robustness = robustness(src, &raw.robustness)?;
    let installation = match &raw.install_joints_deg {
        Some(joints) => Some(installation(src, &robot, joints)?),
        None => None,
    };
    let sites = SiteContext::new(0.5 * cable.diameter_m, installation.as_ref());
    let mut guides = guides::build(src, &robot, &raw.guides, max_guides_per_link, &sites)?;
    let delta_pitch = (robustness.delta_s, cable.sub_segment_pitch_m);
    let mut segments = segments::build(src, &guides, &raw.segments, delta_pitch)?;
    guides::warn_buried_clamps(src, &robot, &guides, &sites);
    coincide::add_copies(&mut guides, &segments);
    guides::expand_kinds(&mut guides);
    let declared_segments = segments.len();
    segments.extend(segments::spans(
        src,
        &guides,
        raw.guides.get_ref(),
        &segments,
    )?);
    let pendant_angles = pendant_angles(src, &robot, raw.pendant_angles.as_ref())?;
    let mut setup = Setup {
        source: path.to_path_buf(),
        text: text.to_string(),
        robot,
        robot_path,
        robot_text,
        cable,
        cable_path,
        cable_text,
        gravity_m_s2,
        max_guides_per_link,
        guides,
        segments,
        declared_segments,
        thresholds,
        robustness,
        installation,
        pendant_angles,
        content_hash: 0,
    };
    setup.content_hash = hash::fnv1a64(&hash::canonical_bytes(&setup));
    Ok(setup)
}

/// Reads (unless `given`) the URDF named by `robot`, relative to the setup file's folder.
fn load_robot(
    src: Source,
    folder: &Path,
    robot: &Spanned<String>,
    given: Option<(&str, &[MeshFile])>,
) -> Result<(PathBuf, String, Robot), SetupError> {
    let path = folder.join(robot.get_ref());
    let fail = |problem: String| src.error(robot.span(), "robot", problem);
    let text = read_or_given(&path, given.map(|g| g.0), input::URDF)
        .map_err(|e| fail(format!("{}: {e}", path.display())))?;
    let model = match given {
        Some((_, meshes)) => Robot::from_urdf_str_with_meshes(&text, &path, meshes),
        None => Robot::from_urdf_str(&text, &path),
    }
    .map_err(|e| fail(format!("cannot load the robot: {e}")))?;
    Ok((path, text, model))
}

/// Reads (unless `given`) the cable file named by `cable`, relative to the setup file's
/// folder.
fn load_cable(
    src: Source,
    folder: &Path,
    cable: &Spanned<String>,
    given: Option<&str>,
) -> Result<(PathBuf, String, CableSpec), SetupError> {
    let path = folder.join(cable.get_ref());
    let fail = |problem: String| src.error(cable.span(), "cable", problem);
    let text = read_or_given(&path, given, input::CABLE)
        .map_err(|e| fail(format!("{}: {e}", path.display())))?;
    let spec = CableSpec::from_toml_str(&text, &path)
        .map_err(|e| fail(format!("cannot load the cable: {e}")))?;
    spec.log_plausibility_warnings(&path);
    Ok((path, text, spec))
}

fn read_or_given(path: &Path, given: Option<&str>, kind: FileKind) -> Result<String, String> {
    match given {
        Some(text) => Ok(text.to_string()),
        None => input::read_text(path, kind),
    }
}

/// `[pendant_angles]`: per named rotary joint, `sign` (±1) and `offset_deg` (finite, within
/// ±360°), in the joint vector's order.
fn pendant_angles(
    src: Source,
    robot: &Robot,
    raw: Option<&Spanned<std::collections::BTreeMap<String, Spanned<super::raw::RawPendant>>>>,
) -> Result<Vec<PendantAngle>, SetupError> {
    let Some(raw) = raw else {
        return Ok(Vec::new());
    };
    let mut angles = Vec::new();
    for (name, entry) in raw.get_ref() {
        let key = format!("pendant_angles.{name}");
        let joint = robot
            .actuated_index(name)
            .filter(|&i| robot.actuated_joint(i).kind.is_rotary())
            .ok_or_else(|| {
                let rotary: Vec<&str> = (0..robot.dof())
                    .map(|i| robot.actuated_joint(i))
                    .filter(|j| j.kind.is_rotary())
                    .map(|j| j.name.as_str())
                    .collect();
                src.error(
                    entry.span(),
                    key.clone(),
                    format!(
                        "the robot has no rotary joint called \"{name}\" (rotary joints: {})",
                        rotary.join(", ")
                    ),
                )
            })?;
        let entry = entry.get_ref();
        let sign = *entry.sign.get_ref();
        if sign != 1.0 && sign != -1.0 {
            return Err(src.error(
                entry.sign.span(),
                format!("{key}.sign"),
                format!("{sign} is neither 1 nor -1"),
            ));
        }
        let offset = *entry.offset_deg.get_ref();
        if !offset.is_finite() || offset.abs() > 360.0 {
            return Err(src.error(
                entry.offset_deg.span(),
                format!("{key}.offset_deg"),
                format!("{offset} is not an angle within ±360°"),
            ));
        }
        angles.push(PendantAngle {
            joint,
            sign,
            offset_deg: offset,
        });
    }
    angles.sort_by_key(|a| a.joint);
    Ok(angles)
}

/// `install_joints_deg`: a joint vector in degrees (millimetres for prismatic joints) within
/// the limits, and the link poses there.
fn installation(
    src: Source,
    robot: &Robot,
    value: &Spanned<Vec<f64>>,
) -> Result<Installation, SetupError> {
    let fail = |problem: String| src.error(value.span(), "install_joints_deg", problem);
    let written = value.get_ref();
    if written.len() != robot.dof() {
        return Err(fail(format!(
            "{} values, but the robot has {} actuated joints",
            written.len(),
            robot.dof()
        )));
    }
    let joints: Vec<f64> = written
        .iter()
        .enumerate()
        .map(|(i, v)| v / robot.actuated_joint(i).kind.display_unit().0)
        .collect();
    robot
        .check_limits(&joints)
        .map_err(|e| fail(e.to_string()))?;
    let link_poses = robot.link_poses(&joints).map_err(|e| fail(e.to_string()))?;
    Ok(Installation { joints, link_poses })
}

fn gravity(src: Source, value: &Spanned<[f64; 3]>) -> Result<Vector3<f64>, SetupError> {
    let g = Vector3::from(src.finite3(value, "gravity_m_s2")?);
    if g.norm() > 0.0 {
        Ok(g)
    } else {
        Err(src.error(
            value.span(),
            "gravity_m_s2",
            "gravity must not be zero: the cable's sag and the dictionary's directions need it",
        ))
    }
}

fn at_least_one(src: Source, value: &Spanned<usize>, key: &str) -> Result<usize, SetupError> {
    match *value.get_ref() {
        0 => Err(src.error(value.span(), key, "must be at least 1")),
        v => Ok(v),
    }
}

/// A finite number ≥ `lowest`, or an error naming `key`.
fn finite_at_least(
    src: Source,
    value: &Spanned<f64>,
    key: &str,
    lowest: f64,
) -> Result<f64, SetupError> {
    let v = *value.get_ref();
    if v.is_finite() && v >= lowest {
        Ok(v)
    } else {
        Err(src.error(
            value.span(),
            key,
            format!("{v} must be a finite number ≥ {lowest}"),
        ))
    }
}

fn thresholds(
    src: Source,
    raw: &RawThresholds,
    cable: &CableSpec,
) -> Result<Thresholds, SetupError> {
    let clearance = finite_at_least(
        src,
        &raw.contact_clearance_mm,
        "thresholds.contact_clearance_mm",
        0.0,
    )?;
    let stretch = finite_at_least(src, &raw.stretch, "thresholds.stretch", 1.0)?;
    let clamp_zone = finite_at_least(src, &raw.clamp_zone_mm, "thresholds.clamp_zone_mm", 0.0)?;
    let (min_bend_radius_m, min_bend_radius_source) =
        bend_radius(src, &raw.min_bend_radius_mm, cable)?;
    let static_bend_margin = match &raw.static_bend_margin_mm {
        Some(margin) => finite_at_least(src, margin, "thresholds.static_bend_margin_mm", 0.0)?,
        None => 0.0,
    };
    let flexing_change = match &raw.flexing_curvature_change_per_m {
        Some(change) => finite_at_least(
            src,
            change,
            "thresholds.flexing_curvature_change_per_m",
            0.0,
        )?,
        None => super::DEFAULT_FLEXING_CURVATURE_CHANGE_PER_M,
    };
    Ok(Thresholds {
        contact_clearance_m: clearance * 1e-3,
        stretch,
        min_bend_radius_m,
        min_bend_radius_source,
        clamp_zone_m: clamp_zone * 1e-3,
        static_bend_margin_m: static_bend_margin * 1e-3,
        cable_flexing_bend_radius_m: cable.datasheet.min_bend_radius_flexing_m,
        torsion_limit_deg_per_m: cable.datasheet.torsion_limit_deg_per_m,
        flexing_curvature_change_per_m: flexing_change,
    })
}

fn bend_radius(
    src: Source,
    value: &Spanned<BendRadiusSetting>,
    cable: &CableSpec,
) -> Result<(f64, BendRadiusSource), SetupError> {
    let key = "thresholds.min_bend_radius_mm";
    match value.get_ref() {
        BendRadiusSetting::Millimetres(mm) if mm.is_finite() && *mm > 0.0 => {
            Ok((mm * 1e-3, BendRadiusSource::Setup))
        }
        BendRadiusSetting::Millimetres(mm) => Err(src.error(
            value.span(),
            key,
            format!("{mm} must be a finite number > 0 (or \"cable\")"),
        )),
        BendRadiusSetting::Word(word) if word == "cable" => {
            Ok((cable.min_bend_radius_m, BendRadiusSource::Cable))
        }
        BendRadiusSetting::Word(word) => Err(src.error(
            value.span(),
            key,
            format!("\"{word}\": expected a radius in mm or \"cable\" (the cable file's value)"),
        )),
    }
}

fn robustness(src: Source, raw: &RawRobustness) -> Result<Robustness, SetupError> {
    let delta_s = at_least_one(src, &raw.delta_s, "robustness.delta_s")?;
    let range = *raw.range.get_ref();
    // R·ΔS is a length: bounded like the segments' lengths (and never overflowing).
    if delta_s.saturating_mul(range) > MAX_SUB_SEGMENTS {
        return Err(src.error(
            raw.range.span(),
            "robustness.range",
            format!(
                "range × delta_s = {range} × {delta_s} sub-segments, more than the \
                 {MAX_SUB_SEGMENTS} a segment may have"
            ),
        ));
    }
    Ok(Robustness { delta_s, range })
}
