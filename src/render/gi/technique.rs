//! The seam every GI technique plugs into (docs/ARCHITECTURE.md, "The GI seam"): what a
//! technique offers the frame, the inspector, the overlays and the editor, and the typed values
//! that cross it.
//!
//! A technique is a long-lived object behind `dyn GiTechnique`. A trait object, not an enum over
//! technique structs, because the techniques share no code and own very different resources
//! (ISM's atlas, MRT's dictionary, a CPU path tracer thread): with a trait, adding one touches
//! its own folder and one row of [`super::registry::TECHNIQUES`], never a `match` in the frame,
//! the inspector or the editor. The few places that need a concrete technique (tests reading
//! ISM's VPLs) downcast through [`GiTechnique::as_any`].

use glam::Vec3;

use super::inputs::GiInputs;
use crate::image_io::HdrImage;
use crate::render::RenderError;
use crate::scene::Scene;
use crate::settings::RenderSettings;

/// What a technique wrote into the `indirect` target, which decides how the composite uses it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GiOutput {
    /// Nothing: the image is the direct term alone (`direct`, or a technique still preparing).
    Nothing,
    /// Irradiance over pi (E / pi) at each pixel: the composite multiplies by the albedo.
    IrradianceOverPi,
    /// Outgoing indirect radiance, already shaded with the pixel's BRDF: added as it is.
    Radiance,
    /// The whole image (direct light included), e.g. the reference path tracer: it replaces the
    /// direct term.
    Complete,
}

/// Why a technique's history (temporal accumulation, caches) is being reset. Techniques decide
/// what each reason invalidates; [`super::changes::ChangeDetector`] derives them from revisions
/// of the scene and the settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ResetReason {
    /// The technique became the active one.
    ModeEntered,
    /// Geometry, an object's transform, material or sampling weight changed.
    SceneEdited,
    /// A light was added, removed, moved or changed.
    LightEdited,
    /// The camera jumped (no reprojection can bridge it), or the field of view changed.
    CameraCut,
    /// The technique's own settings changed.
    SettingsChanged,
    /// The view size changed.
    Resized,
}

impl ResetReason {
    /// A short label for the editor.
    pub fn label(self) -> &'static str {
        match self {
            Self::ModeEntered => "mode entered",
            Self::SceneEdited => "scene edited",
            Self::LightEdited => "light edited",
            Self::CameraCut => "camera cut",
            Self::SettingsChanged => "settings changed",
            Self::Resized => "view resized",
        }
    }
}

/// Whether a technique can render this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Readiness {
    /// Render now.
    Ready,
    /// CPU work (a bake, a precompute) is still running off the frame; `progress` in 0..=1.
    Pending { progress: f32, what: String },
}

/// How the inspector should display a buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BufferView {
    /// Linear colour or radiance (exposure applies).
    Colour,
    /// A signed vector stored as 0.5 + 0.5 v, or octahedral normals (decoded first).
    Normal,
    /// One scalar per texel in r (false colour helps).
    Scalar,
    /// Reversed depth or a distance (auto range helps).
    Depth,
    /// Integer ids.
    Id,
    /// Bits of voxel columns: the name takes `@level,first,last` (the inspector shows a level
    /// and slice-range picker).
    Slices,
}

/// A buffer name and its `@arguments` (the slice viewer's level and slice range; "" when none).
pub fn split_buffer_name(name: &str) -> (&str, &str) {
    name.split_once('@').unwrap_or((name, ""))
}

/// One buffer the inspector can show.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BufferInfo {
    /// Name used by `--buffer` and the inspector.
    pub name: &'static str,
    /// What it holds and what it looks like when right.
    pub description: &'static str,
    /// Storage format as a user reads it (e.g. "rgba16f").
    pub format: &'static str,
    /// How to show it.
    pub view: BufferView,
}

/// A world-space marker a technique draws over the viewport (ISM's VPLs; later cache records
/// and proxy-block texels).
#[derive(Clone, Debug, PartialEq)]
pub struct OverlayPoint {
    /// Where.
    pub position: Vec3,
    /// Colour ramp parameter in 0..=1 (e.g. the bounce).
    pub tone: f32,
    /// Radius in screen points.
    pub radius: f32,
    /// An outline circle of this world radius in metres around it (a cache record's zone of
    /// influence); 0 for none.
    pub ring: f32,
}

/// A world-space line a technique draws over the viewport (MRT's blocks, links and gaps).
#[derive(Clone, Debug, PartialEq)]
pub struct OverlayLine {
    /// One end.
    pub a: Vec3,
    /// The other.
    pub b: Vec3,
    /// Colour ramp parameter in 0..=1.
    pub tone: f32,
    /// Width in screen points.
    pub width: f32,
}

/// A named set of overlay markers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    /// Shown in the viewport toolbar.
    pub name: &'static str,
    /// The markers.
    pub points: Vec<OverlayPoint>,
    /// The lines.
    pub lines: Vec<OverlayLine>,
}

