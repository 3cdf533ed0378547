//! The 3D viewport: input to the orbit camera, rendering at the panel's pixel size, and the
//! tonemapped image shown through a registered egui texture.

use crate::project_file::Project;
use crate::render::{PassTiming, RenderError, Renderer};

use super::Orbit;

/// Renderer and display state of the viewport.
pub struct Viewport {
    renderer: Option<Renderer>,
    texture: Option<(egui::TextureId, (u32, u32))>,
    orbit: Orbit,
    timings: Vec<PassTiming>,
    frame_ms: f32,
    last: Option<std::time::Instant>,
    init_error: Option<String>,
}

impl Viewport {
    /// Creates the renderer on eframe's device (if eframe runs on wgpu).
    pub fn new(rs: Option<&egui_wgpu::RenderState>, project: &Project) -> Self {
        let (renderer, init_error) = match rs.map(|rs| Renderer::new(&rs.device, &rs.queue)) {
            Some(Ok(r)) => (Some(r), None),
            Some(Err(e)) => (None, Some(e.to_string())),
            None => (None, Some("eframe is not running on wgpu".to_owned())),
        };
        let cam = project.scene.camera();
        let dist = project.scene.bounds().map_or(3.0, |b| (b.center() - cam.position).dot(cam.forward()).max(0.1));
        Self {
            renderer,
            texture: None,
            orbit: Orbit::from_camera(cam, dist),
            timings: Vec::new(),
            frame_ms: 0.0,
            last: None,
            init_error,
        }
    }

    /// Shows per-pass timings.
    pub fn timings_ui(&self, ui: &mut egui::Ui) {
        ui.label(format!("frame {:.1} ms", self.frame_ms));
        for t in &self.timings {
            ui.label(format!("{:<10} {:.2} ms", t.name, t.ms));
        }
    }

    /// Handles input, renders and paints into the remaining space.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame, project: &mut Project) -> Result<(), RenderError> {
        if let Some(e) = &self.init_error {
            ui.label(format!("Renderer unavailable: {e}"));
            return Ok(());
        }
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        let ppp = ui.ctx().pixels_per_point();
        let size = ((rect.width() * ppp).round().max(1.0) as u32, (rect.height() * ppp).round().max(1.0) as u32);
        let d = response.drag_delta();
        if response.dragged_by(egui::PointerButton::Primary) {
            self.orbit.rotate(d.x, d.y);
        } else if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            self.orbit.pan(d.x, d.y, rect.height(), project.scene.camera().yfov);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.zoom(scroll);
            }
        }
        let mut cam = *project.scene.camera();
        self.orbit.apply(&mut cam);
        if cam != *project.scene.camera() {
            project.scene.set_camera(cam);
        }
        let (Some(renderer), Some(rs)) = (self.renderer.as_mut(), frame.wgpu_render_state()) else {
            return Ok(());
        };
        renderer.render(&project.scene, &project.render, size)?;
        self.timings = renderer.timings(false);
        let now = std::time::Instant::now();
        if let Some(last) = self.last {
            self.frame_ms = 0.9 * self.frame_ms + 0.1 * (now - last).as_secs_f32() * 1e3;
        }
        self.last = Some(now);
        if let Some(t) = renderer.targets() {
            let mut egui_renderer = rs.renderer.write();
            match self.texture {
                // Same size: the targets (and so the view) are unchanged.
                Some((_, s)) if s == size => {}
                Some((id, _)) => {
                    egui_renderer.update_egui_texture_from_wgpu_texture(
                        &rs.device,
                        &t.ldr.view,
                        wgpu::FilterMode::Linear,
                        id,
                    );
                    self.texture = Some((id, size));
                }
                None => {
                    let id = egui_renderer.register_native_texture(&rs.device, &t.ldr.view, wgpu::FilterMode::Linear);
                    self.texture = Some((id, size));
                }
            }
        }
        if let Some((id, _)) = self.texture {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        }
        ui.ctx().request_repaint();
        Ok(())
    }
}
