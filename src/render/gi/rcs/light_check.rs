//! Which records a light edit changes (`rcs_check.wgsl`): each record keeps the surfaces its 64
//! check strata saw; relighting them with the edited lights and comparing with the sum stored
//! when the record was computed lists the records to renew. The rest of the cache stays.

use bytemuck::{Pod, Zeroable};

use super::store::Store;
use super::{entry, uniform};
use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{
    comparison_sampler_entry, compute_pipeline, depth_array_entry, shadow_sampler, storage_entry, storage_rw_entry,
    uniform_entry,
};
use crate::render::shaders::{self, ShaderError};

/// `CheckParams` in `rcs_check.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CheckParams {
    /// x = mode (0 store for this round's jobs, 1 compare every slot), y = count.
    pub mode: [u32; 4],
    /// x = tolerance.
    pub tolerance: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<CheckParams>() == 32);

/// What the check does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckMode {
    /// Store the sum in this round's `count` jobs' records.
    Store,
    /// Compare the first `count` slots and list the changed ones.
    Compare,
}

/// The check pipeline.
pub struct LightCheckPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    store_params: wgpu::Buffer,
    compare_params: wgpu::Buffer,
}

impl LightCheckPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs light check layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                storage_entry(2, c),
                storage_entry(3, c),
                depth_array_entry(4, c),
                comparison_sampler_entry(5, c),
                storage_rw_entry(6),
                storage_entry(7, c),
                storage_entry(8, c),
                storage_rw_entry(9),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_check.wgsl")?;
        let size = std::mem::size_of::<CheckParams>() as u64;
        Ok(Self {
            pipeline: compute_pipeline(device, "rcs light check", &layout, &module, "cs_main"),
            layout,
            sampler: shadow_sampler(device, "rcs light check shadow sampler"),
            store_params: uniform(device, "rcs light check store params", size),
            compare_params: uniform(device, "rcs light check compare params", size),
        })
    }

    /// Records the check over `count` jobs or slots.
    pub fn record(&self, inputs: &mut GiInputs<'_>, store: &Store, mode: CheckMode, count: u32, tolerance: f32) {
        if count == 0 {
            return;
        }
        let (buffer, m) = match mode {
            CheckMode::Store => (&self.store_params, 0),
            CheckMode::Compare => (&self.compare_params, 1),
        };
        let params = CheckParams { mode: [m, count, 0, 0], tolerance: [tolerance, 0.0, 0.0, 0.0] };
        inputs.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&params));
        if mode == CheckMode::Compare {
            inputs.encoder.clear_buffer(&store.changed, 0, Some(16));
        }
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs light check bind group"),
            layout: &self.layout,
            entries: &[
                entry(0, buffer),
                entry(1, inputs.frame_buffer),
                entry(2, inputs.lights.buffer),
                entry(3, inputs.lights.shadow_views),
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(inputs.lights.shadow_maps),
                },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::Sampler(&self.sampler) },
                entry(6, &store.records),
                entry(7, &store.check_strata),
                entry(8, &store.jobs),
                entry(9, &store.changed),
            ],
        });
        let mut pass = inputs.compute_pass(match mode {
            CheckMode::Store => "rcs light check store",
            CheckMode::Compare => "rcs light check",
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(count, 1, 1);
    }
}
