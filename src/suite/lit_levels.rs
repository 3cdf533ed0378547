//! The suite's levels lit by the lights a level really has besides punctual ones: the sky
//! through a window (with and without the sun), emissive panels in a closed room, and a
//! courtyard open to the sky. Generated from code like [`super::levels`]; the sky travels in the
//! file's root `extras` (glTF has none), an image sky as an EXR written beside the level.

use glam::Vec3;
use serde_json::json;

use super::levels::{CEILING, FLOOR, WALL, camera, light, slab};
use crate::import::extras::{self, RootExtras};
use crate::import::writer::GltfWriter;
use crate::scene::{Environment, Sky, SkyImage, equirect_direction};

/// The image sky of `sunsky`, beside the level in `assets/suite/`.
pub const SKY_IMAGE: &str = "sky_clear.exr";

/// A material emitting `color` x `strength` W/(sr m²) from its front faces (albedo 0.8).
fn emissive(w: &mut GltfWriter, name: &str, color: [f32; 3], strength: f32) -> usize {
    w.material_json(json!({
        "name": name,
        "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "emissiveFactor": color,
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}},
    }))
}

fn with_sky(w: &mut GltfWriter, environment: Environment) {
    w.set_extras(extras::wrap(&RootExtras { light_units: None, render: None, environment: Some(environment) }));
}

/// The window room of [`super::levels::window_room`] without its lamps: floor, ceiling, three
/// walls and a front wall around a 2 x 1.2 m window.
fn windowed_room(w: &mut GltfWriter) {
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let (t, v) = (0.2, Vec3::new);
    let (x1, h, z1) = (6.0, 3.0, 5.0);
    slab(w, "floor", v(-t, -t, -t), v(x1 + t, 0.0, z1 + t), floor);
    slab(w, "ceiling", v(-t, h, -t), v(x1 + t, h + t, z1 + t), ceiling);
    slab(w, "back", v(0.0, 0.0, z1), v(x1, h, z1 + t), wall);
    slab(w, "left", v(-t, 0.0, -t), v(0.0, h, z1 + t), wall);
    slab(w, "right", v(x1, 0.0, -t), v(x1 + t, h, z1 + t), wall);
    let (wx0, wx1, wy0, wy1) = (2.0, 4.0, 1.0, 2.2);
    slab(w, "front_left", v(0.0, 0.0, -t), v(wx0, h, 0.0), wall);
    slab(w, "front_right", v(wx1, 0.0, -t), v(x1, h, 0.0), wall);
    slab(w, "front_sill", v(wx0, 0.0, -t), v(wx1, wy0, 0.0), wall);
    slab(w, "front_head", v(wx0, wy1, -t), v(wx1, h, 0.0), wall);
    camera(w, v(5.6, 1.7, 4.7), v(2.5, 0.9, 0.3), 1.2, 0.05);
}

/// The window room lit only by a clear blue sky (constant, 0.5 x (0.6, 0.8, 1.0) W/(sr m²))
/// through its window.
pub fn skylight() -> GltfWriter {
    let mut w = GltfWriter::default();
    windowed_room(&mut w);
    with_sky(&mut w, Environment { sky: Sky::Constant([0.6, 0.8, 1.0]), intensity: 0.5, rotation_degrees: 0.0 });
    w
}

/// The window room under the sun (4 W/m² through the window) and an image sky ([`sky_image`]).
pub fn sunsky() -> GltfWriter {
    let mut w = GltfWriter::default();
    windowed_room(&mut w);
    light(&mut w, "sun", "directional", 4.0, Vec3::new(3.0, 6.0, -4.0), Vec3::new(0.2, -0.55, 1.0), None);
    with_sky(&mut w, Environment { sky: Sky::Image(SKY_IMAGE.into()), intensity: 1.0, rotation_degrees: 0.0 });
    w
}

/// A clear sky without its sun (the sun is the level's directional light): a horizon-to-zenith
/// gradient from pale (0.35, 0.4, 0.45) to blue (0.12, 0.25, 0.6) W/(sr m²), brighter towards the
/// sun's side (-Z, where the sun shines from), a dark ground (0.05) below the horizon; 128 x 64.
pub fn sky_image() -> SkyImage {
    let (width, height) = (128u32, 64u32);
    let sun = -Vec3::new(0.2, -0.55, 1.0).normalize();
    let texels = (0..width * height)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let d = equirect_direction((x as f32 + 0.5) / width as f32, (y as f32 + 0.5) / height as f32);
            if d.y < 0.0 {
                return [0.05; 3];
            }
            let t = d.y.powf(0.5);
            let base = Vec3::new(0.35, 0.4, 0.45).lerp(Vec3::new(0.12, 0.25, 0.6), t);
            let glow = 1.0 + 1.5 * d.dot(sun).max(0.0).powi(4);
            (base * glow).to_array()
        })
        .collect();
    SkyImage { width, height, texels }
}

