//! The GI panel's ISM section (`ism`, `ism-ritschel`): every IsmSettings field with its
//! cost/quality trade-off as a tooltip.

use crate::settings::{BouncePick, IsmSettings, ShadeResolution, TailRatio};

/// Draws the ISM settings.
pub fn ism_ui(m: &mut IsmSettings, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("ISM (Knecht 2009)").default_open(true).show(ui, |ui| {
        ui.add(egui::Slider::new(&mut m.vpl_count, 4..=1024).logarithmic(true).text("VPLs"))
            .on_hover_text("Cost: shading and ISM splatting grow linearly; quality: fewer blotches, less flicker (256 for flicker-free).");
        egui::ComboBox::from_label("ISM resolution").selected_text(m.ism_resolution.to_string()).show_ui(ui, |ui| {
            for r in [64, 128, 256] {
                ui.selectable_value(&mut m.ism_resolution, r, r.to_string());
            }
        });
        ui.add(egui::Slider::new(&mut m.total_points, 1024..=1 << 22).logarithmic(true).text("point pool"))
            .on_hover_text("Scene sample points every ISM draws from. Too few: coarse detail next to VPLs.");
        ui.add(egui::Slider::new(&mut m.points_per_ism, 64..=4096).logarithmic(true).text("points per ISM"))
            .on_hover_text("Drawn by solid angle from each VPL. Too few: holes and light leaks; cost: linear.");
        ui.add(egui::Slider::new(&mut m.interleave, 1..=8).text("interleave n"))
            .on_hover_text("Each pixel sees VPLs / n² VPLs; the n x n filter hides the pattern.");
        shade_resolution_ui(m, ui);
        ui.add(egui::Slider::new(&mut m.bounces, 1..=6).text("bounces")).on_hover_text("Each extra bounce: one VPL, ISM and shading pass.");
        ui.add(egui::Slider::new(&mut m.base_confidence, 0.0..=0.99).text("base confidence"))
            .on_hover_text("Higher: smoother over time, more afterglow after lighting changes.");
        ui.add(egui::Slider::new(&mut m.still_frames, 0..=256).logarithmic(true).text("still frames"))
            .on_hover_text("While nothing moves, the history keeps refining over this many frames (0: base confidence only). Any edit or camera move returns to the base confidence.");
        ui.add(egui::Slider::new(&mut m.w_position, 0.0..=100.0).text("w position"));
        ui.add(egui::Slider::new(&mut m.w_normal, 0.0..=100.0).text("w normal"));
        ui.add(egui::Slider::new(&mut m.w_illumination, 0.0..=100.0).text("w illumination"))
            .on_hover_text("Higher: reacts faster to lighting changes, but lets VPL resampling noise through.");
        ui.checkbox(&mut m.bounce_tail, "bounces beyond the last (geometric tail)").on_hover_text(
            "Scale the last bounce's VPLs by 1 / (1 - r), r from the ratio below: the light of the bounces the limit cuts off. Free.",
        );
        ui.horizontal(|ui| {
            ui.label("tail ratio");
            ui.radio_value(&mut m.tail_ratio, TailRatio::Power, "scene power")
                .on_hover_text("The last bounce's total power over the previous one's: right for a room lit directly.");
            ui.radio_value(&mut m.tail_ratio, TailRatio::Screen, "screen").on_hover_text(
                "The light the last bounce gives the screen over the previous one's: for a room that light reaches late, through other rooms.",
            );
            ui.radio_value(&mut m.tail_ratio, TailRatio::Mean, "mean")
                .on_hover_text("The geometric mean of the two: the screen's growth slows as the light settles.");
        });
        ui.horizontal(|ui| {
            ui.label("bounce VPL pick");
            ui.radio_value(&mut m.bounce_pick, BouncePick::Resampled, "resampled").on_hover_text(
                "Each bounce's VPLs drawn at once from all lit points, evenly spaced by brightness: as correct as proportional, steadier in rooms lit through doorways.",
            );
            ui.radio_value(&mut m.bounce_pick, BouncePick::Proportional, "proportional").on_hover_text(
                "A lit point picked with probability proportional to its brightness: bounced light goes where it should (through doorways), noisier per frame.",
            );
            ui.radio_value(&mut m.bounce_pick, BouncePick::Brightest, "brightest (thesis)")
                .on_hover_text("The thesis's pick: the brightest lit point. Stable, but bounced light stays near where it landed.");
        });
        ui.add(egui::Slider::new(&mut m.view_importance, 0.0..=64.0).text("view importance")).on_hover_text(
            "Bounce picks favour points that can light what the camera sees, each such VPL carrying less: steadier light in a room lit through doorways. 0: picks by brightness alone.",
        );
        ui.add(egui::Slider::new(&mut m.first_set_seen_weight, 0.0..=64.0).text("first set: seen weight")).on_hover_text(
            "Lit surfaces and emitters the camera sees get up to 1 + this times as many of the lights' own VPLs, each carrying less: steadier frames where most of a light lands out of view (sun on a roof). The sky's VPLs are never in view. 0: by power alone (thesis).",
        );
        ui.add(egui::Slider::new(&mut m.splat_radius, 0.25..=2.0).text("splat radius (x point disk)")).on_hover_text(
            "Each sample point's ISM splat, as a fraction of the surface disk it stands for. Smaller: holes that let light through walls; larger: occluders dilate, doorways close, contacts darken.",
        );
        ui.add(egui::Slider::new(&mut m.clamp_disk, 0.0..=4.0).text("clamp (VPL disk radius²)"))
            .on_hover_text("d² is clamped at this factor x the squared radius of the patch each VPL stands for: bounded light near VPLs at any scene scale. Larger: fewer spikes, darker corners.");
        ui.add(egui::Slider::new(&mut m.clamp_distance, 0.0..=2.0).text("extra clamp distance (m)"))
            .on_hover_text("A fixed minimum VPL distance on top of the disk clamp (0 = none). Larger: fewer spikes near VPLs, darker corners (bias).");
        ui.add(egui::Slider::new(&mut m.bias_constant, 0.0..=1.0).text("ISM normal offset (x point spacing)"))
            .on_hover_text("Constant part of the ISM lookup's normal offset, in units of the spacing of one ISM's sample points. Lookups test the receiver's own ray against the splat's surface, so only curved surfaces need it. Larger: softer contact shadows, light beyond doorways shifted.");
        ui.add(egui::Slider::new(&mut m.bias_slope, 0.0..=2.0).text("ISM slope offset"))
            .on_hover_text("Receiver-slope part of the normal offset: x sin(angle to the VPL) x the point spacing. Off by default: it shifts the light beyond doorways.");
        ui.add(egui::Slider::new(&mut m.filter_depth, 0.001..=0.1).logarithmic(true).text("filter plane tolerance"))
            .on_hover_text("Geometry-aware filter: neighbours farther than this x scene diameter from the pixel's tangent plane are rejected. Lower: sharper contacts, more interleave pattern.");
        ui.add(egui::Slider::new(&mut m.filter_normal, 0.0..=1.0).text("filter normal cosine"))
            .on_hover_text("Neighbours whose normal differs by a cosine below this are rejected (the SH filter tests geometric normals only).");
        ui.checkbox(&mut m.sh_filter, "SH filter (Segovia & Wald)").on_hover_text(
            "Filter incident radiance as 9 SH coefficients per colour, then shade with each pixel's own normal-mapped normal and glossy lobe. Cost: 56 bytes per pixel and 27-channel filtering (on an H100 `ism shade` 0.91 -> 1.08 ms at 320x180, 1.09 -> 1.68 ms at 640x360; docs/BENCHMARKS.md).",
        );
    });
}

/// The gathering resolution's choice; the SH filter always gathers at full resolution.
fn shade_resolution_ui(m: &mut IsmSettings, ui: &mut egui::Ui) {
    ui.add_enabled_ui(!m.sh_filter, |ui| {
        ui.horizontal(|ui| {
            ui.label("gather at");
            ui.radio_value(&mut m.shade_resolution, ShadeResolution::Auto, "auto").on_hover_text(
                "Half resolution from 640 x 360 pixels on, full below: where a view's pixels are small against its indirect light.",
            );
            ui.radio_value(&mut m.shade_resolution, ShadeResolution::Full, "full")
                .on_hover_text("Every pixel gathers its share of the VPLs (the thesis).");
            ui.radio_value(&mut m.shade_resolution, ShadeResolution::Half, "half").on_hover_text(
                "One pixel of each 2 x 2 gathers (a quarter of `ism shade`'s lookups); the geometry-aware filter takes its taps from those.",
            );
        });
    })
    .response
    .on_disabled_hover_text("The SH filter gathers at full resolution.");
}
