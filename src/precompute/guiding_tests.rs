//! Path guiding inside the reference tracer: on a level of two rooms joined by a doorway, lit in
//! one and seen from the other (the case guiding is for), the guided render converges to the
//! unguided one (unbiased) and is the same for the same seed. Its noise against the unguided
//! render's is measured on full-size views (docs/notes/reference-tracer.md): on this 24x16
//! image, whose few training paths make noisy guides, it was 2.3x the unguided error at 128 spp.

use glam::Vec3;

use super::pathtracer::PathTracer;
use super::test_scenes::slab;
use crate::scene::{Camera, Light, Material, Mesh, Resources, Scene, SceneDesc};
use crate::settings::ReferenceSettings;

const SIZE: (u32, u32) = (24, 16);

/// Two 3 m rooms side by side (x < 0 and x > 0) joined by a 1 m doorway in the wall between
/// them; a point light in the left room, the camera in the right one looking at the doorway.
fn two_rooms() -> Scene {
    let t = 0.2;
    let parts: [(&str, Vec3, Vec3); 8] = [
        ("floor", Vec3::new(0.0, -t / 2.0, 0.0), Vec3::new(6.4, t, 3.4)),
        ("ceiling", Vec3::new(0.0, 2.5 + t / 2.0, 0.0), Vec3::new(6.4, t, 3.4)),
        ("west", Vec3::new(-3.0 - t / 2.0, 1.25, 0.0), Vec3::new(t, 2.5, 3.0)),
        ("east", Vec3::new(3.0 + t / 2.0, 1.25, 0.0), Vec3::new(t, 2.5, 3.0)),
        ("north", Vec3::new(0.0, 1.25, -1.5 - t / 2.0), Vec3::new(6.0, 2.5, t)),
        ("south", Vec3::new(0.0, 1.25, 1.5 + t / 2.0), Vec3::new(6.0, 2.5, t)),
        ("divider_n", Vec3::new(0.0, 1.25, -1.0), Vec3::new(t, 2.5, 1.0)),
        ("divider_s", Vec3::new(0.0, 1.25, 1.0), Vec3::new(t, 2.5, 1.0)),
    ];
    let objects = parts.iter().enumerate().map(|(i, (n, c, s))| slab(n, *c, *s, i)).collect();
    let meshes = parts.iter().map(|(n, _, s)| Mesh::cuboid(n, *s)).collect();
    let desc = SceneDesc {
        materials: vec![Material::diffuse("plaster", [0.7; 3])],
        objects,
        lights: vec![Light::point("lamp", Vec3::new(-2.0, 1.8, 0.5), 20.0)],
        camera: Camera::look_at(Vec3::new(2.7, 1.3, 1.2), Vec3::new(0.0, 1.0, 0.0), 1.2),
        ..SceneDesc::default()
    };
    Scene::new(desc, Resources { meshes, images: vec![], sky: None }).expect("scene")
}

fn render(scene: &Scene, spp: u32, guiding: bool, seed: u64) -> Vec<[f32; 4]> {
    let settings = ReferenceSettings { spp, guiding, seed, ..ReferenceSettings::default() };
    let mut tracer = PathTracer::new(scene, SIZE, settings);
    tracer.render(spp, &std::sync::atomic::AtomicBool::new(false), |_| {});
    assert_eq!(tracer.guide_cells() > 0, guiding, "a guide is learnt only with guiding on");
    tracer.image()
}

fn luminance(p: &[f32; 4]) -> f64 {
    f64::from(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
}

fn mean(image: &[[f32; 4]]) -> f64 {
    image.iter().map(luminance).sum::<f64>() / image.len() as f64
}

/// The guided image's mean, and each half's, match a long unguided render's: a wrong mixture
/// density or a guide that learnt from the pass it samples would move them.
#[test]
fn guided_renders_converge_to_the_unguided_image() {
    let scene = two_rooms();
    let truth = render(&scene, 2048, false, 99);
    let guided = render(&scene, 256, true, 1);
    let half = |image: &[[f32; 4]], right: bool| {
        let w = SIZE.0 as usize;
        let part: Vec<[f32; 4]> =
            image.iter().enumerate().filter(|(i, _)| (i % w >= w / 2) == right).map(|(_, p)| *p).collect();
        mean(&part)
    };
    assert!(mean(&truth) > 0.0, "the right room gets light through the doorway");
    for (what, got, want) in [
        ("image", mean(&guided), mean(&truth)),
        ("left half", half(&guided, false), half(&truth, false)),
        ("right half", half(&guided, true), half(&truth, true)),
    ] {
        assert!((got / want - 1.0).abs() < 0.03, "{what}: guided mean {got} vs unguided {want}");
    }
}

#[test]
fn a_guided_render_is_the_same_for_the_same_seed() {
    let scene = two_rooms();
    assert_eq!(render(&scene, 70, true, 5), render(&scene, 70, true, 5));
}
