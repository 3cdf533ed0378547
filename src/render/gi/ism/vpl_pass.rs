//! ISM passes P2, P3 and P5 on the GPU (docs/ARCHITECTURE.md, "ISM pass labels"): the light
//! G-buffer of every light (tiles laid out by [`super::light_tiles`]), its importance sum pyramid,
//! and first-bounce VPL generation by hierarchical warping over the whole atlas, so VPLs spread
//! over all lights in proportion to the power they reflect, and over the emissive surfaces and
//! the sky (the emitter tiles, [`super::emitter_points`]) in proportion to the power they emit,
//! each times the first set's seen weight where the camera sees the surface ([`super::first_view`]).
//! The CPU oracles in [`crate::precompute::ism::warp`] and [`crate::precompute::ism::power`]
//! define what these passes must produce.

use glam::Vec3;

use super::emitter_points::{self, GpuEmitterPoint};
use super::first_view::{AtlasInputs, FirstSetView, ViewInputs};
use super::light_tiles::{LightTiles, layout};
use super::params::{EmitterTileUniforms, GenParams, LightViewUniforms, SeedParams, TileRecord};
use crate::render::gi::technique::texture_bytes;
use crate::render::layouts::{Layouts, compute_pipeline, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::scene_gpu::{SceneGpu, Vertex};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::Target;
use crate::render::uniforms::GpuLight;
use crate::scene::{LightKind, Scene};
use crate::settings::IsmSettings;

/// Formats of the light G-buffer targets: albedo, normal, power, specular
/// (`light_gbuffer.wgsl` documents their contents).
const LIGHT_GBUFFER_FORMATS: [wgpu::TextureFormat; 4] = [
    wgpu::TextureFormat::Rgba8Unorm,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
];

/// `Vpl` in `common/vpl.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuVpl {
    /// xyz position, w = R^2 of the disk the VPL stands for (0: no VPL).
    pub position: [f32; 4],
    /// xyz normal, w = specular luminance.
    pub normal: [f32; 4],
    /// rgb power (W), a = pdf of the chosen texel.
    pub power: [f32; 4],
    /// xyz direction towards the light, w = chosen texel index (row-major).
    pub incident: [f32; 4],
    /// Glossy lobe: rgb = specular reflectance x incident power (scaled like `power`), w =
    /// Blinn-Phong exponent (0 = no lobe).
    pub gloss: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuVpl>() == 80);

/// Total green-channel power of each set of `per_set` VPLs in `vpls` (every bounce's set, as
/// `IsmTechnique::read_all_vpls` returns them): what the energy checks compare between bounces.
pub fn set_powers(vpls: &[GpuVpl], per_set: usize) -> Vec<f64> {
    vpls.chunks(per_set.max(1)).map(|set| set.iter().map(|v| f64::from(v.power[1])).sum()).collect()
}

/// Dynamic-offset slot of one tile's `LightView`.
const VIEW_SLOT: u64 = 256;

/// The atlas-sized targets and the buffers sized by tile and VPL counts.
struct Sized {
    side: u32,
    tile_capacity: u32,
    vpl_capacity: u32,
    view_buffer: wgpu::Buffer,
    view_bind_group: wgpu::BindGroup,
    tile_buffer: wgpu::Buffer,
    albedo: Target,
    normal: Target,
    power: Target,
    specular: Target,
    depth: Target,
    importance: wgpu::Texture,
    pyramid_groups: Vec<wgpu::BindGroup>,
    vpls: wgpu::Buffer,
    gen_bind_group: wgpu::BindGroup,
    emitter_capacity: u32,
    /// The emitter candidates ([`emitter_points`]) the emitter tiles and the warp read.
    emitter_points: wgpu::Buffer,
    emitter_bind_group: wgpu::BindGroup,
}

/// The light G-buffer, importance pyramid and VPL buffer with their pipelines.
pub struct VplPass {
    gbuffer_pipeline: wgpu::RenderPipeline,
    view_layout: wgpu::BindGroupLayout,
    pyramid_layout: wgpu::BindGroupLayout,
    seed_pipeline: wgpu::ComputePipeline,
    reduce_pipeline: wgpu::ComputePipeline,
    gen_pipeline: wgpu::ComputePipeline,
    gen_layout: wgpu::BindGroupLayout,
    gen_params: wgpu::Buffer,
    emitter_pipeline: wgpu::RenderPipeline,
    emitter_layout: wgpu::BindGroupLayout,
    /// P3's seed with the first set's view weight (`first_set_seen_weight` > 0).
    first_view: FirstSetView,
    sized: Option<Sized>,
    /// The layout of the last recorded frame.
    tiles: Option<LightTiles>,
    /// (scene revision, [`emitter_points::key`]) of the uploaded candidates.
    emitters_uploaded: Option<(u64, Vec<u32>)>,
}

