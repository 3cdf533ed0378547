//! Autosave on a timer of its own: the editor hands every changed state to a writer thread,
//! which writes it to the project's recovery file [`QUIET`] after the last change, and at least
//! every [`MAX_WAIT`] while changes keep coming. An idle editor does not repaint, so a timer that
//! lived in the UI frame would never fire after the last edit; this one does. Writes are atomic.
//!
//! [`Autosave`] also owns the instance's lock on its recovery file (see [`super::recovery`]):
//! opening another project moves to that project's file, and saving removes only this
//! instance's file.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::recovery::{self, Lock, RecoveryFile};

/// How long after the last change the recovery file is written.
pub const QUIET: Duration = Duration::from_secs(2);
/// The longest unsaved changes wait while edits keep coming.
pub const MAX_WAIT: Duration = Duration::from_secs(10);

enum Msg {
    /// The current unsaved state for this file.
    Changed(PathBuf, Box<RecoveryFile>),
    /// Nothing unsaved any more: remove this file (and forget a pending write of it).
    Remove(PathBuf),
    /// Write what is pending now and answer whether it was written (tests, a restore).
    Flush(mpsc::Sender<bool>),
}

/// The recovery files of one editor instance and the thread that writes them.
pub struct Autosave {
    dir: PathBuf,
    instance: String,
    /// The project key, its recovery file and the lock held on it.
    current: Option<(String, PathBuf, Lock)>,
    /// The project file the key was computed for, and the key (a canonical path: not per frame).
    keyed: Option<(Option<PathBuf>, String)>,
    /// The history state last handed to the writer, and whether it was unsaved.
    sent: Option<(u64, bool)>,
    /// A key whose lock could not be taken (said once).
    refused: Option<String>,
    tx: mpsc::Sender<Msg>,
}

impl Autosave {
    /// Recovery files in `dir` (created if missing); `None` if the folder cannot be made.
    pub fn new(dir: PathBuf) -> Option<Self> {
        if let Err(e) = std::fs::create_dir_all(&dir) {
            log::warn!("no crash recovery: cannot create {}: {e}", dir.display());
            return None;
        }
        let (tx, rx) = mpsc::channel();
        let spawned = std::thread::Builder::new().name("autosave".into()).spawn(move || writer(&rx));
        if let Err(e) = spawned {
            log::warn!("no crash recovery: cannot start the autosave thread: {e}");
            return None;
        }
        Some(Self {
            dir,
            instance: recovery::instance_name(),
            current: None,
            keyed: None,
            sent: None,
            refused: None,
            tx,
        })
    }

    /// The folder the recovery files live in.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The recovery key of `source`, computed once per project file.
    fn key_of(&mut self, source: Option<&Path>) -> String {
        if let Some((p, k)) = &self.keyed
            && p.as_deref() == source
        {
            return k.clone();
        }
        let key = recovery::key(source);
        self.keyed = Some((source.map(Path::to_owned), key.clone()));
        key
    }

    /// This instance's recovery file for the project opened from `source` (its lock taken).
    fn file_for(&mut self, source: Option<&Path>) -> Option<PathBuf> {
        let key = self.key_of(source);
        if let Some((k, f, _)) = &self.current
            && *k == key
        {
            return Some(f.clone());
        }
        // The project changed without `leave` (a Save As to a new name): nothing is unsaved.
        self.leave();
        if self.refused.as_deref() == Some(key.as_str()) {
            return None;
        }
        let (file, lock_path) = recovery::files(&self.dir, &key, &self.instance);
        match Lock::try_take(&lock_path) {
            Ok(Some(lock)) => {
                self.current = Some((key, file.clone(), lock));
                self.sent = None;
                Some(file)
            }
            Ok(None) | Err(_) => {
                log::warn!("no crash recovery for this project: cannot lock {}", lock_path.display());
                self.refused = Some(key);
                None
            }
        }
    }

    /// The project this instance autosaved is being replaced (another is opened, a new one
    /// made, recovered work restored). Its last state is written first; work that was unsaved
    /// stays on disk with its lock released, so it is offered when that project is opened again
    /// (by this editor too); a clean project's file is removed. Later files get a new instance
    /// name, so the left work is never overwritten.
    pub fn leave(&mut self) {
        let Some((_, file, lock)) = self.current.take() else { return };
        let unsaved = self.sent.is_some_and(|(_, dirty)| dirty);
        if unsaved {
            self.flush();
            self.instance = recovery::instance_name();
        } else {
            let _ = self.tx.send(Msg::Remove(file));
            self.flush();
        }
        drop(lock);
        self.sent = None;
    }

