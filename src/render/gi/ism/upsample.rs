//! The geometry-aware filter when `ism shade` gathers at half resolution
//! ([`crate::settings::ShadeResolution`]): every view pixel averages the n x n gathered samples
//! around it (one of each interleave phase) that lie on its tangent plane with a like normal,
//! read from the split G-buffer that the gathering used (`ism_upsample.wgsl`). It runs before
//! the temporal merge, which then merges the filtered light, as the SH filter's path does.

use crate::render::layouts::{compute_pipeline, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, ViewTargets, formats};
use crate::settings::IsmSettings;

use super::params::UpsampleParams;
use super::screen::{buf, tex, uniform};

/// The split G-buffer and accumulation the filter reads: positions, normals, gathered light.
pub struct Gathered<'a> {
    pub position: &'a Target,
    pub normal: &'a Target,
    pub raw: &'a Target,
}

/// The filter's pipeline and parameters.
pub struct IsmUpsample {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
}

impl IsmUpsample {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism upsample layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, unfilterable),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                texture_entry(5, c, wgpu::TextureSampleType::Depth),
                texture_entry(6, c, unfilterable),
                storage_texture_entry(7, formats::HDR),
            ],
        });
        let module = shaders::module(device, "render/gi/ism/ism_upsample.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "ism upsample", &layout, &module, "cs_main"),
            params: uniform(device, "ism upsample params", std::mem::size_of::<UpsampleParams>() as u64),
            layout,
        })
    }

    /// The bind group that filters `gathered` into `out` (a view-sized HDR target).
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        frame_buffer: &wgpu::Buffer,
        gathered: &Gathered<'_>,
        targets: &ViewTargets,
        out: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism upsample bind group"),
            layout: &self.layout,
            entries: &[
                buf(0, frame_buffer),
                buf(1, &self.params),
                tex(2, &gathered.raw.view),
                tex(3, &gathered.position.view),
                tex(4, &gathered.normal.view),
                tex(5, &targets.depth.view),
                tex(6, &targets.normal.view),
                tex(7, out),
            ],
        })
    }

    /// Writes this frame's parameters: interleave `n`, gathering step `step`, the gathered
    /// samples' count along each axis.
    pub fn write_params(
        &self,
        queue: &wgpu::Queue,
        n: u32,
        step: u32,
        samples: (u32, u32),
        settings: &IsmSettings,
        d_max: f32,
    ) {
        let p = UpsampleParams {
            counts: [n, step, samples.0, samples.1],
            params: [settings.filter_depth, settings.filter_normal, d_max, 0.0],
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&p));
    }

    /// Records the filter over a view of `size`.
    pub fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>, group: &wgpu::BindGroup, size: (u32, u32)) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(8), size.1.div_ceil(8), 1);
    }
}

/// The gathered samples along each axis for a view of `view` at gathering step `step`.
pub fn gathered_size(view: (u32, u32), step: u32) -> (u32, u32) {
    let s = step.max(1);
    (view.0.div_ceil(s), view.1.div_ceil(s))
}
