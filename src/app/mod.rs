//! The editor (eframe + egui; the only place besides `ui` where egui lives).
//!
//! Docking panes (egui_tiles) around the viewport: outliner, properties, GI panel, buffer
//! inspector with the reference comparison, timings, log. Every edit is an undoable step; the
//! layout and recent files persist in eframe's storage, apart from project files; unsaved work
//! is autosaved to a recovery file that is offered back after a crash.
//!
//! The viewport's renderer draws into its own HDR and depth targets, on a second device of the
//! same adapter; each finished display image is copied back and uploaded as an egui texture, so
//! the interface never waits for a GI frame (see [`preview`]).

mod autosave;
pub mod edits;
mod gi_ism;
mod gi_mrt;
mod gi_panel;
mod gi_rcs;
mod gi_sshgi;
mod gi_vo;
pub mod gizmo;
pub mod history;
mod inspector;
mod orbit;
mod outliner;
mod overlays;
mod panes;
pub mod pick;
pub mod preview;
mod properties;
pub mod recovery;
mod recovery_actions;
mod reload;
mod sky_panel;
mod startup;
pub mod state;
mod timings;
mod unseen;
mod viewport;
mod writes;

pub use orbit::Orbit;
pub use panes::Pane;
use startup::empty_project;
pub use startup::{Startup, open_or_fallback};

use std::path::PathBuf;
use std::sync::Arc;

use crate::project_file::{Project, default_project_path};
use crate::render::device_descriptor;
use edits::Selection;
pub use preview::GpuMemory;
use state::EditorState;

/// Keys of the persisted UI state.
const TREE_KEY: &str = "bouncelab.layout";
const RECENT_KEY: &str = "bouncelab.recent";
const PREVIEW_KEY: &str = "bouncelab.preview";

