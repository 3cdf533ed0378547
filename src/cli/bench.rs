//! `bouncelab bench`: per-pass timings of each mode at fixed sizes, written to
//! `docs/BENCHMARKS.md`. Later techniques add their rows here.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use crate::precompute::pathtracer::PathTracer;
use crate::project_file::{Project, default_project_path};
use crate::render::harness::{self, median};
use crate::render::{GpuContext, PassTiming, Renderer};
use crate::settings::GiMode;
use crate::settings::ReferenceSettings;

/// One measured configuration.
pub(crate) struct Row {
    pub(crate) mode: GiMode,
    pub(crate) size: (u32, u32),
    pub(crate) frame_ms: f64,
    pub(crate) passes: Vec<PassTiming>,
}

/// The reference path tracer's image of `project` at `size` (64 spp, 16 quick) and its spp:
/// what the technique sections measure their error against.
pub(crate) fn traced_reference(project: &Project, size: (u32, u32), quick: bool) -> (crate::image_io::HdrImage, u32) {
    let spp = if quick { 16 } else { 64 };
    (harness::reference_image(&project.scene, size, ReferenceSettings { spp, ..Default::default() }), spp)
}

/// Times `mode` on `project` at `size` ([`harness::measure`]).
pub(crate) fn measure(
    ctx: &GpuContext,
    project: &Project,
    mode: GiMode,
    size: (u32, u32),
    frames: usize,
) -> anyhow::Result<Row> {
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    let settings = crate::settings::RenderSettings { mode, ..project.render.clone() };
    let timed = harness::measure(&mut renderer, &project.scene, &settings, size, frames)?;
    Ok(Row { mode, size, frame_ms: timed.frame_ms, passes: timed.passes })
}

/// A technique's section of `docs/BENCHMARKS.md`: appends its tables (`quick`: fewer sizes and
/// frames) measured on `ctx`, the default project at hand.
type BenchSection = fn(&mut String, &GpuContext, &Project, bool) -> anyhow::Result<()>;

/// Each row of `registry::TECHNIQUES`, in the same order: its name and its sections (a test
/// checks that the tables agree, so a new technique cannot be left out of the benchmark by
/// accident).
const SECTIONS: &[(&str, &[BenchSection])] = &[
    ("direct light", &[]),
    ("imperfect shadow maps (Ritschel 2008, Knecht 2009)", &[ism_rows]),
    (
        "modular and delta radiance transfer (Loos 2011, 2012, 2015)",
        &[
            |md, _, _, quick| super::bench_mrt::mrt_rows(md, quick),
            |md, ctx, _, quick| super::bench_mrt::mrt_runtime_rows(md, ctx, quick),
            |md, ctx, _, quick| super::bench_drt::drt_rows(md, ctx, quick),
        ],
    ),
    ("screen-space hierarchical GI (Soler et al. 2010)", &[super::bench_sshgi::sshgi_rows]),
    ("radiance cache splatting (Gautron et al. 2005)", &[super::bench_rcs::rcs_rows]),
    (
        "reference path tracer (CPU)",
        &[|md, _, project, quick| {
            reference_rows(md, project, quick);
            Ok(())
        }],
    ),
];

