//! The screen-space half of the ISM technique: the split G-buffer (P9), interleaved VPL
//! shading (P10) or Segovia & Wald's SH projection, the SH filter with per-pixel BRDF
//! evaluation, the temporal merge with its confidence (P12) and the geometry-aware filter
//! (P13; labels as in docs/ARCHITECTURE.md, "ISM pass labels"), or, when the shading gathers
//! at half resolution, [`super::upsample`]'s filter before the merge. The VPL sets and
//! imperfect shadow maps it reads come from [`super::gather`].

use crate::render::layouts::{compute_pipeline, storage_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, ViewTargets, formats};
use crate::settings::IsmSettings;

use super::params::{FilterParams, ShadeParams, SplitParams, TemporalParams};
use super::sh_filter::ShFilter;
use super::upsample::{Gathered, IsmUpsample, gathered_size};
use crate::render::gi::technique::texture_bytes;

fn size_of<T>() -> u64 {
    std::mem::size_of::<T>() as u64
}

/// What the screen passes read from the ISM stage of this frame.
pub struct IsmInputs<'a> {
    /// VPLs of every set (set b at `b * vpl_count`).
    pub vpls: &'a wgpu::Buffer,
    /// The finest ISM atlas level (`ism_pack` words).
    pub atlas: &'a wgpu::Buffer,
    /// Its coarse levels (`gather::level_base`), which the lookups ask about holes.
    pub coarse: &'a wgpu::Buffer,
    /// Pool point positions, normals and clip lines, and per VPL of every set and slot the
    /// pool point (what `ism_lookup.wgsl` tests a receiver's ray against).
    pub points: &'a wgpu::Buffer,
    pub normals: &'a wgpu::Buffer,
    pub clips: &'a wgpu::Buffer,
    pub chosen_all: &'a wgpu::Buffer,
    /// Pool point albedo, whose w the view-importance pass writes (`ism_view_importance.wgsl`).
    pub albedo: &'a wgpu::Buffer,
    /// The bounce tail's state, to which the shading adds the last two sets' screen sums.
    pub tail: &'a wgpu::Buffer,
    /// Points per ISM.
    pub per_ism: u32,
    /// Points in the pool.
    pub pool_points: u32,
    /// Changes whenever `vpls` or `atlas` were recreated.
    pub generation: u64,
    /// VPLs per set.
    pub vpl_count: u32,
    /// VPL sets (bounces).
    pub sets: u32,
    /// ISM side r.
    pub r: u32,
    /// ISM tiles per atlas row.
    pub tiles_per_row: u32,
    /// Scene diameter (the ISM depth normalisation and the filters' depth range), metres.
    pub d_max: f32,
    /// ISM lookup: neighbour reach (`ism_lit`), normal-offset constant and slope factors (`ism_offset_point`), the
    /// relative depth margin of texels without a point (`ism_lookup.wgsl`).
    pub bias: [f32; 4],
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    view: (u32, u32),
    n: u32,
    sh: bool,
    /// The gathering step (`ShadeResolution::scale`).
    step: u32,
    generation: u64,
}

/// View-sized resources.
/// The temporal merge's targets and bind groups ([`IsmScreen::ensure`]).
struct Temporal {
    history: [Target; 2],
    count: [Target; 2],
    confidence: Target,
    prev_normal: Target,
    filter_groups: [wgpu::BindGroup; 3],
    temporal_groups: [wgpu::BindGroup; 2],
}

struct Sized {
    key: Key,
    split_position: Target,
    split_normal: Target,
    raw: Target,
    split_group: wgpu::BindGroup,
    shade_group: wgpu::BindGroup,
    history: [Target; 2],
    /// The histories' effective sample counts (`ism_temporal.wgsl`), ping-pong like `history`.
    count: [Target; 2],
    prev_normal: Target,
    confidence: Target,
    /// Temporal merge reading history[p], writing history[1 - p].
    temporal_groups: [wgpu::BindGroup; 2],
    /// Filter input: 0 = raw (no temporal reuse), 1 + p = history[p].
    filter_groups: [wgpu::BindGroup; 3],
    /// The view-importance pass over the pool points.
    importance_group: wgpu::BindGroup,
    /// With a gathering step over 1: the filtered light the temporal merge reads, and the
    /// filter's bind groups writing it (0) or the view's indirect target (1, no temporal reuse).
    upsampled: Option<(Target, [wgpu::BindGroup; 2])>,
}

