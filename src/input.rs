//! Reading input files with their size bounded before anything is allocated: a file from
//! another tool or team may be a device (`/dev/zero` never ends), a pipe, a folder or simply
//! far larger than any real file of its kind, and must be refused with a message, not read
//! until memory runs out.

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// A kind of input file and the largest one accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FileKind {
    /// What the file is, for messages ("URDF file").
    pub what: &'static str,
    /// The largest accepted size (bytes).
    pub limit_bytes: u64,
}

const MIB: u64 = 1 << 20;

/// URDF robot descriptions: real ones are kilobytes (meshes are separate files).
pub const URDF: FileKind = FileKind {
    what: "URDF file",
    limit_bytes: 16 * MIB,
};
/// Setup files: a hand-written catalogue of thousands of clamp places is well under this.
pub const SETUP: FileKind = FileKind {
    what: "setup file",
    limit_bytes: 16 * MIB,
};
/// Cable files: a dozen numbers.
pub const CABLE: FileKind = FileKind {
    what: "cable file",
    limit_bytes: MIB,
};
/// Motion CSVs: an hour at 1 ms with six joints is about 220 MB.
pub const MOTION: FileKind = FileKind {
    what: "motion CSV",
    limit_bytes: 512 * MIB,
};
/// Waypoint files: a few hundred waypoints.
pub const WAYPOINTS: FileKind = FileKind {
    what: "waypoint file",
    limit_bytes: 16 * MIB,
};
/// STL meshes: the embedded files of a dictionary may total 63 MB.
pub const MESH: FileKind = FileKind {
    what: "mesh file",
    limit_bytes: 64 * MIB,
};
/// Result JSONs of `solve -o`, read back by `export-scene`.
pub const RESULT: FileKind = FileKind {
    what: "result JSON",
    limit_bytes: 256 * MIB,
};

/// The bytes of `path`, refused (with the reason, without the path: callers name the file)
/// when it is not a regular file or is larger than `kind` allows.
pub fn read_bytes(path: &Path, kind: FileKind) -> Result<Vec<u8>, String> {
    let cannot = |e: std::io::Error| format!("cannot read the {}: {e}", kind.what);
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!(
            "the {} is not a regular file ({}); give the path of a file",
            kind.what,
            file_type(&meta)
        ));
    }
    if meta.len() > kind.limit_bytes {
        return Err(too_large(kind, meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // A file that grows while it is read is cut at the limit, and refused.
    File::open(path)
        .map_err(cannot)?
        .take(kind.limit_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > kind.limit_bytes {
        return Err(too_large(kind, bytes.len() as u64));
    }
    Ok(bytes)
}

/// The text of `path`, as [`read_bytes`], refused when it is not UTF-8 (naming the line).
pub fn read_text(path: &Path, kind: FileKind) -> Result<String, String> {
    let bytes = read_bytes(path, kind)?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count();
        format!(
            "the {} is not UTF-8 text: line {line} has a byte that is not (a binary file?)",
            kind.what
        )
    })
}

fn too_large(kind: FileKind, len: u64) -> String {
    format!(
        "the {} is {}, more than the {} a {} may have",
        kind.what,
        megabytes(len),
        megabytes(kind.limit_bytes),
        kind.what
    )
}

/// `1.4 MiB`, `512 MiB`: in the binary unit the limits are set in, so that a limit prints as
/// the documented figure (16 MiB, not "17 MB").
fn megabytes(bytes: u64) -> String {
    let mib = bytes as f64 / (1024.0 * 1024.0);
    if mib < 10.0 {
        format!("{mib:.1} MiB")
    } else {
        format!("{mib:.0} MiB")
    }
}

/// What kind of entry `meta` describes, for a message (`a device`, `a pipe`, `a folder`, …).
pub(crate) fn file_type(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_fifo() {
            return "a pipe";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a folder"
    } else {
        "not a file"
    }
}

/// Whether `path` is a `.toml` file of `kind` with a line that is exactly `table` (e.g.
/// `[[motions]]`): how a command tells a cell, a mounting or a setup file apart before it
/// parses one. Unreadable files are none of them.
pub fn is_toml_with(path: &Path, kind: FileKind, table: &str) -> bool {
    let toml = path.extension().is_some_and(|e| e == "toml");
    toml && read_text(path, kind).is_ok_and(|text| text.lines().any(|l| l.trim() == table))
}

/// 1-based line number of byte `offset` in `text` (the end of the text when beyond it): how
/// every input error names its place.
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    let head = &text.as_bytes()[..offset.min(text.len())];
    head.iter().filter(|&&b| b == b'\n').count() + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_device_is_refused_before_anything_is_read() {
        let e = read_text(Path::new("/dev/zero"), URDF).unwrap_err();
        assert!(e.contains("not a regular file (a device)"), "{e}");
    }

    #[test]
    fn a_folder_is_refused() {
        let e = read_bytes(Path::new("."), SETUP).unwrap_err();
        assert!(e.contains("not a regular file (a folder)"), "{e}");
    }

    #[test]
    fn a_file_over_the_limit_is_refused_naming_both_sizes() {
        let dir = std::env::temp_dir().join(format!("cable-dict-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.toml");
        std::fs::write(&path, vec![b'#'; 1_500_000]).unwrap();
        let e = read_text(&path, CABLE).unwrap_err();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(
            e,
            "the cable file is 1.4 MiB, more than the 1.0 MiB a cable file may have"
        );
    }

    #[test]
    fn binary_text_is_refused_with_its_line() {
        let dir = std::env::temp_dir().join(format!("cable-dict-utf8-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("m.csv");
        std::fs::write(&path, b"t,a\n0,1\n\xff\xfe\n").unwrap();
        let e = read_text(&path, MOTION).unwrap_err();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(e.contains("line 3"), "{e}");
    }
}
