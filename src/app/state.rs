//! The editor's state outside egui: the open project, its path, undo history, selection, and
//! the status line. Panels borrow it mutably, one at a time.

use std::path::{Path, PathBuf};

use super::edits::Selection;
use super::history::History;
use crate::project_file::{Project, ProjectError, is_default_project};

/// What the editor is working on.
pub struct EditorState {
    /// The open project.
    pub project: Project,
    /// Where it is saved (`None` for a new, unsaved project or an opened glTF).
    pub path: Option<PathBuf>,
    /// The file it was opened from (a project or a glTF; `None` for a new one): its crash
    /// recovery file is keyed by this.
    pub opened: Option<PathBuf>,
    /// `path` is the shipped default project: Save asks for a new path rather than writing
    /// into the install.
    pub read_only: bool,
    /// Edits restored from a recovery file, which the (cleared) undo history does not count;
    /// a later recovery file adds them to its own count.
    pub carried_edits: u64,
    /// Undo and redo.
    pub history: History,
    /// Current selection.
    pub selection: Selection,
    /// Last status or error message for the status bar.
    pub status: String,
    /// Recently opened files, newest first.
    pub recent: Vec<PathBuf>,
    /// `sshgi`'s known limitation measured on the view (the GI panel shows it).
    pub unseen: super::unseen::UnseenProbe,
}

impl EditorState {
    /// State for `project` opened from `path`.
    pub fn new(project: Project, path: Option<PathBuf>) -> Self {
        let read_only = path.as_deref().is_some_and(is_default_project);
        Self {
            project,
            opened: path.clone(),
            path,
            read_only,
            carried_edits: 0,
            history: History::default(),
            selection: Selection::None,
            status: String::new(),
            recent: Vec::new(),
            unseen: super::unseen::UnseenProbe::default(),
        }
    }

    /// Title-bar text: file name and a dirty marker.
    pub fn title(&self) -> String {
        let name = self
            .path
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or("untitled".into(), |n| n.to_string_lossy().into_owned());
        let read_only = if self.read_only { " (read-only: Save asks for a new name)" } else { "" };
        format!("{}{}{read_only} — Bounce Lab", name, if self.history.is_dirty() { " *" } else { "" })
    }

    /// Opens a project or glTF file, replacing the current one.
    pub fn open(&mut self, path: &Path) -> Result<(), ProjectError> {
        let project = Project::open(path)?;
        self.open_loaded(path, project)
    }

    /// Replaces the current project with `project`, loaded from `path`.
    pub fn open_loaded(&mut self, path: &Path, project: Project) -> Result<(), ProjectError> {
        let is_project = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ron"));
        self.project = project;
        self.path = is_project.then(|| path.to_owned());
        self.opened = Some(path.to_owned());
        self.read_only = is_project && is_default_project(path);
        self.carried_edits = 0;
        self.history.clear();
        self.selection = Selection::None;
        self.remember(path);
        self.status = format!("opened {}", path.display());
        Ok(())
    }

    /// Saves to `path` (atomically) and makes it the project's path. The shipped default
    /// project is never written: saving onto it is refused.
    pub fn save_as(&mut self, path: &Path) -> Result<(), ProjectError> {
        if is_default_project(path) {
            return Err(ProjectError::Io {
                path: path.to_owned(),
                source: std::io::Error::new(
                    std::io::ErrorKind::PermissionDenied,
                    "this is the shipped default project, which is never overwritten: save under another name",
                ),
            });
        }
        self.project.save(path)?;
        self.path = Some(path.to_owned());
        self.opened = Some(path.to_owned());
        self.read_only = false;
        self.carried_edits = 0;
        self.history.mark_saved();
        self.remember(path);
        self.status = format!("saved {}", path.display());
        Ok(())
    }

    /// Replaces the project with recovered work that belongs to `source` (its own file, never
    /// the one open before); the work counts as unsaved.
    pub fn restore(&mut self, project: Project, source: Option<PathBuf>, edits: u64) {
        self.carried_edits = edits;
        let is_project =
            source.as_deref().is_some_and(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ron")));
        self.project = project;
        self.path = source.clone().filter(|_| is_project);
        self.read_only = self.path.as_deref().is_some_and(is_default_project);
        self.opened = source;
        self.history.clear();
        self.history.mark_unsaved();
        self.selection = Selection::None;
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