/// Runs the benchmark and writes `out` (normally `docs/BENCHMARKS.md`).
pub fn run(out: &Path, quick: bool) -> anyhow::Result<String> {
    crate::output_path::check(out, crate::output_path::MARKDOWN, &[])?;
    let ctx = GpuContext::new_headless()?;
    let project = Project::load(&default_project_path())?;
    let sizes: &[(u32, u32)] = if quick { &[(320, 180)] } else { &[(320, 180), (640, 360), (1280, 720)] };
    let frames = if quick { 5 } else { 20 };
    let mut rows = Vec::new();
    for &size in sizes {
        rows.push(measure(&ctx, &project, GiMode::Direct, size, frames)?);
    }
    // ISM at its defaults, with the irradiance and the SH filter (1280x720 is too slow here).
    let mut sh_project = project.clone();
    sh_project.render.ism.sh_filter = true;
    let mut ism_rows_timed = Vec::new();
    for &size in sizes.iter().take(2) {
        ism_rows_timed.push(("irradiance", measure(&ctx, &project, GiMode::Ism, size, frames)?));
        ism_rows_timed.push(("SH", measure(&ctx, &sh_project, GiMode::Ism, size, frames)?));
    }
    let mut md = String::new();
    let _ = writeln!(md, "# Benchmarks\n");
    let _ = writeln!(
        md,
        "Written by `bouncelab bench{}` (release build). Adapter: **{}**.",
        if quick { " --quick" } else { "" },
        ctx.describe()
    );
    let _ = writeln!(
        md,
        "Scene: the default project (Cornell box, one shadowed point light). Frame time is wall-clock per frame \
         including submission and waiting for the GPU (median of {frames}); pass times are GPU timestamps (median). \
         Software adapters are not GPUs: compare ratios, not absolute numbers.\n"
    );
    let _ = writeln!(md, "## Direct lighting\n");
    let _ = writeln!(md, "| mode | size | frame ms | per-pass GPU ms |");
    let _ = writeln!(md, "|---|---|---|---|");
    let passes = |r: &Row| {
        if r.passes.is_empty() {
            "(no timestamp queries on this adapter)".to_owned()
        } else {
            r.passes.iter().map(|p| format!("{} {:.2}", p.name, p.ms)).collect::<Vec<_>>().join(", ")
        }
    };
    for r in &rows {
        let _ = writeln!(md, "| {} | {}x{} | {:.2} | {} |", r.mode.name(), r.size.0, r.size.1, r.frame_ms, passes(r));
    }
    let _ = writeln!(md, "\n## ISM per pass (defaults: 256 VPLs, 6 bounces, 128² ISMs, n = 4)\n");
    let _ = writeln!(md, "| filter | size | frame ms | per-pass GPU ms |");
    let _ = writeln!(md, "|---|---|---|---|");
    for (filter, r) in &ism_rows_timed {
        let _ = writeln!(md, "| {filter} | {}x{} | {:.2} | {} |", r.size.0, r.size.1, r.frame_ms, passes(r));
    }
    for (_, sections) in SECTIONS {
        for section in *sections {
            section(&mut md, &ctx, &project, quick)?;
        }
    }
    // Anything after the manual marker (hand-run external comparisons) survives a rerun.
    if let Ok(old) = std::fs::read_to_string(out)
        && let Some(i) = old.find(MANUAL_MARKER)
    {
        md.push('\n');
        md.push_str(&old[i..]);
    }
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    crate::atomic_file::write(out, md.as_bytes())?;
    Ok(md)
}

/// Marks the hand-maintained tail of `docs/BENCHMARKS.md`.
const MANUAL_MARKER: &str = "<!-- manual -->";

/// Reference path tracer throughput on the default project (CPU, rayon over all cores).
fn reference_rows(md: &mut String, project: &Project, quick: bool) {
    let size = (320, 180);
    let spp = if quick { 4 } else { 32 };
    let _ = writeln!(md, "\n## Reference path tracer (CPU)\n");
    let _ = writeln!(
        md,
        "{} threads. Rays = camera + bounce + shadow rays. {}x{}, {spp} spp, Russian roulette from bounce {}.\n",
        rayon::current_num_threads(),
        size.0,
        size.1,
        crate::settings::ReferenceSettings::default().rr_start
    );
    let _ = writeln!(md, "| max bounces | Mrays/s | Msamples/s | seconds |");
    let _ = writeln!(md, "|---|---|---|---|");
    for max_bounces in [1, 8, 64] {
        let settings = ReferenceSettings { spp, max_bounces, ..ReferenceSettings::default() };
        let mut tracer = PathTracer::new(&project.scene, size, settings);
        let start = Instant::now();
        tracer.render(spp, &std::sync::atomic::AtomicBool::new(false), |_| {});
        let p = tracer.progress();
        let _ = writeln!(
            md,
            "| {max_bounces} | {:.2} | {:.3} | {:.2} |",
            p.rays_per_second * 1e-6,
            p.samples_per_second * 1e-6,
            start.elapsed().as_secs_f64()
        );
    }
}

