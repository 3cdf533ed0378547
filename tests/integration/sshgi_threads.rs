//! `sshgi`'s passes that spread a texel's (or sender's) samples over the threads of a workgroup
//! on a GPU (the screen's gathers at every level, the panorama's gather and receive, the sky's
//! rays: `passes::steps::split`) compute what one thread per texel computes. The tests run on a
//! software adapter, which keeps a thread per texel, so this renders the suite's sky-lit room
//! (every shared pass: panorama, hidden senders, sky, visibility) both ways and compares. With
//! the senders picked uniformly only the order of the sums differs; with part of them picked by
//! power (the default) a later bounce's prefix sums carry that rounding too, and a pick whose
//! sample falls on a boundary the rounding moved takes the neighbouring sender.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::render::gi::sshgi::passes::share_samples_as_on_a_gpu;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, RenderSettings, SshgiSettings};
use bouncelab::suite;
use std::path::Path;

/// Three frames of the sky-lit room at 128x72 (a 32x18 start level, 4x2 on level 3), with
/// `sender_power_share` of the senders picked by power.
fn frames(ctx: &GpuContext, sender_power_share: f32) -> HdrImage {
    let project = suite::scene("skylight").expect("suite scene").load(Path::new(".")).expect("skylight");
    let sshgi = SshgiSettings { sender_power_share, ..project.render.sshgi.clone() };
    let settings = RenderSettings { mode: GiMode::Sshgi, sshgi, ..project.render.clone() };
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
    let compare = |share: f32| {
        share_samples_as_on_a_gpu(false);
        let one = frames(&ctx, share);
        share_samples_as_on_a_gpu(true);
        let shared = frames(&ctx, share);
        share_samples_as_on_a_gpu(false);
        (metrics::luminance_ratio(&shared, &one).expect("ratio"), metrics::relmse(&shared, &one, 1e-4).expect("relmse"))
    };
    // Uniform picks: only the order of the sums differs.
    let (ratio, relmse) = compare(0.0);
    assert!((ratio - 1.0).abs() < 1e-5 && relmse < 1e-8, "shared / one thread: energy {ratio}, relMSE {relmse}");
    // Half by power: a few picks on a moved boundary take their neighbour.
    let (ratio, relmse) = compare(0.5);
    eprintln!("picked half by power, shared / one thread: energy {ratio}, relMSE {relmse}");
    assert!((ratio - 1.0).abs() < 1e-3 && relmse < 1e-4, "shared / one thread: energy {ratio}, relMSE {relmse}");
}
