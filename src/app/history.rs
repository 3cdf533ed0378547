//! Undo and redo of every edit, as snapshots of the authored state (scene description and
//! render settings). Snapshots make undo exact by construction: undoing every edit gives back
//! the original project byte for byte. A property drag is one step: `begin` takes the snapshot
//! when the drag starts, `commit` records it when the drag ends (if anything changed).
//! Pure (no egui), so it is tested directly.

use std::sync::Arc;

use crate::import::Asset;
use crate::project_file::Project;
use crate::scene::SceneDesc;
use crate::settings::RenderSettings;

/// The authored state one undo step restores.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// Objects, materials, lights, camera.
    pub desc: SceneDesc,
    /// GI mode and settings.
    pub render: RenderSettings,
    /// The imported assets, kept only by the steps that change them (a live reload), so that
    /// undoing one gives back the geometry the description's mesh sources name. Not compared:
    /// a step is an authored change.
    pub imported: Option<Arc<Vec<Asset>>>,
}

impl PartialEq for Snapshot {
    fn eq(&self, other: &Self) -> bool {
        self.desc == other.desc && self.render == other.render
    }
}

impl Snapshot {
    /// The current state of `project`.
    pub fn of(project: &Project) -> Self {
        Self { desc: project.scene.desc().clone(), render: project.render.clone(), imported: None }
    }

    /// The current state of `project` with its imported assets (before a step that replaces
    /// them).
    pub fn with_assets(project: &Project) -> Self {
        Self { imported: Some(Arc::new(project.imported.clone())), ..Self::of(project) }
    }
}

struct Entry {
    label: String,
    state: Snapshot,
    id: u64,
}

/// The undo and redo stacks plus the saved-state marker.
#[derive(Default)]
pub struct History {
    undo: Vec<Entry>,
    redo: Vec<Entry>,
    pending: Option<(String, Snapshot)>,
    current_id: u64,
    next_id: u64,
    saved_id: u64,
}

/// Upper bound on undo steps kept.
const MAX_STEPS: usize = 500;

impl History {
    /// Starts an edit (e.g. a drag) whose before-state is the project's current state. A second
    /// `begin` before `commit` keeps the first snapshot, so a whole drag is one step.
    pub fn begin(&mut self, label: &str, project: &Project) {
        if self.pending.is_none() {
            self.pending = Some((label.to_owned(), Snapshot::of(project)));
        }
    }

    /// Ends the edit started by `begin`; records a step if the state changed.
    pub fn commit(&mut self, project: &Project) {
        if let Some((label, before)) = self.pending.take()
            && before != Snapshot::of(project)
        {
            self.push(label, before);
        }
    }

    /// Records a finished edit whose before-state is `before`. An edit still open (`begin`
    /// without `commit`: the GI panel commits on the next idle frame) ends at `before` and is
    /// recorded first, so both stay separate steps in the order they happened.
    pub fn record(&mut self, label: &str, before: Snapshot, project: &Project) {
        if let Some((open, open_before)) = self.pending.take()
            && open_before != before
        {
            self.push(open, open_before);
        }
        if before != Snapshot::of(project) {
            self.push(label.to_owned(), before);
        }
    }

    fn push(&mut self, label: String, before: Snapshot) {
        self.undo.push(Entry { label, state: before, id: self.current_id });
        if self.undo.len() > MAX_STEPS {
            self.undo.remove(0);
        }
        self.redo.clear();
        self.next_id += 1;
        self.current_id = self.next_id;
    }

    fn restore(project: &mut Project, state: Snapshot) {
        project.render = state.render;
        let restored = match state.imported {
            Some(imported) => project.set_desc_and_assets(state.desc, imported.as_ref().clone()),
            None => project.set_desc(state.desc),
        };
        if let Err(e) = restored {
            // Snapshots were valid when taken; a failure here is a bug, reported not hidden.
            log::error!("undo/redo could not restore the scene: {e}");
        }
    }

    /// The project's state to keep for the way back from restoring `to`: with the assets when
    /// `to` replaces them.
    fn current(project: &Project, to: &Snapshot) -> Snapshot {
        if to.imported.is_some() { Snapshot::with_assets(project) } else { Snapshot::of(project) }
    }

    /// Undoes the last step; returns its label.
    pub fn undo(&mut self, project: &mut Project) -> Option<String> {
        self.commit(project);
        let entry = self.undo.pop()?;
        let current = Self::current(project, &entry.state);
        self.redo.push(Entry { label: entry.label.clone(), state: current, id: self.current_id });
        self.current_id = entry.id;
        Self::restore(project, entry.state);
        Some(entry.label)
    }

    /// Redoes the last undone step; returns its label.
    pub fn redo(&mut self, project: &mut Project) -> Option<String> {
        // An open edit that changed something is a new step, which ends the redo branch.
        self.commit(project);
        let entry = self.redo.pop()?;
        let current = Self::current(project, &entry.state);
        self.undo.push(Entry { label: entry.label.clone(), state: current, id: self.current_id });
        self.current_id = entry.id;
        Self::restore(project, entry.state);
        Some(entry.label)
    }

    /// Label of the step `undo` would revert.
    pub fn undo_label(&self) -> Option<&str> {
        self.undo.last().map(|e| e.label.as_str())
    }

    /// Label of the step `redo` would apply.
    pub fn redo_label(&self) -> Option<&str> {
        self.redo.last().map(|e| e.label.as_str())
    }

    /// Marks the current state as saved.
    pub fn mark_saved(&mut self) {
        self.saved_id = self.current_id;
    }

    /// Whether the state differs from the last save.
    pub fn is_dirty(&self) -> bool {
        self.current_id != self.saved_id
    }

    /// Identifies the authored state: it changes with every recorded edit, undo and redo, and
    /// returns to an earlier value only when the state does (the autosave watches it).
    pub fn state_id(&self) -> u64 {
        self.current_id
    }

    /// How many undoable edits there are.
    pub fn steps(&self) -> usize {
        self.undo.len()
    }

    /// Makes the current state count as unsaved (restored work, not yet in its file).
    pub fn mark_unsaved(&mut self) {
        self.next_id += 1;
        self.saved_id = self.next_id;
    }

    /// Forgets everything (a new or reopened project). State ids keep counting, so a cleared
    /// history never repeats an id an observer (the autosave) has seen.
    pub fn clear(&mut self) {
        let id = self.next_id + 1;
        *self = Self { current_id: id, next_id: id, saved_id: id, ..Self::default() };
    }
}
