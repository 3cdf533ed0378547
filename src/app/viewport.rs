//! The 3D viewport: camera control (orbit, pan, zoom, fly with WASD while the right button is
//! held), picking through the object-id buffer and light icons, the transform gizmo, overlays,
//! and the rendered image shown through a registered egui texture.

use glam::{Quat, Vec2, Vec3};

use super::Orbit;
use super::edits::Selection;
use super::gizmo::{self, Drag, GizmoMode, View};
use super::overlays;
use super::state::EditorState;
use super::timings::Timings;
use crate::render::{RenderError, Renderer};

/// Gizmo options shown in the viewport toolbar.
#[derive(Clone, Copy, Debug)]
pub struct GizmoOptions {
    pub mode: GizmoMode,
    pub local: bool,
    pub snap: bool,
    /// Snap step for translation (metres).
    pub step: f32,
    /// Snap step for rotation (degrees).
    pub angle_step: f32,
    /// Show the scene sample points (where ISM points and VPL samples land).
    pub show_points: bool,
    /// How many sample points to distribute for the overlay.
    pub point_count: usize,
    /// Show the active technique's overlays (ISM's VPLs of every bounce; refreshed every 10
    /// frames).
    pub show_overlays: bool,
}

impl Default for GizmoOptions {
    fn default() -> Self {
        Self {
            mode: GizmoMode::Translate,
            local: false,
            snap: false,
            step: 0.1,
            angle_step: 15.0,
            show_points: false,
            point_count: 4096,
            show_overlays: false,
        }
    }
}

/// Renderer and display state of the viewport.
pub struct Viewport {
    renderer: Option<Renderer>,
    texture: Option<(egui::TextureId, (u32, u32))>,
    orbit: Orbit,
    last: Option<std::time::Instant>,
    init_error: Option<String>,
    drag: Option<Drag>,
    /// Gizmo options.
    pub gizmo: GizmoOptions,
    /// Frame counter (inspector refresh cadence).
    pub frames: u64,
    /// Per-pass timing history.
    pub timings: Timings,
    points: Option<PointsCache>,
    /// Screen rectangle of the last drawn image (egui points).
    pub rect: Option<egui::Rect>,
    overlays: Vec<crate::render::gi::Overlay>,
    /// The view size of the last frame (pixels).
    size: (u32, u32),
}

/// The sample-point overlay's distribution and what it was computed from.
struct PointsCache {
    /// Per object: sampling weight, rendered, scale (what changes the distribution).
    key: Vec<(f32, bool, [f32; 3])>,
    resources_revision: u64,
    points: crate::precompute::sample_points::SamplePoints,
}

const AXIS_COLOURS: [egui::Color32; 3] =
    [egui::Color32::from_rgb(230, 70, 70), egui::Color32::from_rgb(80, 200, 80), egui::Color32::from_rgb(80, 120, 240)];

impl Viewport {
    /// Creates the renderer on eframe's device (if eframe runs on wgpu).
    pub fn new(rs: Option<&egui_wgpu::RenderState>, state: &EditorState) -> Self {
        let (renderer, init_error) = match rs.map(|rs| Renderer::new(&rs.device, &rs.queue)) {
            Some(Ok(r)) => (Some(r), None),
            Some(Err(e)) => (None, Some(e.to_string())),
            None => (None, Some("eframe is not running on wgpu".to_owned())),
        };
        let mut v = Self {
            renderer,
            texture: None,
            orbit: Orbit { target: Vec3::ZERO, distance: 3.0, yaw: 0.0, pitch: 0.0 },
            last: None,
            init_error,
            drag: None,
            gizmo: GizmoOptions::default(),
            frames: 0,
            timings: Timings::default(),
            points: None,
            rect: None,
            overlays: Vec::new(),
            size: (1, 1),
        };
        v.reset_orbit(state);
        v
    }

    /// Re-derives the orbit controller from the project's camera (after opening a project).
    pub fn reset_orbit(&mut self, state: &EditorState) {
        let scene = &state.project.scene;
        let cam = scene.camera();
        let dist = scene.bounds().map_or(3.0, |b| (b.center() - cam.position).dot(cam.forward()).max(0.1));
        self.orbit = Orbit::from_camera(cam, dist);
    }

    /// The renderer, for the inspector.
    pub fn renderer(&self) -> Option<&Renderer> {
        self.renderer.as_ref()
    }

