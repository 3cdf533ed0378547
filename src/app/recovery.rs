//! Autosave to a recovery file while there are unsaved changes, and the offer to restore it
//! after a crash. The file lives in the user's data folder, never next to the user's project,
//! and is removed on save and on a clean exit.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::project_file::Project;

/// How often unsaved work is written.
const INTERVAL: Duration = Duration::from_secs(30);

/// The recovery file and its timer.
pub struct Recovery {
    path: PathBuf,
    last: Instant,
}

impl Recovery {
    /// The recovery location in the platform's data folder (`None` if there is none).
    pub fn new() -> Option<Self> {
        let dir = eframe::storage_dir("Bounce Lab")?;
        std::fs::create_dir_all(&dir).ok()?;
        Some(Self { path: dir.join("recovery.ron"), last: Instant::now() })
    }

    /// A recovery file left by an earlier session, if any.
    pub fn pending(&self) -> Option<PathBuf> {
        self.path.exists().then(|| self.path.clone())
    }

    /// Writes the project if the interval has passed.
    pub fn maybe_save(&mut self, project: &Project) {
        if self.last.elapsed() < INTERVAL {
            return;
        }
        self.last = Instant::now();
        if let Err(e) = project.save(&self.path) {
            log::warn!("autosave failed: {e}");
        }
    }

    /// Removes the recovery file.
    pub fn clear(&self) {
        let _ = std::fs::remove_file(&self.path);
    }
}
