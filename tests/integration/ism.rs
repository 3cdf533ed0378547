//! `ism-ritschel` (instant radiosity with imperfect shadow maps, no temporal reuse) against the
//! reference path tracer with two bounces (direct + one indirect, what first-bounce VPLs model):
//! it must be much closer to the reference than `direct`, with the mean luminance close.

use crate::common;

use bouncelab::image_io::{self, HdrImage};
use bouncelab::metrics;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::scene::Light;
use bouncelab::settings::{GiMode, ReferenceSettings};
use glam::Vec3;

fn spot_cornell() -> Project {
    let mut project = Project::load(&default_project_path()).expect("default project");
    project.scene.desc_mut().lights =
        vec![Light::spot("spot", Vec3::new(0.0, 1.9, 0.2), Vec3::new(0.1, -1.0, -0.15).normalize(), 6.0, 0.5, 0.9)];
    project
}

fn raster(ctx: &bouncelab::render::GpuContext, project: &Project, mode: GiMode, size: (u32, u32), k: u32) -> HdrImage {
    let mut settings = project.render.clone();
    settings.mode = mode;
    let big = common::render(ctx, &project.scene, &settings, (size.0 * k, size.1 * k));
    HdrImage { width: size.0, height: size.1, pixels: image_io::box_downsample(&big, (size.0 * k, size.1 * k), k) }
}

fn check_against_reference(project: &Project, label: &str) {
    // First-bounce VPLs against direct + one indirect bounce.
    let mut project = project.clone();
    project.render.ism.bounces = 1;
    let project = &project;
    let Some(ctx) = common::gpu() else { return };
    let size = (64, 36);
    let reference =
        common::reference(&project.scene, size, ReferenceSettings { spp: 512, max_bounces: 2, ..Default::default() });
    let direct = raster(&ctx, project, GiMode::Direct, size, 2);
    let ism = raster(&ctx, project, GiMode::IsmRitschel, size, 2);
    let out = std::env::temp_dir();
    for (name, img) in [("ref", &reference), ("direct", &direct), ("ism", &ism)] {
        image_io::write_exr(&out.join(format!("bouncelab-ism-{label}-{name}.exr")), img).expect("exr");
    }
    let (fd, fi) = (
        metrics::flip(&direct, &reference, 0.0).expect("flip").0,
        metrics::flip(&ism, &reference, 0.0).expect("flip").0,
    );
    let (rd, ri) = (
        metrics::relmse(&direct, &reference, 0.01).expect("relmse"),
        metrics::relmse(&ism, &reference, 0.01).expect("relmse"),
    );
    let (ld, li) = (
        metrics::luminance_ratio(&direct, &reference).expect("ratio"),
        metrics::luminance_ratio(&ism, &reference).expect("ratio"),
    );
    eprintln!(
        "direct: FLIP {fd:.4} relMSE {rd:.4} luminance {ld:.3}; ism-ritschel: FLIP {fi:.4} relMSE {ri:.4} luminance {li:.3}"
    );
    assert!(fi < 0.75 * fd, "ISM FLIP {fi} vs direct {fd}");
    assert!(ri < 0.5 * rd, "ISM relMSE {ri} vs direct {rd}");
    assert!((li - 1.0).abs() < 0.1, "ISM mean luminance off by {:.1}%", (li - 1.0) * 100.0);
}

#[test]
fn ism_ritschel_with_a_spot_light() {
    check_against_reference(&spot_cornell(), "spot");
}

#[test]
fn ism_ritschel_with_a_point_light() {
    check_against_reference(&Project::load(&default_project_path()).expect("default project"), "point");
}

