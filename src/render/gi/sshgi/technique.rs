//! The `sshgi` technique behind the GI seam: asks the frame for the shared voted depth/normal
//! pyramid, runs [`super::passes`] and returns E / pi for the composite to multiply by albedo.

use super::panorama::Panorama;
use super::passes::{Plan, Sources, SshgiPasses, ViewAxis, Visibility};
use super::temporal::TemporalPass;
use super::voxels::{VoxelParams, VoxelPass, automatic_range};
use crate::image_io::HdrImage;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::{
    BufferInfo, BufferView, GiOutput, GiTechnique, Needs, Readiness, ResetReason, SupportQuery, TechniqueStatus,
    note_reset, split_buffer_name,
};
use crate::render::{RenderError, readback};
use crate::scene::Scene;
use crate::settings::{RenderSettings, SshgiSettings};

/// An inspector entry of one level's buffer.
const fn level(name: &'static str, description: &'static str) -> BufferInfo {
    BufferInfo { name, description, format: "rgba32f", view: BufferView::Colour }
}

/// The inspector's buffers: per gather level k (0 = the start level) its illumination, its
/// gather and the up-sampled sum, and each bounce's E / pi.
pub const BUFFERS: &[BufferInfo] = &[
    level(
        "sshgi_illumination_0",
        "outgoing radiance of the start level (box average of the direct term as diffuse senders send it, `exitance`)",
    ),
    level("sshgi_illumination_1", "outgoing radiance of level 1 (2x2 box average)"),
    level("sshgi_illumination_2", "outgoing radiance of level 2"),
    level("sshgi_illumination_3", "outgoing radiance of level 3"),
    level("sshgi_gather_0", "E / pi gathered on the start level over the full disc: local colour bleeding"),
    level("sshgi_gather_1", "E / pi gathered on level 1 over its ring: broad ring-shaped blobs are right"),
    level("sshgi_gather_2", "E / pi gathered on level 2 over its ring"),
    level("sshgi_gather_3", "E / pi gathered on level 3 over its ring"),
    level("sshgi_sum_0", "levels 0.. summed by joint bilateral up-sampling: smooth, no halos at edges"),
    level("sshgi_sum_1", "levels 1.. summed by joint bilateral up-sampling"),
    level("sshgi_sum_2", "levels 2.. summed by joint bilateral up-sampling"),
    level("sshgi_bounce_1", "first bounce's E / pi at the start level (the screen's and the panorama's)"),
    level(
        "sshgi_screen_bounce",
        "first bounce's E / pi from the screen alone, before the panorama's senders join it (sshgi_bounce_1 minus this is their light)",
    ),
    level("sshgi_bounce_2", "second bounce's E / pi (reflectance x the first, gathered again)"),
    level("sshgi_bounce_3", "third bounce's E / pi"),
    level("sshgi_bounce_4", "fourth bounce's E / pi"),
    level(
        "sshgi_sky",
        "the sky's E / pi at the start level through the directions the voxels leave open (not in the paper; with a sky)",
    ),
    level(
        "sshgi_bounce_sum",
        "the bounces' and the sky's E / pi summed at the start level (before the view up-sampling)",
    ),
    level("sshgi_raw", "this frame's E / pi before the temporal blend (view resolution)"),
    level(
        "sshgi_visibility_difference",
        "first bounce's E / pi without visibility minus with it, the same samples (light the voxels block: bright under occluders and behind walls, black elsewhere; one more gather chain while shown)",
    ),
    BufferInfo {
        name: "sshgi_voxels",
        description: "solid voxelisation of the view, per pixel: r = solid share of the 128 slices, g = first solid slice, b = last (closed objects show solid cross-sections; open meshes streak to the end)",
        format: "4 x u32 per pixel",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "sshgi_voxel_slices",
        description: "voxel slice viewer: name@level,first,last (level 0 = the view's columns; default the start level, all slices): r = any solid slice in the range (their OR), g = the range's solid share, b = its first solid slice",
        format: "4 x u32 per texel",
        view: BufferView::Slices,
    },
    BufferInfo {
        name: "sshgi_voxels_start",
        description: "the voxel columns the gathers march (OR of the view's, visibility_detail levels finer than the start level), as sshgi_voxels",
        format: "4 x u32 per texel",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "sshgi_acceptance",
        description: "temporal blend: r = the history's weight (0 at disocclusions and after resets), g = bilinear taps kept",
        format: "rgba32f",
        view: BufferView::Scalar,
    },
];

