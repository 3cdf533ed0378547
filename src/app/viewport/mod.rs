//! The 3D viewport: camera control (orbit, pan, zoom, fly with WASD while the right button is
//! held), picking through the object-id buffer and light icons, the transform gizmo, overlays,
//! and the latest finished preview image (see [`super::preview`]: the interface never waits for
//! the renderer, and the render scale follows a frame budget while something moves).

mod paint;

use glam::{Quat, Vec2, Vec3};

use std::time::Instant;

use super::Orbit;
use super::edits::Selection;
use super::gizmo::{self, Drag, GizmoMode, View};
use super::overlays;
use super::pick::Picker;
use super::preview::{AsyncView, GpuMemory, GpuProblem, LADDER, PreviewSettings, ScaleController, scaled_size};
use super::state::EditorState;
use super::timings::Timings;
use crate::render::{RenderError, Renderer};
use crate::settings::RenderSettings;

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

/// What a frame was rendered from: when it differs from the last frame's, something moved.
#[derive(Clone, Debug, PartialEq)]
struct FrameKey {
    revision: u64,
    resources_revision: u64,
    settings: RenderSettings,
    size: (u32, u32),
}

/// Renderer and display state of the viewport.
pub struct Viewport {
    ctx: egui::Context,
    view: Option<AsyncView>,
    /// The latest finished image and the ladder step it was rendered at.
    texture: Option<(egui::TextureHandle, usize)>,
    orbit: Orbit,
    last: Option<Instant>,
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
    /// The overlays were read since they were turned on.
    overlays_read: bool,
    /// The full view size of the last UI frame (physical pixels).
    size: (u32, u32),
    /// Frame budget and adaptive scale (editor preferences).
    pub preview: PreviewSettings,
    controller: ScaleController,
    picker: Picker,
    /// What the last submitted frame showed, and when it last changed.
    submitted: Option<FrameKey>,
    changed_at: Option<Instant>,
    /// Whether the pointer is dragging in the viewport (camera or gizmo) this UI frame.
    interacting: bool,
    /// The duration of the last finished viewport frame (ms).
    pub last_frame_ms: f64,
    /// UI frames drawn (the interface's own rate, whatever the renderer does).
    pub ui_frames: u64,
    /// The slowest UI frame's own work in the statistics window (ms): the editor's logic,
    /// layout and the viewport's submit, without egui's painting.
    pub logic_ms: f64,
    /// The start of the current statistics window and the counters at its start.
    stats: (Instant, u64, u64),
}

/// The sample-point overlay's distribution and what it was computed from.
struct PointsCache {
    /// Per object: sampling weight, rendered, scale (what changes the distribution).
    key: Vec<(f32, bool, [f32; 3])>,
    resources_revision: u64,
    points: crate::precompute::sample_points::SamplePoints,
}

/// What the stages of [`Viewport::ui`] read of this UI frame's view.
struct UiFrame {
    /// The image's screen rectangle (egui points) and its response.
    rect: egui::Rect,
    response: egui::Response,
    /// Pixels per point, and the view's size in physical pixels.
    ppp: f32,
    size: (u32, u32),
    /// The camera as the frame began, looking at `rect`.
    view: View,
    /// The pointer relative to `rect`'s corner (points).
    mouse: Option<Vec2>,
}

const AXIS_COLOURS: [egui::Color32; 3] =
    [egui::Color32::from_rgb(230, 70, 70), egui::Color32::from_rgb(80, 200, 80), egui::Color32::from_rgb(80, 120, 240)];

