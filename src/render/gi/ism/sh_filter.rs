//! Segovia & Wald's screen-space SH filter for instant global illumination: the interleaved
//! shading projects each pixel's incident radiance on 9 SH coefficients per colour (the
//! `project_sh` entry of `ism_shade.wgsl`); this pass filters those coefficients over the
//! n x n interleave window across geometric discontinuities only, then shades with each pixel's
//! own normal-mapped normal and glossy lobe, so detail the irradiance filter would blur stays.

use crate::render::layouts::{compute_pipeline, storage_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, ViewTargets, formats};
use crate::settings::IsmSettings;

use super::params::FilterParams;
use super::screen::{buf, tex, uniform};
use crate::render::gi::technique::texture_bytes;

/// u32 words per pixel of the packed coefficients: 27 f16 values and one pad.
pub const SH_WORDS: u64 = 14;

struct Sized {
    /// Incident-radiance coefficients in the split layout, `SH_WORDS` per texel.
    raw: wgpu::Buffer,
    /// Outgoing indirect radiance, a = accepted taps / n^2.
    shaded: Target,
    /// Filtered DC (mean incident radiance), a = accepted taps / n^2.
    dc: Target,
    /// Filtered band-1 luminance direction as 0.5 + 0.5 dir, a = band-2 share of the energy.
    dir: Target,
    group: wgpu::BindGroup,
}

/// The SH filter pass and its buffers.
pub struct ShFilter {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    sized: Option<Sized>,
}

impl ShFilter {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism sh filter layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                storage_entry(2, c),
                texture_entry(3, c, wgpu::TextureSampleType::Depth),
                texture_entry(4, c, unfilterable),
                texture_entry(5, c, unfilterable),
                texture_entry(6, c, unfilterable),
                texture_entry(7, c, wgpu::TextureSampleType::Uint),
                storage_texture_entry(8, formats::HDR),
                storage_texture_entry(9, formats::HDR),
                storage_texture_entry(10, formats::HDR),
            ],
        });
        let module = shaders::module(device, "render/gi/ism/ism_sh_filter.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "ism sh filter", &layout, &module, "cs_main"),
            params: uniform(device, "ism sh filter params", std::mem::size_of::<FilterParams>() as u64),
            layout,
            sized: None,
        })
    }

    /// Bytes of the coefficient buffer for a split layout of `split` texels.
    pub fn raw_bytes(split: (u32, u32)) -> u64 {
        u64::from(split.0) * u64::from(split.1) * SH_WORDS * 4
    }

    /// (Re)creates the buffers for a split layout of `split` texels and a `view`-sized output,
    /// bound to this frame's G-buffer.
    pub fn ensure(
        &mut self,
        device: &wgpu::Device,
        split: (u32, u32),
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
    ) {
        use wgpu::TextureUsages as U;
        let raw = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ism sh coefficients"),
            size: Self::raw_bytes(split).max(16),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let rw = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let shaded = Target::new(device, "ism sh shaded", targets.size, formats::HDR, rw);
        let dc = Target::new(device, "ism sh filtered dc", targets.size, formats::HDR, rw);
        let dir = Target::new(device, "ism sh filtered direction", targets.size, formats::HDR, rw);
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ism sh filter bind group"),
            layout: &self.layout,
            entries: &[
                buf(0, frame_buffer),
                buf(1, &self.params),
                buf(2, &raw),
                tex(3, &targets.depth.view),
                tex(4, &targets.normal.view),
                tex(5, &targets.albedo.view),
                tex(6, &targets.material.view),
                tex(7, &targets.object_id.view),
                tex(8, &shaded.view),
                tex(9, &dc.view),
                tex(10, &dir.view),
            ],
        });
        self.sized = Some(Sized { raw, shaded, dc, dir, group });
    }

    /// Frees the coefficient buffer and the output targets.
    pub fn release(&mut self) {
        self.sized = None;
    }

    /// Bytes of GPU memory held.
    pub fn gpu_bytes(&self) -> u64 {
        self.sized.as_ref().map_or(0, |s| {
            s.raw.size() + [&s.shaded, &s.dc, &s.dir].iter().map(|t| texture_bytes(&t.texture)).sum::<u64>()
        })
    }

    /// The coefficient buffer the projection writes.
    pub fn raw(&self) -> Option<&wgpu::Buffer> {
        self.sized.as_ref().map(|s| &s.raw)
    }

    /// The shaded result of the last frame.
    pub fn shaded(&self) -> Option<&Target> {
        self.sized.as_ref().map(|s| &s.shaded)
    }

    /// (shaded, DC, band-1 direction) of the last frame.
    pub fn views(&self) -> Option<(&Target, &Target, &Target)> {
        self.sized.as_ref().map(|s| (&s.shaded, &s.dc, &s.dir))
    }

    /// Writes this frame's parameters (the same discontinuity thresholds as the irradiance
    /// filter, applied to geometric normals).
    pub fn write_params(&self, queue: &wgpu::Queue, n: u32, settings: &IsmSettings, d_max: f32) {
        let params =
            FilterParams { counts: [n, 0, 0, 0], params: [settings.filter_depth, settings.filter_normal, d_max, 0.0] };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
    }

    /// Records the filter over a `view`-sized image.
    pub fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>, view: (u32, u32)) {
        if let Some(s) = &self.sized {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &s.group, &[]);
            pass.dispatch_workgroups(view.0.div_ceil(8), view.1.div_ceil(8), 1);
        }
    }
}
