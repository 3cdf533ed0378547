//! The prefix sums of a bounce's sender power (`sshgi_sender_cdf.wgsl`), from which the
//! panorama's gather and receive draw part of their sender picks by power
//! (`sshgi_sender_pick.wgsl`; not in Soler et al. 2010). On the suite's three rooms seen from the
//! unlit room, most of the 8,192 senders are dark and the few the spot lights carry the light:
//! picked uniformly, a receiver's samples met them in some frames and not in others. Two passes:
//! a workgroup per block of [`BLOCK`] senders scans the block, then one workgroup scans the
//! blocks' totals (at most [`MAX_BLOCKS`]).

use crate::render::layouts::{compute_pipeline, storage_entry, storage_rw_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};

/// Senders per block (`BLOCK` in `sshgi_sender_cdf.wgsl` and `PICK_BLOCK` in
/// `sshgi_sender_pick.wgsl`).
pub const BLOCK: u32 = 256;

/// The blocks the scan of totals takes: 256 threads of two (`PER_THREAD`).
pub const MAX_BLOCKS: u32 = 512;

// The largest list the settings allow: six faces of 128^2 and 16,384 hidden senders.
const _: () = assert!((6 * 128 * 128 + 16_384_u32).div_ceil(BLOCK) <= MAX_BLOCKS);

/// The list's total power of the last two bounces, kept after the prefix sums (previous,
/// last): the world's ratio the bounce tail reads (`sshgi_tail.wgsl`).
pub const HISTORY: u64 = 2;

/// Floats of the prefix sums of a list of `count` senders: one per sender, one per block, and
/// the [`HISTORY`] of the list's totals.
pub fn floats(count: u64) -> u64 {
    count + count.div_ceil(u64::from(BLOCK)) + HISTORY
}

/// The layout (1: the panorama's parameter slot, whose first word is the sender count; 2 the
/// sender list, 3 this bounce's sender radiance, 4 the prefix sums) and the pipelines: the
/// blocks' scans (a workgroup of 256 per block) and the scan of their totals (one workgroup).
pub(super) fn pipelines(
    device: &wgpu::Device,
) -> Result<(wgpu::BindGroupLayout, [wgpu::ComputePipeline; 2]), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sshgi sender cdf layout"),
        entries: &[uniform_entry(1, c, true), storage_entry(2, c), storage_entry(3, c), storage_rw_entry(4)],
    });
    let module = shaders::module(device, "render/gi/sshgi/sshgi_sender_cdf.wgsl")?;
    let pipelines = [("sshgi sender cdf blocks", "blocks"), ("sshgi sender cdf totals", "totals")]
        .map(|(label, entry)| compute_pipeline(device, label, &layout, &module, entry));
    Ok((layout, pipelines))
}
