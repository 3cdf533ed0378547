//! The properties panel: every field of the selected light or object. Widgets edit a copy; a
//! change writes it back inside an undo step, and a drag or a text edit stays one step until
//! the pointer is released and focus leaves (see `History::begin`).

use glam::{EulerRot, Quat, Vec3};

use super::edits::Selection;
use super::state::EditorState;
use crate::scene::{Light, LightKind, LightUnits, Object, ObjectRole};

fn vec3_ui(ui: &mut egui::Ui, label: &str, v: &mut Vec3, speed: f32) {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(egui::DragValue::new(&mut v.x).speed(speed).prefix("x "));
        ui.add(egui::DragValue::new(&mut v.y).speed(speed).prefix("y "));
        ui.add(egui::DragValue::new(&mut v.z).speed(speed).prefix("z "));
    });
}

fn light_ui(ui: &mut egui::Ui, light: &mut Light, units: LightUnits) {
    ui.horizontal(|ui| {
        ui.label("Name");
        ui.text_edit_singleline(&mut light.name);
    });
    ui.horizontal(|ui| {
        ui.label("Colour");
        ui.color_edit_button_rgb(&mut light.color);
    });
    intensity_ui(ui, light, units);
    if light.kind != LightKind::Directional {
        vec3_ui(ui, "Position", &mut light.position, 0.01);
        let mut has_range = light.range.is_some();
        ui.horizontal(|ui| {
            ui.checkbox(&mut has_range, "Range")
                .on_hover_text("Smooth cut-off distance (KHR window); off = pure inverse-square.");
            if has_range {
                let mut r = light.range.unwrap_or(5.0);
                ui.add(egui::DragValue::new(&mut r).speed(0.05).range(0.01..=1.0e4).suffix(" m"));
                light.range = Some(r);
            } else {
                light.range = None;
            }
        });
    }
    if light.kind != LightKind::Point {
        let mut d = light.direction;
        vec3_ui(ui, "Direction", &mut d, 0.01);
        if let Some(n) = d.try_normalize() {
            light.direction = n;
        }
    }
    if let LightKind::Spot { inner_cone_angle, outer_cone_angle } = &mut light.kind {
        let (mut inner, mut outer) = (inner_cone_angle.to_degrees(), outer_cone_angle.to_degrees());
        ui.add(egui::Slider::new(&mut outer, 1.0..=90.0).text("outer cone (°)"));
        ui.add(egui::Slider::new(&mut inner, 0.0..=outer - 0.5).text("inner cone (°)"));
        *outer_cone_angle = outer.to_radians();
        *inner_cone_angle = inner.clamp(0.0, outer - 0.5).to_radians();
    }
    ui.checkbox(&mut light.cast_shadows, "Cast shadows").on_hover_text("Costs one shadow map (six for a point light).");
}

/// The intensity in the scene's light units (`units`), the other units beside it. The light
/// keeps its radiometric value; only what is shown and typed converts (683 lm/W).
fn intensity_ui(ui: &mut egui::Ui, light: &mut Light, units: LightUnits) {
    let symbol = units.symbol(&light.kind);
    let mut shown = units.from_radiometric(light.intensity);
    // A Blender lamp of 1000 W is about 80 W/sr; the slider reaches 10x that, typing goes on.
    let top = units.from_radiometric(1000.0);
    let slider = egui::Slider::new(&mut shown, 0.0..=top)
        .logarithmic(true)
        .clamping(egui::SliderClamping::Never)
        .text(format!("intensity ({symbol})"));
    let what = match (light.kind, units) {
        (LightKind::Directional, LightUnits::Photometric) => "Illuminance in lux",
        (LightKind::Directional, LightUnits::Radiometric) => "Irradiance in W/m²",
        (_, LightUnits::Photometric) => "Luminous intensity in candela",
        (_, LightUnits::Radiometric) => "Radiant intensity in W/sr",
    };
    let tip = format!(
        "{what}, the scene's light units (Scene > light units); 683 lm/W between the two, as glTF exporters convert."
    );
    if ui.add(slider).on_hover_text(tip).changed() && shown.is_finite() {
        light.intensity = units.to_radiometric(shown.max(0.0));
    }
    let other = units.other();
    ui.label(format!("= {:.4} {}", other.from_radiometric(light.intensity), other.symbol(&light.kind)));
}

