//! The editor's state outside egui: the open project, its path, undo history, selection, and
//! the status line. Panels borrow it mutably, one at a time.

use std::path::{Path, PathBuf};

use super::edits::Selection;
use super::history::History;
use crate::project_file::{Project, ProjectError};

/// What the editor is working on.
pub struct EditorState {
    /// The open project.
    pub project: Project,
    /// Where it is saved (`None` for a new, unsaved project or an opened glTF).
    pub path: Option<PathBuf>,
    /// Undo and redo.
    pub history: History,
    /// Current selection.
    pub selection: Selection,
    /// Last status or error message for the status bar.
    pub status: String,
    /// Recently opened files, newest first.
    pub recent: Vec<PathBuf>,
}

impl EditorState {
    /// State for `project` opened from `path`.
    pub fn new(project: Project, path: Option<PathBuf>) -> Self {
        Self {
            project,
            path,
            history: History::default(),
            selection: Selection::None,
            status: String::new(),
            recent: Vec::new(),
        }
    }

    /// Title-bar text: file name and a dirty marker.
    pub fn title(&self) -> String {
        let name = self
            .path
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or("untitled".into(), |n| n.to_string_lossy().into_owned());
        format!("{}{} — Bounce Lab", name, if self.history.is_dirty() { " *" } else { "" })
    }

    /// Opens a project or glTF file, replacing the current one.
    pub fn open(&mut self, path: &Path) -> Result<(), ProjectError> {
        let project = Project::open(path)?;
        let is_project = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ron"));
        self.project = project;
        self.path = is_project.then(|| path.to_owned());
        self.history.clear();
        self.selection = Selection::None;
        self.remember(path);
        self.status = format!("opened {}", path.display());
        Ok(())
    }

    /// Saves to `path` (atomically) and makes it the project's path.
    pub fn save_as(&mut self, path: &Path) -> Result<(), ProjectError> {
        self.project.save(path)?;
        self.path = Some(path.to_owned());
        self.history.mark_saved();
        self.remember(path);
        self.status = format!("saved {}", path.display());
        Ok(())
    }

    fn remember(&mut self, path: &Path) {
        self.recent.retain(|p| p != path);
        self.recent.insert(0, path.to_owned());
        self.recent.truncate(10);
    }

    /// Shows an error in the status bar and the log.
    pub fn report(&mut self, what: &str, error: &dyn std::fmt::Display) {
        log::error!("{what}: {error}");
        self.status = format!("{what}: {error}");
    }
}
