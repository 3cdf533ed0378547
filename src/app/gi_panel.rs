//! The GI panel: the live mode switch (modes this build or adapter cannot run are disabled
//! with the reason), what the active technique leaves out, its history and GPU memory, and
//! every setting with its cost/quality trade-off as a tooltip. Each technique's own section
//! lives in its own file (`gi_ism.rs`, `gi_sshgi.rs`, `gi_mrt.rs`, `gi_rcs.rs`).

use super::state::EditorState;
use crate::render::Renderer;
use crate::render::gi::registry;
use crate::settings::{GiMode, RenderSettings, Tonemap};

/// A technique's settings section: draws it for `render`'s settings; true when the user asked
/// for an action the panel carries out after the section (MRT's "fit proxy blocks").
pub type Section = fn(&mut egui::Ui, &mut RenderSettings, &EditorState) -> bool;

/// The editor's side of each row of [`registry::TECHNIQUES`], in the same order: the row's
/// name and its settings section (`None`: the technique has no settings of its own here).
/// Adding a technique adds its row here and its `gi_<name>.rs`; a test checks that the two
/// tables agree.
pub const SECTIONS: &[(&str, Option<Section>)] = &[
    ("direct light", None),
    (
        "imperfect shadow maps (Ritschel 2008, Knecht 2009)",
        Some(|ui, r, _| {
            super::gi_ism::ism_ui(&mut r.ism, ui);
            false
        }),
    ),
    ("modular and delta radiance transfer (Loos 2011, 2012, 2015)", Some(mrt_section)),
    (
        "screen-space hierarchical GI (Soler et al. 2010)",
        Some(|ui, r, _| {
            super::gi_sshgi::sshgi_ui(&mut r.sshgi, ui);
            false
        }),
    ),
    (
        "radiance cache splatting (Gautron et al. 2005)",
        Some(|ui, r, _| {
            super::gi_rcs::rcs_ui(&mut r.rcs, ui);
            false
        }),
    ),
    // The reference's settings are always shown (the inspector's comparison uses them).
    ("reference path tracer (CPU)", None),
];

/// The settings section of the technique serving `mode`.
fn technique_section(mode: GiMode) -> Option<Section> {
    let index = registry::entry_index(mode)?;
    SECTIONS.get(index).and_then(|(_, section)| *section)
}

/// MRT's section: its settings, with the scene's static objects and proxy blocks for the
/// block overrides; true when "fit proxy blocks" was pressed.
fn mrt_section(ui: &mut egui::Ui, render: &mut RenderSettings, state: &EditorState) -> bool {
    let names = |role: crate::scene::ObjectRole| -> Vec<String> {
        state.project.scene.objects().iter().filter(|o| o.role == role).map(|o| o.name.clone()).collect()
    };
    let (objects, blocks) = (names(crate::scene::ObjectRole::Static), names(crate::scene::ObjectRole::ProxyBlock));
    super::gi_mrt::mrt_ui(&mut render.mrt, ui, &objects, &blocks)
}

/// The scene-level choices: the light units the scene's glTF files are read in, an export
/// writes and the properties panel shows (the lights themselves do not change), and the sky.
fn scene_ui(state: &mut EditorState, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Scene").default_open(false).show(ui, |ui| {
        super::sky_panel::sky_ui(state, ui);
        ui.separator();
        let mut units = state.project.scene.desc().light_units;
        egui::ComboBox::from_label("light units").selected_text(units.name()).show_ui(ui, |ui| {
            for u in crate::scene::LightUnits::ALL {
                ui.selectable_value(&mut units, u, u.name());
            }
        })
        .response
        .on_hover_text(
            "photometric: candela and lux, the glTF specification's units (Blender, Godot and Bevy write and read them); \
             radiometric: W/sr and W/m². The units the scene's glTF files are read in where they do not record theirs, \
             that an export writes, and that the properties panel shows. The lights stay as bright as they are.",
        );
        if units != state.project.scene.desc().light_units {
            state.history.begin("Light units", &state.project);
            state.project.scene.desc_mut().light_units = units;
            state.history.commit(&state.project);
        }
        if state.project.has_unrecorded_lights() {
            let tip = "The glTF file does not say what its light numbers are: read them again as the light units above \
                       (candela and lux, or W/sr and W/m²). Lights edited since keep their values.";
            if ui.button(format!("Read the file's lights as {}", units.name())).on_hover_text(tip).clicked() {
                let before = super::history::Snapshot::of(&state.project);
                let n = state.project.reread_file_lights(units);
                state.history.record("Read lights as", before, &state.project);
                state.status = format!("read {n} lights of the glTF file as {}", units.name());
            }
        }
    });
}

