//! sshgi's solid voxelisation of the view and its OR-reduced levels (Soler et al. 2010 after
//! Eisemann & Décoret 2008; `sshgi_voxelize.wgsl`, `sshgi_voxel_mip.wgsl`): 128 depth slices per
//! pixel, a bit set where the pixel's ray is inside a closed solid, for the gather's visibility
//! march. Rebuilt every frame (the camera and objects move); its cost does not depend on lights.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::render::layouts::{Layouts, compute_pipeline, storage_entry, uniform_entry};
use crate::render::scene_gpu::{SceneGpu, Vertex};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::Target;
use crate::render::timing::TimestampPair;

/// Bytes of one pixel's column (128 bits).
const COLUMN_BYTES: u64 = 16;
/// Bytes between two levels' parameter slots.
const SLOT: u64 = 256;
/// Most levels (the pyramid's cap).
const MAX_LEVELS: u64 = 8;

/// `VoxelParams` in `sshgi_voxelize.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct VoxelParams {
    /// near, far (view depth, m), slices per metre, the raster's width in columns (set by
    /// [`VoxelPass::record`]).
    pub range: [f32; 4],
    /// xyz the camera's forward axis.
    pub forward: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<VoxelParams>() == 32);

/// `VoxelMipParams` in `sshgi_voxel_mip.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct MipParams {
    /// Fine width and height, coarse width and height.
    pub sizes: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<MipParams>() == 16);

/// The voxel depth range for a camera at `camera` looking along `forward` at a scene within
/// `bounds` (min, max corners): from the nearest to the farthest corner's view depth, the near
/// end at 0 when the camera is inside. `None` when nothing lies in front.
pub fn automatic_range(camera: Vec3, forward: Vec3, bounds: (Vec3, Vec3)) -> Option<(f32, f32)> {
    let (lo, hi) = bounds;
    let depths = (0..8).map(|i| {
        let c = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        (c - camera).dot(forward)
    });
    let (near, far) = depths.fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), d| (a.min(d), b.max(d)));
    (far > 0.0 && far.is_finite()).then(|| (near.max(0.0), far))
}

/// The finest level of a view of `size` whose columns fit in `limit` bytes (one storage binding
/// on the device): the voxelisation rasterises there, level 0 (a column per view pixel) wherever
/// it fits. A view of 5760 x 3240 (1920 x 1080 supersampled 3x) needs 299 MB at level 0, over a
/// software adapter's 128 MiB.
pub fn finest_fitting_level(size: (u32, u32), limit: u64) -> u32 {
    let bytes = |l: u32| u64::from((size.0 >> l).max(1)) * u64::from((size.1 >> l).max(1)) * COLUMN_BYTES;
    (0..MAX_LEVELS as u32 - 1).find(|&l| bytes(l) <= limit).unwrap_or(MAX_LEVELS as u32 - 1)
}

/// [`finest_fitting_level`] within `device`'s storage binding and buffer limits.
pub fn finest_level(device: &wgpu::Device, size: (u32, u32)) -> u32 {
    let limits = device.limits();
    finest_fitting_level(size, limits.max_storage_buffer_binding_size.min(limits.max_buffer_size))
}

struct Sized {
    size: (u32, u32),
    /// The level the voxelisation rasterises ([`finest_level`]); the levels below it hold a
    /// placeholder and are never marched.
    first: usize,
    levels: Vec<wgpu::Buffer>,
    sizes: Vec<(u32, u32)>,
    dummy: Target,
    /// The voxelisation's bind group and one per reduction, for the frame buffer they name.
    groups: Option<(wgpu::Buffer, wgpu::BindGroup, Vec<wgpu::BindGroup>)>,
}

/// The voxelisation pipeline and the per-level column buffers.
pub struct VoxelPass {
    pipeline: wgpu::RenderPipeline,
    draw_layout: wgpu::BindGroupLayout,
    mip_pipeline: wgpu::ComputePipeline,
    mip_layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    mip_params: wgpu::Buffer,
    sized: Option<Sized>,
}