    /// The view size of the last frame in pixels (what mode support is checked against).
    pub fn view_size(&self) -> (u32, u32) {
        self.size
    }

    /// Tells the renderer which buffer the inspector shows.
    pub fn set_inspected(&mut self, name: Option<&str>) {
        if let Some(r) = &mut self.renderer {
            r.set_inspected(name);
        }
    }

    /// The position and rotation the gizmo edits for the selection.
    fn target(state: &EditorState) -> Option<(Vec3, Quat)> {
        match state.selection {
            Selection::Object(i) => {
                state.project.scene.objects().get(i).map(|o| (o.transform.translation, o.transform.rotation))
            }
            Selection::Light(i) => {
                let l = state.project.scene.lights().get(i)?;
                let rot = crate::scene::Camera::look_at(Vec3::ZERO, l.direction, 1.0).rotation;
                (l.kind != crate::scene::LightKind::Directional)
                    .then_some((l.position, rot))
                    .or(Some((overlays::light_anchor(&state.project.scene, i)?, rot)))
            }
            Selection::None => None,
        }
    }

    fn apply_gizmo(state: &mut EditorState, drag: &Drag, view: &View, s: Vec2, opts: &GizmoOptions) {
        let before_pos = drag.origin;
        match drag.mode {
            GizmoMode::Translate => {
                let Some(offset) = drag.translation(view, s, if opts.snap { opts.step } else { 0.0 }) else { return };
                state.history.begin("Move", &state.project);
                match state.selection {
                    Selection::Object(i) => {
                        state.project.scene.desc_mut().objects[i].transform.translation = before_pos + offset
                    }
                    Selection::Light(i)
                        if state.project.scene.lights()[i].kind != crate::scene::LightKind::Directional =>
                    {
                        state.project.scene.desc_mut().lights[i].position = before_pos + offset;
                    }
                    _ => {}
                }
            }
            GizmoMode::Scale => {
                let handle = view.world_size(drag.origin, 70.0);
                let Some(f) = drag.scale_factor(view, s, handle, if opts.snap { 0.1 } else { 0.0 }) else { return };
                if let Selection::Object(i) = state.selection {
                    let Some(o) = state.project.scene.objects().get(i) else { return };
                    // Scale along the object's local axis closest to the dragged one.
                    let local = o.transform.rotation.inverse() * drag.axis;
                    let k = local.abs().max_position();
                    let mut scale = drag.start_scale;
                    scale[k] = (scale[k] * f).max(1e-3);
                    state.history.begin("Scale", &state.project);
                    state.project.scene.desc_mut().objects[i].transform.scale = scale;
                }
            }
            GizmoMode::Rotate => {
                let Some(rot) = drag.rotation(view, s, if opts.snap { opts.angle_step } else { 0.0 }) else { return };
                state.history.begin("Rotate", &state.project);
                match state.selection {
                    Selection::Object(i) => state.project.scene.desc_mut().objects[i].transform.rotation = rot,
                    Selection::Light(i) => {
                        state.project.scene.desc_mut().lights[i].direction = (rot * Vec3::NEG_Z).normalize()
                    }
                    Selection::None => {}
                }
            }
        }
    }

    /// Draws the scene sample points, redistributing them when weights or geometry change.
    fn draw_points(&mut self, painter: &egui::Painter, rect: egui::Rect, view: &View, state: &EditorState) {
        let scene = &state.project.scene;
        let key: Vec<(f32, bool, [f32; 3])> = scene
            .objects()
            .iter()
            .map(|o| (o.sampling_weight, o.is_rendered(), o.transform.scale.to_array()))
            .collect();
        let stale =
            self.points.as_ref().is_none_or(|c| c.key != key || c.resources_revision != scene.resources_revision());
        if stale {
            let points = crate::precompute::sample_points::distribute(scene, self.gizmo.point_count, 1, 1);
            self.points = Some(PointsCache { key, resources_revision: scene.resources_revision(), points });
        }
        let Some(PointsCache { points: pts, .. }) = &self.points else { return };
        for (sp, (p, _)) in pts.points.iter().zip(pts.world(scene)) {
            if let Some(s) = view.project(p) {
                let [r, g, b] =
                    super::inspector::false_colour(((sp.object.wrapping_mul(2_654_435_761)) >> 24) as f32 / 255.0);
                painter.circle_filled(rect.min + egui::vec2(s.x, s.y), 1.5, egui::Color32::from_rgb(r, g, b));
            }
        }
    }

