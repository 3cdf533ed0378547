//! The GPU resources of one ISM atlas size and point count: every buffer the maps passes read
//! and write ([`Buffers`]), and the bind groups over them ([`Groups`]), made together by
//! `IsmGather::ensure` whenever the settings or the point pool change size.

use super::{IsmGather, Key, PULL_LEVELS, VPL_BYTES, level_base};
use crate::render::gi::ism::params::{BounceParams, GpuCluster, PullPushParams, SelectParams, SplatParams};

/// Where the tail's partial screen sums start (words) and how many pairs there are: the
/// `TAIL_SUMS_AT` and `TAIL_SLOTS` of `ism_bounce.wgsl` and `ism_shade.wgsl`.
const TAIL_SUMS_AT: u64 = 8;
const TAIL_SLOTS: u64 = 1024;

/// The bounce tail's state (`ism_bounce.wgsl` `tail`): 8 words of running means and scale, then
/// `TAIL_SLOTS` pairs of partial screen sums, one per group of the shading's workgroups
/// (`ism_shade.wgsl`; one pair for the whole screen made every workgroup contend for it).
const TAIL_BYTES: u64 = (TAIL_SUMS_AT + 2 * TAIL_SLOTS) * 4;

/// The buffers of one atlas size and point count ([`IsmGather::ensure`]), before they join
/// their bind groups in [`Sized`].
pub(super) struct Buffers {
    pub(super) atlas: wgpu::Buffer,
    pub(super) coarse: wgpu::Buffer,
    pub(super) points: wgpu::Buffer,
    pub(super) all_vpls: wgpu::Buffer,
    pub(super) normals: wgpu::Buffer,
    pub(super) albedo: wgpu::Buffer,
    pub(super) specular: wgpu::Buffer,
    pub(super) selection: wgpu::Buffer,
    pub(super) lit: wgpu::Buffer,
    pub(super) chosen: wgpu::Buffer,
    pub(super) chosen_all: wgpu::Buffer,
    pub(super) tail: wgpu::Buffer,
    pub(super) clips: wgpu::Buffer,
    pub(super) clusters: wgpu::Buffer,
}

impl Buffers {
    /// Every buffer sized for `key` (contents undefined until the first upload and frame).
    pub(super) fn new(device: &wgpu::Device, key: Key) -> Self {
        let side = key.r * IsmGather::tiles_per_row(key.vpls * key.bounces);
        let buffer = |label: &str, texels: u32| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: u64::from(texels.max(1)) * 4,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let storage = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let slots = u64::from(key.vpls) * u64::from(key.per_ism);
        let clip_bytes = u64::from(key.points) * 16 * crate::precompute::open_edges::CLIPS_PER_POINT as u64;
        let cluster_count = key.points.div_ceil(crate::render::gi::ism::clusters::CLUSTER_POINTS as u32);
        Self {
            // Whole vec4 words, as the clear writes them (`ism_clear.wgsl`).
            atlas: buffer("ism atlas", (side * side).next_multiple_of(4)),
            // The coarse levels in one buffer, each after the finer ones (`level_base`): the
            // lookups read them too (`ism_lookup.wgsl`) with one binding.
            coarse: buffer("ism atlas coarse levels", level_base(side, PULL_LEVELS as u32 + 1)),
            points: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ism scene sample points"),
                size: u64::from(key.points.max(1)) * 16,
                // COPY_SRC: read back for oracles (`IsmTechnique::read_lookup_data`).
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            all_vpls: storage("ism vpls of every bounce", u64::from(key.vpls * key.bounces) * VPL_BYTES),
            normals: storage("ism sample point normals", u64::from(key.points) * 16),
            albedo: storage("ism sample point albedo", u64::from(key.points) * 16),
            specular: storage("ism sample point specular", u64::from(key.points) * 16),
            selection: storage("ism bounce selection", u64::from(key.vpls) * 8),
            lit: storage("ism bounce lit points", slots * 32),
            chosen: storage("ism chosen points", slots * 8),
            chosen_all: storage("ism chosen points of every set", slots * u64::from(key.bounces) * 4),
            tail: storage("ism bounce tail state", TAIL_BYTES),
            clips: storage("ism sample point clip lines", clip_bytes),
            clusters: storage(
                "ism point clusters",
                u64::from(cluster_count) * std::mem::size_of::<GpuCluster>() as u64,
            ),
        }
    }
}

