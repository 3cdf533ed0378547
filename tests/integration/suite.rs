//! The scene suite: the shipped levels and cached references are current, and `ism` holds on
//! level-like scenes at CI sizes against the cached references (box-filtered to 64x36): the
//! energy within 10% on the windowed room, the cluttered room and the diorama, and no light
//! through the walls into the unlit third room of the multi-room level, whose frames the default
//! bounce pick keeps steadier than the per-chain pick.

use crate::common;

use std::path::Path;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::render::Renderer;
use bouncelab::settings::{BouncePick, GiMode, IsmSettings};
use bouncelab::suite::{self, REFERENCE_SIZE, SCENES};

const SIZE: (u32, u32) = (REFERENCE_SIZE.0 / 2, REFERENCE_SIZE.1 / 2);

#[test]
fn suite_levels_and_references_are_current() {
    let root = Path::new(".");
    for scene in SCENES {
        if let Some(text) = scene.gltf_text() {
            let on_disk = std::fs::read_to_string(scene.gltf_path(root)).expect("level file");
            assert!(on_disk == text, "{} is out of date: run `bouncelab suite --references`", scene.name);
        }
        let reference = scene.reference(root).unwrap_or_else(|e| panic!("{e}"));
        assert!(reference.pixels.iter().all(|p| p.iter().all(|v| v.is_finite() && *v >= 0.0)));
        assert!(metrics::mean_luminance(&reference) > 0.0, "{} reference is black", scene.name);
    }
    assert!(matches!(suite::scene("nope"), Err(suite::SuiteError::Unknown(..))));
}

/// `ism` of suite scene `name`, the mean of frames 17 to `frames` (the estimator's expectation:
/// one frame of a room lit by a handful of bounce VPLs swings by tens of percent), and the
/// reference at the same size.
fn ism_and_reference(ctx: &bouncelab::render::GpuContext, name: &str, frames: usize) -> (HdrImage, HdrImage, Renderer) {
    let (img, reference, r, _) = ism_frames_and_reference(ctx, name, frames);
    (img, reference, r)
}

/// [`ism_and_reference`], with the frames from 33 on (after a still view's history has settled,
/// `IsmSettings::still_frames`) kept one by one.
fn ism_frames_and_reference(
    ctx: &bouncelab::render::GpuContext,
    name: &str,
    frames: usize,
) -> (HdrImage, HdrImage, Renderer, Vec<HdrImage>) {
    let scene = suite::scene(name).expect("scene");
    let mut project = scene.load(Path::new(".")).expect("loads");
    project.render.mode = GiMode::Ism;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mut sum = vec![[0.0f32; 4]; (SIZE.0 * SIZE.1) as usize];
    let averaged = (frames - 16) as f32;
    let mut settled = Vec::new();
    for frame in 0..frames {
        r.render(&project.scene, &project.render, SIZE).expect("render");
        if frame >= 16 {
            let pixels = r.read_hdr().expect("hdr");
            for (s, p) in sum.iter_mut().zip(&pixels) {
                (0..4).for_each(|c| s[c] += p[c] / averaged);
            }
            if frame >= 32 {
                settled.push(HdrImage { width: SIZE.0, height: SIZE.1, pixels });
            }
        }
    }
    let img = HdrImage { width: SIZE.0, height: SIZE.1, pixels: sum };
    let reference = suite::downsample(&scene.reference(Path::new(".")).expect("reference"), 2);
    (img, reference, r, settled)
}

