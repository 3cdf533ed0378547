//! `bouncelab bench` rows for `rcs` (radiance cache splatting): per accuracy a, the time to the
//! first fully covered frame and to converged bounce passes, the warm-cache frame as a ratio to
//! `direct`, the record counts, and the error against the reference path tracer with and
//! without gradients; then what a small camera move and a light move cost a warm cache.

use std::fmt::Write as _;
use std::time::Instant;

use glam::Vec3;

use crate::image_io::HdrImage;
use crate::metrics;
use crate::project_file::Project;
use crate::render::harness::median;
use crate::render::{GpuContext, Renderer};
use crate::settings::{GiMode, RcsSettings, RenderSettings};

/// Most frames a fill may take.
const FILL_LIMIT: usize = 400;

/// What filling and warming one cache measured.
struct Fill {
    first_full_ms: f64,
    first_full_frames: usize,
    converged_ms: f64,
    converged_frames: usize,
    warm_ms: f64,
    warm_gpu_ms: f64,
    passes: String,
}

fn counter(r: &Renderer, name: &str) -> u64 {
    r.technique_status().map_or(0, |s| s.counter(name))
}

/// Renders until the cache is converged, then eight warm frames.
fn fill(
    ctx: &GpuContext,
    r: &mut Renderer,
    project: &Project,
    settings: &RenderSettings,
    size: (u32, u32),
) -> anyhow::Result<Fill> {
    let start = Instant::now();
    let mut first_full = None;
    let mut frames = 0;
    while frames < FILL_LIMIT {
        r.render(&project.scene, settings, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        frames += 1;
        if first_full.is_none() && counter(r, "uncovered tiles") == 0 {
            first_full = Some((start.elapsed().as_secs_f64() * 1e3, frames));
        }
        if !r.technique_status().is_some_and(|s| s.refining) {
            break;
        }
    }
    let converged = (start.elapsed().as_secs_f64() * 1e3, frames);
    let (mut times, mut gpu) = (Vec::new(), Vec::new());
    let mut passes = String::new();
    for f in 0..8 {
        let t = Instant::now();
        r.render(&project.scene, settings, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        times.push(t.elapsed().as_secs_f64() * 1e3);
        let timings = r.timings(true);
        gpu.push(timings.iter().filter(|p| p.name.starts_with("rcs")).map(|p| p.ms).sum::<f64>());
        if f == 7 {
            passes = timings
                .iter()
                .filter(|p| p.name.starts_with("rcs"))
                .map(|p| format!("{} {:.2}", p.name.trim_start_matches("rcs "), p.ms))
                .collect::<Vec<_>>()
                .join(", ");
        }
    }
    let first_full = first_full.unwrap_or(converged);
    Ok(Fill {
        first_full_ms: first_full.0,
        first_full_frames: first_full.1,
        converged_ms: converged.0,
        converged_frames: converged.1,
        warm_ms: median(times),
        warm_gpu_ms: median(gpu),
        passes,
    })
}

/// FLIP and energy of the renderer's last image.
fn error(r: &Renderer, size: (u32, u32), reference: &HdrImage) -> anyhow::Result<(f64, f64)> {
    let img = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr()? };
    let ev = super::quality::exposure(reference);
    let c = metrics::compare(&img, reference, ev)?;
    Ok((c.flip, c.luminance_ratio))
}

/// Appends the rcs section to `md`.
pub fn rcs_rows(md: &mut String, ctx: &GpuContext, project: &Project, quick: bool) -> anyhow::Result<()> {
    let size = if quick { (320, 180) } else { (640, 360) };
    let (reference, spp) = super::bench::traced_reference(project, size, quick);
    let direct_settings = RenderSettings { mode: GiMode::Direct, ..project.render.clone() };
    let mut d = Renderer::new(&ctx.device, &ctx.queue)?;
    let mut times = Vec::new();
    for _ in 0..9 {
        let t = Instant::now();
        d.render(&project.scene, &direct_settings, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let direct_ms = median(times[1..].to_vec());
    let (direct_flip, _) = error(&d, size, &reference)?;
    let defaults = RcsSettings::default();
    let _ = writeln!(md, "\n## Radiance cache splatting (Gautron et al.)\n");
    let _ = writeln!(
        md,
        "Default project (Cornell box, point light), {}x{}; `direct` {direct_ms:.1} ms a frame (FLIP {direct_flip:.4}). \
         Times are wall clock from an empty cache: to the first frame with every pixel covered, and to converged \
         bounce passes (each frame computes at most {} records in at most {} rounds); the warm frame reuses the \
         converged cache (median of 8; rcs GPU ms is the sum of its passes' timestamps). Error against the reference \
         path tracer ({spp} spp, full GI) at the exposure that puts its mean at 0.18, with gradients and without \
         (the same cache). Other settings at their defaults ({}x{} planes, at most {} bounces).\n",
        size.0,
        size.1,
        defaults.records_per_frame,
        defaults.rounds,
        defaults.hemisphere_resolution,
        defaults.hemisphere_resolution,
        defaults.bounces
    );
    let _ = writeln!(
        md,
        "| a | records (secondary) | first full frame ms (frames) / direct | converged ms (frames, passes) | warm frame / direct | rcs GPU ms | FLIP | FLIP without gradients | energy | warm passes (GPU ms) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|");
    let accuracies: &[f32] = if quick { &[0.25] } else { &[0.5, 0.25, 0.125] };
    for &accuracy in accuracies {
        let rcs = RcsSettings { accuracy, ..defaults.clone() };
        let settings = RenderSettings { mode: GiMode::Rcs, rcs: rcs.clone(), ..project.render.clone() };
        let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
        let f = fill(ctx, &mut r, project, &settings, size)?;
        let (flip, energy) = error(&r, size, &reference)?;
        let flat = RenderSettings { rcs: RcsSettings { gradients: false, ..rcs }, ..settings.clone() };
        r.render(&project.scene, &flat, size)?;
        let (flip_flat, _) = error(&r, size, &reference)?;
        let _ = writeln!(
            md,
            "| {accuracy} | {} ({}) | {:.0} ({}) / {:.0} | {:.0} ({}, {}) | {:.2} | {:.2} | {flip:.4} | {flip_flat:.4} | {energy:.3} | {} |",
            counter(&r, "records"),
            counter(&r, "secondary records"),
            f.first_full_ms,
            f.first_full_frames,
            f.first_full_ms / direct_ms,
            f.converged_ms,
            f.converged_frames,
            counter(&r, "bounce passes"),
            f.warm_ms / direct_ms,
            f.warm_gpu_ms,
            f.passes
        );
    }
    // A warm cache under edits: a small camera move, then a light move.
    let settings = RenderSettings { mode: GiMode::Rcs, ..project.render.clone() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    fill(ctx, &mut r, project, &settings, size)?;
    let live = counter(&r, "records");
    let mut moved = project.clone();
    let mut camera = *moved.scene.camera();
    camera.position += Vec3::new(0.1, 0.05, 0.0);
    moved.scene.set_camera(camera);
    // The first frame after the move finds the uncovered pixels, the second makes their records.
    let t = Instant::now();
    let mut made = 0;
    for _ in 0..2 {
        r.render(&moved.scene, &settings, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        made += counter(&r, "records made last frame");
    }
    let move_ms = t.elapsed().as_secs_f64() * 1e3;
    let mut lit = moved.clone();
    if let Some(light) = lit.scene.desc_mut().lights.first_mut() {
        light.position += Vec3::new(0.3, 0.0, 0.0);
    }
    let renewed_before = counter(&r, "records renewed");
    let f = fill(ctx, &mut r, &lit, &settings, size)?;
    let _ = writeln!(
        md,
        "\nWarm cache of {live} records (a = {}): a 10 cm camera move made {made} records in the two frames after it, {move_ms:.0} ms together \
         ({:.2} of `direct`), the rest reused. Moving the light 30 cm: the light check renewed {} records \
         (then {} renewals in all before the passes settled again) in {:.0} ms ({} frames).",
        defaults.accuracy,
        move_ms / direct_ms,
        counter(&r, "light check renewals"),
        counter(&r, "records renewed") - renewed_before,
        f.converged_ms,
        f.converged_frames
    );
    Ok(())
}
