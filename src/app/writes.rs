//! The editor's traffic with files beyond opening and saving projects: exporting the viewport
//! image and the scene as glTF (File menu), and live reload of the glTF files a project reads.

use std::path::PathBuf;

use super::{EditorApp, edits, history};

impl EditorApp {
    /// Watches the project's files and reloads an asset that changed on disk, as one undo
    /// step; the status bar says what was kept and what no longer matches, or why a file that
    /// does not import yet is tried again.
    pub(super) fn live_reload(&mut self, ctx: &egui::Context) {
        self.watcher.watch(self.state.project.file_paths(), ctx);
        if let Some(problem) = self.watcher.problem.take() {
            self.state.status = problem;
        }
        for (path, failures) in self.watcher.poll() {
            let Some(index) = self.state.project.asset_of_file(&path) else { continue };
            let name =
                path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
            let before = history::Snapshot::with_assets(&self.state.project);
            match self.state.project.reload_asset(index) {
                Ok(report) => {
                    self.state.history.record(&format!("Reload {name}"), before, &self.state.project);
                    self.state.selection = edits::Selection::None;
                    self.state.status = report.to_string();
                }
                Err(e) if self.watcher.retry(&path, failures + 1) => {
                    self.state.status = format!("{name} changed but does not import yet, trying again: {e}");
                }
                Err(e) => self.state.report(&format!("{name} changed but does not import"), &e),
            }
        }
        if let Some(wait) = self.watcher.next_due() {
            ctx.request_repaint_after(wait);
        }
    }

    pub(super) fn export_gltf_dialog(&mut self) {
        let Some(path) =
            rfd::FileDialog::new().add_filter("glTF", &["glb", "gltf"]).set_file_name("scene.glb").save_file()
        else {
            return;
        };
        self.export_gltf(&path);
    }

    /// Exports the scene as glTF to `path` (refused where `path` is one of the project's own
    /// files); the status bar says what was written.
    pub fn export_gltf(&mut self, path: &std::path::Path) {
        let mut inputs = self.state.project.files();
        inputs.extend(self.state.opened.clone());
        inputs.extend(self.state.path.clone());
        let inputs: Vec<&std::path::Path> = inputs.iter().map(PathBuf::as_path).collect();
        if let Err(e) = crate::output_path::check(path, crate::output_path::GLTF, &inputs) {
            self.state.report("export refused", &e);
            return;
        }
        match crate::export::export(&self.state.project, path) {
            Ok(summary) => self.state.status = format!("exported {}: {summary}", path.display()),
            Err(e) => self.state.report("export failed", &e),
        }
    }

    pub(super) fn export_dialog(&mut self) {
        let Some(path) =
            rfd::FileDialog::new().add_filter("Image", &["png", "exr"]).set_file_name("viewport.png").save_file()
        else {
            return;
        };
        let mut inputs = self.state.project.files();
        inputs.extend(self.state.opened.clone());
        let inputs: Vec<&std::path::Path> = inputs.iter().map(PathBuf::as_path).collect();
        if let Err(e) = crate::output_path::check(&path, crate::output_path::IMAGE, &inputs) {
            self.state.report("export refused", &e);
            return;
        }
        if let Err(e) = self.viewport.render_full(&self.state) {
            self.state.report("export failed", &e);
            return;
        }
        let Some(renderer) = self.viewport.renderer() else { return };
        let result = renderer.read_buffer("hdr").map_err(anyhow::Error::from).and_then(|img| {
            let kind = crate::image_io::output_kind(&path)?;
            Ok(crate::image_io::write_image(&path, kind, &img, &self.state.project.render.view)?)
        });
        match result {
            Ok(()) => self.state.status = format!("exported {}", path.display()),
            Err(e) => self.state.report("export failed", &e),
        }
    }
}
