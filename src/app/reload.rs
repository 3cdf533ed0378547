//! Live reload: the editor watches the glTF files the project reads (the assets and the buffers
//! and images they name) and, when one changes on disk, reloads that asset into the project
//! ([`crate::project_file::Project::reload_asset`]: the file's geometry and materials, every
//! authored light, block, weight and edit kept). A change is acted on once the file has been
//! quiet for [`SETTLE`] (an exporter writes in pieces); a file that does not import yet (caught
//! half-written) is tried again every [`RETRY`] for up to [`RETRIES`] times, and the project is
//! never changed by a broken file.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

use notify::Watcher as _;

/// How long a file must be quiet before it is read.
pub const SETTLE: Duration = Duration::from_millis(200);
/// How long to wait before reading a file again that did not import.
pub const RETRY: Duration = Duration::from_millis(500);
/// How often a file that does not import is tried before the editor gives up on that change.
pub const RETRIES: u32 = 20;

/// Watches a set of files through their folders (an exporter that writes a new file and
/// renames it over the old one is seen too).
#[derive(Default)]
pub struct FileWatcher {
    watcher: Option<notify::RecommendedWatcher>,
    events: Option<Receiver<notify::Result<notify::Event>>>,
    /// The files watched as the project names them, and canonical.
    given: Vec<PathBuf>,
    files: Vec<PathBuf>,
    /// Changed files: when to read them next, and how many reads failed.
    due: HashMap<PathBuf, (Instant, u32)>,
    /// Why watching failed, once (the editor works on without live reload).
    pub problem: Option<String>,
}

fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_owned())
}

impl FileWatcher {
    /// Watches exactly `files` (a no-op when they are already the ones watched; called every
    /// frame, so it compares without copying or touching the file system, and a watcher that
    /// could not start is not tried again until the files change). Every change asks `ctx` for
    /// a repaint from the watcher's thread, so an idle window notices.
    pub fn watch<'a>(&mut self, files: impl Iterator<Item = &'a Path> + Clone, ctx: &egui::Context) {
        if self.given.iter().map(PathBuf::as_path).eq(files.clone()) {
            return;
        }
        self.given = files.map(Path::to_owned).collect();
        self.files = self.given.iter().map(|f| canonical(f)).collect();
        self.due.clear();
        let mut folders: Vec<PathBuf> = self.files.iter().filter_map(|f| f.parent().map(Path::to_owned)).collect();
        folders.sort();
        folders.dedup();
        let (tx, rx) = channel();
        let wake = ctx.clone();
        let watcher = notify::recommended_watcher(move |event| {
            let _ = tx.send(event);
            wake.request_repaint_after(SETTLE);
        });
        let mut watcher = match watcher {
            Ok(w) => w,
            Err(e) => {
                self.problem = Some(format!("live reload is off: {e}"));
                return;
            }
        };
        for folder in &folders {
            if let Err(e) = watcher.watch(folder, notify::RecursiveMode::NonRecursive) {
                self.problem = Some(format!("live reload is off for {}: {e}", folder.display()));
            }
        }
        self.watcher = Some(watcher);
        self.events = Some(rx);
    }

    /// The watched files that changed and have been quiet for [`SETTLE`] (or are due to be
    /// tried again), each with the number of failed reads of this change so far.
    pub fn poll(&mut self) -> Vec<(PathBuf, u32)> {
        let now = Instant::now();
        if let Some(rx) = &self.events {
            while let Ok(event) = rx.try_recv() {
                let Ok(event) = event else { continue };
                if matches!(event.kind, notify::EventKind::Access(_)) {
                    continue;
                }
                for path in event.paths {
                    let path = canonical(&path);
                    if self.files.contains(&path) {
                        // Every new write starts the wait (and the retries) afresh.
                        self.due.insert(path, (now + SETTLE, 0));
                    }
                }
            }
        }
        let ready: Vec<(PathBuf, u32)> =
            self.due.iter().filter(|(_, (at, _))| *at <= now).map(|(p, (_, n))| (p.clone(), *n)).collect();
        for (path, _) in &ready {
            self.due.remove(path);
        }
        ready
    }

    /// `path` did not import for the `failures`-th time: try it again after [`RETRY`]; false
    /// once it has failed [`RETRIES`] times (the change is dropped until the file changes again).
    pub fn retry(&mut self, path: &Path, failures: u32) -> bool {
        if failures >= RETRIES {
            return false;
        }
        self.due.insert(path.to_owned(), (Instant::now() + RETRY, failures));
        true
    }

    /// How long until the next change is due to be read, if one is waiting.
    pub fn next_due(&self) -> Option<Duration> {
        let now = Instant::now();
        self.due.values().map(|(at, _)| at.saturating_duration_since(now)).min()
    }
}
