//! ISM passes P2, P3 and P5 on the GPU: the light G-buffer of a spot or point light, its importance sum
//! pyramid, and first-bounce VPL generation by hierarchical warping. The CPU oracles in
//! [`super::warp`] and [`super::power`] define what these passes must produce.

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use glam::{Mat4, Vec3};

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

/// Side of the light G-buffer (a power of two, for the warp pyramid).
pub const LIGHT_GBUFFER_SIZE: u32 = 256;
const LEVELS: u32 = LIGHT_GBUFFER_SIZE.trailing_zeros();

/// `LightView` in `light_gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct LightViewUniforms {
    clip_from_world: [[f32; 4]; 4],
    light: GpuLight,
    params: [f32; 4],
    /// The tile's view axis (xyz).
    axis: [f32; 4],
}

/// `GenParams` in `vpl_generate.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct GenParams {
    world_from_clip: [[[f32; 4]; 4]; 6],
    light_position: [f32; 4],
    counts: [u32; 4],
    /// Tiles per row, tile side (texels), tile count, unused.
    tiles: [u32; 4],
}

/// Dynamic-offset slot of one tile's `LightView`.
const VIEW_SLOT: u64 = 256;

/// How a light's G-buffer is laid out in the square atlas: one tile for a spot light (its
/// frustum), six cube faces in a 4 x 4 grid for a point light (the other tiles stay empty and
/// have zero importance, so the warp never picks them).
pub struct LightLayout {
    /// Clip-from-world per tile.
    pub tiles: Vec<Mat4>,
    /// Tile side in texels.
    pub tile_size: u32,
    /// Tiles per atlas row.
    pub per_row: u32,
    /// tan(half field of view) of each tile's frustum.
    pub tan_half: f32,
    /// View axis per tile.
    pub axes: Vec<Vec3>,
}

/// `Vpl` in `vpl_generate.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuVpl {
    /// xyz position, w = 1 when valid.
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

/// The light G-buffer, importance pyramid and VPL buffer with their pipelines.
pub struct VplPass {
    gbuffer_pipeline: wgpu::RenderPipeline,
    view_buffer: wgpu::Buffer,
    view_bind_group: wgpu::BindGroup,
    /// Albedo (rgb) and specular luminance (a) seen from the light.
    pub albedo: Target,
    /// World normals seen from the light.
    pub normal: Target,
    /// Reflected power (rgb) and importance (a) per texel.
    pub power: Target,
    /// Specular reflectance x incident power (rgb) and Blinn-Phong exponent (a) per texel.
    pub specular: Target,
    depth: Target,
    /// The importance sum pyramid (mip 0 = per texel, last mip = total).
    pub importance: wgpu::Texture,
    importance_full: wgpu::TextureView,
    seed_pipeline: wgpu::ComputePipeline,
    reduce_pipeline: wgpu::ComputePipeline,
    pyramid_groups: Vec<wgpu::BindGroup>,
    gen_pipeline: wgpu::ComputePipeline,
    gen_layout: wgpu::BindGroupLayout,
    gen_params: wgpu::Buffer,
    /// The VPLs of the last generation.
    pub vpls: wgpu::Buffer,
    vpl_capacity: u32,
    gen_bind_group: wgpu::BindGroup,
}

