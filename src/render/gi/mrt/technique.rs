//! The `mrt` technique behind the GI seam (Loos 2015): prepares the dictionary and the level off
//! the frame ([`super::job`]), uploads the level's records ([`super::pack`]) and runs the per-frame
//! passes ([`super::passes`]) into E / pi for the composite. A scene without proxy blocks gets
//! blocks fitted to its geometry, and says so.

use std::sync::Arc;

use super::job::{BuiltLevel, DictionaryJob, LevelJob};
use super::pack::Packed;
use super::passes::MrtPasses;
use crate::image_io::HdrImage;
use crate::precompute::mrt::dictionary::{Dictionary, DictionaryParams};
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::{
    BufferInfo, BufferView, GiOutput, GiTechnique, Overlay, OverlayLine, OverlayPoint, Readiness, ResetReason,
    SupportQuery, TechniqueStatus, note_reset,
};
use crate::render::{RenderError, readback};
use crate::scene::Scene;
use crate::settings::RenderSettings;

/// An atlas buffer: one row of six face tiles (canonical faces -x +x -y +y -z +z) per block.
const fn atlas(name: &'static str, description: &'static str) -> BufferInfo {
    BufferInfo { name, description, format: "rgba32f, texels^2 per face", view: BufferView::Colour }
}

/// The inspector's buffers, each described with what it looks like when right.
pub const BUFFERS: &[BufferInfo] = &[
    atlas(
        "mrt_geometry_positions",
        "geometry images: each texel's real surface position (fract of metres); one row of six face tiles per block (its canonical faces -x +x -y +y -z +z: floor third, ceiling fourth), open sides black. Smooth walls, no holes",
    ),
    BufferInfo {
        name: "mrt_geometry_normals",
        description: "geometry images' normals (facing into the block), same atlas; mostly aligned with each face",
        format: "rgba32f, texels^2 per face",
        view: BufferView::Normal,
    },
    atlas("mrt_geometry_albedo", "geometry images' albedo, same atlas (black: no real surface behind the texel)"),
    atlas(
        "mrt_direct_texels",
        "l_d: direct light (outgoing radiance) at the texels, with the feedback bounce; hot spots under lights, zero in unlit blocks without feedback",
    ),
    atlas("mrt_within_block", "U_b b: each block's indirect light from its own direct light"),
    atlas("mrt_inter_block", "U_r r: indirect light that entered through the interfaces (zero in closed blocks)"),
    atlas("mrt_lightmap", "the texels' indirect light (E / pi), within plus inter-block, before clamping at zero"),
    BufferInfo {
        name: "mrt_side_texels",
        description: "the light (E / pi) on the walls around doorways: one P x P tile per partly open block side (u across, up up), in (block, side) order; the doorway's positions read the light passing through it",
        format: "rgba32f, P^2 per side",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "mrt_b",
        description: "b = T_d->b l_d per emitting face: six rows per block (its face slots), one column per mode (rgb); energy falls off to the right",
        format: "rgb f32 per mode",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "mrt_r",
        description: "r = T_b->r b: one row per directed interface, one column per response mode",
        format: "rgb f32 per mode",
        view: BufferView::Colour,
    },
    atlas(
        "mrt_prior_error",
        "the part of this frame's direct light the block's prior cannot represent, |l_d - Q Q^T l_d| (Q spans P S): small and smooth; bright at shadow edges sharper than the training lights",
    ),
    BufferInfo {
        name: "mrt_u_b",
        description: "the dictionary's U_b per shape (n texels down, k_b modes across, a column block per shape): red positive, blue negative, each mode scaled to its peak; smooth first modes, finer later ones",
        format: "f64 matrices",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "mrt_t_db",
        description: "T_d->b per shape, transposed to the same layout as mrt_u_b (the projection of direct light onto the modes)",
        format: "f64 matrices",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "mrt_spectra",
        description: "singular values per shape (a panel each, log scale over four decades): red the direct light's (the prior's data), green the indirect transfer's, which falls far faster",
        format: "bar plot",
        view: BufferView::Colour,
    },
    atlas(
        "drt_occlusion",
        "DRT's ΔU_b b as the light it hides: per block texel, the indirect light the clutter blocks (same atlas); bright under and beside clutter, black far from it",
    ),
    atlas(
        "drt_reflection",
        "DRT's ΔU_c c: per block texel, the light the clutter's faces bounce onto it (same atlas); bright beside lit clutter faces",
    ),
    atlas(
        "drt_covered",
        "DRT's inpainting mask: block texels that clutter covers (white), which take their neighbours' light",
    ),
    BufferInfo {
        name: "drt_clutter_radiance",
        description: "clutter texels' outgoing radiance (albedo x (direct + gathered), the light DRT's ΔU_c and the other clutter read): one row of six box-face tiles (-x +x -y +y -z +z) per clutter object",
        format: "rgba32f, res^2 per face",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "drt_clutter_gather",
        description: "C_b b: the indirect light (E / pi) each clutter texel gathers from the level and the other clutter, what its pixels show; same tiles",
        format: "rgba32f, res^2 per face",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "mrt_assignment",
        description: "per pixel: r = the block it reads, g = the canonical face, b = its distance outside the block (m); a surface outside every block shows b > 0",
        format: "rgba32f",
        view: BufferView::Id,
    },
];

