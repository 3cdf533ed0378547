//! Atomic file replacement, the one way the program writes a file (images, heat maps, assets,
//! benchmark documents, project and recovery files): write a sibling temp file, fsync it, give
//! it the old file's permissions, rename it over the target, fsync the folder. A crash, a kill
//! or a full disk at any point leaves either the old or the new file, never a mix.
//!
//! A symlinked target keeps its link (the file it points to is replaced), and temp files left
//! by a process that died mid-write are removed on the next write of the same file.

use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The suffix of temp files: `<name>.tmp<pid>`.
const TMP: &str = ".tmp";

/// Atomically replaces `path` with `bytes`.
pub fn write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    // Write through a symlink: replacing the link itself would turn it into a plain file.
    let path = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => std::fs::canonicalize(path)?,
        _ => path.to_owned(),
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_owned(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| std::io::Error::other("path has no file name"))?.to_owned();
    remove_stale(&dir, &name.to_string_lossy());
    let mut tmp_name = name;
    tmp_name.push(format!("{TMP}{}", std::process::id()));
    let tmp = dir.join(tmp_name);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        if let Ok(old) = std::fs::metadata(&path) {
            f.set_permissions(old.permissions())?;
        }
        drop(f);
        std::fs::rename(&tmp, &path)?;
        if let Ok(d) = std::fs::File::open(&dir) {
            // Persist the rename; not all platforms allow syncing a directory.
            let _ = d.sync_all();
        }
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Removes `<name>.tmp<pid>` files in `dir` whose process is gone (Linux: no `/proc/<pid>`;
/// elsewhere only files over a day old, which no running write can still own).
fn remove_stale(dir: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let prefix = format!("{name}{TMP}");
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(pid) = file.to_str().and_then(|f| f.strip_prefix(&prefix)).and_then(|p| p.parse::<u32>().ok()) else {
            continue;
        };
        let proc = Path::new("/proc");
        let dead = if proc.is_dir() {
            pid != std::process::id() && !proc.join(pid.to_string()).exists()
        } else {
            entry
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age > std::time::Duration::from_secs(86_400))
        };
        if dead {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("bouncelab-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).expect("dir");
        d
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_keeps_its_link_and_the_file_its_permissions() {
        use std::os::unix::fs::PermissionsExt as _;
        let d = dir("link");
        let target = d.join("real.ron");
        std::fs::write(&target, "old").expect("write");
        std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o600)).expect("chmod");
        let link = d.join("link.ron");
        std::os::unix::fs::symlink(&target, &link).expect("symlink");
        write(&link, b"new").expect("atomic write");
        assert!(std::fs::symlink_metadata(&link).expect("meta").file_type().is_symlink(), "still a link");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "new");
        let mode = std::fs::metadata(&target).expect("meta").permissions().mode() & 0o777;
        assert_eq!(mode, 0o600, "permissions kept");
    }

    #[test]
    fn temp_files_of_dead_writers_are_removed_and_a_failed_write_keeps_the_old_file() {
        let d = dir("stale");
        let target = d.join("image.png");
        std::fs::write(&target, "old").expect("write");
        // A pid far above any running process's left its temp file behind.
        let stale = d.join("image.png.tmp4000000000");
        std::fs::write(&stale, "partial").expect("write");
        write(&target, b"new").expect("atomic write");
        assert!(!stale.exists() || !Path::new("/proc").is_dir(), "stale temp file removed");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "new");
        // Writing into a folder that does not exist fails and leaves nothing behind.
        let missing = d.join("nowhere").join("x.png");
        assert!(write(&missing, b"x").is_err());
        assert_eq!(std::fs::read_dir(&d).expect("dir").count(), 1, "only the target remains");
    }
}
