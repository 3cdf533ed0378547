//! `bouncelab bench` rows for `sshgi` (Soler et al. 2010): the paper's four configurations
//! (start resolution / levels / samples: ¼/4/64, ¼/4/256, ½/4/64, ½/5/64) with visibility on and
//! off, as frame-time ratios to `direct` in the same run with the sshgi passes' GPU times and the
//! error against the reference path tracer; and the same frame with ten times the clutter
//! triangles, the paper's claim that the cost does not depend on the geometry.

use std::fmt::Write as _;
use std::time::Instant;

use glam::Vec3;

use crate::image_io::HdrImage;
use crate::metrics;
use crate::project_file::Project;
use crate::render::harness::median;
use crate::render::{GpuContext, Renderer};
use crate::scene::{MeshSource, Object, ObjectRole, Transform};
use crate::settings::{GiMode, SshgiSettings};

/// One configuration's figures.
struct Measured {
    frame_ms: f64,
    sshgi_gpu_ms: f64,
    passes: String,
    flip: f64,
    energy: f64,
}

/// Renders `frames` frames of `project` in `mode` with `sshgi`; times the second half.
fn run(
    ctx: &GpuContext,
    project: &Project,
    mode: GiMode,
    sshgi: &SshgiSettings,
    size: (u32, u32),
    reference: Option<&HdrImage>,
) -> anyhow::Result<Measured> {
    let frames = 16;
    let mut settings = project.render.clone();
    settings.mode = mode;
    settings.sshgi = sshgi.clone();
    settings.validate()?;
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    let (mut times, mut gpu) = (Vec::new(), Vec::new());
    let mut passes = String::new();
    for f in 0..frames {
        let t = Instant::now();
        r.render(&project.scene, &settings, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        times.push(t.elapsed().as_secs_f64() * 1e3);
        let timings = r.timings(true);
        gpu.push(timings.iter().filter(|p| p.name.starts_with("sshgi")).map(|p| p.ms).sum::<f64>());
        if f + 1 == frames {
            passes = timings
                .iter()
                .filter(|p| p.name.starts_with("sshgi"))
                .map(|p| format!("{} {:.2}", p.name.trim_start_matches("sshgi "), p.ms))
                .collect::<Vec<_>>()
                .join(", ");
        }
    }
    let (flip, energy) = match reference {
        Some(reference) => {
            let img = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr()? };
            let c = metrics::compare(&img, reference, 0.0)?;
            (c.flip, c.luminance_ratio)
        }
        None => (f64::NAN, f64::NAN),
    };
    Ok(Measured {
        frame_ms: median(times[frames / 2..].to_vec()),
        sshgi_gpu_ms: median(gpu[frames / 2..].to_vec()),
        passes,
        flip,
        energy,
    })
}

/// `project` with `count` small boxes scattered on the floor (more triangles, same light).
fn with_clutter(project: &Project, count: usize) -> anyhow::Result<Project> {
    let mut p = project.clone();
    let desc = p.scene.desc_mut();
    for i in 0..count {
        let (u, v) = ((i as f32 * 0.618_034).fract(), (i as f32 * 0.414_214).fract());
        desc.objects.push(Object {
            name: format!("clutter_{i}"),
            source: MeshSource::Cuboid { size: Vec3::splat(0.05), openings: [false; 6] },
            mesh: 0,
            material: 0,
            transform: Transform { translation: Vec3::new(u * 1.6 - 0.8, 0.025, v * 1.6 - 0.8), ..Default::default() },
            sampling_weight: 1.0,
            role: ObjectRole::Static,
            visible: true,
        });
    }
    let desc = p.scene.desc().clone();
    p.scene = crate::import::resolve(desc, &p.imported)?;
    Ok(p)
}

/// Appends the sshgi section to `md`.
pub fn sshgi_rows(md: &mut String, ctx: &GpuContext, project: &Project, quick: bool) -> anyhow::Result<()> {
    let size = if quick { (320, 180) } else { (640, 360) };
    let (reference, spp) = super::bench::traced_reference(project, size, quick);
    let defaults = SshgiSettings::default();
    let direct = run(ctx, project, GiMode::Direct, &defaults, size, Some(&reference))?;
    let _ = writeln!(md, "\n## Screen-space hierarchical GI (Soler et al. 2010)\n");
    let _ = writeln!(
        md,
        "Default project (point light), {}x{}; frame time relative to `direct` ({:.1} ms, FLIP {:.4}) in the same run \
         (median of the last 8 of 16 frames); `sshgi` GPU ms is the sum of its passes' timestamps; error after 16 \
         frames against the reference path tracer ({spp} spp, full GI). The paper's configurations (start resolution \
         / levels / samples) at its other defaults here: {} bounces, visibility on the first, temporal weight {}.\n",
        size.0, size.1, direct.frame_ms, direct.flip, defaults.bounces, defaults.temporal_weight
    );
    let _ = writeln!(
        md,
        "| start / levels / samples | visibility | frame / direct | sshgi GPU ms | FLIP | energy | sshgi passes (GPU ms) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    let configs: &[(u32, u32, u32, &str)] = if quick {
        &[(2, 4, 64, "¼/4/64")]
    } else {
        &[(2, 4, 64, "¼/4/64"), (2, 4, 256, "¼/4/256"), (1, 4, 64, "½/4/64"), (1, 5, 64, "½/5/64")]
    };
    for &(start_level, levels, samples, label) in configs {
        for visibility in [false, true] {
            let s = SshgiSettings { start_level, levels, samples, visibility, ..defaults.clone() };
            let m = run(ctx, project, GiMode::Sshgi, &s, size, Some(&reference))?;
            let _ = writeln!(
                md,
                "| {label} | {} | {:.2} | {:.2} | {:.4} | {:.3} | {} |",
                if visibility { "on" } else { "off" },
                m.frame_ms / direct.frame_ms,
                m.sshgi_gpu_ms,
                m.flip,
                m.energy,
                m.passes
            );
        }
    }
    // The cost claim: ten times the clutter triangles (12 -> 120 boxes of 12 triangles).
    let few = with_clutter(project, 12)?;
    let many = with_clutter(project, 120)?;
    let (a, b) =
        (run(ctx, &few, GiMode::Sshgi, &defaults, size, None)?, run(ctx, &many, GiMode::Sshgi, &defaults, size, None)?);
    let _ = writeln!(
        md,
        "\nTriangle count (defaults, visibility on): 12 clutter boxes {:.2} ms sshgi GPU ({:.1} ms frame), 120 boxes \
         {:.2} ms ({:.1} ms frame): ratio {:.2} (only the voxelisation rasterises geometry).",
        a.sshgi_gpu_ms,
        a.frame_ms,
        b.sshgi_gpu_ms,
        b.frame_ms,
        b.sshgi_gpu_ms / a.sshgi_gpu_ms.max(1e-9)
    );
    Ok(())
}