/// The bind groups over [`Buffers`].
pub(super) struct Groups {
    pub(super) splat: wgpu::BindGroup,
    pub(super) select: wgpu::BindGroup,
    pub(super) bounce: wgpu::BindGroup,
    pub(super) pull_push: wgpu::BindGroup,
}

impl IsmGather {
    /// The splat, point-selection, bounce and pull-push bind groups over `b`.
    pub(super) fn bind_groups(&self, device: &wgpu::Device, b: &Buffers) -> Groups {
        use crate::render::gi::ism::screen::buf;
        fn slot(b: u32, x: &wgpu::Buffer, size: u64) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding: b,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: x,
                    offset: 0,
                    size: wgpu::BufferSize::new(size),
                }),
            }
        }
        let group = |label: &str, layout: &wgpu::BindGroupLayout, entries: &[wgpu::BindGroupEntry<'_>]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(label), layout, entries })
        };
        let splat = group(
            "ism splat bind group",
            &self.splat_layout,
            &[
                slot(0, &self.splat_params, std::mem::size_of::<SplatParams>() as u64),
                buf(1, &b.points),
                buf(2, &b.all_vpls),
                buf(3, &b.atlas),
                buf(4, &b.normals),
                buf(5, &b.chosen),
                buf(6, &b.clips),
            ],
        );
        let select = group(
            "ism point selection bind group",
            &self.select_layout,
            &[
                slot(0, &self.select_params, std::mem::size_of::<SelectParams>() as u64),
                buf(1, &b.clusters),
                buf(2, &b.normals),
                buf(3, &b.all_vpls),
                buf(4, &b.chosen),
                buf(5, &b.chosen_all),
            ],
        );
        let bounce = group(
            "ism bounce bind group",
            &self.bounce_layout,
            &[
                slot(0, &self.bounce_params, std::mem::size_of::<BounceParams>() as u64),
                buf(1, &b.points),
                buf(2, &b.normals),
                buf(3, &b.albedo),
                buf(4, &b.all_vpls),
                buf(5, &b.atlas),
                buf(6, &b.selection),
                buf(7, &b.lit),
                buf(8, &b.specular),
                buf(9, &b.chosen),
                buf(10, &b.clips),
                buf(11, &b.chosen_all),
                buf(12, &b.tail),
                buf(13, &b.coarse),
            ],
        );
        let pull_push = group(
            "ism pull-push bind group",
            &self.pp_layout,
            &[
                slot(0, &self.pp_params, std::mem::size_of::<PullPushParams>() as u64),
                buf(1, &b.atlas),
                buf(2, &b.coarse),
            ],
        );
        Groups { splat, select, bounce, pull_push }
    }
}

#[cfg(test)]
mod tests {
    use super::{TAIL_SLOTS, TAIL_SUMS_AT};

    /// The shaders that write and read the tail's sums lay them out as the buffer is sized.
    #[test]
    fn the_tail_buffer_holds_the_pairs_the_shaders_address() {
        for (name, text) in [
            ("ism_bounce.wgsl", include_str!("../../../../../shaders/render/gi/ism/ism_bounce.wgsl")),
            ("ism_shade.wgsl", include_str!("../../../../../shaders/render/gi/ism/ism_shade.wgsl")),
        ] {
            assert!(text.contains(&format!("const TAIL_SUMS_AT: u32 = {TAIL_SUMS_AT}u;")), "{name}: TAIL_SUMS_AT");
            assert!(text.contains(&format!("const TAIL_SLOTS: u32 = {TAIL_SLOTS}u;")), "{name}: TAIL_SLOTS");
        }
    }
}
