//! `bouncelab probe`: the tuning probe. Renders a technique and `direct` on suite scenes (or
//! levels outside the suite, each with its reference `.exr` beside it) with settings overridden
//! on the command line, and prints each scene's energy ratio, the indirect light's share of the
//! reference's, and FLIP against `direct`'s, judged as `docs/QUALITY.md` judges (the exposure
//! that puts the reference's mean at 0.18). On the three-room level it adds the unlit third
//! room's energy ratio; `--objects` adds one line per object. What a default is changed with:
//!
//! `bouncelab probe rooms,clutter --mode ism --settings "(total_points: 524288)"`

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::image_io::{self, HdrImage};
use crate::metrics;
use crate::project_file::Project;
use crate::render::{GpuContext, Renderer, harness};
use crate::settings::{GiMode, ViewSettings};
use crate::suite::{self, REFERENCE_SIZE};

/// The scenes probed when none are named.
const DEFAULT_SCENES: &str = "rooms,window,clutter,hall,diorama,cornell";

/// `bouncelab probe`'s arguments.
#[derive(clap::Args, Clone, Debug)]
pub struct ProbeArgs {
    /// Comma-separated suite scenes, or `.gltf` levels (each compared with the `.exr` beside it).
    #[arg(default_value = DEFAULT_SCENES)]
    pub scenes: String,
    /// The technique probed (`ism`, `ism-ritschel`, `sshgi`, `mrt`, `rcs`).
    #[arg(long, default_value = "ism", value_parser = parse_mode)]
    pub mode: GiMode,
    /// The technique's settings as RON, e.g. "(splat_radius: 0.8)" for `ism` (fields left out
    /// keep their defaults; the scene's own settings are replaced).
    #[arg(long)]
    pub settings: Option<String>,
    /// Volumetric obscurance settings as RON, e.g. "(mrt: false)".
    #[arg(long)]
    pub vo: Option<String>,
    /// Frames rendered (the last is judged, or the mean with --average-from).
    #[arg(long, default_value_t = 32)]
    pub frames: usize,
    /// Judge the mean of frames K+1 to --frames instead of the last (the estimator's
    /// expectation; the tests take frames 17-32, K = 16).
    #[arg(long, value_name = "K")]
    pub average_from: Option<usize>,
    /// Start the renderer's frame counter at S x 1000: every random sequence of the temporal
    /// techniques (VPLs, point sets, sample patterns) seeds from it, so another S is another
    /// realization of the same estimator. On levels lit through doorways the settled energy of
    /// `ism` differs by 1-15% between realizations: compare changes over a few seeds.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u32,
    /// Supersampling per axis, box-filtered to the references' pixels.
    #[arg(long, default_value_t = 2)]
    pub ssaa: u32,
    /// Another reference (`.exr`) for every scene, e.g. `render --mode reference --max-bounces 2`
    /// to judge one bounce.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Another glTF in place of each scene (with --reference).
    #[arg(long)]
    pub gltf: Option<PathBuf>,
    /// Move the first light to this height in metres (the reference then needs --reference).
    #[arg(long, allow_negative_numbers = true)]
    pub light_y: Option<f32>,
    /// One line per object: its energy, indirect share, share of the view's light and what is
    /// missing of it.
    #[arg(long)]
    pub objects: bool,
    /// Each frame's mean luminance over the reference's, and the mean and the worst of each
    /// frame's FLIP over `direct`'s (what a single-frame mode shows from frame to frame).
    #[arg(long)]
    pub trace: bool,
    /// The last frame's GPU pass timings.
    #[arg(long)]
    pub timings: bool,
    /// Write `<scene>_<mode>.png/.exr`, `<scene>_ref.png` and `<scene>_direct.exr` into this
    /// folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub units: super::SceneArgs,
}

