//! The reference path tracer's emissive surfaces and sky against closed-form answers: a floor
//! under a constant sky, under an image sky with a sun, and under a square emissive panel (the
//! parallel-rectangle form factor), each with next-event estimation and BRDF sampling combined
//! by MIS. A wrong density, weight or orientation moves these by far more than their tolerance.

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Quat, Vec3};

use super::pathtracer::PathTracer;
use super::rng::Pcg32;
use crate::scene::{
    Environment, Material, Mesh, MeshSource, Object, ObjectRole, Resources, Scene, SceneDesc, Sky, SkyImage, Transform,
};
use crate::settings::ReferenceSettings;

const ALBEDO: f32 = 0.5;

fn plane(name: &str, size: f32, material: usize, transform: Transform, mesh: usize) -> Object {
    Object {
        name: name.into(),
        source: MeshSource::Plane { size },
        mesh,
        material,
        transform,
        sampling_weight: 1.0,
        role: ObjectRole::Static,
        visible: true,
    }
}

/// A 20 m floor at y = 0, a downward `panel` of side `panel` at height 1 (if > 0) emitting
/// `emission`, under `environment`.
fn scene(panel: f32, emission: f32, environment: Environment, sky: Option<SkyImage>) -> Scene {
    let mut objects = vec![plane("floor", 20.0, 0, Transform::default(), 0)];
    let mut meshes = vec![Mesh::plane("floor", 20.0)];
    let emitter = Material {
        emissive_color: [1.0, 0.8, 0.6],
        emissive_strength: emission,
        ..Material::diffuse("panel", [0.0; 3])
    };
    if panel > 0.0 {
        let down = Transform { translation: Vec3::Y, rotation: Quat::from_rotation_x(PI), ..Transform::default() };
        objects.push(plane("panel", panel, 1, down, 1));
        meshes.push(Mesh::plane("panel", panel));
    }
    let desc = SceneDesc {
        materials: vec![Material::diffuse("floor", [ALBEDO; 3]), emitter],
        objects,
        environment,
        ..SceneDesc::default()
    };
    Scene::new(desc, Resources { meshes, images: vec![], sky: sky.map(Arc::new) }).expect("scene")
}

/// The mean radiance leaving the floor at `at` towards +Y, over `n` paths from just above it.
fn floor_radiance(scene: &Scene, at: Vec3, n: u32, max_bounces: u32) -> Vec3 {
    let settings = ReferenceSettings { max_bounces, ..ReferenceSettings::default() };
    let tracer = PathTracer::new(scene, (1, 1), settings);
    let mut sum = Vec3::ZERO;
    for i in 0..n {
        let mut rng = Pcg32::new(3, 0, u64::from(i));
        sum += tracer.radiance(at + Vec3::Y * 0.5, Vec3::NEG_Y, &mut rng).0;
    }
    sum / n as f32
}

/// Irradiance under the corner of an a x b rectangle of radiance 1, parallel at distance h.
fn corner_irradiance(a: f32, b: f32, h: f32) -> f32 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    let f = (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI);
    PI * f
}

fn close(got: Vec3, want: Vec3, tolerance: f32) -> bool {
    (got - want).abs().max_element() <= tolerance * want.max_element()
}

#[test]
fn a_floor_under_a_constant_sky_reflects_albedo_times_the_sky() {
    let sky = Environment { sky: Sky::Constant([0.2, 0.4, 0.8]), intensity: 2.5, rotation_degrees: 0.0 };
    let scene = scene(0.0, 0.0, sky, None);
    // E = π L over the open hemisphere, so the floor sends albedo x L.
    let want = Vec3::new(0.2, 0.4, 0.8) * 2.5 * ALBEDO;
    let got = floor_radiance(&scene, Vec3::ZERO, 4000, 4);
    assert!(close(got, want, 0.03), "{got} vs {want}");
    // The camera sees the sky itself where nothing is in the way.
    let tracer = PathTracer::new(&scene, (1, 1), ReferenceSettings::default());
    let up = tracer.radiance(Vec3::Y, Vec3::Y, &mut Pcg32::new(1, 1, 1)).0;
    assert!(close(up, Vec3::new(0.5, 1.0, 2.0), 1e-5), "{up}");
}

