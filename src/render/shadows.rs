//! Shadow maps for the direct term. Every map is a layer of one `Depth32Float` array:
//! spot lights get a perspective layer, directional lights an orthographic layer fitted to the
//! scene bounds, point lights six perspective faces (+X -X +Y -Y +Z -Z) whose field of view is
//! slightly wider than 90 degrees so the PCF kernel never reads across a face edge. All geometry
//! is drawn without culling (one-sided surfaces still block light, as in the path tracer), with
//! slope-scaled depth bias; receivers add a normal offset sized in texels (`common/shadow.wgsl`).
//!
//! A layer's depth depends only on its matrix and the scene's geometry, so a layer is drawn
//! again only when one of them changed since it was last drawn and submitted (cached shadow
//! maps, as engines keep them for lights that stand still): a still frame draws none, moving
//! one light redraws that light's layers, moving an object redraws all of them.

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use glam::{Mat4, Vec3};

use super::layouts::{Layouts, uniform_entry};
use super::scene_gpu::{SceneGpu, Vertex};
use super::shaders::{self, ShaderError};
use super::targets::formats;
use super::timing::TimestampPair;
use super::uniforms::GpuLight;
use crate::scene::{Aabb, LightKind, Scene};
use crate::settings::ShadowSettings;

/// Upper bound on shadow layers (a point light uses six).
pub const MAX_SHADOW_LAYERS: u32 = 48;
const DRAW_SLOT: u64 = 256;

/// The shadow pipeline, the layer array and the per-layer matrices of the current frame.
pub struct ShadowPass {
    pipeline: wgpu::RenderPipeline,
    draw_layout: wgpu::BindGroupLayout,
    draw_buffer: wgpu::Buffer,
    draw_bind_group: wgpu::BindGroup,
    draw_capacity: u64,
    /// The depth array (all layers).
    pub texture: wgpu::Texture,
    /// D2Array view of all layers, for sampling.
    pub array_view: wgpu::TextureView,
    layer_views: Vec<wgpu::TextureView>,
    resolution: u32,
    /// Clip-from-world of each layer used this frame.
    pub layer_matrices: Vec<Mat4>,
    /// Bumped whenever `texture` is recreated (bind groups that use it must be rebuilt).
    pub generation: u64,
    /// Per layer: what its depth was last drawn from, once that frame was submitted.
    drawn: Vec<Option<LayerKey>>,
    /// The layers recorded into the frame not yet submitted (`Self::submitted` keeps them).
    pending: Vec<(usize, LayerKey)>,
    /// How many layers the last [`Self::record`] drew.
    pub last_drawn: usize,
}

/// What a layer's depth is drawn from: its matrix and the scene geometry's generation
/// ([`SceneGpu::geometry_generation`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct LayerKey {
    clip_from_world: Mat4,
    geometry: u64,
}

/// Per-light output of [`ShadowPass::prepare`].
pub struct ShadowAssignment {
    /// Packed lights with their shadow layers.
    pub lights: Vec<GpuLight>,
}

pub(crate) fn face_views(position: Vec3) -> [Mat4; 6] {
    let dirs = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];
    dirs.map(|d| {
        let up = if d.y.abs() > 0.5 { Vec3::Z } else { Vec3::Y };
        look_at_mat4(position, position + d, up)
    })
}

fn up_for(dir: Vec3) -> Vec3 {
    if dir.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y }
}

