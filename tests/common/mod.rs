//! Shared helpers for integration tests: the GPU (a missing adapter fails under CI, is skipped
//! locally), small scenes built in code, and rendering to linear radiance.
#![allow(dead_code)]

use bouncelab::render::{GpuContext, Renderer};
use bouncelab::scene::{
    Camera, Light, Material, Mesh, MeshSource, Object, ObjectRole, Resources, Scene, SceneDesc, Transform,
};
use bouncelab::settings::RenderSettings;
use glam::Vec3;

/// The GPU, or `None` (with a note) when there is none and we are not in CI.
pub fn gpu() -> Option<GpuContext> {
    match GpuContext::new_headless() {
        Ok(ctx) => Some(ctx),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("CI must have a GPU adapter (lavapipe): {e}")
        }
        Err(e) => {
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}

/// An object with a generated mesh.
pub fn object(name: &str, source: MeshSource, material: usize, transform: Transform) -> Object {
    Object {
        name: name.into(),
        source,
        mesh: 0,
        material,
        transform,
        sampling_weight: 1.0,
        role: ObjectRole::Static,
        visible: true,
    }
}

/// Builds a scene from objects with generated meshes.
pub fn scene(objects: Vec<Object>, materials: Vec<Material>, lights: Vec<Light>, camera: Camera) -> Scene {
    let desc = SceneDesc { materials, objects, lights, camera };
    bouncelab::import::resolve(desc, &[]).expect("scene resolves")
}

/// A `size` x `size` floor plane at y = 0 with albedo `albedo`.
pub fn floor(size: f32, albedo: f32) -> (Object, Material) {
    (object("floor", MeshSource::Plane { size }, 0, Transform::default()), Material::diffuse("floor", [albedo; 3]))
}

/// Renders `scene` and returns linear radiance.
pub fn render(ctx: &GpuContext, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Vec<[f32; 4]> {
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(scene, settings, size).expect("render");
    r.read_hdr().expect("readback")
}

/// Where the camera ray through pixel (x, y) hits the plane y = 0 within `half` of the origin.
pub fn floor_hit(camera: &Camera, x: u32, y: u32, size: (u32, u32), half: f32) -> Option<Vec3> {
    let d = camera.ray_direction(x as f32 + 0.5, y as f32 + 0.5, size.0, size.1);
    if d.y >= 0.0 {
        return None;
    }
    let t = -camera.position.y / d.y;
    let p = camera.position + d * t;
    (p.x.abs() < half && p.z.abs() < half).then_some(p)
}

/// Unused silencer for helpers some test files do not need.
pub fn _unused(_: Resources, _: Mesh) {}

/// The reference path tracer's image of `scene` at `size` with `settings` (all its spp).
pub fn reference(
    scene: &Scene,
    size: (u32, u32),
    settings: bouncelab::settings::ReferenceSettings,
) -> bouncelab::image_io::HdrImage {
    let spp = settings.spp;
    let mut tracer = bouncelab::precompute::pathtracer::PathTracer::new(scene, size, settings);
    tracer.render(spp, &std::sync::atomic::AtomicBool::new(false), |_| {});
    bouncelab::image_io::HdrImage { width: size.0, height: size.1, pixels: tracer.image() }
}