fn parse_mode(name: &str) -> Result<GiMode, String> {
    match GiMode::from_name(name) {
        Some(GiMode::Direct | GiMode::Reference) => {
            Err(format!("{name} is the baseline or the yardstick, not a probe"))
        }
        Some(mode) => Ok(mode),
        None => Err(format!("unknown mode {name:?}")),
    }
}

/// One probed render: the judged image, its trace, and the renderer (for ids and timings).
struct Probed {
    image: HdrImage,
    /// Each frame box-filtered to the references' pixels, with `--trace`.
    trace: Vec<HdrImage>,
    renderer: Renderer,
}

/// Runs the probe; returns the report (one block per scene).
pub fn run(args: &ProbeArgs) -> anyhow::Result<String> {
    if args.frames == 0 || args.ssaa == 0 || args.average_from.is_some_and(|k| k >= args.frames) {
        anyhow::bail!("--frames and --ssaa must be positive and --average-from below --frames");
    }
    let ctx = GpuContext::new_headless()?;
    let mut out = String::new();
    for name in args.scenes.split(',').filter(|n| !n.is_empty()) {
        let (mut project, reference, label) = scene(args, name)?;
        apply(args, &mut project)?;
        writeln!(out, "{}", probe_scene(&ctx, args, &mut project, &reference, &label)?)?;
    }
    Ok(out)
}

/// The project, reference and label of scene `name`.
fn scene(args: &ProbeArgs, name: &str) -> anyhow::Result<(Project, HdrImage, String)> {
    let root = Path::new(".");
    let outside = name.ends_with(".gltf").then(|| Path::new(name));
    let label = outside.and_then(|p| p.file_stem()).and_then(|s| s.to_str()).unwrap_or(name).to_owned();
    let reference = match (&args.reference, outside) {
        (Some(path), _) => image_io::read_linear(path)?,
        (None, Some(gltf)) => image_io::read_linear(&gltf.with_extension("exr"))?,
        (None, None) => suite::scene(name)?.reference(root)?,
    };
    let mut project = match (&args.gltf, outside) {
        (Some(path), _) => Project::from_gltf_with(path, args.units.options().unwrap_or_default())?,
        (None, Some(gltf)) => Project::from_gltf_with(gltf, args.units.options().unwrap_or_default())?,
        (None, None) => suite::scene(name)?.load(root)?,
    };
    args.units.apply_sky(&mut project)?;
    Ok((project, reference, label))
}

/// The command line's overrides: settings, obscurance, the first light's height.
fn apply(args: &ProbeArgs, project: &mut Project) -> anyhow::Result<()> {
    let r = &mut project.render;
    if let Some(text) = &args.settings {
        match args.mode {
            GiMode::Ism | GiMode::IsmRitschel => r.ism = ron::from_str(text)?,
            GiMode::Sshgi => r.sshgi = crate::settings::SshgiSettings::from_overrides(text)?,
            GiMode::Mrt => r.mrt = ron::from_str(text)?,
            GiMode::Rcs => r.rcs = ron::from_str(text)?,
            GiMode::Direct | GiMode::Reference => {}
        }
    }
    if let Some(text) = &args.vo {
        r.vo = ron::from_str(text)?;
    }
    if let Some(y) = args.light_y {
        let lights = &mut project.scene.desc_mut().lights;
        let first = lights.first_mut().ok_or_else(|| anyhow::anyhow!("--light-y: the scene has no light"))?;
        first.position.y = y;
    }
    project.render.validate()?;
    Ok(())
}