    /// Toolbar, input, rendering and painting into the remaining space.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame, state: &mut EditorState) -> Result<(), RenderError> {
        if let Some(e) = &self.init_error {
            ui.label(format!("Renderer unavailable: {e}"));
            return Ok(());
        }
        ui.horizontal(|ui| {
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Translate, "Move (G)");
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Rotate, "Rotate (R)");
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Scale, "Scale (S)");
            ui.checkbox(&mut self.gizmo.local, "local axes");
            ui.checkbox(&mut self.gizmo.snap, "snap");
            ui.checkbox(&mut self.gizmo.show_overlays, "overlays").on_hover_text(
                "The active technique's markers: ISM's virtual point lights, coloured by bounce (refreshed every 10 frames).",
            );
            ui.checkbox(&mut self.gizmo.show_points, "sample points")
                .on_hover_text("Where scene sample points land: area x sampling weight per object.");
            ui.label(format!("mode: {}", state.project.render.mode.name()));
        });
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        self.rect = Some(rect);
        let ppp = ui.ctx().pixels_per_point();
        let size = ((rect.width() * ppp).round().max(1.0) as u32, (rect.height() * ppp).round().max(1.0) as u32);
        let view = View { camera: *state.project.scene.camera(), size: Vec2::new(rect.width(), rect.height()) };
        let mouse = response
            .hover_pos()
            .or(response.interact_pointer_pos())
            .map(|p| Vec2::new(p.x - rect.min.x, p.y - rect.min.y));

        // Gizmo handles of the selection; a drag starts where the button went down.
        let target = Self::target(state);
        let axis_at = |m: Vec2| -> Option<(usize, Vec3)> {
            let (origin, rotation) = target?;
            let len = view.world_size(origin, 70.0);
            gizmo::axes(rotation, self.gizmo.local).into_iter().enumerate().find(|(_, axis)| {
                matches!((view.project(origin), view.project(origin + *axis * len)), (Some(a), Some(b)) if gizmo::segment_distance(m, a, b) < 8.0)
            })
        };
        let hovered_axis = mouse.and_then(axis_at);
        if response.drag_started_by(egui::PointerButton::Primary) {
            let press = ui.input(|i| i.pointer.press_origin()).map(|p| Vec2::new(p.x - rect.min.x, p.y - rect.min.y));
            if let (Some(p), Some((origin, rotation))) = (press, target)
                && let Some((_, axis)) = axis_at(p)
            {
                self.drag = Drag::begin(&view, self.gizmo.mode, axis, origin, rotation, p).map(|mut d| {
                    if let Selection::Object(i) = state.selection
                        && let Some(o) = state.project.scene.objects().get(i)
                    {
                        d.start_scale = o.transform.scale;
                    }
                    d
                });
            }
        }
        if let (Some(drag), Some(m)) = (self.drag, mouse)
            && response.dragged_by(egui::PointerButton::Primary)
        {
            Self::apply_gizmo(state, &drag, &view, m, &self.gizmo);
        } else {
            let d = response.drag_delta();
            if response.dragged_by(egui::PointerButton::Primary) {
                self.orbit.rotate(d.x, d.y);
            } else if response.dragged_by(egui::PointerButton::Middle)
                || (response.dragged_by(egui::PointerButton::Secondary) && ui.input(|i| i.modifiers.shift))
            {
                self.orbit.pan(d.x, d.y, rect.height(), state.project.scene.camera().yfov);
            } else if response.dragged_by(egui::PointerButton::Secondary) {
                // Fly: look around with the right button, WASD/QE to move.
                self.orbit.rotate(d.x, d.y);
                let step = self.orbit.distance * 0.02;
                let r = self.orbit.rotation();
                let mut mv = Vec3::ZERO;
                ui.input(|i| {
                    for (key, dir) in [
                        (egui::Key::W, Vec3::NEG_Z),
                        (egui::Key::S, Vec3::Z),
                        (egui::Key::A, Vec3::NEG_X),
                        (egui::Key::D, Vec3::X),
                        (egui::Key::Q, Vec3::NEG_Y),
                        (egui::Key::E, Vec3::Y),
                    ] {
                        if i.key_down(key) {
                            mv += r * dir;
                        }
                    }
                });
                self.orbit.target += mv * step;
            }
        }
        if !response.dragged() {
            self.drag = None;
            if ui.input(|i| !i.pointer.any_down()) {
                state.history.commit(&state.project);
            }
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.zoom(scroll);
            }
        }
        // Picking: light icons first, then the object-id buffer.
        if response.clicked_by(egui::PointerButton::Primary)
            && let Some(m) = mouse
        {
            let light = (0..state.project.scene.lights().len()).find(|&i| {
                overlays::light_anchor(&state.project.scene, i)
                    .and_then(|p| view.project(p))
                    .is_some_and(|s| s.distance(m) < 10.0)
            });
            state.selection = match (light, &self.renderer) {
                (Some(i), _) => Selection::Light(i),
                (None, Some(r)) => match r.pick((m.x * ppp) as u32, (m.y * ppp) as u32) {
                    Ok(Some(i)) => Selection::Object(i),
                    Ok(None) => Selection::None,
                    Err(e) => {
                        log::warn!("pick failed: {e}");
                        state.selection
                    }
                },
                (None, None) => state.selection,
            };
        }
        // Camera: only written when the user moved it, so undo history stays clean.
        let mut cam = *state.project.scene.camera();
        self.orbit.apply(&mut cam);
        if cam != *state.project.scene.camera() {
            state.project.scene.set_camera(cam);
        }
        let (Some(renderer), Some(rs)) = (self.renderer.as_mut(), frame.wgpu_render_state()) else { return Ok(()) };
        self.size = size;
        renderer.render(&state.project.scene, &state.project.render, size)?;
        self.frames += 1;
        let now = std::time::Instant::now();
        let frame_ms = self.last.map_or(0.0, |l| (now - l).as_secs_f64() * 1e3);
        self.last = Some(now);
        self.timings.push(frame_ms, &renderer.timings(false));
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
        let painter = ui.painter_at(rect);
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        if let Some((id, _)) = self.texture {
            painter.image(id, rect, uv, egui::Color32::WHITE);
        }
        // What the technique is doing (the reference's spp, a bake's progress).
        let status = renderer.technique_status().and_then(|s| s.progress);
        if let Some(text) = status {
            painter.text(
                rect.left_top() + egui::vec2(8.0, 8.0),
                egui::Align2::LEFT_TOP,
                text,
                egui::FontId::proportional(13.0),
                egui::Color32::WHITE,
            );
        }
        let view = View { camera: *state.project.scene.camera(), size: Vec2::new(rect.width(), rect.height()) };
        overlays::draw(&painter, rect, &view, &state.project.scene, state.selection);
        if self.gizmo.show_points {
            self.draw_points(&painter, rect, &view, state);
        }
        if self.gizmo.show_overlays {
            if self.frames % 10 == 1
                && let Some(r) = &self.renderer
            {
                self.overlays = r.overlays();
            }
            for p in self.overlays.iter().flat_map(|o| &o.points) {
                if let Some(s) = view.project(p.position) {
                    let [r, g, b] = super::inspector::false_colour(p.tone);
                    painter.circle_filled(rect.min + egui::vec2(s.x, s.y), p.radius, egui::Color32::from_rgb(r, g, b));
                }
            }
        } else {
            self.overlays.clear();
        }
        if let Some((origin, rotation)) = Self::target(state) {
            let len = view.world_size(origin, 70.0);
            for (k, axis) in gizmo::axes(rotation, self.gizmo.local).into_iter().enumerate() {
                if let (Some(a), Some(b)) = (view.project(origin), view.project(origin + axis * len)) {
                    let hot = hovered_axis.is_some_and(|(h, _)| h == k) || self.drag.is_some_and(|d| d.axis == axis);
                    let stroke = egui::Stroke::new(if hot { 4.0 } else { 2.5 }, AXIS_COLOURS[k]);
                    let (pa, pb) = (rect.min + egui::vec2(a.x, a.y), rect.min + egui::vec2(b.x, b.y));
                    painter.line_segment([pa, pb], stroke);
                    match self.gizmo.mode {
                        GizmoMode::Translate => {
                            painter.circle_filled(pb, 4.0, AXIS_COLOURS[k]);
                        }
                        GizmoMode::Rotate => {
                            painter.circle_stroke(pb, 6.0, stroke);
                        }
                        GizmoMode::Scale => {
                            painter.rect_filled(
                                egui::Rect::from_center_size(pb, egui::vec2(8.0, 8.0)),
                                0.0,
                                AXIS_COLOURS[k],
                            );
                        }
                    }
                }
            }
        }
        ui.ctx().request_repaint();
        Ok(())
    }
}
