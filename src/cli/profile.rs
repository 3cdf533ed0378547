//! `bouncelab profile`: the GPU profile one run on the GPU machine produces. Every mode on the
//! suite's scenes at the given resolutions (default 720p, 1080p and 4K), each after its
//! technique is ready and warm: per row the median GPU time of every pass, the technique's own
//! passes summed (`technique_ms`) apart from the shared direct path (`direct_ms`: G-buffer,
//! shadows, direct light, composite, tonemap), the CPU time to record and submit a frame
//! (`cpu_ms`), and the frames' wall-clock time; one Chrome trace per mode (chrome://tracing,
//! Perfetto) of a frame at the first scene and resolution. Still frames keep their shadow maps,
//! so each row also measures one frame that redraws them (`shadows_redraw_ms`), and the two after
//! a 10 cm camera move (`moved_technique_ms`: the costlier; `moved_cpu_waits`: both); `rcs` rows fill and converge
//! their cache first (at most 128 frames). The JSON is rewritten after every
//! row, so a run cut short by the machine's time limit keeps what it measured, and rows past
//! `--budget-s` are skipped and named. `tools/gpu_bench.sh` packs the binary for the machine.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use crate::render::gi::registry;
use crate::render::harness::{converge, median, median_passes, until_ready};
use crate::render::timing::{PassKind, PassTiming};
use crate::render::{GpuContext, Renderer};
use crate::scene::Scene;
use crate::settings::{GiMode, RenderSettings};
use crate::suite::SCENES;

/// The passes of the shared direct path; every other pass is the technique's own.
pub const DIRECT_PASSES: &[&str] = &["gbuffer", "emission", "shadows", "lighting", "composite", "tonemap"];

/// Arguments of `bouncelab profile`.
#[derive(clap::Args, Debug)]
pub struct ProfileArgs {
    /// Resolutions, WxH, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1280x720,1920x1080,3840x2160", value_parser = parse_size)]
    pub resolutions: Vec<(u32, u32)>,
    /// Suite scenes (default: every one).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Modes (default: every mode but `reference`).
    #[arg(long, value_delimiter = ',', value_parser = super::render::parse_mode)]
    pub modes: Vec<GiMode>,
    /// Frames measured per row, after the technique is ready and `--warm-up` frames.
    #[arg(long, default_value_t = 8)]
    pub frames: usize,
    /// Frames rendered before measuring (pipelines compiled, temporal history and caches warm).
    #[arg(long, default_value_t = 8)]
    pub warm_up: usize,
    /// The profile (JSON).
    #[arg(long, default_value = "docs/gpu-profile.json")]
    pub out: PathBuf,
    /// Folder for the Chrome traces, one per mode.
    #[arg(long, default_value = "docs/gpu-trace")]
    pub traces: PathBuf,
    /// Seconds the whole profile may take; rows not started by then are skipped (and named).
    #[arg(long, default_value_t = 270)]
    pub budget_s: u64,
    /// The commit profiled (default: `BOUNCELAB_COMMIT`, else `git rev-parse HEAD`).
    #[arg(long)]
    pub commit: Option<String>,
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    text.split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .filter(|(w, h): &(u32, u32)| *w > 0 && *h > 0)
        .ok_or_else(|| format!("{text:?} is not a size WxH"))
}

/// The costlier of the two frames after a 10 cm camera move.
struct Moved {
    /// The technique's own passes' GPU time.
    technique_ms: f64,
    /// The CPU's blocking waits for the GPU inside both frames' `render`.
    waits: u64,
    /// Every pass of that frame.
    passes: Vec<PassTiming>,
    /// The technique's counters after the second frame (what it did: records made, rounds).
    counters: Vec<(&'static str, u64)>,
}

/// One measured row.
struct Row {
    mode: GiMode,
    scene: &'static str,
    size: (u32, u32),
    passes: Vec<PassTiming>,
    cpu_ms: f64,
    /// The most blocking GPU waits inside one measured frame's `render`.
    cpu_waits: u64,
    frame_ms: f64,
    /// The shadow maps' GPU time in a frame that redraws every layer, as after a light or an
    /// object moved (a still frame keeps them: `render/shadows.rs`); 0 without shadowed lights.
    shadows_redraw_ms: f64,
    /// The costlier of the two frames after the camera moved 10 cm (what `rcs`'s second
    /// budget is about: records for the uncovered surface).
    moved: Moved,
    /// One frame's passes with their start times (ms from the frame's first pass).
    trace: Vec<(String, f64, f64)>,
}

impl Row {
    fn split(&self) -> (f64, f64) {
        let direct: f64 = self.passes.iter().filter(|p| DIRECT_PASSES.contains(&p.name.as_str())).map(|p| p.ms).sum();
        let all: f64 = self.passes.iter().map(|p| p.ms).sum();
        (all - direct, direct)
    }

