//! Crash recovery files: one per project and editor instance, so recovered work can never land
//! in another project and two instances never take each other's autosaves.
//!
//! A recovery file is named `<project key>.<instance>.ron`, where the key is the project file's
//! name and a hash of its canonical path (`untitled` for a project never saved), and holds the
//! project's path, the time it was written, the number of edits and the authored state with
//! absolute asset paths. Beside it, `<same>.lock` is held locked (an OS file lock) by the instance
//! that writes it for as long as it runs: a file whose lock can be taken belongs to an instance
//! that is gone (it crashed or was killed), and only such files are offered back. Restoring
//! reopens the project the file names, never the one that happens to be open. The files live in
//! the user's data folder, never next to the project; [`super::autosave`] writes them on a timer.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::project_file::{Project, ProjectError};
use crate::scene::SceneDesc;
use crate::settings::RenderSettings;

/// The version of the recovery file's layout.
pub const RECOVERY_VERSION: u32 = 1;

/// Why a recovery file could not be read or used.
#[derive(Debug, thiserror::Error)]
pub enum RecoveryError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// Not a recovery file this build reads.
    #[error("{path}: not a recovery file this version reads: {message}")]
    Parse { path: PathBuf, message: String },
    /// The recovered project does not load (an asset is gone).
    #[error(transparent)]
    Project(#[from] ProjectError),
}

/// What a recovery file holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecoveryFile {
    /// Always first: [`RECOVERY_VERSION`].
    pub recovery_version: u32,
    /// The project (or glTF) file the work belongs to; `None` for an untitled project.
    pub project: Option<PathBuf>,
    /// When it was written (seconds since the Unix epoch).
    pub saved_unix: u64,
    /// Undoable edits since the project was opened.
    pub edits: u64,
    /// The glTF assets, absolute.
    pub assets: Vec<PathBuf>,
    /// The authored scene.
    pub scene: SceneDesc,
    /// The render settings.
    pub render: RenderSettings,
}

impl RecoveryFile {
    /// The recovery of `project`, opened from `source`, after `edits` edits.
    pub fn of(project: &Project, source: Option<&Path>, edits: u64) -> Self {
        Self {
            recovery_version: RECOVERY_VERSION,
            project: source.map(absolute),
            saved_unix: 0,
            edits,
            assets: project.assets.iter().map(|a| absolute(a)).collect(),
            scene: project.scene.desc().clone(),
            render: project.render.clone(),
        }
    }

    /// The RON text, stamped with the current time.
    pub fn to_text(&self) -> Result<String, String> {
        let stamped = Self { saved_unix: now_unix(), ..self.clone() };
        let config = ron::ser::PrettyConfig::new().indentor("  ").struct_names(false);
        ron::ser::to_string_pretty(&stamped, config).map_err(|e| e.to_string())
    }

    /// Reads a recovery file (bounded like a project file).
    pub fn read(path: &Path) -> Result<Self, RecoveryError> {
        let text = crate::input_file::read_text(path, crate::input_file::Kind::Project)
            .map_err(|source| RecoveryError::Io { path: path.to_owned(), source })?;
        let file: Self =
            ron::from_str(&text).map_err(|e| RecoveryError::Parse { path: path.to_owned(), message: e.to_string() })?;
        if file.recovery_version != RECOVERY_VERSION {
            return Err(RecoveryError::Parse {
                path: path.to_owned(),
                message: format!("recovery_version {} (this build reads {RECOVERY_VERSION})", file.recovery_version),
            });
        }
        Ok(file)
    }

    /// The recovered project; `file` names the recovery file in errors.
    pub fn project(&self, file: &Path) -> Result<Project, RecoveryError> {
        Ok(Project::from_parts(file, self.assets.clone(), self.scene.clone(), self.render.clone())?)
    }

    /// "name.ron (folder)" or "an untitled project", for the dialog.
    pub fn describe(&self) -> String {
        match &self.project {
            Some(p) => format!(
                "{} (in {})",
                p.file_name().map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into_owned()),
                p.parent().map_or_else(String::new, |d| d.display().to_string())
            ),
            None => "an untitled project".to_owned(),
        }
    }
}

