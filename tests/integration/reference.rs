//! The reference path tracer: convergence as 1/sqrt(spp), the analytic multi-bounce energy of a
//! closed box, agreement with the raster direct mode at one bounce, determinism, cancellation.

use crate::common;

use std::sync::atomic::AtomicBool;

use bouncelab::image_io::{self, HdrImage};
use bouncelab::metrics;
use bouncelab::precompute::pathtracer::PathTracer;
use bouncelab::precompute::rng::Pcg32;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::scene::{Camera, Light, Material, Mesh, MeshSource, Transform};
use bouncelab::settings::ReferenceSettings;
use glam::Vec3;

fn render(project: &Project, size: (u32, u32), settings: ReferenceSettings) -> HdrImage {
    let mut t = PathTracer::new(&project.scene, size, settings.clone());
    t.render(settings.spp, &AtomicBool::new(false), |_| {});
    HdrImage { width: size.0, height: size.1, pixels: t.image() }
}

/// The default project in `direct` (these tests hold the raster's direct light against the
/// path tracer's; the project itself opens in a GI mode).
fn default_project() -> Project {
    let mut p = Project::load(&default_project_path()).expect("default project");
    p.render.mode = bouncelab::settings::GiMode::Direct;
    p
}

#[test]
fn error_falls_as_inverse_sqrt_spp() {
    let project = default_project();
    let size = (32, 18);
    let reference = render(&project, size, ReferenceSettings { spp: 2048, seed: 99, ..Default::default() });
    let errors: Vec<f64> = [4, 16, 64]
        .iter()
        .map(|&spp| {
            metrics::rmse(&render(&project, size, ReferenceSettings { spp, seed: 1, ..Default::default() }), &reference)
                .expect("rmse")
        })
        .collect();
    eprintln!("rmse at 4/16/64 spp: {errors:?}");
    // Each 4x more samples should halve the error (the reference's own noise adds ~1%).
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((1.6..2.5).contains(&ratio), "4x spp reduced the error by {ratio}, expected ~2");
    }
}

#[test]
fn closed_box_matches_the_geometric_series() {
    // A closed 2 m box of inward-facing quads with albedo rho and a point light inside: all of
    // the light's power 4 pi I lands on the walls, and each bounce returns rho of it, so the
    // area-averaged outgoing radiance is rho / (pi (1 - rho)) * 4 pi I / A, exactly.
    let rho = 0.6f32;
    let intensity = 2.0f32;
    let side = 2.0f32;
    let inward = {
        let mut m = Mesh::cuboid("room", Vec3::splat(side));
        for tri in m.indices.chunks_exact_mut(3) {
            tri.swap(1, 2);
        }
        for n in &mut m.normals {
            *n = -*n;
        }
        m
    };
    let mut scene = common::scene(
        vec![common::object(
            "room",
            MeshSource::Cuboid { size: Vec3::splat(side), openings: [false; 6] },
            0,
            Transform::default(),
        )],
        vec![Material::diffuse("grey", [rho; 3])],
        vec![Light::point("bulb", Vec3::new(0.3, 0.2, -0.1), intensity)],
        Camera::default(),
    );
    scene.resources_mut().meshes[0] = inward;
    let settings = ReferenceSettings { spp: 1, max_bounces: 256, ..Default::default() };
    let tracer = PathTracer::new(&scene, (1, 1), settings);
    // Area-uniform points on the walls, each looked at from just inside along its normal.
    let mut rng = Pcg32::new(5, 0, 0);
    let n = 200_000;
    let mut sum = 0.0f64;
    for _ in 0..n {
        let face = (rng.next_f32() * 6.0) as usize % 6;
        let (a, b) = (rng.next_f32() * side - 1.0, rng.next_f32() * side - 1.0);
        let axis = face / 2;
        let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
        let mut p = [a, b, a];
        p[axis] = sign;
        p[(axis + 1) % 3] = a;
        p[(axis + 2) % 3] = b;
        let p = Vec3::from_array(p);
        let mut normal = Vec3::ZERO;
        normal[axis] = -sign;
        let (l, _) = tracer.radiance(p + normal * 1e-3, -normal, &mut rng);
        sum += f64::from(l.x);
    }
    let measured = sum / f64::from(n);
    let area = 6.0 * side * side;
    let expected =
        f64::from(rho / (std::f32::consts::PI * (1.0 - rho)) * 4.0 * std::f32::consts::PI * intensity / area);
    eprintln!("closed box: measured {measured:.5}, analytic {expected:.5}");
    assert!((measured / expected - 1.0).abs() < 0.01, "measured {measured}, analytic {expected}");
}