/// The level on the GPU and what the inspector needs of it.
struct Shown {
    packed: Packed,
    fitted: bool,
    blocks: Vec<crate::precompute::mrt::level::Block>,
    /// Each linked side's centre and the share of it that is open.
    openings: Vec<(glam::Vec3, f32)>,
    warnings: Vec<String>,
    links: usize,
    unlinked: usize,
    millis: f64,
    /// What the blocks leave out, and each link as two lines (block centre to side centre).
    gaps: Vec<crate::precompute::mrt::proxy::GapNote>,
    link_lines: Vec<(glam::Vec3, glam::Vec3)>,
}

/// The blocks' edges (fitted or the scene's), each link from a block's centre to its side, and
/// the gaps' boxes (the part of the level no block covers or links), so a partial fit shows.
fn block_overlay(s: &Shown) -> Overlay {
    let mut lines = Vec::new();
    let mut boxed = |lo: glam::Vec3, hi: glam::Vec3, tone: f32, width: f32| {
        let c = |k: usize| {
            glam::Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        };
        for (a, b) in [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)] {
            lines.push(OverlayLine { a: c(a), b: c(b), tone, width });
        }
    };
    for b in &s.blocks {
        boxed(b.origin, b.origin + b.size, 0.3, 1.0);
    }
    for g in s.gaps.iter().filter(|g| g.max != g.min) {
        boxed(g.min, g.max, 1.0, 2.5);
    }
    lines.extend(s.link_lines.iter().map(|(a, b)| OverlayLine { a: *a, b: *b, tone: 0.6, width: 2.0 }));
    Overlay { name: "MRT blocks, links (green) and gaps (red)", points: Vec::new(), lines }
}

/// Modular radiance transfer.
pub struct MrtTechnique {
    passes: MrtPasses,
    status: TechniqueStatus,
    dictionary: Option<(DictionaryParams, Arc<Dictionary>)>,
    dictionary_job: Option<DictionaryJob>,
    /// How the dictionary was obtained (loaded from / built into which file).
    dictionary_source: String,
    level_job: Option<LevelJob>,
    /// The level must be rebuilt (scene edited, depth or dictionary changed).
    level_dirty: bool,
    /// The sky and emission the texels were packed with: they are baked into the texels, so
    /// an edit of either rebuilds the level.
    emitters: crate::render::gi::changes::EmittersWatch,
    depth: usize,
    overrides: Vec<crate::settings::BlockOverride>,
    drt: crate::settings::DrtSettings,
    shown: Option<Shown>,
    /// The dictionary parameters that failed to build, and why (not retried until they change).
    dictionary_error: Option<(DictionaryParams, String)>,
    /// Why the last level could not be built (retried at the next scene edit).
    level_error: Option<String>,
    /// A new level waits for upload (its texels' light starts at zero).
    upload_pending: bool,
}