/// The thesis's sweeps (VPLs, ISM resolution, bounces) as frame-time ratios to `direct` in the
/// same run, with the error against the reference path tracer after 16 frames.
fn ism_rows(md: &mut String, ctx: &GpuContext, project: &Project, quick: bool) -> anyhow::Result<()> {
    use crate::image_io::HdrImage;
    use crate::metrics;
    let size = if quick { (160, 90) } else { (320, 180) };
    let frames = 16;
    let mut tracer = PathTracer::new(
        &project.scene,
        size,
        ReferenceSettings { spp: if quick { 16 } else { 64 }, ..ReferenceSettings::default() },
    );
    let spp = tracer.settings_spp();
    tracer.render(spp, &std::sync::atomic::AtomicBool::new(false), |_| {});
    let reference = HdrImage { width: size.0, height: size.1, pixels: tracer.image() };
    let direct_ms = measure(ctx, project, GiMode::Direct, size, 8)?.frame_ms;
    let run =
        |mode: GiMode, edit: &dyn Fn(&mut crate::settings::IsmSettings)| -> anyhow::Result<(f64, f64, f64, f64)> {
            let mut settings = project.render.clone();
            settings.mode = mode;
            edit(&mut settings.ism);
            settings.validate()?;
            let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
            let mut times = Vec::new();
            for _ in 0..frames {
                let t = Instant::now();
                r.render(&project.scene, &settings, size)?;
                let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
                times.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let img = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr()? };
            let c = metrics::compare(&img, &reference, 0.0)?;
            Ok((median(times[frames / 2..].to_vec()), c.flip, c.relmse, c.luminance_ratio))
        };
    let _ = writeln!(md, "\n## ISM (Knecht 2009) sweeps\n");
    let _ = writeln!(
        md,
        "Default project (point light), {}x{}, frame time relative to `direct` ({direct_ms:.1} ms) in the same run; error after {frames} \
         frames against the reference path tracer ({spp} spp, full GI). The VPL and ISM-resolution sweeps use one \
         bounce (as the thesis's tables). Other settings at their defaults (6 bounces, 128² ISMs, irradiance \
         filter).\n",
        size.0, size.1
    );
    let _ = writeln!(md, "| sweep | setting | mode | frame / direct | FLIP | relMSE | luminance ratio |");
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    let vpls: &[u32] = if quick { &[16, 256] } else { &[4, 16, 64, 256, 1024] };
    for &n in vpls {
        for mode in [GiMode::Ism, GiMode::IsmRitschel] {
            let (ms, flip, rel, lum) = run(mode, &|m| {
                m.vpl_count = n;
                m.bounces = 1;
            })?;
            let _ = writeln!(
                md,
                "| VPLs | {n} | {} | {:.2} | {flip:.4} | {rel:.4} | {lum:.3} |",
                mode.name(),
                ms / direct_ms
            );
        }
    }
    let resolutions: &[u32] = if quick { &[128] } else { &[64, 128, 256] };
    for &res in resolutions {
        let (ms, flip, rel, lum) = run(GiMode::Ism, &|m| {
            m.ism_resolution = res;
            m.bounces = 1;
        })?;
        let _ =
            writeln!(md, "| ISM resolution | {res} | ism | {:.2} | {flip:.4} | {rel:.4} | {lum:.3} |", ms / direct_ms);
    }
    let bounces: &[u32] = if quick { &[1, 2] } else { &[1, 2, 3, 4, 5, 6] };
    for &b in bounces {
        let (ms, flip, rel, lum) = run(GiMode::Ism, &|m| m.bounces = b)?;
        let _ = writeln!(md, "| bounces | {b} | ism | {:.2} | {flip:.4} | {rel:.4} | {lum:.3} |", ms / direct_ms);
    }
    for mode in [GiMode::Ism, GiMode::IsmRitschel] {
        for sh in [false, true] {
            let (ms, flip, rel, lum) = run(mode, &|m| m.sh_filter = sh)?;
            let filter = if sh { "SH (Segovia & Wald)" } else { "irradiance" };
            let _ = writeln!(
                md,
                "| filter | {filter} | {} | {:.2} | {flip:.4} | {rel:.4} | {lum:.3} |",
                mode.name(),
                ms / direct_ms
            );
        }
    }
    let (ms, flip, rel, lum) = run(GiMode::Direct, &|_| {})?;
    let _ = writeln!(md, "| baseline | - | direct | {:.2} | {flip:.4} | {rel:.4} | {lum:.3} |", ms / direct_ms);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::SECTIONS;
    use crate::render::gi::registry::TECHNIQUES;

    #[test]
    fn every_technique_row_has_its_bench_row_in_the_same_order() {
        let rows: Vec<&str> = TECHNIQUES.iter().map(|t| t.name).collect();
        let bench: Vec<&str> = SECTIONS.iter().map(|(name, _)| *name).collect();
        assert_eq!(rows, bench, "cli::bench::SECTIONS must follow render::gi::registry::TECHNIQUES");
    }
}