/// What a technique reports about itself for the editor and tests.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TechniqueStatus {
    /// Frames accumulated since the history was last reset (0 for techniques without one).
    pub history_frames: u32,
    /// The most recent reset.
    pub last_reset: Option<ResetReason>,
    /// Every reset since the technique was created, in order (tests check exactly which).
    pub resets: Vec<ResetReason>,
    /// Named counters (uploads, rebuilds) so that tests and the editor can tell what was redone.
    pub counters: Vec<(&'static str, u64)>,
    /// A one-line progress text for the viewport (e.g. the reference's spp).
    pub progress: Option<String>,
    /// Another frame of an unchanged view would still improve the image (temporal history
    /// not yet at its steady state, progressive samples below their target). The editor stops
    /// rendering an unchanged view once this is false, so an idle editor leaves the GPU alone
    /// and a drag never waits behind a frame that changes nothing.
    pub refining: bool,
    /// Where `history_frames` stops refining (frames, or the reference's samples per pixel);
    /// 0 when the technique does not refine. The viewport shows `history_frames / this`.
    pub refine_target: u32,
}

impl TechniqueStatus {
    /// The value of counter `name` (0 when absent).
    pub fn counter(&self, name: &str) -> u64 {
        self.counters.iter().find(|(n, _)| *n == name).map_or(0, |(_, v)| *v)
    }
}

/// What the frame must provide beyond the G-buffer and the direct term.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Needs {
    /// The previous frame's final HDR image (reproject it with the motion buffer).
    pub previous_frame: bool,
    /// The shared depth/normal pyramid.
    pub pyramid: bool,
}

/// The question "can this mode run here?", answered by each technique's associated
/// `support` function through [`super::registry::TECHNIQUES`] (before the technique exists).
pub struct SupportQuery<'a> {
    /// The adapter's limits as granted to the device.
    pub limits: &'a wgpu::Limits,
    /// The device's features.
    pub features: wgpu::Features,
    /// The view size in pixels.
    pub size: (u32, u32),
    /// The settings it would run with.
    pub settings: &'a RenderSettings,
}

/// A GI technique (docs/ARCHITECTURE.md, "The GI seam"). Owns its pipelines, GPU memory and
/// history.
pub trait GiTechnique {
    /// What the frame must provide for [`GiTechnique::render`].
    fn needs(&self) -> Needs {
        Needs::default()
    }

    /// CPU work before recording (point caches, bakes) for a view of `size` pixels. Returns
    /// [`Readiness::Pending`] while long work runs elsewhere; the frame then shows direct light.
    fn prepare(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Readiness;

    /// Records the technique's passes; writes `inputs.targets.indirect` and says what it holds.
    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError>;

    /// Reads buffer `name` of the last frame; `None` if the name is not this technique's.
    fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>>;

    /// Overlays for the viewport (read back from the last frame; may cost a GPU sync).
    fn overlays(&self, _device: &wgpu::Device, _queue: &wgpu::Queue) -> Vec<Overlay> {
        Vec::new()
    }

    /// Drops the history that `reason` invalidates.
    fn reset(&mut self, reason: ResetReason);

    /// Frees every GPU allocation except pipelines (another mode became active). The next
    /// [`GiTechnique::render`] recreates what it needs.
    fn release(&mut self);

    /// Bytes of GPU memory this technique holds now (buffers and textures it created).
    fn gpu_bytes(&self) -> u64;

    /// What this technique ignores in `scene` (a light type, a material feature), as sentences
    /// for the GI panel and the CLI; empty when it handles everything.
    fn limitations(&self, _scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        Vec::new()
    }

    /// Why the last frame is not what `settings` ask for, as sentences (the technique could not
    /// do its work: a missing precomputation, a level it could not build); empty when it did.
    /// `render` refuses to write such an image unless `--allow-partial`, and the editor shows
    /// these in the GI panel.
    fn shortfalls(&self, _scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        Vec::new()
    }

    /// The inspector now shows buffer `name` (or nothing): a technique may then keep debug
    /// copies it does not make otherwise (ISM's atlas before hole filling).
    fn set_inspected(&mut self, _name: Option<&str>) {}

    /// Its status for the editor and tests.
    fn status(&self) -> TechniqueStatus;

    /// For downcasting to the concrete technique (tests, tools).
    fn as_any(&self) -> &dyn std::any::Any;
}

/// Bytes of a 2D texture with all its mips and layers.
pub fn texture_bytes(texture: &wgpu::Texture) -> u64 {
    let block = u64::from(texture.format().block_copy_size(None).unwrap_or(4));
    let layers = u64::from(texture.depth_or_array_layers());
    (0..texture.mip_level_count())
        .map(|m| u64::from((texture.width() >> m).max(1)) * u64::from((texture.height() >> m).max(1)))
        .sum::<u64>()
        * block
        * layers
}

/// Records a reset in a status: appends to the list and sets the last reason.
pub fn note_reset(status: &mut TechniqueStatus, reason: ResetReason) {
    status.last_reset = Some(reason);
    status.resets.push(reason);
    // Keep the list bounded in long editor sessions.
    if status.resets.len() > 256 {
        status.resets.drain(..128);
    }
}