impl Viewport {
    /// Creates the renderer on a second device of eframe's adapter (if eframe runs on wgpu).
    pub fn new(ctx: &egui::Context, rs: Option<&egui_wgpu::RenderState>, state: &EditorState) -> Self {
        let repaint = ctx.clone();
        let wake: std::sync::Arc<dyn Fn() + Send + Sync> = std::sync::Arc::new(move || repaint.request_repaint());
        let (view, init_error) = match rs.map(|rs| AsyncView::new(&rs.adapter, wake)) {
            Some(Ok(v)) => (Some(v), None),
            Some(Err(e)) => (None, Some(e.to_string())),
            None => (None, Some("eframe is not running on wgpu".to_owned())),
        };
        let preview = view
            .as_ref()
            .map_or_else(PreviewSettings::default, |v| PreviewSettings::for_device_type(v.adapter().device_type));
        let mut v = Self {
            ctx: ctx.clone(),
            view,
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
            overlays_read: false,
            size: (1, 1),
            preview,
            controller: ScaleController::new(),
            picker: Picker::default(),
            submitted: None,
            changed_at: None,
            interacting: false,
            last_frame_ms: 0.0,
            ui_frames: 0,
            stats: (Instant::now(), 0, 0),
            logic_ms: 0.0,
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

    /// The renderer, for the inspector. Its blocking reads wait for the frame in flight: read
    /// only while [`Viewport::idle`].
    pub fn renderer(&self) -> Option<&Renderer> {
        self.view.as_ref().map(AsyncView::renderer)
    }

    /// Whether no frame is in flight (blocking reads of the renderer return at once).
    pub fn idle(&self) -> bool {
        self.view.as_ref().is_none_or(|v| !v.busy())
    }

    /// The render scale of the image on screen (1.0: full resolution).
    pub fn shown_scale(&self) -> Option<f32> {
        self.texture.as_ref().map(|(_, step)| LADDER[*step])
    }

    /// The view size of the last frame in pixels (what mode support is checked against).
    pub fn view_size(&self) -> (u32, u32) {
        self.size
    }

    /// Tells the renderer which buffer the inspector shows.
    pub fn set_inspected(&mut self, name: Option<&str>) {
        if let Some(v) = &mut self.view {
            v.set_inspected(name);
        }
    }

    /// Collects the frame in flight if the GPU has finished it (never blocks): uploads its
    /// image, records its time for the budget, refreshes the timings and overlays.
    pub fn poll(&mut self) -> Result<(), RenderError> {
        let Some(view) = &mut self.view else { return Ok(()) };
        let finished = view.poll()?;
        self.finish(finished);
        Ok(())
    }

    /// What the user must be told about the viewport's GPU since the last call: each new GPU
    /// error once, and a lost device, after which the view is recreated on a new device (the
    /// image on screen stays until the new renderer's first frame replaces it).
    pub fn gpu_problems(&mut self) -> Vec<GpuProblem> {
        let Some(view) = &mut self.view else { return Vec::new() };
        let mut messages = Vec::new();
        for problem in view.problems() {
            let why = match problem {
                GpuProblem::Error(e) => {
                    messages.push(GpuProblem::Error(format!("GPU error in the viewport: {e}")));
                    continue;
                }
                GpuProblem::Lost(why) => why,
            };
            let outcome = match view.restart() {
                Ok(()) => {
                    self.submitted = None;
                    self.controller = ScaleController::new();
                    "the viewport restarted on a new device; the project is unchanged".to_owned()
                }
                Err(e) => {
                    self.init_error = Some(e.to_string());
                    self.view = None;
                    format!("a new device could not be created ({e}); save your work and restart")
                }
            };
            messages.push(GpuProblem::Lost(format!("The viewport's GPU device was lost ({why}): {outcome}.")));
            break;
        }
        messages
    }

    /// The viewport device's GPU memory and live objects (wgpu's internal counters).
    pub fn gpu_memory(&self) -> Option<GpuMemory> {
        self.view.as_ref().map(AsyncView::gpu_memory)
    }

    /// Destroys the viewport's device as a driver reset would ("simulate device loss" in the
    /// View menu, and tests); the next [`Viewport::gpu_problems`] reports it and recovers.
    pub fn simulate_device_loss(&mut self) {
        if let Some(view) = &self.view {
            view.lose_device();
        }
    }

    /// Waits for the frame in flight and shows it (tests; before a full-size export).
    pub fn wait(&mut self) -> Result<(), RenderError> {
        let Some(view) = &mut self.view else { return Ok(()) };
        let finished = view.wait()?;
        self.finish(finished);
        Ok(())
    }

    fn finish(&mut self, finished: Option<super::preview::Finished>) {
        let (Some(view), Some(f)) = (&mut self.view, finished) else { return };
        self.controller.record(f.step, f.ms);
        self.last_frame_ms = f.ms;
        self.frames += 1;
        let passes = view.renderer_mut().timings(false);
        self.timings.push(f.ms, &passes);
        let options = egui::TextureOptions::LINEAR;
        match &mut self.texture {
            Some((t, step)) => {
                t.set(f.image, options);
                *step = f.step;
            }
            None => self.texture = Some((self.ctx.load_texture("viewport", f.image, options), f.step)),
        }
        // The device is idle now: reading the technique's markers does not wait.
        if self.gizmo.show_overlays && self.frames % 10 == 1 {
            self.overlays = view.renderer().overlays();
        }
    }

    /// Starts the next frame if none is in flight: at the scale the budget allows while
    /// something moves, at full resolution otherwise. An unchanged full-resolution view is
    /// rendered again only while the technique is still refining (temporal history short of
    /// its steady state, progressive samples short of their target).
    pub fn submit(&mut self, state: &mut EditorState) {
        let scene = &state.project.scene;
        let key = FrameKey {
            revision: scene.revision(),
            resources_revision: scene.resources_revision(),
            settings: state.project.render.clone(),
            size: self.size,
        };
        let changed = self.submitted.as_ref() != Some(&key);
        if changed && self.submitted.is_some() {
            self.changed_at = Some(Instant::now());
        }
        let moving = self.moving();
        let Some(view) = &mut self.view else { return };
        if view.busy() {
            return;
        }
        let accumulating = view.renderer().technique_status().is_some_and(|s| s.refining);
        let shown_full = self.texture.as_ref().is_some_and(|(_, step)| *step == 0);
        if !changed && !moving && shown_full && !accumulating {
            return;
        }
        let step = self.controller.next(moving, &self.preview);
        let size = scaled_size(self.size, step);
        let cost = super::preview::budget::COST[step];
        let settings = if cost < 1.0 { state.project.render.cheaper(cost) } else { state.project.render.clone() };
        match view.submit(scene, &settings, size, step) {
            Ok(()) => self.submitted = Some(key),
            Err(e) => {
                // Not again until something changes: the same frame would fail the same way.
                self.submitted = Some(key);
                state.report("render failed", &e);
            }
        }
    }

    /// Whether something moved within the last [`super::preview::budget::HOLD`].
    fn moving(&self) -> bool {
        self.interacting || self.changed_at.is_some_and(|t| t.elapsed() < super::preview::budget::HOLD)
    }

    /// A full-resolution frame, rendered now (waits for the GPU): the export's image.
    pub fn render_full(&mut self, state: &EditorState) -> Result<(), RenderError> {
        self.wait()?;
        let Some(view) = &mut self.view else { return Ok(()) };
        view.submit(&state.project.scene, &state.project.render, self.size, 0)?;
        self.wait()
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

    /// Toolbar, input, rendering and painting into the remaining space.
    pub fn ui(&mut self, ui: &mut egui::Ui, state: &mut EditorState) {
        if let Some(e) = &self.init_error {
            ui.label(format!("Renderer unavailable: {e}"));
            return;
        }
        self.toolbar(ui, state);
        let frame = self.allocate(ui, state);
        let hovered_axis = self.gizmo_handles(ui, state, &frame);
        self.drag(ui, state, &frame);
        self.release(ui, state, &frame.response);
        self.zoom(ui, &frame.response);
        self.pick(state, &frame);
        self.write_camera(state);
        self.count_frame(&frame);
        self.paint(ui, state, frame.rect, hovered_axis);
    }

    /// The toolbar: gizmo mode and options, overlay toggles, the GI mode and the preview menu.
    fn toolbar(&mut self, ui: &mut egui::Ui, state: &EditorState) {
        ui.horizontal(|ui| {
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Translate, "Move (G)");
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Rotate, "Rotate (R)");
            ui.selectable_value(&mut self.gizmo.mode, GizmoMode::Scale, "Scale (S)");
            ui.checkbox(&mut self.gizmo.local, "local axes");
            ui.checkbox(&mut self.gizmo.snap, "snap");
            ui.checkbox(&mut self.gizmo.show_overlays, "overlays").on_hover_text(
                "The active technique's markers: ISM's virtual point lights, coloured by bounce (refreshed every 10 frames); MRT's blocks, their links and the gaps they leave.",
            );
            ui.checkbox(&mut self.gizmo.show_points, "sample points")
                .on_hover_text("Where scene sample points land: area x sampling weight per object.");
            ui.label(format!("mode: {}", state.project.render.mode.name()));
            self.preview_menu(ui);
        });
    }

    /// Takes the remaining space for the image and reads its size, camera and pointer.
    fn allocate(&mut self, ui: &mut egui::Ui, state: &EditorState) -> UiFrame {
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
        self.rect = Some(rect);
        let ppp = ui.ctx().pixels_per_point();
        let size = ((rect.width() * ppp).round().max(1.0) as u32, (rect.height() * ppp).round().max(1.0) as u32);
        let view = View { camera: *state.project.scene.camera(), size: Vec2::new(rect.width(), rect.height()) };
        let mouse = response
            .hover_pos()
            .or(response.interact_pointer_pos())
            .map(|p| Vec2::new(p.x - rect.min.x, p.y - rect.min.y));
        UiFrame { rect, response, ppp, size, view, mouse }
    }

    /// The gizmo handle (index and world axis) of the selection at view position `m`.
    fn axis_at(view: &View, target: Option<(Vec3, Quat)>, local: bool, m: Vec2) -> Option<(usize, Vec3)> {
        let (origin, rotation) = target?;
        let len = view.world_size(origin, 70.0);
        gizmo::axes(rotation, local).into_iter().enumerate().find(|(_, axis)| {
            matches!((view.project(origin), view.project(origin + *axis * len)), (Some(a), Some(b)) if gizmo::segment_distance(m, a, b) < 8.0)
        })
    }

    /// Gizmo handles of the selection: returns the hovered one, and starts a drag where the
    /// button went down on one.
    fn gizmo_handles(&mut self, ui: &egui::Ui, state: &EditorState, f: &UiFrame) -> Option<(usize, Vec3)> {
        let (rect, view) = (f.rect, &f.view);
        let target = Self::target(state);
        let local = self.gizmo.local;
        let hovered_axis = f.mouse.and_then(|m| Self::axis_at(view, target, local, m));
        if f.response.drag_started_by(egui::PointerButton::Primary) {
            let press = ui.input(|i| i.pointer.press_origin()).map(|p| Vec2::new(p.x - rect.min.x, p.y - rect.min.y));
            if let (Some(p), Some((origin, rotation))) = (press, target)
                && let Some((_, axis)) = Self::axis_at(view, target, local, p)
            {
                self.drag = Drag::begin(view, self.gizmo.mode, axis, origin, rotation, p).map(|mut d| {
                    if let Selection::Object(i) = state.selection
                        && let Some(o) = state.project.scene.objects().get(i)
                    {
                        d.start_scale = o.transform.scale;
                    }
                    d
                });
            }
        }
        hovered_axis
    }

    /// A primary drag of a gizmo handle edits the selection; any other drag moves the camera.
    fn drag(&mut self, ui: &egui::Ui, state: &mut EditorState, f: &UiFrame) {
        if let (Some(drag), Some(m)) = (self.drag, f.mouse)
            && f.response.dragged_by(egui::PointerButton::Primary)
        {
            Self::apply_gizmo(state, &drag, &f.view, m, &self.gizmo);
        } else {
            self.navigate(ui, state, f);
        }
    }

    /// Camera drags: orbit (primary), pan (middle, or shift and secondary), fly (secondary).
    fn navigate(&mut self, ui: &egui::Ui, state: &EditorState, f: &UiFrame) {
        let response = &f.response;
        let d = response.drag_delta();
        if response.dragged_by(egui::PointerButton::Primary) {
            self.orbit.rotate(d.x, d.y);
        } else if response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Secondary) && ui.input(|i| i.modifiers.shift))
        {
            self.orbit.pan(d.x, d.y, f.rect.height(), state.project.scene.camera().yfov);
        } else if response.dragged_by(egui::PointerButton::Secondary) {
            self.fly(ui, d);
        }
    }

    /// Fly: look around with the right button (drag `d`), WASD/QE to move.
    fn fly(&mut self, ui: &egui::Ui, d: egui::Vec2) {
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

    /// Without a drag: ends the gizmo drag, and commits the edit once no button is down.
    fn release(&mut self, ui: &egui::Ui, state: &mut EditorState, response: &egui::Response) {
        if !response.dragged() {
            self.drag = None;
            if ui.input(|i| !i.pointer.any_down()) {
                state.history.commit(&state.project);
            }
        }
    }

    /// Scrolling over the view zooms the camera.
    fn zoom(&mut self, ui: &egui::Ui, response: &egui::Response) {
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.zoom(scroll);
            }
        }
    }

    /// Picking on a primary click: light icons first, then the object-id buffer.
    fn pick(&mut self, state: &mut EditorState, f: &UiFrame) {
        if f.response.clicked_by(egui::PointerButton::Primary)
            && let Some(m) = f.mouse
        {
            let light = (0..state.project.scene.lights().len()).find(|&i| {
                overlays::light_anchor(&state.project.scene, i)
                    .and_then(|p| f.view.project(p))
                    .is_some_and(|s| s.distance(m) < 10.0)
            });
            state.selection = match light {
                Some(i) => Selection::Light(i),
                None => match self.picker.pick(&state.project.scene, m.x * f.ppp, m.y * f.ppp, f.size) {
                    Some(i) => Selection::Object(i),
                    None => Selection::None,
                },
            };
        }
    }

    /// Camera: only written when the user moved it, so undo history stays clean.
    fn write_camera(&self, state: &mut EditorState) {
        let mut cam = *state.project.scene.camera();
        self.orbit.apply(&mut cam);
        if cam != *state.project.scene.camera() {
            state.project.scene.set_camera(cam);
        }
    }

    /// Records the view size and interaction, counts the UI frame and its interval, logs stats.
    fn count_frame(&mut self, f: &UiFrame) {
        self.size = f.size;
        self.interacting = f.response.dragged();
        self.ui_frames += 1;
        let now = Instant::now();
        let ui_ms = self.last.map_or(0.0, |l| (now - l).as_secs_f64() * 1e3);
        self.last = Some(now);
        self.timings.push_ui(ui_ms);
        self.log_stats();
    }

    /// Every 2 s at debug level (`RUST_LOG=bouncelab=debug`): the interface's frame intervals
    /// and the viewport frames of the window, what `docs/BENCHMARKS.md` quotes for the editor.
    fn log_stats(&mut self) {
        let (since, ui0, vp0) = self.stats;
        if since.elapsed().as_secs_f64() < 2.0 {
            return;
        }
        let n = (self.ui_frames - ui0) as usize;
        log::debug!(
            "preview: {n} UI frames in {:.1} s (interval max {:.0} ms, logic max {:.0} ms), {} viewport frames (last {:.0} ms at {:.0}%)",
            since.elapsed().as_secs_f64(),
            self.timings.ui_worst(n),
            self.logic_ms,
            self.frames - vp0,
            self.last_frame_ms,
            self.shown_scale().unwrap_or(0.0) * 100.0
        );
        self.stats = (Instant::now(), self.ui_frames, self.frames);
        self.logic_ms = 0.0;
    }

    /// The frame budget and adaptive scale, in a small menu of the toolbar.
    fn preview_menu(&mut self, ui: &mut egui::Ui) {
        // A fixed label: a width that followed the scale would move the layout, resize the view
        // and so start another frame at another scale, for ever.
        ui.menu_button("preview", |ui| {
            let scale = self.shown_scale().unwrap_or(1.0);
            ui.label(format!("showing {:.0}% resolution", scale * 100.0));
            ui.checkbox(&mut self.preview.adaptive, "adapt the render scale").on_hover_text(
                "While something moves, render at the scale that holds the frame budget; full resolution when idle.",
            );
            ui.add(
                egui::DragValue::new(&mut self.preview.budget_ms)
                    .range(1.0..=5000.0)
                    .speed(1.0)
                    .suffix(" ms")
                    .prefix("frame budget "),
            );
            ui.label(format!("last viewport frame {:.0} ms", self.last_frame_ms));
            for (k, s) in LADDER.iter().enumerate() {
                if let Some(ms) = self.controller.predict(k) {
                    ui.label(format!("{:>3.0}%: ~{ms:.0} ms", s * 100.0));
                }
            }
        });
    }
}