impl VoxelPass {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let module = shaders::module(device, "render/gi/sshgi/sshgi_voxelize.wgsl")?;
        let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi voxelize layout"),
            entries: &[
                uniform_entry(0, stages, false),
                uniform_entry(1, wgpu::ShaderStages::FRAGMENT, false),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sshgi voxelize pipeline layout"),
            bind_group_layouts: &[Some(&draw_layout), Some(&layouts.object)],
            immediate_size: 0,
        });
        // Every surface counts (no culling, no depth test); the colour target only gives the
        // pass its size and is never written.
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("sshgi voxelize pipeline"),
            layout: Some(&layout),
            vertex: Vertex::state(&module),
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: wgpu::TextureFormat::R8Unorm,
                    blend: None,
                    write_mask: wgpu::ColorWrites::empty(),
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let c = wgpu::ShaderStages::COMPUTE;
        let mip_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi voxel mip layout"),
            entries: &[uniform_entry(0, c, true), storage_entry(1, c), crate::render::layouts::storage_rw_entry(2)],
        });
        let mip_module = shaders::module(device, "render/gi/sshgi/sshgi_voxel_mip.wgsl")?;
        let uniform = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Ok(Self {
            pipeline,
            draw_layout,
            mip_pipeline: compute_pipeline(device, "sshgi voxel mip", &mip_layout, &mip_module, "reduce"),
            mip_layout,
            params: uniform("sshgi voxel params", std::mem::size_of::<VoxelParams>() as u64),
            mip_params: uniform("sshgi voxel mip params", SLOT * MAX_LEVELS),
            sized: None,
        })
    }

    fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32), levels: u32, first: u32) {
        let levels = u64::from(levels).clamp(1, MAX_LEVELS) as usize;
        if self.sized.as_ref().is_some_and(|s| s.size == size && s.levels.len() == levels) {
            return;
        }
        let sizes: Vec<(u32, u32)> = (0..levels).map(|l| ((size.0 >> l).max(1), (size.1 >> l).max(1))).collect();
        let first = (first as usize).min(levels - 1);
        let buffers = sizes
            .iter()
            .enumerate()
            .map(|(l, &(w, h))| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("sshgi voxel columns"),
                    size: if l < first { COLUMN_BYTES } else { u64::from(w) * u64::from(h) * COLUMN_BYTES },
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let dummy = Target::new(
            device,
            "sshgi voxelize raster target",
            sizes[first],
            wgpu::TextureFormat::R8Unorm,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        self.sized = Some(Sized { size, first, levels: buffers, sizes, dummy, groups: None });
    }

    /// Voxelises the scene for a view of `size` at level `first` ([`finest_level`]) and reduces
    /// the levels after it up to `levels` levels (level 0 = the view).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffer: &wgpu::Buffer,
        gpu: &SceneGpu,
        size: (u32, u32),
        levels: u32,
        first: u32,
        params: VoxelParams,
        timestamps: Option<TimestampPair<'_>>,
    ) {
        self.ensure(device, size, levels, first);
        let Some(s) = &mut self.sized else { return };
        if s.groups.as_ref().is_none_or(|(frame, ..)| frame != frame_buffer) {
            let draw = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("sshgi voxelize bind group"),
                layout: &self.draw_layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.params.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: s.levels[s.first].as_entire_binding() },
                ],
            });
            let mips = (s.first + 1..s.levels.len())
                .map(|l| {
                    device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("sshgi voxel mip bind group"),
                        layout: &self.mip_layout,
                        entries: &[
                            wgpu::BindGroupEntry {
                                binding: 0,
                                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                    buffer: &self.mip_params,
                                    offset: 0,
                                    size: wgpu::BufferSize::new(16),
                                }),
                            },
                            wgpu::BindGroupEntry { binding: 1, resource: s.levels[l - 1].as_entire_binding() },
                            wgpu::BindGroupEntry { binding: 2, resource: s.levels[l].as_entire_binding() },
                        ],
                    })
                })
                .collect();
            // The reductions' sizes change only with the view.
            let mut slots = [0u8; (SLOT * MAX_LEVELS) as usize];
            for l in s.first + 1..s.levels.len() {
                let (f, c) = (s.sizes[l - 1], s.sizes[l]);
                let p = MipParams { sizes: [f.0, f.1, c.0, c.1] };
                slots[l * SLOT as usize..l * SLOT as usize + 16].copy_from_slice(bytemuck::bytes_of(&p));
            }
            queue.write_buffer(&self.mip_params, 0, &slots[..SLOT as usize * s.levels.len()]);
            s.groups = Some((frame_buffer.clone(), draw, mips));
        }
        let Some((_, draw_group, mip_groups)) = &s.groups else { return };
        // The raster's width, for the fragment's column index.
        let params = VoxelParams {
            range: [params.range[0], params.range[1], params.range[2], s.sizes[s.first].0 as f32],
            ..params
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        encoder.clear_buffer(&s.levels[s.first], 0, None);
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("sshgi voxelize"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &s.dummy.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: timestamps.as_ref().map(|t| t.render_writes(true, s.levels.len() == s.first + 1)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, draw_group, &[]);
            pass.set_bind_group(1, &gpu.object_bind_group, &[]);
            gpu.draw_geometry(&mut pass);
        }
        if s.levels.len() > s.first + 1 {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("sshgi voxel levels"),
                timestamp_writes: timestamps.as_ref().map(|t| t.compute_end_writes()),
            });
            pass.set_pipeline(&self.mip_pipeline);
            for (l, group) in mip_groups.iter().enumerate().map(|(i, g)| (s.first + 1 + i, g)) {
                pass.set_bind_group(0, group, &[(l as u64 * SLOT) as u32]);
                pass.dispatch_workgroups(s.sizes[l].0.div_ceil(8), s.sizes[l].1.div_ceil(8), 1);
            }
        }
    }

    /// The columns of level `l` (row-major, four words per texel) of the last frame; none below
    /// the level the voxelisation rasterised.
    pub fn level(&self, l: usize) -> Option<&wgpu::Buffer> {
        let s = self.sized.as_ref()?;
        if l < s.first { None } else { s.levels.get(l) }
    }

    /// The level the last voxelisation rasterised (0: a column per view pixel; coarser where
    /// the view's columns exceed one storage binding).
    pub fn first_level(&self) -> u32 {
        self.sized.as_ref().map_or(0, |s| s.first as u32)
    }

    /// The size of level `l`.
    pub fn level_size(&self, l: usize) -> Option<(u32, u32)> {
        self.sized.as_ref()?.sizes.get(l).copied()
    }

    /// Level `l`'s columns as an image for the inspector: r = the solid share of the 128 slices,
    /// g = the first solid slice / 128 (1 where none), b = the last solid slice / 128.
    pub fn read_level(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        l: usize,
    ) -> Option<Result<crate::image_io::HdrImage, crate::render::readback::ReadbackError>> {
        let (buffer, (w, h)) = (self.level(l)?, self.level_size(l)?);
        Some(crate::render::readback::read_buffer(device, queue, buffer).map(|bytes| {
            let words: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
            let pixels = words.chunks_exact(4).map(column_summary).collect();
            crate::image_io::HdrImage { width: w, height: h, pixels }
        }))
    }

    /// The voxel levels of the last frame (0 = the view's columns).
    pub fn level_count(&self) -> usize {
        self.sized.as_ref().map_or(0, |s| s.levels.len())
    }

    /// Slices `first..=last` of level `l`'s columns as an image for the inspector's slice viewer:
    /// r = 1 where any of them is solid (their OR), g = the solid share of the range, b = the
    /// first solid slice of the range as a fraction of it (1 where none).
    pub fn read_slices(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        l: usize,
        slices: (u32, u32),
    ) -> Option<Result<crate::image_io::HdrImage, crate::render::readback::ReadbackError>> {
        let (buffer, (w, h)) = (self.level(l)?, self.level_size(l)?);
        Some(crate::render::readback::read_buffer(device, queue, buffer).map(|bytes| {
            let words: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
            let pixels = words.chunks_exact(4).map(|c| slice_range(c, slices)).collect();
            crate::image_io::HdrImage { width: w, height: h, pixels }
        }))
    }

    /// Frees the buffers.
    pub fn release(&mut self) {
        self.sized = None;
    }

    /// Bytes of the buffers.
    pub fn gpu_bytes(&self) -> u64 {
        self.sized.as_ref().map_or(0, |s| s.levels.iter().map(wgpu::Buffer::size).sum())
    }
}

