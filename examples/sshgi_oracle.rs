//! An oracle for `sshgi`'s first bounce: the exact screen-space gather it approximates. Renders a
//! suite scene in `sshgi` with one bounce (256x144, the given settings, no temporal filter), reads
//! the start level's voted points and normals and its outgoing radiance, and sums on the CPU, for
//! every start-level texel, every other texel's light with the same bounded form factor (Eq. 4
//! with one texel's area, Eq. 2) and exact visibility by ray casting the scene's triangles. The
//! gap between that sum and sshgi's first bounce is what the hierarchy, its sampling and the
//! voxel visibility lose; the gap between the sum and the one-bounce reference is what screen
//! space itself loses (off-screen and hidden senders).
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

use bouncelab::image_io::HdrImage;
use bouncelab::precompute::bvh::SceneBvh;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, SshgiSettings};
use bouncelab::suite;
use glam::Vec3;
use rayon::prelude::*;

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

fn oct_decode(e: [f32; 2]) -> Vec3 {
    let mut n = Vec3::new(e[0], e[1], 1.0 - e[0].abs() - e[1].abs());
    let t = (-n.z).clamp(0.0, 1.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize_or_zero()
}

fn mean_rgb(img: &HdrImage) -> f64 {
    img.pixels.iter().map(|p| f64::from(p[0] + p[1] + p[2]) / 3.0).sum::<f64>() / img.pixels.len().max(1) as f64
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
    let start = settings.start_level as usize;
    let levels = settings.levels as usize;
    let mut bounce: Option<HdrImage> = None;
    let mut gathers = vec![0.0f64; levels];
    // Per level below the coarsest: the up-sampled sum of the levels above it, minus its gather.
    let mut carried = vec![0.0f64; levels];
    for _ in 0..frames {
        r.render(&project.scene, &project.render, view_size)?;
        let b = r.read_buffer("sshgi_bounce_1")?;
        match &mut bounce {
            Some(sum) => sum.pixels.iter_mut().zip(&b.pixels).for_each(|(s, p)| (0..4).for_each(|c| s[c] += p[c])),
            None => bounce = Some(b),
        }
        for (k, g) in gathers.iter_mut().enumerate() {
            if levels > 1 {
                *g += mean_rgb(&r.read_buffer(&format!("sshgi_gather_{k}"))?) / frames as f64;
            }
        }
        for (k, c) in carried.iter_mut().enumerate().take(levels.saturating_sub(1)) {
            let sum = if k == 0 { "sshgi_bounce_1".to_owned() } else { format!("sshgi_sum_{k}") };
            let gather = mean_rgb(&r.read_buffer(&format!("sshgi_gather_{k}"))?);
            *c += (mean_rgb(&r.read_buffer(&sum)?) - gather) / frames as f64;
        }
    }
    let mut bounce = bounce.ok_or_else(|| anyhow::anyhow!("no frames"))?;
    bounce.pixels.iter_mut().for_each(|p| p.iter_mut().for_each(|v| *v /= frames as f32));
    let geo = r.read_buffer(&format!("pyramid_{start}"))?;
    let light = r.read_buffer("sshgi_illumination_0")?;
    let (w, h) = (geo.width as usize, geo.height as usize);
    let camera = *project.scene.camera();
    let forward = camera.forward();
    let tan_y = (camera.yfov * 0.5).tan();
    let tan_x = tan_y * view_size.0 as f32 / view_size.1 as f32;
    let texel_sr = 4.0 * tan_x * tan_y / (view_size.0 * view_size.1) as f32 * (1u32 << (2 * start)) as f32;
    // Each texel's point, normal and radiance (None: background).
    let texels: Vec<Option<(Vec3, Vec3, Vec3, f32)>> = geo
        .pixels
        .iter()
        .zip(&light.pixels)
        .map(|(g, l)| {
            (g[3] >= 0.5).then(|| {
                let index = (g[3] - 0.5) as u32;
                let (px, py) = ((index % view_size.0) as f32 + 0.5, (index / view_size.0) as f32 + 0.5);
                let dir = camera.ray_direction(px, py, view_size.0, view_size.1);
                let cos_a = dir.dot(forward).max(0.0);
                let n = oct_decode([g[1], g[2]]);
                let cos_b = n.dot(-dir).max(0.05);
                let ds = texel_sr * cos_a.powi(3) * g[0] * g[0] / cos_b;
                (camera.position + dir * g[0], n, Vec3::new(l[0], l[1], l[2]), ds)
            })
        })
        .collect();
    let radius = settings.ring_radius((w as u32, h as u32), settings.levels);
    let bucket =
        |d: f32| -> usize { if d < radius { 0 } else { ((d / radius).log2().floor() as usize + 1).min(levels) } };
    let bvh = SceneBvh::build(&project.scene);
    let eps = 1e-3 * bvh.scale;
    // Per texel: E / pi by bucket, with and without visibility.
    let sums: Vec<(Vec<f64>, Vec<f64>)> = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (mut vis, mut open) = (vec![0.0f64; levels + 1], vec![0.0f64; levels + 1]);
            let Some((x, nx, _, _)) = texels[i] else { return (vis, open) };
            for (j, t) in texels.iter().enumerate() {
                let Some((y, ny, l, ds)) = *t else { continue };
                if i == j {
                    continue;
                }
                let v = y - x;
                let d2 = v.length_squared();
                if d2 < 1e-10 {
                    continue;
                }
                let vh = v / d2.sqrt();
                let (cos_r, cos_s) = (nx.dot(vh), ny.dot(-vh));
                if cos_r <= 0.0 || cos_s <= 0.0 {
                    continue;
                }
                let r2 = cos_s * ds / std::f32::consts::PI;
                let e = f64::from((l.x + l.y + l.z) / 3.0 * r2 * cos_r / (d2 + r2));
                let (dx, dy) = ((i % w) as f32 - (j % w) as f32, (i / w) as f32 - (j / w) as f32);
                let k = bucket((dx * dx + dy * dy).sqrt());
                open[k] += e;
                let o = x + nx * eps;
                let to = y + ny * eps - o;
                if !bvh.occluded(o, to.normalize(), to.length() * 0.999) {
                    vis[k] += e;
                }
            }
            (vis, open)
        })
        .collect();
    let n = (w * h) as f64;
    let (vis, open): (Vec<f64>, Vec<f64>) = (0..=levels)
        .map(|k| (sums.iter().map(|s| s.0[k]).sum::<f64>() / n, sums.iter().map(|s| s.1[k]).sum::<f64>() / n))
        .unzip();
    let (sv, so): (f64, f64) = (vis.iter().sum(), open.iter().sum());
    let ss = mean_rgb(&bounce);
    println!("{name}: start level {w}x{h}, r = {radius} texels, {frames} frames");
    println!(
        "  sshgi first bounce {ss:.5}; oracle visible {sv:.5} ({:.3}), unoccluded {so:.5} ({:.3})",
        ss / sv,
        ss / so
    );
    for k in 0..=levels {
        let g = gathers.get(k).map_or(String::from("-"), |g| format!("{g:.5}"));
        let g = match carried.get(k) {
            Some(c) if k + 1 < levels => format!("{g}, levels above up-sampled onto it {c:.5}"),
            _ => g,
        };
        println!("  level {k}: oracle visible {:.5} unoccluded {:.5}; sshgi gather {g}", vis[k], open[k]);
    }
    Ok(())
}
