//! Replacing output files and folders so that readers see the old one or the whole new one,
//! never a torn or mixed one — and so that nothing else is touched on the way.
//!
//! - A temporary is created next to its target with an unpredictable name and *exclusively*
//!   (`O_CREAT | O_EXCL`): an existing file or a planted symbolic link of that name makes the
//!   creation fail instead of being written through.
//! - Temporaries in progress are registered, so that an interrupted run
//!   ([`remove_temporaries`], called from the command line's Ctrl-C handler) leaves none
//!   behind; those of a killed run (`kill -9`) are removed by the next write of the same
//!   target, once their process is gone.

use std::collections::hash_map::RandomState;
use std::fs::{self, File, OpenOptions};
use std::hash::{BuildHasher, Hasher};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Distinguishes temporaries of concurrent writers within one process.
static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// Temporary files and folders being written now.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Attempts at an unused temporary name before giving up (each name is random).
const NAME_ATTEMPTS: usize = 16;

/// Writes `bytes` to `path` through a temporary file in the same folder, flushed to disk
/// (`fsync`) and then renamed over `path`. On failure the temporary file is removed and
/// `path` is left as it was.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let (dir, name) = split(path)?;
    remove_stale_temporaries(&dir, &name);
    let (temp, mut file) = create_exclusively(&dir, &name, |p| {
        OpenOptions::new().write(true).create_new(true).open(p)
    })?;
    let result = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temp, path)
        });
    if result.is_err() {
        let _ = fs::remove_file(&temp);
    } else {
        sync_folder(&dir);
    }
    unregister(&temp);
    result
}

/// Writes `bytes` to `path`, which must not exist yet, with permissions `mode` on Unix (0o600
/// for a secret key: its owner only). Like [`write_atomically`], the file appears whole or
/// not at all; an existing file (or link) at `path` is an error, never replaced.
pub fn write_new(path: &Path, bytes: &[u8], mode: u32) -> io::Result<()> {
    let (dir, name) = split(path)?;
    let (temp, mut file) = create_exclusively(&dir, &name, |p| {
        let mut options = OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::mode(&mut options, mode);
        options.open(p)
    })?;
    // A hard link fails on an existing target: no check-then-rename window.
    let result = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| fs::hard_link(&temp, path));
    let _ = fs::remove_file(&temp);
    unregister(&temp);
    if result.is_ok() {
        sync_folder(&dir);
    }
    result
}

/// A folder being filled next to the one it will replace as a whole ([`Self::commit`]);
/// dropped without a commit, it is removed and the old folder stays as it was.
#[derive(Debug)]
pub struct FolderReplacement {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl FolderReplacement {
    /// Creates the (empty, exclusive) staging folder for `target`. Refuses when `target`
    /// exists and holds an entry `may_replace` does not accept: replacing a folder removes
    /// what is in it, and only what the caller wrote there before may be removed.
    pub fn begin(
        target: &Path,
        may_replace: impl Fn(&str) -> bool,
    ) -> io::Result<FolderReplacement> {
        let (dir, name) = split(target)?;
        Self::check(target, may_replace)?;
        remove_stale_temporaries(&dir, &name);
        let (staging, ()) = create_exclusively(&dir, &name, |p| fs::create_dir(p))?;
        Ok(FolderReplacement {
            target: target.to_path_buf(),
            staging,
            committed: false,
        })
    }