/// A render pipeline into the light G-buffer's four targets and its depth (`depth`: write,
/// compare).
fn into_light_gbuffer(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    vertex: wgpu::VertexState<'_>,
    primitive: wgpu::PrimitiveState,
    (depth_write, compare): (bool, wgpu::CompareFunction),
) -> wgpu::RenderPipeline {
    let target = |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex,
        primitive,
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(depth_write),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &LIGHT_GBUFFER_FORMATS.map(target),
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The emitter tiles' pipeline (`ism_emitter_tiles.wgsl`: one triangle over each tile, into
/// the light G-buffer's targets, leaving its depth alone) and the layout of its candidates.
fn emitter_pipeline(
    device: &wgpu::Device,
    view_layout: &wgpu::BindGroupLayout,
) -> Result<(wgpu::RenderPipeline, wgpu::BindGroupLayout), ShaderError> {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("ism emitter points layout"),
        entries: &[crate::render::layouts::storage_entry(0, wgpu::ShaderStages::FRAGMENT)],
    });
    let module = shaders::module(device, "render/gi/ism/ism_emitter_tiles.wgsl")?;
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("ism emitter tiles layout"),
        bind_group_layouts: &[Some(view_layout), Some(&layout)],
        immediate_size: 0,
    });
    let vertex = wgpu::VertexState {
        module: &module,
        entry_point: Some("vs_main"),
        compilation_options: Default::default(),
        buffers: &[],
    };
    let depth = (false, wgpu::CompareFunction::Always);
    let pipeline =
        into_light_gbuffer(device, "ism emitter tiles pipeline", &pl, &module, vertex, Default::default(), depth);
    Ok((pipeline, layout))
}

