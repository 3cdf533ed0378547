//! `bouncelab render`: headless rendering of a project or glTF file to EXR or PNG, with the
//! rasteriser (`direct`, GI modes) or the CPU reference path tracer (`reference`).

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use crate::image_io::{self, HdrImage, OutputKind};
use crate::output_path;
use crate::precompute::pathtracer::PathTracer;
use crate::project_file::Project;
use crate::render::gi::registry;
use crate::render::harness;
use crate::render::{GpuContext, Renderer};
use crate::settings::{GiMode, Tonemap, ViewSettings};

/// Options of one headless render (also the `render` subcommand's arguments).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct RenderArgs {
    /// Project (.ron) or scene (.gltf/.glb).
    pub input: PathBuf,
    /// GI mode (default: the project's).
    #[arg(long, value_parser = parse_mode)]
    pub mode: Option<GiMode>,
    /// Output file (.exr or .png).
    #[arg(long)]
    pub out: PathBuf,
    /// Width in pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Height in pixels.
    #[arg(long, default_value_t = 360)]
    pub height: u32,
    /// Frames to render; the last one is written. Without it, temporal and progressive modes
    /// (ism, sshgi, mrt, rcs) render until their history has converged, as the editor's
    /// "refining" shows (at most 2000 frames); with it, that many frames are rendered (rcs
    /// still fills its cache first) and a note says when the image had not converged yet.
    #[arg(long)]
    pub frames: Option<u32>,
    /// Write the image even when it is not what was asked for (a technique could not do its
    /// work, the scene has no light, the mode does not light with its sky or emission): the problems
    /// are still printed. Without it, such a render writes nothing and exits non-zero.
    #[arg(long)]
    pub allow_partial: bool,
    /// Exposure in stops for the PNG view (`--exposure -1.5` darkens).
    #[arg(long, allow_negative_numbers = true)]
    pub exposure: Option<f32>,
    /// Samples per pixel (reference mode).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Longest path in bounces, 1 = direct light only (reference mode).
    #[arg(long)]
    pub max_bounces: Option<u32>,
    /// Random seed (reference mode).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Bounce from which Russian roulette may end paths (reference mode).
    #[arg(long)]
    pub rr_start: Option<u32>,
    /// Path guiding, true or false (reference mode; unbiased either way; off by default).
    #[arg(long)]
    pub guiding: Option<bool>,
    /// Write an intermediate buffer instead of the final image: albedo, normal, material,
    /// motion, object_id, depth, direct, exitance, indirect, hdr, ldr, shadow_map, pyramid_0..7,
    /// and the mode's own (ISM: ism_light_*, ism_importance, ism_atlas(_splats), ism_split_*, ism_raw,
    /// ism_upsampled, ism_confidence, ism_history, ism_sh_*; sshgi: sshgi_illumination_k, sshgi_gather_k,
    /// sshgi_sum_k, sshgi_bounce_b, sshgi_screen_bounce, sshgi_bounce_sum, sshgi_raw, sshgi_visibility_difference,
    /// sshgi_acceptance, sshgi_voxels(_start), sshgi_voxel_slices@level,first,last); an unknown
    /// name lists the mode's buffers.
    #[arg(long)]
    pub buffer: Option<String>,
    /// Supersampling per axis for raster modes: renders at N times the size and box-filters
    /// down, as a path tracer's pixel filter does (1 = one sample at each pixel centre).
    #[arg(long, default_value_t = 3)]
    pub ssaa: u32,
    #[command(flatten)]
    pub units: super::SceneArgs,
}

