//! The composite pass (`shaders/render/composite.wgsl`): adds the active technique's indirect
//! term to the direct term as its [`GiOutput`] says, into the HDR target, the indirect term
//! times the volumetric obscurance factor where it applies ([`super::obscurance`]).

use super::gi::GiOutput;
use super::layouts::{compute_pipeline, storage_texture_entry, texture_entry, uniform_entry};
use super::shaders::{self, ShaderError};
use super::targets::{ViewTargets, formats};
use super::timing::TimestampPair;
use super::uniforms::CompositeUniforms;

/// What a frame's composite adds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Composite {
    /// What the technique wrote into `indirect`.
    pub output: GiOutput,
    /// Multiply the indirect term by the volumetric obscurance factor.
    pub obscurance: bool,
}

/// The composite pipeline and its parameter block.
pub struct CompositePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
}

/// The shader's code for an output kind.
fn code(output: GiOutput) -> u32 {
    match output {
        GiOutput::Nothing => 0,
        GiOutput::IrradianceOverPi => 1,
        GiOutput::Radiance => 2,
        GiOutput::Complete => 3,
    }
}

impl CompositePass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("composite layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                texture_entry(5, c, unfilterable),
                storage_texture_entry(6, formats::HDR),
                texture_entry(7, c, unfilterable),
            ],
        });
        let module = shaders::module(device, "render/composite.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "composite pipeline", &layout, &module, "cs_main"),
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("composite params"),
                size: std::mem::size_of::<CompositeUniforms>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            layout,
        })
    }

    /// The bind group over the view targets.
    pub fn bind_group(&self, device: &wgpu::Device, frame: &wgpu::Buffer, t: &ViewTargets) -> wgpu::BindGroup {
        use super::layouts::view_entry as view;
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("composite bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.params.as_entire_binding() },
                view(2, &t.depth.view),
                view(3, &t.albedo.view),
                view(4, &t.direct.view),
                view(5, &t.indirect.view),
                view(6, &t.hdr.view),
                view(7, &t.vo.view),
            ],
        })
    }

    /// Records the pass.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        group: &wgpu::BindGroup,
        what: Composite,
        size: (u32, u32),
        timestamps: Option<TimestampPair<'_>>,
    ) {
        let params = CompositeUniforms { output: [code(what.output), u32::from(what.obscurance), 0, 0] };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("composite pass"),
            timestamp_writes: timestamps.as_ref().map(TimestampPair::compute_writes),
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(8), size.1.div_ceil(8), 1);
    }
}