/// Raster direct light (supersampled `k` x `k`, box-filtered) against two one-bounce
/// references with different seeds: the mean luminance within 2% and the per-pixel difference
/// within the references' own noise plus the raster's own sampling error. The latter is twice
/// the raster's change from `k` to `2k` samples a side (an error falling as 1/k): with the
/// path tracer's stratified samples (since 2026-11-30) the references' noise alone (0.0003)
/// is far below the raster's edge sampling (0.0025-0.0058), which the old independent
/// samples' noise (0.005-0.028) had covered.
fn assert_raster_matches_one_bounce(
    ctx: &bouncelab::render::GpuContext,
    project: &Project,
    size: (u32, u32),
    k: u32,
    label: &str,
) {
    // Direct light: the project's own mode may be a GI technique (the default project's is).
    let direct =
        bouncelab::settings::RenderSettings { mode: bouncelab::settings::GiMode::Direct, ..project.render.clone() };
    let big = common::render(ctx, &project.scene, &direct, (size.0 * k, size.1 * k));
    let raster =
        HdrImage { width: size.0, height: size.1, pixels: image_io::box_downsample(&big, (size.0 * k, size.1 * k), k) };
    let big2 = common::render(ctx, &project.scene, &direct, (size.0 * 2 * k, size.1 * 2 * k));
    let finer = HdrImage {
        width: size.0,
        height: size.1,
        pixels: image_io::box_downsample(&big2, (size.0 * 2 * k, size.1 * 2 * k), 2 * k),
    };
    let sampling = 2.0 * metrics::rmse(&raster, &finer).expect("rmse");
    let one = ReferenceSettings { spp: 256, max_bounces: 1, ..Default::default() };
    let a = render(project, size, one.clone());
    let b = render(project, size, ReferenceSettings { seed: 7, ..one });
    let ratio = metrics::luminance_ratio(&raster, &a).expect("ratio");
    let (err, noise) = (metrics::rmse(&raster, &a).expect("rmse"), metrics::rmse(&a, &b).expect("rmse"));
    eprintln!(
        "{label}: raster/reference luminance {ratio:.4}, rmse {err:.4}, reference noise {noise:.4}, raster sampling {sampling:.4}"
    );
    assert!((ratio - 1.0).abs() < 0.02, "{label}: mean luminance differs by {:.2}%", (ratio - 1.0) * 100.0);
    // A raster fault that changes with the resolution (acne, speckle) would widen its own
    // allowance: the sampling error has a bound of its own (measured 0.0032-0.0095).
    assert!(sampling < 0.012, "{label}: the raster changes by {sampling} from {k} to {} samples a side", 2 * k);
    assert!(
        err < 1.5 * (noise + sampling) + 1e-3,
        "{label}: raster differs from the reference by {err}, more than its noise {noise} and its own sampling {sampling}"
    );
}