/// Draws the GI panel and records setting changes as undo steps; `renderer` answers which
/// modes can run at the viewport's `size`.
pub fn gi_ui(state: &mut EditorState, ui: &mut egui::Ui, renderer: Option<&Renderer>, size: (u32, u32)) {
    let mut render = state.project.render.clone();
    ui.label(egui::RichText::new("Mode").strong());
    for row in registry::modes() {
        let mode = row.mode;
        let candidate = RenderSettings { mode, ..render.clone() };
        let available = match renderer {
            Some(r) => r.support(&candidate, size),
            None => Err("no renderer: the GPU is unavailable".to_owned()),
        };
        let enabled = available.is_ok();
        let tip = match &available {
            Ok(()) => row.tip.to_owned(),
            Err(reason) => format!("{} Unavailable: {reason}.", row.tip),
        };
        ui.add_enabled(enabled, egui::RadioButton::new(render.mode == mode, mode.name()))
            .on_hover_text(&tip)
            .on_disabled_hover_text(&tip)
            .clicked()
            .then(|| render.mode = mode);
    }
    if render.mode == GiMode::Sshgi {
        state.unseen.update(&state.project.scene, size);
        if state.unseen.wants_repaint(&state.project.scene) {
            ui.ctx().request_repaint_after(std::time::Duration::from_millis(100));
        }
    }
    if let Some(r) = renderer {
        technique_summary(ui, r, state);
    }
    ui.separator();
    egui::CollapsingHeader::new("Shadows").default_open(true).show(ui, |ui| {
        let s = &mut render.shadows;
        egui::ComboBox::from_label("resolution").selected_text(s.resolution.to_string()).show_ui(ui, |ui| {
            for r in [256, 512, 1024, 2048, 4096] {
                ui.selectable_value(&mut s.resolution, r, r.to_string());
            }
        })
        .response
        .on_hover_text("Side of each shadow map (x6 for point lights). Cost: memory and raster time grow with its square; quality: sharper edges.");
        ui.add(egui::Slider::new(&mut s.pcf_radius, 0..=4).text("PCF radius"))
            .on_hover_text("Filter taps (2r+1)², each a 2x2 hardware comparison. Cost: linear in taps; quality: softer, less aliased edges.");
        ui.add(egui::Slider::new(&mut s.normal_bias_texels, 0.0..=4.0).text("normal bias (texels)"))
            .on_hover_text("Receiver offset along the normal on top of the receiver-plane bias. Free; too large leaks light at contacts.");
    });
    let fit = technique_section(render.mode).is_some_and(|section| section(ui, &mut render, state));
    super::gi_vo::vo_ui(&mut render.vo, render.mode, ui);
    if fit {
        match super::edits::fit_proxy_blocks(&mut state.project, &mut state.history) {
            Ok(fitted) => {
                state.selection = fitted.selection;
                state.status = fitted.status();
            }
            Err(e) => state.report("fit proxy blocks", &e),
        }
    }
    scene_ui(state, ui);
    egui::CollapsingHeader::new("Reference path tracer").default_open(false).show(ui, |ui| {
        let r = &mut render.reference;
        ui.add(egui::Slider::new(&mut r.spp, 1..=16384).logarithmic(true).text("samples per pixel"))
            .on_hover_text("Cost: linear; noise falls as 1/sqrt(spp) or faster (stratified samples).");
        ui.add(egui::Slider::new(&mut r.max_bounces, 1..=64).text("max bounces"))
            .on_hover_text("1 = direct light only. Cutting paths short darkens the image (bias).");
        ui.add(egui::Slider::new(&mut r.rr_start, 1..=64).text("Russian roulette from"))
            .on_hover_text("Unbiased; earlier = faster but noisier.");
        ui.checkbox(&mut r.guiding, "path guiding").on_hover_text(
            "Unbiased: bounces learn from earlier passes where the light comes from. Less noise a \
             sample where light arrives by bounces (Cornell box: half the samples for nearly \
             the same error), but 30-80% more time a sample: a net gain only in such views.",
        );
    });
    egui::CollapsingHeader::new("View").default_open(true).show(ui, |ui| {
        let v = &mut render.view;
        ui.add(egui::Slider::new(&mut v.exposure_ev, -8.0..=8.0).text("exposure (EV)"))
            .on_hover_text("Display only; EXR output is before exposure.");
        egui::ComboBox::from_label("tonemap").selected_text(format!("{:?}", v.tonemap)).show_ui(ui, |ui| {
            for t in [Tonemap::Aces, Tonemap::Reinhard, Tonemap::Clamp] {
                ui.selectable_value(&mut v.tonemap, t, format!("{t:?}"));
            }
        });
    });
    if render != state.project.render {
        match render.validate() {
            Ok(()) => {
                state.history.begin("GI settings", &state.project);
                state.project.render = render;
            }
            // The edit is refused; say why instead of letting the slider snap back silently.
            Err(e) => state.status = format!("setting not applied: {e}"),
        }
    }
}

