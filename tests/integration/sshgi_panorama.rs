//! `sshgi`'s panorama (the surfaces around the camera that the view does not show, from a
//! low-resolution cube G-buffer) on the suite's window room, whose spot lights the wall behind
//! the camera, as the quality matrix renders it (256x144, box-filtered to the cached reference's
//! 128x72): the mean of frames 17-24 within 15% of the path tracer's energy where the screen
//! alone reads under 0.65 of it (0.599), FLIP well below the screen's alone, and every settled
//! frame within 3% of their mean (the cube turns each frame, and the temporal filter averages
//! its samples).

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::render::Renderer;
use bouncelab::settings::{GiMode, RenderSettings, SshgiSettings};
use bouncelab::suite;
use std::path::Path;

/// Frames rendered, and the first judged (the history has settled).
const FRAMES: usize = 24;
const SETTLED: usize = 16;

/// Each frame from `SETTLED` on, box-filtered to the reference's pixels.
fn frames(ctx: &bouncelab::render::GpuContext, sshgi: SshgiSettings) -> Vec<HdrImage> {
    let project = suite::scene("window").expect("suite scene").load(Path::new(".")).expect("window");
    let settings = RenderSettings { mode: GiMode::Sshgi, sshgi, ..project.render.clone() };
    let (w, h) = suite::REFERENCE_SIZE;
    let big = (2 * w, 2 * h);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    (0..FRAMES)
        .filter_map(|i| {
            r.render(&project.scene, &settings, big).expect("render");
            let pixels = r.read_hdr().expect("hdr");
            (i >= SETTLED).then(|| HdrImage {
                width: w,
                height: h,
                pixels: bouncelab::image_io::box_downsample(&pixels, big, 2),
            })
        })
        .collect()
}

fn mean(frames: &[HdrImage]) -> HdrImage {
    let n = frames.len() as f32;
    let mut pixels = vec![[0.0f32; 4]; frames[0].pixels.len()];
    for f in frames {
        for (s, p) in pixels.iter_mut().zip(&f.pixels) {
            (0..4).for_each(|c| s[c] += p[c] / n);
        }
    }
    HdrImage { width: frames[0].width, height: frames[0].height, pixels }
}

#[test]
fn the_panorama_brings_the_window_rooms_light_from_behind_the_camera_steadily() {
    let Some(ctx) = common::gpu() else { return };
    let reference = suite::scene("window").expect("suite scene").reference(Path::new(".")).expect("cached reference");
    let ev = metrics::judging_exposure(&reference);
    let screen = mean(&frames(&ctx, SshgiSettings { panorama: 0, ..SshgiSettings::default() }));
    let with = frames(&ctx, SshgiSettings::default());
    let panorama = mean(&with);
    let energy = |img: &HdrImage| metrics::luminance_ratio(img, &reference).expect("ratio");
    let flip = |img: &HdrImage| metrics::flip(img, &reference, ev).expect("flip").0;
    let (e_screen, e_panorama) = (energy(&screen), energy(&panorama));
    let (f_screen, f_panorama) = (flip(&screen), flip(&panorama));
    let per_frame: Vec<f64> = with.iter().map(energy).collect();
    let spread = per_frame.iter().map(|e| (e / e_panorama - 1.0).abs()).fold(0.0f64, f64::max);
    eprintln!(
        "window room: screen alone energy {e_screen:.3} FLIP {f_screen:.4}; with the panorama {e_panorama:.3} FLIP \
         {f_panorama:.4}; frames {per_frame:.3?}"
    );
    assert!(e_screen < 0.65, "the screen alone misses the light from behind the camera: {e_screen:.3}");
    assert!((0.85..=1.15).contains(&e_panorama), "with the panorama {e_panorama:.3} of the reference");
    assert!(f_panorama < 0.7 * f_screen, "FLIP {f_panorama:.4} against the screen's {f_screen:.4}");
    assert!(spread <= 0.03, "a settled frame strays {:.1}% from their mean", 100.0 * spread);
}