/// `p` made absolute and canonical where it exists.
fn absolute(p: &Path) -> PathBuf {
    crate::output_path::resolved(p)
}

/// Seconds since the Unix epoch.
pub fn now_unix() -> u64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs())
}

/// The key of a project's recovery files: its file stem and a hash of its canonical path, or
/// `untitled`.
pub fn key(project: Option<&Path>) -> String {
    let Some(p) = project else { return "untitled".to_owned() };
    let canonical = absolute(p);
    let hash = canonical
        .to_string_lossy()
        .bytes()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3));
    let stem: String = p
        .file_stem()
        .map(|s| s.to_string_lossy().chars().filter(|c| c.is_alphanumeric() || *c == '_').take(40).collect())
        .unwrap_or_default();
    format!("{stem}-{hash:016x}")
}

/// A name for this editor instance, unique among running ones (process id and a counter, so
/// two editors in one test process differ too).
pub fn instance_name() -> String {
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    // The start time too: a process id can come back after a reboot.
    let started = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis());
    format!("{}-{started}-{n}", std::process::id())
}

/// The recovery file and lock of `key` for `instance` in `dir`.
pub fn files(dir: &Path, key: &str, instance: &str) -> (PathBuf, PathBuf) {
    (dir.join(format!("{key}.{instance}.ron")), dir.join(format!("{key}.{instance}.lock")))
}

/// A held lock on a recovery file: while it lives no other instance offers or deletes the file.
#[derive(Debug)]
pub struct Lock {
    file: std::fs::File,
    path: PathBuf,
}

impl Lock {
    /// Takes the lock at `path` (creating it), or `None` if another instance holds it. A lock
    /// file that another editor removed between our open and our lock is opened again, so the
    /// lock held is always on the file the path names.
    pub fn try_take(path: &Path) -> std::io::Result<Option<Self>> {
        for _ in 0..8 {
            let file = std::fs::OpenOptions::new().create(true).truncate(false).read(true).write(true).open(path)?;
            match file.try_lock() {
                Ok(()) if same_file(&file, path) => return Ok(Some(Self { file, path: path.to_owned() })),
                Ok(()) => continue,
                Err(std::fs::TryLockError::WouldBlock) => return Ok(None),
                Err(std::fs::TryLockError::Error(e)) => return Err(e),
            }
        }
        Ok(None)
    }

    /// Releases the lock and removes its file.
    pub fn remove(self) {
        let _ = std::fs::remove_file(&self.path);
        let _ = self.file.unlock();
    }
}

/// Whether the open `file` is the file `path` names now (not one unlinked meanwhile).
#[cfg(unix)]
fn same_file(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_file: &std::fs::File, path: &Path) -> bool {
    path.exists()
}

/// Unsaved work an instance that is gone left behind, with its lock held while it is offered.
#[derive(Debug)]
pub struct Orphan {
    /// The recovery file.
    pub path: PathBuf,
    /// What it holds.
    pub file: RecoveryFile,
    lock: Lock,
}

impl Orphan {
    /// Deletes the file (after a restore or a discard).
    pub fn remove(self) {
        let _ = std::fs::remove_file(&self.path);
        self.lock.remove();
    }

    /// The dialog's text: whose work and when.
    pub fn message(&self) -> String {
        format!(
            "Bounce Lab found unsaved work on {} from a session that did not end cleanly: {}, saved {}.",
            self.file.describe(),
            edits_text(self.file.edits),
            describe_time(self.file.saved_unix, now_unix())
        )
    }
}

/// "1 edit", "3 edits".
pub fn edits_text(n: u64) -> String {
    format!("{n} edit{}", if n == 1 { "" } else { "s" })
}