fn object_ui(ui: &mut egui::Ui, object: &mut Object, materials: &[String]) {
    ui.horizontal(|ui| {
        ui.label("Name");
        ui.text_edit_singleline(&mut object.name);
    });
    ui.checkbox(&mut object.visible, "Visible");
    egui::ComboBox::from_label("Role").selected_text(format!("{:?}", object.role)).show_ui(ui, |ui| {
        for role in [ObjectRole::Static, ObjectRole::ProxyBlock, ObjectRole::Clutter] {
            ui.selectable_value(&mut object.role, role, format!("{role:?}"));
        }
    });
    egui::ComboBox::from_label("Material")
        .selected_text(materials.get(object.material).cloned().unwrap_or_default())
        .show_ui(ui, |ui| {
            for (i, name) in materials.iter().enumerate() {
                ui.selectable_value(&mut object.material, i, name);
            }
        });
    ui.add(egui::Slider::new(&mut object.sampling_weight, 0.0..=10.0).text("sampling weight")).on_hover_text(
        "Multiplies this object's triangle area when scene sample points (ISM points, VPL sampling) are \
         distributed: more points here, fewer elsewhere. 0 excludes the object.",
    );
    let t = &mut object.transform;
    vec3_ui(ui, "Position", &mut t.translation, 0.01);
    let (y, x, z) = t.rotation.to_euler(EulerRot::YXZ);
    let mut euler = Vec3::new(x.to_degrees(), y.to_degrees(), z.to_degrees());
    let before = euler;
    vec3_ui(ui, "Rotation (°)", &mut euler, 0.5);
    if euler != before {
        t.rotation = Quat::from_euler(EulerRot::YXZ, euler.y.to_radians(), euler.x.to_radians(), euler.z.to_radians());
    }
    let mut s = t.scale;
    vec3_ui(ui, "Scale", &mut s, 0.01);
    t.scale = s.max(Vec3::splat(1e-3));
    let proxy = object.role == ObjectRole::ProxyBlock;
    if let crate::scene::MeshSource::Cuboid { size, openings } = &mut object.source {
        let mut sz = *size;
        vec3_ui(ui, "Box size", &mut sz, 0.01);
        *size = sz.max(Vec3::splat(1e-3));
        if proxy {
            ui.horizontal_wrapped(|ui| {
                ui.label("Open faces")
                    .on_hover_text("Interfaces through which light passes to neighbouring blocks (MRT).");
                for (open, name) in openings.iter_mut().zip(["+X", "-X", "+Y", "-Y", "+Z", "-Z"]) {
                    ui.checkbox(open, name);
                }
            });
        }
    }
}

/// The emission colour (glTF's `emissiveFactor`) and strength in the scene's light units
/// (cd/m² or W/(sr m²); the model keeps it radiometric), and its texture among the scene's
/// `images`.
fn emission_ui(ui: &mut egui::Ui, m: &mut crate::scene::Material, units: LightUnits, images: &[crate::scene::Image]) {
    ui.horizontal(|ui| {
        ui.label("Emission");
        ui.color_edit_button_rgb(&mut m.emissive_color)
            .on_hover_text("Colour the front face emits (black: none); x the strength below.");
    });
    let tip =
        "Radiance of the front face per unit colour (KHR_materials_emissive_strength), in the scene's light units.";
    super::sky_panel::radiance_slider(ui, &mut m.emissive_strength, units, "emission strength", tip);
    emission_texture_ui(ui, m, images);
}

/// The name the emission-texture picker gives image `i`.
pub fn image_label(i: usize, image: &crate::scene::Image) -> String {
    format!("image {i} ({}x{})", image.width, image.height)
}

