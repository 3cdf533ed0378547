//! `ism` and `ism-ritschel` behind the technique seam: owns the VPL pass, the ISM gather and
//! screen passes, the scene sample points and their upload key, and maps the seam's reset
//! reasons onto what ISM keeps between frames.
//!
//! What each reset reason invalidates (Knecht 2009 section 3.5: the confidence already follows
//! moving lights and objects, so their edits keep the temporal history):
//! - light edited: nothing (VPLs are regenerated every frame anyway), but a still view refines
//!   past c_base (`IsmSettings::still_frames`) only once the history from before the edit has
//!   faded ([`super::stillness::refresh_frames`]);
//! - scene edited: the uploaded point data (positions, albedo) is re-checked by its key and the
//!   point distribution by its own key; the temporal history stays; as for a light edit;
//! - camera cut, settings changed, mode entered, resized: the temporal history.

use super::first_view::ViewInputs;
use super::gather::{IsmGather, MapScale, PointData};
use super::light_tiles::LightTiles;
use super::points::{mean_linear_colour, point_data, point_data_key};
use super::stillness::Stillness;
use super::vpl_pass::{GpuVpl, VplPass};
use crate::image_io::HdrImage;
use crate::precompute::open_edges::PointClips;
use crate::precompute::sample_points::SamplePoints;
use crate::render::RenderError;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::{
    BufferInfo, BufferView, GiOutput, GiTechnique, Overlay, OverlayPoint, Readiness, ResetReason, SupportQuery,
    TechniqueStatus, note_reset,
};
use crate::render::layouts::Layouts;
use crate::render::readback;
use crate::scene::Scene;
use crate::settings::{GiMode, IsmSettings, RenderSettings};

/// What the ISM sample-point distribution depends on.
#[derive(Clone, Debug, PartialEq)]
struct PointsKey {
    resources: u64,
    total: u32,
    objects: Vec<(f32, bool, [f32; 3])>,
}

/// Read-back results of the first-bounce VPL generation of the last frame.
#[derive(Clone, Debug)]
pub struct IsmVpls {
    /// The generated VPLs.
    pub vpls: Vec<GpuVpl>,
    /// Importance per light-G-buffer texel (mip 0), row-major.
    pub importance: Vec<f32>,
    /// Reflected power (rgb) and importance (a) per texel.
    pub power: Vec<[f32; 4]>,
    /// The atlas layout (which light each tile belongs to).
    pub tiles: LightTiles,
    /// The frame index the sample set was drawn for.
    pub frame: u32,
}

/// The point pool and what is derived from it once per distribution: the key it was made for,
/// the points, the textures' mean colours, each point's clip lines, and whether it lies inside
/// solid geometry and how deep the solid behind it runs (`facing::point_solids`).
type PoolPoints = (PointsKey, SamplePoints, Vec<[f32; 3]>, PointClips, crate::precompute::facing::PointSolids);

/// The ISM technique (Knecht 2009; `ism-ritschel` is the same without temporal reuse).
pub struct IsmTechnique {
    vpl_pass: VplPass,
    gather: IsmGather,
    points: Option<PoolPoints>,
    points_generation: u64,
    /// (gather buffer generation, point set generation, [`point_data_key`]) of the uploaded
    /// point data; the upload is skipped while it stays equal.
    uploaded: Option<(u64, u64, Vec<u32>)>,
    last_frame: u32,
    /// Whether the view stands still (`IsmSettings::still_frames`).
    stillness: Stillness,
    status: TechniqueStatus,
    rebuilds: u64,
    uploads: u64,
}

