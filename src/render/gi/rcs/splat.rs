//! Splatting and normalisation (`rcs_splat.wgsl`, `rcs_resolve.wgsl`): Ward-weighted
//! irradiance summed into two float buffers (with and without the gradients, each with the
//! summed weight), then E = sum w E / sum w as E / pi. The paper draws one blended quad per
//! record; this is the same sum gathered by a tiled compute pass that keeps, per 16 x 16 tile,
//! only the records whose zone meets the tile's visible surface (the quads cost every pixel of
//! their bounds: 3.6 s on the software adapter for the rooms' 4,536 records at 640x360).
//! 32-bit float sums keep w up to 1000 times irradiance in the hundreds without the overflow
//! 16-bit floats have at 65504.

use bytemuck::{Pod, Zeroable};

use super::store::Store;
use super::{entry, uniform};
use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{compute_pipeline, storage_entry, storage_rw_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};

/// Pixels per side of the tile one workgroup splats.
pub const TILE: u32 = 16;

/// Bytes per pixel of each accumulation buffer (one vec4<f32>).
pub const ACCUM_TEXEL_BYTES: u64 = 16;

/// `SplatParams` in `rcs_splat.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SplatParams {
    /// x = accuracy a.
    pub accuracy: [f32; 4],
    /// x = 1: add the splat list's records to the sums, 0: replace them; y = records; z = 1:
    /// keep every record in every tile (no tile test).
    pub mode: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<SplatParams>() == 32);

/// `ResolveParams` in `rcs_resolve.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ResolveParams {
    /// x = 1 with gradients.
    pub mode: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<ResolveParams>() == 16);

/// Which records a splat draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Splat {
    /// Clear, then every slot below the high-water mark.
    All(u32),
    /// This round's `n` records (their slots in the splat list), on top of what is there.
    New(u32),
}

/// Set by [`keep_every_record_in_every_tile`].
static NO_TILE_TEST: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Makes every splat after the call keep every record in every tile (no tile test), so that a
/// test can check that the tile test drops no record that reaches a pixel. Process-wide.
pub fn keep_every_record_in_every_tile(on: bool) {
    NO_TILE_TEST.store(on, std::sync::atomic::Ordering::Relaxed);
}

/// The two accumulation buffers of a view, row-major, one vec4<f32> per pixel.
pub struct Accum {
    /// (sum w E^ with gradients, sum w).
    pub weighted: wgpu::Buffer,
    /// (sum w E, records reaching the pixel).
    pub plain: wgpu::Buffer,
    /// The view's size.
    pub size: (u32, u32),
}

/// The pipelines and the accumulation buffers.
pub struct SplatPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    all_params: wgpu::Buffer,
    new_params: wgpu::Buffer,
    resolve_pipeline: wgpu::ComputePipeline,
    resolve_layout: wgpu::BindGroupLayout,
    resolve_params: wgpu::Buffer,
    accum: Option<Accum>,
}

impl SplatPass {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs splat layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                storage_entry(2, c),
                storage_entry(3, c),
                texture_entry(4, c, wgpu::TextureSampleType::Depth),
                texture_entry(5, c, unfilterable),
                storage_rw_entry(6),
                storage_rw_entry(7),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_splat.wgsl")?;
        let resolve_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs resolve layout"),
            entries: &[
                uniform_entry(0, c, false),
                storage_entry(1, c),
                storage_entry(2, c),
                crate::render::layouts::storage_texture_entry(3, crate::render::targets::formats::HDR),
            ],
        });
        let resolve_module = shaders::module(device, "render/gi/rcs/rcs_resolve.wgsl")?;
        let size = std::mem::size_of::<SplatParams>() as u64;
        Ok(Self {
            pipeline: compute_pipeline(device, "rcs splat", &layout, &module, "cs_main"),
            layout,
            all_params: uniform(device, "rcs splat all params", size),
            new_params: uniform(device, "rcs splat new params", size),
            resolve_pipeline: compute_pipeline(device, "rcs resolve", &resolve_layout, &resolve_module, "cs_main"),
            resolve_layout,
            resolve_params: uniform(device, "rcs resolve params", std::mem::size_of::<ResolveParams>() as u64),
            accum: None,
        })
    }

    /// The accumulation buffers for a view of `size`.
    pub fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if self.accum.as_ref().is_some_and(|a| a.size == size) {
            return;
        }
        let bytes = u64::from(size.0) * u64::from(size.1) * ACCUM_TEXEL_BYTES;
        let buffer = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        self.accum = Some(Accum { weighted: buffer("rcs splat weighted"), plain: buffer("rcs splat plain"), size });
    }

    /// The accumulation buffers.
    pub fn accum(&self) -> Option<&Accum> {
        self.accum.as_ref()
    }

    /// Splats records at accuracy `accuracy`.
    pub fn record(&self, inputs: &mut GiInputs<'_>, store: &Store, which: Splat, accuracy: f32) {
        let Some(accum) = &self.accum else { return };
        let (buffer, mode, count, name) = match which {
            Splat::All(n) => (&self.all_params, 0, n, "rcs splat"),
            Splat::New(n) => (&self.new_params, 1, n, "rcs splat new"),
        };
        let keep_all = u32::from(NO_TILE_TEST.load(std::sync::atomic::Ordering::Relaxed));
        let params = SplatParams { accuracy: [accuracy, 0.0, 0.0, 0.0], mode: [mode, count, keep_all, 0] };
        inputs.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&params));
        let t = inputs.targets;
        let view = |b, v| wgpu::BindGroupEntry { binding: b, resource: wgpu::BindingResource::TextureView(v) };
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs splat bind group"),
            layout: &self.layout,
            entries: &[
                entry(0, inputs.frame_buffer),
                entry(1, buffer),
                entry(2, &store.records),
                entry(3, &store.splat_list),
                view(4, &t.depth.view),
                view(5, &t.normal.view),
                entry(6, &accum.weighted),
                entry(7, &accum.plain),
            ],
        });
        let (w, h) = t.size;
        let mut pass = inputs.compute_pass(name);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(TILE), h.div_ceil(TILE), 1);
    }

    /// Writes E / pi into the frame's indirect target.
    pub fn resolve(&self, inputs: &mut GiInputs<'_>, gradients: bool) {
        let Some(accum) = &self.accum else { return };
        let params = ResolveParams { mode: [u32::from(gradients), 0, 0, 0] };
        inputs.queue.write_buffer(&self.resolve_params, 0, bytemuck::bytes_of(&params));
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs resolve bind group"),
            layout: &self.resolve_layout,
            entries: &[
                entry(0, &self.resolve_params),
                entry(1, &accum.weighted),
                entry(2, &accum.plain),
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&inputs.targets.indirect.view),
                },
            ],
        });
        let (w, h) = inputs.targets.size;
        let mut pass = inputs.compute_pass("rcs resolve");
        pass.set_pipeline(&self.resolve_pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
    }

    /// Frees the buffers.
    pub fn release(&mut self) {
        self.accum = None;
    }

    /// Bytes held.
    pub fn gpu_bytes(&self) -> u64 {
        self.accum.as_ref().map_or(0, |a| a.weighted.size() + a.plain.size())
    }
}