/// Probes one scene: `direct`, then the technique; the report's lines.
fn probe_scene(
    ctx: &GpuContext,
    args: &ProbeArgs,
    project: &mut Project,
    reference: &HdrImage,
    label: &str,
) -> anyhow::Result<String> {
    let ev = metrics::judging_exposure(reference);
    let reference_mean = metrics::mean_luminance(reference);
    project.render.mode = GiMode::Direct;
    let direct = render(ctx, args, project, 1, None)?.image;
    project.render.mode = args.mode;
    let Probed { image: img, trace, renderer: mut r } = render(ctx, args, project, args.frames, args.average_from)?;
    let (c, d) = (metrics::compare(&img, reference, ev)?, metrics::compare(&direct, reference, ev)?);
    let (mi, md) = (metrics::mean_luminance(&img), metrics::mean_luminance(&direct));
    let mut out = format!(
        "{label:8} energy {:.3}  indirect {:.3}  FLIP {:.4} / direct {:.4} = {:.2}",
        c.luminance_ratio,
        (mi - md) / (reference_mean - md),
        c.flip,
        d.flip,
        c.flip / d.flip
    );
    if args.trace {
        let traced: Vec<String> =
            trace.iter().map(|f| format!("{:.2}", metrics::mean_luminance(f) / reference_mean)).collect();
        write!(out, "\n         frames: {}", traced.join(" "))?;
        let flips =
            trace.iter().map(|f| Ok(metrics::compare(f, reference, ev)?.flip)).collect::<anyhow::Result<Vec<_>>>()?;
        let (mean, worst) =
            (flips.iter().sum::<f64>() / flips.len().max(1) as f64, flips.iter().fold(0.0f64, |a, b| a.max(*b)));
        write!(out, "\n         each frame's FLIP / direct: mean {:.2}, worst {:.2}", mean / d.flip, worst / d.flip)?;
    }
    if args.timings {
        let passes: Vec<String> = r.timings(true).iter().map(|p| format!("{} {:.2}", p.name, p.ms)).collect();
        write!(out, "\n         passes (ms): {}", passes.join(", "))?;
    }
    let ids = reference_ids(&r)?;
    objects_report(&mut out, args, project, label, &img, &direct, reference, &ids)?;
    if let Some(dir) = &args.out {
        write_images(dir, label, args.mode, &img, &direct, reference, ev)?;
    }
    Ok(out)
}

/// Renders `frames` frames of `project` at the references' size times `--ssaa`: the last frame,
/// or the mean of frames `average_from + 1 ..= frames`, box-filtered to the references' pixels.
fn render(
    ctx: &GpuContext,
    args: &ProbeArgs,
    project: &Project,
    frames: usize,
    average_from: Option<usize>,
) -> anyhow::Result<Probed> {
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    renderer.set_frame_index(args.seed.wrapping_mul(1000));
    let size = (REFERENCE_SIZE.0 * args.ssaa, REFERENCE_SIZE.1 * args.ssaa);
    let (scene, settings) = (&project.scene, &project.render);
    let ready = harness::until_ready(&mut renderer, scene, settings, size, |w| eprintln!("{w}"))? as usize;
    let from = average_from.unwrap_or(frames).max(ready);
    let mut sum = vec![[0.0f32; 4]; size.0 as usize * size.1 as usize];
    let mut trace = Vec::new();
    let averaged = frames.saturating_sub(from).max(1) as f32;
    for frame in ready..frames {
        renderer.render(scene, settings, size)?;
        // Between frames, as the editor: a readback issued in this frame lands for the next.
        renderer.wait_for_gpu()?;
        let summed = average_from.is_some() && frame >= from;
        if !args.trace && !summed {
            continue;
        }
        let px = renderer.read_hdr()?;
        if args.trace {
            let pixels = image_io::box_downsample(&px, size, args.ssaa);
            trace.push(HdrImage { width: REFERENCE_SIZE.0, height: REFERENCE_SIZE.1, pixels });
        }
        if summed {
            for (s, p) in sum.iter_mut().zip(px) {
                (0..4).for_each(|c| s[c] += p[c] / averaged);
            }
        }
    }
    let pixels = if average_from.is_some() { sum } else { renderer.read_hdr()? };
    let pixels = image_io::box_downsample(&pixels, size, args.ssaa);
    let image = HdrImage { width: REFERENCE_SIZE.0, height: REFERENCE_SIZE.1, pixels };
    Ok(Probed { image, trace, renderer })
}