    /// `Ok` when [`Self::begin`] can start on `target`: its parent folder exists and
    /// `target` is missing or a folder of only entries `may_replace` accepts — checked before
    /// a long run whose output would then have nowhere to go.
    pub fn check(target: &Path, may_replace: impl Fn(&str) -> bool) -> io::Result<()> {
        let (dir, _) = split(target)?;
        if fs::symlink_metadata(target).is_ok_and(|meta| !meta.is_dir()) {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!(
                    "{} is a symbolic link or a file, not a folder: give a new folder or an \
                     earlier report's (a link is not followed: the folder it points to would \
                     be replaced)",
                    target.display()
                ),
            ));
        }
        if !dir.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::NotFound,
                format!("folder {} does not exist", dir.display()),
            ));
        }
        match foreign_entry(target, &may_replace)? {
            None => Ok(()),
            Some(foreign) => Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!(
                    "{} holds `{foreign}`, which a report does not write: give a new folder \
                     or an earlier report's (the whole folder is replaced)",
                    target.display()
                ),
            )),
        }
    }

    /// The staging folder to write into.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Puts the staging folder in the target's place: the old folder (if any) is renamed
    /// aside, the new one renamed in, the old one removed. A reader sees the old folder, no
    /// folder for an instant, or the new one — never a mix.
    pub fn commit(mut self) -> io::Result<()> {
        let (dir, name) = split(&self.target)?;
        if self.target.exists() && exchange(&self.staging, &self.target)? {
            // One atomic step: the staging path now holds the old folder.
            self.committed = true;
            let _ = fs::remove_dir_all(&self.staging);
            unregister(&self.staging);
            sync_folder(&dir);
            return Ok(());
        }
        // Where folders cannot be exchanged, a crash between the two renames leaves the old
        // folder aside and none at the target; the next `begin` puts it back.
        let old = match self.target.exists() {
            true => {
                let (old, ()) =
                    create_exclusively(&dir, &format!("{name}.old"), |p| fs::create_dir(p))?;
                fs::rename(&self.target, &old)?;
                Some(old)
            }
            false => None,
        };
        if let Err(e) = fs::rename(&self.staging, &self.target) {
            if let Some(old) = &old {
                let _ = fs::rename(old, &self.target);
            }
            return Err(e);
        }
        self.committed = true;
        unregister(&self.staging);
        if let Some(old) = old {
            let _ = fs::remove_dir_all(&old);
            unregister(&old);
        }
        sync_folder(&dir);
        Ok(())
    }
}

impl Drop for FolderReplacement {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
            unregister(&self.staging);
        }
    }
}

/// Removes every temporary file and folder this process is writing now: for an interrupt
/// handler, just before the process exits.
pub fn remove_temporaries() {
    let temporaries = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
    temporaries.iter().for_each(|temp| remove_entry(temp));
}

/// Removes the file, link or folder at `path`, best effort. A link is not followed: it is
/// removed itself, never what it points to.
fn remove_entry(path: &Path) {
    match fs::symlink_metadata(path) {
        Ok(meta) if meta.is_dir() => {
            let _ = fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// The folder (`.` for a bare name) and file name of `path`.
fn split(path: &Path) -> io::Result<(PathBuf, String)> {
    // `.` or `out/..` name no file: the absolute path does.
    let path = std::path::absolute(path)?;
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} names no file", path.display()),
        )
    })?;
    let dir = path.parent().unwrap_or(Path::new("/")).to_path_buf();
    Ok((dir, name.to_string_lossy().into_owned()))
}

/// `.{name}.tmp-{pid}-`: the start of every temporary name of `name` made by process `pid`.
fn temporary_prefix(name: &str, pid: u32) -> String {
    format!(".{name}.tmp-{pid}-")
}

/// Creates (with `create`, which must fail on an existing path) and registers a temporary
/// next to `name` in `dir` under a random name.
fn create_exclusively<T>(
    dir: &Path,
    name: &str,
    create: impl Fn(&Path) -> io::Result<T>,
) -> io::Result<(PathBuf, T)> {
    let prefix = temporary_prefix(name, std::process::id());
    for _ in 0..NAME_ATTEMPTS {
        let nonce = RandomState::new().build_hasher().finish();
        let counter = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!("{prefix}{counter}-{nonce:016x}"));
        // Registered first: an interrupt between the creation and the registration would
        // leave the temporary behind.
        TEMPORARIES
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(temp.clone());
        match create(&temp) {
            Ok(made) => return Ok((temp, made)),
            Err(e) => {
                unregister(&temp);
                if e.kind() != io::ErrorKind::AlreadyExists {
                    return Err(e);
                }
            }
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!(
            "no unused temporary name next to {name} in {}",
            dir.display()
        ),
    ))
}

fn unregister(temp: &Path) {
    let mut temporaries = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
    temporaries.retain(|t| t != temp);
}