/// Opens the editor window on `project` (the default project if `None`), a glTF read with
/// `options` where given (`--light-units`).
pub fn run(project: Option<PathBuf>, options: Option<crate::import::ImportOptions>) -> anyhow::Result<()> {
    let path = project.unwrap_or_else(default_project_path);
    let Startup { project, path, opened, error } = open_or_fallback(&path, options)?;
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = Arc::new(device_descriptor);
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1400.0, 860.0]).with_title("Bounce Lab"),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    };
    eframe::run_native(
        "Bounce Lab",
        options,
        Box::new(move |cc| {
            let mut app = EditorApp::new(cc, project, path);
            app.state_mut().opened = opened;
            if let Some(e) = error {
                app.show_error(e);
            }
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the editor window: {e}"))
}

/// A dialog the editor is showing.
#[derive(Clone, Debug, PartialEq)]
enum Modal {
    None,
    /// Unsaved changes and the user asked to close.
    ConfirmClose,
    /// Work that a crashed or killed instance left unsaved (`EditorApp::offers`' first).
    OfferRecovery,
    /// Something the user must read (a project that could not be opened at start).
    Error(String),
}

/// The editor application.
pub struct EditorApp {
    state: EditorState,
    viewport: viewport::Viewport,
    inspector: inspector::Inspector,
    tree: egui_tiles::Tree<Pane>,
    modal: Modal,
    allow_close: bool,
    /// This instance's recovery files and their writer (`None` without a data folder).
    autosave: Option<autosave::Autosave>,
    /// Unsaved work of instances that are gone, offered one at a time (their locks held).
    offers: Vec<recovery::Orphan>,
    /// The window title last sent.
    title: String,
    /// Watches the project's glTF files for live reload.
    watcher: reload::FileWatcher,
}

impl EditorApp {
    /// Creates the app; the renderer is created on eframe's wgpu device. Without eframe storage
    /// (tests) nothing is persisted and no recovery file is written.
    pub fn new(cc: &eframe::CreationContext<'_>, project: Project, path: Option<PathBuf>) -> Self {
        let data = cc.storage.is_some().then(|| eframe::storage_dir("Bounce Lab")).flatten();
        let mut app = Self::with_recovery(cc, project, path, data.as_ref().map(|d| d.join("recovery")));
        if let Some(data) = data {
            app.note_legacy_recovery(&data);
        }
        app
    }

    /// [`EditorApp::new`] with crash recovery files in `recovery_dir` (tests give a temporary
    /// folder; `None`: no recovery).
    pub fn with_recovery(
        cc: &eframe::CreationContext<'_>,
        project: Project,
        path: Option<PathBuf>,
        recovery_dir: Option<PathBuf>,
    ) -> Self {
        let mut state = EditorState::new(project, path);
        let tree = cc.storage.and_then(|s| eframe::get_value(s, TREE_KEY)).unwrap_or_else(panes::default_tree);
        if let Some(recent) = cc.storage.and_then(|s| eframe::get_value::<Vec<PathBuf>>(s, RECENT_KEY)) {
            state.recent = recent;
        }
        let autosave = recovery_dir.and_then(autosave::Autosave::new);
        let offers = autosave
            .as_ref()
            .map(|a| recovery::orphans(a.dir(), &recovery::key(state.opened.as_deref())))
            .unwrap_or_default();
        let modal = if offers.is_empty() { Modal::None } else { Modal::OfferRecovery };
        let mut viewport = viewport::Viewport::new(&cc.egui_ctx, cc.wgpu_render_state.as_ref(), &state);
        if let Some(p) = cc.storage.and_then(|s| eframe::get_value::<preview::PreviewSettings>(s, PREVIEW_KEY)) {
            viewport.preview = p;
        }
        Self {
            state,
            viewport,
            inspector: inspector::Inspector::default(),
            tree,
            modal,
            allow_close: false,
            autosave,
            offers,
            title: String::new(),
            watcher: reload::FileWatcher::default(),
        }
    }

    /// Shows `message` in a dialog until the user dismisses it (and in the status bar).
    pub fn show_error(&mut self, message: String) {
        self.state.status = message.lines().next().unwrap_or_default().to_owned();
        self.modal = Modal::Error(message);
    }

    /// What the viewport's GPU device holds (soak tests; the timings pane).
    pub fn viewport_gpu_memory(&self) -> Option<GpuMemory> {
        self.viewport.gpu_memory()
    }

    /// Destroys the viewport's GPU device as a driver reset would (tests; the View menu).
    pub fn simulate_device_loss(&mut self) {
        self.viewport.simulate_device_loss();
    }

    /// The message of the error dialog, if one is open (tests).
    pub fn error_shown(&self) -> Option<&str> {
        match &self.modal {
            Modal::Error(m) => Some(m),
            _ => None,
        }
    }

    /// Shows buffer `name` in the inspector (tests; the combo box does the same).
    pub fn inspect(&mut self, name: &str) {
        self.inspector.select(name);
    }

    /// The inspected buffer's name and the size of its last read-back image.
    pub fn inspected(&self) -> (String, Option<(u32, u32)>) {
        let (name, img) = self.inspector.shown();
        (name.to_owned(), img.map(|i| (i.width, i.height)))
    }

    /// Where the viewport image was drawn last frame (tests aim the gizmo with it).
    pub fn viewport_rect(&self) -> Option<egui::Rect> {
        self.viewport.rect
    }

    /// The viewport's renderer (tests read its technique state). Its blocking reads wait for
    /// the frame in flight; [`EditorApp::wait_viewport`] first.
    pub fn renderer(&self) -> Option<&crate::render::Renderer> {
        self.viewport.renderer()
    }

    /// Waits for the viewport's frame in flight and shows it (tests).
    pub fn wait_viewport(&mut self) {
        if let Err(e) = self.viewport.wait() {
            self.state.report("render failed", &e);
        }
    }

    /// The render scale of the image in the viewport (1.0: full resolution).
    pub fn viewport_scale(&self) -> Option<f32> {
        self.viewport.shown_scale()
    }

    /// Whether the viewport has no frame in flight.
    pub fn viewport_idle(&self) -> bool {
        self.viewport.idle()
    }

    /// The duration of the last finished viewport frame, submit to image (ms).
    pub fn viewport_last_frame_ms(&self) -> f64 {
        self.viewport.last_frame_ms
    }

    /// The viewport's frame budget and adaptive scale.
    pub fn preview_settings_mut(&mut self) -> &mut preview::PreviewSettings {
        &mut self.viewport.preview
    }

    /// Finished viewport frames so far, and the slowest of the last `n` interface frames (ms).
    pub fn viewport_frames(&self, n: usize) -> (u64, f64) {
        (self.viewport.frames, self.viewport.timings.ui_worst(n))
    }

    /// The editor state (tests read it).
    pub fn state(&self) -> &EditorState {
        &self.state
    }

    /// The editor state, mutable (tests drive actions that normally need file dialogs).
    pub fn state_mut(&mut self) -> &mut EditorState {
        &mut self.state
    }

    fn new_project(&mut self) {
        match empty_project() {
            Ok(project) => {
                self.leave_project();
                self.state.project = project;
                self.state.path = None;
                self.state.opened = None;
                self.state.read_only = false;
                self.state.carried_edits = 0;
                self.state.history.clear();
                self.state.selection = Selection::None;
                self.viewport.reset_orbit(&self.state);
            }
            Err(e) => self.state.report("new project", &e),
        }
    }

    fn open_dialog(&mut self) {
        let picked = rfd::FileDialog::new().add_filter("Project or glTF", &["ron", "gltf", "glb"]).pick_file();
        if let Some(path) = picked {
            self.open(&path);
        }
    }

    /// Opens a project or glTF file, and offers work on it that a crashed instance left.
    pub fn open(&mut self, path: &std::path::Path) {
        // Loaded before the current project is left, so a file that does not open changes nothing.
        let project = match crate::project_file::Project::open(path) {
            Ok(p) => p,
            Err(e) => return self.state.report("open failed", &e),
        };
        self.leave_project();
        match self.state.open_loaded(path, project) {
            Ok(()) => {
                self.viewport.reset_orbit(&self.state);
                self.offer_recovery_of(path);
            }
            Err(e) => self.state.report("open failed", &e),
        }
    }

    /// Save: to the project's file, or asks for one (a new project, a glTF, the read-only
    /// default project).
    fn save(&mut self) {
        match self.state.path.clone().filter(|_| !self.state.read_only) {
            Some(p) => self.save_to(&p),
            None => self.save_as_dialog(),
        }
    }

    fn save_as_dialog(&mut self) {
        if let Some(path) =
            rfd::FileDialog::new().add_filter("Bounce Lab project", &["ron"]).set_file_name("scene.ron").save_file()
        {
            self.save_to(&path);
        }
    }

    /// Saves to `path` and removes this instance's recovery file (only its own).
    pub fn save_to(&mut self, path: &std::path::Path) {
        match self.state.save_as(path) {
            Ok(()) => {
                if let Some(a) = &mut self.autosave {
                    a.saved();
                }
            }
            Err(e) => self.state.report("save failed", &e),
        }
    }

    fn undo(&mut self) {
        if let Some(label) = self.state.history.undo(&mut self.state.project) {
            self.state.status = format!("undid {label}");
            self.clamp_selection();
        }
    }

    fn redo(&mut self) {
        if let Some(label) = self.state.history.redo(&mut self.state.project) {
            self.state.status = format!("redid {label}");
            self.clamp_selection();
        }
    }

    fn clamp_selection(&mut self) {
        let s = &self.state;
        let valid = match s.selection {
            Selection::Light(i) => i < s.project.scene.lights().len(),
            Selection::Object(i) => i < s.project.scene.objects().len(),
            Selection::None => true,
        };
        if !valid {
            self.state.selection = Selection::None;
        }
    }

    fn edit(&mut self, f: fn(&mut Project, &mut history::History, Selection) -> Result<Selection, edits::EditError>) {
        match f(&mut self.state.project, &mut self.state.history, self.state.selection) {
            Ok(sel) => self.state.selection = sel,
            Err(e) => self.state.report("edit failed", &e),
        }
    }

    fn shortcuts(&mut self, ui: &egui::Ui) {
        use egui::{Key, KeyboardShortcut as K, Modifiers as M};
        // A dialog is open: no edit, open or new may change what it asks about.
        if self.modal != Modal::None {
            return;
        }
        let typing = ui.memory(|m| m.focused().is_some());
        let pressed = |sc: K| ui.input_mut(|i| i.consume_shortcut(&sc));
        if pressed(K::new(M::COMMAND | M::SHIFT, Key::Z)) || pressed(K::new(M::COMMAND, Key::Y)) {
            self.redo();
        }
        if pressed(K::new(M::COMMAND, Key::Z)) {
            self.undo();
        }
        if pressed(K::new(M::COMMAND | M::SHIFT, Key::S)) {
            self.save_as_dialog();
        }
        if pressed(K::new(M::COMMAND, Key::S)) {
            self.save();
        }
        if pressed(K::new(M::COMMAND, Key::O)) {
            self.open_dialog();
        }
        if pressed(K::new(M::COMMAND, Key::N)) {
            self.new_project();
        }
        if pressed(K::new(M::COMMAND, Key::D)) {
            self.edit(edits::duplicate);
        }
        if !typing {
            if pressed(K::new(M::NONE, Key::Delete)) {
                self.edit(edits::delete);
            }
            if pressed(K::new(M::NONE, Key::G)) {
                self.viewport.gizmo.mode = gizmo::GizmoMode::Translate;
            }
            if pressed(K::new(M::NONE, Key::R)) {
                self.viewport.gizmo.mode = gizmo::GizmoMode::Rotate;
            }
            if pressed(K::new(M::NONE, Key::S)) {
                self.viewport.gizmo.mode = gizmo::GizmoMode::Scale;
            }
        }
    }

    fn menu_bar(&mut self, ui: &mut egui::Ui) {
        let sc = |ui: &egui::Ui, m: egui::Modifiers, k: egui::Key| {
            ui.ctx().format_shortcut(&egui::KeyboardShortcut::new(m, k))
        };
        let cmd = egui::Modifiers::COMMAND;
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.add(egui::Button::new("New").shortcut_text(sc(ui, cmd, egui::Key::N))).clicked() {
                    self.new_project();
                }
                if ui.add(egui::Button::new("Open...").shortcut_text(sc(ui, cmd, egui::Key::O))).clicked() {
                    self.open_dialog();
                }
                ui.menu_button("Open recent", |ui| {
                    for p in self.state.recent.clone() {
                        if ui.button(p.display().to_string()).clicked() {
                            self.open(&p);
                        }
                    }
                });
                if ui.add(egui::Button::new("Save").shortcut_text(sc(ui, cmd, egui::Key::S))).clicked() {
                    self.save();
                }
                if ui
                    .add(egui::Button::new("Save As...").shortcut_text(sc(
                        ui,
                        cmd | egui::Modifiers::SHIFT,
                        egui::Key::S,
                    )))
                    .clicked()
                {
                    self.save_as_dialog();
                }
                if ui.button("Export viewport image...").clicked() {
                    self.export_dialog();
                }
                if ui.button("Export glTF...").on_hover_text(
                    "The scene with its authored lights (in the scene's light units), proxy blocks, sampling weights and clutter marks, for the engine or DCC it came from",
                ).clicked() {
                    self.export_gltf_dialog();
                }
            });
            ui.menu_button("Edit", |ui| {
                let undo = self.state.history.undo_label().map_or("Undo".to_owned(), |l| format!("Undo {l}"));
                let redo = self.state.history.redo_label().map_or("Redo".to_owned(), |l| format!("Redo {l}"));
                if ui.add(egui::Button::new(undo).shortcut_text(sc(ui, cmd, egui::Key::Z))).clicked() {
                    self.undo();
                }
                if ui
                    .add(egui::Button::new(redo).shortcut_text(sc(ui, cmd | egui::Modifiers::SHIFT, egui::Key::Z)))
                    .clicked()
                {
                    self.redo();
                }
                ui.separator();
                if ui.add(egui::Button::new("Duplicate").shortcut_text(sc(ui, cmd, egui::Key::D))).clicked() {
                    self.edit(edits::duplicate);
                }
                if ui.add(egui::Button::new("Delete").shortcut_text("Del")).clicked() {
                    self.edit(edits::delete);
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Reset layout").clicked() {
                    self.tree = panes::default_tree();
                }
                ui.separator();
                if ui
                    .button("Simulate GPU device loss")
                    .on_hover_text(
                        "Destroys the viewport's device as a driver reset would, to check that the editor recovers",
                    )
                    .clicked()
                {
                    self.viewport.simulate_device_loss();
                }
            });
        });
    }

    fn modal_ui(&mut self, ui: &mut egui::Ui) {
        match self.modal.clone() {
            Modal::None => {}
            Modal::ConfirmClose => {
                egui::Modal::new(egui::Id::unique("confirm close")).show(ui.ctx(), |ui| {
                    ui.label("The project has unsaved changes.");
                    ui.horizontal(|ui| {
                        if ui.button("Save and quit").clicked() {
                            self.save();
                            if !self.state.history.is_dirty() {
                                self.close_now(ui);
                            }
                        }
                        if ui.button("Quit without saving").clicked() {
                            self.close_now(ui);
                        }
                        if ui.button("Cancel").clicked() {
                            self.modal = Modal::None;
                        }
                    });
                });
            }
            Modal::Error(message) => {
                egui::Modal::new(egui::Id::unique("error dialog")).show(ui.ctx(), |ui| {
                    ui.label(message);
                    if ui.button("OK").clicked() {
                        self.modal = Modal::None;
                    }
                });
            }
            Modal::OfferRecovery => self.recovery_dialog(ui),
        }
    }

    fn close_now(&mut self, ui: &egui::Ui) {
        if let Some(a) = &mut self.autosave {
            a.close();
        }
        self.allow_close = true;
        ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

struct Behavior<'a> {
    state: &'a mut EditorState,
    viewport: &'a mut viewport::Viewport,
    inspector: &'a mut inspector::Inspector,
}

