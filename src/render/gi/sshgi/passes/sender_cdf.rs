//! The prefix sums of a bounce's sender power (`sshgi_sender_cdf.wgsl`), from which the
//! panorama's gather and receive draw part of their sender picks by power
//! (`sshgi_sender_pick.wgsl`; not in Soler et al. 2010). On the suite's three rooms seen from the
//! unlit room, most of the 8,192 senders are dark and the few the spot lights carry the light:
//! picked uniformly, a receiver's samples met them in some frames and not in others.

use crate::render::layouts::{compute_pipeline, storage_entry, storage_rw_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};

/// The layout (1: the panorama's parameter slot, whose first word is the sender count; 2 the
/// sender list, 3 this bounce's sender radiance, 4 the prefix sums) and the pipeline: one
/// workgroup of 256 threads.
pub(super) fn pipeline(device: &wgpu::Device) -> Result<(wgpu::BindGroupLayout, wgpu::ComputePipeline), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sshgi sender cdf layout"),
        entries: &[uniform_entry(1, c, true), storage_entry(2, c), storage_entry(3, c), storage_rw_entry(4)],
    });
    let module = shaders::module(device, "render/gi/sshgi/sshgi_sender_cdf.wgsl")?;
    let pipeline = compute_pipeline(device, "sshgi sender cdf", &layout, &module, "prefix");
    Ok((layout, pipeline))
}
