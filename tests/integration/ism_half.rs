//! `ism` gathering its VPLs at half resolution (`IsmSettings::shade_resolution`): the split
//! G-buffer holds every second pixel along each axis (a quarter of `ism shade`'s texels), and
//! the filter that takes its taps from those samples keeps full gathering's light, error and
//! steadiness on the Cornell box against the path tracer.

use crate::common;

use bouncelab::image_io::{self, HdrImage};
use bouncelab::metrics;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::settings::{GiMode, ReferenceSettings, ShadeResolution};

#[test]
fn half_resolution_gathering_splits_every_second_pixel_into_a_quarter_of_the_texels() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    settings.ism.bounces = 1;
    settings.ism.shade_resolution = ShadeResolution::Half;
    let n = settings.ism.interleave;
    // Odd sizes: the last sample of a row stands at the view's last pixel.
    let size = (71u32, 45u32);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&project.scene, &settings, size).expect("render");
    let normal = r.read_buffer("normal").expect("normal");
    let split = r.read_buffer("ism_split_normal").expect("split normals");
    let samples = (size.0.div_ceil(2), size.1.div_ceil(2));
    let block = (samples.0.div_ceil(n), samples.1.div_ceil(n));
    assert_eq!((split.width, split.height), (block.0 * n, block.1 * n), "a quarter of the view, padded to n");
    let raw = r.read_buffer("ism_raw").expect("split accumulation");
    assert_eq!((raw.width, raw.height), (split.width, split.height));
    for y in 0..samples.1 {
        for x in 0..samples.0 {
            let (sx, sy) = ((x % n) * block.0 + x / n, (y % n) * block.1 + y / n);
            let a = normal.pixels[(2 * y * size.0 + 2 * x) as usize];
            let b = split.pixels[(sy * split.width + sx) as usize];
            assert_eq!(a, b, "sample ({x}, {y}) -> pixel ({}, {}) -> split ({sx}, {sy})", 2 * x, 2 * y);
        }
    }
    let indirect = r.read_buffer("indirect").expect("indirect");
    assert!(indirect.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())), "finite indirect light");
}

/// Per frame of `mode` at `shade` over 12 frames at 64 x 36 from 2 x 2 supersampling: the
/// images box-filtered to 64 x 36.
fn frames(
    ctx: &bouncelab::render::GpuContext,
    project: &Project,
    mode: GiMode,
    shade: ShadeResolution,
) -> Vec<HdrImage> {
    let (size, k) = ((64u32, 36u32), 2u32);
    let big = (size.0 * k, size.1 * k);
    let mut settings = project.render.clone();
    settings.mode = mode;
    settings.ism.shade_resolution = shade;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    (0..12)
        .map(|_| {
            r.render(&project.scene, &settings, big).expect("render");
            let pixels = image_io::box_downsample(&r.read_hdr().expect("hdr"), big, k);
            HdrImage { width: size.0, height: size.1, pixels }
        })
        .collect()
}

/// The mean of `frames`' images.
fn mean_image(frames: &[HdrImage]) -> HdrImage {
    let mut out = frames[0].clone();
    for (i, p) in out.pixels.iter_mut().enumerate() {
        for (c, v) in p.iter_mut().enumerate() {
            *v = frames.iter().map(|f| f.pixels[i][c]).sum::<f32>() / frames.len() as f32;
        }
    }
    out
}

#[test]
#[ignore = "heavy: 48 default-settings ism frames and a reference"]
fn half_resolution_gathering_keeps_full_gatherings_light_error_and_steadiness() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let reference = common::reference(&project.scene, (64, 36), ReferenceSettings { spp: 256, ..Default::default() });
    let direct = {
        let mut settings = project.render.clone();
        settings.mode = GiMode::Direct;
        let big = common::render(&ctx, &project.scene, &settings, (128, 72));
        HdrImage { width: 64, height: 36, pixels: image_io::box_downsample(&big, (128, 72), 2) }
    };
    let fd = metrics::flip(&direct, &reference, 0.0).expect("flip").0;
    for mode in [GiMode::Ism, GiMode::IsmRitschel] {
        let full = frames(&ctx, &project, mode, ShadeResolution::Full);
        let half = frames(&ctx, &project, mode, ShadeResolution::Half);
        // ism: the settled frames; ism-ritschel: the mean of its independent frames.
        let judged = |f: &[HdrImage]| if mode == GiMode::Ism { f[11].clone() } else { mean_image(&f[6..]) };
        let (jf, jh) = (judged(&full), judged(&half));
        let (lf, lh) = (
            metrics::luminance_ratio(&jf, &reference).expect("ratio"),
            metrics::luminance_ratio(&jh, &reference).expect("ratio"),
        );
        let (ff, fh) = (
            metrics::flip(&jf, &reference, 0.0).expect("flip").0,
            metrics::flip(&jh, &reference, 0.0).expect("flip").0,
        );
        let (cf, ch) = (
            metrics::mean_frame_change(&full[6..]).expect("frames"),
            metrics::mean_frame_change(&half[6..]).expect("frames"),
        );
        eprintln!(
            "{mode:?} full / half: energy {lf:.4} / {lh:.4}, FLIP {ff:.4} / {fh:.4} (direct {fd:.4}), frame change {cf:.5} / {ch:.5}"
        );
        assert!((lh / lf - 1.0).abs() < 0.03, "{mode:?}: half gathering's energy {lh} against full's {lf}");
        assert!(fh < ff * 1.15 + 0.005, "{mode:?}: half gathering's FLIP {fh} against full's {ff}");
        assert!(ch < cf * 1.5 + 1.0e-4, "{mode:?}: half gathering's frame change {ch} against full's {cf}");
    }
}