/// The buffers the ISM modes add to the inspector.
pub const BUFFERS: &[BufferInfo] = &[
    BufferInfo {
        name: "ism_light_albedo",
        description: "Albedo seen from the lights (every light's tiles); a = specular luminance.",
        format: "rgba8",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_light_normal",
        description: "World normals seen from the lights.",
        format: "rgba16f",
        view: BufferView::Normal,
    },
    BufferInfo {
        name: "ism_light_power",
        description: "Power each light-G-buffer texel's patch reflects (W); a = importance.",
        format: "rgba16f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_importance",
        description: "Importance (mip 0 of the warp pyramid); bright where VPLs will land.",
        format: "r32f",
        view: BufferView::Scalar,
    },
    BufferInfo {
        name: "ism_atlas",
        description: "The ISM atlas after pull-push: one paraboloid map per VPL of every bounce; 1 = empty.",
        format: "r32f",
        view: BufferView::Depth,
    },
    BufferInfo {
        name: "ism_atlas_splats",
        description: "The ISM atlas as splatted, before pull-push fills the holes (a copy made while shown).",
        format: "r32f",
        view: BufferView::Depth,
    },
    BufferInfo {
        name: "ism_split_position",
        description: "The split G-buffer's world positions (n x n tiles of the view).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_split_normal",
        description: "The split G-buffer's normals (octahedral).",
        format: "rgba16f",
        view: BufferView::Normal,
    },
    BufferInfo {
        name: "ism_raw",
        description: "Interleaved VPL shading in the split layout, before filtering (irradiance filter only; a quarter of the view when gathering at half resolution).",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_upsampled",
        description: "Half-resolution gathering: the filter's full-resolution light from the gathered samples, before the temporal merge.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_confidence",
        description: "Temporal confidence: r position, g normal, b illumination change; a = confidence.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_history",
        description: "The temporal history after this frame's merge.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_history_count",
        description: "The frames the history's average is worth (effective sample count); it caps the confidence at m / (m + 1).",
        format: "r32f",
        view: BufferView::Scalar,
    },
    BufferInfo {
        name: "ism_sh_shaded",
        description: "SH filter: outgoing indirect radiance; a = accepted taps / n^2.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_sh_dc",
        description: "SH filter: filtered DC (mean incident radiance); a = accepted taps / n^2.",
        format: "rgba32f",
        view: BufferView::Colour,
    },
    BufferInfo {
        name: "ism_sh_direction",
        description: "SH filter: band-1 luminance direction as 0.5 + 0.5 dir; a = band-2 share.",
        format: "rgba32f",
        view: BufferView::Normal,
    },
];

