//! `sshgi`'s bounce tail (not in Soler et al. 2010): the bounces after the last one gathered,
//! added as a geometric series of the last bounce at the ratio of the last bounce's light on the
//! start level to the previous bounce's (`sshgi_tail.wgsl`: per-tile sums, one workgroup for the
//! ratio, then the add). A room's bounces decay at about its albedo, so a fixed count of bounces
//! leaves out a share of the light that grows with it and with how late the light reaches the
//! view: the suite's cluttered room read 0.688 / 0.753 / 0.795 of the path tracer's energy at 2 /
//! 3 / 4 bounces, the development levels lit through doorways gained 0.06-0.14 at the fourth.

use crate::render::layouts::{
    compute_pipeline, storage_entry, storage_rw_entry, storage_texture_entry, texture_entry, uniform_entry,
};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::formats;

/// The tail's layout (0: the steps' parameter slot, unused; 1 the previous bounce, 2 the last,
/// 3 the sum so far, 4 the sum with the tail, 5 the factor and per-tile sums, 6 the sender power
/// prefix sums, whose last two floats are the list's total power of the previous and the last
/// bounce, or [`no_world`]) and its three pipelines: sums, ratio, add.
pub(super) fn pipelines(
    device: &wgpu::Device,
) -> Result<(wgpu::BindGroupLayout, [wgpu::ComputePipeline; 3]), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let float = wgpu::TextureSampleType::Float { filterable: false };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sshgi tail layout"),
        entries: &[
            uniform_entry(0, c, true),
            texture_entry(1, c, float),
            texture_entry(2, c, float),
            texture_entry(3, c, float),
            storage_texture_entry(4, formats::HDR),
            storage_rw_entry(5),
            storage_entry(6, c),
        ],
    });
    let module = shaders::module(device, "render/gi/sshgi/sshgi_tail.wgsl")?;
    let pipelines = [("sshgi tail sums", "sums"), ("sshgi tail ratio", "ratio"), ("sshgi tail add", "add")]
        .map(|(label, entry)| compute_pipeline(device, label, &layout, &module, entry));
    Ok((layout, pipelines))
}

/// What the tail reads in place of the sender list's powers when there is no list (no panorama):
/// two zeros, so the ratio is the screen's alone.
pub(super) fn no_world(device: &wgpu::Device) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sshgi tail: no sender powers"),
        size: 8,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}

/// The factor and one pair of sums per 8x8 tile of a start level of `size`.
pub(super) fn buffer(device: &wgpu::Device, size: (u32, u32)) -> wgpu::Buffer {
    let tiles = u64::from(size.0.div_ceil(8)) * u64::from(size.1.div_ceil(8));
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sshgi tail sums"),
        size: 16 * (1 + tiles),
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}