/// A closed 5 x 3 x 4 m room lit only by emissive surfaces: two ceiling panels (1.2 x 0.6 m,
/// 6 W/(sr m²) warm white), a screen on the left wall (0.9 x 0.5 m, 2 W/(sr m²) blue) and a
/// table and a cabinet that shade the floor.
pub fn panels() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let panel = emissive(&mut w, "panel", [1.0, 0.92, 0.8], 6.0);
    let screen = emissive(&mut w, "screen", [0.4, 0.6, 1.0], 2.0);
    let furniture = w.material("furniture", [0.5, 0.35, 0.25, 1.0]);
    let (t, v) = (0.2, Vec3::new);
    let (x1, h, z1) = (5.0, 3.0, 4.0);
    slab(&mut w, "floor", v(-t, -t, -t), v(x1 + t, 0.0, z1 + t), floor);
    slab(&mut w, "ceiling", v(-t, h, -t), v(x1 + t, h + t, z1 + t), ceiling);
    slab(&mut w, "front", v(0.0, 0.0, -t), v(x1, h, 0.0), wall);
    slab(&mut w, "back", v(0.0, 0.0, z1), v(x1, h, z1 + t), wall);
    slab(&mut w, "left", v(-t, 0.0, -t), v(0.0, h, z1 + t), wall);
    slab(&mut w, "right", v(x1, 0.0, -t), v(x1 + t, h, z1 + t), wall);
    slab(&mut w, "panel_a", v(1.0, h - 0.04, 1.7), v(2.2, h, 2.3), panel);
    slab(&mut w, "panel_b", v(3.0, h - 0.04, 1.7), v(4.2, h, 2.3), panel);
    slab(&mut w, "screen", v(0.0, 1.0, 1.5), v(0.03, 1.5, 2.4), screen);
    slab(&mut w, "table", v(1.8, 0.7, 1.4), v(3.4, 0.76, 2.6), furniture);
    slab(&mut w, "cabinet", v(4.2, 0.0, 0.3), v(4.9, 1.8, 1.2), furniture);
    camera(&mut w, v(4.6, 1.6, 3.7), v(1.0, 1.0, 1.0), 1.2, 0.05);
    w
}

/// A 12 x 12 m courtyard open to the sky: four 4 m walls 0.4 m thick (a gap of 2 m in one), two
/// benches, the sun (5 W/m², low from the west) and a constant sky of 0.6 x (0.55, 0.7, 1.0).
pub fn courtyard() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (wall, floor) = (w.material("wall", WALL), w.material("paving", FLOOR));
    let stone = w.material("stone", [0.6, 0.55, 0.5, 1.0]);
    let (t, h, s, v) = (0.4, 4.0, 12.0, Vec3::new);
    slab(&mut w, "paving", v(-t - 4.0, -t, -t - 4.0), v(s + t + 4.0, 0.0, s + t + 4.0), floor);
    slab(&mut w, "north", v(-t, 0.0, -t), v(s + t, h, 0.0), wall);
    slab(&mut w, "south_a", v(-t, 0.0, s), v(5.0, h, s + t), wall);
    slab(&mut w, "south_b", v(7.0, 0.0, s), v(s + t, h, s + t), wall);
    slab(&mut w, "west", v(-t, 0.0, 0.0), v(0.0, h, s), wall);
    slab(&mut w, "east", v(s, 0.0, 0.0), v(s + t, h, s), wall);
    slab(&mut w, "bench_a", v(2.0, 0.0, 3.0), v(5.0, 0.45, 3.6), stone);
    slab(&mut w, "bench_b", v(7.0, 0.0, 7.5), v(7.6, 0.45, 10.5), stone);
    let sun = Vec3::new((60f32).to_radians().cos(), -(35f32).to_radians().sin(), 0.3).normalize();
    light(&mut w, "sun", "directional", 5.0, v(0.0, 10.0, 6.0), sun, None);
    with_sky(&mut w, Environment { sky: Sky::Constant([0.55, 0.7, 1.0]), intensity: 0.6, rotation_degrees: 0.0 });
    camera(&mut w, v(10.8, 1.7, 11.0), v(3.0, 1.0, 2.0), 1.2, 0.05);
    w
}