/// Screen-space hierarchical GI.
pub struct SshgiTechnique {
    passes: SshgiPasses,
    /// The cube G-buffer around the camera whose senders the view does not show.
    panorama: Panorama,
    voxels: VoxelPass,
    /// The voxel level the last frame's gathers marched (`visibility_detail` finer than the start;
    /// only levels up to it are reduced).
    voxel_marched: usize,
    temporal: TemporalPass,
    status: TechniqueStatus,
    /// The visibility difference is inspected: gather the first bounce unshadowed too.
    unshadowed: bool,
    /// The last frame's view size and pyramid level count (what the start level's cap acted on).
    last_view: Option<((u32, u32), u32)>,
}

impl SshgiTechnique {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device, layouts: &crate::render::layouts::Layouts) -> Result<Self, RenderError> {
        Ok(Self {
            passes: SshgiPasses::new(device)?,
            panorama: Panorama::new(device, layouts)?,
            voxels: VoxelPass::new(device, layouts)?,
            voxel_marched: 0,
            temporal: TemporalPass::new(device)?,
            status: TechniqueStatus::default(),
            unshadowed: false,
            last_view: None,
        })
    }

    /// The voxel slices' depth range this frame: the setting, or the scene's bounds along the
    /// view axis; `None` when visibility is off or nothing lies in front.
    fn voxel_range(inputs: &GiInputs<'_>, axis: &ViewAxis) -> Option<(f32, f32)> {
        let s = &inputs.settings.sshgi;
        if !s.visibility {
            return None;
        }
        if s.voxel_range != [0.0, 0.0] {
            return Some((s.voxel_range[0], s.voxel_range[1]));
        }
        let bounds = inputs.scene.bounds()?;
        automatic_range(axis.camera, axis.forward, (bounds.min, bounds.max))
    }

    /// Needs compute with storage textures only, which every adapter the renderer runs on has.
    pub fn support(_query: &SupportQuery<'_>) -> Result<(), String> {
        Ok(())
    }

    /// The inspector's visibility difference: the unshadowed first bounce minus the shadowed one.
    fn visibility_difference(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<HdrImage, RenderError> {
        // The screen's own first bounce where the panorama joins it (the unshadowed chain has none).
        let shadowed = self.passes.buffer("sshgi_screen_bounce").or_else(|| self.passes.buffer("sshgi_bounce_1"));
        let (Some(open), Some(shadowed)) = (self.passes.buffer("sshgi_unshadowed"), shadowed) else {
            return Err(RenderError::UnknownBuffer {
                name: "sshgi_visibility_difference".into(),
                known: "render a frame with visibility on while this buffer is inspected".into(),
            });
        };
        let (mut open, shadowed) = (read_texture(device, queue, open)?, read_texture(device, queue, shadowed)?);
        for (o, s) in open.pixels.iter_mut().zip(&shadowed.pixels) {
            *o = [o[0] - s[0], o[1] - s[1], o[2] - s[2], 1.0];
        }
        Ok(open)
    }
}

/// A texture read back as RGBA floats.
fn read_texture(device: &wgpu::Device, queue: &wgpu::Queue, texture: &wgpu::Texture) -> Result<HdrImage, RenderError> {
    let pixels = readback::read_as_rgba_f32(device, queue, texture)?;
    Ok(HdrImage { width: texture.width(), height: texture.height(), pixels })
}

impl SshgiTechnique {
    /// The note that the last frame's view started coarser than `start_level` because of
    /// `max_start_texels`, naming both sizes (none when the cap did not act).
    fn capped_start(&self, settings: &SshgiSettings) -> Option<String> {
        let (view, levels) = self.last_view?;
        let start = settings.start_level_for(view, levels);
        let set = settings.start_level.min(levels.saturating_sub(1));
        (start > set).then(|| {
            let size = |l: u32| ((view.0 >> l).max(1), (view.1 >> l).max(1));
            let ((w, h), (sw, sh)) = (size(start), size(set));
            format!(
                "the {}x{} view starts its gathers at {w}x{h} texels, not {sw}x{sh}: the start level holds at most {} texels (`start level at most`), which keeps most of sshgi's cost from growing with the view; light through narrow openings is sampled coarser (the rooms at 1080p: 3% darker); turn the cap off or raise it for a final image",
                view.0, view.1, settings.max_start_texels
            )
        })
    }
}

impl GiTechnique for SshgiTechnique {
    fn needs(&self) -> Needs {
        Needs { pyramid: true, ..Needs::default() }
    }

