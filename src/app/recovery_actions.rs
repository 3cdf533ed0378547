//! The editor's side of crash recovery: offering another instance's orphaned work, restoring it
//! into the project it belongs to, and leaving a project without losing its unsaved edits. The
//! files and their locks are [`super::recovery`]; the writer thread is [`super::autosave`].

use std::path::PathBuf;

use super::{EditorApp, Modal, autosave, recovery};

impl EditorApp {
    /// The recovery dialog's text, if it is open (tests).
    pub fn recovery_offered(&self) -> Option<String> {
        (self.modal == Modal::OfferRecovery).then(|| self.offers.first().map(recovery::Orphan::message)).flatten()
    }

    /// This instance's recovery file, and waits until what is pending is written (tests).
    pub fn flush_autosave(&self) -> Option<PathBuf> {
        let a = self.autosave.as_ref()?;
        a.flush();
        a.current_file().map(std::path::Path::to_owned)
    }

    /// The open project is about to be replaced: its autosave writes its last state, and work
    /// that was unsaved stays on disk to be offered again (see `Autosave::leave`).
    pub(super) fn leave_project(&mut self) {
        let view = self.autosave_view();
        if let Some(a) = &mut self.autosave {
            a.track(&self.state.project, self.state.opened.as_deref(), &view);
            a.leave();
        }
    }

    /// Queues the orphaned recovery files of the project at `path`.
    pub(super) fn offer_recovery_of(&mut self, path: &std::path::Path) {
        let Some(a) = &self.autosave else { return };
        let key = recovery::key(Some(path));
        let prefix = format!("{key}.");
        let held: Vec<PathBuf> = self.offers.iter().map(|o| o.path.clone()).collect();
        let new = recovery::orphans(a.dir(), &key).into_iter().filter(|o| {
            o.path.file_name().is_some_and(|n| n.to_string_lossy().starts_with(&prefix)) && !held.contains(&o.path)
        });
        self.offers.extend(new);
        if !self.offers.is_empty() && self.modal == Modal::None {
            self.modal = Modal::OfferRecovery;
        }
    }

    /// Restores the first offered recovery into the project it belongs to, or discards it.
    pub fn answer_recovery(&mut self, restore: bool) {
        if self.offers.is_empty() {
            self.modal = Modal::None;
            return;
        }
        let offer = self.offers.remove(0);
        if restore {
            match offer.file.project(&offer.path) {
                Ok(project) => {
                    self.leave_project();
                    self.state.restore(project, offer.file.project.clone(), offer.file.edits);
                    self.state.status =
                        format!("restored {} of {}", recovery::edits_text(offer.file.edits), offer.file.describe());
                    self.viewport.reset_orbit(&self.state);
                    // This instance's own recovery file holds the work before the old one goes.
                    let view = self.autosave_view();
                    let kept = self.autosave.as_mut().is_some_and(|a| {
                        a.track(&self.state.project, self.state.opened.as_deref(), &view);
                        a.flush() && a.current_file().is_some_and(std::path::Path::exists)
                    });
                    if kept {
                        offer.remove();
                    } else {
                        log::warn!("kept {}: the restored work could not be autosaved yet", offer.path.display());
                    }
                }
                // The file stays for a later try (an asset may be on a drive not mounted now).
                Err(e) => self.state.report("recovery failed", &e),
            }
        } else {
            offer.remove();
        }
        self.modal = if self.offers.is_empty() { Modal::None } else { Modal::OfferRecovery };
    }

    /// What the autosave reads of the history.
    pub(super) fn autosave_view(&self) -> autosave::History {
        let h = &self.state.history;
        let edits = self.state.carried_edits + h.steps() as u64;
        autosave::History { state_id: h.state_id(), dirty: h.is_dirty(), edits }
    }

    /// The dialog offering the first orphaned recovery.
    pub(super) fn recovery_dialog(&mut self, ui: &egui::Ui) {
        let Some(message) = self.offers.first().map(recovery::Orphan::message) else {
            self.modal = Modal::None;
            return;
        };
        egui::Modal::new(egui::Id::unique("recovery")).show(ui.ctx(), |ui| {
            ui.label(message);
            ui.label("Restore opens that project with the work; Discard deletes the work.");
            ui.horizontal(|ui| {
                if ui.button("Restore").clicked() {
                    self.answer_recovery(true);
                }
                if ui.button("Discard").clicked() {
                    self.answer_recovery(false);
                }
            });
        });
    }

    /// Before per-project recovery files, one `recovery.ron` in the data folder served every
    /// project; it is a plain project file (assets relative to it), so File → Open restores it.
    pub(super) fn note_legacy_recovery(&mut self, data: &std::path::Path) {
        let legacy = data.join("recovery.ron");
        if legacy.is_file() {
            let message = format!(
                "An older Bounce Lab left unsaved work in {}: open it with File → Open to restore it (the project it belongs to is not recorded), then delete it.",
                legacy.display()
            );
            log::warn!("{message}");
            self.state.status = message;
        }
    }
}