impl MrtTechnique {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device, _layouts: &crate::render::layouts::Layouts) -> Result<Self, RenderError> {
        Ok(Self {
            passes: MrtPasses::new(device)?,
            status: TechniqueStatus::default(),
            dictionary: None,
            dictionary_job: None,
            dictionary_source: String::new(),
            level_job: None,
            level_dirty: true,
            emitters: Default::default(),
            depth: 0,
            overrides: Vec::new(),
            drt: crate::settings::DrtSettings::default(),
            shown: None,
            dictionary_error: None,
            level_error: None,
            upload_pending: false,
        })
    }

    /// The last frame's per-texel buffer `which` ("l_d", "indirect" or "within"), block after
    /// block as [`Self::level`]'s records lay them out (tests, tools).
    pub fn texels(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        which: &str,
    ) -> Option<Result<Vec<[f32; 4]>, crate::render::readback::ReadbackError>> {
        self.passes.read_texels(device, queue, which)
    }

    /// The level in use: its blocks and their GPU records.
    pub fn level(&self) -> Option<(&[crate::precompute::mrt::level::Block], &Packed)> {
        self.shown.as_ref().map(|s| (s.blocks.as_slice(), &s.packed))
    }

    /// Storage buffers a pass binds at most (the reconstruction: 12).
    pub const STORAGE_BUFFERS: u32 = 12;

    /// Compute with up to [`Self::STORAGE_BUFFERS`] storage buffers in one pass.
    pub fn support(query: &SupportQuery<'_>) -> Result<(), String> {
        let have = query.limits.max_storage_buffers_per_shader_stage;
        if have < Self::STORAGE_BUFFERS {
            return Err(format!(
                "mrt binds {} storage buffers in one pass; this adapter allows {have}",
                Self::STORAGE_BUFFERS
            ));
        }
        Ok(())
    }

    /// Counts one event in the status counters.
    fn count(&mut self, name: &'static str) {
        match self.status.counters.iter_mut().find(|(n, _)| *n == name) {
            Some((_, v)) => *v += 1,
            None => self.status.counters.push((name, 1)),
        }
    }

    /// Advances the dictionary; `Some` while it is not ready.
    fn prepare_dictionary(&mut self, params: DictionaryParams) -> Option<Readiness> {
        if self.dictionary.as_ref().is_some_and(|(p, _)| *p == params) {
            // Parameters changed and changed back: stop building the other set.
            self.dictionary_job = None;
            return None;
        }
        if self.dictionary_error.as_ref().is_some_and(|(p, _)| *p == params) {
            return Some(Readiness::Ready);
        }
        if self.dictionary_job.as_ref().is_none_or(|j| j.params != params) {
            self.dictionary_job = Some(DictionaryJob::start(params));
        }
        let job = self.dictionary_job.as_ref()?;
        match job.finished() {
            Some(Ok((d, how))) => {
                self.dictionary_error = None;
                self.dictionary = Some((params, Arc::new(d)));
                self.dictionary_source = how;
                self.dictionary_job = None;
                self.level_dirty = true;
                self.count("dictionary loads");
                None
            }
            Some(Err(e)) => {
                self.dictionary_error = Some((params, format!("mrt dictionary: {e}")));
                self.dictionary_job = None;
                Some(Readiness::Ready)
            }
            None => {
                let (fraction, left) = job.progress();
                let left = left.map_or(String::new(), |s| format!(", {s:.0} s left"));
                let what = format!("mrt: preparing the dictionary ({:.0}%{left})", 100.0 * fraction);
                self.status.progress = Some(what.clone());
                self.status.refining = true;
                Some(Readiness::Pending { progress: fraction as f32, what })
            }
        }
    }

    /// Why nothing can be shown with dictionary `params`, if so.
    fn error(&self, params: &DictionaryParams) -> Option<String> {
        let dictionary = self.dictionary_error.as_ref().filter(|(p, _)| p == params).map(|(_, e)| e.clone());
        dictionary.or_else(|| self.level_error.clone())
    }

    /// Takes a finished level into use.
    fn accept(&mut self, level: BuiltLevel) {
        self.shown = Some(Shown {
            fitted: level.fitted,
            openings: level.openings,
            warnings: level.warnings,
            blocks: level.blocks,
            links: level.links,
            unlinked: level.unlinked,
            millis: level.millis,
            gaps: level.gaps,
            link_lines: level.link_lines,
            packed: level.packed,
        });
        self.level_error = None;
        self.upload_pending = true;
        self.count("level builds");
    }

    /// Lays per-texel values out as the atlas.
    fn atlas(&self, values: &[[f32; 4]]) -> Option<HdrImage> {
        Some(super::inspect::atlas(&self.shown.as_ref()?.packed, values))
    }

    /// The texel buffer `which` as an atlas.
    fn texel_atlas(&self, device: &wgpu::Device, queue: &wgpu::Queue, which: &str) -> Result<HdrImage, RenderError> {
        let values = self.passes.read_texels(device, queue, which).ok_or_else(|| not_yet(which))??;
        self.atlas(&values).ok_or_else(|| not_yet(which))
    }
}

