//! Record computation, step 2: one workgroup per record reduces its hemisphere plane to the
//! record (irradiance with the border compensation, harmonic mean distance, Ward and Heckbert's
//! gradients, the light check's strata, secondary record sites), `rcs_reduce.wgsl`.

use bytemuck::{Pod, Zeroable};

use super::hemisphere::Atlas;
use super::store::Store;
use super::{entry, uniform};
use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{compute_pipeline, storage_entry, storage_rw_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};

/// `ReduceParams` in `rcs_reduce.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ReduceParams {
    /// x = plane texels per side, y = planes per atlas row, z = jobs, w unused.
    pub sizes: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<ReduceParams>() == 16);

/// The reduction pipeline.
pub struct ReducePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
}

impl ReducePass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs reduce layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, unfilterable),
                texture_entry(2, c, unfilterable),
                storage_entry(3, c),
                storage_entry(4, c),
                storage_rw_entry(5),
                storage_rw_entry(6),
                storage_rw_entry(7),
                storage_rw_entry(8),
                texture_entry(9, c, unfilterable),
                uniform_entry(10, c, false),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_reduce.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "rcs reduce", &layout, &module, "cs_main"),
            layout,
            params: uniform(device, "rcs reduce params", std::mem::size_of::<ReduceParams>() as u64),
        })
    }

    /// Reduces `count` planes of `atlas` into their records.
    pub fn record(&self, inputs: &mut GiInputs<'_>, atlas: &Atlas, store: &Store, count: u32) {
        let params = ReduceParams { sizes: [atlas.resolution, atlas.per_row, count, 0] };
        inputs.queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs reduce bind group"),
            layout: &self.layout,
            entries: &[
                entry(0, &self.params),
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&atlas.radiance.view) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&atlas.surface.view) },
                entry(3, &store.weights),
                entry(4, &store.jobs),
                entry(5, &store.records),
                entry(6, &store.check_strata),
                entry(7, &store.results),
                entry(8, &store.secondaries),
                wgpu::BindGroupEntry { binding: 9, resource: wgpu::BindingResource::TextureView(&inputs.sky.view) },
                entry(10, &inputs.sky.buffer),
            ],
        });
        inputs.encoder.clear_buffer(&store.secondaries, 0, Some(16));
        let mut pass = inputs.compute_pass("rcs reduce");
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(count, 1, 1);
    }
}