    fn prepare(&mut self, _scene: &Scene, _settings: &RenderSettings, _size: (u32, u32)) -> Readiness {
        Readiness::Ready
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        let Some(pyramid) = inputs.pyramid.as_ref().map(|p| p.levels) else {
            return Ok(GiOutput::Nothing);
        };
        if pyramid.is_empty() {
            return Ok(GiOutput::Nothing);
        }
        let settings = inputs.settings.sshgi.clone();
        let mut plan = Plan::new(&settings, inputs.targets.size, pyramid.len() as u32);
        self.last_view = Some((inputs.targets.size, pyramid.len() as u32));
        let axis = ViewAxis::new(inputs.frame);
        let range = Self::voxel_range(inputs, &axis);
        plan.unshadowed = self.unshadowed && range.is_some();
        // The voxel level the gathers march: `visibility_detail` levels finer than the start, and
        // no finer than the columns one storage binding of the device holds.
        let finest = super::voxels::finest_level(inputs.device, inputs.targets.size);
        let level = plan.start.saturating_sub(settings.visibility_detail).max(finest);
        self.voxel_marched = level as usize;
        if let Some((near, far)) = range {
            let params = VoxelParams {
                range: [near, far, 128.0 / (far - near).max(1e-6), 0.0],
                forward: [axis.forward.x, axis.forward.y, axis.forward.z, 0.0],
            };
            let ts = inputs.timer.scope("sshgi voxelize");
            self.voxels.record(
                inputs.device,
                inputs.queue,
                inputs.encoder,
                inputs.frame_buffer,
                inputs.scene_gpu,
                inputs.targets.size,
                level + 1,
                finest,
                params,
                ts,
            );
        }
        let visibility =
            range.and_then(|range| Some(Visibility { columns: self.voxels.level(level as usize)?, range, level }));
        let panorama = if settings.panorama > 0 {
            self.panorama.record(inputs, settings.panorama, settings.hidden_senders)
        } else {
            self.panorama.release();
            None
        };
        let targets = inputs.targets;
        // The sky pass marches the voxels: without visibility the sky lights nothing (the
        // limitation says so).
        plan.sky = settings.sky_rays > 0 && visibility.is_some() && inputs.scene.has_sky();
        let sources = Sources { axis: &axis, visibility: visibility.as_ref(), panorama, sky: Some(inputs.sky) };
        if settings.temporal_weight > 0.0 {
            self.temporal.ensure(inputs.device, targets.size);
            let Some(current) = self.temporal.current() else { return Ok(GiOutput::Nothing) };
            self.passes.record(inputs, pyramid, plan, &sources, current);
            self.temporal.record(inputs, settings.temporal_weight, settings.temporal_two_tap);
        } else {
            self.passes.record(inputs, pyramid, plan, &sources, &targets.indirect);
        }
        self.status.history_frames = self.status.history_frames.saturating_add(1);
        // The history has converged when the first frame's weight a^n is below 1%.
        let a = settings.temporal_weight;
        self.status.refine_target = if a > 0.0 { (0.01f32.ln() / a.ln()).ceil() as u32 } else { 0 };
        self.status.refining = self.status.history_frames < self.status.refine_target;
        Ok(GiOutput::IrradianceOverPi)
    }

    fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>> {
        let (base, args) = split_buffer_name(name);
        if !BUFFERS.iter().any(|b| b.name == base) {
            return None;
        }
        let no_voxels =
            || RenderError::UnknownBuffer { name: name.into(), known: "render sshgi with visibility on first".into() };
        if base == "sshgi_voxel_slices" {
            let parsed =
                if args.is_empty() { Some((self.voxel_marched, 0, 127)) } else { super::voxels::parse_slices(args) };
            let Some((level, first, last)) = parsed else {
                return Some(Err(RenderError::UnknownBuffer {
                    name: name.into(),
                    known: "sshgi_voxel_slices@level,first,last with first <= last <= 127".into(),
                }));
            };
            let levels = self.voxels.level_count();
            if levels > 0 && level >= levels {
                return Some(Err(RenderError::UnknownBuffer {
                    name: name.into(),
                    known: format!("voxel levels 0..={}", levels - 1),
                }));
            }
            return Some(
                self.voxels
                    .read_slices(device, queue, level, (first, last))
                    .ok_or_else(no_voxels)
                    .and_then(|r| r.map_err(Into::into)),
            );
        }
        if base == "sshgi_visibility_difference" {
            return Some(self.visibility_difference(device, queue));
        }
        let voxel_level = match name {
            "sshgi_voxels" => Some(0),
            "sshgi_voxels_start" => Some(self.voxel_marched),
            _ => None,
        };
        if let Some(l) = voxel_level {
            return Some(
                self.voxels.read_level(device, queue, l).ok_or_else(no_voxels).and_then(|r| r.map_err(Into::into)),
            );
        }
        let texture = match name {
            "sshgi_raw" => self.temporal.raw(),
            "sshgi_acceptance" => self.temporal.acceptance(),
            _ => self.passes.buffer(name),
        };
        let Some(texture) = texture else {
            return Some(Err(RenderError::UnknownBuffer {
                name: name.into(),
                known: "render sshgi first (with enough levels and bounces for this buffer)".into(),
            }));
        };
        Some(read_texture(device, queue, texture))
    }

