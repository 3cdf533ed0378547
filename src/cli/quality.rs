//! `bouncelab bench --quality`: every available mode on every scene of the suite against its
//! cached reference: FLIP, relMSE, energy ratio and frame time relative to `direct`, written to
//! `docs/QUALITY.md` with a contact sheet (`docs/quality_sheet.png`: one row per scene, the
//! reference, then each mode with its signed error map beneath). What a user reads to choose a
//! technique, and what every technique issue reports.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use crate::image_io::{self, HdrImage};
use crate::metrics;
use crate::render::gi::registry;
use crate::render::harness::median;
use crate::render::{GpuContext, Renderer};
use crate::settings::{GiMode, ViewSettings};
use crate::suite::{REFERENCE_SIZE, SCENES, SuiteScene};

/// Modes in the matrix: every row's (the reference is the yardstick, not a row).
fn modes() -> Vec<GiMode> {
    registry::modes().map(|m| m.mode).filter(|m| *m != GiMode::Reference).collect()
}
/// Most frames a technique whose cache must fill first (`fill_before_final`) may take to fill
/// it and converge its bounce passes.
const FILL_FRAMES: usize = 128;
/// Frames a temporal mode renders after its history has settled (the technique stops
/// refining): each is judged on its own, the last is compared.
const SETTLED_FRAMES: usize = 24;
/// Frames rendered per mode without history (the timing takes the last eight).
const STATIC_FRAMES: usize = 9;
/// Supersampling per axis, as the reference's box-filtered pixels.
const SSAA: u32 = 2;

/// One cell of the matrix.
struct Cell {
    mode: GiMode,
    flip: f64,
    relmse: f64,
    energy: f64,
    frame_ms: f64,
    image: HdrImage,
    /// A temporal mode's settled frames, judged one by one.
    settled: Option<Settled>,
}

/// A temporal mode's settled frames against the reference (`docs/QUALITY.md`'s second table).
struct Settled {
    /// The energy of the frame furthest from the reference's.
    worst: f64,
    /// The frames' energies: standard deviation over mean.
    spread: f64,
    /// `metrics::temporal_instability` against the static reference.
    instability: f64,
    /// Frames the history took to settle before the judged ones.
    after: usize,
}

impl Settled {
    /// The figures of `frames` against `reference`; `None` for fewer than two frames.
    fn of(frames: &[HdrImage], reference: &HdrImage, after: usize) -> anyhow::Result<Option<Self>> {
        if frames.len() < 2 {
            return Ok(None);
        }
        let energies = frames.iter().map(|f| metrics::luminance_ratio(f, reference)).collect::<Result<Vec<_>, _>>()?;
        let worst = energies.iter().copied().fold(1.0f64, |w, e| if (e - 1.0).abs() > (w - 1.0).abs() { e } else { w });
        let spread = metrics::relative_spread(&energies);
        let statics = [reference.clone(), reference.clone()];
        let instability = metrics::temporal_instability(frames, &statics)?;
        Ok(Some(Self { worst, spread, instability, after }))
    }
}

/// A mode's render of a scene: the last frame, the median frame time of the last eight, and a
/// temporal mode's settled frames (each box-filtered to the reference's size) with the frames
/// rendered before them.
pub(crate) struct Rendered {
    pub image: HdrImage,
    pub frame_ms: f64,
    pub settled: Vec<HdrImage>,
    pub settle_frames: usize,
}

/// Renders `scene` in `mode`: a temporal mode until its history has settled and then
/// [`SETTLED_FRAMES`] more, a cache-filling one until its cache is warm and then
/// [`STATIC_FRAMES`], others [`STATIC_FRAMES`]; the last frame box-filtered to the
/// reference's size, and the median wall-clock frame time of the last eight.
fn render(ctx: &GpuContext, scene: &SuiteScene, root: &Path, mode: GiMode) -> anyhow::Result<Rendered> {
    render_project(ctx, scene.load(root)?, mode)
}

