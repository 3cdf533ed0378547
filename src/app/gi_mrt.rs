//! The GI panel's `mrt` section: the runtime settings and the dictionary's parameters with
//! their cost as tooltips, and the command that fits proxy blocks to the level.

use crate::settings::MrtSettings;

/// Draws the mrt settings; true when "Fit proxy blocks" was clicked.
pub fn mrt_ui(m: &mut MrtSettings, ui: &mut egui::Ui) -> bool {
    let mut fit = false;
    egui::CollapsingHeader::new("Modular radiance transfer (Loos 2015)").default_open(true).show(ui, |ui| {
        fit = ui
            .button("Fit proxy blocks")
            .on_hover_text("Add proxy blocks fitted to the level's rooms and doorways as objects you can move, resize and open (refused where the scene has blocks). Without blocks, mrt fits them on the fly and says so.")
            .clicked();
        ui.add(egui::Slider::new(&mut m.feedback, 0.0..=1.0).text("bounce feedback"))
            .on_hover_text("Each frame adds albedo x the last frame's indirect light to the texels' direct light: one more bounce per frame (0 = one bounce). Free.");
        ui.checkbox(&mut m.padding, "pad across open sides")
            .on_hover_text("Blend towards the block beyond within half a texel of a side open over its whole area, so blocks meet without a seam (off: the unpadded lightmap). Cost: a second lookup near such sides.");
        ui.add(egui::Slider::new(&mut m.depth, 0..=16).text("propagation depth"))
            .on_hover_text("Blocks beyond a source's neighbours its light is carried through the interfaces. Cost: T_b->r grows with the blocks reached (level rebuild and per-frame r).");
        egui::CollapsingHeader::new("Dictionary (precomputed, cached)").default_open(false).show(ui, |ui| {
            let d = &mut m.dictionary;
            egui::ComboBox::from_label("texels per face side").selected_text(d.res.to_string()).show_ui(ui, |ui| {
                for r in [4, 6, 8, 12, 16] {
                    ui.selectable_value(&mut d.res, r, r.to_string());
                }
            })
            .response
            .on_hover_text("The dissertation's 16. A new value builds a new dictionary (about 22 s at 16 on two cores, then cached): the gather grows with its square, the SVDs up to its fourth power.");
            ui.add(egui::Slider::new(&mut d.k_b, 4..=d.k_d.max(4)).text("modes k_b"))
                .on_hover_text("Indirect modes per block (32 on desktop, 12 on the iPad). Per frame: k_b x texels multiply-adds per block for b and again for U_b b.");
            ui.add(egui::Slider::new(&mut d.rays, 64..=16384).logarithmic(true).text("gather rays per texel"))
                .on_hover_text("The dictionary's gather (the dissertation: 16K). Build time is linear in it.");
        });
    });
    fit
}
