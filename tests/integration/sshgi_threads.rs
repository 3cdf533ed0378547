//! `sshgi`'s passes that spread a texel's (or sender's) samples over the threads of a workgroup
//! on a GPU (the screen's gathers at every level, the panorama's gather and receive, the sky's
//! rays: `passes::steps::split`) compute what one thread per texel computes. The tests run on a
//! software adapter, which keeps a thread per texel, so this renders the suite's sky-lit room
//! (every shared pass: panorama, hidden senders, sky, visibility) both ways and compares.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::render::gi::sshgi::passes::share_samples_as_on_a_gpu;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, RenderSettings};
use bouncelab::suite;
use std::path::Path;

/// Three frames of the sky-lit room at 128x72 (a 32x18 start level, 4x2 on level 3).
fn frames(ctx: &GpuContext) -> HdrImage {
    let project = suite::scene("skylight").expect("suite scene").load(Path::new(".")).expect("skylight");
    let settings = RenderSettings { mode: GiMode::Sshgi, ..project.render.clone() };
    let size = (128, 72);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for _ in 0..3 {
        r.render(&project.scene, &settings, size).expect("render");
    }
    HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") }
}

#[test]
fn samples_shared_over_threads_as_on_a_gpu_give_the_one_thread_image() {
    if !common::has_gpu() {
        return;
    }
    let ctx = GpuContext::new_headless().expect("gpu");
    share_samples_as_on_a_gpu(false);
    let one = frames(&ctx);
    share_samples_as_on_a_gpu(true);
    let shared = frames(&ctx);
    share_samples_as_on_a_gpu(false);
    let (ratio, relmse) = (
        metrics::luminance_ratio(&shared, &one).expect("ratio"),
        metrics::relmse(&shared, &one, 1e-4).expect("relmse"),
    );
    // Only the order of the sums differs.
    assert!((ratio - 1.0).abs() < 1e-5 && relmse < 1e-8, "shared / one thread: energy {ratio}, relMSE {relmse}");
}