/// Renders and writes the output file; returns a one-line summary.
pub fn run(args: &RenderArgs) -> anyhow::Result<String> {
    let kind = image_io::output_kind(&args.out)?;
    let (project, size) = checked_project(args)?;
    // A scene with no light is not what a render asks for
    // (buffers such as albedo or normal do not need light).
    let scene_shortfalls = if args.buffer.is_some() { Vec::new() } else { project.shortfalls() };
    if project.render.mode == GiMode::Reference {
        if args.buffer.is_some() {
            anyhow::bail!("--buffer is for raster modes; the reference mode has no intermediate buffers");
        }
        super::budget::check_reference(size)?;
        refuse_partial(&args.out, &scene_shortfalls, args.allow_partial)?;
        return reference(&project, &args.out, kind, size);
    }
    let (ctx, mut renderer, render_size) = raster_renderer(args, size)?;
    let frames = render_frames(&ctx, &mut renderer, &project, render_size, args.frames)?;
    report_notes(args, &project, &renderer, frames);
    let mut shortfalls = renderer.shortfalls(&project.scene, &project.render);
    shortfalls.extend(scene_shortfalls);
    // A buffer is inspected to find out what went wrong: it is written whatever it holds.
    refuse_partial(&args.out, &shortfalls, args.allow_partial || args.buffer.is_some())?;
    let img = match &args.buffer {
        Some(name) => renderer.read_buffer(name)?,
        None => HdrImage {
            width: size.0,
            height: size.1,
            pixels: image_io::box_downsample(&renderer.read_hdr()?, render_size, render_size.0 / size.0),
        },
    };
    write_checked(args, &project, &renderer, kind, &img)?;
    Ok(format!(
        "{} ({}x{}, mode {}, {})",
        args.out.display(),
        img.width,
        img.height,
        project.render.mode.name(),
        ctx.describe()
    ))
}