/// Picks the emission texture (glTF's `emissiveTexture`) among the images the scene's glTF
/// files brought, or none; a screen or a sign usually emits its base colour texture.
fn emission_texture_ui(ui: &mut egui::Ui, m: &mut crate::scene::Material, images: &[crate::scene::Image]) {
    if images.is_empty() {
        return;
    }
    let label = |t: Option<crate::scene::TextureRef>| match t {
        Some(t) => {
            images.get(t.image).map_or_else(|| format!("image {}", t.image), |image| image_label(t.image, image))
        }
        None => "none".to_owned(),
    };
    // The base colour's UV set where the same image is picked, else the first.
    let uv = |i: usize| m.base_color_texture.filter(|t| t.image == i).map_or(0, |t| t.tex_coord);
    let mut picked = m.emissive_texture;
    egui::ComboBox::from_label("emission texture")
        .selected_text(label(picked))
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut picked, None, "none");
            for (i, image) in images.iter().enumerate() {
                let texture = Some(crate::scene::TextureRef { image: i, tex_coord: uv(i) });
                ui.selectable_value(&mut picked, texture, image_label(i, image));
            }
        })
        .response
        .on_hover_text("Multiplies the emission colour per texel (sRGB); images come with the scene's glTF files.");
    m.emissive_texture = picked;
}

/// Edits the object's material (shared by every object that uses it).
fn material_ui(ui: &mut egui::Ui, state: &mut EditorState, index: usize) {
    let Some(original) = state.project.scene.materials().get(index).cloned() else { return };
    let units = state.project.scene.desc().light_units;
    let images = &state.project.scene.resources().images;
    let users = state.project.scene.objects().iter().filter(|o| o.material == index).count();
    let mut m = original.clone();
    egui::CollapsingHeader::new(format!("Material \"{}\" ({users} objects)", m.name)).default_open(false).show(
        ui,
        |ui| {
            ui.horizontal(|ui| {
                ui.label("Albedo");
                let mut rgb = [m.base_color[0], m.base_color[1], m.base_color[2]];
                ui.color_edit_button_rgb(&mut rgb)
                    .on_hover_text("Linear Lambertian albedo (x the base colour texture, if any).");
                m.base_color[..3].copy_from_slice(&rgb);
            });
            ui.horizontal(|ui| {
                ui.label("Specular");
                ui.color_edit_button_rgb(&mut m.specular)
                    .on_hover_text("Colour of the Blinn-Phong lobe; black = purely diffuse.");
            });
            ui.add(egui::Slider::new(&mut m.roughness, 0.02..=1.0).text("roughness"));
            emission_ui(ui, &mut m, units, images);
            if m.base_color_texture.is_some() || m.normal_texture.is_some() || m.emissive_texture.is_some() {
                ui.label("Textured (base colour, normal map and/or emission from the glTF).");
            }
        },
    );
    if m != original && m.validate().is_ok() {
        state.history.begin("Edit material", &state.project);
        state.project.scene.desc_mut().materials[index] = m;
    }
}

/// Draws the properties of the selection and records edits.
pub fn properties_ui(state: &mut EditorState, ui: &mut egui::Ui) {
    egui::ScrollArea::vertical().show(ui, |ui| match state.selection {
        Selection::None => {
            ui.label("Select a light or an object in the outliner or the viewport.");
        }
        Selection::Light(i) => {
            let Some(original) = state.project.scene.lights().get(i).cloned() else { return };
            let mut light = original.clone();
            light_ui(ui, &mut light, state.project.scene.desc().light_units);
            if light != original && light.validate().is_ok() {
                state.history.begin("Edit light", &state.project);
                state.project.scene.desc_mut().lights[i] = light;
            }
        }
        Selection::Object(i) => {
            let Some(original) = state.project.scene.objects().get(i).cloned() else { return };
            let materials: Vec<String> = state.project.scene.materials().iter().map(|m| m.name.clone()).collect();
            let mut object = original.clone();
            object_ui(ui, &mut object, &materials);
            material_ui(ui, state, original.material);
            if object != original && object.validate().is_ok() {
                state.history.begin("Edit object", &state.project);
                if object.source == original.source {
                    state.project.scene.desc_mut().objects[i] = object;
                } else {
                    // A new box size needs a new mesh.
                    let mut desc = state.project.scene.desc().clone();
                    desc.objects[i] = object;
                    if let Err(e) = state.project.set_desc(desc) {
                        state.report("edit failed", &e);
                    }
                }
            }
        }
    });
    // A drag or a text edit is one undo step: commit once the pointer is up and nothing has focus.
    let idle = ui.input(|i| !i.pointer.any_down()) && ui.memory(|m| m.focused().is_none());
    if idle {
        state.history.commit(&state.project);
    }
}
