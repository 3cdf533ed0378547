//! Deferred direct lighting (`shaders/render/lighting.wgsl`), one compute pass over the
//! G-buffer into the view's `direct` target, with the emission the camera sees and the sky, and
//! the same light as diffuse senders send it into `exitance`.

use super::layouts::{
    comparison_sampler_entry, depth_array_entry, shadow_sampler, storage_entry, storage_texture_entry, texture_entry,
    uniform_entry,
};
use super::shaders::{self, ShaderError};
use super::targets::{ViewTargets, formats};

/// Workgroup edge of the full-screen compute passes.
pub const TILE: u32 = 8;

/// The lighting pipeline and its bind groups.
pub struct LightingPass {
    pipeline: wgpu::ComputePipeline,
    inputs_layout: wgpu::BindGroupLayout,
    targets_layout: wgpu::BindGroupLayout,
    shadow_sampler: wgpu::Sampler,
}

/// Buffers and textures the lighting pass reads besides the G-buffer.
pub struct LightingInputs<'a> {
    pub frame: &'a wgpu::Buffer,
    pub lights: &'a wgpu::Buffer,
    pub shadow_views: &'a wgpu::Buffer,
    pub shadow_maps: &'a wgpu::TextureView,
    pub sky: &'a super::sky::SkyGpu,
}

impl LightingPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let inputs_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lighting inputs layout"),
            entries: &[
                uniform_entry(0, c, false),
                storage_entry(1, c),
                storage_entry(2, c),
                depth_array_entry(3, c),
                comparison_sampler_entry(4, c),
                texture_entry(5, c, wgpu::TextureSampleType::Float { filterable: false }),
                uniform_entry(6, c, false),
            ],
        });
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let targets_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lighting targets layout"),
            entries: &[
                texture_entry(0, c, wgpu::TextureSampleType::Depth),
                texture_entry(1, c, unfilterable),
                texture_entry(2, c, unfilterable),
                texture_entry(3, c, unfilterable),
                storage_texture_entry(4, formats::HDR),
                texture_entry(5, c, unfilterable),
                storage_texture_entry(6, formats::EXITANCE),
            ],
        });
        let module = shaders::module(device, "render/lighting.wgsl")?;
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lighting pipeline layout"),
            bind_group_layouts: &[Some(&inputs_layout), Some(&targets_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("lighting pipeline"),
            layout: Some(&layout),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let shadow_sampler = shadow_sampler(device, "shadow comparison sampler");
        Ok(Self { pipeline, inputs_layout, targets_layout, shadow_sampler })
    }

    /// The layout of [`Self::inputs_bind_group`] (for passes that light points of their own with
    /// the same lights and shadow maps).
    pub fn inputs_layout(&self) -> &wgpu::BindGroupLayout {
        &self.inputs_layout
    }

    /// The bind group of lights, shadows and frame constants.
    pub fn inputs_bind_group(&self, device: &wgpu::Device, inputs: &LightingInputs<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lighting inputs bind group"),
            layout: &self.inputs_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: inputs.frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: inputs.lights.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: inputs.shadow_views.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(inputs.shadow_maps) },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::Sampler(&self.shadow_sampler) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&inputs.sky.view) },
                wgpu::BindGroupEntry { binding: 6, resource: inputs.sky.buffer.as_entire_binding() },
            ],
        })
    }

    /// The bind group of the view targets.
    pub fn targets_bind_group(&self, device: &wgpu::Device, t: &ViewTargets) -> wgpu::BindGroup {
        use super::layouts::view_entry as view;
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lighting targets bind group"),
            layout: &self.targets_layout,
            entries: &[
                view(0, &t.depth.view),
                view(1, &t.albedo.view),
                view(2, &t.normal.view),
                view(3, &t.material.view),
                view(4, &t.direct.view),
                view(5, &t.emission.view),
                view(6, &t.exitance.view),
            ],
        })
    }

    /// Records the pass.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &wgpu::BindGroup,
        targets: &wgpu::BindGroup,
        size: (u32, u32),
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("lighting pass"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, inputs, &[]);
        pass.set_bind_group(1, targets, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(TILE), size.1.div_ceil(TILE), 1);
    }
}
