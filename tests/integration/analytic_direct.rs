//! Per-pixel analytic checks of the raster direct lighting on the software adapter:
//! a Lambertian plane under a point light equals albedo/pi * I * cos / d^2 within 1% (away from
//! shadow edges), a spot light follows the KHR cone falloff, a directional light gives
//! albedo/pi * E * cos, and an occluder's shadow is black without acne or peter-panning.

use crate::common;

use bouncelab::scene::{Camera, Light, Material, MeshSource, Transform, spot_attenuation};
use bouncelab::settings::RenderSettings;
use glam::Vec3;

const SIZE: (u32, u32) = (96, 64);
const ALBEDO: f32 = 0.6;

fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.3, 2.2, 2.4), Vec3::new(0.0, 0.0, -0.2), 0.9)
}

/// Compares every floor pixel with `expected(p)`; returns (checked, worst relative error).
fn compare(pixels: &[[f32; 4]], mut expected: impl FnMut(Vec3) -> Option<f32>) -> (usize, f32) {
    let cam = camera();
    let mut checked = 0;
    let mut worst = 0.0f32;
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let Some(p) = common::floor_hit(&cam, x, y, SIZE, 1.9) else {
                continue;
            };
            let Some(want) = expected(p) else { continue };
            let got = pixels[(y * SIZE.0 + x) as usize];
            for c in &got[..3] {
                let err = (c - want).abs() / want.max(1e-3);
                assert!(err < 0.01, "pixel ({x},{y}) at {p}: got {c}, want {want} ({:.2}% off)", err * 100.0);
                worst = worst.max(err);
            }
            checked += 1;
        }
    }
    (checked, worst)
}

#[test]
fn point_light_on_lambertian_plane() {
    let Some(ctx) = common::gpu() else { return };
    let (floor, mat) = common::floor(4.0, ALBEDO);
    let light = Light::point("p", Vec3::new(0.3, 1.2, -0.4), 3.0);
    let scene = common::scene(vec![floor], vec![mat], vec![light.clone()], camera());
    let pixels = common::render(&ctx, &scene, &RenderSettings::default(), SIZE);
    let (checked, worst) = compare(&pixels, |p| {
        let to = light.position - p;
        let d2 = to.length_squared();
        Some(ALBEDO / std::f32::consts::PI * 3.0 * (to.y / d2.sqrt()) / d2)
    });
    assert!(checked > 2000, "only {checked} floor pixels");
    eprintln!("point light: {checked} pixels, worst error {:.3}%", worst * 100.0);
}

#[test]
fn spot_light_follows_khr_cone() {
    let Some(ctx) = common::gpu() else { return };
    let (floor, mat) = common::floor(4.0, ALBEDO);
    let dir = Vec3::new(0.2, -1.0, -0.1).normalize();
    let (inner, outer) = (0.25, 0.6);
    let light = Light::spot("s", Vec3::new(-0.2, 1.5, 0.0), dir, 5.0, inner, outer);
    let scene = common::scene(vec![floor], vec![mat], vec![light.clone()], camera());
    let pixels = common::render(&ctx, &scene, &RenderSettings::default(), SIZE);
    let mut inside = 0;
    let (checked, worst) = compare(&pixels, |p| {
        let to = light.position - p;
        let d = to.length();
        let l = to / d;
        let cone = spot_attenuation(dir.dot(-l), inner, outer);
        // Skip the last percent of the falloff, where the value is tiny and relative error meaningless.
        if cone > 0.0 && cone < 0.01 {
            return None;
        }
        if cone >= 1.0 {
            inside += 1;
        }
        Some(ALBEDO / std::f32::consts::PI * 5.0 * cone * l.y / (d * d))
    });
    assert!(checked > 2000 && inside > 100, "checked {checked}, fully inside the cone {inside}");
    eprintln!("spot light: {checked} pixels, worst error {:.3}%", worst * 100.0);
}