/// Object ids at the references' size: the id of each pixel's first sample.
fn reference_ids(r: &Renderer) -> anyhow::Result<Vec<u32>> {
    let full = r.read_buffer("object_id")?;
    let k = (full.width / REFERENCE_SIZE.0).max(1);
    Ok((0..REFERENCE_SIZE.0 * REFERENCE_SIZE.1)
        .map(|i| full.pixels[((i / REFERENCE_SIZE.0) * k * full.width + (i % REFERENCE_SIZE.0) * k) as usize][0] as u32)
        .collect())
}

/// The unlit third room's line (the three-room level) and, with `--objects`, one per object.
#[allow(clippy::too_many_arguments)]
fn objects_report(
    out: &mut String,
    args: &ProbeArgs,
    project: &Project,
    label: &str,
    img: &HdrImage,
    direct: &HdrImage,
    reference: &HdrImage,
    ids: &[u32],
) -> anyhow::Result<()> {
    let objects = project.scene.objects();
    let lum_sum = |img: &HdrImage, keep: &dyn Fn(u32) -> bool| -> (f64, usize) {
        ids.iter()
            .zip(&img.pixels)
            .filter(|(id, _)| keep(**id))
            .fold((0.0, 0), |(s, n), (_, p)| (s + f64::from(metrics::luminance(p)), n + 1))
    };
    if label == "rooms" {
        let third = |id: u32| {
            id > 0
                && objects
                    .get(id as usize - 1)
                    .is_some_and(|o| o.name.ends_with("_2") || o.name.starts_with("partition_1") || o.name == "end_2")
        };
        let ((a, _), (b, _)) = (lum_sum(img, &third), lum_sum(reference, &third));
        write!(out, "\n         unlit third room {:.3}", a / b.max(1e-12))?;
    }
    if !args.objects {
        return Ok(());
    }
    let total = metrics::mean_luminance(reference) * ids.len() as f64;
    let direct_errors = metrics::per_object(direct, reference, ids)?;
    for (o, d) in metrics::per_object(img, reference, ids)?.iter().zip(direct_errors) {
        let name = objects.get(o.id as usize - 1).map_or("?", |o| o.name.as_str());
        // Indirect share: (probed - direct) / (reference - direct) from the luminance ratios.
        let indirect = (o.luminance_ratio - d.luminance_ratio) / (1.0 - d.luminance_ratio);
        let own = |id: u32| id == o.id;
        let ((seen, _), (got, _)) = (lum_sum(reference, &own), lum_sum(img, &own));
        write!(
            out,
            "\n         {name:20} {:6} px  energy {:.3}  indirect {indirect:.3}  share {:.3}  missing {:+.3}",
            o.pixels,
            o.luminance_ratio,
            seen / total,
            (seen - got) / total
        )?;
    }
    Ok(())
}

/// `--out`: the probed image and the reference as PNG at the judging exposure, and the probed
/// and `direct` images as EXR.
fn write_images(
    dir: &Path,
    label: &str,
    mode: GiMode,
    img: &HdrImage,
    direct: &HdrImage,
    reference: &HdrImage,
    ev: f32,
) -> anyhow::Result<()> {
    let view = ViewSettings { exposure_ev: ev, ..Default::default() };
    let (w, h) = (img.width, img.height);
    let m = mode.name();
    image_io::write_png(&dir.join(format!("{label}_{m}.png")), w, h, image_io::tonemap_srgb8(img, &view))?;
    image_io::write_png(&dir.join(format!("{label}_ref.png")), w, h, image_io::tonemap_srgb8(reference, &view))?;
    image_io::write_exr(&dir.join(format!("{label}_{m}.exr")), img)?;
    image_io::write_exr(&dir.join(format!("{label}_direct.exr")), direct)?;
    Ok(())
}
