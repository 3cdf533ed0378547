//! The GI panel's `mrt` section: the runtime settings and the dictionary's parameters with
//! their cost as tooltips, and the command that fits proxy blocks to the level.

use crate::settings::{BlockOverride, MrtSettings};

/// Draws the mrt settings; `objects` and `blocks` name the scene's objects and proxy blocks
/// (for the block overrides). True when "Fit proxy blocks" was clicked.
pub fn mrt_ui(m: &mut MrtSettings, ui: &mut egui::Ui, objects: &[String], blocks: &[String]) -> bool {
    let mut fit = false;
    egui::CollapsingHeader::new("Modular radiance transfer (Loos 2015)").default_open(true).show(ui, |ui| {
        fit = ui
            .button("Fit proxy blocks")
            .on_hover_text("Add proxy blocks fitted to the level's rooms and doorways as objects you can move, resize and open (refused where the scene has blocks). Without blocks, mrt fits them on the fly and says so.")
            .clicked();
        ui.add(egui::Slider::new(&mut m.feedback, 0.0..=1.0).text("feedback"))
            .on_hover_text("Each frame adds albedo x the last frame's indirect light to the texels' direct light: one more bounce per frame (0 = one bounce). Free.");
        ui.checkbox(&mut m.padding, "pad across open sides")
            .on_hover_text("Blend towards the block beyond within half a texel of a side open over its whole area, so blocks meet without a seam (off: the unpadded lightmap). Cost: a second lookup near such sides.");
        ui.add(egui::Slider::new(&mut m.depth, 0..=16).text("depth"))
            .on_hover_text("Blocks beyond a source's neighbours its light is carried through the interfaces. Cost: T_b->r grows with the blocks reached (level rebuild and per-frame r).");
        overrides_ui(&mut m.block_overrides, ui, objects, blocks);
        egui::CollapsingHeader::new("Dictionary (precomputed, cached)").default_open(false).show(ui, |ui| {
            let d = &mut m.dictionary;
            egui::ComboBox::from_label("texels per face side").selected_text(d.res.to_string()).show_ui(ui, |ui| {
                for r in [4, 6, 8, 12, 16] {
                    ui.selectable_value(&mut d.res, r, r.to_string());
                }
            })
            .response
            .on_hover_text("The dissertation's 16. A new value builds a new dictionary (27 s at 16 on two cores, then cached): the gather grows with its square, the SVDs up to its fourth power.");
            ui.add(egui::Slider::new(&mut d.k_b, 4..=d.k_d.max(4)).text("modes k_b"))
                .on_hover_text("Indirect modes per block (32 on desktop, 12 on the iPad). Per frame: k_b x texels multiply-adds per block for b and again for U_b b.");
            ui.add(egui::Slider::new(&mut d.rays, 64..=16384).logarithmic(true).text("gather rays per texel"))
                .on_hover_text("The dictionary's gather (the dissertation: 16K). Build time is linear in it.");
        });
    });
    fit
}

/// The artist's object-to-block assignments: a row per override (object, block, remove) and an
/// add button.
fn overrides_ui(list: &mut Vec<BlockOverride>, ui: &mut egui::Ui, objects: &[String], blocks: &[String]) {
    egui::CollapsingHeader::new(format!("Block overrides ({})", list.len())).default_open(false).show(ui, |ui| {
        let mut remove = None;
        for (i, o) in list.iter_mut().enumerate() {
            ui.horizontal(|ui| {
                egui::ComboBox::from_id_salt(("mrt override object", i)).selected_text(o.object.as_str()).show_ui(
                    ui,
                    |ui| {
                        for name in objects {
                            ui.selectable_value(&mut o.object, name.clone(), name);
                        }
                    },
                );
                ui.label("reads");
                egui::ComboBox::from_id_salt(("mrt override block", i)).selected_text(o.block.as_str()).show_ui(ui, |ui| {
                    for name in blocks {
                        ui.selectable_value(&mut o.block, name.clone(), name);
                    }
                });
                if ui.small_button("x").on_hover_text("Remove this override").clicked() {
                    remove = Some(i);
                }
            });
        }
        if let Some(i) = remove {
            list.remove(i);
        }
        let can_add = !objects.is_empty() && !blocks.is_empty();
        if ui
            .add_enabled(can_add, egui::Button::new("Add override"))
            .on_hover_text("Make an object's surfaces read their light from a chosen proxy block instead of the nearest one (a pillar in an opening, a beam across two rooms). Needs proxy blocks in the scene.")
            .clicked()
        {
            list.push(BlockOverride { object: objects[0].clone(), block: blocks[0].clone() });
        }
    });
}