#[test]
#[ignore = "heavy: 48 default-settings ism frames of the three-room level"]
fn ism_puts_no_light_through_the_walls_into_the_unlit_room_and_its_settled_frames_hold_within_ten_percent() {
    let Some(ctx) = common::gpu() else { return };
    let (img, reference, r, settled) = ism_frames_and_reference(&ctx, "rooms", 48);
    let project = suite::scene("rooms").expect("scene").load(Path::new(".")).expect("loads");
    // Pixels on the third room's own surfaces (the camera stands in it).
    let ids = r.read_buffer("object_id").expect("ids");
    let third: Vec<usize> =
        (0..ids.pixels.len())
            .filter(|&i| {
                let id = ids.pixels[i][0] as usize;
                id > 0
                    && project.scene.objects().get(id - 1).is_some_and(|o| {
                        o.name.ends_with("_2") || o.name.starts_with("partition_1") || o.name == "end_2"
                    })
            })
            .collect();
    assert!(third.len() > SIZE.0 as usize * SIZE.1 as usize / 3, "the view shows the third room: {}", third.len());
    let mean = |img: &HdrImage| {
        third.iter().map(|&i| f64::from(bouncelab::metrics::luminance(&img.pixels[i]))).sum::<f64>()
            / third.len() as f64
    };
    let (ism, truth) = (mean(&img), mean(&reference));
    eprintln!("unlit third room over {} px: ism {ism:.5}, reference {truth:.5}, ratio {:.3}", third.len(), ism / truth);
    // No leak: at most 10% over the reference; and the light that reaches the room through the
    // two doorways (three bounces and more) not lost: at most 10% under it (lookups that dilate
    // the doorways, or bounces that keep light near where it landed, fall below). Measured
    // 0.983 (mean of frames 17-48, the resampled pick with view importance; over frames 17-32
    // 0.905, hence the longer window); 1.004 with the per-chain pick over frames 17-32.
    let ratio = ism / truth;
    assert!(ratio < 1.1, "light through the walls: the unlit room reads {ratio:.3} of the reference");
    assert!(ratio > 0.9, "too little light through the doorways: {ratio:.3} of the reference");
    // Steady once settled (#46 item 3): every single frame 33-48 of the unlit room within 10%,
    // and their spread (standard deviation over mean) at most 3%. Before `still_frames` the
    // matrix's frames 9-32 of this view read 0.72 at worst with an 8.9% spread.
    let frames: Vec<f64> = settled.iter().map(|f| mean(f) / truth).collect();
    let spread = metrics::relative_spread(&frames);
    eprintln!("unlit third room, frames 33-48 one by one: {frames:.3?}, spread {:.1}%", 100.0 * spread);
    assert!(frames.iter().all(|e| (e - 1.0).abs() < 0.1), "a settled frame off by 10% or more: {frames:.3?}");
    assert!(spread <= 0.03, "settled frames wander: spread {:.1}%", 100.0 * spread);
}

/// Asserts that `ism`'s energy on suite scene `name` (mean of frames 17 to 32) is within 10% of
/// the reference's.
fn energy_within_ten_percent(name: &str) {
    let Some(ctx) = common::gpu() else { return };
    let (img, reference, _) = ism_and_reference(&ctx, name, 32);
    let ratio = metrics::luminance_ratio(&img, &reference).expect("ratio");
    eprintln!("{name}: ism energy / reference {ratio:.3}");
    assert!((ratio - 1.0).abs() < 0.1, "{name}: ism energy off by 10% or more: {ratio:.3}");
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames of a level"]
fn ism_energy_is_within_ten_percent_on_the_window_room() {
    energy_within_ten_percent("window");
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames of a level"]
fn ism_energy_is_within_ten_percent_on_the_cluttered_room() {
    energy_within_ten_percent("clutter");
}

#[test]
#[ignore = "heavy: 32 default-settings ism frames of a level"]
fn ism_energy_is_within_ten_percent_on_the_diorama() {
    energy_within_ten_percent("diorama");
}

/// Relative spread (standard deviation over mean) of the view's mean luminance over frames 2 to
/// `frames` of `ism` on suite scene `name` with `ism` settings and no temporal reuse (frame 1
/// is skipped: the view importance is the last frame's).
fn raw_spread(ctx: &bouncelab::render::GpuContext, name: &str, ism: IsmSettings, frames: usize) -> f64 {
    let mut project = suite::scene(name).expect("scene").load(Path::new(".")).expect("loads");
    project.render.mode = GiMode::Ism;
    project.render.ism = IsmSettings { base_confidence: 0.0, still_frames: 0, ..ism };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mut energies = Vec::new();
    for frame in 0..frames {
        r.render(&project.scene, &project.render, SIZE).expect("render");
        if frame > 0 {
            let img = HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") };
            energies.push(metrics::mean_luminance(&img));
        }
    }
    let n = energies.len() as f64;
    let mean = energies.iter().sum::<f64>() / n;
    let var = energies.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1.0);
    eprintln!("{name} {:?}: frame energies {energies:.4?}", project.render.ism.bounce_pick);
    var.sqrt() / mean
}

/// Seen from the unlit third room, each frame's light arrives through two doorways on a
/// handful of VPLs: one chain more or less in the room swings the frame by tens of percent.
/// Drawing each set at once (systematic resampling) with the view importance halves that swing.
#[test]
#[ignore = "heavy: 26 default-settings ism frames of the three-room level"]
fn resampled_bounces_with_view_importance_steady_the_unlit_room_from_frame_to_frame() {
    let Some(ctx) = common::gpu() else { return };
    let frames = 13;
    let per_chain =
        IsmSettings { bounce_pick: BouncePick::Proportional, view_importance: 0.0, ..IsmSettings::default() };
    let plain = raw_spread(&ctx, "rooms", per_chain, frames);
    let default = raw_spread(&ctx, "rooms", IsmSettings::default(), frames);
    eprintln!("relative spread of the frames' energy: per-chain pick {plain:.3}, default {default:.3}");
    // Measured at 128x72 over 20 frames: 0.379 and 0.164.
    assert!(default < 0.7 * plain, "spread {default:.3} with the default pick against {plain:.3} per chain");
}