    /// Called every UI frame: hands the state to the writer when it changed (`state_id` is the
    /// undo history's state), or has the file removed once nothing is unsaved.
    pub fn track(&mut self, project: &crate::project_file::Project, source: Option<&Path>, history: &History) {
        let Some(file) = self.file_for(source) else { return };
        if self.sent.is_some_and(|(id, _)| id == history.state_id) {
            return;
        }
        self.sent = Some((history.state_id, history.dirty));
        let msg = if history.dirty {
            Msg::Changed(file, Box::new(RecoveryFile::of(project, source, history.edits)))
        } else {
            Msg::Remove(file)
        };
        let _ = self.tx.send(msg);
    }

    /// The project was saved (or the work discarded): remove this instance's file, and only it.
    pub fn saved(&mut self) {
        if let Some((_, file, _)) = &self.current {
            let _ = self.tx.send(Msg::Remove(file.clone()));
        }
        self.sent = None;
    }

    /// A clean exit: removes this instance's recovery file and its lock, and waits for that.
    pub fn close(&mut self) {
        self.saved();
        self.flush();
        if let Some((_, _, lock)) = self.current.take() {
            lock.remove();
        }
    }

    /// Writes whatever is pending now and waits for it (a restore, tests); false if a write
    /// failed or the writer did not answer.
    pub fn flush(&self) -> bool {
        let (tx, rx) = mpsc::channel();
        self.tx.send(Msg::Flush(tx)).is_ok() && rx.recv_timeout(Duration::from_secs(10)).unwrap_or(false)
    }

    /// This instance's current recovery file, if it has one.
    pub fn current_file(&self) -> Option<&Path> {
        self.current.as_ref().map(|(_, f, _)| f.as_path())
    }
}

/// What [`Autosave::track`] reads of the undo history.
pub struct History {
    /// Identifies the authored state (changes with every edit, undo and redo).
    pub state_id: u64,
    /// The state differs from the saved one.
    pub dirty: bool,
    /// Undoable edits.
    pub edits: u64,
}

/// The writer thread: waits for changes and writes each file's latest state on the timer. It
/// ends when the editor drops its [`Autosave`], writing what is pending first (a clean exit
/// removed it already; an editor unwinding from a panic keeps its last edits).
fn writer(rx: &mpsc::Receiver<Msg>) {
    let mut pending: Option<(PathBuf, Box<RecoveryFile>)> = None;
    let (mut first, mut last) = (Instant::now(), Instant::now());
    loop {
        let msg = match &pending {
            None => rx.recv().map_err(|_| mpsc::RecvTimeoutError::Disconnected),
            Some(_) => {
                let due = (last + QUIET).min(first + MAX_WAIT);
                rx.recv_timeout(due.saturating_duration_since(Instant::now()))
            }
        };
        match msg {
            Ok(Msg::Changed(file, body)) => {
                if pending.as_ref().is_none_or(|(f, _)| *f != file) {
                    let _ = write_pending(&mut pending);
                    first = Instant::now();
                }
                last = Instant::now();
                pending = Some((file, body));
            }
            Ok(Msg::Remove(file)) => {
                if pending.as_ref().is_some_and(|(f, _)| *f == file) {
                    pending = None;
                }
                let _ = std::fs::remove_file(&file);
            }
            Ok(Msg::Flush(done)) => {
                let _ = done.send(write_pending(&mut pending));
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                write_pending(&mut pending);
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                write_pending(&mut pending);
                return;
            }
        }
    }
}

/// Writes the pending state, if any; false if the write failed.
fn write_pending(pending: &mut Option<(PathBuf, Box<RecoveryFile>)>) -> bool {
    let Some((file, body)) = pending.take() else { return true };
    let written =
        body.to_text().map_err(std::io::Error::other).and_then(|t| crate::atomic_file::write(&file, t.as_bytes()));
    match written {
        Ok(()) => {
            log::debug!("autosaved {}", file.display());
            true
        }
        Err(e) => {
            log::warn!("autosave to {} failed: {e}", file.display());
            false
        }
    }
}
