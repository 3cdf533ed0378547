//! Cached shadow maps (`src/render/shadows.rs`): a frame in which no light and no object moved
//! (the camera or a material's colour may have) draws no shadow layer, moving a light redraws
//! that light's layers only, moving an object redraws every layer, and in each case the image equals a fresh renderer's image of the same
//! scene (a cache that missed a change would leave the old shadow in place); so does showing one
//! of two alike boxes in place of the other, which changes neither the draw batches nor the
//! lights' matrices.

use crate::common;

use bouncelab::render::{GpuContext, Renderer};
use bouncelab::scene::{Camera, Light, Material, MeshSource, Scene, Transform};
use bouncelab::settings::RenderSettings;
use glam::Vec3;

const SIZE: (u32, u32) = (64, 48);

/// A floor, a box on it, a point light (six layers) and a spot (one layer).
fn scene() -> Scene {
    let (floor, floor_mat) = common::floor(4.0, 0.6);
    let cube = common::object(
        "box",
        MeshSource::Cuboid { size: Vec3::splat(0.5), openings: [false; 6] },
        1,
        Transform { translation: Vec3::new(0.0, 0.25, -0.3), ..Transform::default() },
    );
    let spot = Light::spot("s", Vec3::new(0.8, 1.6, 0.4), Vec3::new(-0.4, -1.0, -0.5), 4.0, 0.3, 0.6);
    common::scene(
        vec![floor, cube],
        vec![floor_mat, Material::diffuse("box", [0.5; 3])],
        vec![Light::point("p", Vec3::new(-0.4, 1.3, -1.1), 3.0), spot],
        Camera::look_at(Vec3::new(0.3, 2.2, 2.4), Vec3::new(0.0, 0.0, -0.2), 0.9),
    )
}

/// The largest per-channel difference between two images.
fn max_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs())).fold(0.0, f32::max)
}

/// Renders `scene` with `r` and checks that the image equals a fresh renderer's; returns how
/// many layers `r` drew.
fn frame_matches_fresh(ctx: &GpuContext, r: &mut Renderer, scene: &Scene, what: &str) -> usize {
    let settings = RenderSettings::default();
    r.render(scene, &settings, SIZE).expect("render");
    let cached = r.read_hdr().expect("readback");
    let fresh = common::render(ctx, scene, &settings, SIZE);
    let diff = max_difference(&cached, &fresh);
    assert!(diff < 1e-6, "{what}: the cached renderer's image differs from a fresh one's by {diff}");
    r.shadow_layers_drawn()
}

#[test]
fn shadow_layers_are_redrawn_exactly_when_a_light_or_an_object_moves() {
    let Some(ctx) = common::gpu() else { return };
    let mut scene = scene();
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "first frame"), 7, "first frame draws all 7 layers");
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "still frame"), 0, "a still frame draws no layer");
    // The camera moving, or a material's colour, changes no shadow.
    scene.set_camera(Camera::look_at(Vec3::new(0.5, 2.0, 2.4), Vec3::new(0.0, 0.0, -0.2), 0.9));
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "camera moved"), 0, "a camera move draws no layer");
    scene.desc_mut().materials[1].base_color = [0.9, 0.2, 0.1, 1.0];
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "colour changed"), 0, "a colour edit draws no layer");
    scene.desc_mut().lights[1].position += Vec3::new(0.2, 0.0, 0.0);
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "spot moved"), 1, "moving the spot redraws its layer");
    scene.desc_mut().lights[0].position += Vec3::new(0.0, 0.0, 0.3);
    assert_eq!(
        frame_matches_fresh(&ctx, &mut r, &scene, "point light moved"),
        6,
        "moving the point light redraws its 6"
    );
    scene.desc_mut().objects[1].transform.translation += Vec3::new(0.3, 0.0, 0.0);
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "box moved"), 7, "moving the box redraws every layer");
    scene.desc_mut().objects[1].visible = false;
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "box hidden"), 7, "hiding the box redraws every layer");
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "still again"), 0, "a still frame draws no layer");
}

#[test]
fn showing_one_box_in_place_of_its_twin_redraws_the_shadows() {
    let Some(ctx) = common::gpu() else { return };
    let (floor, floor_mat) = common::floor(4.0, 0.6);
    let twin = |name: &str, x: f32, visible: bool| {
        let mut o = common::object(
            name,
            MeshSource::Cuboid { size: Vec3::splat(0.5), openings: [false; 6] },
            1,
            Transform { translation: Vec3::new(x, 0.25, -0.3), ..Transform::default() },
        );
        o.visible = visible;
        o
    };
    let mut scene = common::scene(
        vec![floor, twin("a", -0.6, true), twin("b", 0.6, false)],
        vec![floor_mat, Material::diffuse("box", [0.5; 3])],
        vec![Light::point("p", Vec3::new(0.0, 1.4, -0.6), 3.0)],
        Camera::look_at(Vec3::new(0.3, 2.2, 2.4), Vec3::new(0.0, 0.0, -0.2), 0.9),
    );
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "box a"), 6);
    let objects = &mut scene.desc_mut().objects;
    (objects[1].visible, objects[2].visible) = (false, true);
    assert_eq!(frame_matches_fresh(&ctx, &mut r, &scene, "box b in a's place"), 6, "the swap redraws the layers");
}