/// One column's inspector texel: solid share, first and last solid slice (each / 128).
fn column_summary(words: &[u32]) -> [f32; 4] {
    let solid: u32 = words.iter().map(|w| w.count_ones()).sum();
    let bit = |i: u32| words[(i / 32) as usize] >> (i % 32) & 1 == 1;
    let first = (0..128).find(|&i| bit(i)).unwrap_or(128);
    let last = (0..128).rev().find(|&i| bit(i)).unwrap_or(128);
    [solid as f32 / 128.0, first as f32 / 128.0, last as f32 / 128.0, 1.0]
}

/// One column's slice-viewer texel over slices `first..=last` (clamped to 0..=127): OR of the
/// range, its solid share, and its first solid slice as a fraction of the range (1 where none).
fn slice_range(words: &[u32], (first, last): (u32, u32)) -> [f32; 4] {
    let (a, b) = (first.min(127), last.min(127));
    let (a, b) = (a.min(b), a.max(b));
    let bit = |i: u32| words[(i / 32) as usize] >> (i % 32) & 1 == 1;
    let solid = (a..=b).filter(|&i| bit(i)).count() as f32;
    let span = (b - a + 1) as f32;
    let at = (a..=b).find(|&i| bit(i)).map_or(1.0, |i| (i - a) as f32 / span);
    [f32::from(u8::from(solid > 0.0)), solid / span, at, 1.0]
}