/// What the active technique leaves out, its history and the GPU memory each technique holds.
fn technique_summary(ui: &mut egui::Ui, renderer: &Renderer, state: &EditorState) {
    let (warn, error) = (ui.visuals().warn_fg_color, ui.visuals().error_fg_color);
    // What makes the view other than what was asked for comes first, in the error colour.
    let mut shortfalls = state.project.shortfalls();
    shortfalls.extend(renderer.shortfalls(&state.project.scene, &state.project.render));
    for problem in shortfalls {
        ui.colored_label(error, problem);
    }
    for note in renderer.limitations(&state.project.scene, &state.project.render) {
        ui.colored_label(warn, note);
    }
    if state.project.render.mode == GiMode::Sshgi {
        ui.colored_label(warn, state.unseen.line(&state.project.scene)).on_hover_text(
            "Measured with the path tracer on the CPU: the indirect light of the view by the surface it left last. \
             sshgi gathers from the screen only; light from surfaces off screen or behind others is missing from it. \
             `bouncelab unseen-light` prints it per scene.",
        );
    }
    if let Some(s) = renderer.technique_status().filter(|s| s.history_frames > 0) {
        let reset = s.last_reset.map_or("none".to_owned(), |r| r.label().to_owned());
        ui.label(format!("history: {} frames · last reset: {reset}", s.history_frames))
            .on_hover_text("Frames accumulated since the technique last dropped its history, and why it did.");
    }
    let memory: Vec<String> = renderer
        .technique_gpu_bytes()
        .into_iter()
        .filter(|(_, b)| *b > 0)
        .map(|(m, b)| format!("{} {:.1} MiB", m.name(), b as f64 / (1024.0 * 1024.0)))
        .collect();
    if !memory.is_empty() {
        ui.label(format!("GPU memory: {}", memory.join(", ")))
            .on_hover_text("Buffers and textures each technique holds; a mode that is not active holds none.");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_technique_row_has_its_panel_row_in_the_same_order() {
        let rows: Vec<&str> = registry::TECHNIQUES.iter().map(|t| t.name).collect();
        let panels: Vec<&str> = SECTIONS.iter().map(|(name, _)| *name).collect();
        assert_eq!(rows, panels, "app::gi_panel::SECTIONS must follow render::gi::registry::TECHNIQUES");
        for mode in [GiMode::Ism, GiMode::IsmRitschel, GiMode::Mrt, GiMode::Sshgi, GiMode::Rcs] {
            assert!(technique_section(mode).is_some(), "{} has settings of its own", mode.name());
        }
    }
}
