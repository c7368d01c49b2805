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
        return Err(unsupported_format(uri, source));
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
    let stl = read_stl(&bytes).map_err(|why| {
        format!(
            "mesh '{uri}': {} is not a readable STL file: {why}; {READABLE}",
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

/// The mesh formats the tool reads, for error messages.
const READABLE: &str = "only STL meshes are supported (binary or ASCII STL, file extension \
     .stl in any case): convert the mesh to STL or use primitive shapes";

/// Why the mesh `uri` is not read: its extension is not `.stl`. Names the format when the
/// extension tells it and the file the URI resolves to when it can be found.
fn unsupported_format(uri: &str, source: MeshSource<'_>) -> String {
    let extension = Path::new(uri)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let format = match extension.as_deref() {
        Some("dae") => "COLLADA (.dae)".to_string(),
        Some("obj") => "Wavefront OBJ (.obj)".to_string(),
        Some("ply") => "PLY (.ply)".to_string(),
        Some("gltf" | "glb") => "glTF".to_string(),
        Some(other) => format!(".{other}"),
        None => String::new(),
    };
    let what = if format.is_empty() {
        "has no file extension, so it is not read as STL".to_string()
    } else {
        format!("is a {format} file, which the tool does not read")
    };
    let (found, missing) = match source {
        MeshSource::Files(base_dir) => match locate(uri, base_dir) {
            Ok(file) => (format!(" ({})", file.display()), String::new()),
            Err(problem) => (String::new(), format!(" (besides, {problem})")),
        },
        MeshSource::Embedded(_) => (String::new(), String::new()),
    };
    format!("mesh '{uri}'{found} {what}; {READABLE}{missing}")
}

/// Reads binary or ASCII STL bytes; the error says what the bytes are instead.
///
/// Bytes whose length is exactly 84 + 50 n, n being the triangle count in bytes 80..84, are
/// binary STL even when their header begins with "solid" (some exporters write that, and
/// `stl_io` would take them for ASCII); an ASCII file whose first line is a bare "solid" (no
/// name) is read as ASCII (`stl_io` wants "solid " and would take it for binary).
fn read_stl(bytes: &[u8]) -> Result<stl_io::IndexedMesh, String> {
    let announced = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize);
    let binary_size = announced.and_then(|n| n.checked_mul(50)?.checked_add(84));
    let is_binary = binary_size == Some(bytes.len());
    let read = |bytes: &[u8]| stl_io::read_stl(&mut std::io::Cursor::new(bytes));
    let result = if is_binary && bytes.starts_with(b"solid") {
        let mut copy = bytes.to_vec();
        copy[..80].fill(0);
        read(&copy)
    } else if !is_binary && (bytes.starts_with(b"solid\n") || bytes.starts_with(b"solid\r")) {
        let mut copy = b"solid ".to_vec();
        copy.extend_from_slice(&bytes[5..]);
        read(&copy)
    } else {
        read(bytes)
    };
    result.map_err(|e| {
        let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        let text = &text[text.iter().take_while(|b| b.is_ascii_whitespace()).count()..];
        let head = &text[..text.len().min(1024)];
        let contains = |word: &[u8]| head.windows(word.len()).any(|w| w == word);
        if bytes.is_empty() {
            "the file is empty".to_string()
        } else if contains(b"<COLLADA") {
            "it is a COLLADA (XML) file, not STL".to_string()
        } else if text.starts_with(b"<") {
            "it is XML text, not STL".to_string()
        } else if text.starts_with(b"ply") {
            "it is a PLY file, not STL".to_string()
        } else if text.starts_with(b"glTF") || text.starts_with(b"{") {
            "it looks like glTF, not STL".to_string()
        } else if text.starts_with(b"solid") {
            format!("as ASCII STL: {e}")
        } else if let (Some(n), Some(size)) = (announced, binary_size) {
            format!(
                "as binary STL its header announces {n} triangles ({size} bytes), but the file \
                 has {} bytes; as ASCII STL it does not begin with \"solid\"",
                bytes.len()
            )
        } else {
            format!(
                "{} bytes are too few for binary STL (84 bytes before the first triangle) and \
                 as ASCII STL it does not begin with \"solid\"",
                bytes.len()
            )
        }
    })
}

/// Resolves a URDF mesh filename to a file that exists.
///
/// `package://name/rest` is found by walking up from `base_dir` for a folder that is called
/// `name` or contains a folder `name`, so a robot description works from a plain checkout
/// without a ROS installation.
fn resolve_mesh_uri(uri: &str, base_dir: &Path) -> Result<PathBuf, String> {
    locate(uri, base_dir).map_err(|problem| format!("mesh '{uri}': {problem}"))
}

/// [`resolve_mesh_uri`] without the URI in front of the problem.
fn locate(uri: &str, base_dir: &Path) -> Result<PathBuf, String> {
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
                    "no folder named '{package}' found in {} or any folder above it",
                    start.display()
                )
            })?
            .join(relative)
    } else if let Some(absolute) = uri.strip_prefix("file://") {
        PathBuf::from(absolute)
    } else {
        base_dir.join(uri)
    };
    match std::fs::metadata(&path) {
        Ok(meta) if meta.is_file() => Ok(path),
        Ok(meta) => Err(format!(
            "{} is not a regular file ({}); give the path of a mesh file",
            path.display(),
            crate::input::file_type(&meta)
        )),
        Err(_) => Err(format!("file {} does not exist", path.display())),
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
