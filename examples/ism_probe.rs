//! A tuning probe for ISM on the scene suite: renders `ism` (32 frames) and `direct` on the
//! named suite scenes with ISM settings overridden from the command line, and prints each
//! scene's energy ratio and FLIP against the cached reference, and on the multi-room level the
//! unlit third room's energy ratio and the per-object ratios. What every ISM change in the
//! scene-suite issue was measured with:
//!
//! `cargo run --release --example ism_probe -- rooms,clutter "(total_points: 524288)"`
//!
//! `PROBE_TIMINGS=1` prints the last frame's GPU pass timings. `PROBE_SSHGI="()"` renders
//! `sshgi` with those settings in place of `ism` (the ISM settings argument is then ignored);
//! `PROBE_MRT="()"` renders `mrt` likewise, `PROBE_RCS="()"` `rcs`.
//!
//! A name ending in `.gltf` is a scene outside the suite, compared with the `.exr` next to it
//! (`tools/unseen_levels.py` writes the held-out levels; `bouncelab render --mode reference
//! --width 128 --height 72` their references).

use std::path::Path;

use bouncelab::image_io::{self, HdrImage};
use bouncelab::metrics;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, IsmSettings};
use bouncelab::suite::{self, REFERENCE_SIZE};

fn render(
    ctx: &GpuContext,
    project: &bouncelab::project_file::Project,
    frames: usize,
    reference_mean: f64,
) -> anyhow::Result<(HdrImage, Renderer)> {
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    // PROBE_SSAA: supersampling per axis, box-filtered as the references' pixels (default 2).
    let ssaa: u32 = std::env::var("PROBE_SSAA").ok().and_then(|v| v.parse().ok()).unwrap_or(2);
    let size = (REFERENCE_SIZE.0 * ssaa, REFERENCE_SIZE.1 * ssaa);
    // PROBE_AVG: the mean of every frame instead of the last (the estimator's expectation).
    let average = std::env::var_os("PROBE_AVG").is_some();
    // PROBE_FROM: with PROBE_AVG, the mean of the frames from this one on (the tail's running
    // mean and the temporal filter settled; the CI tests take frames 17-32).
    let from: usize = std::env::var("PROBE_FROM").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let mut sum = vec![[0.0f32; 4]; (size.0 * size.1) as usize];
    // A technique preparing on the CPU (MRT's dictionary and level) first.
    let ready =
        bouncelab::render::harness::until_ready(&mut r, &project.scene, &project.render, size, |w| eprintln!("{w}"))?
            as usize;
    let averaged = frames.saturating_sub(from.max(ready)).max(1) as f32;
    // PROBE_TRACE: each frame's mean luminance over the reference's.
    let trace = std::env::var_os("PROBE_TRACE").is_some();
    let mut traced = Vec::new();
    for frame in ready..frames {
        r.render(&project.scene, &project.render, size)?;
        let summed = average && frame >= from;
        if !trace && !summed {
            continue;
        }
        // One readback serves both.
        let px = r.read_hdr()?;
        if trace {
            let mean = px.iter().map(|p| f64::from(metrics::luminance(p))).sum::<f64>() / px.len() as f64;
            traced.push(format!("{:.2}", mean / reference_mean));
        }
        if summed {
            for (s, p) in sum.iter_mut().zip(px) {
                (0..4).for_each(|c| s[c] += p[c] / averaged);
            }
        }
    }
    if !traced.is_empty() {
        println!("         frames: {}", traced.join(" "));
    }
    // PROBE_TIMINGS: the last frame's GPU passes (ms).
    if std::env::var_os("PROBE_TIMINGS").is_some() {
        let passes: Vec<String> = r.timings(true).iter().map(|p| format!("{} {:.2}", p.name, p.ms)).collect();
        println!("         passes (ms): {}", passes.join(", "));
    }
    let pixels = if average { sum } else { r.read_hdr()? };
    let pixels = image_io::box_downsample(&pixels, size, ssaa);
    let img = HdrImage { width: REFERENCE_SIZE.0, height: REFERENCE_SIZE.1, pixels };
    Ok((img, r))
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let names = args.get(1).map_or("rooms,window,clutter,hall,diorama,cornell", String::as_str);
    let ism: IsmSettings = ron::from_str(args.get(2).map_or("()", String::as_str))?;
    let frames: usize = args.get(3).map_or(Ok(32), |s| s.parse())?;
    let ctx = GpuContext::new_headless()?;
    let root = Path::new(".");
    for name in names.split(',') {
        // A name ending in .gltf is a scene outside the suite, its reference next to it (.exr).
        let outside = name.ends_with(".gltf").then(|| Path::new(name));
        let label = outside.and_then(|p| p.file_stem()).and_then(|s| s.to_str()).unwrap_or(name);
        // PROBE_REF: another reference (e.g. `render --mode reference --max-bounces 2`).
        let reference = match (std::env::var("PROBE_REF"), outside) {
            (Ok(path), _) => image_io::read_linear(Path::new(&path))?,
            (Err(_), Some(gltf)) => image_io::read_linear(&gltf.with_extension("exr"))?,
            (Err(_), None) => suite::scene(name)?.reference(root)?,
        };
        let ev = bouncelab::metrics::judging_exposure(&reference);
        // PROBE_GLTF: another glTF in place of the suite scene (with PROBE_REF).
        let mut project = match (std::env::var("PROBE_GLTF"), outside) {
            (Ok(path), _) => bouncelab::project_file::Project::from_gltf(Path::new(&path))?,
            (Err(_), Some(gltf)) => bouncelab::project_file::Project::from_gltf(gltf)?,
            (Err(_), None) => suite::scene(name)?.load(root)?,
        };
        project.render.ism = ism.clone();
        // PROBE_LIGHT_Y: move the first light to this height (references then need PROBE_REF).
        if let Some(y) = std::env::var("PROBE_LIGHT_Y").ok().and_then(|v| v.parse::<f32>().ok()) {
            project.scene.desc_mut().lights[0].position.y = y;
        }
        project.render.mode = GiMode::Direct;
        let reference_mean = metrics::mean_luminance(&reference);
        let (direct, _) = render(&ctx, &project, 1, reference_mean)?;
        project.render.mode =
            if std::env::var_os("PROBE_RITSCHEL").is_some() { GiMode::IsmRitschel } else { GiMode::Ism };
        // PROBE_SSHGI: render `sshgi` with these settings (RON) instead of `ism`.
        if let Ok(ron_text) = std::env::var("PROBE_SSHGI") {
            project.render.sshgi = ron::from_str(&ron_text)?;
            project.render.mode = GiMode::Sshgi;
        }
        // PROBE_VO: volumetric obscurance settings (RON), e.g. "(mrt: false)".
        if let Ok(ron_text) = std::env::var("PROBE_VO") {
            project.render.vo = ron::from_str(&ron_text)?;
        }
        // PROBE_MRT: render `mrt` with these settings (RON) instead of `ism`.
        if let Ok(ron_text) = std::env::var("PROBE_MRT") {
            project.render.mrt = ron::from_str(&ron_text)?;
            project.render.mode = GiMode::Mrt;
        }
        // PROBE_RCS: render `rcs` with these settings (RON) instead of `ism`.
        if let Ok(ron_text) = std::env::var("PROBE_RCS") {
            project.render.rcs = ron::from_str(&ron_text)?;
            project.render.mode = GiMode::Rcs;
        }
        let (img, r) = render(&ctx, &project, frames, reference_mean)?;
        let c = metrics::compare(&img, &reference, ev)?;
        let d = metrics::compare(&direct, &reference, ev)?;
        let (mi, md, mr) =
            (metrics::mean_luminance(&img), metrics::mean_luminance(&direct), metrics::mean_luminance(&reference));
        println!(
            "{label:8} energy {:.3}  indirect {:.3}  FLIP {:.4} / direct {:.4} = {:.2}",
            c.luminance_ratio,
            (mi - md) / (mr - md),
            c.flip,
            d.flip,
            c.flip / d.flip
        );
        // Object ids at the references' size: the id of each pixel's first sample.
        let full = r.read_buffer("object_id")?;
        let k = full.width / REFERENCE_SIZE.0;
        let ids: Vec<u32> = (0..REFERENCE_SIZE.0 * REFERENCE_SIZE.1)
            .map(|i| {
                full.pixels[((i / REFERENCE_SIZE.0) * k * full.width + (i % REFERENCE_SIZE.0) * k) as usize][0] as u32
            })
            .collect();
        let objects = project.scene.objects();
        if name == "rooms" {
            let third = |id: u32| {
                id > 0
                    && objects.get(id as usize - 1).is_some_and(|o| {
                        o.name.ends_with("_2") || o.name.starts_with("partition_1") || o.name == "end_2"
                    })
            };
            let mean = |img: &HdrImage| {
                let v: Vec<f64> = ids
                    .iter()
                    .zip(&img.pixels)
                    .filter(|(id, _)| third(**id))
                    .map(|(_, p)| f64::from(metrics::luminance(p)))
                    .collect();
                v.iter().sum::<f64>() / v.len().max(1) as f64
            };
            println!("         unlit third room {:.3}", mean(&img) / mean(&reference));
        }
        if std::env::var_os("PROBE_OBJECTS").is_some() {
            let dref = metrics::per_object(&direct, &reference, &ids)?;
            for (o, d) in metrics::per_object(&img, &reference, &ids)?.iter().zip(dref) {
                let n = objects.get(o.id as usize - 1).map_or("?", |o| o.name.as_str());
                // Indirect share: (ism - direct) / (reference - direct) from the luminance ratios.
                let ind = (o.luminance_ratio - d.luminance_ratio) / (1.0 - d.luminance_ratio);
                // The object's share of the reference's light on screen, and what `ism` misses of
                // it as a share of the whole screen's reference light.
                let sum = |img: &HdrImage| -> f64 {
                    ids.iter()
                        .zip(&img.pixels)
                        .filter(|(id, _)| **id == o.id)
                        .map(|(_, p)| f64::from(metrics::luminance(p)))
                        .sum()
                };
                let total = mr * (ids.len() as f64);
                let seen = sum(&reference);
                let (share, missing) = (seen / total, (seen - sum(&img)) / total);
                println!(
                    "         {n:20} {:6} px  energy {:.3}  indirect {ind:.3}  share {share:.3}  missing {missing:+.3}",
                    o.pixels, o.luminance_ratio
                );
            }
        }
        if let Ok(dir) = std::env::var("PROBE_OUT") {
            let view = bouncelab::settings::ViewSettings { exposure_ev: ev, ..Default::default() };
            let (w, h) = REFERENCE_SIZE;
            image_io::write_png(
                Path::new(&format!("{dir}/{label}_ism.png")),
                w,
                h,
                image_io::tonemap_srgb8(&img, &view),
            )?;
            image_io::write_png(
                Path::new(&format!("{dir}/{label}_ref.png")),
                w,
                h,
                image_io::tonemap_srgb8(&reference, &view),
            )?;
            image_io::write_exr(Path::new(&format!("{dir}/{label}_ism.exr")), &img)?;
            image_io::write_exr(Path::new(&format!("{dir}/{label}_direct.exr")), &direct)?;
        }
    }
    Ok(())
}