/// [`render`] of a loaded suite `project` (its settings as they are) in `mode`.
pub(crate) fn render_project(
    ctx: &GpuContext,
    mut project: crate::project_file::Project,
    mode: GiMode,
) -> anyhow::Result<Rendered> {
    project.render.mode = mode;
    let size = (REFERENCE_SIZE.0 * SSAA, REFERENCE_SIZE.1 * SSAA);
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    let temporal = registry::mode_row(mode).is_some_and(|m| m.temporal);
    let mut times = Vec::new();
    let mut first = super::render::until_ready(&mut r, &project, size)? as usize;
    let mut end = STATIC_FRAMES;
    let fills = registry::entry(mode).is_some_and(|e| e.fill_before_final);
    if fills || temporal {
        // The cache fills (and its bounce passes converge), or the history settles, first.
        while first < FILL_FRAMES && (first == 0 || r.technique_status().is_some_and(|s| s.refining)) {
            r.render(&project.scene, &project.render, size)?;
            // Between frames: rcs's placement readback lands for the next, as in the editor.
            r.wait_for_gpu()?;
            first += 1;
        }
        end = first + if fills { STATIC_FRAMES } else { SETTLED_FRAMES };
    }
    let read = |r: &Renderer| -> anyhow::Result<HdrImage> {
        let pixels = image_io::box_downsample(&r.read_hdr()?, size, SSAA);
        Ok(HdrImage { width: REFERENCE_SIZE.0, height: REFERENCE_SIZE.1, pixels })
    };
    let mut settled = Vec::new();
    for f in first..end {
        let t = Instant::now();
        r.render(&project.scene, &project.render, size)?;
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        if f + 8 >= end {
            times.push(t.elapsed().as_secs_f64() * 1e3);
        }
        if temporal && !fills {
            settled.push(read(&r)?);
        }
    }
    Ok(Rendered { image: read(&r)?, frame_ms: median(times), settled, settle_frames: first })
}

/// The judging exposure; it lives in [`metrics::judging_exposure`] so tests and examples use it
/// without the CLI.
pub use metrics::judging_exposure as exposure;

/// A tonemapped tile of the contact sheet.
fn tile(img: &HdrImage, view: &ViewSettings) -> Vec<u8> {
    image_io::tonemap_srgb8(img, view)
}

/// Writes the matrix to `out` (markdown) and the contact sheet beside it.
pub fn run(root: &Path, out: &Path) -> anyhow::Result<String> {
    crate::output_path::check(out, crate::output_path::MARKDOWN, &[])?;
    let ctx = GpuContext::new_headless()?;
    let mut rows: Vec<(&SuiteScene, HdrImage, Vec<Cell>)> = Vec::new();
    for scene in SCENES {
        let reference = scene.reference(root)?;
        let ev = exposure(&reference);
        let mut cells = Vec::new();
        for mode in modes() {
            let Rendered { image, frame_ms, settled, settle_frames } = render(&ctx, scene, root, mode)?;
            // FLIP compares display images: expose each scene as the sheet shows it.
            let c = metrics::compare(&image, &reference, ev)?;
            let settled = Settled::of(&settled, &reference, settle_frames)?;
            cells.push(Cell {
                mode,
                flip: c.flip,
                relmse: c.relmse,
                energy: c.luminance_ratio,
                frame_ms,
                image,
                settled,
            });
            eprintln!("{}: {} FLIP {:.4} energy {:.3}", scene.name, mode.name(), c.flip, c.luminance_ratio);
        }
        rows.push((scene, reference, cells));
    }
    let mut md = String::new();
    let _ = writeln!(md, "# Quality matrix\n");
    let _ = writeln!(
        md,
        "Written by `bouncelab bench --quality` (release build). Adapter: **{}**. Every mode on every \
         scene of the suite (`src/suite/`) at {}x{} ({}x{} supersampling), against the cached \
         {}-spp path-traced reference (32768 spp for the rooms, seen from the unlit room); FLIP at the exposure that puts the reference's mean at 0.18 (`assets/suite/references/`, `bouncelab suite --references`). \
         `ism`, `sshgi` and `mrt` (temporal, or multi-bounce feedback for `mrt`, whose blocks are fitted on the fly where a scene has none) render until the technique says its history has settled (the viewport's refining indicator ends), then {SETTLED_FRAMES} frames, the last of which is compared here; `rcs` renders until its cache has filled and its bounce passes converged (at most {FILL_FRAMES} frames), then 9 frames with the warm cache; `direct` and `ism-ritschel` single frames. Energy is the \
         mean-luminance ratio to the reference; frame time is relative to `direct` on the same scene in \
         the same run (wall clock, median of the last 8 frames; `rcs`: with the warm cache in a still view, whose frames only resolve the last splat; a camera move costs the splat and placement again, `bouncelab profile`'s `moved_technique_ms`).\n",
        ctx.describe(),
        REFERENCE_SIZE.0,
        REFERENCE_SIZE.1,
        SSAA,
        SSAA,
        crate::suite::REFERENCE_SPP
    );
    let _ = writeln!(md, "| scene | what it tests | mode | FLIP | FLIP / direct | relMSE | energy | frame / direct |");
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
    for (scene, _, cells) in &rows {
        let direct = cells.iter().find(|c| c.mode == GiMode::Direct);
        let (df, dt) = direct.map_or((1.0, 1.0), |d| (d.flip, d.frame_ms));
        for c in cells {
            let _ = writeln!(
                md,
                "| {} | {} | `{}` | {:.4} | {:.2} | {:.4} | {:.3} | {:.2} |",
                scene.name,
                scene.description,
                c.mode.name(),
                c.flip,
                c.flip / df.max(1e-9),
                c.relmse,
                c.energy,
                c.frame_ms / dt.max(1e-9)
            );
        }
    }
    settled_table(&mut md, &rows);
    let sheet = out.with_file_name("quality_sheet.png");
    let _ = writeln!(
        md,
        "\n![Contact sheet: per scene, the reference then each mode; the row beneath holds each mode's signed \
         error (red too bright, blue too dark)]({})",
        sheet.file_name().and_then(|n| n.to_str()).unwrap_or("quality_sheet.png")
    );
    write_sheet(&sheet, &rows)?;
    crate::atomic_file::write(out, md.as_bytes())?;
    Ok(md)
}

