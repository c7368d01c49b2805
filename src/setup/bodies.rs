//! Bodies a setup attaches to the robot's links — the gripper, a camera, a valve block: what
//! the URDF does not describe but the cable must not touch either.
//!
//! ```toml
//! [[bodies]]
//! name = "gripper"
//! link = "link_6"
//! position_mm = [0.0, 0.0, 50.0]   # the shape's centre in the link frame
//! rpy_deg = [0.0, 0.0, 0.0]
//! box_mm = [44.0, 44.0, 100.0]     # or cylinder_mm = { radius = …, length = … } (axis z),
//!                                  # sphere_radius_mm = …, or mesh = "gripper.stl"
//!                                  # (+ mesh_scale = [0.001, 0.001, 0.001])
//! ```
//!
//! A body is one more collider of its link: the contact test, the static sweep and the
//! motion test see it, clamp zones at guides on that link leave it out as they leave the
//! link out, and clamp sites are not generated on it.

use super::SetupError;
use super::error::Source;
use super::guides::link_named;
use super::raw::RawBody;
use crate::pose::pose_from_mm_deg;
use crate::robot::{MeshFile, Robot, Shape};
use nalgebra::Vector3;
use std::path::Path;
use toml::Spanned;

/// Attaches every `[[bodies]]` entry to its link; meshes are read relative to `folder`, or
/// from `embedded` when given (a dictionary's files).
pub(super) fn attach(
    src: Source,
    robot: &mut Robot,
    raw: &Spanned<Vec<Spanned<RawBody>>>,
    folder: &Path,
    embedded: Option<&[MeshFile]>,
) -> Result<(), SetupError> {
    let mut names: Vec<&str> = Vec::new();
    for (b, entry) in raw.get_ref().iter().enumerate() {
        let body = entry.get_ref();
        let key = |field: &str| format!("bodies[{b}].{field}");
        let name = body.name.get_ref();
        if names.contains(&name.as_str()) {
            return Err(src.error(
                body.name.span(),
                key("name"),
                format!("body name \"{name}\" is used twice"),
            ));
        }
        names.push(name);
        let link = link_named(src, robot, &body.link, key("link"))?;
        let position = src.finite3(&body.position_mm, key("position_mm"))?;
        let rpy = src.finite3(&body.rpy_deg, key("rpy_deg"))?;
        let shape = shape(src, robot, body, b, folder, embedded)?;
        robot.attach_body(link, name, pose_from_mm_deg(position, rpy), shape);
    }
    Ok(())
}

/// The body's one shape key, validated (positive, finite dimensions).
fn shape(
    src: Source,
    robot: &mut Robot,
    body: &RawBody,
    b: usize,
    folder: &Path,
    embedded: Option<&[MeshFile]>,
) -> Result<Shape, SetupError> {
    let key = |field: &str| format!("bodies[{b}].{field}");
    let positive = |span: std::ops::Range<usize>, field: &str, values: &[f64]| {
        if values.iter().all(|v| v.is_finite() && *v > 0.0) {
            Ok(())
        } else {
            Err(src.error(
                span,
                key(field),
                format!("{values:?} must be finite and > 0"),
            ))
        }
    };
    match (
        &body.box_mm,
        &body.cylinder_mm,
        &body.sphere_radius_mm,
        &body.mesh,
    ) {
        (Some(size), None, None, None) => {
            positive(size.span(), "box_mm", size.get_ref())?;
            Ok(Shape::Box {
                half_extents_m: Vector3::from(*size.get_ref()) * 0.5e-3,
            })
        }
        (None, Some(cylinder), None, None) => {
            let c = cylinder.get_ref();
            positive(cylinder.span(), "cylinder_mm", &[c.radius, c.length])?;
            Ok(Shape::Cylinder {
                radius_m: c.radius * 1e-3,
                length_m: c.length * 1e-3,
            })
        }
        (None, None, Some(radius), None) => {
            positive(radius.span(), "sphere_radius_mm", &[*radius.get_ref()])?;
            Ok(Shape::Sphere {
                radius_m: radius.get_ref() * 1e-3,
            })
        }
        (None, None, None, Some(uri)) => {
            let scale = match &body.mesh_scale {
                Some(scale) if !scale.get_ref().iter().all(|v| v.is_finite() && *v != 0.0) => {
                    return Err(src.error(
                        scale.span(),
                        key("mesh_scale"),
                        format!("{:?} must be finite and non-zero", scale.get_ref()),
                    ));
                }
                Some(scale) => Vector3::from(*scale.get_ref()),
                None => Vector3::repeat(1.0),
            };
            let mesh = robot
                .read_body_mesh(uri.get_ref(), scale, folder, embedded)
                .map_err(|problem| src.error(uri.span(), key("mesh"), problem))?;
            Ok(Shape::Mesh(mesh))
        }
        _ => {
            let given: Vec<&str> = [
                (body.box_mm.is_some(), "box_mm"),
                (body.cylinder_mm.is_some(), "cylinder_mm"),
                (body.sphere_radius_mm.is_some(), "sphere_radius_mm"),
                (body.mesh.is_some(), "mesh"),
            ]
            .into_iter()
            .filter_map(|(present, key)| present.then_some(key))
            .collect();
            let what = match given.as_slice() {
                [] => "no shape".to_string(),
                keys => format!("{} shapes ({})", keys.len(), keys.join(", ")),
            };
            Err(src.error(
                body.name.span(),
                format!("bodies[{b}]"),
                format!(
                    "{what} given; give exactly one: box_mm = [x, y, z], cylinder_mm = \
                     {{ radius, length }}, sphere_radius_mm or mesh = \"file.stl\""
                ),
            ))
        }
    }
}