#[test]
fn a_floor_under_a_square_panel_gets_the_form_factor_irradiance_at_any_panel_size() {
    for (side, strength) in [(0.2f32, 400.0f32), (1.0, 20.0), (6.0, 2.0)] {
        let scene = scene(side, strength, Environment::default(), None);
        let e = 4.0 * corner_irradiance(side / 2.0, side / 2.0, 1.0) * strength;
        let want = Vec3::new(1.0, 0.8, 0.6) * e * ALBEDO / PI;
        let got = floor_radiance(&scene, Vec3::ZERO, 4000, 1);
        assert!(close(got, want, 0.03), "panel {side} m: {got} vs {want}");
    }
    // The panel's back (facing up) emits nothing; its front, seen from below, is its radiance.
    let scene = scene(1.0, 20.0, Environment::default(), None);
    let tracer = PathTracer::new(&scene, (1, 1), ReferenceSettings::default());
    let mut rng = Pcg32::new(1, 1, 1);
    let back = tracer.radiance(Vec3::new(0.0, 2.0, 0.0), Vec3::NEG_Y, &mut rng).0;
    assert_eq!(back, Vec3::ZERO, "the back of the panel");
    let front = tracer.radiance(Vec3::new(0.0, 0.5, 0.0), Vec3::Y, &mut rng).0;
    assert!(close(front, Vec3::new(20.0, 16.0, 12.0), 1e-5), "{front}");
}

#[test]
fn a_floor_under_an_image_sky_with_a_sun_gets_the_texel_sum_irradiance_after_rotation() {
    let (w, h) = (32u32, 16u32);
    let mut texels = vec![[0.1, 0.2, 0.3]; (w * h) as usize];
    texels[(3 * w + 5) as usize] = [300.0, 280.0, 260.0];
    let img = SkyImage { width: w, height: h, texels };
    // Exact irradiance of the upper rows on an upward floor: L dφ (sin² θ1 - sin² θ0) / 2 each
    // (rotation about +Y does not change it).
    let mut want = Vec3::ZERO;
    for y in 0..h / 2 {
        let (t0, t1) = (PI * y as f32 / h as f32, PI * (y + 1) as f32 / h as f32);
        let band = 2.0 * PI / w as f32 * (t1.sin().powi(2) - t0.sin().powi(2)) / 2.0;
        want += (0..w).map(|x| img.texel(x, y) * band).sum::<Vec3>();
    }
    want *= ALBEDO / PI * 0.5;
    let sky = Environment { sky: Sky::Image("sky.exr".into()), intensity: 0.5, rotation_degrees: 40.0 };
    let scene = scene(0.0, 0.0, sky, Some(img));
    let got = floor_radiance(&scene, Vec3::ZERO, 4000, 1);
    assert!(close(got, want, 0.03), "{got} vs {want}");
}

/// An emission texture scales the emission where the point lies, for every consumer that reads
/// emission at a surface point: MRT's block texels (`geometry_image::surface`) and ISM's emitter
/// candidates. The panel's texture is white on one half and black on the other.
#[test]
fn the_emission_texture_is_read_at_the_surface_point() {
    let base = scene(2.0, 3.0, Environment::default(), None);
    let mut desc = base.desc().clone();
    desc.materials[1].emissive_texture = Some(crate::scene::TextureRef { image: 0, tex_coord: 0 });
    let half = crate::scene::Image { width: 2, height: 1, rgba8: vec![255, 255, 255, 255, 0, 0, 0, 255] };
    let scene = Scene::new(desc, Resources { images: vec![half], ..base.resources().clone() }).expect("scene");
    let bvh = super::bvh::SceneBvh::build(&scene);
    let full = Vec3::new(1.0, 0.8, 0.6) * 3.0;
    // The panel faces down from 1 m: texels of a block face below it look up at it.
    // At the texels' centres (the 2 m panel spans u = 0..1 along one axis): -0.5 and 0.5 m.
    let samples: Vec<Vec3> = (0..4)
        .map(|i| {
            let (x, z) = (if i % 2 == 0 { -0.5 } else { 0.5 }, if i / 2 == 0 { -0.5 } else { 0.5 });
            super::mrt::geometry_image::surface(&scene, &bvh, Vec3::new(x, 0.9, z), Vec3::NEG_Y, 0.5).emission
        })
        .collect();
    assert!(samples.iter().any(|e| close(*e, full, 0.02)), "the white half emits fully: {samples:?}");
    assert!(samples.iter().any(|e| e.max_element() < 0.02), "the black half emits nothing: {samples:?}");
    let points = crate::render::gi::ism::emitter_points::emitter_points(&scene, 4096, 64);
    let total = crate::render::gi::ism::emitter_points::total_power(&points);
    let untextured = PI * 4.0 * full;
    assert!(close(total, 0.5 * untextured, 0.03), "half the panel's power: {total} of {untextured}");
}
