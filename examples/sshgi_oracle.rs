//! An oracle for `sshgi`'s first bounce: the exact screen-space gather it approximates. Renders a
//! suite scene in `sshgi` with one bounce (256x144, the given settings, no temporal filter), reads
//! the start level's voted points and normals and its outgoing radiance, and sums on the CPU, for
//! every start-level texel, every other texel's light with the same bounded form factor (Eq. 4
//! with one texel's area, Eq. 2) and exact visibility by ray casting the scene's triangles. The
//! gap between that sum and sshgi's first bounce is what the hierarchy, its sampling and the
//! voxel visibility lose; the gap between the sum and the one-bounce reference is what screen
//! space itself loses (off-screen and hidden senders).
//!
//! The oracle itself is `bouncelab::render::gi::sshgi::oracle` (a heavy test holds the user
//! guide's claim to it); this example prints it with other settings or views.
//!
//! `cargo run --release --example sshgi_oracle -- cornell --settings "()" --frames 16`
//!
//! `--view 128x72` renders at another size; `--time 640x360` only times the settings (all
//! bounces, median of the sshgi passes' GPU times over 12 frames) and prints each pass.
//!
//! Prints the means of E / pi over the start level: sshgi (mean of the frames), the oracle with
//! ray-cast visibility and without visibility, and both split by the screen distance each
//! level's ring covers (level 0: the disc of r texels; level k: r 2^(k-1)..r 2^k), next to the
//! mean of each level's gather.

use std::path::Path;

use bouncelab::render::gi::sshgi::oracle;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, SshgiSettings};
use bouncelab::suite;

/// The exact screen-space gather that `sshgi`'s first bounce approximates.
#[derive(clap::Parser)]
struct Args {
    /// Suite scene.
    #[arg(default_value = "cornell")]
    scene: String,
    /// sshgi settings (RON); fields left out keep their defaults.
    #[arg(long, default_value = "()")]
    settings: String,
    /// Frames averaged.
    #[arg(long, default_value_t = 16)]
    frames: usize,
    /// The view size, WxH.
    #[arg(long, default_value = "256x144", value_parser = parse_size)]
    view: (u32, u32),
    /// Only time the settings at WxH (all bounces, temporal as set): the median of the sshgi
    /// passes' GPU times over 12 frames, and each pass.
    #[arg(long, value_parser = parse_size)]
    time: Option<(u32, u32)>,
}

/// `WxH` as a size.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    text.split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .filter(|(w, h)| *w > 0 && *h > 0)
        .ok_or_else(|| format!("{text:?} is not a size WxH"))
}

fn main() -> anyhow::Result<()> {
    let args = <Args as clap::Parser>::parse();
    let name = args.scene.as_str();
    let mut settings: SshgiSettings = ron::from_str(&args.settings)?;
    let frames = args.frames;
    settings.bounces = 1;
    settings.temporal_weight = 0.0;
    let ctx = GpuContext::new_headless()?;
    let view_size = args.view;
    let mut project = suite::scene(name)?.load(Path::new("."))?;
    project.render.mode = GiMode::Sshgi;
    project.render.sshgi = settings.clone();
    if let Some(size) = args.time {
        // Times the given settings (all bounces, temporal as set) at WxH: median of 8 frames.
        project.render.sshgi = ron::from_str(&args.settings)?;
        let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
        let mut gpu = Vec::new();
        for _ in 0..12 {
            r.render(&project.scene, &project.render, size)?;
            let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
            let t = r.timings(true);
            gpu.push(t.iter().filter(|p| p.name.starts_with("sshgi")).map(|p| p.ms).sum::<f64>());
            if gpu.len() == 12 {
                let passes: Vec<String> = t.iter().map(|p| format!("{} {:.1}", p.name, p.ms)).collect();
                println!("{}", passes.join(", "));
            }
        }
        gpu.sort_by(f64::total_cmp);
        println!("sshgi GPU ms median {:.1}", gpu[6]);
        return Ok(());
    }
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    let report = oracle::first_bounce(&mut r, &project, &settings, view_size, frames)?;
    let (w, h) = report.start;
    let (ss, sv, so) = (report.sshgi, report.visible, report.unoccluded);
    println!("{name}: start level {w}x{h}, r = {} texels, {frames} frames", report.radius);
    println!(
        "  sshgi first bounce {ss:.5}; oracle visible {sv:.5} ({:.3}), unoccluded {so:.5} ({:.3})",
        ss / sv,
        ss / so
    );
    for (k, (vis, open)) in report.per_level.iter().enumerate() {
        let g = report.gathers.get(k).map_or(String::from("-"), |g| format!("{g:.5}"));
        let g = match report.carried.get(k) {
            Some(c) if k + 1 < report.gathers.len() => format!("{g}, levels above up-sampled onto it {c:.5}"),
            _ => g,
        };
        println!("  level {k}: oracle visible {vis:.5} unoccluded {open:.5}; sshgi gather {g}");
    }
    Ok(())
}
