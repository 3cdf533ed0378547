//! The outliner: every object and light, selection, and the add / duplicate / delete actions.
//! A filter narrows the list by name, and only the rows on screen are laid out, so a level
//! with 100,000 objects costs the interface the rows it shows, not every row every frame.

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
            if ui
                .button("Fit proxy blocks")
                .on_hover_text("MRT: find the level's box-shaped rooms and corridors and their doorways, and add a proxy block for each (edit them afterwards)")
                .clicked()
            {
                result = Some(edits::fit_proxy_blocks(&mut state.project, &mut state.history).map(|fitted| {
                    state.status = fitted.status();
                    fitted.selection
                }));
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
    let filter_id = egui::Id::unique("outliner filter");
    let mut filter: String = ui.data(|d| d.get_temp(filter_id)).unwrap_or_default();
    ui.horizontal(|ui| {
        ui.label("Filter");
        ui.add(egui::TextEdit::singleline(&mut filter).hint_text("name"));
    });
    ui.data_mut(|d| d.insert_temp(filter_id, filter.clone()));
    let rows = rows(state, &filter.to_lowercase());
    let height = ui.spacing().interact_size.y;
    egui::ScrollArea::vertical().show_rows(ui, height, rows.len(), |ui, range| {
        for row in &rows[range] {
            match *row {
                Row::Header(text) => {
                    ui.label(egui::RichText::new(text).strong());
                }
                Row::Light(i) => {
                    let Some(light) = state.project.scene.lights().get(i) else { continue };
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
                Row::Object(i) => {
                    let Some(object) = state.project.scene.objects().get(i) else { continue };
                    let selected = state.selection == Selection::Object(i);
                    if ui.selectable_label(selected, format!("{}{}", object.name, role_tag(object.role))).clicked() {
                        state.selection = Selection::Object(i);
                    }
                }
            }
        }
    });
}

/// One line of the outliner.
#[derive(Clone, Copy)]
enum Row {
    Header(&'static str),
    Light(usize),
    Object(usize),
}

/// The rows whose names contain `filter` (lower case; empty: every row), under their headers.
fn rows(state: &EditorState, filter: &str) -> Vec<Row> {
    let keep = |name: &str| filter.is_empty() || name.to_lowercase().contains(filter);
    let scene = &state.project.scene;
    let mut rows = vec![Row::Header("Lights")];
    rows.extend(scene.lights().iter().enumerate().filter(|(_, l)| keep(&l.name)).map(|(i, _)| Row::Light(i)));
    rows.push(Row::Header("Objects"));
    rows.extend(scene.objects().iter().enumerate().filter(|(_, o)| keep(&o.name)).map(|(i, _)| Row::Object(i)));
    rows
}
