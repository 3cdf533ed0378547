//! The editor window (eframe + egui). This first version shows the project in a viewport with
//! an orbit camera, the render settings and per-pass timings; the full editor builds on it.
//!
//! The viewport follows platform-notes.md pattern B: the renderer draws into its own HDR and
//! depth targets, the tonemapped `Rgba8Unorm` image is registered with egui as a native texture.

mod orbit;
mod viewport;

pub use orbit::Orbit;

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context as _;

use crate::project_file::{Project, default_project_path};
use crate::render::device_descriptor;

/// Opens the editor window on `project` (the default project if `None`).
pub fn run(project: Option<PathBuf>) -> anyhow::Result<()> {
    let path = project.unwrap_or_else(default_project_path);
    let project = Project::open(&path).with_context(|| format!("opening {}", path.display()))?;
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = Arc::new(device_descriptor);
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1280.0, 800.0]).with_title("Bounce Lab"),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    };
    let title = format!("Bounce Lab — {}", path.display());
    eframe::run_native(&title, options, Box::new(move |cc| Ok(Box::new(EditorApp::new(cc, project, path)))))
        .map_err(|e| anyhow::anyhow!("cannot open the editor window: {e}"))
}

/// The editor application state.
pub struct EditorApp {
    project: Project,
    path: PathBuf,
    viewport: viewport::Viewport,
    error: Option<String>,
}

impl EditorApp {
    /// Creates the app; the renderer is created on eframe's wgpu device.
    pub fn new(cc: &eframe::CreationContext<'_>, project: Project, path: PathBuf) -> Self {
        let viewport = viewport::Viewport::new(cc.wgpu_render_state.as_ref(), &project);
        Self { project, path, viewport, error: None }
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Project");
        ui.label(self.path.display().to_string());
        ui.separator();
        ui.heading("Scene");
        ui.label(format!(
            "{} objects, {} lights",
            self.project.scene.objects().len(),
            self.project.scene.lights().len()
        ));
        for light in self.project.scene.lights() {
            ui.label(format!("{} ({:?}, {} W/sr)", light.name, light.kind, light.intensity));
        }
        ui.separator();
        ui.heading("View");
        let view = &mut self.project.render.view;
        ui.add(egui::Slider::new(&mut view.exposure_ev, -8.0..=8.0).text("exposure (EV)"));
        egui::ComboBox::from_label("tonemap").selected_text(format!("{:?}", view.tonemap)).show_ui(ui, |ui| {
            for t in
                [crate::settings::Tonemap::Aces, crate::settings::Tonemap::Reinhard, crate::settings::Tonemap::Clamp]
            {
                ui.selectable_value(&mut view.tonemap, t, format!("{t:?}"));
            }
        });
        ui.separator();
        ui.heading("Timings");
        self.viewport.timings_ui(ui);
        if let Some(e) = &self.error {
            ui.separator();
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        ui.separator();
        ui.small("Drag: orbit · Right/middle drag: pan · Scroll: zoom");
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        egui::Panel::left("side panel").default_size(280.0).show(ui, |ui| self.side_panel(ui));
        egui::CentralPanel::default().show(ui, |ui| {
            self.error = self.viewport.ui(ui, frame, &mut self.project).err().map(|e| e.to_string());
        });
    }
}