/// Everything about the command line checked before a long render starts: frames, supersampling,
/// the output against every input, the overrides applied to the project and validated, the
/// size, the buffer's name. Returns the project and the output size.
fn checked_project(args: &RenderArgs) -> anyhow::Result<(Project, (u32, u32))> {
    if args.frames == Some(0) {
        anyhow::bail!("--frames 0: at least one frame is rendered (the last one is written)");
    }
    if !(1..=8).contains(&args.ssaa) {
        anyhow::bail!("--ssaa {} is outside 1..=8 (samples per axis)", args.ssaa);
    }
    output_path::check(&args.out, output_path::IMAGE, &[&args.input])?;
    let mut project = args.units.open(&args.input)?;
    let inputs = project.files();
    output_path::check(&args.out, output_path::IMAGE, &inputs.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    let r = &mut project.render;
    if let Some(mode) = args.mode {
        r.mode = mode;
    }
    if let Some(ev) = args.exposure {
        r.view.exposure_ev = ev;
    }
    r.reference.spp = args.spp.unwrap_or(r.reference.spp);
    r.reference.max_bounces = args.max_bounces.unwrap_or(r.reference.max_bounces);
    r.reference.seed = args.seed.unwrap_or(r.reference.seed);
    r.reference.rr_start = args.rr_start.unwrap_or(r.reference.rr_start);
    r.reference.guiding = args.guiding.unwrap_or(r.reference.guiding);
    r.validate()?;
    let size = (args.width, args.height);
    if size.0 == 0 || size.1 == 0 || size.0 > 16384 || size.1 > 16384 {
        anyhow::bail!("image size {}x{} is outside 1..=16384 pixels per side", size.0, size.1);
    }
    if let Some(name) = &args.buffer {
        let names: Vec<&str> = Renderer::buffers_for(project.render.mode).iter().map(|b| b.name).collect();
        if !names.contains(&crate::render::gi::technique::split_buffer_name(name).0) {
            anyhow::bail!(
                "unknown buffer {name:?} for mode {}; available: {}",
                project.render.mode.name(),
                names.join(", ")
            );
        }
    }
    Ok((project, size))
}

/// The device and renderer for a raster render of `size`, with the render size (supersampled,
/// except for an inspected buffer, which is read at its own resolution) checked against the
/// memory budget and the adapter's limits.
fn raster_renderer(args: &RenderArgs, size: (u32, u32)) -> anyhow::Result<(GpuContext, Renderer, (u32, u32))> {
    let k = if args.buffer.is_some() { 1 } else { args.ssaa };
    let render_size = (size.0 * k, size.1 * k);
    let ctx = GpuContext::new_headless()?;
    ctx.log_errors();
    log::info!("rendering {} with {}", args.input.display(), ctx.describe());
    super::budget::check_raster(&ctx, render_size)?;
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    renderer.set_inspected(args.buffer.as_deref());
    let max = ctx.device.limits().max_texture_dimension_2d;
    if render_size.0 > max || render_size.1 > max {
        anyhow::bail!(
            "{}x{} with --ssaa {k} renders at {}x{}, over this adapter's {max} pixels per side: lower --ssaa or the size",
            size.0,
            size.1,
            render_size.0,
            render_size.1
        );
    }
    Ok((ctx, renderer, render_size))
}

/// Says what the technique leaves out (a light type, a feature), so nobody mistakes it for
/// error, and whether it had converged when the image was taken.
fn report_notes(args: &RenderArgs, project: &Project, renderer: &Renderer, frames: u32) {
    for note in renderer.limitations(&project.scene, &project.render) {
        eprintln!("note: {} {note}", project.render.mode.name());
    }
    if let (Some(asked), Some(status)) = (args.frames, renderer.technique_status())
        && status.refining
    {
        eprintln!(
            "note: {} had not converged after the {asked} frames asked for ({} of {} frames of history): the image holds only part of its light; without --frames the render converges first",
            project.render.mode.name(),
            status.history_frames,
            status.refine_target
        );
    }
    if args.frames.is_none() && renderer.technique_status().is_some_and(|s| s.refining) {
        eprintln!(
            "note: {} still refining after {frames} frames, the most a render gives a technique",
            project.render.mode.name()
        );
    }
}

/// Writes `img` unless it holds a non-finite pixel (then names the first pass of the frame whose
/// output already holds one). PNGs of buffers show raw values (clamped); the final image uses
/// the project's view.
fn write_checked(
    args: &RenderArgs,
    project: &Project,
    renderer: &Renderer,
    kind: OutputKind,
    img: &HdrImage,
) -> anyhow::Result<()> {
    let view = if args.buffer.is_some() {
        ViewSettings { exposure_ev: 0.0, tonemap: Tonemap::Clamp }
    } else {
        project.render.view.clone()
    };
    if let Some((x, y)) = image_io::first_non_finite(img) {
        let pass = ["direct", "indirect", "hdr"]
            .into_iter()
            .find(|b| renderer.read_buffer(b).is_ok_and(|i| image_io::first_non_finite(&i).is_some()))
            .unwrap_or("hdr");
        anyhow::bail!(
            "{}: not written: pixel ({x}, {y}) is NaN or infinite; the `{pass}` buffer of mode {} is the first that holds such values (`--buffer {pass}` shows it)",
            args.out.display(),
            project.render.mode.name()
        );
    }
    image_io::write_image(&args.out, kind, img, &view)?;
    Ok(())
}

/// Most frames `render` gives a technique to converge (and `rcs` to fill its cache).
const CONVERGE_LIMIT: u32 = 2000;

/// Renders `asked` frames, or until the technique stops refining when `None` (at most
/// [`CONVERGE_LIMIT`]); `rcs` always fills and converges its cache (a budget of records per
/// frame), so its written frame is the converged one however few were asked for. One frame is
/// in flight at a time: submitting without waiting queued every frame's command buffers and
/// uploads until the driver ran out of memory (a segfault after ~600 frames). Returns the
/// frames rendered.
fn render_frames(
    ctx: &GpuContext,
    renderer: &mut Renderer,
    project: &Project,
    size: (u32, u32),
    asked: Option<u32>,
) -> anyhow::Result<u32> {
    let refining = |r: &Renderer| r.technique_status().is_some_and(|s| s.refining);
    // The first frame allocates what the size needs: an adapter that runs out says so here.
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let mut done = until_ready(renderer, project, size)?;
    if let Some(e) = pollster::block_on(scope.pop()) {
        anyhow::bail!(
            "the adapter ran out of memory for a {}x{} render ({e}): render smaller or with a lower --ssaa",
            size.0,
            size.1
        );
    }
    let target = renderer.technique_status().map_or(1, |s| s.refine_target.max(1));
    let total = asked.unwrap_or(target);
    // A technique whose settings ask for more frames than the usual limit gets them.
    let limit = CONVERGE_LIMIT.max(target.saturating_add(1));
    let mut progress = super::progress::Progress::new(u64::from(total));
    // A cache that must fill before its image is final (`rcs`) gets its frames whatever was asked.
    let must_fill = registry::entry(project.render.mode).is_some_and(|e| e.fill_before_final);
    loop {
        let more = match asked {
            Some(n) => done < n || (must_fill && refining(renderer) && done < n + limit),
            None => refining(renderer) && done < limit,
        };
        if !more {
            break;
        }
        renderer.render(&project.scene, &project.render, size)?;
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| anyhow::anyhow!("waiting for the GPU: {e}"))?;
        done += 1;
        if done <= total {
            progress.tick(u64::from(done));
        }
    }
    if let Some(p) = renderer.technique_status().and_then(|s| s.progress).filter(|_| must_fill) {
        eprintln!("{p} after {done} frames");
    }
    Ok(done)
}