/// The temporal merge's blend for one frame (`ism_temporal.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// The confidence's cap: `c_base`, or 1 - 1 / `still_frames` while nothing moves.
    pub confidence_cap: f32,
    /// The illumination change's weight: `w_illumination`, or 0 while nothing moves (no light
    /// changed, and the term would only let VPL noise's bright frames through).
    pub w_illumination: f32,
}

/// Pipelines and view-sized resources of the ISM screen passes.
pub struct IsmScreen {
    split_layout: wgpu::BindGroupLayout,
    split: wgpu::ComputePipeline,
    split_params: wgpu::Buffer,
    shade_layout: wgpu::BindGroupLayout,
    shade: wgpu::ComputePipeline,
    project_sh: wgpu::ComputePipeline,
    shade_params: wgpu::Buffer,
    sh: ShFilter,
    temporal_layout: wgpu::BindGroupLayout,
    temporal: wgpu::ComputePipeline,
    temporal_params: wgpu::Buffer,
    filter_layout: wgpu::BindGroupLayout,
    filter: wgpu::ComputePipeline,
    filter_params: wgpu::Buffer,
    upsample: IsmUpsample,
    importance_layout: wgpu::BindGroupLayout,
    view_importance: wgpu::ComputePipeline,
    parity: usize,
    reset: bool,
    sized: Option<Sized>,
}

pub(super) fn uniform(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

pub(super) fn buf(b: u32, x: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding: b, resource: x.as_entire_binding() }
}

pub(super) use crate::render::layouts::view_entry as tex;

/// Size of the split layout: n x n blocks of ceil(W / n) x ceil(H / n) (common/interleave.wgsl).
pub fn split_size(view: (u32, u32), n: u32) -> (u32, u32) {
    let n = n.max(1);
    (view.0.div_ceil(n) * n, view.1.div_ceil(n) * n)
}

