//! `bouncelab render`: headless rendering of a project or glTF file to EXR or PNG.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use crate::image_io::{self, HdrImage, OutputKind};
use crate::project_file::Project;
use crate::render::{GpuContext, Renderer};
use crate::settings::GiMode;

/// Options of one headless render.
#[derive(Clone, Debug)]
pub struct RenderArgs {
    /// Project (`.ron`) or scene (`.gltf`, `.glb`).
    pub input: PathBuf,
    /// GI mode (overrides the project's).
    pub mode: Option<GiMode>,
    /// Output file.
    pub out: PathBuf,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Frames to render (temporal techniques converge); the last is written.
    pub frames: u32,
    /// Exposure override in stops (PNG only).
    pub exposure: Option<f32>,
}

/// Renders and writes the output file; returns a one-line summary.
pub fn run(args: &RenderArgs) -> anyhow::Result<String> {
    let kind = image_io::output_kind(&args.out)?;
    let mut project = Project::open(&args.input)?;
    if let Some(mode) = args.mode {
        project.render.mode = mode;
    }
    if let Some(ev) = args.exposure {
        project.render.view.exposure_ev = ev;
    }
    let ctx = GpuContext::new_headless()?;
    ctx.log_errors();
    log::info!("rendering {} with {}", args.input.display(), ctx.describe());
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    let size = (args.width, args.height);
    for _ in 0..args.frames.max(1) {
        renderer.render(&project.scene, &project.render, size)?;
    }
    write_output(&renderer, &args.out, kind, size)?;
    Ok(format!(
        "{} ({}x{}, mode {}, {})",
        args.out.display(),
        size.0,
        size.1,
        project.render.mode.name(),
        ctx.describe()
    ))
}

fn write_output(
    renderer: &Renderer,
    out: &Path,
    kind: OutputKind,
    size: (u32, u32),
) -> anyhow::Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    match kind {
        OutputKind::Exr => {
            let pixels = renderer.read_hdr()?;
            image_io::write_exr(
                out,
                &HdrImage {
                    width: size.0,
                    height: size.1,
                    pixels,
                },
            )?;
        }
        OutputKind::Png => image_io::write_png(out, size.0, size.1, renderer.read_ldr()?)?,
    }
    Ok(())
}