impl IsmTechnique {
    /// Creates the pipelines; memory comes with the first frame.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, RenderError> {
        Ok(Self {
            vpl_pass: VplPass::new(device, layouts)?,
            gather: IsmGather::new(device)?,
            points: None,
            points_generation: 0,
            uploaded: None,
            last_frame: 0,
            stillness: Stillness::default(),
            status: TechniqueStatus::default(),
            rebuilds: 0,
            uploads: 0,
        })
    }

    /// Storage buffers a pass binds at most (the bounce pass, `ism_bounce.wgsl`: 13).
    pub const STORAGE_BUFFERS: u32 = 13;

    /// The seam's support check: the bounce pass's storage buffers must be allowed, and the SH
    /// filter's coefficients must fit one storage binding.
    pub fn support(query: &SupportQuery<'_>) -> Result<(), String> {
        let have = query.limits.max_storage_buffers_per_shader_stage;
        if have < Self::STORAGE_BUFFERS {
            return Err(format!(
                "ism binds {} storage buffers in one pass; this adapter allows {have}",
                Self::STORAGE_BUFFERS
            ));
        }
        let s = &query.settings.ism;
        if s.sh_filter {
            let split = super::screen::split_size(query.size, s.interleave);
            let bytes = super::sh_filter::ShFilter::raw_bytes(split);
            let limit = query.limits.max_storage_buffer_binding_size.min(query.limits.max_buffer_size);
            if bytes > limit {
                return Err(format!(
                    "the SH filter needs {} MiB of coefficients at {}x{}, this adapter binds at most {} MiB; \
                     lower the resolution or turn the SH filter off",
                    bytes >> 20,
                    query.size.0,
                    query.size.1,
                    limit >> 20
                ));
            }
        }
        Ok(())
    }

    fn update_points(&mut self, scene: &Scene, ism: &IsmSettings) {
        let key = PointsKey {
            resources: scene.resources_revision(),
            total: ism.total_points,
            objects: scene
                .objects()
                .iter()
                .map(|o| (o.sampling_weight, o.is_rendered(), o.transform.scale.to_array()))
                .collect(),
        };
        if self.points.as_ref().is_none_or(|(k, ..)| *k != key) {
            // One stratified pool; each VPL then draws its own points from it by solid angle.
            let points = crate::precompute::sample_points::distribute(scene, ism.total_points as usize, 1, 1);
            let means = scene.resources().images.iter().map(mean_linear_colour).collect();
            // The ISMs' resolution on the surfaces, in the units the artist works in (once per
            // distribution, not per frame).
            let total = points.weighted_area.iter().sum::<f64>();
            let pool_spacing = (total / points.points.len().max(1) as f64).sqrt() as f32;
            let unseen = points.unseen_area / (points.unseen_area + total).max(1e-30);
            self.status.progress = Some(format!(
                "ism: {} points per ISM, about {:.1} deg apart, drawn from a pool of {} ({} apart); \
                 {:.0}% of the area faces nothing (no points)",
                ism.points_per_ism,
                angular_spacing(ism.points_per_ism).to_degrees(),
                points.points.len(),
                metres(pool_spacing),
                100.0 * unseen
            ));
            // Open edges to clip the splats at: the nearest of each point's own surface (a
            // splat's disk can reach across any face; a slab face has four edges), seams where
            // other geometry continues the surface within 0.2% of the scene's size excluded.
            let diameter = 2.0 * scene.bounds().map_or(1.0, |b| b.radius());
            let clips = crate::precompute::open_edges::point_clips(scene, &points.points, diameter, 0.002 * diameter);
            // Points inside solid geometry (a floor under a wall) reflect nothing: lit through
            // an ISM's hole, they would become bounce VPLs inside the wall. The depth of the
            // solid behind each point lets a lookup take the slab behind a face for occluder.
            let solids = crate::precompute::facing::point_solids(scene, &points);
            self.points = Some((key, points, means, clips, solids));
            self.points_generation += 1;
            self.rebuilds += 1;
        }
    }

    /// The first-bounce VPLs, importance and reflected power of the last frame (tests).
    pub fn read_vpls(&self, device: &wgpu::Device, queue: &wgpu::Queue, count: u32) -> Result<IsmVpls, RenderError> {
        let missing =
            || RenderError::UnknownBuffer { name: "ism vpls".into(), known: "render an ism mode first".into() };
        let (vpls, views, tiles) = (self.vpl_pass.vpls(), self.vpl_pass.views(), self.vpl_pass.tiles());
        let (Some(buffer), Some((_, _, power, importance)), Some(tiles)) = (vpls, views, tiles) else {
            return Err(missing());
        };
        let mut vpls: Vec<GpuVpl> = bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, buffer)?);
        vpls.truncate(count as usize);
        let importance = readback::read_as_rgba_f32(device, queue, importance)?.into_iter().map(|p| p[0]).collect();
        let power = readback::read_as_rgba_f32(device, queue, &power.texture)?;
        Ok(IsmVpls { vpls, importance, power, tiles: tiles.clone(), frame: self.last_frame })
    }

    /// The VPLs of every bounce of the last frame (set b at `b * vpl_count`).
    pub fn read_all_vpls(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<GpuVpl>, RenderError> {
        let buffer = self.gather.all_vpls().ok_or_else(|| RenderError::UnknownBuffer {
            name: "ism vpls".into(),
            known: "render an ism mode first".into(),
        })?;
        Ok(bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, buffer)?))
    }

    /// What the last frame's ISM lookups read (for oracles): the pool point of every VPL's
    /// slots, the pool's positions, normals and clip lines, and points per ISM.
    pub fn read_lookup_data(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<crate::precompute::ism::atlas_word::IsmLookupData, RenderError> {
        let ([chosen, points, normals, clips], per_ism) = self.gather.lookup_buffers().ok_or_else(|| {
            RenderError::UnknownBuffer { name: "ism lookup data".into(), known: "render an ism mode first".into() }
        })?;
        let read = |b: &wgpu::Buffer| readback::read_buffer(device, queue, b);
        Ok(crate::precompute::ism::atlas_word::IsmLookupData {
            chosen_all: bytemuck::pod_collect_to_vec(&read(chosen)?),
            points: bytemuck::pod_collect_to_vec(&read(points)?),
            normals: bytemuck::pod_collect_to_vec(&read(normals)?),
            clips: bytemuck::pod_collect_to_vec(&read(clips)?),
            per_ism,
        })
    }

    /// The last set's chosen points per VPL and slot: pool point (`u32::MAX`: none) and the
    /// area (m^2) it stands for, as the splats and the bounce pass read them.
    pub fn read_chosen(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<(u32, f32)>, RenderError> {
        let buffer = self.gather.chosen().ok_or_else(|| RenderError::UnknownBuffer {
            name: "ism chosen points".into(),
            known: "render an ism mode first".into(),
        })?;
        let words: Vec<[u32; 2]> = bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, buffer)?);
        Ok(words.into_iter().map(|[j, a]| (j, f32::from_bits(a))).collect())
    }

    /// The filled ISM atlas of the last frame as its raw words (`ism_pack` in
    /// `common/vpl.wgsl`), row-major, its coarse levels after it (each at side^2 +
    /// `gather::level_base`), and the finest level's side in texels.
    pub fn read_atlas_words(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(Vec<u32>, u32), RenderError> {
        self.atlas_words(device, queue, false)
    }

    /// The atlas words after hole filling, or as splatted (the inspector's copy).
    fn atlas_words(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        splats: bool,
    ) -> Result<(Vec<u32>, u32), RenderError> {
        let name = if splats { "ism_atlas_splats" } else { "ism_atlas" };
        let missing = |why: &str| RenderError::UnknownBuffer { name: name.into(), known: why.into() };
        let (atlas, coarse, side) = self.gather.atlas().ok_or_else(|| missing("render an ism mode first"))?;
        if splats {
            let buffer =
                self.gather.splats().ok_or_else(|| missing("render one ism frame while this buffer is shown"))?;
            return Ok((bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, buffer)?), side));
        }
        let mut words: Vec<u32> = bytemuck::pod_collect_to_vec(&readback::read_buffer(device, queue, atlas)?);
        words.extend(bytemuck::pod_collect_to_vec::<u8, u32>(&readback::read_buffer(device, queue, coarse)?));
        Ok((words, side))
    }

    fn read_atlas(&self, device: &wgpu::Device, queue: &wgpu::Queue, splats: bool) -> Result<HdrImage, RenderError> {
        let (words, side) = self.atlas_words(device, queue, splats)?;
        let finest = (side as usize) * (side as usize);
        Ok(HdrImage {
            width: side,
            height: side,
            pixels: words.into_iter().take(finest).map(crate::precompute::ism::atlas_word::texel).collect(),
        })
    }
}

