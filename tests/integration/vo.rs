//! Volumetric obscurance (Loos 2015 ch. 6): an open floor reads a uniform factor of one, with the
//! normal clamp and (through 2V) without it, and the crease where a wall stands on it is darker;
//! the thickness model frees the floor far behind a thin post; the factor reaches the composite
//! only where it applies.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::render::Renderer;
use bouncelab::scene::{Camera, Light, MeshSource, Scene, Transform};
use bouncelab::settings::{GiMode, RenderSettings, VoSettings};
use glam::Vec3;

const SIZE: (u32, u32) = (128, 96);

/// A 6 m floor with a 4 m wall standing across it at z = 0 (and, with `post`, a thin 2 m post
/// at z = 1.2), seen from the front.
fn scene(post: bool) -> Scene {
    let (floor, floor_material) = common::floor(6.0, 0.7);
    let cuboid = |name: &str, centre: Vec3, size: Vec3| {
        common::object(
            name,
            MeshSource::Cuboid { size, openings: [false; 6] },
            0,
            Transform { translation: centre, ..Default::default() },
        )
    };
    let mut objects = vec![floor, cuboid("wall", Vec3::new(0.0, 0.75, 0.0), Vec3::new(4.0, 1.5, 0.2))];
    if post {
        objects.push(cuboid("post", Vec3::new(0.0, 1.0, 1.2), Vec3::new(0.05, 2.0, 0.05)));
    }
    let lights = vec![Light::point("lamp", Vec3::new(0.0, 2.5, 2.0), 10.0)];
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 3.2), Vec3::new(0.0, 0.0, 0.6), 1.0);
    common::scene(objects, vec![floor_material], lights, camera)
}

/// The `vo` buffer (r: the factor, g: before the blur) of `scene` under `vo`, in `sshgi` with
/// obscurance on for the other modes.
fn obscurance(ctx: &bouncelab::render::GpuContext, scene: &Scene, vo: VoSettings) -> HdrImage {
    let settings =
        RenderSettings { mode: GiMode::Sshgi, vo: VoSettings { other_modes: true, ..vo }, ..RenderSettings::default() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(scene, &settings, SIZE).expect("render");
    r.read_buffer("vo").expect("vo buffer")
}

/// The factors of the floor pixels whose point satisfies `keep`.
fn floor_factors(img: &HdrImage, camera: &Camera, keep: impl Fn(Vec3) -> bool) -> Vec<f32> {
    let mut out = Vec::new();
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            if let Some(p) = common::floor_hit(camera, x, y, SIZE, 3.0)
                && keep(p)
            {
                out.push(img.pixels[(y * SIZE.0 + x) as usize][0]);
            }
        }
    }
    assert!(out.len() > 30, "{} pixels", out.len());
    out
}

fn mean(v: &[f32]) -> f32 {
    v.iter().sum::<f32>() / v.len() as f32
}

#[test]
fn an_open_floor_reads_one_everywhere_and_the_crease_at_a_wall_is_darker() {
    let Some(ctx) = common::gpu() else { return };
    let s = scene(false);
    let camera = s.desc().camera;
    for clamp in [true, false] {
        // A 0.5 m sphere: the crease within 0.1 m of the wall has it a quarter full of wall.
        let img = obscurance(&ctx, &s, VoSettings { normal_clamp: clamp, radius: 0.5, ..VoSettings::default() });
        let open = floor_factors(&img, &camera, |p| p.z > 1.0 && p.x.abs() < 1.5);
        let crease = floor_factors(&img, &camera, |p| (0.1..0.2).contains(&p.z) && p.x.abs() < 1.5);
        let (lo, hi) = open.iter().fold((f32::MAX, 0.0f32), |(a, b), v| (a.min(*v), b.max(*v)));
        eprintln!("normal clamp {clamp}: open floor {lo:.3} .. {hi:.3}, crease mean {:.3}", mean(&crease));
        assert!(lo > 0.97 && hi <= 1.0, "normal clamp {clamp}: the open floor reads {lo:.3} .. {hi:.3}");
        assert!(mean(&crease) < 0.85, "normal clamp {clamp}: the crease reads {:.3}", mean(&crease));
    }
}

#[test]
fn the_thickness_model_frees_the_floor_behind_a_thin_post() {
    let Some(ctx) = common::gpu() else { return };
    let s = scene(true);
    let camera = s.desc().camera;
    // Floor pixels beside the post's silhouette and far behind it (the post stands at z = 1.2
    // and hides the floor at x = 0 beyond it; these see past it, their chords meet it).
    let behind = |p: Vec3| (0.3..0.9).contains(&p.z) && (0.05..0.15).contains(&p.x.abs());
    let radius = 1.0;
    let thin = obscurance(&ctx, &s, VoSettings { radius, thickness: 0.1, ..VoSettings::default() });
    let solid = obscurance(&ctx, &s, VoSettings { radius, thickness: 0.0, ..VoSettings::default() });
    let (a, b) = (mean(&floor_factors(&thin, &camera, behind)), mean(&floor_factors(&solid, &camera, behind)));
    eprintln!("floor behind the post: thickness 0.1 m {a:.3}, no thickness model {b:.3}");
    assert!(a > b + 0.02, "with a slab 0.1 m thick the floor behind reads {a:.3}, as an infinite solid {b:.3}");
}

#[test]
fn obscurance_reaches_the_image_only_where_it_applies() {
    let Some(ctx) = common::gpu() else { return };
    let s = scene(false);
    let image = |vo: VoSettings| {
        let settings = RenderSettings { mode: GiMode::Sshgi, vo, ..RenderSettings::default() };
        common::render(&ctx, &s, &settings, SIZE)
    };
    let off = image(VoSettings { other_modes: false, ..VoSettings::default() });
    let on = image(VoSettings { other_modes: true, ..VoSettings::default() });
    let sum = |v: &[[f32; 4]]| v.iter().map(|p| f64::from(p[0] + p[1] + p[2])).sum::<f64>();
    assert!(sum(&on) < sum(&off), "obscurance darkens the indirect term: {} vs {}", sum(&on), sum(&off));
    let never = RenderSettings {
        mode: GiMode::Direct,
        vo: VoSettings { other_modes: true, ..VoSettings::default() },
        ..RenderSettings::default()
    };
    let direct = common::render(&ctx, &s, &never, SIZE);
    let plain = common::render(&ctx, &s, &RenderSettings { mode: GiMode::Direct, ..RenderSettings::default() }, SIZE);
    assert_eq!(direct, plain, "direct light is never obscured");
}
