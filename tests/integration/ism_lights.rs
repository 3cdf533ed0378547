//! Every light feeds ISM: in the Cornell box lit by a spot, a point and a directional light of
//! comparable strength (none brighter than twice another), `ism` after 32 frames has less than
//! half the FLIP error of `direct` against the full-GI reference and its mean luminance within
//! 10%, with all three lights together and with each light alone.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::scene::Light;
use bouncelab::settings::{GiMode, ReferenceSettings};
use glam::Vec3;

const SIZE: (u32, u32) = (64, 36);

fn lights() -> Vec<Light> {
    vec![
        Light::spot("spot", Vec3::new(-0.5, 1.9, 0.3), Vec3::new(0.25, -1.0, -0.1).normalize(), 7.5, 0.3, 0.6),
        Light::point("point", Vec3::new(0.45, 1.2, -0.3), 0.6),
        // The box is open to +z: the sun shines in over the camera onto the floor and back wall.
        Light::directional("sun", Vec3::new(0.15, -0.6, -1.0).normalize(), 1.0),
    ]
}

fn render(ctx: &bouncelab::render::GpuContext, project: &Project, mode: GiMode, frames: usize) -> HdrImage {
    let mut settings = project.render.clone();
    settings.mode = mode;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for _ in 0..frames {
        r.render(&project.scene, &settings, SIZE).expect("render");
    }
    HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") }
}

/// Renders `lights` with `direct` (1 frame) and `ism` (32 frames) against the full-GI
/// reference; asserts that `ism` has less than half of `direct`'s FLIP error and its mean
/// luminance within 10%.
fn check(ctx: &bouncelab::render::GpuContext, name: &str, lights: Vec<Light>) {
    let mut base = Project::load(&default_project_path()).expect("default project");
    base.scene.desc_mut().lights = lights;
    let reference = common::reference(&base.scene, SIZE, ReferenceSettings { spp: 512, ..Default::default() });
    let direct = render(ctx, &base, GiMode::Direct, 1);
    let ism = render(ctx, &base, GiMode::Ism, 32);
    let (fd, fi) = (
        metrics::flip(&direct, &reference, 0.0).expect("flip").0,
        metrics::flip(&ism, &reference, 0.0).expect("flip").0,
    );
    let (ld, li) = (
        metrics::luminance_ratio(&direct, &reference).expect("ratio"),
        metrics::luminance_ratio(&ism, &reference).expect("ratio"),
    );
    eprintln!("{name}: direct FLIP {fd:.4} lum {ld:.3}; ism FLIP {fi:.4} ({:.2}x direct) lum {li:.3}", fi / fd);
    assert!(fi < 0.5 * fd, "{name}: ism FLIP {fi} is not below half of direct's {fd}");
    // The scene-suite issue's 10%: three lights read 0.94 (the first bounce's ISM
    // over-occlusion, no longer offset by the brightest-point bounce pick; tests/integration/ism.rs).
    assert!((li - 1.0).abs() < 0.1, "{name}: ism luminance ratio {li}");
}

/// The light of `lights()` called `name`, alone.
fn alone(name: &str) -> Vec<Light> {
    lights().into_iter().filter(|l| l.name == name).collect()
}

#[test]
fn the_spot_the_point_and_the_sun_are_comparable_no_light_twice_another() {
    let Some(ctx) = common::gpu() else { return };
    let mut base = Project::load(&default_project_path()).expect("default project");
    let direct_lum: Vec<f64> = lights()
        .into_iter()
        .map(|l| {
            base.scene.desc_mut().lights = vec![l];
            metrics::mean_luminance(&render(&ctx, &base, GiMode::Direct, 1))
        })
        .collect();
    let (lo, hi) = direct_lum.iter().fold((f64::MAX, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    eprintln!("direct luminance per light alone: {direct_lum:.4?}");
    assert!(hi <= 2.0 * lo, "lights are not comparable: {direct_lum:?}");
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames and a 512 spp reference"]
fn ism_with_a_spot_a_point_and_a_sun_together_halves_the_error_of_direct() {
    let Some(ctx) = common::gpu() else { return };
    check(&ctx, "all three", lights());
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames and a 512 spp reference"]
fn ism_with_the_spot_alone_halves_the_error_of_direct() {
    let Some(ctx) = common::gpu() else { return };
    check(&ctx, "spot", alone("spot"));
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames and a 512 spp reference"]
fn ism_with_the_point_alone_halves_the_error_of_direct() {
    let Some(ctx) = common::gpu() else { return };
    check(&ctx, "point", alone("point"));
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames and a 512 spp reference"]
fn ism_with_the_sun_alone_halves_the_error_of_direct() {
    let Some(ctx) = common::gpu() else { return };
    check(&ctx, "sun", alone("sun"));
}
