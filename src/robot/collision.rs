//! Collision geometry of the links, as URDF describes it.

use super::mesh::{MeshFile, MeshSource, load_mesh};
use crate::pose::{Pose, pose_from_xyz_rpy};
use nalgebra::{Point3, Vector3};
use std::path::PathBuf;

/// One collision shape of a link, posed in the link frame.
#[derive(Debug, Clone)]
pub struct Collider {
    /// Pose of the shape's own frame in the link frame (the URDF `<origin>`).
    pub origin: Pose,
    /// The shape in its own frame.
    pub shape: Shape,
    /// `None` for the URDF's own collision shapes; the name of the body a setup attached to
    /// the link (a tool, a camera: an obstacle for the cable, not a surface for clamps).
    pub attached: Option<String>,
}

/// A collision shape in its own frame, URDF conventions (metres).
#[derive(Debug, Clone)]
pub enum Shape {
    /// Box centred on the origin.
    Box {
        /// Half of the edge lengths along x, y, z.
        half_extents_m: Vector3<f64>,
    },
    /// Cylinder centred on the origin, axis along z.
    Cylinder {
        /// Radius.
        radius_m: f64,
        /// Full length along z.
        length_m: f64,
    },
    /// Sphere centred on the origin.
    Sphere {
        /// Radius.
        radius_m: f64,
    },
    /// Capsule centred on the origin, axis along z; `length_m` is the cylindrical part.
    Capsule {
        /// Radius of the cylinder and the end caps.
        radius_m: f64,
        /// Length of the cylindrical part along z (caps not included).
        length_m: f64,
    },
    /// Triangle mesh read from an STL file, already scaled.
    Mesh(TriMesh),
}

/// A triangle mesh in its own frame (metres).
#[derive(Debug, Clone)]
pub struct TriMesh {
    /// The resolved file it was read from.
    pub file: PathBuf,
    /// Vertex positions, scaled.
    pub vertices: Vec<Point3<f64>>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The mesh's shells, wound and classified (see [`shells`](super::shells)).
    pub fn shells(&self) -> super::shells::MeshShells {
        super::shells::analyse(&self.vertices, &self.triangles)
    }
}

impl Shape {
    /// How far a shape posed at `pose` reaches along the unit direction `d` (m): the largest
    /// `d·x` over its points.
    pub fn support_m(&self, pose: &Pose, d: &Vector3<f64>) -> f64 {
        let centre = pose.translation.vector.dot(d);
        let local = pose.rotation.inverse() * d;
        centre
            + match self {
                Shape::Box { half_extents_m: h } => h.dot(&local.abs()),
                Shape::Cylinder { radius_m, length_m } => {
                    radius_m * (1.0 - local.z * local.z).max(0.0).sqrt()
                        + 0.5 * length_m * local.z.abs()
                }
                Shape::Sphere { radius_m } => *radius_m,
                Shape::Capsule { radius_m, length_m } => radius_m + 0.5 * length_m * local.z.abs(),
                Shape::Mesh(mesh) => mesh
                    .vertices
                    .iter()
                    .map(|v| v.coords.dot(&local))
                    .fold(f64::NEG_INFINITY, f64::max),
            }
    }

    /// One-line human description with dimensions in millimetres.
    pub fn describe(&self) -> String {
        let mm = |v: f64| v * 1e3;
        match self {
            Shape::Box { half_extents_m: h } => {
                format!(
                    "box {:.1} × {:.1} × {:.1} mm",
                    mm(2.0 * h.x),
                    mm(2.0 * h.y),
                    mm(2.0 * h.z)
                )
            }
            Shape::Cylinder { radius_m, length_m } => {
                format!(
                    "cylinder r {:.1} mm, length {:.1} mm",
                    mm(*radius_m),
                    mm(*length_m)
                )
            }
            Shape::Sphere { radius_m } => format!("sphere r {:.1} mm", mm(*radius_m)),
            Shape::Capsule { radius_m, length_m } => {
                format!(
                    "capsule r {:.1} mm, length {:.1} mm",
                    mm(*radius_m),
                    mm(*length_m)
                )
            }
            Shape::Mesh(mesh) => format!(
                "mesh {} ({} triangles)",
                mesh.file.display(),
                mesh.triangles.len()
            ),
        }
    }
}

/// The colliders of a URDF link, with meshes from `meshes`; each mesh file read joins
/// `files` (once per URI). The error text names the offending `<collision>`.
pub(super) fn colliders_of_link(
    link: &urdf_rs::Link,
    meshes: MeshSource<'_>,
    files: &mut Vec<MeshFile>,
) -> Result<Vec<Collider>, String> {
    link.collision
        .iter()
        .enumerate()
        .map(|(i, collision)| {
            let at = |problem: String| format!("<collision> #{}: {problem}", i + 1);
            let xyz = collision.origin.xyz.0;
            let rpy = collision.origin.rpy.0;
            if xyz.iter().chain(rpy.iter()).any(|v| !v.is_finite()) {
                return Err(at("<origin> has a non-finite value".into()));
            }
            let shape = shape_of(&collision.geometry, meshes, files).map_err(at)?;
            Ok(Collider {
                origin: pose_from_xyz_rpy(xyz, rpy),
                shape,
                attached: None,
            })
        })
        .collect()
}

fn shape_of(
    geometry: &urdf_rs::Geometry,
    meshes: MeshSource<'_>,
    files: &mut Vec<MeshFile>,
) -> Result<Shape, String> {
    use urdf_rs::Geometry as G;
    match geometry {
        G::Box { size } => {
            positive("box size", &size.0)?;
            Ok(Shape::Box {
                half_extents_m: Vector3::from(size.0) * 0.5,
            })
        }
        G::Cylinder { radius, length } => {
            positive("cylinder radius/length", &[*radius, *length])?;
            Ok(Shape::Cylinder {
                radius_m: *radius,
                length_m: *length,
            })
        }
        G::Sphere { radius } => {
            positive("sphere radius", &[*radius])?;
            Ok(Shape::Sphere { radius_m: *radius })
        }
        G::Capsule { radius, length } => {
            positive("capsule radius", &[*radius])?;
            if !(length.is_finite() && *length >= 0.0) {
                return Err(format!("capsule length {length} must be ≥ 0"));
            }
            Ok(Shape::Capsule {
                radius_m: *radius,
                length_m: *length,
            })
        }
        G::Mesh { filename, scale } => {
            let scale = scale.map_or([1.0; 3], |s| s.0);
            if scale.iter().any(|v| !v.is_finite() || *v == 0.0) {
                return Err(format!("mesh scale {scale:?} must be finite and non-zero"));
            }
            let (mesh, file) = load_mesh(filename, Vector3::from(scale), meshes)?;
            if !files.iter().any(|f| f.uri == file.uri) {
                files.push(file);
            }
            Ok(Shape::Mesh(mesh))
        }
    }
}

fn positive(what: &str, values: &[f64]) -> Result<(), String> {
    if values.iter().all(|v| v.is_finite() && *v > 0.0) {
        Ok(())
    } else {
        Err(format!("{what} {values:?} must be finite and > 0"))
    }
}
