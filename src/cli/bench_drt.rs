//! `bouncelab bench`'s DRT rows (issue #13): on the suite's cluttered room, the rebuild time of
//! the delta operators for one, ten and all of its clutter objects (the level job's CPU work,
//! release build), the per-frame GPU cost of `mrt` with and without DRT and volumetric
//! obscurance as ratios to `direct` on the same view, and their error against the room's
//! path-traced reference with and without each.

use std::fmt::Write as _;

use crate::precompute::mrt::cache;
use crate::precompute::mrt::dictionary::Progress;
use crate::render::GpuContext;
use crate::render::gi::mrt::job::build_level;
use crate::settings::GiMode;

/// Appends the DRT section to `md`.
pub fn drt_rows(md: &mut String, ctx: &GpuContext, quick: bool) -> anyhow::Result<()> {
    let project = crate::suite::scene("clutter")?.load(std::path::Path::new("."))?;
    let s = &project.render.mrt;
    let (dictionary, _) = cache::load_or_build(&cache::default_dir(), &s.dictionary, &Progress::default())?;
    let depth = s.depth as usize;
    let all = build_level(&project.scene, &dictionary, depth, &[], &s.drt, &Progress::default())
        .map_err(|e| anyhow::anyhow!("the clutter room's level: {e}"))?;
    let names: Vec<String> = all
        .packed
        .drt
        .as_ref()
        .map(|d| {
            d.object_clutter
                .iter()
                .enumerate()
                .filter(|(_, c)| **c != crate::render::gi::mrt::pack::NONE)
                .filter_map(|(i, _)| project.scene.objects().get(i).map(|o| o.name.clone()))
                .collect()
        })
        .unwrap_or_default();
    let _ = writeln!(md, "\n## DRT (delta radiance transfer for clutter, the suite's cluttered room)\n");
    let _ = writeln!(
        md,
        "Rebuild of the delta operators when clutter moves (level job, CPU, {} threads; {} rays per block texel near clutter, {} per clutter texel, {}² texels per clutter face):\n",
        rayon::current_num_threads(),
        s.drt.rays,
        s.drt.gather_rays,
        s.drt.clutter_res
    );
    let _ = writeln!(md, "| clutter objects | DRT build ms | rows | entries | rays traced (M) | level build ms |");
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    let mut counts = vec![1usize, 10, names.len()];
    counts.retain(|n| *n <= names.len());
    counts.dedup();
    for n in counts {
        let mut drt = s.drt.clone();
        drt.not_clutter = names[n..].to_vec();
        let level = build_level(&project.scene, &dictionary, depth, &[], &drt, &Progress::default())
            .map_err(|e| anyhow::anyhow!("the clutter room's level with {n} clutter objects: {e}"))?;
        if let Some(d) = &level.packed.drt {
            let _ = writeln!(
                md,
                "| {} | {:.0} | {} | {} | {:.2} | {:.0} |",
                d.clutter.len(),
                d.millis,
                d.rows.len(),
                d.entries.len(),
                d.traced as f64 / 1e6,
                level.millis
            );
        }
    }
    let size = (640, 360);
    let frames = if quick { 5 } else { 20 };
    let direct = super::bench::measure(ctx, &project, GiMode::Direct, size, frames)?;
    let variant = |drt: bool, vo: bool| {
        let mut p = project.clone();
        p.render.mrt.drt.enabled = drt;
        p.render.vo.mrt = vo;
        p
    };
    let _ = writeln!(
        md,
        "\nPer frame, {}x{}, `direct` {:.2} ms on the same view (GPU timestamps, median of {frames} frames):\n",
        size.0, size.1, direct.frame_ms
    );
    let _ = writeln!(md, "| mrt | frame ms | frame / direct | DRT and VO passes, GPU ms (/ direct) |");
    let _ = writeln!(md, "|---|---|---|---|");
    let variants = [
        ("DRT and VO (defaults)", variant(true, true)),
        ("DRT, no VO", variant(true, false)),
        ("no DRT, VO", variant(false, true)),
        ("neither", variant(false, false)),
    ];
    for (name, p) in &variants {
        let row = super::bench::measure(ctx, p, GiMode::Mrt, size, frames)?;
        super::bench_mrt::stage_row(md, name, &row, direct.frame_ms, &["drt", "vo"]);
    }
    let reference = crate::suite::scene("clutter")?.reference(std::path::Path::new("."))?;
    let ev = super::quality::exposure(&reference);
    let _ = writeln!(
        md,
        "\nError against the room's path-traced reference ({}x{}, as in `docs/QUALITY.md`):\n",
        reference.width, reference.height
    );
    let _ = writeln!(md, "| mrt | energy | FLIP | relMSE |");
    let _ = writeln!(md, "|---|---|---|---|");
    for (name, p) in variants {
        let image = super::quality::render_project(ctx, p, GiMode::Mrt)?.image;
        let m = crate::metrics::compare(&image, &reference, ev)?;
        let _ = writeln!(md, "| {name} | {:.3} | {:.4} | {:.4} |", m.luminance_ratio, m.flip, m.relmse);
    }
    Ok(())
}
