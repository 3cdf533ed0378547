//! Exposure and tonemapping from the linear HDR image to the gamma-encoded display image
//! (`shaders/render/tonemap.wgsl`).

use wgpu::util::DeviceExt as _;

use super::layouts::{storage_texture_entry, texture_entry, uniform_entry};
use super::lighting::TILE;
use super::shaders::{self, ShaderError};
use super::targets::formats;
use super::timing::TimestampPair;
use super::uniforms::TonemapUniforms;
use crate::settings::{Tonemap, ViewSettings};

/// The tonemap pipeline and its parameters.
pub struct TonemapPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
}

impl TonemapPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tonemap layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, wgpu::TextureSampleType::Float { filterable: false }),
                storage_texture_entry(2, formats::LDR),
            ],
        });
        let module = shaders::module(device, "render/tonemap.wgsl")?;
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("tonemap pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("tonemap pipeline"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tonemap params"),
            contents: bytemuck::bytes_of(&TonemapUniforms { exposure: [1.0; 4], op: [0; 4] }),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        Ok(Self { pipeline, layout, params })
    }

    /// A bind group reading `hdr` and writing `ldr`.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        hdr: &wgpu::TextureView,
        ldr: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.params.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(hdr) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(ldr) },
            ],
        })
    }

    /// Writes the parameters and records the pass.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        view: &ViewSettings,
        size: (u32, u32),
        timestamps: Option<TimestampPair<'_>>,
    ) {
        let op = match view.tonemap {
            Tonemap::Clamp => 0,
            Tonemap::Reinhard => 1,
            Tonemap::Aces => 2,
        };
        let params = TonemapUniforms { exposure: [view.exposure_ev.exp2(), 0.0, 0.0, 0.0], op: [op, 0, 0, 0] };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("tonemap pass"),
            timestamp_writes: timestamps.as_ref().map(TimestampPair::compute_writes),
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(TILE), size.1.div_ceil(TILE), 1);
    }
}