/// Removes the temporaries of `name` (files and folders, `.old` folders too) left in `dir`
/// by processes that no longer run (best effort: only where `/proc` tells which run).
fn remove_stale_temporaries(dir: &Path, name: &str) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let (new, old) = (format!(".{name}.tmp-"), format!(".{name}.old.tmp-"));
    let mut set_aside: Vec<PathBuf> = Vec::new();
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let file_name = file_name.to_string_lossy();
        let (rest, aside) = match (file_name.strip_prefix(&new), file_name.strip_prefix(&old)) {
            (Some(rest), _) => (rest, false),
            (_, Some(rest)) => (rest, true),
            _ => continue,
        };
        let pid = rest.split('-').next().and_then(|p| p.parse::<u32>().ok());
        let running = pid.is_some_and(|pid| Path::new(&format!("/proc/{pid}")).exists());
        if pid.is_none() || running {
            continue;
        }
        match aside {
            true => set_aside.push(entry.path()),
            false => remove_entry(&entry.path()),
        }
    }
    // A folder set aside by a run that stopped before it renamed the new one in is the last
    // complete one: it goes back to the target when the target is missing.
    set_aside.sort();
    let target = dir.join(name);
    if let Some(last) = set_aside.pop()
        && fs::symlink_metadata(&target).is_err()
        && fs::rename(&last, &target).is_ok()
    {
        log::warn!(
            "{}: put back the folder an interrupted run had set aside",
            target.display()
        );
    }
    set_aside.iter().for_each(|path| remove_entry(path));
}

/// Exchanges the folders `a` and `b` in one atomic step; `Ok(false)` where the platform or the
/// file system cannot (the caller then renames twice).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<bool> {
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| {
        std::ffi::CString::new(p.as_os_str().as_bytes())
            .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, e))
    };
    let (a, b) = (c(a)?, c(b)?);
    // SAFETY: both paths are NUL-terminated strings that live across the call.
    let done = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if done == 0 {
        return Ok(true);
    }
    let error = io::Error::last_os_error();
    match error.raw_os_error() {
        Some(libc::EINVAL | libc::ENOSYS | libc::EOPNOTSUPP) => Ok(false),
        _ => Err(error),
    }
}

/// Exchanges the folders `a` and `b` in one atomic step; `Ok(false)` where the platform or the
/// file system cannot (the caller then renames twice).
#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> io::Result<bool> {
    Ok(false)
}

/// The first entry of folder `target` that `may_replace` does not accept; `None` when
/// there is no such folder.
fn foreign_entry(target: &Path, may_replace: &impl Fn(&str) -> bool) -> io::Result<Option<String>> {
    let entries = match fs::read_dir(target) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            let what = format!("{}: {e}", target.display());
            return Err(io::Error::new(e.kind(), what));
        }
    };
    let mut names: Vec<String> = entries
        .map(|entry| entry.map(|e| e.file_name().to_string_lossy().into_owned()))
        .collect::<io::Result<_>>()?;
    names.sort();
    Ok(names.into_iter().find(|n| !may_replace(n)))
}