impl GiTechnique for IsmTechnique {
    fn prepare(&mut self, scene: &Scene, settings: &RenderSettings, _size: (u32, u32)) -> Readiness {
        self.update_points(scene, &settings.ism);
        Readiness::Ready
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        let settings = &inputs.settings.ism;
        let Some((_, points, means, clips, solids)) = self.points.as_ref() else { return Ok(GiOutput::Nothing) };
        self.last_frame = inputs.frame_index;
        let recorded = self.vpl_pass.record(
            inputs.device,
            inputs.queue,
            inputs.encoder,
            inputs.scene,
            inputs.scene_gpu,
            settings,
            inputs.frame_index,
            &ViewInputs { frame: inputs.frame_buffer, depth: &inputs.targets.depth.view },
            inputs.timer.scope("ism vpls"),
        );
        let Some(vpls) = self.vpl_pass.vpls().filter(|_| recorded) else { return Ok(GiOutput::Nothing) };
        let buffers = self.gather.prepare(inputs.device, settings, points.points.len() as u32);
        let current = (buffers, self.points_generation, point_data_key(inputs.scene));
        if self.uploaded.as_ref() != Some(&current) {
            let data: PointData = point_data(inputs.scene, points, means, clips, solids);
            self.gather.upload_points(inputs.queue, &data);
            self.uploaded = Some(current);
            self.uploads += 1;
        }
        let diameter = 2.0 * inputs.scene.bounds().map_or(1.0, |b| b.radius());
        let total_area = points.weighted_area.iter().sum::<f64>() as f32;
        let scale = MapScale {
            d_max: diameter,
            // A texel without a point (pull-push filled it) is compared by depth with a margin
            // of two texels' angle at the paraboloid's centre (4 / r each) as a share of it.
            bias: [
                crate::precompute::ism::atlas_word::NEIGHBOUR_REACH,
                settings.bias_constant,
                settings.bias_slope,
                8.0 / settings.ism_resolution as f32,
            ],
            // Two depths more than 15% apart are two surfaces, not one to average, when a coarse
            // level is pulled (a 2x2 block of one surface spans that much only beyond ~67
            // degrees of incidence). It replaces Ritschel's 5% of the scene extent, which no fixed
            // length can stand for from a 20 cm diorama to a 60 m hall.
            pull_push: PULL_PUSH_RELATIVE,
            total_area,
        };
        self.gather.seed = inputs.frame_index;
        self.gather.record_maps(inputs.device, inputs.queue, inputs.encoder, vpls, &scale, settings, inputs.timer);
        // Still: the camera where it was last frame, and no light or object edited for a while.
        let camera_still = inputs.frame.clip_from_world == inputs.frame.prev_clip_from_world;
        let (blend, settle_at) = self.stillness.next(settings, self.status.history_frames, camera_still);
        let temporal = (inputs.mode == GiMode::Ism).then_some(blend);
        let exposure = inputs.settings.view.exposure_ev.exp2();
        self.gather.record_screen(
            inputs.device,
            inputs.queue,
            inputs.encoder,
            inputs.frame_buffer,
            inputs.targets,
            &scale,
            settings,
            temporal,
            exposure,
            inputs.timer,
        );
        self.status.history_frames = if temporal.is_some() { self.status.history_frames.saturating_add(1) } else { 1 };
        self.status.refine_target = if temporal.is_some() { settle_at } else { 0 };
        self.status.refining = self.status.history_frames < self.status.refine_target;
        // The SH filter shades with the full BRDF: `indirect` is outgoing radiance.
        Ok(if settings.sh_filter { GiOutput::Radiance } else { GiOutput::IrradianceOverPi })
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
        if name == "ism_atlas" || name == "ism_atlas_splats" {
            return Some(self.read_atlas(device, queue, name == "ism_atlas_splats"));
        }
        let missing = || RenderError::UnknownBuffer { name: name.into(), known: "render an ism mode first".into() };
        let sh_missing = || RenderError::UnknownBuffer {
            name: name.into(),
            known: "render an ism mode with the SH filter on first".into(),
        };
        let light = self.vpl_pass.views();
        let screen = &self.gather.screen;
        let texture: Result<&wgpu::Texture, RenderError> = match name {
            "ism_light_albedo" => light.map(|l| &l.0.texture).ok_or_else(missing),
            "ism_light_normal" => light.map(|l| &l.1.texture).ok_or_else(missing),
            "ism_light_power" => light.map(|l| &l.2.texture).ok_or_else(missing),
            "ism_importance" => light.map(|l| l.3).ok_or_else(missing),
            "ism_split_position" => screen.split_gbuffer().map(|g| &g.0.texture).ok_or_else(missing),
            "ism_split_normal" => screen.split_gbuffer().map(|g| &g.1.texture).ok_or_else(missing),
            "ism_raw" => screen.raw().map(|t| &t.texture).ok_or_else(|| RenderError::UnknownBuffer {
                name: name.into(),
                known: "render an ism mode with the irradiance filter first (the SH filter accumulates \
                        coefficients: see ism_sh_shaded, ism_sh_dc, ism_sh_direction)"
                    .into(),
            }),
            "ism_upsampled" => screen.upsampled().map(|t| &t.texture).ok_or_else(|| RenderError::UnknownBuffer {
                name: name.into(),
                known: "render an ism mode that gathers at half resolution first (shade_resolution: half, or auto \
                        from 640 x 360)"
                    .into(),
            }),
            "ism_confidence" => screen.confidence().map(|t| &t.texture).ok_or_else(missing),
            "ism_history" => screen.history().map(|t| &t.texture).ok_or_else(missing),
            "ism_history_count" => screen.history_count().map(|t| &t.texture).ok_or_else(missing),
            "ism_sh_shaded" => screen.sh_views().map(|v| &v.0.texture).ok_or_else(sh_missing),
            "ism_sh_dc" => screen.sh_views().map(|v| &v.1.texture).ok_or_else(sh_missing),
            "ism_sh_direction" => screen.sh_views().map(|v| &v.2.texture).ok_or_else(sh_missing),
            _ => Err(missing()),
        };
        Some(texture.and_then(|t| {
            let pixels = readback::read_as_rgba_f32(device, queue, t)?;
            Ok(HdrImage { width: t.width(), height: t.height(), pixels })
        }))
    }

