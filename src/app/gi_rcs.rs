//! The GI panel's radiance cache splatting section (Gautron et al. 2005): the cache's accuracy,
//! record computation and budget settings, each with its cost as a tooltip (the `bouncelab bench`
//! rcs table has the measured figures).

use crate::settings::RcsSettings;

/// Draws the rcs settings.
pub fn rcs_ui(s: &mut RcsSettings, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Radiance cache splatting").default_open(true).show(ui, |ui| {
        ui.add(egui::Slider::new(&mut s.accuracy, 0.05..=1.0).logarithmic(true).text("accuracy a"))
            .on_hover_text("Ward's a: a record reaches a x R around it (R its harmonic mean distance). Smaller: more records, about 1/a² of them, each one render of the scene; larger: blotches. Changing it rebuilds the cache.");
        egui::ComboBox::from_label("hemisphere resolution")
            .selected_text(format!("{0}x{0}", s.hemisphere_resolution))
            .show_ui(ui, |ui| {
                for r in [8, 16, 32, 64] {
                    ui.selectable_value(&mut s.hemisphere_resolution, r, format!("{r}x{r}"));
                }
            })
            .response
            .on_hover_text("Texels of each record's wide-angle plane (126.87 degrees plus the border band). Cost: each record's raster and reduction grow with the square; small planes miss thin senders.");
        ui.checkbox(&mut s.gradients, "gradients")
            .on_hover_text("Ward and Heckbert's rotational and translational gradients in the interpolation: smooth where flat records leave discs. Free at splat time (the gradients are always computed).");
        ui.add(egui::Slider::new(&mut s.bounces, 1..=16).text("bounces (most)"))
            .on_hover_text("1: the records see the direct light only. Each further bounce is a pass renewing every record with the cache's own light at what it sees; passes stop once they converge. Each pass costs what the first fill did.");
        ui.add(egui::Slider::new(&mut s.convergence, 0.001..=0.1).logarithmic(true).text("convergence"))
            .on_hover_text("Bounce passes stop when one changes the records' luminance by less than this on average.");
        ui.add(egui::Slider::new(&mut s.records_per_frame, 16..=8192).logarithmic(true).text("records per frame"))
            .on_hover_text("New or renewed records computed per frame: the editor stays interactive while the cache fills, and the viewport shows it filling.");
        ui.add(egui::Slider::new(&mut s.rounds, 1..=16).text("rounds per frame"))
            .on_hover_text("Placement rounds per frame. The first uses the uncovered pixels the last frame found and waits for nothing; each further round waits for the GPU once (a faster fill, slower frames).");
        ui.add(egui::Slider::new(&mut s.max_records, 256..=262_144).logarithmic(true).text("max records"))
            .on_hover_text("Cache capacity (160 bytes and a 1 KiB light-check stratum set each). Beyond it uncovered pixels stay without indirect light (the coverage buffer shows them).");
        ui.add(egui::Slider::new(&mut s.min_zone_pixels, 1.0..=64.0).logarithmic(true).text("min zone (px)"))
            .on_hover_text("Smallest zone a x R on screen when a record is made: keeps creases from getting a record per pixel. Smaller: sharper contact light, more records.");
        ui.add(egui::Slider::new(&mut s.light_tolerance, 0.001..=0.5).logarithmic(true).text("light tolerance"))
            .on_hover_text("A light edit renews the records whose directly lit surroundings change by more than this fraction of their irradiance; the rest stay.");
        ui.checkbox(&mut s.furnace, "white furnace (debug)")
            .on_hover_text("Every surface and the background the records see emit 1: every record must read E = pi (a check of the integration, not lighting).");
    });
}