#[test]
fn directional_light_gives_e_cos() {
    let Some(ctx) = common::gpu() else { return };
    let (floor, mat) = common::floor(4.0, ALBEDO);
    let dir = Vec3::new(0.3, -1.0, 0.2).normalize();
    let light = Light::directional("sun", dir, 2.0);
    let scene = common::scene(vec![floor], vec![mat], vec![light], camera());
    let pixels = common::render(&ctx, &scene, &RenderSettings::default(), SIZE);
    let want = ALBEDO / std::f32::consts::PI * 2.0 * -dir.y;
    let (checked, worst) = compare(&pixels, |_| Some(want));
    assert!(checked > 2000);
    eprintln!("directional light: {checked} pixels, worst error {:.3}%", worst * 100.0);
}

fn ray_box(origin: Vec3, dir: Vec3, min: Vec3, max: Vec3, t_max: f32) -> bool {
    let inv = dir.recip();
    let (t0, t1) = ((min - origin) * inv, (max - origin) * inv);
    let near = t0.min(t1).max_element().max(0.0);
    let far = t0.max(t1).min_element().min(t_max);
    near <= far
}

#[test]
fn box_shadow_is_black_with_clean_edges() {
    let Some(ctx) = common::gpu() else { return };
    let (floor, floor_mat) = common::floor(4.0, ALBEDO);
    // A box resting on the floor: contact shadows must not leak (peter-panning) and the lit
    // floor must not show acne.
    let size = Vec3::new(0.5, 0.5, 0.5);
    let center = Vec3::new(0.0, 0.25, -0.3);
    let cube = common::object(
        "box",
        MeshSource::Cuboid { size, openings: [false; 6] },
        1,
        Transform { translation: center, ..Transform::default() },
    );
    let light = Light::point("p", Vec3::new(-0.4, 1.3, -1.1), 3.0);
    let scene = common::scene(
        vec![floor, cube],
        vec![floor_mat, Material::diffuse("box", [0.5; 3])],
        vec![light.clone()],
        camera(),
    );
    let pixels = common::render(&ctx, &scene, &RenderSettings::default(), SIZE);
    let (bmin, bmax) = (center - 0.5 * size, center + 0.5 * size);
    let cam = camera();
    let visible = |p: Vec3| {
        let to = light.position - p;
        !ray_box(p, to.normalize(), bmin, bmax, to.length())
    };
    let (mut lit, mut dark) = (0, 0);
    for y in 2..SIZE.1 - 2 {
        for x in 2..SIZE.0 - 2 {
            let Some(p) = common::floor_hit(&cam, x, y, SIZE, 1.9) else {
                continue;
            };
            // Camera sees the box instead of the floor here.
            let d = cam.ray_direction(x as f32 + 0.5, y as f32 + 0.5, SIZE.0, SIZE.1);
            if ray_box(cam.position, d, bmin, bmax, (p - cam.position).length()) {
                continue;
            }
            // Skip pixels within two pixels of a shadow edge.
            let v = visible(p);
            let near_edge = (-2i32..=2).any(|dy| {
                (-2i32..=2).any(|dx| {
                    common::floor_hit(&cam, (x as i32 + dx) as u32, (y as i32 + dy) as u32, SIZE, 1.95)
                        .is_some_and(|q| visible(q) != v)
                })
            });
            if near_edge {
                continue;
            }
            let got = pixels[(y * SIZE.0 + x) as usize][1];
            if v {
                let to = light.position - p;
                let d2 = to.length_squared();
                let want = ALBEDO / std::f32::consts::PI * 3.0 * (to.y / d2.sqrt()) / d2;
                assert!((got - want).abs() / want < 0.01, "lit pixel ({x},{y}): {got} vs {want} (acne?)");
                lit += 1;
            } else {
                assert!(got < 1e-4, "shadowed pixel ({x},{y}) = {got} (light leak?)");
                dark += 1;
            }
        }
    }
    assert!(lit > 1000 && dark > 100, "lit {lit}, shadowed {dark}");
}
