//! What the viewport paints over the rendered image with egui, at full resolution whatever the
//! render scale: the status text, the sample points, the technique's markers and the gizmo.

use super::*;

impl Viewport {
    /// Draws the scene sample points, redistributing them when weights or geometry change.
    pub(super) fn draw_points(&mut self, painter: &egui::Painter, rect: egui::Rect, view: &View, state: &EditorState) {
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
                    crate::app::inspector::false_colour(((sp.object.wrapping_mul(2_654_435_761)) >> 24) as f32 / 255.0);
                painter.circle_filled(rect.min + egui::vec2(s.x, s.y), 1.5, egui::Color32::from_rgb(r, g, b));
            }
        }
    }

    /// Paints the latest image, the status text, the scene overlays, the sample points, the
    /// technique's markers and the gizmo, from the camera as this frame left it.
    pub(super) fn paint(
        &mut self,
        ui: &egui::Ui,
        state: &EditorState,
        rect: egui::Rect,
        hovered_axis: Option<(usize, Vec3)>,
    ) {
        let painter = ui.painter_at(rect);
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        if let Some((t, _)) = &self.texture {
            painter.image(t.id(), rect, uv, egui::Color32::WHITE);
        }
        self.status_text(&painter, rect, state.project.render.mode);
        let view = View { camera: *state.project.scene.camera(), size: Vec2::new(rect.width(), rect.height()) };
        let blocks = state.project.render.mode == crate::settings::GiMode::Mrt;
        overlays::draw(&painter, rect, &view, &state.project.scene, state.selection, blocks);
        if self.gizmo.show_points {
            self.draw_points(&painter, rect, &view, state);
        }
        self.draw_markers(&painter, rect, &view);
        self.draw_gizmo(&painter, rect, &view, state, hovered_axis);
    }

    /// The technique's markers while the overlays are on; forgets them when they are off.
    pub(super) fn draw_markers(&mut self, painter: &egui::Painter, rect: egui::Rect, view: &View) {
        if self.gizmo.show_overlays {
            // Turned on over an idle view (a converged cache renders no more frames): read the
            // markers once now.
            if !self.overlays_read
                && let Some(view) = self.view.as_ref().filter(|v| !v.busy())
            {
                self.overlays = view.renderer().overlays();
                self.overlays_read = true;
            }
            overlays::draw_markers(painter, rect, view, &self.overlays);
        } else {
            self.overlays.clear();
            self.overlays_read = false;
        }
    }

    /// The selection's gizmo: an axis line per handle (thicker when hovered or dragged) and the
    /// mode's end shape.
    pub(super) fn draw_gizmo(
        &self,
        painter: &egui::Painter,
        rect: egui::Rect,
        view: &View,
        state: &EditorState,
        hovered_axis: Option<(usize, Vec3)>,
    ) {
        let Some((origin, rotation)) = Self::target(state) else { return };
        let len = view.world_size(origin, 70.0);
        for (k, axis) in gizmo::axes(rotation, self.gizmo.local).into_iter().enumerate() {
            if let (Some(a), Some(b)) = (view.project(origin), view.project(origin + axis * len)) {
                let hot = hovered_axis.is_some_and(|(h, _)| h == k) || self.drag.is_some_and(|d| d.axis == axis);
                let stroke = egui::Stroke::new(if hot { 4.0 } else { 2.5 }, AXIS_COLOURS[k]);
                let (pa, pb) = (rect.min + egui::vec2(a.x, a.y), rect.min + egui::vec2(b.x, b.y));
                painter.line_segment([pa, pb], stroke);
                self.draw_handle_end(painter, pb, k, stroke);
            }
        }
    }

    /// The end of gizmo handle `k` at `pb`: a dot (move), a ring (rotate) or a square (scale).
    pub(super) fn draw_handle_end(&self, painter: &egui::Painter, pb: egui::Pos2, k: usize, stroke: egui::Stroke) {
        match self.gizmo.mode {
            GizmoMode::Translate => {
                painter.circle_filled(pb, 4.0, AXIS_COLOURS[k]);
            }
            GizmoMode::Rotate => {
                painter.circle_stroke(pb, 6.0, stroke);
            }
            GizmoMode::Scale => {
                painter.rect_filled(egui::Rect::from_center_size(pb, egui::vec2(8.0, 8.0)), 0.0, AXIS_COLOURS[k]);
            }
        }
    }

    /// The technique's progress and the preview's refinement in the image's top-left corner.
    pub(super) fn status_text(&self, painter: &egui::Painter, rect: egui::Rect, mode: crate::settings::GiMode) {
        let mut lines = Vec::new();
        let status = self.renderer().and_then(Renderer::technique_status);
        if let Some(text) = status.as_ref().and_then(|s| s.progress.clone()) {
            lines.push(text);
        }
        // Temporal history (frames) toward its steady state; the reference reports its samples
        // in its own progress line.
        if let Some(s) = status.filter(|s| s.refining && s.refine_target > 0)
            && self.shown_scale() == Some(1.0)
            && mode != crate::settings::GiMode::Reference
        {
            let left = f64::from(s.refine_target.saturating_sub(s.history_frames)) * self.last_frame_ms / 1e3;
            lines.push(format!(
                "refining: {} / {} frames of history, ~{left:.0} s to go",
                s.history_frames, s.refine_target
            ));
        }
        if let Some(scale) = self.shown_scale().filter(|s| *s < 1.0) {
            let full = self.controller.predict(0).map_or(String::new(), |ms| format!(" · full in ~{:.1} s", ms / 1e3));
            // While something moves the next frame is another preview; after that, full resolution.
            let state = if self.moving() { "preview" } else { "refining" };
            lines.push(format!("{state} {:.0}%{full}", scale * 100.0));
        }
        for (k, line) in lines.into_iter().enumerate() {
            painter.text(
                rect.left_top() + egui::vec2(8.0, 8.0 + 16.0 * k as f32),
                egui::Align2::LEFT_TOP,
                line,
                egui::FontId::proportional(13.0),
                egui::Color32::WHITE,
            );
        }
    }
}