/// Every recovery file in `dir` whose instance is gone, newest first, those of `prefer` (a
/// project key) before the others. Files that do not parse are logged and left alone.
pub fn orphans(dir: &Path, prefer: &str) -> Vec<Orphan> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    sweep_locks(&paths);
    let mut found: Vec<Orphan> = paths
        .into_iter()
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .filter_map(|path| {
            let lock = Lock::try_take(&path.with_extension("lock")).ok().flatten()?;
            match RecoveryFile::read(&path) {
                Ok(file) => Some(Orphan { path, file, lock }),
                Err(e) => {
                    log::warn!("ignoring a recovery file: {e}");
                    None
                }
            }
        })
        .collect();
    let prefer = format!("{prefer}.");
    found.sort_by_key(|o| {
        let name = o.path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        (!name.starts_with(&prefer), std::cmp::Reverse(o.file.saved_unix))
    });
    found
}

/// Removes lock files that guard nothing (their instance ended cleanly or was killed after a
/// save) and that no running instance holds.
fn sweep_locks(paths: &[PathBuf]) {
    for lock in paths.iter().filter(|p| p.extension().is_some_and(|x| x == "lock")) {
        if !lock.with_extension("ron").exists()
            && let Ok(Some(held)) = Lock::try_take(lock)
        {
            held.remove();
        }
    }
}

/// "2026-11-28 03:55 UTC, 12 minutes ago".
pub fn describe_time(unix: u64, now: u64) -> String {
    let days = unix / 86_400;
    let secs = unix % 86_400;
    let (y, m, d) = civil_from_days(days as i64);
    let ago = now.saturating_sub(unix);
    let ago = match ago {
        0..60 => "less than a minute ago".to_owned(),
        60..7200 => format!("{} minutes ago", ago / 60),
        7200..172_800 => format!("{} hours ago", ago / 3600),
        _ => format!("{} days ago", ago / 86_400),
    };
    format!("{y:04}-{m:02}-{d:02} {:02}:{:02} UTC, {ago}", secs / 3600, secs % 3600 / 60)
}

/// The proleptic Gregorian date of a day count since 1970-01-01 (Howard Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_read_as_dates() {
        assert_eq!(describe_time(0, 30), "1970-01-01 00:00 UTC, less than a minute ago");
        // 2026-11-28 03:55:00 UTC.
        assert_eq!(describe_time(1_795_838_100, 1_795_838_100 + 720), "2026-11-28 03:55 UTC, 12 minutes ago");
    }

    #[test]
    fn keys_differ_by_project_and_name_it() {
        let a = key(Some(Path::new("/tmp/a.ron")));
        let b = key(Some(Path::new("/tmp/b.ron")));
        assert_ne!(a, b);
        assert!(a.starts_with("a-"), "{a}");
        assert_eq!(key(None), "untitled");
        assert_eq!(key(Some(Path::new("/tmp/x/../a.ron"))), a, "canonical");
    }

    #[test]
    fn a_held_lock_hides_the_file_and_a_released_one_offers_it() {
        let dir = std::env::temp_dir().join(format!("bouncelab-recovery-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("dir");
        let (file, lock) = files(&dir, "a-1", "7-0");
        let held = Lock::try_take(&lock).expect("lock").expect("free");
        let project = Project {
            assets: Vec::new(),
            scene: crate::scene::Scene::new(SceneDesc::default(), Default::default()).expect("empty scene"),
            render: RenderSettings::default(),
            imported: Vec::new(),
        };
        let text = RecoveryFile::of(&project, Some(Path::new("/tmp/a.ron")), 3).to_text().expect("ron");
        std::fs::write(&file, text).expect("write");
        assert!(orphans(&dir, "a-1").is_empty(), "its instance still runs");
        drop(held);
        // A process another test forks in the meantime holds a copy of the lock's descriptor
        // until it execs: give it a moment.
        let mut found = orphans(&dir, "a-1");
        for _ in 0..20 {
            if !found.is_empty() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
            found = orphans(&dir, "a-1");
        }
        assert_eq!(found.len(), 1, "{:?}", RecoveryFile::read(&file).err());
        assert_eq!(found[0].file.edits, 3);
        assert!(found[0].message().contains("a.ron"), "{}", found[0].message());
        assert!(orphans(&dir, "a-1").is_empty(), "an offered file is locked by the offer");
        found.into_iter().for_each(Orphan::remove);
        assert_eq!(std::fs::read_dir(&dir).expect("dir").count(), 0, "file and lock removed");
    }
}
