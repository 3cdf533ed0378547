//! The outliner: every object and light, selection, and the add / duplicate / delete actions.

use super::edits::{self, Selection};
use super::state::EditorState;
use crate::scene::{LightKind, ObjectRole};

fn role_tag(role: ObjectRole) -> &'static str {
    match role {
        ObjectRole::Static => "",
        ObjectRole::ProxyBlock => " [proxy]",
        ObjectRole::Clutter => " [clutter]",
    }
}

/// Draws the outliner.
pub fn outliner_ui(state: &mut EditorState, ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        let mut result = None;
        ui.menu_button("Add", |ui| {
            if ui.button("Point light").clicked() {
                result = Some(edits::add_light(&mut state.project, &mut state.history, LightKind::Point));
            }
            if ui.button("Spot light").clicked() {
                let spot = LightKind::Spot { inner_cone_angle: 0.3, outer_cone_angle: 0.6 };
                result = Some(edits::add_light(&mut state.project, &mut state.history, spot));
            }
            if ui.button("Directional light").clicked() {
                result = Some(edits::add_light(&mut state.project, &mut state.history, LightKind::Directional));
            }
            ui.separator();
            if ui.button("Proxy block").clicked() {
                result = Some(edits::add_box(&mut state.project, &mut state.history, ObjectRole::ProxyBlock));
            }
            if ui.button("Clutter box").clicked() {
                result = Some(edits::add_box(&mut state.project, &mut state.history, ObjectRole::Clutter));
            }
            if ui.button("Clutter from glTF...").clicked()
                && let Some(path) = rfd::FileDialog::new().add_filter("glTF", &["gltf", "glb"]).pick_file()
            {
                result = Some(edits::add_clutter_asset(&mut state.project, &mut state.history, &path));
            }
        });
        let has_selection = state.selection != Selection::None;
        if ui.add_enabled(has_selection, egui::Button::new("Duplicate")).on_hover_text("Ctrl+D").clicked() {
            result = Some(edits::duplicate(&mut state.project, &mut state.history, state.selection));
        }
        if ui.add_enabled(has_selection, egui::Button::new("Delete")).on_hover_text("Delete").clicked() {
            result = Some(edits::delete(&mut state.project, &mut state.history, state.selection));
        }
        match result {
            Some(Ok(sel)) => state.selection = sel,
            Some(Err(e)) => state.report("edit failed", &e),
            None => {}
        }
    });
    ui.separator();
    egui::ScrollArea::vertical().show(ui, |ui| {
        ui.label(egui::RichText::new("Lights").strong());
        for (i, light) in state.project.scene.lights().iter().enumerate() {
            let kind = match light.kind {
                LightKind::Point => "point",
                LightKind::Spot { .. } => "spot",
                LightKind::Directional => "directional",
            };
            let selected = state.selection == Selection::Light(i);
            if ui.selectable_label(selected, format!("{} ({kind})", light.name)).clicked() {
                state.selection = Selection::Light(i);
            }
        }
        ui.add_space(6.0);
        ui.label(egui::RichText::new("Objects").strong());
        for (i, object) in state.project.scene.objects().iter().enumerate() {
            let selected = state.selection == Selection::Object(i);
            if ui.selectable_label(selected, format!("{}{}", object.name, role_tag(object.role))).clicked() {
                state.selection = Selection::Object(i);
            }
        }
    });
}
