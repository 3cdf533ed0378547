//! The GI panel's `sshgi` section: every SshgiSettings field with its cost/quality trade-off as
//! a tooltip.

use crate::settings::SshgiSettings;

/// Draws the sshgi settings.
pub fn sshgi_ui(m: &mut SshgiSettings, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Screen-space hierarchical GI (Soler 2010)").default_open(true).show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.label("start resolution");
            for (level, name) in [(0, "full"), (1, "half"), (2, "quarter")] {
                ui.radio_value(&mut m.start_level, level, name);
            }
        })
        .response
        .on_hover_text("The start level's gather dominates the cost: each step finer costs about 4x (the paper: 6.6 ms at a quarter, 25.9 ms at half, 1280x720).");
        ui.add(egui::Slider::new(&mut m.levels, 1..=6).text("levels"))
            .on_hover_text("Each level doubles the reach for about a quarter of the previous level's cost.");
        ui.add(egui::Slider::new(&mut m.samples, 1..=1024).logarithmic(true).text("samples per level"))
            .on_hover_text("Cost: every gather is linear in it; quality: less noise (the paper: 64 or 256).");
        ui.add(egui::Slider::new(&mut m.radius, 0.0..=128.0).text("ring radius (texels, 0 = automatic)"))
            .on_hover_text("Automatic: the smallest radius whose disc on the coarsest level spans the view.");
        ui.add(egui::Slider::new(&mut m.bounces, 1..=4).text("bounces"))
            .on_hover_text("Each bounce gathers albedo x the previous one again: one more gather chain (linear cost).");
    });
}