impl egui_tiles::Behavior<Pane> for Behavior<'_> {
    fn tab_title_for_pane(&mut self, pane: &Pane) -> egui::WidgetText {
        pane.title().into()
    }

    fn pane_ui(&mut self, ui: &mut egui::Ui, _tile: egui_tiles::TileId, pane: &mut Pane) -> egui_tiles::UiResponse {
        match pane {
            Pane::Viewport => self.viewport.ui(ui, self.state),
            Pane::Outliner => outliner::outliner_ui(self.state, ui),
            Pane::Properties => properties::properties_ui(self.state, ui),
            Pane::Gi => gi_panel::gi_ui(self.state, ui, self.viewport.renderer(), self.viewport.view_size()),
            Pane::Inspector => {
                let frame = inspector::ViewFrame {
                    index: self.viewport.frames,
                    idle: self.viewport.idle(),
                    full: self.viewport.shown_scale() == Some(1.0),
                    full_size: self.viewport.view_size(),
                };
                self.inspector.ui(ui, self.viewport.renderer(), &self.state.project, frame)
            }
            Pane::Timings => self.viewport.timings.ui(ui),
            Pane::Log => {
                egui::ScrollArea::vertical().stick_to_bottom(true).show(ui, |ui| {
                    for (level, line) in crate::logging::recent() {
                        let colour = match level {
                            log::Level::Error => ui.visuals().error_fg_color,
                            log::Level::Warn => ui.visuals().warn_fg_color,
                            _ => ui.visuals().text_color(),
                        };
                        ui.colored_label(colour, line);
                    }
                });
            }
        }
        egui_tiles::UiResponse::None
    }

    fn simplification_options(&self) -> egui_tiles::SimplificationOptions {
        egui_tiles::SimplificationOptions { all_panes_must_have_tabs: true, ..Default::default() }
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let started = std::time::Instant::now();
        // The frame the GPU finished since the last UI frame, if any (never waits).
        if let Err(e) = self.viewport.poll() {
            self.state.report("render failed", &e);
        }
        for problem in self.viewport.gpu_problems() {
            match problem {
                preview::GpuProblem::Error(message) => self.state.report("GPU", &message),
                preview::GpuProblem::Lost(message) => self.show_error(message),
            }
        }
        self.shortcuts(ui);
        self.live_reload(ui.ctx());
        // Drag and drop a project or glTF onto the window to open it.
        let dropped: Vec<PathBuf> = ui.input(|i| {
            i.raw.dropped_files.iter().map(|f| f.path().to_owned()).filter(|p| !p.as_os_str().is_empty()).collect()
        });
        if let Some(path) = dropped.first().filter(|_| self.modal == Modal::None) {
            self.open(path);
        }
        if ui.input(|i| i.viewport().close_requested()) && self.state.history.is_dirty() && !self.allow_close {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.modal = Modal::ConfirmClose;
        }
        // Only when it changes: every viewport command asks for another repaint, and a UI that
        // repaints continuously takes a software adapter's CPU from the viewport's frame.
        let title = self.state.title();
        if self.title != title {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
        egui::Panel::top("menu bar").show(ui, |ui| self.menu_bar(ui));
        egui::Panel::bottom("status bar").show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label(if self.state.history.is_dirty() { "* unsaved" } else { "saved" });
                ui.separator();
                ui.label(&self.state.status);
            });
        });
        // Techniques keep debug copies (and the frame its pyramid) only while shown.
        self.viewport.set_inspected(Some(self.inspector.shown().0));
        egui::CentralPanel::default().show(ui, |ui| {
            let mut behavior =
                Behavior { state: &mut self.state, viewport: &mut self.viewport, inspector: &mut self.inspector };
            self.tree.ui(&mut behavior, ui);
        });
        // After every pane has read the finished frame: start the next one.
        self.viewport.submit(&mut self.state);
        self.viewport.logic_ms = self.viewport.logic_ms.max(started.elapsed().as_secs_f64() * 1e3);
        self.modal_ui(ui);
        let view = self.autosave_view();
        if let Some(a) = &mut self.autosave {
            a.track(&self.state.project, self.state.opened.as_deref(), &view);
        }
    }

    fn on_exit(&mut self) {
        // A clean exit with nothing unsaved removes this instance's recovery file and lock.
        if let Some(a) = &mut self.autosave
            && !self.state.history.is_dirty()
        {
            a.close();
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, TREE_KEY, &self.tree);
        eframe::set_value(storage, RECENT_KEY, &self.state.recent);
        eframe::set_value(storage, PREVIEW_KEY, &self.viewport.preview);
    }
}