/// Prints each shortfall of the result and refuses to write it unless `allow` (the user's
/// `--allow-partial`).
fn refuse_partial(out: &Path, shortfalls: &[String], allow: bool) -> anyhow::Result<()> {
    for s in shortfalls {
        eprintln!("{}: {s}", if allow { "warning" } else { "error" });
    }
    if shortfalls.is_empty() || allow {
        return Ok(());
    }
    anyhow::bail!(
        "{}: not written: the image would not be what was asked for ({} problem{} above); --allow-partial writes it anyway",
        out.display(),
        shortfalls.len(),
        if shortfalls.len() == 1 { "" } else { "s" }
    )
}

/// [`harness::until_ready`] for `project`, saying on stderr what it waits for.
pub fn until_ready(renderer: &mut Renderer, project: &Project, size: (u32, u32)) -> anyhow::Result<u32> {
    Ok(harness::until_ready(renderer, &project.scene, &project.render, size, |what| eprintln!("{what}"))?)
}

fn reference(project: &Project, out: &Path, kind: OutputKind, size: (u32, u32)) -> anyhow::Result<String> {
    let settings = project.render.reference.clone();
    let mut tracer = PathTracer::new(&project.scene, size, settings.clone());
    let cancel = AtomicBool::new(false);
    let mut last = std::time::Instant::now();
    tracer.render(settings.spp, &cancel, |p| {
        if last.elapsed().as_secs_f32() > 2.0 || p.spp == settings.spp {
            eprintln!(
                "reference: {} / {} spp, {:.2} Mrays/s, {:.2} Msamples/s",
                p.spp,
                settings.spp,
                p.rays_per_second * 1e-6,
                p.samples_per_second * 1e-6
            );
            last = std::time::Instant::now();
        }
    });
    let img = HdrImage { width: size.0, height: size.1, pixels: tracer.image() };
    image_io::write_image(out, kind, &img, &project.render.view)?;
    let p = tracer.progress();
    Ok(format!(
        "{} ({}x{}, reference, {} spp, max {} bounces, {:.2} Mrays/s)",
        out.display(),
        size.0,
        size.1,
        p.spp,
        settings.max_bounces,
        p.rays_per_second * 1e-6
    ))
}

/// Parses `--mode` (the settings stay free of the command line's types).
pub(crate) fn parse_mode(name: &str) -> Result<GiMode, String> {
    GiMode::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = GiMode::ALL.iter().map(|m| m.name()).collect();
        format!("unknown mode {name:?}; the modes are {}", names.join(", "))
    })
}