    fn overlays(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Vec<crate::render::gi::technique::Overlay> {
        let Ok(vpls) = self.read_all_vpls(device, queue) else { return Vec::new() };
        let sets = self.gather.sets().max(1);
        let per_set = (vpls.len() as u32 / sets).max(1) as usize;
        let points = vpls
            .iter()
            .enumerate()
            .filter(|(_, v)| v.position[3] > 0.0)
            .map(|(i, v)| OverlayPoint {
                position: glam::Vec3::new(v.position[0], v.position[1], v.position[2]),
                tone: (i / per_set) as f32 / 5.0,
                radius: 2.5,
                ring: 0.0,
            })
            .collect();
        vec![Overlay { name: "VPLs", points, ..Default::default() }]
    }

    fn reset(&mut self, reason: ResetReason) {
        note_reset(&mut self.status, reason);
        match reason {
            // The confidence follows moving lights and objects (Knecht 2009 section 3.5); the
            // point data is re-checked by its keys every frame. A still view refines again only
            // once the light from before the edit has faded (`Stillness`).
            ResetReason::LightEdited | ResetReason::SceneEdited => self.stillness.edited = true,
            ResetReason::CameraCut | ResetReason::SettingsChanged | ResetReason::ModeEntered | ResetReason::Resized => {
                self.gather.screen.reset_history();
                self.status.history_frames = 0;
                self.stillness = Stillness::default();
            }
        }
    }

    fn release(&mut self) {
        self.vpl_pass.release();
        self.gather.release();
        self.uploaded = None;
        self.status.history_frames = 0;
        self.stillness = Stillness::default();
    }

    fn gpu_bytes(&self) -> u64 {
        self.vpl_pass.gpu_bytes() + self.gather.gpu_bytes()
    }

    fn limitations(&self, scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        let tiles = super::light_tiles::layout(scene);
        let mut out: Vec<String> = tiles
            .skipped
            .iter()
            .filter_map(|i| scene.lights().get(*i))
            .map(|l| format!("light {:?} adds no bounce light: the light G-buffer atlas is full", l.name))
            .collect();
        if matches!(scene.environment().sky, crate::scene::Sky::Image(_) | crate::scene::Sky::Preetham { .. })
            && scene.has_sky()
        {
            out.push(
                "the sky lights through VPLs on the scene's bounding sphere, each with the sky's radiance in its direction from the centre: away from the centre an image sky is seen with parallax (a constant sky is exact)".to_owned(),
            );
        }
        out
    }

    fn set_inspected(&mut self, name: Option<&str>) {
        // Keep a copy of the atlas before hole filling only while it is shown.
        self.gather.capture_splats = name == Some("ism_atlas_splats");
    }

    fn status(&self) -> TechniqueStatus {
        let mut s = self.status.clone();
        s.counters = vec![("point rebuilds", self.rebuilds), ("point uploads", self.uploads)];
        s
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// Pull-push threshold: the relative depth difference that separates two surfaces.
const PULL_PUSH_RELATIVE: f32 = 0.15;

/// The angular spacing of `per_ism` points spread evenly over a VPL's hemisphere,
/// sqrt(2 pi / P) radians (each VPL's own spacing, sqrt(W / P) with W the solid angle its
/// geometry subtends counted through occluders, is its `normal.w`; `ism_select.wgsl`).
fn angular_spacing(per_ism: u32) -> f32 {
    (std::f32::consts::TAU / per_ism.max(1) as f32).sqrt()
}

/// A length for the viewport's status line: metres, centimetres or millimetres.
fn metres(x: f32) -> String {
    if x >= 1.0 {
        format!("{x:.2} m")
    } else if x >= 0.01 {
        format!("{:.1} cm", x * 100.0)
    } else {
        format!("{:.1} mm", x * 1000.0)
    }
}
