//! The GI panel: the live mode switch (modes this build or adapter cannot run are disabled
//! with the reason) and every setting, each with its cost/quality trade-off as a tooltip.

use super::state::EditorState;
use crate::render::Renderer;
use crate::settings::{GiMode, Tonemap};

const MODES: [GiMode; 7] =
    [GiMode::Direct, GiMode::Ism, GiMode::IsmRitschel, GiMode::Mrt, GiMode::Sshgi, GiMode::Rcs, GiMode::Reference];

fn mode_tip(mode: GiMode) -> &'static str {
    match mode {
        GiMode::Direct => "Shadowed punctual lights only: the baseline every technique adds to.",
        GiMode::Ism => "Instant radiosity with imperfect shadow maps and temporal reuse (Knecht 2009).",
        GiMode::IsmRitschel => {
            "The same ISM pipeline without temporal reuse (Ritschel 2008): the baseline for flicker."
        }
        GiMode::Mrt => "Modular and delta radiance transfer on proxy blocks (Loos 2015).",
        GiMode::Sshgi => "Screen-space hierarchical indirect light (Soler et al. 2010).",
        GiMode::Rcs => "GPU irradiance caching by radiance cache splatting (Gautron et al.).",
        GiMode::Reference => "Progressive CPU path tracer: the ground truth (shown in the inspector's comparison).",
    }
}

/// Draws the GI panel and records setting changes as undo steps.
pub fn gi_ui(state: &mut EditorState, ui: &mut egui::Ui) {
    let mut render = state.project.render.clone();
    ui.label(egui::RichText::new("Mode").strong());
    for mode in MODES {
        let available = if mode == GiMode::Reference { Ok(()) } else { Renderer::supports(mode) };
        let enabled = available.is_ok();
        let tip = match &available {
            Ok(()) => mode_tip(mode).to_owned(),
            Err(reason) => format!("{} Unavailable: {reason}.", mode_tip(mode)),
        };
        ui.add_enabled(enabled, egui::RadioButton::new(render.mode == mode, mode.name()))
            .on_hover_text(&tip)
            .on_disabled_hover_text(&tip)
            .clicked()
            .then(|| render.mode = mode);
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
    egui::CollapsingHeader::new("ISM (Knecht 2009)").default_open(false).show(ui, |ui| {
        let m = &mut render.ism;
        ui.add(egui::Slider::new(&mut m.vpl_count, 4..=1024).logarithmic(true).text("VPLs"))
            .on_hover_text("Cost: shading and ISM splatting grow linearly; quality: fewer blotches, less flicker (256 for flicker-free).");
        egui::ComboBox::from_label("ISM resolution").selected_text(m.ism_resolution.to_string()).show_ui(ui, |ui| {
            for r in [64, 128, 256] {
                ui.selectable_value(&mut m.ism_resolution, r, r.to_string());
            }
        });
        ui.add(egui::Slider::new(&mut m.total_points, 1024..=1 << 20).logarithmic(true).text("sample points"))
            .on_hover_text("Split over the ISMs (points per ISM = points / VPLs). Too few: holes and light leaks.");
        ui.add(egui::Slider::new(&mut m.interleave, 1..=8).text("interleave n"))
            .on_hover_text("Each pixel sees VPLs / n² VPLs; the n x n filter hides the pattern.");
        ui.add(egui::Slider::new(&mut m.bounces, 1..=6).text("bounces")).on_hover_text("Each extra bounce: one VPL, ISM and shading pass.");
        ui.add(egui::Slider::new(&mut m.base_confidence, 0.0..=0.99).text("base confidence"))
            .on_hover_text("Higher: smoother over time, more afterglow after lighting changes.");
        ui.add(egui::Slider::new(&mut m.w_position, 0.0..=100.0).text("w position"));
        ui.add(egui::Slider::new(&mut m.w_normal, 0.0..=100.0).text("w normal"));
        ui.add(egui::Slider::new(&mut m.w_illumination, 0.0..=100.0).text("w illumination"))
            .on_hover_text("Higher: reacts faster to lighting changes, but lets VPL resampling noise through.");
        ui.add(egui::Slider::new(&mut m.clamp_distance, 0.0..=2.0).text("clamp distance (m)"))
            .on_hover_text("Minimum VPL distance: fewer spikes near VPLs, darker corners (bias).");
        ui.add(egui::Slider::new(&mut m.filter_depth, 0.001..=0.1).logarithmic(true).text("filter plane tolerance"))
            .on_hover_text("Geometry-aware filter: neighbours farther than this x scene diameter from the pixel's tangent plane are rejected. Lower: sharper contacts, more interleave pattern.");
        ui.add(egui::Slider::new(&mut m.filter_normal, 0.0..=1.0).text("filter normal cosine"))
            .on_hover_text("Neighbours whose normal differs by a cosine below this are rejected (the SH filter tests geometric normals only).");
        ui.checkbox(&mut m.sh_filter, "SH filter (Segovia & Wald)").on_hover_text(
            "Filter incident radiance as 9 SH coefficients per colour, then shade with each pixel's own normal-mapped normal and glossy lobe. Cost: 56 bytes per pixel and 27-channel filtering (`ism shade` +7% at 320x180, +17% at 640x360 in docs/BENCHMARKS.md).",
        );
    });
    egui::CollapsingHeader::new("Reference path tracer").default_open(false).show(ui, |ui| {
        let r = &mut render.reference;
        ui.add(egui::Slider::new(&mut r.spp, 1..=16384).logarithmic(true).text("samples per pixel"))
            .on_hover_text("Cost: linear; noise falls as 1/sqrt(spp).");
        ui.add(egui::Slider::new(&mut r.max_bounces, 1..=64).text("max bounces"))
            .on_hover_text("1 = direct light only. Cutting paths short darkens the image (bias).");
        ui.add(egui::Slider::new(&mut r.rr_start, 1..=64).text("Russian roulette from"))
            .on_hover_text("Unbiased; earlier = faster but noisier.");
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