#[test]
fn bounces_add_energy_monotonically_and_converge() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&default_project_path()).expect("default project");
    let size = (64, 36);
    let reference = common::reference(&project.scene, size, ReferenceSettings { spp: 256, ..Default::default() });
    let full = metrics::mean_luminance(&reference);
    let mut lums = Vec::new();
    for bounces in 1..=4u32 {
        project.render.ism.bounces = bounces;
        project.render.mode = GiMode::IsmRitschel;
        // Average a few frames (new VPLs each frame) to keep the comparison above the noise.
        let mut r = bouncelab::render::Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut sum = 0.0;
        for _ in 0..6 {
            r.render(&project.scene, &project.render, size).expect("render");
            sum += metrics::mean_luminance(&HdrImage {
                width: size.0,
                height: size.1,
                pixels: r.read_hdr().expect("hdr"),
            });
        }
        lums.push(sum / 6.0);
    }
    let ratios: Vec<f64> = lums.iter().map(|l| l / full).collect();
    eprintln!("mean luminance / full-GI reference by bounces 1..4: {ratios:.3?}");
    for w in lums.windows(2) {
        assert!(w[1] >= 0.99 * w[0], "a bounce removed energy: {lums:?}");
    }
    assert!(lums[3] - lums[2] < lums[1] - lums[0], "added energy shrinks with each bounce: {lums:?}");
    assert!(ratios[3] > ratios[0], "more bounces come closer to the full reference");
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames and a reference"]
fn ism_with_defaults_after_32_frames_halves_the_flip_of_direct_against_full_gi() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let size = (64, 36);
    let reference = common::reference(&project.scene, size, ReferenceSettings { spp: 512, ..Default::default() });
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    let mut r = bouncelab::render::Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for _ in 0..32 {
        r.render(&project.scene, &settings, size).expect("render");
    }
    let ism = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
    settings.mode = GiMode::Direct;
    r.render(&project.scene, &settings, size).expect("render");
    let direct = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
    let (fd, fi) = (
        metrics::flip(&direct, &reference, 0.0).expect("flip").0,
        metrics::flip(&ism, &reference, 0.0).expect("flip").0,
    );
    let li = metrics::luminance_ratio(&ism, &reference).expect("ratio");
    eprintln!("defaults, 32 frames, full GI: direct FLIP {fd:.4}; ism FLIP {fi:.4}, luminance {li:.3}");
    assert!(fi < 0.5 * fd, "ism FLIP {fi} vs direct {fd}");
    // Within the scene-suite issue's 10% (0.924 here, 0.94 at 128x72 with 2x2 supersampling).
    // It read 0.99 while the bounce pass picked the brightest point, whose bias towards light
    // that stays near where it landed made up for the first bounce's ISM over-occlusion (0.87
    // of the path tracer's one-bounce light with the default maps, 0.96 with dense ones; the
    // one-bounce references agree with Mitsuba 3 within 0.02%).
    assert!((li - 1.0).abs() < 0.1, "ism mean luminance off by {:.1}%", (li - 1.0) * 100.0);
}

#[test]
fn more_vpls_never_make_it_worse_on_average() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let size = (64, 36);
    let reference = common::reference(&project.scene, size, ReferenceSettings { spp: 256, ..Default::default() });
    let mut errors = Vec::new();
    for n in [16u32, 64, 256] {
        let mut settings = project.render.clone();
        settings.mode = GiMode::IsmRitschel;
        settings.ism.vpl_count = n;
        settings.ism.bounces = 1;
        let mut r = bouncelab::render::Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        // Average over frames: each frame draws a new VPL set.
        let mut sum = 0.0;
        for _ in 0..4 {
            r.render(&project.scene, &settings, size).expect("render");
            let img = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
            sum += metrics::relmse(&img, &reference, 0.01).expect("relmse");
        }
        errors.push(sum / 4.0);
    }
    eprintln!("relMSE against full GI at 16/64/256 VPLs: {errors:.4?}");
    for w in errors.windows(2) {
        assert!(w[1] <= 1.05 * w[0], "more VPLs made it worse: {errors:?}");
    }
}

/// Every VPL lights exactly one interleave tile whatever the VPL count: 31 VPLs at n = 4 (16
/// tiles) give the same indirect light as 32 on average. Before the tiles took the remainder,
/// blocks of 31 / 16 = 1 VPL used 16 of the 31 and the indirect light read 0.498; the editor's
/// preview (fewer VPLs while something moves) left 12 of its 76 VPLs unused.
#[test]
fn a_vpl_count_that_no_tile_count_divides_loses_no_light() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let size = (48, 48);
    let mean = |mode: GiMode, vpl_count: u32, frames: usize| {
        let mut settings = project.render.clone();
        settings.mode = mode;
        settings.ism.vpl_count = vpl_count;
        settings.ism.interleave = 4;
        settings.ism.bounces = 1;
        let mut r = bouncelab::render::Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut sum = 0.0;
        // Each frame draws a new VPL set.
        for _ in 0..frames {
            r.render(&project.scene, &settings, size).expect("render");
            let img = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
            sum += metrics::mean_luminance(&img);
        }
        sum / frames as f64
    };
    let direct = mean(GiMode::Direct, 32, 1);
    let (odd, even) = (mean(GiMode::IsmRitschel, 31, 8) - direct, mean(GiMode::IsmRitschel, 32, 8) - direct);
    eprintln!("indirect light, 31 VPLs over 32: {:.3}", odd / even);
    assert!(even > 0.0 && (odd / even - 1.0).abs() < 0.1, "31 VPLs give {:.3} of 32's indirect light", odd / even);
}