/// Makes the rename itself durable where the platform allows it (best effort).
fn sync_folder(dir: &Path) {
    if cfg!(unix)
        && let Ok(folder) = File::open(dir)
    {
        let _ = folder.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("cable-dict-atomic-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_leaves_the_target_alone_in_its_folder() {
        let dir = scratch("write");
        let path = dir.join("out.json");
        write_atomically(&path, b"old").unwrap();
        write_atomically(&path, b"new").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        assert_eq!(listing(&dir), ["out.json"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_removed_and_live_ones_kept() {
        let dir = scratch("stale");
        // No process has a pid above the kernel's pid_max (at most 2^22).
        let dead = dir.join(format!("{}0-1", temporary_prefix("out.json", 99_999_999)));
        let live = dir.join(format!(
            "{}0-1",
            temporary_prefix("out.json", std::process::id())
        ));
        let other = dir.join(format!("{}0-1", temporary_prefix("other.json", 99_999_999)));
        for p in [&dead, &live, &other] {
            fs::write(p, b"partial").unwrap();
        }
        write_atomically(&dir.join("out.json"), b"x").unwrap();
        assert!(!dead.exists() && live.exists() && other.exists());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_planted_link_is_removed_never_written_through() {
        let dir = scratch("link");
        let victim = dir.join("victim");
        fs::write(&victim, b"precious").unwrap();
        let planted = dir.join(format!("{}0-1", temporary_prefix("out.json", 99_999_999)));
        std::os::unix::fs::symlink(&victim, &planted).unwrap();
        write_atomically(&dir.join("out.json"), b"x").unwrap();
        assert_eq!(fs::read(&victim).unwrap(), b"precious");
        assert!(fs::symlink_metadata(&planted).is_err());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_is_replaced_whole_or_not_at_all() {
        let dir = scratch("folder");
        let target = dir.join("report");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("a.svg"), b"old").unwrap();
        fs::write(target.join("b.svg"), b"old").unwrap();
        let staging = FolderReplacement::begin(&target, |n| n.ends_with(".svg")).unwrap();
        fs::write(staging.path().join("a.svg"), b"new").unwrap();
        drop(staging);
        assert_eq!(listing(&target), ["a.svg", "b.svg"]);
        assert_eq!(listing(&dir), ["report"]);
        let staging = FolderReplacement::begin(&target, |n| n.ends_with(".svg")).unwrap();
        fs::write(staging.path().join("a.svg"), b"new").unwrap();
        staging.commit().unwrap();
        assert_eq!(listing(&target), ["a.svg"]);
        assert_eq!(fs::read(target.join("a.svg")).unwrap(), b"new");
        assert_eq!(listing(&dir), ["report"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_with_foreign_files_is_not_replaced() {
        let dir = scratch("foreign");
        fs::write(dir.join("thesis.tex"), b"years of work").unwrap();
        let e = FolderReplacement::begin(&dir, |n| n.ends_with(".svg")).unwrap_err();
        assert!(e.to_string().contains("holds `thesis.tex`"), "{e}");
        assert_eq!(fs::read(dir.join("thesis.tex")).unwrap(), b"years of work");
        fs::remove_dir_all(&dir).unwrap();
    }

    /// A folder at `path` holding `a.svg` with `bytes`.
    fn folder_with_a_picture(path: &Path, bytes: &[u8]) -> PathBuf {
        fs::create_dir(path).unwrap();
        fs::write(path.join("a.svg"), bytes).unwrap();
        path.to_path_buf()
    }

    #[test]
    fn a_linked_folder_is_refused_and_what_it_points_to_kept() {
        let dir = scratch("linked");
        let real = folder_with_a_picture(&dir.join("real"), b"kept");
        let link = dir.join("link");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        let e = FolderReplacement::check(&link, |n| n.ends_with(".svg")).unwrap_err();
        assert!(e.to_string().contains("symbolic link"), "{e}");
        assert!(FolderReplacement::begin(&link, |n| n.ends_with(".svg")).is_err());
        assert_eq!(listing(&dir), ["link", "real"]);
        assert_eq!(fs::read(real.join("a.svg")).unwrap(), b"kept");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_set_aside_by_a_run_that_died_is_put_back() {
        let dir = scratch("aside");
        let target = dir.join("report");
        // What a run killed between its two renames leaves: the old folder set aside under
        // its temporary name, no folder at the target.
        folder_with_a_picture(
            &dir.join(format!("{}0-1", temporary_prefix("report.old", 99_999_999))),
            b"old",
        );
        assert!(FolderReplacement::check(&target, |n| n.ends_with(".svg")).is_ok());
        let staging = FolderReplacement::begin(&target, |n| n.ends_with(".svg")).unwrap();
        assert_eq!(fs::read(target.join("a.svg")).unwrap(), b"old");
        fs::write(staging.path().join("a.svg"), b"new").unwrap();
        staging.commit().unwrap();
        assert_eq!(fs::read(target.join("a.svg")).unwrap(), b"new");
        assert_eq!(listing(&dir), ["report"]);
        fs::remove_dir_all(&dir).unwrap();
    }
}
