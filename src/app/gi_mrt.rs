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
        drt_ui(&mut m.drt, ui, objects);
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

/// Delta radiance transfer: the toggle to compare, what counts as clutter and the rebuild's
/// cost.
fn drt_ui(d: &mut crate::settings::DrtSettings, ui: &mut egui::Ui, objects: &[String]) {
    egui::CollapsingHeader::new("Clutter (delta radiance transfer)").default_open(true).show(ui, |ui| {
        ui.checkbox(&mut d.enabled, "DRT")
            .on_hover_text("Clutter shadows and reflects the blocks' indirect light and gathers its own (off: mrt as without DRT, to compare). Rebuilt off the frame when clutter moves (bench: 29 objects 1.5 s, one 58 ms on two cores).");
        ui.checkbox(&mut d.automatic, "find clutter automatically")
            .on_hover_text("Static objects lower than 90% of their block and narrower than half of it count as clutter (a bare glTF has no roles). Objects whose role is Clutter always do.");
        ui.add(egui::Slider::new(&mut d.rays, 16..=4096).logarithmic(true).text("rays per texel"))
            .on_hover_text("Rays per block texel near clutter for the delta operators (the dissertation: 1024). Rebuild time linear in it; only rays meeting a clutter box are traced.");
        ui.add(egui::Slider::new(&mut d.gather_rays, 16..=4096).logarithmic(true).text("gather rays"))
            .on_hover_text("Rays per clutter texel for its gathered light: most of the rebuild (x 6 x res² texels per object).");
        egui::ComboBox::from_label("clutter texels per face").selected_text(d.clutter_res.to_string()).show_ui(ui, |ui| {
            for r in [4, 8, 16, 32] {
                ui.selectable_value(&mut d.clutter_res, r, r.to_string());
            }
        })
        .response
        .on_hover_text("The dissertation's 16. The gather's cost grows with its square.");
        ui.checkbox(&mut d.inpaint, "inpaint covered texels")
            .on_hover_text("Texels under clutter take their neighbours' light (off: the rim their own deltas leave, for comparison). Free.");
        // The artist's override of the automatic choice: static objects never treated as clutter.
        let mut remove = None;
        for (i, name) in d.not_clutter.iter().enumerate() {
            ui.horizontal(|ui| {
                ui.label(format!("never clutter: {name}"));
                if ui.small_button("x").on_hover_text("Let the automatic choice decide again").clicked() {
                    remove = Some(i);
                }
            });
        }
        if let Some(i) = remove {
            d.not_clutter.remove(i);
        }
        let mut add = None;
        egui::ComboBox::from_id_salt("drt never clutter").selected_text("never clutter...").show_ui(ui, |ui| {
            for name in objects.iter().filter(|n| !d.not_clutter.contains(n)) {
                if ui.selectable_label(false, name).clicked() {
                    add = Some(name.clone());
                }
            }
        })
        .response
        .on_hover_text("Keep a static object out of the automatic clutter (a counter that is structure). Objects whose role is Clutter are clutter regardless.");
        if let Some(name) = add {
            d.not_clutter.push(name);
        }
    });
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