impl VplPass {
    /// Creates the targets and pipelines.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        use wgpu::TextureUsages as U;
        let size = (LIGHT_GBUFFER_SIZE, LIGHT_GBUFFER_SIZE);
        let rt = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        let [fa, fn_, fp, fs] = LIGHT_GBUFFER_FORMATS;
        let albedo = Target::new(device, "ism light albedo", size, fa, rt);
        let normal = Target::new(device, "ism light normal", size, fn_, rt);
        let power = Target::new(device, "ism light power", size, fp, rt);
        let specular = Target::new(device, "ism light specular", size, fs, rt);
        let depth = Target::new(device, "ism light depth", size, wgpu::TextureFormat::Depth32Float, rt);

        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism light view layout"),
            entries: &[uniform_entry(0, vf, true)],
        });
        let view_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism light view"),
            size: 6 * VIEW_SLOT,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism light view bind group"),
            layout: &view_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &view_buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<LightViewUniforms>() as u64),
                }),
            }],
        });
        let module = shaders::module(device, "render/gi/ism/light_gbuffer.wgsl")?;
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ism light gbuffer layout"),
            bind_group_layouts: &[Some(&view_layout), Some(&layouts.object), Some(&layouts.material)],
            immediate_size: 0,
        });
        let target = |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
        let gbuffer_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("ism light gbuffer pipeline"),
            layout: Some(&pl),
            vertex: Vertex::state(&module),
            // No culling: the nearest surface wins even when the light sees its back (it then reflects nothing).
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &LIGHT_GBUFFER_FORMATS.map(target),
            }),
            multiview_mask: None,
            cache: None,
        });

        let importance = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ism importance pyramid"),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: LEVELS + 1,
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
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let pyramid_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism importance layout"),
            entries: &[texture_entry(0, c, unfilterable), storage_texture_entry(1, wgpu::TextureFormat::R32Float)],
        });
        let imp_module = shaders::module(device, "render/gi/ism/importance.wgsl")?;
        let seed_pipeline = compute_pipeline(device, "ism importance seed", &pyramid_layout, &imp_module, "seed");
        let reduce_pipeline = compute_pipeline(device, "ism importance reduce", &pyramid_layout, &imp_module, "reduce");
        let mut pyramid_groups = Vec::new();
        for m in 0..=LEVELS {
            let source = if m == 0 { power.view.clone() } else { mip(m - 1) };
            let dest = mip(m);
            pyramid_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("ism importance bind group"),
                layout: &pyramid_layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&source) },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&dest) },
                ],
            }));
        }
        let importance_full = importance
            .create_view(&wgpu::TextureViewDescriptor { label: Some("ism importance all mips"), ..Default::default() });

        let gen_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism vpl generation layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, unfilterable),
                texture_entry(2, c, wgpu::TextureSampleType::Float { filterable: true }),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                texture_entry(5, c, wgpu::TextureSampleType::Depth),
                texture_entry(7, c, unfilterable),
                wgpu::BindGroupLayoutEntry {
                    binding: 6,
                    visibility: c,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let gen_module = shaders::module(device, "render/gi/ism/vpl_generate.wgsl")?;
        let gen_pipeline = compute_pipeline(device, "ism vpl generation", &gen_layout, &gen_module, "cs_main");
        let gen_params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism vpl generation params"),
            size: std::mem::size_of::<GenParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut pass = Self {
            gbuffer_pipeline,
            view_buffer,
            view_bind_group,
            albedo,
            normal,
            power,
            specular,
            depth,
            importance,
            importance_full,
            seed_pipeline,
            reduce_pipeline,
            pyramid_groups,
            gen_pipeline,
            gen_bind_group: device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("placeholder"),
                layout: &device
                    .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("empty"), entries: &[] }),
                entries: &[],
            }),
            gen_layout,
            gen_params,
            vpls: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ism vpls"),
                size: 64,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
            vpl_capacity: 0,
        };
        pass.ensure_capacity(device, 256);
        Ok(pass)
    }

    fn ensure_capacity(&mut self, device: &wgpu::Device, count: u32) {
        if count <= self.vpl_capacity {
            return;
        }
        self.vpl_capacity = count.next_power_of_two();
        self.vpls = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism vpls"),
            size: u64::from(self.vpl_capacity) * std::mem::size_of::<GpuVpl>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        fn view(binding: u32, v: &wgpu::TextureView) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) }
        }
        let entries = [
            wgpu::BindGroupEntry { binding: 0, resource: self.gen_params.as_entire_binding() },
            view(1, &self.importance_full),
            view(2, &self.albedo.view),
            view(3, &self.normal.view),
            view(4, &self.power.view),
            view(5, &self.depth.view),
            view(7, &self.specular.view),
            wgpu::BindGroupEntry { binding: 6, resource: self.vpls.as_entire_binding() },
        ];
        self.gen_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism vpl generation bind group"),
            layout: &self.gen_layout,
            entries: &entries,
        });
    }

    /// The light's clip-from-world for the light G-buffer of spot light `light` (a frustum that
    /// holds the outer cone), or `None` if it is not a spot light.
    pub fn light_layout(scene: &Scene, light: usize) -> Option<LightLayout> {
        let l = scene.lights().get(light)?;
        let radius = scene.bounds().map_or(10.0, |b| b.radius() + (b.center() - l.position).length());
        let (near, far) = (0.01f32.min(0.1 * radius), radius + 0.01);
        match l.kind {
            LightKind::Spot { outer_cone_angle, .. } => {
                let fov = (2.0 * outer_cone_angle).min(170f32.to_radians());
                let up = if l.direction.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
                let view = look_at_mat4(l.position, l.position + l.direction, up);
                Some(LightLayout {
                    tiles: vec![directx::perspective(fov, 1.0, near, far) * view],
                    tile_size: LIGHT_GBUFFER_SIZE,
                    per_row: 1,
                    tan_half: (0.5 * fov).tan(),
                    axes: vec![l.direction],
                })
            }
            LightKind::Point => {
                let proj = directx::perspective(std::f32::consts::FRAC_PI_2, 1.0, near, far);
                Some(LightLayout {
                    tiles: crate::render::shadows::face_views(l.position).iter().map(|v| proj * *v).collect(),
                    tile_size: LIGHT_GBUFFER_SIZE / 4,
                    per_row: 4,
                    tan_half: 1.0,
                    axes: vec![Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z],
                })
            }
            LightKind::Directional => None,
        }
    }

    /// Records P2, P3 and P5 for spot or point light `light`; returns false (nothing recorded)
    /// for a directional light.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        gpu: &SceneGpu,
        light: usize,
        settings: &IsmSettings,
        frame: u32,
        timestamps: Option<crate::render::timing::TimestampPair<'_>>,
    ) -> bool {
        let Some(layout) = Self::light_layout(scene, light) else { return false };
        let Some(l) = scene.lights().get(light) else { return false };
        self.ensure_capacity(device, settings.vpl_count);
        for (t, clip) in layout.tiles.iter().enumerate() {
            let view = LightViewUniforms {
                clip_from_world: clip.to_cols_array_2d(),
                light: GpuLight::new(l, None, 0.0),
                params: [layout.tan_half, layout.tile_size as f32, 0.0, 0.0],
                axis: layout.axes.get(t).copied().unwrap_or(l.direction).extend(0.0).to_array(),
            };
            queue.write_buffer(&self.view_buffer, t as u64 * VIEW_SLOT, bytemuck::bytes_of(&view));
        }
        let mut world_from_clip = [[[0.0f32; 4]; 4]; 6];
        for (slot, clip) in world_from_clip.iter_mut().zip(&layout.tiles) {
            *slot = clip.inverse().to_cols_array_2d();
        }
        let params = GenParams {
            world_from_clip,
            light_position: l.position.extend(1.0).to_array(),
            counts: [settings.vpl_count, frame, settings.interleave, LEVELS],
            tiles: [layout.per_row, layout.tile_size, layout.tiles.len() as u32, 0],
        };
        queue.write_buffer(&self.gen_params, 0, bytemuck::bytes_of(&params));
        {
            fn color(v: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
                Some(wgpu::RenderPassColorAttachment {
                    view: v,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            }
            let (a, n, p) = (self.albedo.view.clone(), self.normal.view.clone(), self.power.view.clone());
            let sp = self.specular.view.clone();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("ism light gbuffer pass"),
                color_attachments: &[color(&a), color(&n), color(&p), color(&sp)],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth.view,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: timestamps.as_ref().map(|t| t.render_writes(true, false)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.gbuffer_pipeline);
            for t in 0..layout.tiles.len() as u32 {
                let size = layout.tile_size as f32;
                let (x, y) = ((t % layout.per_row) as f32 * size, (t / layout.per_row) as f32 * size);
                pass.set_viewport(x, y, size, size, 0.0, 1.0);
                pass.set_bind_group(0, &self.view_bind_group, &[(u64::from(t) * VIEW_SLOT) as u32]);
                gpu.draw_objects(&mut pass, scene);
            }
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ism importance pyramid"),
            timestamp_writes: timestamps.as_ref().map(|t| t.compute_end_writes()),
        });
        for (m, group) in self.pyramid_groups.iter().enumerate() {
            pass.set_pipeline(if m == 0 { &self.seed_pipeline } else { &self.reduce_pipeline });
            pass.set_bind_group(0, group, &[]);
            let side = (LIGHT_GBUFFER_SIZE >> m).max(1);
            pass.dispatch_workgroups(side.div_ceil(8), side.div_ceil(8), 1);
        }
        pass.set_pipeline(&self.gen_pipeline);
        pass.set_bind_group(0, &self.gen_bind_group, &[]);
        pass.dispatch_workgroups(settings.vpl_count.div_ceil(64), 1, 1);
        true
    }
}