impl IsmScreen {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let depth = wgpu::TextureSampleType::Depth;
        let split_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism split layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, depth),
                texture_entry(3, c, unfilterable),
                storage_texture_entry(4, formats::HDR),
                storage_texture_entry(5, formats::NORMAL),
            ],
        });
        let split_module = shaders::module(device, "render/gi/ism/ism_split.wgsl")?;
        let shade_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism shade layout"),
            entries: &[
                uniform_entry(0, c, false),
                storage_entry(1, c),
                storage_entry(2, c),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                storage_texture_entry(5, formats::HDR),
                super::gather::storage_rw(6),
                storage_entry(7, c),
                storage_entry(8, c),
                storage_entry(9, c),
                storage_entry(10, c),
                super::gather::storage_rw(11),
                storage_entry(12, c),
            ],
        });
        let shade_module = shaders::module(device, "render/gi/ism/ism_shade.wgsl")?;
        let filter_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism filter layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, unfilterable),
                texture_entry(3, c, depth),
                texture_entry(4, c, unfilterable),
                storage_texture_entry(5, formats::HDR),
            ],
        });
        let filter_module = shaders::module(device, "render/gi/ism/ism_filter.wgsl")?;
        let temporal_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism temporal layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, unfilterable),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, depth),
                texture_entry(5, c, unfilterable),
                texture_entry(6, c, unfilterable),
                texture_entry(7, c, unfilterable),
                storage_texture_entry(8, formats::HDR),
                storage_texture_entry(9, formats::HDR),
                texture_entry(10, c, unfilterable),
                storage_texture_entry(11, wgpu::TextureFormat::R32Float),
            ],
        });
        let temporal_module = shaders::module(device, "render/gi/ism/ism_temporal.wgsl")?;
        let importance_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism view importance layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, depth),
                storage_entry(2, c),
                storage_entry(3, c),
                super::gather::storage_rw(4),
            ],
        });
        let importance_module = shaders::module(device, "render/gi/ism/ism_view_importance.wgsl")?;
        Ok(Self {
            view_importance: compute_pipeline(
                device,
                "ism view importance",
                &importance_layout,
                &importance_module,
                "view_importance",
            ),
            importance_layout,
            split: compute_pipeline(device, "ism split g-buffer", &split_layout, &split_module, "cs_main"),
            split_params: uniform(device, "ism split params", size_of::<SplitParams>()),
            split_layout,
            shade: compute_pipeline(device, "ism shade", &shade_layout, &shade_module, "shade"),
            project_sh: compute_pipeline(device, "ism sh projection", &shade_layout, &shade_module, "project_sh"),
            shade_params: uniform(device, "ism shade params", size_of::<ShadeParams>()),
            shade_layout,
            sh: ShFilter::new(device)?,
            temporal: compute_pipeline(device, "ism temporal merge", &temporal_layout, &temporal_module, "cs_main"),
            temporal_params: uniform(device, "ism temporal params", size_of::<TemporalParams>()),
            temporal_layout,
            filter: compute_pipeline(device, "ism filter", &filter_layout, &filter_module, "cs_main"),
            filter_params: uniform(device, "ism filter params", size_of::<FilterParams>()),
            filter_layout,
            upsample: IsmUpsample::new(device)?,
            parity: 0,
            reset: true,
            sized: None,
        })
    }

    /// Creates the view-sized targets and bind groups for `key` (the split G-buffer, shading,
    /// temporal merge, filter and view importance), unless the current ones already fit it.
    fn ensure(
        &mut self,
        device: &wgpu::Device,
        key: Key,
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
        ism: &IsmInputs<'_>,
    ) {
        if self.sized.as_ref().is_some_and(|s| s.key == key) {
            return;
        }
        let split = split_size(gathered_size(key.view, key.step), key.n);
        let [split_position, split_normal, raw] = Self::split_targets(device, split);
        let upsampled = (key.step > 1).then(|| {
            let gathered = Gathered { position: &split_position, normal: &split_normal, raw: &raw };
            self.upsample_stage(device, key, frame_buffer, targets, &gathered)
        });
        let temporal_input = upsampled.as_ref().map(|(t, _)| t);
        if key.sh {
            self.sh.ensure(device, split, frame_buffer, targets);
        }
        let split_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism split bind group"),
            layout: &self.split_layout,
            entries: &[
                buf(0, frame_buffer),
                buf(1, &self.split_params),
                tex(2, &targets.depth.view),
                tex(3, &targets.normal.view),
                tex(4, &split_position.view),
                tex(5, &split_normal.view),
            ],
        });
        let shade_group = self.shade_group(device, key, ism, [&split_position, &split_normal, &raw]);
        let temporal = self.temporal_stage(device, key, frame_buffer, targets, temporal_input.unwrap_or(&raw));
        let importance_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism view importance bind group"),
            layout: &self.importance_layout,
            entries: &[
                buf(0, frame_buffer),
                tex(1, &targets.depth.view),
                buf(2, ism.points),
                buf(3, ism.normals),
                buf(4, ism.albedo),
            ],
        });
        let Temporal { history, count, confidence, prev_normal, filter_groups, temporal_groups } = temporal;
        self.reset = true;
        self.sized = Some(Sized {
            key,
            split_position,
            split_normal,
            raw,
            split_group,
            shade_group,
            history,
            count,
            prev_normal,
            confidence,
            temporal_groups,
            filter_groups,
            importance_group,
            upsampled,
        });
    }

    /// The filtered light of half-resolution gathering and the filter's two bind groups
    /// (writing it, or the view's indirect target).
    fn upsample_stage(
        &self,
        device: &wgpu::Device,
        key: Key,
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
        gathered: &Gathered<'_>,
    ) -> (Target, [wgpu::BindGroup; 2]) {
        use wgpu::TextureUsages as U;
        let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let target = Target::new(device, "ism upsampled", key.view, formats::HDR, usage);
        let groups = [
            self.upsample.bind_group(device, frame_buffer, gathered, targets, &target.view),
            self.upsample.bind_group(device, frame_buffer, gathered, targets, &targets.indirect.view),
        ];
        (target, groups)
    }

    /// The split G-buffer's positions and normals and the split accumulation, at `split`.
    fn split_targets(device: &wgpu::Device, split: (u32, u32)) -> [Target; 3] {
        use wgpu::TextureUsages as U;
        let rw = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        [
            Target::new(device, "ism split positions", split, formats::HDR, rw),
            Target::new(device, "ism split normals", split, formats::NORMAL, rw),
            Target::new(device, "ism split accumulation", split, formats::HDR, rw),
        ]
    }

    /// The shading pass's bind group: the VPLs, the atlas and its lookups' buffers, the split
    /// G-buffer and accumulation (`split`: positions, normals, accumulation), and the SH
    /// projection when the SH filter is on (a 16-byte stand-in otherwise).
    fn shade_group(
        &self,
        device: &wgpu::Device,
        key: Key,
        ism: &IsmInputs<'_>,
        split: [&Target; 3],
    ) -> wgpu::BindGroup {
        let dummy;
        let sh_buffer = match self.sh.raw().filter(|_| key.sh) {
            Some(b) => b,
            None => {
                dummy = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("ism sh projection (unused)"),
                    size: 16,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                });
                &dummy
            }
        };
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism shade bind group"),
            layout: &self.shade_layout,
            entries: &[
                buf(0, &self.shade_params),
                buf(1, ism.vpls),
                buf(2, ism.atlas),
                tex(3, &split[0].view),
                tex(4, &split[1].view),
                tex(5, &split[2].view),
                buf(6, sh_buffer),
                buf(7, ism.points),
                buf(8, ism.normals),
                buf(9, ism.clips),
                buf(10, ism.chosen_all),
                buf(11, ism.tail),
                buf(12, ism.coarse),
            ],
        })
    }

    /// The temporal merge's history (ping-pong), confidence and previous normals, with the
    /// filter's and the merge's bind groups; the merge reads `raw` (the split accumulation, or
    /// the half-resolution gathering's filtered light), or the SH-shaded radiance.
    fn temporal_stage(
        &self,
        device: &wgpu::Device,
        key: Key,
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
        raw: &Target,
    ) -> Temporal {
        use wgpu::TextureUsages as U;
        let rw = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let history = [
            Target::new(device, "ism history a", key.view, formats::HDR, rw),
            Target::new(device, "ism history b", key.view, formats::HDR, rw),
        ];
        let count = [
            Target::new(device, "ism history count a", key.view, wgpu::TextureFormat::R32Float, rw),
            Target::new(device, "ism history count b", key.view, wgpu::TextureFormat::R32Float, rw),
        ];
        let confidence = Target::new(device, "ism confidence", key.view, formats::HDR, rw);
        let prev_normal = Target::new(
            device,
            "ism previous normals",
            key.view,
            formats::NORMAL,
            U::TEXTURE_BINDING | U::COPY_DST | U::COPY_SRC,
        );
        let filter_group = |input: &wgpu::TextureView| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("ism filter bind group"),
                layout: &self.filter_layout,
                entries: &[
                    buf(0, frame_buffer),
                    buf(1, &self.filter_params),
                    tex(2, input),
                    tex(3, &targets.depth.view),
                    tex(4, &targets.normal.view),
                    tex(5, &targets.indirect.view),
                ],
            })
        };
        let filter_groups = [filter_group(&raw.view), filter_group(&history[0].view), filter_group(&history[1].view)];
        let new_input = self.sh.shaded().filter(|_| key.sh).map_or(&raw.view, |t| &t.view);
        let temporal_group = |p: usize| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("ism temporal bind group"),
                layout: &self.temporal_layout,
                entries: &[
                    buf(0, frame_buffer),
                    buf(1, &self.temporal_params),
                    tex(2, new_input),
                    tex(3, &history[p].view),
                    tex(4, &targets.depth.view),
                    tex(5, &targets.normal.view),
                    tex(6, &prev_normal.view),
                    tex(7, &targets.motion.view),
                    tex(8, &history[1 - p].view),
                    tex(9, &confidence.view),
                    tex(10, &count[p].view),
                    tex(11, &count[1 - p].view),
                ],
            })
        };
        let temporal_groups = [temporal_group(0), temporal_group(1)];
        Temporal { history, count, confidence, prev_normal, filter_groups, temporal_groups }
    }

    /// Drops the temporal history (the next frame uses only new VPLs).
    pub fn reset_history(&mut self) {
        self.reset = true;
    }

    /// Frees every view-sized buffer (another mode is active); the history restarts.
    pub fn release(&mut self) {
        self.sized = None;
        self.sh.release();
        self.reset = true;
    }

    /// Bytes of GPU memory held by the view-sized resources.
    pub fn gpu_bytes(&self) -> u64 {
        let own = self.sized.as_ref().map_or(0, |s| {
            [
                &s.split_position,
                &s.split_normal,
                &s.raw,
                &s.history[0],
                &s.history[1],
                &s.count[0],
                &s.count[1],
                &s.prev_normal,
                &s.confidence,
            ]
            .iter()
            .map(|t| texture_bytes(&t.texture))
            .sum::<u64>()
                + s.upsampled.as_ref().map_or(0, |(t, _)| texture_bytes(&t.texture))
        });
        own + self.sh.gpu_bytes()
    }

    /// The confidence buffer of the last temporal frame: r = position change, g = normal
    /// change, b = illumination change (each saturated), a = confidence.
    pub fn confidence(&self) -> Option<&Target> {
        self.sized.as_ref().map(|s| &s.confidence)
    }

    /// The history written by the last temporal frame.
    pub fn history(&self) -> Option<&Target> {
        self.sized.as_ref().map(|s| &s.history[self.parity])
    }

    /// The effective sample count of that history, per pixel (`ism_temporal.wgsl`).
    pub fn history_count(&self) -> Option<&Target> {
        self.sized.as_ref().map(|s| &s.count[self.parity])
    }

    /// The split accumulation buffer (the unfiltered interleaved result in the split layout);
    /// `None` with the SH filter, which accumulates SH coefficients instead.
    pub fn raw(&self) -> Option<&Target> {
        self.sized.as_ref().filter(|s| !s.key.sh).map(|s| &s.raw)
    }

    /// Half-resolution gathering's filtered light, before the temporal merge.
    pub fn upsampled(&self) -> Option<&Target> {
        self.sized.as_ref().and_then(|s| s.upsampled.as_ref()).map(|(t, _)| t)
    }

    /// The split G-buffer: world positions and octahedral normals.
    pub fn split_gbuffer(&self) -> Option<(&Target, &Target)> {
        self.sized.as_ref().map(|s| (&s.split_position, &s.split_normal))
    }

    /// The SH filter's views of the last SH frame: (shaded, DC, band-1 direction).
    pub fn sh_views(&self) -> Option<(&Target, &Target, &Target)> {
        self.sized.as_ref().filter(|s| s.key.sh).and_then(|_| self.sh.views())
    }

    /// Records the screen passes into `targets.indirect` (E / pi for the composite to multiply
    /// by albedo, or outgoing radiance when `settings.sh_filter` is on). `temporal` is the
    /// temporal merge's blend; `None` renders without temporal reuse (`ism-ritschel`).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
        ism: &IsmInputs<'_>,
        settings: &IsmSettings,
        temporal: Option<Blend>,
        exposure: f32,
        timer: &mut crate::render::timing::GpuTimer,
    ) {
        let blend = temporal.unwrap_or(Blend { confidence_cap: 0.0, w_illumination: 0.0 });
        let temporal = temporal.is_some();
        let n = settings.interleave.max(1);
        let step = settings.shade_resolution.scale(targets.size, settings.sh_filter);
        let key = Key { view: targets.size, n, sh: settings.sh_filter, step, generation: ism.generation };
        self.ensure(device, key, frame_buffer, targets, ism);
        let Some(s) = &self.sized else { return };
        let d_min = settings.clamp_distance;
        let (w, h) = targets.size;
        let gathered = gathered_size(targets.size, step);
        queue.write_buffer(&self.split_params, 0, bytemuck::bytes_of(&SplitParams { counts: [n, step, 0, 0] }));
        let shade = ShadeParams {
            counts: [ism.vpl_count, ism.r, ism.tiles_per_row, n],
            params: [1.0 / ism.d_max, 0.0, d_min * d_min, settings.clamp_disk],
            sets: [ism.sets, gathered.0, gathered.1, ism.per_ism],
            bias: ism.bias,
        };
        queue.write_buffer(&self.shade_params, 0, bytemuck::bytes_of(&shade));
        let reset = u32::from(self.reset || !temporal);
        // The SH path and half-resolution gathering filter before the merge, which then reads
        // the view's layout.
        let filtered_first = settings.sh_filter || s.upsampled.is_some();
        let raw_split = if filtered_first { 0 } else { n };
        let merge = TemporalParams {
            flags: [reset, raw_split, 0, 0],
            weights: [settings.base_confidence, settings.w_position, settings.w_normal, blend.w_illumination],
            params: [ism.d_max, exposure, blend.confidence_cap, 0.0],
        };
        queue.write_buffer(&self.temporal_params, 0, bytemuck::bytes_of(&merge));
        let filter_split = if temporal { 0 } else { n };
        let filter = FilterParams {
            counts: [n, filter_split, 0, 0],
            params: [settings.filter_depth, settings.filter_normal, ism.d_max, 0.0],
        };
        queue.write_buffer(&self.filter_params, 0, bytemuck::bytes_of(&filter));
        if settings.sh_filter {
            self.sh.write_params(queue, n, settings, ism.d_max);
        }
        if s.upsampled.is_some() {
            self.upsample.write_params(queue, n, step, gathered, settings, ism.d_max);
        }
        let (sw, sh) = split_size(gathered, n);
        // Three timed passes: the shading on the split G-buffer, the filters on the view, and
        // the view importance over the pool's points.
        let mut pass = super::gather::step_pass(encoder, timer, "ism shade");
        pass.set_pipeline(&self.split);
        pass.set_bind_group(0, &s.split_group, &[]);
        pass.dispatch_workgroups(sw.div_ceil(8), sh.div_ceil(8), 1);
        pass.set_pipeline(if settings.sh_filter { &self.project_sh } else { &self.shade });
        pass.set_bind_group(0, &s.shade_group, &[]);
        pass.dispatch_workgroups(sw.div_ceil(8), sh.div_ceil(8), 1);
        if settings.sh_filter {
            self.sh.dispatch(&mut pass, targets.size);
        }
        drop(pass);
        let mut pass = super::gather::step_pass(encoder, timer, "ism filter");
        let p = self.parity;
        if let Some((_, groups)) = &s.upsampled {
            self.upsample.dispatch(&mut pass, &groups[usize::from(!temporal)], targets.size);
        }
        if temporal {
            pass.set_pipeline(&self.temporal);
            pass.set_bind_group(0, &s.temporal_groups[p], &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        if !filtered_first {
            let input = if temporal { 2 - p } else { 0 };
            pass.set_pipeline(&self.filter);
            pass.set_bind_group(0, &s.filter_groups[input], &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        drop(pass);
        if settings.view_importance > 0.0 {
            // How strongly each pool point could light this view, for the next frame's bounce picks.
            let mut pass = super::gather::step_pass(encoder, timer, "ism view importance");
            pass.set_pipeline(&self.view_importance);
            pass.set_bind_group(0, &s.importance_group, &[]);
            pass.dispatch_workgroups(ism.pool_points.div_ceil(64), 1, 1);
        }
        if filtered_first && (temporal || settings.sh_filter) {
            // The SH path filters before shading and half-resolution gathering before the merge,
            // so their result (merged with the history when temporal) is the indirect light
            // itself; without temporal reuse the half-resolution filter wrote it already.
            let result = if temporal { Some(&s.history[1 - p]) } else { self.sh.shaded() };
            if let Some(result) = result {
                encoder.copy_texture_to_texture(
                    result.texture.as_image_copy(),
                    targets.indirect.texture.as_image_copy(),
                    targets.indirect.texture.size(),
                );
            }
        }
        if temporal {
            // Keep this frame's normals for the next frame's confidence, then swap the history.
            encoder.copy_texture_to_texture(
                targets.normal.texture.as_image_copy(),
                s.prev_normal.texture.as_image_copy(),
                s.prev_normal.texture.size(),
            );
            self.parity = 1 - p;
            self.reset = false;
        }
    }
}
