//! Splatting and normalisation (`rcs_splat.wgsl`, `rcs_resolve.wgsl`): one quad per record
//! with additive blending of Ward-weighted irradiance into two float targets (with and without
//! the gradients, each with the summed weight), then E = sum w E / sum w as E / pi.
//! 32-bit float blending of the weighted sums keeps w up to 1000 times irradiance in the hundreds
//! without the overflow 16-bit floats have at 65504.

use bytemuck::{Pod, Zeroable};

use super::store::Store;
use super::{entry, uniform};
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::texture_bytes;
use crate::render::layouts::{compute_pipeline, storage_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::Target;

/// Format of the accumulation targets.
pub const ACCUM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// `SplatParams` in `rcs_splat.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SplatParams {
    /// x = accuracy a.
    pub accuracy: [f32; 4],
    /// x = 1: instances index the splat list.
    pub mode: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<SplatParams>() == 32);

/// `ResolveParams` in `rcs_resolve.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ResolveParams {
    /// x = 1 with gradients.
    pub mode: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<ResolveParams>() == 16);

/// Which records a splat draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Splat {
    /// Clear, then every slot below the high-water mark.
    All(u32),
    /// This round's `n` records (their slots in the splat list), on top of what is there.
    New(u32),
}

/// The pipelines and the accumulation targets.
pub struct SplatPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    all_params: wgpu::Buffer,
    new_params: wgpu::Buffer,
    resolve_pipeline: wgpu::ComputePipeline,
    resolve_layout: wgpu::BindGroupLayout,
    resolve_params: wgpu::Buffer,
    targets: Option<(Target, Target)>,
}

impl SplatPass {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let f = wgpu::ShaderStages::FRAGMENT;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs splat layout"),
            entries: &[
                uniform_entry(0, vf, false),
                uniform_entry(1, vf, false),
                storage_entry(2, vf),
                storage_entry(3, vf),
                texture_entry(4, f, wgpu::TextureSampleType::Depth),
                texture_entry(5, f, unfilterable),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_splat.wgsl")?;
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rcs splat pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let target = Some(wgpu::ColorTargetState {
            format: ACCUM_FORMAT,
            blend: Some(wgpu::BlendState { color: add, alpha: add }),
            write_mask: wgpu::ColorWrites::ALL,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("rcs splat pipeline"),
            layout: Some(&pl),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[target.clone(), target],
            }),
            multiview_mask: None,
            cache: None,
        });
        let c = wgpu::ShaderStages::COMPUTE;
        let resolve_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs resolve layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, unfilterable),
                texture_entry(2, c, unfilterable),
                storage_texture_entry(3, crate::render::targets::formats::HDR),
            ],
        });
        let resolve_module = shaders::module(device, "render/gi/rcs/rcs_resolve.wgsl")?;
        let size = std::mem::size_of::<SplatParams>() as u64;
        Ok(Self {
            pipeline,
            layout,
            all_params: uniform(device, "rcs splat all params", size),
            new_params: uniform(device, "rcs splat new params", size),
            resolve_pipeline: compute_pipeline(device, "rcs resolve", &resolve_layout, &resolve_module, "cs_main"),
            resolve_layout,
            resolve_params: uniform(device, "rcs resolve params", std::mem::size_of::<ResolveParams>() as u64),
            targets: None,
        })
    }

    /// The accumulation targets for a view of `size`.
    pub fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if self.targets.as_ref().is_some_and(|(t, _)| (t.texture.width(), t.texture.height()) == size) {
            return;
        }
        use wgpu::TextureUsages as U;
        let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        self.targets = Some((
            Target::new(device, "rcs splat weighted", size, ACCUM_FORMAT, usage),
            Target::new(device, "rcs splat plain", size, ACCUM_FORMAT, usage),
        ));
    }

    /// The targets: (sum w E^ with gradients, sum w; sum w E, record count).
    pub fn targets(&self) -> Option<&(Target, Target)> {
        self.targets.as_ref()
    }

    /// Splats records at accuracy `accuracy`.
    pub fn record(&self, inputs: &mut GiInputs<'_>, store: &Store, which: Splat, accuracy: f32) {
        let Some((weighted, plain)) = &self.targets else { return };
        let (buffer, mode, instances, load) = match which {
            Splat::All(n) => (&self.all_params, 0, n, wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)),
            Splat::New(n) => (&self.new_params, 1, n, wgpu::LoadOp::Load),
        };
        let params = SplatParams { accuracy: [accuracy, 0.0, 0.0, 0.0], mode: [mode, 0, 0, 0] };
        inputs.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&params));
        let t = inputs.targets;
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs splat bind group"),
            layout: &self.layout,
            entries: &[
                entry(0, inputs.frame_buffer),
                entry(1, buffer),
                entry(2, &store.records),
                entry(3, &store.splat_list),
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(&t.depth.view) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&t.normal.view) },
            ],
        });
        let ts = inputs.timer.scope(if mode == 0 { "rcs splat" } else { "rcs splat new" });
        let colour = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
            })
        };
        let mut pass = inputs.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("rcs splat"),
            color_attachments: &[colour(&weighted.view), colour(&plain.view)],
            depth_stencil_attachment: None,
            timestamp_writes: ts.as_ref().map(|t| t.render_writes(true, true)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if instances > 0 {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..6, 0..instances);
        }
    }

    /// Writes E / pi into the frame's indirect target.
    pub fn resolve(&self, inputs: &mut GiInputs<'_>, gradients: bool) {
        let Some((weighted, plain)) = &self.targets else { return };
        let params = ResolveParams { mode: [u32::from(gradients), 0, 0, 0] };
        inputs.queue.write_buffer(&self.resolve_params, 0, bytemuck::bytes_of(&params));
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs resolve bind group"),
            layout: &self.resolve_layout,
            entries: &[
                entry(0, &self.resolve_params),
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&weighted.view) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&plain.view) },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&inputs.targets.indirect.view),
                },
            ],
        });
        let (w, h) = inputs.targets.size;
        let mut pass = inputs.compute_pass("rcs resolve");
        pass.set_pipeline(&self.resolve_pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
    }

    /// Frees the targets.
    pub fn release(&mut self) {
        self.targets = None;
    }

    /// Bytes held.
    pub fn gpu_bytes(&self) -> u64 {
        self.targets.as_ref().map_or(0, |(a, b)| texture_bytes(&a.texture) + texture_bytes(&b.texture))
    }
}