/// Parses the slice viewer's `@level,first,last` suffix; `None` when it is malformed.
pub fn parse_slices(args: &str) -> Option<(usize, u32, u32)> {
    let mut parts = args.split(',').map(str::trim);
    let l = parts.next()?.parse().ok()?;
    let first = parts.next()?.parse().ok()?;
    let last = parts.next()?.parse().ok()?;
    (parts.next().is_none() && first <= last && last < 128).then_some((l, first, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_voxelisation_rasterises_the_finest_level_that_fits_one_binding() {
        let mib = 1u64 << 20;
        assert_eq!(finest_fitting_level((1920, 1080), 128 * mib), 0, "1080p's 33 MB fit");
        assert_eq!(finest_fitting_level((3840, 2160), 128 * mib), 0, "4K's 133 MB fit in 128 MiB");
        assert_eq!(finest_fitting_level((5760, 3240), 128 * mib), 1, "5760 x 3240's 299 MB do not");
        assert_eq!(finest_fitting_level((5760, 3240), 4096 * mib), 0);
        assert_eq!(finest_fitting_level((5760, 3240), 1), MAX_LEVELS as u32 - 1, "never past the last level");
    }

    #[test]
    fn a_column_summary_names_the_solid_share_and_its_ends() {
        // Slices 40..=99 solid (a box between two depths).
        let mut words = [0u32; 4];
        (40..100).for_each(|i: u32| words[(i / 32) as usize] |= 1 << (i % 32));
        assert_eq!(column_summary(&words), [60.0 / 128.0, 40.0 / 128.0, 99.0 / 128.0, 1.0]);
        assert_eq!(column_summary(&[0; 4]), [0.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn a_slice_range_is_the_or_of_its_slices_with_its_share_and_first_solid_slice() {
        let mut words = [0u32; 4];
        (40..100).for_each(|i: u32| words[(i / 32) as usize] |= 1 << (i % 32));
        assert_eq!(slice_range(&words, (0, 39)), [0.0, 0.0, 1.0, 1.0], "in front of the box");
        assert_eq!(slice_range(&words, (30, 49)), [1.0, 0.5, 0.5, 1.0], "its front face");
        assert_eq!(slice_range(&words, (64, 64)), [1.0, 1.0, 0.0, 1.0], "one slice inside");
        assert_eq!(slice_range(&words, (100, 300)), [0.0, 0.0, 1.0, 1.0], "behind, clamped");
        assert_eq!(parse_slices("2, 40,60"), Some((2, 40, 60)));
        assert_eq!(parse_slices("2,60,40"), None, "reversed");
        assert_eq!(parse_slices("2,40,128"), None, "past the last slice");
        assert_eq!(parse_slices("2,40"), None);
    }

    #[test]
    fn automatic_range_spans_the_bounds_in_front_and_starts_at_the_camera_inside_them() {
        let bounds = (Vec3::new(-1.0, -1.0, -10.0), Vec3::new(1.0, 1.0, -2.0));
        let (near, far) = automatic_range(Vec3::ZERO, Vec3::NEG_Z, bounds).expect("in front");
        assert!((near - 2.0).abs() < 1e-6 && (far - 10.0).abs() < 1e-6, "{near} {far}");
        let inside = automatic_range(Vec3::new(0.0, 0.0, -5.0), Vec3::NEG_Z, bounds).expect("inside");
        assert_eq!(inside, (0.0, 5.0));
        assert_eq!(automatic_range(Vec3::ZERO, Vec3::Z, bounds), None, "all behind");
    }
}