impl VplPass {
    /// Creates the pipelines (targets come with the first [`Self::record`]).
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism light view layout"),
            entries: &[uniform_entry(0, vf, true)],
        });
        let module = shaders::module(device, "render/gi/ism/light_gbuffer.wgsl")?;
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ism light gbuffer layout"),
            bind_group_layouts: &[Some(&view_layout), Some(&layouts.object), Some(&layouts.material)],
            immediate_size: 0,
        });
        // No culling: the nearest surface wins even when the light sees its back (it then reflects nothing).
        let primitive = wgpu::PrimitiveState { cull_mode: None, ..Default::default() };
        let depth = (true, wgpu::CompareFunction::Less);
        let vertex = Vertex::state(&module);
        let gbuffer_pipeline =
            into_light_gbuffer(device, "ism light gbuffer pipeline", &pl, &module, vertex, primitive, depth);
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let pyramid_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism importance layout"),
            entries: &[texture_entry(0, c, unfilterable), storage_texture_entry(1, wgpu::TextureFormat::R32Float)],
        });
        let imp_module = shaders::module(device, "render/gi/ism/importance.wgsl")?;
        let gen_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism vpl generation layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, unfilterable),
                texture_entry(2, c, wgpu::TextureSampleType::Float { filterable: true }),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                texture_entry(5, c, wgpu::TextureSampleType::Depth),
                super::gather::storage_rw(6),
                texture_entry(7, c, unfilterable),
                crate::render::layouts::storage_entry(8, c),
                crate::render::layouts::storage_entry(9, c),
            ],
        });
        let gen_module = shaders::module(device, "render/gi/ism/vpl_generate.wgsl")?;
        let (emitter_pipeline, emitter_layout) = emitter_pipeline(device, &view_layout)?;
        let first_view = FirstSetView::new(device, &pyramid_layout)?;
        Ok(Self {
            first_view,
            gbuffer_pipeline,
            seed_pipeline: compute_pipeline(device, "ism importance seed", &pyramid_layout, &imp_module, "seed"),
            reduce_pipeline: compute_pipeline(device, "ism importance reduce", &pyramid_layout, &imp_module, "reduce"),
            gen_pipeline: compute_pipeline(device, "ism vpl generation", &gen_layout, &gen_module, "cs_main"),
            gen_params: super::screen::uniform(device, "ism vpl generation params", GenParams::SIZE),
            view_layout,
            pyramid_layout,
            gen_layout,
            emitter_pipeline,
            emitter_layout,
            sized: None,
            tiles: None,
            emitters_uploaded: None,
        })
    }

    /// (Re)creates the targets for an atlas of `side` texels, `tiles` tiles, `vpls` VPLs and
    /// `emitters` emitter candidates.
    fn ensure(&mut self, device: &wgpu::Device, side: u32, tiles: u32, vpls: u32, emitters: u32) {
        if self.sized.as_ref().is_some_and(|s| {
            s.side == side && s.tile_capacity >= tiles && s.vpl_capacity >= vpls && s.emitter_capacity >= emitters
        }) {
            return;
        }
        self.emitters_uploaded = None;
        // The first set's view group holds the old targets; let them go with the rest.
        self.first_view.release();
        use wgpu::TextureUsages as U;
        let tile_capacity = tiles.max(1).next_power_of_two();
        let vpl_capacity = vpls.max(1).next_power_of_two();
        let size = (side, side);
        let rt = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        let [fa, fn_, fp, fs] = LIGHT_GBUFFER_FORMATS;
        let albedo = Target::new(device, "ism light albedo", size, fa, rt);
        let normal = Target::new(device, "ism light normal", size, fn_, rt);
        let power = Target::new(device, "ism light power", size, fp, rt);
        let specular = Target::new(device, "ism light specular", size, fs, rt);
        let depth = Target::new(device, "ism light depth", size, wgpu::TextureFormat::Depth32Float, rt);
        let view_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism light views"),
            size: u64::from(tile_capacity) * VIEW_SLOT,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism light view bind group"),
            layout: &self.view_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &view_buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<LightViewUniforms>() as u64),
                }),
            }],
        });
        let tile_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism light tiles"),
            size: u64::from(tile_capacity) * std::mem::size_of::<TileRecord>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (importance, pyramid_groups, importance_full) = self.importance_pyramid(device, side, &power);
        let vpls = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism vpls"),
            size: u64::from(vpl_capacity) * std::mem::size_of::<GpuVpl>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let (emitter_capacity, emitter_points, emitter_bind_group) = self.emitter_buffer(device, emitters);
        use crate::render::layouts::view_entry as view;
        let gen_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism vpl generation bind group"),
            layout: &self.gen_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.gen_params.as_entire_binding() },
                view(1, &importance_full),
                view(2, &albedo.view),
                view(3, &normal.view),
                view(4, &power.view),
                view(5, &depth.view),
                wgpu::BindGroupEntry { binding: 6, resource: vpls.as_entire_binding() },
                view(7, &specular.view),
                wgpu::BindGroupEntry { binding: 8, resource: tile_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 9, resource: emitter_points.as_entire_binding() },
            ],
        });
        self.sized = Some(Sized {
            side,
            tile_capacity,
            vpl_capacity,
            view_buffer,
            view_bind_group,
            tile_buffer,
            albedo,
            normal,
            power,
            specular,
            depth,
            importance,
            pyramid_groups,
            vpls,
            gen_bind_group,
            emitter_capacity,
            emitter_points,
            emitter_bind_group,
        });
    }

    /// P3's importance pyramid over an atlas of `side` texels: the texture, each level's bind
    /// group (level 0 seeded from `power`'s importance) and a view of all levels for the warp.
    fn importance_pyramid(
        &self,
        device: &wgpu::Device,
        side: u32,
        power: &Target,
    ) -> (wgpu::Texture, Vec<wgpu::BindGroup>, wgpu::TextureView) {
        use wgpu::TextureUsages as U;
        let levels = side.trailing_zeros();
        let importance = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ism importance pyramid"),
            size: wgpu::Extent3d { width: side, height: side, depth_or_array_layers: 1 },
            mip_level_count: levels + 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Float,
            usage: U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC,
            view_formats: &[],
        });
        let mip = |m: u32| {
            importance.create_view(&wgpu::TextureViewDescriptor {
                label: Some("ism importance mip"),
                base_mip_level: m,
                mip_level_count: Some(1),
                ..Default::default()
            })
        };
        let pyramid_groups = (0..=levels)
            .map(|m| {
                let source = if m == 0 { power.view.clone() } else { mip(m - 1) };
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("ism importance bind group"),
                    layout: &self.pyramid_layout,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&source) },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&mip(m)) },
                    ],
                })
            })
            .collect();
        let importance_full = importance
            .create_view(&wgpu::TextureViewDescriptor { label: Some("ism importance all mips"), ..Default::default() });
        (importance, pyramid_groups, importance_full)
    }

    /// The emitter candidates' buffer for `emitters` candidates (a power of two, at least one)
    /// and the emitter tiles' bind group of it.
    fn emitter_buffer(&self, device: &wgpu::Device, emitters: u32) -> (u32, wgpu::Buffer, wgpu::BindGroup) {
        let emitter_capacity = emitters.max(1).next_power_of_two();
        let emitter_points = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism emitter points"),
            size: u64::from(emitter_capacity) * std::mem::size_of::<GpuEmitterPoint>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let emitter_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism emitter points bind group"),
            layout: &self.emitter_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: emitter_points.as_entire_binding() }],
        });
        (emitter_capacity, emitter_points, emitter_bind_group)
    }

    /// Frees the targets (another mode is active); pipelines stay.
    pub fn release(&mut self) {
        self.first_view.release();
        self.sized = None;
        self.tiles = None;
        self.emitters_uploaded = None;
    }

    /// Bytes of GPU memory held by the targets and buffers.
    pub fn gpu_bytes(&self) -> u64 {
        self.sized.as_ref().map_or(0, |s| {
            let textures = [&s.albedo, &s.normal, &s.power, &s.specular, &s.depth].map(|t| texture_bytes(&t.texture));
            textures.iter().sum::<u64>()
                + texture_bytes(&s.importance)
                + s.vpls.size()
                + s.view_buffer.size()
                + s.tile_buffer.size()
                + s.emitter_points.size()
        })
    }

    /// The light G-buffer layout of the last frame.
    pub fn tiles(&self) -> Option<&LightTiles> {
        self.tiles.as_ref()
    }

    /// The first-bounce VPLs of the last frame.
    pub fn vpls(&self) -> Option<&wgpu::Buffer> {
        self.sized.as_ref().map(|s| &s.vpls)
    }

    /// Light G-buffer views for the inspector: albedo, normal, power, importance.
    pub fn views(&self) -> Option<(&Target, &Target, &Target, &wgpu::Texture)> {
        self.sized.as_ref().map(|s| (&s.albedo, &s.normal, &s.power, &s.importance))
    }

    /// Records P2, P3 and P5 for every light and emitter of `scene`; returns false (nothing
    /// recorded) when the scene has neither. `view` is this frame's camera view, which the
    /// first set's view weight reads (`settings.first_set_seen_weight` > 0).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        gpu: &SceneGpu,
        settings: &IsmSettings,
        frame: u32,
        view: &ViewInputs<'_>,
        timestamps: Option<crate::render::timing::TimestampPair<'_>>,
    ) -> bool {
        let tiles = layout(scene);
        if tiles.count() == 0 {
            self.tiles = Some(tiles);
            return false;
        }
        let candidates = tiles.emitter_candidates() as u32;
        self.ensure(device, tiles.side, tiles.count() as u32, settings.vpl_count, candidates);
        self.upload_emitters(queue, scene, candidates as usize, tiles.tile_size as usize);
        let Some(s) = &self.sized else { return false };
        write_views(queue, s, scene, &tiles);
        let levels = tiles.side.trailing_zeros();
        if settings.first_set_seen_weight <= 0.0 {
            // Unused this frame: keep no view or atlas resources alive through its group.
            self.first_view.release();
        }
        let atlas = [tiles.per_row, tiles.tile_size, tiles.count() as u32, 0];
        let params = GenParams { counts: [settings.vpl_count, frame, settings.interleave, levels], tiles: atlas };
        queue.write_buffer(&self.gen_params, 0, bytemuck::bytes_of(&params));
        self.draw_tiles(encoder, s, &tiles, gpu, timestamps.as_ref());
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ism importance pyramid"),
            timestamp_writes: timestamps.as_ref().map(|t| t.compute_end_writes()),
        });
        for (m, group) in s.pyramid_groups.iter().enumerate() {
            if m == 0 && settings.first_set_seen_weight > 0.0 {
                let seed = SeedParams { tiles: atlas, weight: [settings.first_set_seen_weight, 0.0, 0.0, 0.0] };
                let inputs = AtlasInputs {
                    tiles: &s.tile_buffer,
                    depth: &s.depth.view,
                    normal: &s.normal.view,
                    emitters: &s.emitter_points,
                };
                self.first_view.bind(device, queue, &mut pass, &seed, view, &inputs);
            } else {
                pass.set_pipeline(if m == 0 { &self.seed_pipeline } else { &self.reduce_pipeline });
            }
            pass.set_bind_group(0, group, &[]);
            let side = (tiles.side >> m).max(1);
            pass.dispatch_workgroups(side.div_ceil(8), side.div_ceil(8), 1);
        }
        pass.set_pipeline(&self.gen_pipeline);
        pass.set_bind_group(0, &s.gen_bind_group, &[]);
        pass.dispatch_workgroups(settings.vpl_count.div_ceil(64), 1, 1);
        drop(pass);
        self.tiles = Some(tiles);
        true
    }

    /// Uploads `count` emitter candidates for tiles of `row` texels a row when the emitters
    /// changed since the last upload (a scene whose revision stands still costs one comparison).
    fn upload_emitters(&mut self, queue: &wgpu::Queue, scene: &Scene, count: usize, row: usize) {
        let Some(s) = &self.sized else { return };
        if count == 0 || self.emitters_uploaded.as_ref().is_some_and(|(r, _)| *r == scene.revision()) {
            return;
        }
        let key = emitter_points::key(scene, count, row);
        if self.emitters_uploaded.as_ref().is_some_and(|(_, k)| *k == key) {
            self.emitters_uploaded = Some((scene.revision(), key));
            return;
        }
        let mut points = emitter_points::emitter_points(scene, count, row);
        // Candidates the emitters could not fill (no power) send nothing, not last upload's light.
        points.resize(count, GpuEmitterPoint::default());
        queue.write_buffer(&s.emitter_points, 0, bytemuck::cast_slice(&points));
        self.emitters_uploaded = Some((scene.revision(), key));
    }

    /// P2: every light's tiles, then the emitter tiles.
    fn draw_tiles(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        s: &Sized,
        tiles: &LightTiles,
        gpu: &SceneGpu,
        timestamps: Option<&crate::render::timing::TimestampPair<'_>>,
    ) {
        use crate::render::targets::cleared as color;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("ism light gbuffer pass"),
            color_attachments: &[
                color(&s.albedo.view),
                color(&s.normal.view),
                color(&s.power.view),
                color(&s.specular.view),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &s.depth.view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps.map(|t| t.render_writes(true, false)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let size = tiles.tile_size as f32;
        pass.set_pipeline(&self.gbuffer_pipeline);
        for t in 0..tiles.tiles.len() {
            let (x, y) = tiles.origin(t);
            pass.set_viewport(x as f32, y as f32, size, size, 0.0, 1.0);
            pass.set_bind_group(0, &s.view_bind_group, &[(t as u64 * VIEW_SLOT) as u32]);
            gpu.draw_objects(&mut pass);
        }
        if tiles.emitters > 0 {
            pass.set_pipeline(&self.emitter_pipeline);
            pass.set_bind_group(1, &s.emitter_bind_group, &[]);
            for t in tiles.tiles.len()..tiles.count() {
                let (x, y) = tiles.origin(t);
                pass.set_viewport(x as f32, y as f32, size, size, 0.0, 1.0);
                pass.set_bind_group(0, &s.view_bind_group, &[(t as u64 * VIEW_SLOT) as u32]);
                pass.draw(0..3, 0..1);
            }
        }
    }
}

/// Writes every tile's view (a light's `LightView` or an emitter tile's `EmitterTile`, each in
/// its dynamic-offset slot) and the warp's tile records.
fn write_views(queue: &wgpu::Queue, s: &Sized, scene: &Scene, tiles: &LightTiles) {
    let mut records = Vec::with_capacity(tiles.count());
    for (t, tile) in tiles.tiles.iter().enumerate() {
        let Some(l) = scene.lights().get(tile.light) else { continue };
        let view = LightViewUniforms {
            clip_from_world: tile.clip_from_world.to_cols_array_2d(),
            light: GpuLight::new(l, None, 0.0),
            params: [tile.tan_half, tiles.tile_size as f32, tile.ortho_texel_area, 0.0],
            axis: tile.axis.extend(0.0).to_array(),
        };
        queue.write_buffer(&s.view_buffer, t as u64 * VIEW_SLOT, bytemuck::bytes_of(&view));
        let towards = match l.kind {
            LightKind::Directional => (-l.direction.normalize_or(Vec3::NEG_Y)).extend(1.0),
            _ => l.position.extend(0.0),
        };
        records.push(TileRecord {
            world_from_clip: tile.clip_from_world.inverse().to_cols_array_2d(),
            light: towards.to_array(),
        });
    }
    let per_tile = tiles.tile_size * tiles.tile_size;
    for e in 0..tiles.emitters {
        let t = tiles.tiles.len() + e as usize;
        let (x, y) = tiles.origin(t);
        let view = EmitterTileUniforms { origin: [x, y, tiles.tile_size, e * per_tile] };
        queue.write_buffer(&s.view_buffer, t as u64 * VIEW_SLOT, bytemuck::bytes_of(&view));
        records.push(TileRecord { world_from_clip: [[0.0; 4]; 4], light: [(e * per_tile) as f32, 0.0, 0.0, 2.0] });
    }
    queue.write_buffer(&s.tile_buffer, 0, bytemuck::cast_slice(&records));
}