impl ShadowPass {
    /// Creates the pipeline and an initial array.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let module = shaders::module(device, "render/shadow_depth.wgsl")?;
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow layer layout"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX, true)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow pipeline layout"),
            bind_group_layouts: &[Some(&draw_layout), Some(&layouts.object)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadow pipeline"),
            layout: Some(&layout),
            vertex: Vertex::state(&module),
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: formats::DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: wgpu::DepthBiasState { constant: 0, slope_scale: 0.0, clamp: 0.0 },
            }),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
        let (draw_buffer, draw_bind_group) = Self::draw_buffer(device, &draw_layout, 64);
        let (texture, array_view, layer_views) = Self::array(device, 64, 1);
        Ok(Self {
            pipeline,
            draw_layout,
            draw_buffer,
            draw_bind_group,
            draw_capacity: 64,
            texture,
            array_view,
            layer_views,
            resolution: 64,
            layer_matrices: Vec::new(),
            generation: 0,
            drawn: Vec::new(),
            pending: Vec::new(),
            last_drawn: 0,
        })
    }

    fn draw_buffer(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        capacity: u64,
    ) -> (wgpu::Buffer, wgpu::BindGroup) {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shadow layer uniforms"),
            size: DRAW_SLOT * capacity,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow layer bind group"),
            layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(64),
                }),
            }],
        });
        (buffer, bind_group)
    }

    fn array(
        device: &wgpu::Device,
        resolution: u32,
        layers: u32,
    ) -> (wgpu::Texture, wgpu::TextureView, Vec<wgpu::TextureView>) {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow map array"),
            size: wgpu::Extent3d { width: resolution, height: resolution, depth_or_array_layers: layers },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: formats::DEPTH,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("shadow map array view"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let layer_views = (0..layers)
            .map(|l| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("shadow map layer view"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: l,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        (texture, array_view, layer_views)
    }

    /// Assigns layers to shadowed lights, computes their matrices and packs the lights.
    pub fn prepare(&mut self, device: &wgpu::Device, scene: &Scene, settings: &ShadowSettings) -> ShadowAssignment {
        let res = settings.resolution.max(16);
        let bounds = scene.bounds().unwrap_or(Aabb { min: Vec3::splat(-1.0), max: Vec3::splat(1.0) });
        let (center, radius) = (bounds.center(), bounds.radius().max(1e-3));
        self.layer_matrices.clear();
        let mut lights = Vec::with_capacity(scene.lights().len());
        for light in scene.lights() {
            let needed = match light.kind {
                LightKind::Point => 6,
                _ => 1,
            };
            let first = self.layer_matrices.len() as u32;
            if !light.cast_shadows || first + needed > MAX_SHADOW_LAYERS {
                if light.cast_shadows {
                    log::warn!("light {:?}: more than {MAX_SHADOW_LAYERS} shadow layers, drawn unshadowed", light.name);
                }
                lights.push(GpuLight::new(light, None, 0.0));
                continue;
            }
            let far_for = |p: Vec3| (p - center).length() + radius + 0.01;
            let texel_factor = match light.kind {
                LightKind::Point => {
                    let t = 1.0 + 2.0 * (settings.pcf_radius as f32 + 2.0) / res as f32;
                    let (near, far) = (0.01f32.min(0.1 * radius), far_for(light.position));
                    let proj = directx::perspective(2.0 * t.atan(), 1.0, near, far);
                    self.layer_matrices.extend(face_views(light.position).map(|v| proj * v));
                    2.0 * t / res as f32
                }
                LightKind::Spot { outer_cone_angle, .. } => {
                    let margin = 2.0 * (settings.pcf_radius as f32 + 2.0) / res as f32;
                    let fov = (2.0 * outer_cone_angle + margin).min(170f32.to_radians());
                    let (near, far) = (0.01f32.min(0.1 * radius), far_for(light.position));
                    let proj = directx::perspective(fov, 1.0, near, far);
                    let view = look_at_mat4(light.position, light.position + light.direction, up_for(light.direction));
                    self.layer_matrices.push(proj * view);
                    2.0 * (0.5 * fov).tan() / res as f32
                }
                LightKind::Directional => {
                    let eye = center - light.direction * (2.0 * radius);
                    let view = look_at_mat4(eye, center, up_for(light.direction));
                    let proj = directx::orthographic(-radius, radius, -radius, radius, 0.0, 4.0 * radius);
                    self.layer_matrices.push(proj * view);
                    2.0 * radius / res as f32
                }
            };
            lights.push(GpuLight::new(light, Some(first), texel_factor));
        }
        let layers = (self.layer_matrices.len() as u32).max(1);
        // Exactly the layers needed, so deleting lights gives back their maps (4 MiB a layer at
        // 1024²); the array is made anew only when the resolution or the layer count changes.
        if res != self.resolution || layers as usize != self.layer_views.len() {
            (self.texture, self.array_view, self.layer_views) = Self::array(device, res, layers);
            self.resolution = res;
            self.generation += 1;
            self.drawn.clear();
        }
        ShadowAssignment { lights }
    }

    /// The layers whose depth must be drawn this frame: those never drawn into the current
    /// array, and those whose matrix or the scene's geometry changed since.
    pub fn stale_layers(&self, gpu: &SceneGpu) -> Vec<usize> {
        let geometry = gpu.geometry_generation();
        (0..self.layer_matrices.len())
            .filter(|&l| {
                let key = LayerKey { clip_from_world: self.layer_matrices[l], geometry };
                self.drawn.get(l).copied().flatten() != Some(key)
            })
            .collect()
    }

    /// Renders the `stale` layers ([`Self::stale_layers`]); the others keep their depth.
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        gpu: &SceneGpu,
        stale: &[usize],
        timestamps: Option<TimestampPair<'_>>,
    ) {
        self.pending.clear();
        self.last_drawn = stale.len();
        if stale.is_empty() {
            return;
        }
        self.write_layer_matrices(device, queue);
        let geometry = gpu.geometry_generation();
        for (i, &l) in stale.iter().enumerate() {
            let (first, last) = (i == 0, i + 1 == stale.len());
            let ts = timestamps.as_ref().filter(|_| first || last).map(|t| t.render_writes(first, last));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow pass"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.layer_views[l],
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: ts,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.draw_bind_group, &[(l as u64 * DRAW_SLOT) as u32]);
            pass.set_bind_group(1, &gpu.object_bind_group, &[]);
            gpu.draw_geometry(&mut pass);
            self.pending.push((l, LayerKey { clip_from_world: self.layer_matrices[l], geometry }));
        }
    }

    /// The frame holding the last [`Self::record`] was submitted: its layers are drawn. (A
    /// frame dropped before submission leaves them stale, so the next frame draws them.)
    pub fn submitted(&mut self) {
        for (l, key) in self.pending.drain(..) {
            if self.drawn.len() <= l {
                self.drawn.resize(l + 1, None);
            }
            self.drawn[l] = Some(key);
        }
    }

    /// Forgets what every layer was drawn from: the next frame draws them all.
    pub fn invalidate(&mut self) {
        self.drawn.clear();
        self.pending.clear();
    }

    /// Every layer's matrix into its dynamic-offset slot of the draw buffer.
    fn write_layer_matrices(&mut self, device: &wgpu::Device, queue: &wgpu::Queue) {
        let layers = self.layer_matrices.len() as u64;
        if layers > self.draw_capacity {
            self.draw_capacity = layers.next_power_of_two();
            (self.draw_buffer, self.draw_bind_group) = Self::draw_buffer(device, &self.draw_layout, self.draw_capacity);
        }
        let mut data = vec![0u8; (DRAW_SLOT * layers) as usize];
        for (l, m) in self.layer_matrices.iter().enumerate() {
            let at = l * DRAW_SLOT as usize;
            data[at..at + 64].copy_from_slice(bytemuck::cast_slice(&m.to_cols_array()));
        }
        if !data.is_empty() {
            queue.write_buffer(&self.draw_buffer, 0, &data);
        }
    }

    /// Current map resolution.
    pub fn resolution(&self) -> u32 {
        self.resolution
    }
}