fn not_yet(name: &str) -> RenderError {
    RenderError::UnknownBuffer { name: name.into(), known: "render mrt first (once its level is ready)".into() }
}

impl GiTechnique for MrtTechnique {
    fn prepare(&mut self, scene: &Scene, settings: &RenderSettings, _size: (u32, u32)) -> Readiness {
        let s = &settings.mrt;
        if let Some(pending) = self.prepare_dictionary(s.dictionary) {
            return pending;
        }
        let depth = s.depth as usize;
        if depth != self.depth || s.block_overrides != self.overrides || s.drt != self.drt {
            self.depth = depth;
            self.overrides = s.block_overrides.clone();
            self.drt = s.drt.clone();
            self.level_dirty = true;
        }
        if self.emitters.changed(scene) {
            self.level_dirty = true;
        }
        if let Some(job) = &self.level_job
            && let Some(result) = job.finished()
        {
            self.level_job = None;
            match result {
                Ok(level) => self.accept(level),
                Err(e) if e == super::job::CANCELLED => {}
                Err(e) => {
                    // Show nothing rather than the previous level beside the message.
                    self.level_error = Some(format!("mrt: {e}"));
                    self.shown = None;
                    self.passes.release();
                }
            }
        }
        // A new edit cancels the build in flight (its DRT rays stop at the next texel) rather
        // than queueing behind it: a drag ends with one build of where the object stopped.
        if self.level_dirty
            && let Some((_, d)) = self.dictionary.clone()
        {
            if self.level_job.take().is_some() {
                self.count("level builds cancelled");
            }
            self.level_job = Some(LevelJob::start(scene, d, depth, &self.overrides, &self.drt));
            self.level_dirty = false;
        }
        let building = self.level_job.is_some();
        // Feedback adds a bounce per frame; 16 frames leave less than 3% of an albedo-0.8 tail.
        // Set here, before the first frame of a level, so an editor that renders only while
        // this says "refining" gives the feedback its frames.
        self.status.refine_target = if s.feedback > 0.0 { 16 } else { 1 };
        self.status.refining =
            building || self.upload_pending || self.status.history_frames < self.status.refine_target;
        if let Some(e) = self.error(&s.dictionary) {
            self.status.progress = Some(e);
            return Readiness::Ready;
        }
        match &self.shown {
            Some(shown) => {
                let fitted = if shown.fitted { ", fitted (the scene has none)" } else { "" };
                let rebuilding = match &self.level_job {
                    Some(job) => {
                        let (fraction, left) = job.progress();
                        let left = left.map_or(String::new(), |s| format!(", {s:.1} s left"));
                        format!(", rebuilding ({:.0}% of the DRT rays{left})", 100.0 * fraction)
                    }
                    None => String::new(),
                };
                let drt = shown.packed.drt.as_ref().map_or(String::new(), |d| {
                    format!(", {} clutter objects (DRT built in {:.0} ms)", d.clutter.len(), d.millis)
                });
                self.status.progress =
                    Some(format!("mrt: {} blocks{fitted}, {} links{drt}{rebuilding}", shown.blocks.len(), shown.links));
                Readiness::Ready
            }
            None => {
                let fitting = !scene.objects().iter().any(|o| o.role == crate::scene::ObjectRole::ProxyBlock);
                let what = if fitting {
                    "mrt: building the level (fitting proxy blocks: the scene has none)"
                } else {
                    "mrt: building the level"
                }
                .to_owned();
                self.status.progress = Some(what.clone());
                Readiness::Pending { progress: 0.0, what }
            }
        }
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        if let Some(shown) = &self.shown
            && (!self.passes.has_level() || self.upload_pending)
        {
            self.passes.upload(inputs.device, &shown.packed);
            self.count("uploads");
            self.upload_pending = false;
            self.status.history_frames = 0;
        }
        let m = &inputs.settings.mrt;
        let (feedback, padding) = (m.feedback, m.padding);
        if !self.passes.record(inputs, feedback, padding) {
            // No level to light (no enclosed space was fitted): there is nothing to refine, so
            // an editor that renders while "refining" stops.
            self.status.history_frames = self.status.refine_target;
            return Ok(GiOutput::Nothing);
        }
        self.status.history_frames = self.status.history_frames.saturating_add(1);
        Ok(GiOutput::IrradianceOverPi)
    }

    fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>> {
        if !BUFFERS.iter().any(|b| b.name == name) {
            return None;
        }
        let shown = self.shown.as_ref();
        let geometry = |f: &dyn Fn(&super::pack::GpuTexel) -> [f32; 4]| {
            let values: Vec<[f32; 4]> = shown.map_or(Vec::new(), |s| s.packed.texels.iter().map(f).collect());
            self.atlas(&values).ok_or_else(|| not_yet(name))
        };
        Some(match name {
            "mrt_geometry_positions" => geometry(&|t| {
                let p = t.position;
                [p[0].rem_euclid(1.0), p[1].rem_euclid(1.0), p[2].rem_euclid(1.0), 1.0]
            }),
            "mrt_geometry_normals" => geometry(&|t| {
                let n = t.normal;
                [0.5 + 0.5 * n[0], 0.5 + 0.5 * n[1], 0.5 + 0.5 * n[2], 1.0]
            }),
            "mrt_geometry_albedo" => geometry(&|t| t.albedo),
            "mrt_direct_texels" => self.texel_atlas(device, queue, "l_d"),
            "mrt_within_block" => self.texel_atlas(device, queue, "within"),
            "mrt_lightmap" => self.texel_atlas(device, queue, "indirect"),
            "drt_occlusion" | "drt_reflection" => self.texel_atlas(device, queue, name),
            "drt_covered" => (|| {
                // A level without clutter shows black.
                let empty = super::drt_pack::DrtPacked::default();
                let d = shown.ok_or_else(|| not_yet(name))?.packed.drt.as_ref().unwrap_or(&empty);
                let mask: Vec<[f32; 4]> =
                    d.covered.iter().map(|c| if *c { [1.0, 1.0, 1.0, 1.0] } else { [0.0, 0.0, 0.0, 1.0] }).collect();
                self.atlas(&mask).ok_or_else(|| not_yet(name))
            })(),
            "drt_clutter_radiance" | "drt_clutter_gather" => (|| {
                let empty = super::drt_pack::DrtPacked::default();
                let d = shown.ok_or_else(|| not_yet(name))?.packed.drt.as_ref().unwrap_or(&empty);
                let which = if name == "drt_clutter_radiance" { "clutter_radiance" } else { "clutter_gather" };
                let values = self.passes.read_texels(device, queue, which).ok_or_else(|| not_yet(name))??;
                Ok(super::inspect::clutter_tiles(d, &values))
            })(),
            "mrt_side_texels" => (|| {
                let s = shown.ok_or_else(|| not_yet(name))?;
                let values = self.passes.read_texels(device, queue, "sides").ok_or_else(|| not_yet(name))??;
                Ok(super::inspect::side_tiles(&s.packed, &values))
            })(),
            "mrt_inter_block" => (|| {
                let all = self.passes.read_texels(device, queue, "indirect").ok_or_else(|| not_yet(name))??;
                let own = self.passes.read_texels(device, queue, "within").ok_or_else(|| not_yet(name))??;
                let diff: Vec<[f32; 4]> =
                    all.iter().zip(&own).map(|(a, o)| [a[0] - o[0], a[1] - o[1], a[2] - o[2], 1.0]).collect();
                self.atlas(&diff).ok_or_else(|| not_yet(name))
            })(),
            "mrt_u_b" | "mrt_t_db" | "mrt_spectra" => {
                let Some((_, d)) = &self.dictionary else { return Some(Err(not_yet(name))) };
                Ok(match name {
                    "mrt_u_b" => super::inspect::matrices(d, false),
                    "mrt_t_db" => super::inspect::matrices(d, true),
                    _ => super::inspect::spectra(d),
                })
            }
            "mrt_prior_error" => (|| {
                let s = shown.ok_or_else(|| not_yet(name))?;
                let Some((_, d)) = &self.dictionary else { return Err(not_yet(name)) };
                let l_d = self.passes.read_texels(device, queue, "l_d").ok_or_else(|| not_yet(name))??;
                let error = super::inspect::prior_error(d, &s.packed, &s.blocks, &l_d);
                self.atlas(&error).ok_or_else(|| not_yet(name))
            })(),
            "mrt_b" | "mrt_r" => (|| {
                let p = &shown.ok_or_else(|| not_yet(name))?.packed;
                let which = if name == "mrt_b" { "b" } else { "r" };
                let values = self.passes.read_coefficients(device, queue, which).ok_or_else(|| not_yet(name))??;
                let (rows, cols) =
                    if which == "b" { (6 * p.blocks.len(), p.k_b as usize) } else { (p.slots.len(), p.k_r as usize) };
                Ok(super::inspect::coefficients(&values, rows, cols))
            })(),
            _ => (|| {
                let texture = self.passes.assignment().ok_or_else(|| not_yet(name))?;
                let pixels = readback::read_as_rgba_f32(device, queue, texture)?;
                Ok(HdrImage { width: texture.width(), height: texture.height(), pixels })
            })(),
        })
    }

