//! The GI panel's volumetric obscurance section (Loos 2015 ch. 6): where it applies and its
//! parameters, each with its cost as a tooltip (`bouncelab bench` figures).

use crate::settings::{GiMode, VoSettings};

/// Draws the obscurance settings for the active `mode` (none for `direct` and the reference,
/// which it never touches).
pub fn vo_ui(v: &mut VoSettings, mode: GiMode, ui: &mut egui::Ui) {
    if matches!(mode, GiMode::Direct | GiMode::Reference) {
        return;
    }
    egui::CollapsingHeader::new("Volumetric obscurance (Loos 2015 ch. 6)").default_open(false).show(ui, |ui| {
        if mode == GiMode::Mrt {
            ui.checkbox(&mut v.mrt, "on for mrt")
                .on_hover_text("Multiply mrt's indirect term by the obscurance: contact detail finer than its lightmap texels. Three screen passes, 1.4x a direct frame on llvmpipe at 640x360 (bench: DRT section).");
        } else {
            ui.checkbox(&mut v.other_modes, "on for this mode")
                .on_hover_text("Multiply this technique's indirect term by the obscurance (off by default: measure it on the suite first).");
        }
        ui.add(egui::Slider::new(&mut v.radius, 0.05..=4.0).logarithmic(true).text("radius (m)"))
            .on_hover_text("The sphere around each point, in metres: the contact scale it darkens. Free.");
        egui::ComboBox::from_label("line samples").selected_text(v.samples.to_string()).show_ui(ui, |ui| {
            for n in [5, 9, 12] {
                ui.selectable_value(&mut v.samples, n, n.to_string());
            }
        })
        .response
        .on_hover_text("The dissertation's low-noise counts (5 and 9 with the centre, 12 without). Cost linear in the count.");
        ui.add(egui::Slider::new(&mut v.thickness, 0.0..=2.0).text("thickness (m)"))
            .on_hover_text("Surfaces are slabs this thick, so a thin object does not darken what lies far behind its silhouette. 0: infinitely deep. Free.");
        ui.checkbox(&mut v.normal_clamp, "normal clamp")
            .on_hover_text("Count only the hemisphere above the surface (finer detail at larger radii). Free.");
        ui.checkbox(&mut v.blur, "bilateral blur")
            .on_hover_text("Edge-aware blur over the 4x4 sample rotation pattern: a row pass and a column pass (bench: 0.37 and 0.36 of a direct frame on llvmpipe).");
    });
}
