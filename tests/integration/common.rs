//! Shared helpers for integration tests: the GPU (a missing adapter fails under CI, is skipped
//! locally), small scenes built in code, and rendering to linear radiance.
#![allow(dead_code)]

use std::sync::Mutex;

use bouncelab::render::{GpuContext, Renderer};
use bouncelab::scene::{
    Camera, Light, Material, Mesh, MeshSource, Object, ObjectRole, Resources, Scene, SceneDesc, Transform,
};
use bouncelab::settings::RenderSettings;
use glam::Vec3;

/// Devices created by earlier tests of this process, free for the next one. A test holds its
/// device alone (lavapipe runs a submission on the submitting thread, so two tests sharing one
/// queue would wait for each other); the pool never holds more devices than tests have run at
/// once, so the whole run creates about `--test-threads` devices instead of one per test.
static POOL: Mutex<Vec<GpuContext>> = Mutex::new(Vec::new());

/// A device of [`POOL`], lent to one test; it goes back when the test ends, unless the test
/// panicked (its device may be in any state).
pub struct Gpu(Option<GpuContext>);

impl std::ops::Deref for Gpu {
    type Target = GpuContext;

    fn deref(&self) -> &GpuContext {
        self.0.as_ref().expect("a lent device is present until dropped")
    }
}

impl Drop for Gpu {
    fn drop(&mut self) {
        if let Some(ctx) = self.0.take()
            && !std::thread::panicking()
        {
            POOL.lock().unwrap_or_else(|e| e.into_inner()).push(ctx);
        }
    }
}

/// The GPU, or `None` (with a note) when there is none and we are not in CI.
pub fn gpu() -> Option<Gpu> {
    if let Some(ctx) = POOL.lock().unwrap_or_else(|e| e.into_inner()).pop() {
        return Some(Gpu(Some(ctx)));
    }
    match GpuContext::new_headless() {
        Ok(ctx) => Some(Gpu(Some(ctx))),
        Err(e) if std::env::var_os("CI").is_some() => {
            panic!("CI must have a GPU adapter (lavapipe): {e}")
        }
        Err(e) => {
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}

/// Whether there is a GPU adapter (under CI there must be one: a missing adapter panics).
pub fn has_gpu() -> bool {
    gpu().is_some()
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
    let desc = SceneDesc { materials, objects, lights, camera, ..SceneDesc::default() };
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

/// The default Cornell box with a dark glossy floor (albedo 0.2, specular 0.6, roughness 0.4)
/// that a spot grazes: most of the floor's first-bounce light leaves it in its specular lobe.
pub fn glossy_cornell() -> bouncelab::project_file::Project {
    use bouncelab::project_file::{Project, default_project_path};
    let mut project = Project::load(&default_project_path()).expect("default project");
    let desc = project.scene.desc_mut();
    let mut floor = desc.materials[0].clone();
    floor.name = "glossy floor".into();
    floor.base_color = [0.2, 0.2, 0.2, 1.0];
    floor.specular = [0.6, 0.6, 0.6];
    floor.roughness = 0.4;
    desc.materials.push(floor);
    let glossy = desc.materials.len() - 1;
    desc.objects[0].material = glossy;
    desc.lights =
        vec![Light::spot("spot", Vec3::new(-0.9, 1.2, 0.3), Vec3::new(1.0, -1.1, -0.2).normalize(), 8.0, 0.4, 0.8)];
    let desc = desc.clone();
    project.scene = bouncelab::import::resolve(desc, &project.imported).expect("resolves");
    project
}

/// Unused silencer for helpers some test files do not need.
pub fn _unused(_: Resources, _: Mesh) {}

/// The reference path tracer's image of `scene` at `size` with `settings` (all its spp).
pub fn reference(
    scene: &Scene,
    size: (u32, u32),
    settings: bouncelab::settings::ReferenceSettings,
) -> bouncelab::image_io::HdrImage {
    bouncelab::render::harness::reference_image(scene, size, settings)
}

/// Renders until the active technique is ready (its CPU preparation and any rebuild done,
/// sleeping between frames so the preparation has the cores).
pub fn until_ready(r: &mut Renderer, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) {
    bouncelab::render::harness::until_ready(r, scene, settings, size, |_| {}).expect("render");
}

/// A fresh, empty folder for one test: `<tmp>/bouncelab-<kind>-<pid>-<name>`.
pub fn temp_dir(kind: &str, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("bouncelab-{kind}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}