/// The second table: each temporal mode's settled frames per scene.
fn settled_table(md: &mut String, rows: &[(&SuiteScene, HdrImage, Vec<Cell>)]) {
    let _ = writeln!(
        md,
        "\n## Settled frames\n\nThe temporal modes' {SETTLED_FRAMES} frames after the history has settled (after the frames the \
         technique refines for, listed; `rcs` fills its cache first and is left out), each judged on its own: the energy of the frame furthest from the \
         reference's, the spread of the frames' energies (standard deviation over mean), and `metrics::temporal`'s \
         instability against the static reference (mean absolute change of luminance between consecutive frames; 0 \
         is steady).\n"
    );
    let _ =
        writeln!(md, "| scene | mode | settled after | worst frame's energy | energy spread | temporal instability |");
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    for (scene, _, cells) in rows {
        for c in cells {
            if let Some(s) = &c.settled {
                let _ = writeln!(
                    md,
                    "| {} | `{}` | {} frames | {:.3} | {:.1}% | {:.5} |",
                    scene.name,
                    c.mode.name(),
                    s.after,
                    s.worst,
                    100.0 * s.spread,
                    s.instability
                );
            }
        }
    }
}

/// The contact sheet ([`super::sheet`]): per scene the reference and each mode, each mode's
/// signed error map beneath, every scene exposed so its reference's mean sits mid-grey.
fn write_sheet(path: &Path, rows: &[(&SuiteScene, HdrImage, Vec<Cell>)]) -> anyhow::Result<()> {
    let columns: Vec<String> =
        std::iter::once("reference".to_owned()).chain(modes().into_iter().map(|m| m.name().to_owned())).collect();
    let rows: Vec<super::sheet::SheetRow> = rows
        .iter()
        .map(|(scene, reference, cells)| {
            let view = ViewSettings { exposure_ev: exposure(reference), ..ViewSettings::default() };
            super::sheet::SheetRow {
                scene: scene.name.to_owned(),
                reference: tile(reference, &view),
                cells: cells
                    .iter()
                    .map(|c| (tile(&c.image, &view), metrics::signed_heatmap(&c.image, reference, 0.5).ok()))
                    .collect(),
            }
        })
        .collect();
    super::sheet::write(path, REFERENCE_SIZE, &columns, &rows)
}

/// `bouncelab suite`: writes the suite's glTF levels and, with `references`, path-traces and
/// caches the references of `only` (every scene when empty).
pub fn suite(root: &Path, references: bool, only: &[String]) -> anyhow::Result<String> {
    let written = crate::suite::write_levels(root)?;
    let mut out = format!("wrote {} levels under {}", written.len(), root.join("assets/suite").display());
    if references {
        for scene in SCENES.iter().filter(|s| only.is_empty() || only.iter().any(|o| o == s.name)) {
            let t = Instant::now();
            scene.render_reference(root)?;
            let _ = write!(out, "\nreference {}: {:.1} s", scene.name, t.elapsed().as_secs_f64());
            eprintln!("reference {}: {:.1} s", scene.name, t.elapsed().as_secs_f64());
        }
    }
    Ok(out)
}