    fn overlays(&self, _device: &wgpu::Device, _queue: &wgpu::Queue) -> Vec<Overlay> {
        let Some(s) = &self.shown else { return Vec::new() };
        let openings = s
            .openings
            .iter()
            .map(|(p, share)| OverlayPoint { position: *p, tone: *share, radius: 7.0, ring: 0.0 })
            .collect();
        let texels = s
            .packed
            .texels
            .iter()
            .filter(|t| t.position[3] > 0.5)
            .map(|t| OverlayPoint {
                position: glam::Vec3::from_slice(&t.position[..3]),
                tone: 0.0,
                radius: 1.5,
                ring: 0.0,
            })
            .collect();
        vec![
            block_overlay(s),
            Overlay { name: "MRT openings (tone: open share)", points: openings, ..Default::default() },
            Overlay { name: "MRT texels (geometry images)", points: texels, ..Default::default() },
        ]
    }

    fn reset(&mut self, reason: ResetReason) {
        note_reset(&mut self.status, reason);
        self.status.history_frames = 0;
        match reason {
            ResetReason::SceneEdited | ResetReason::ModeEntered => self.level_dirty = true,
            // A light edit changes l_d, which every frame recomputes; the feedback's bounces
            // follow within a few frames.
            _ => {}
        }
    }

    fn release(&mut self) {
        self.passes.release();
        self.level_job = None;
        self.dictionary_job = None;
    }

    fn gpu_bytes(&self) -> u64 {
        self.passes.gpu_bytes()
    }

    fn shortfalls(&self, _scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        self.error(&settings.mrt.dictionary).map(|e| format!("no indirect light: {e}")).into_iter().collect()
    }

    fn limitations(&self, _scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        let mut out = vec![
            "indirect light is diffuse; objects inside blocks shadow and reflect it only as clutter (delta radiance transfer: small objects found automatically or marked clutter)".to_owned(),
            "geometry images read materials' base colour factors, not their textures".to_owned(),
        ];
        if let Some(s) = &self.shown {
            if s.fitted {
                out.insert(
                    0,
                    format!(
                        "the scene has no proxy blocks: {} were fitted to its geometry (Fit proxy blocks adds them to the scene for editing)",
                        s.blocks.len()
                    ),
                );
            }
            out.extend(s.warnings.iter().cloned());
            if s.unlinked > 0 {
                out.push(format!(
                    "{} open block sides lead to no other block: light leaving there is lost",
                    s.unlinked
                ));
            }
            if let Some(d) = &s.packed.drt {
                out.push(format!(
                    "drt: {} clutter objects ({} found automatically, {} marked), {} clutter texels, {} covered block texels inpainted, {} operator rows with {} entries ({:.1} MB), {:.2} M rays traced, built in {:.0} ms",
                    d.clutter.len(),
                    d.automatic,
                    d.marked,
                    d.texels.len(),
                    d.covered.iter().filter(|c| **c).count(),
                    d.rows.len(),
                    d.entries.len(),
                    d.bytes() as f64 / 1e6,
                    d.traced as f64 / 1e6,
                    d.millis
                ));
            }
            out.push(format!(
                "level: {} blocks, {} links, {} texels ({} on real surfaces), {:.0} ms to build, {:.1} MB on the GPU; dictionary {}",
                s.blocks.len(),
                s.links,
                s.packed.texels.len(),
                s.packed.surfaces_found,
                s.millis,
                s.packed.bytes() as f64 / 1e6,
                self.dictionary_source
            ));
        }
        out
    }

    fn status(&self) -> TechniqueStatus {
        self.status.clone()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