    /// GPU milliseconds in render passes and in compute passes (an H100 rasterises on a small
    /// part of the chip only).
    fn by_kind(&self) -> (f64, f64) {
        let sum = |k: PassKind| self.passes.iter().filter(|p| p.kind == k).map(|p| p.ms).sum::<f64>();
        (sum(PassKind::Raster), sum(PassKind::Compute))
    }

    fn json(&self) -> Value {
        let (technique, direct) = self.split();
        let (raster, compute) = self.by_kind();
        json!({
            "mode": self.mode.name(),
            "scene": self.scene,
            "resolution": format!("{}x{}", self.size.0, self.size.1),
            "technique_ms": technique,
            "direct_ms": direct,
            "cpu_ms": self.cpu_ms,
            "cpu_waits": self.cpu_waits,
            "frame_ms": self.frame_ms,
            "shadows_redraw_ms": self.shadows_redraw_ms,
            "moved_technique_ms": self.moved.technique_ms,
            "moved_cpu_waits": self.moved.waits,
            "moved_passes": timings_json(&self.moved.passes),
            "moved_counters": self.moved.counters.iter().map(|(k, v)| ((*k).to_owned(), json!(v))).collect::<serde_json::Map<_, _>>(),
            "raster_ms": raster,
            "compute_ms": compute,
            "passes": timings_json(&self.passes),
        })
    }
}

/// Passes as JSON: name, GPU ms and kind.
fn timings_json(passes: &[PassTiming]) -> Vec<Value> {
    passes.iter().map(|p| json!({"name": p.name, "ms": p.ms, "kind": p.kind.name()})).collect()
}

/// Runs the profile; returns the markdown table.
pub fn run(args: &ProfileArgs) -> anyhow::Result<String> {
    crate::output_path::check(&args.out, crate::output_path::JSON, &[])?;
    std::fs::create_dir_all(&args.traces)?;
    let ctx = GpuContext::new_headless()?;
    let started = Instant::now();
    let budget = Duration::from_secs(args.budget_s);
    let modes: Vec<GiMode> = if args.modes.is_empty() {
        registry::modes().map(|m| m.mode).filter(|m| *m != GiMode::Reference).collect()
    } else {
        args.modes.clone()
    };
    let scenes: Vec<&'static crate::suite::SuiteScene> =
        SCENES.iter().filter(|s| args.scenes.is_empty() || args.scenes.iter().any(|n| n == s.name)).collect();
    anyhow::ensure!(!scenes.is_empty(), "no suite scene is named {:?}", args.scenes);
    let header = header(&ctx, args);
    let (mut rows, mut skipped) = (Vec::new(), Vec::new());
    for mode in &modes {
        for scene in &scenes {
            for &size in &args.resolutions {
                let what = format!("{} {} {}x{}", mode.name(), scene.name, size.0, size.1);
                if started.elapsed() > budget {
                    skipped.push(what);
                    continue;
                }
                eprintln!("profile: {what}");
                match row(&ctx, *mode, scene, size, args) {
                    Ok(r) => rows.push(r),
                    Err(e) => skipped.push(format!("{what}: {e}")),
                }
                write_json(&args.out, &header, &rows, &skipped)?;
            }
        }
    }
    write_traces(&args.traces, &rows)?;
    write_json(&args.out, &header, &rows, &skipped)?;
    Ok(table(&header, &rows, &skipped))
}

/// The card, driver and commit.
fn header(ctx: &GpuContext, args: &ProfileArgs) -> Value {
    let info = ctx.adapter.get_info();
    let commit = args
        .commit
        .clone()
        .or_else(|| std::env::var("BOUNCELAB_COMMIT").ok())
        .or_else(|| {
            let out = std::process::Command::new("git").args(["rev-parse", "HEAD"]).output().ok()?;
            out.status.success().then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
        })
        .unwrap_or_else(|| "unknown".to_owned());
    json!({
        "card": info.name,
        "driver": format!("{} {}", info.driver, info.driver_info),
        "backend": format!("{:?}", info.backend),
        "device_type": format!("{:?}", info.device_type),
        "commit": commit,
        "frames": args.frames,
        "warm_up": args.warm_up,
    })
}

/// Measures one (mode, scene, size).
fn row(
    ctx: &GpuContext,
    mode: GiMode,
    scene: &'static crate::suite::SuiteScene,
    size: (u32, u32),
    args: &ProfileArgs,
) -> anyhow::Result<Row> {
    let project = scene.load(Path::new("."))?;
    let mut settings = project.render.clone();
    settings.mode = mode;
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    r.support(&settings, size).map_err(|why| anyhow::anyhow!("cannot run here: {why}"))?;
    until_ready(&mut r, &project.scene, &settings, size, |_| {})?;
    if mode == GiMode::Rcs {
        // Its warm cost is the filled cache's (at most 128 frames, as the quality matrix).
        converge(&mut r, &project.scene, &settings, size, 128)?;
    }
    for _ in 0..args.warm_up {
        r.render(&project.scene, &settings, size)?;
        r.wait_for_gpu()?;
    }
    let (mut cpu, mut wall, mut frames, mut waits) = (Vec::new(), Vec::new(), Vec::new(), 0);
    let mut pieces = Vec::new();
    for _ in 0..args.frames.max(1) {
        let before = crate::render::readback::blocking_waits();
        let t = Instant::now();
        r.render(&project.scene, &settings, size)?;
        cpu.push(t.elapsed().as_secs_f64() * 1e3);
        waits = waits.max(crate::render::readback::blocking_waits() - before);
        r.wait_for_gpu()?;
        wall.push(t.elapsed().as_secs_f64() * 1e3);
        frames.push(r.timings(true));
        pieces = r.timing_pieces();
    }
    let passes = median_passes(&frames);
    let moved = after_camera_move(&mut r, &project.scene, &settings, size)?;
    let shadows_redraw_ms = shadows_redrawn(&mut r, &project.scene, &settings, size)?;
    // The trace shows the last frame's passes as recorded: the ISM's steps once per VPL set.
    let trace = pieces.iter().map(|p| (p.name.clone(), p.start_ms, p.ms)).collect();
    Ok(Row {
        mode,
        scene: scene.name,
        size,
        passes,
        cpu_ms: median(cpu),
        cpu_waits: waits,
        frame_ms: median(wall),
        shadows_redraw_ms,
        moved,
        trace,
    })
}

/// The two frames after the camera moved 10 cm sideways (the scene itself is left as it was):
/// the first splats and finds the uncovered pixels, the second makes their records (`rcs`);
/// the costlier one's passes, and the waits of both.
fn after_camera_move(
    r: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
) -> anyhow::Result<Moved> {
    let mut moved = scene.clone();
    let mut camera = *scene.camera();
    camera.position += camera.world_from_view().x_axis.truncate() * 0.1;
    moved.set_camera(camera);
    let mut worst = Moved { technique_ms: -1.0, waits: 0, passes: Vec::new(), counters: Vec::new() };
    for _ in 0..2 {
        let (passes, waits) = one_frame(r, &moved, settings, size)?;
        worst.waits += waits;
        let technique_ms = sum_ms(&passes, |name| !DIRECT_PASSES.contains(&name));
        if technique_ms > worst.technique_ms {
            (worst.technique_ms, worst.passes) = (technique_ms, passes);
        }
    }
    worst.counters = r.technique_status().map(|s| s.counters).unwrap_or_default();
    Ok(worst)
}

/// The shadow maps' GPU time in one frame after every layer was made stale.
fn shadows_redrawn(
    r: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
) -> anyhow::Result<f64> {
    r.invalidate_shadow_maps();
    let (passes, _) = one_frame(r, scene, settings, size)?;
    Ok(sum_ms(&passes, |name| name == "shadows"))
}

/// One frame's pass timings, once the GPU has finished it, and the blocking waits inside it.
fn one_frame(
    r: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
) -> anyhow::Result<(Vec<PassTiming>, u64)> {
    let before = crate::render::readback::blocking_waits();
    r.render(scene, settings, size)?;
    let waits = crate::render::readback::blocking_waits() - before;
    r.wait_for_gpu()?;
    Ok((r.timings(true), waits))
}

/// The summed GPU time of the passes whose names `keep` accepts (0 for none).
fn sum_ms(passes: &[PassTiming], keep: impl Fn(&str) -> bool) -> f64 {
    // Summed from 0.0: an empty `sum()` of f64 is -0.
    passes.iter().filter(|p| keep(&p.name)).fold(0.0, |t, p| t + p.ms)
}

/// The profile JSON in the shape `docs/gpu-profile.json` is checked against (atomically).
fn write_json(out: &Path, header: &Value, rows: &[Row], skipped: &[String]) -> anyhow::Result<()> {
    let mut doc = header.clone();
    doc["rows"] = Value::Array(rows.iter().map(Row::json).collect());
    doc["skipped"] = json!(skipped);
    let mut text = serde_json::to_string_pretty(&doc)?;
    text.push('\n');
    crate::atomic_file::write(out, text.as_bytes())?;
    Ok(())
}

/// One Chrome trace per mode: the first row's frame, each pass a complete event.
fn write_traces(folder: &Path, rows: &[Row]) -> anyhow::Result<()> {
    let mut done: Vec<GiMode> = Vec::new();
    for r in rows.iter().filter(|r| !r.trace.is_empty()) {
        if done.contains(&r.mode) {
            continue;
        }
        done.push(r.mode);
        let events: Vec<Value> = r
            .trace
            .iter()
            .map(|(name, start, ms)| {
                let direct = DIRECT_PASSES.contains(&name.as_str());
                json!({"name": name, "cat": if direct { "direct" } else { "technique" }, "ph": "X",
                       "ts": start * 1e3, "dur": ms * 1e3, "pid": 1, "tid": 1})
            })
            .collect();
        let doc = json!({"traceEvents": events, "displayTimeUnit": "ms",
                         "otherData": {"mode": r.mode.name(), "scene": r.scene, "resolution": format!("{}x{}", r.size.0, r.size.1)}});
        let path = folder.join(format!("{}.json", r.mode.name()));
        crate::atomic_file::write(&path, serde_json::to_string(&doc)?.as_bytes())?;
    }
    Ok(())
}

/// The markdown table of the profile.
fn table(header: &Value, rows: &[Row], skipped: &[String]) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "GPU profile on **{}** ({}), commit `{}`: median of {} frames after warm-up; technique = its own passes, direct = G-buffer, shadows, direct light, composite, tonemap. Shadow maps are drawn only when a light or an object moved; \"shadows redrawn\" is their time in such a frame.\n",
        header["card"].as_str().unwrap_or_default(),
        header["driver"].as_str().unwrap_or_default(),
        header["commit"].as_str().unwrap_or_default(),
        header["frames"]
    );
    let _ = writeln!(
        md,
        "| mode | scene | resolution | technique ms | direct ms | raster ms | compute ms | CPU record+submit ms | CPU waits | frame ms | shadows redrawn ms | technique ms after a 10 cm move (waits) | slowest passes |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let (technique, direct) = r.split();
        let (raster, compute) = r.by_kind();
        let mut passes = r.passes.clone();
        passes.sort_by(|a, b| b.ms.total_cmp(&a.ms));
        let top: Vec<String> = passes.iter().take(3).map(|p| format!("{} {:.2}", p.name, p.ms)).collect();
        let _ = writeln!(
            md,
            "| {} | {} | {}x{} | {technique:.2} | {direct:.2} | {raster:.2} | {compute:.2} | {:.2} | {} | {:.2} | {:.2} | {:.2} ({}) | {} |",
            r.mode.name(),
            r.scene,
            r.size.0,
            r.size.1,
            r.cpu_ms,
            r.cpu_waits,
            r.frame_ms,
            r.shadows_redraw_ms,
            r.moved.technique_ms,
            r.moved.waits,
            top.join(", ")
        );
    }
    if !skipped.is_empty() {
        let _ = writeln!(md, "\nSkipped: {}", skipped.join("; "));
    }
    md
}