#[test]
fn one_bounce_reference_agrees_with_raster_direct() {
    let Some(ctx) = common::gpu() else { return };
    let project = default_project();
    assert_raster_matches_one_bounce(&ctx, &project, (64, 36), 4, "point light");
    let flip = {
        let a = render(&project, (64, 36), ReferenceSettings { spp: 64, max_bounces: 1, ..Default::default() });
        let big = common::render(&ctx, &project.scene, &project.render, (256, 144));
        let raster = HdrImage { width: 64, height: 36, pixels: image_io::box_downsample(&big, (256, 144), 4) };
        metrics::flip(&raster, &a, 0.0).expect("flip").0
    };
    assert!(flip < 0.08, "FLIP {flip}");
}

#[test]
fn deterministic_for_a_seed_and_cancelable() {
    let project = default_project();
    let s = ReferenceSettings { spp: 2, ..Default::default() };
    let a = render(&project, (16, 9), s.clone());
    let b = render(&project, (16, 9), s.clone());
    assert_eq!(a, b, "same seed, same image");
    let c = render(&project, (16, 9), ReferenceSettings { seed: 3, ..s.clone() });
    assert_ne!(a, c);
    let mut t = PathTracer::new(&project.scene, (16, 9), s);
    assert!(t.add_sample(&AtomicBool::new(true)).is_none());
    assert_eq!(t.spp(), 0, "a cancelled pass adds nothing");
    let p = t.add_sample(&AtomicBool::new(false)).expect("pass");
    assert!(p.spp == 1 && p.rays_per_second > 0.0);
}

#[test]
fn flip_of_identical_images_is_zero_and_grows_with_difference() {
    let project = default_project();
    let a = render(&project, (24, 16), ReferenceSettings { spp: 4, max_bounces: 1, ..Default::default() });
    assert_eq!(metrics::flip(&a, &a, 0.0).expect("flip").0, 0.0);
    let mut darker = a.clone();
    for p in &mut darker.pixels {
        for c in &mut p[..3] {
            *c *= 0.5;
        }
    }
    let mut much_darker = a.clone();
    for p in &mut much_darker.pixels {
        for c in &mut p[..3] {
            *c *= 0.1;
        }
    }
    let (f1, f2) =
        (metrics::flip(&darker, &a, 0.0).expect("flip").0, metrics::flip(&much_darker, &a, 0.0).expect("flip").0);
    assert!(0.0 < f1 && f1 < f2, "{f1} {f2}");
}

#[test]
fn spot_and_directional_lights_agree_with_raster() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = default_project();
    let desc = project.scene.desc_mut();
    desc.lights = vec![
        Light::spot("spot", Vec3::new(0.2, 1.9, 0.3), Vec3::new(-0.2, -1.0, -0.3).normalize(), 6.0, 0.3, 0.7),
        Light::directional("sun", Vec3::new(0.25, -0.35, -1.0).normalize(), 1.5),
    ];
    assert_raster_matches_one_bounce(&ctx, &project, (48, 27), 8, "spot + sun");
}

#[test]
fn glossy_materials_agree_with_raster() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = default_project();
    for m in &mut project.scene.desc_mut().materials {
        m.specular = [0.3, 0.3, 0.3];
        m.roughness = 0.4;
        for c in &mut m.base_color[..3] {
            *c *= 0.6;
        }
    }
    assert_raster_matches_one_bounce(&ctx, &project, (48, 27), 8, "glossy");
}

#[test]
fn large_scenes_with_a_tiny_near_plane_stay_exact() {
    // The Cornell box scaled 100x (200 m) seen through a 1 mm near plane: reversed depth keeps
    // reconstructed positions, and so lighting and shadows, exact.
    let Some(ctx) = common::gpu() else { return };
    let mut project = default_project();
    let k = 100.0;
    let desc = project.scene.desc_mut();
    for o in &mut desc.objects {
        o.transform.translation *= k;
        o.transform.scale *= k;
    }
    for l in &mut desc.lights {
        l.position *= k;
        l.intensity *= k * k;
    }
    desc.camera.position *= k;
    desc.camera.znear = 0.001;
    desc.camera.zfar = None;
    assert_raster_matches_one_bounce(&ctx, &project, (64, 36), 4, "scaled 100x");
}
