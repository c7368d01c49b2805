//! Mesh files referenced by a URDF: path resolution without ROS, STL reading, and the same
//! from bytes embedded in a dictionary.

use super::TriMesh;
use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A mesh file's bytes under the URI the URDF names it by: what a dictionary embeds so that
/// it carries the whole robot.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct MeshFile {
    /// The `filename` attribute as written in the URDF.
    pub uri: String,
    /// The file's bytes.
    pub bytes: Vec<u8>,
}

/// Where mesh files come from.
#[derive(Debug, Clone, Copy)]
pub(super) enum MeshSource<'a> {
    /// Files, relative URIs resolved against this folder.
    Files(&'a Path),
    /// Files embedded in a dictionary, found by URI.
    Embedded(&'a [MeshFile]),
}

/// Reads the STL mesh `uri` (from a file relative to the URDF's folder, `file://` or
/// `package://`, or embedded) and scales it; with it, the file's bytes.
pub(super) fn load_mesh(
    uri: &str,
    scale: Vector3<f64>,
    source: MeshSource<'_>,
) -> Result<(TriMesh, MeshFile), String> {
    let is_stl = Path::new(uri)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("stl"));
    if !is_stl {
        return Err(format!(
            "mesh '{uri}': only STL meshes are supported; convert it or use primitive shapes"
        ));
    }
    let (file, bytes) = match source {
        MeshSource::Files(base_dir) => {
            let file = resolve_mesh_uri(uri, base_dir)?;
            let bytes = crate::input::read_bytes(&file, crate::input::MESH)
                .map_err(|e| format!("mesh '{uri}' ({}): {e}", file.display()))?;
            (file, bytes)
        }
        MeshSource::Embedded(files) => {
            let embedded = files.iter().find(|f| f.uri == uri).ok_or_else(|| {
                format!("mesh '{uri}' is not among the mesh files embedded with the URDF")
            })?;
            (PathBuf::from(uri), embedded.bytes.clone())
        }
    };
    let stl = stl_io::read_stl(&mut std::io::Cursor::new(&bytes)).map_err(|e| {
        format!(
            "mesh '{uri}': {} is not a readable STL file: {e}",
            file.display()
        )
    })?;
    if stl.faces.is_empty() {
        return Err(format!("mesh '{uri}': {} has no triangles", file.display()));
    }
    let vertices: Vec<Point3<f64>> = stl
        .vertices
        .iter()
        .map(|v| Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .map(|p| Point3::from(p.coords.component_mul(&scale)))
        .collect();
    if vertices
        .iter()
        .any(|p| !p.coords.iter().all(|c| c.is_finite()))
    {
        return Err(format!(
            "mesh '{uri}': {} has non-finite vertices",
            file.display()
        ));
    }
    let triangles = stl
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i as u32))
        .collect();
    let mesh = TriMesh {
        file,
        vertices,
        triangles,
    };
    Ok((
        mesh,
        MeshFile {
            uri: uri.to_string(),
            bytes,
        },
    ))
}

/// Resolves a URDF mesh filename to a file that exists.
///
/// `package://name/rest` is found by walking up from `base_dir` for a folder that is called
/// `name` or contains a folder `name`, so a robot description works from a plain checkout
/// without a ROS installation.
fn resolve_mesh_uri(uri: &str, base_dir: &Path) -> Result<PathBuf, String> {
    let path = if let Some(rest) = uri.strip_prefix("package://") {
        let (package, relative) = rest.split_once('/').unwrap_or((rest, ""));
        // Walking up needs the absolute folder: the parent of `robot.urdf` is "" and that of
        // `./robot.urdf` is ".", neither of which has the folders above it.
        let start = base_dir
            .canonicalize()
            .unwrap_or_else(|_| base_dir.to_path_buf());
        find_package(package, &start)
            .ok_or_else(|| {
                format!(
                    "mesh '{uri}': no folder named '{package}' found in {} or any folder above it",
                    start.display()
                )
            })?
            .join(relative)
    } else if let Some(absolute) = uri.strip_prefix("file://") {
        PathBuf::from(absolute)
    } else {
        base_dir.join(uri)
    };
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!(
            "mesh '{uri}': file {} does not exist",
            path.display()
        ))
    }
}

/// The package folder nearest to `start`: going up from `start`, the first folder that is
/// called `package` or holds a folder `package` (that one, then).
fn find_package(package: &str, start: &Path) -> Option<PathBuf> {
    start.ancestors().find_map(|dir| {
        if dir.file_name().is_some_and(|n| n == package) {
            Some(dir.to_path_buf())
        } else {
            let inside = dir.join(package);
            inside.is_dir().then_some(inside)
        }
    })
}