    fn set_inspected(&mut self, name: Option<&str>) {
        self.unshadowed = name == Some("sshgi_visibility_difference");
    }

    fn reset(&mut self, reason: ResetReason) {
        // Every reason invalidates the screen-space history: a moved light or object changes
        // the gathered light everywhere, and the paper's blend has no per-pixel confidence to
        // let it fade (ISM's has).
        note_reset(&mut self.status, reason);
        self.status.history_frames = 0;
        self.temporal.reset();
    }

    fn release(&mut self) {
        self.passes.release();
        self.panorama.release();
        self.voxels.release();
        self.temporal.release();
    }

    fn gpu_bytes(&self) -> u64 {
        self.passes.gpu_bytes() + self.panorama.gpu_bytes() + self.voxels.gpu_bytes() + self.temporal.gpu_bytes()
    }

    fn limitations(&self, scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        let emissive = scene.materials().iter().any(crate::scene::Material::emits);
        let senders = if settings.sshgi.panorama > 0
            && settings.sshgi.hidden_senders > 0
            && settings.sshgi.world_voxels > 0
        {
            "surfaces off screen send indirect light through the panorama, without indirect shadows; those hidden from the camera's position through a set of points on every surface, shadowed by the view's voxels and, where their light leaves the view or the view's voxel columns are coarser, by a grid of the surfaces' voxels in the world (which also shadows within a voxel of a surface); a point set is coarser than the screen"
        } else if settings.sshgi.panorama > 0 && settings.sshgi.hidden_senders > 0 {
            "surfaces off screen send indirect light through the panorama, without indirect shadows; those hidden from the camera's position through a set of points on every surface, whose light is lost where it leaves the view (the world grid setting follows it there); a point set is coarser than the screen"
        } else if settings.sshgi.panorama > 0 {
            "surfaces hidden from the camera's position send no indirect light (the hidden senders setting adds them); those off screen send it through the panorama, without indirect shadows"
        } else {
            "only surfaces on screen send indirect light: off-screen and hidden senders are missing (the panorama setting adds those off screen)"
        };
        let mut out = vec![
            senders.to_owned(),
            "indirect shadows come from a voxelisation of the view: occluders hidden behind others or off screen cast none, and meshes must be closed".to_owned(),
            "senders and receivers are diffuse: a glossy surface sends its lobe's share of the light spread over its hemisphere, and receives no glossy reflection of the bounce light".to_owned(),
        ];
        out.extend(self.capped_start(&settings.sshgi));
        let finest = self.voxels.first_level();
        if finest > 0 && settings.sshgi.visibility {
            out.push(format!(
                "the view's voxel columns exceed one storage buffer of this GPU: the voxelisation casts a ray per {0}x{0} pixels, so occluders thinner than that can miss the indirect shadows",
                1u32 << finest
            ));
        }
        if emissive {
            out.push(
                if settings.sshgi.panorama > 0 && settings.sshgi.hidden_senders > 0 {
                    "emissive surfaces are senders like any other: on screen and in the panorama through the direct term, hidden ones through the hidden senders' points (an emitter smaller than their spacing may be missed in a frame)".to_owned()
                } else {
                    "emissive surfaces are senders like any other (their emission is in the direct term): they light the scene only from where the camera sees them".to_owned()
                },
            );
        }
        if scene.has_sky() && settings.sshgi.sky_rays > 0 && settings.sshgi.visibility {
            out.push(
                if settings.sshgi.panorama > 0 && settings.sshgi.world_voxels > 0 {
                    "the sky lights the screen through directions the view's voxels show open (out past the scene or into a column where the camera sees the sky): a window off screen lets none onto it directly; the surfaces off screen and hidden see the sky through the world grid".to_owned()
                } else {
                    "the sky lights through directions the view's voxels show open (out past the scene or into a column where the camera sees the sky): a window or opening off screen lets none in".to_owned()
                },
            );
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
