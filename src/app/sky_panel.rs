//! The sky section of the scene panel: none, a constant colour, an equirectangular HDR image or
//! Preetham's analytic clear sky (turbidity; it follows the scene's sun), with intensity (in the
//! scene's light units: cd/m² or W/(sr m²); a plain scale for the analytic sky, which is
//! physical) and rotation. glTF has no
//! sky, so this is where a level gets one; every change is an undo step, and an image that does
//! not load is reported and leaves the sky as it was.

use super::state::EditorState;
use crate::scene::{Environment, LightUnits, Sky};

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    None,
    Constant,
    Image,
    Clear,
}

fn kind_of(sky: &Sky) -> Kind {
    match sky {
        Sky::None => Kind::None,
        Sky::Constant(_) => Kind::Constant,
        Sky::Image(_) => Kind::Image,
        Sky::Preetham { .. } => Kind::Clear,
    }
}

/// Draws the sky controls and applies a change as one undo step.
pub fn sky_ui(state: &mut EditorState, ui: &mut egui::Ui) {
    let original = state.project.scene.environment().clone();
    let units = state.project.scene.desc().light_units;
    let mut env = original.clone();
    kind_ui(ui, &mut env);
    match &mut env.sky {
        Sky::Constant(rgb) => {
            ui.horizontal(|ui| {
                ui.label("Colour");
                for (c, name) in rgb.iter_mut().zip(["r ", "g ", "b "]) {
                    ui.add(egui::DragValue::new(c).speed(0.01).range(0.0..=1.0e6).prefix(name));
                }
            })
            .response
            .on_hover_text("Linear radiance per unit intensity.");
        }
        Sky::Image(path) => {
            ui.horizontal(|ui| {
                ui.label("Image");
                ui.label(
                    std::path::Path::new(path.as_str())
                        .file_name()
                        .map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned()),
                )
                .on_hover_text(path.as_str());
                if ui.button("Choose…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("HDR image", &["hdr", "exr"]).pick_file()
                {
                    *path = p.to_string_lossy().into_owned();
                }
            });
        }
        Sky::Preetham { turbidity } => {
            let (lo, hi) = crate::scene::preetham::TURBIDITY_RANGE;
            ui.add(egui::Slider::new(turbidity, lo..=hi).text("turbidity")).on_hover_text(
                "Preetham et al. 1999: 2 very clear, 3 clear, 6 hazy, 10 thin overcast. The sky follows the \
                 scene's sun (its first directional light); its brightness is physical (at turbidity 3 with the sun \
                 45° up the zenith is 7.3 kcd/m²), the intensity a scale on it.",
            );
        }
        Sky::None => {}
    }
    if matches!(env.sky, Sky::Preetham { .. }) {
        ui.add(egui::Slider::new(&mut env.intensity, 0.0..=10.0).logarithmic(true).text("intensity (scale)"));
        ui.add(egui::Slider::new(&mut env.rotation_degrees, -180.0..=180.0).text("rotation (°)"));
    } else if env.sky != Sky::None {
        intensity_ui(ui, &mut env, units);
        ui.add(egui::Slider::new(&mut env.rotation_degrees, -180.0..=180.0).text("rotation (°)"))
            .on_hover_text("Turns the sky about +Y (an image's sun to where the level needs it).");
    }
    if env != original && env.validate().is_ok() {
        apply(state, env);
    }
}

fn kind_ui(ui: &mut egui::Ui, env: &mut Environment) {
    let mut kind = kind_of(&env.sky);
    let names = [
        (Kind::None, "none"),
        (Kind::Constant, "constant colour"),
        (Kind::Image, "HDR image"),
        (Kind::Clear, "clear sky (Preetham)"),
    ];
    let shown = names.iter().find(|(k, _)| *k == kind).map_or("none", |(_, n)| *n);
    egui::ComboBox::from_label("sky").selected_text(shown).show_ui(ui, |ui| {
        for (k, name) in names {
            ui.selectable_value(&mut kind, k, name);
        }
    });
    if kind == kind_of(&env.sky) {
        return;
    }
    env.sky = match kind {
        Kind::None => Sky::None,
        Kind::Constant => Sky::Constant([0.4, 0.6, 1.0]),
        Kind::Image => match rfd::FileDialog::new().add_filter("HDR image", &["hdr", "exr"]).pick_file() {
            Some(p) => Sky::Image(p.to_string_lossy().into_owned()),
            None => env.sky.clone(),
        },
        Kind::Clear => {
            env.intensity = 1.0;
            Sky::Preetham { turbidity: 3.0 }
        }
    };
}

/// The intensity in the scene's light units (the model keeps it radiometric).
fn intensity_ui(ui: &mut egui::Ui, env: &mut Environment, units: LightUnits) {
    radiance_slider(ui, &mut env.intensity, units, "intensity", "The sky's radiance per unit colour.");
}

/// A logarithmic slider of a radiometric radiance `value` shown and typed in `units` (cd/m² or
/// W/(sr m²)), labelled `label (symbol)`; the emission strength's and the sky's.
pub(super) fn radiance_slider(ui: &mut egui::Ui, value: &mut f32, units: LightUnits, label: &str, tip: &str) {
    let mut shown = units.from_radiometric(*value);
    let slider = egui::Slider::new(&mut shown, 0.0..=units.from_radiometric(1.0e4))
        .logarithmic(true)
        .clamping(egui::SliderClamping::Never)
        .text(format!("{label} ({})", units.radiance_symbol()));
    if ui.add(slider).on_hover_text(tip).changed() && shown.is_finite() {
        *value = units.to_radiometric(shown.max(0.0));
    }
}

/// Replaces the environment in one undo step (loading a new image; a failure is reported and
/// the step dropped).
fn apply(state: &mut EditorState, env: Environment) {
    let image_changed = env.sky != state.project.scene.environment().sky;
    state.history.begin("Edit sky", &state.project);
    let mut desc = state.project.scene.desc().clone();
    desc.environment = env;
    if let Err(e) = state.project.set_desc(desc) {
        state.report("sky", &e);
    }
    if image_changed {
        state.history.commit(&state.project);
    }
}
