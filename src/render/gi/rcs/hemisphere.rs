//! Record computation, step 1: the scene rasterised into each record's hemisphere plane (the
//! notes' wide-angle camera, tan of the half aperture 2) in one atlas, one viewport per record
//! and one submission per round, lit by the shadowed direct light of every light (and the
//! cache for later bounces) in `rcs_hemisphere.wgsl`. Also the plane's integration weights.

use super::record::GpuJob;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::texture_bytes;
use crate::render::layouts::{
    Layouts, comparison_sampler_entry, depth_array_entry, shadow_sampler, storage_entry, uniform_entry,
};
use crate::render::scene_gpu::Vertex;
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::Target;

/// Largest atlas side in texels (2048: 112 MiB of planes and depth at most).
const ATLAS_LIMIT: u32 = 2048;

/// Records one round can compute with planes of `resolution` texels and a frame budget of
/// `budget` records.
pub fn round_capacity(resolution: u32, budget: u32) -> u32 {
    budget.min((ATLAS_LIMIT / resolution).pow(2)).max(1)
}

/// Format of the radiance/distance plane and of the surface plane.
pub const RADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const SURFACE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// `int int (1 + x^2 + y^2)^-2 dx dy` over [0, x] x [0, y]: the projected solid angle of a
/// rectangle on the plane at distance 1 from one corner at the foot of the normal (odd in x
/// and in y, so rectangles anywhere follow by inclusion-exclusion).
fn corner_integral(x: f64, y: f64) -> f64 {
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
}

/// `int cos^2(theta_b(phi)) / 2 dphi` over the azimuths `phi0..phi1` of a border segment on
/// the line `u = 2` (in the edge's own frame): the missing band theta_b..pi/2 beyond it,
/// cosine-weighted. For irradiance the band's measure is cos^2(theta_b) dphi / 2: the course
/// notes' border term Omega_p + cos(theta_b) dPhi, weighted by cos(theta_b), would count it
/// twice. tan theta_b = 2 / cos phi on that line.
fn band_integral(phi0: f64, phi1: f64) -> f64 {
    const STEPS: usize = 32;
    let h = (phi1 - phi0) / STEPS as f64;
    (0..STEPS)
        .map(|i| {
            let phi = phi0 + (i as f64 + 0.5) * h;
            let c2 = phi.cos().powi(2);
            c2 / (c2 + 4.0) * 0.5 * h
        })
        .sum()
}

/// The weight of each texel of an `h` x `h` plane (row-major, row 0 at +y): its exact
/// projected solid angle plus, for border texels, the band beyond their outer edges. Radiance
/// times these weights summed is the irradiance; the weights sum to pi.
pub fn plane_weights(h: u32) -> Vec<f32> {
    let n = h as usize;
    let edge = |i: usize| -2.0 + 4.0 * i as f64 / n as f64;
    let mut w = vec![0.0f64; n * n];
    for row in 0..n {
        // Row 0 is the top (+v).
        let (v0, v1) = (-edge(row + 1), -edge(row));
        for col in 0..n {
            let (u0, u1) = (edge(col), edge(col + 1));
            let g = corner_integral;
            w[row * n + col] = g(u1, v1) - g(u0, v1) - g(u1, v0) + g(u0, v0);
        }
    }
    // The band beyond each border texel's outer edge: by symmetry each side's segment at
    // coordinates s0..s1 along it spans azimuths atan(s / 2) in its own frame.
    for k in 0..n {
        let (s0, s1) = (edge(k), edge(k + 1));
        let band = band_integral((s0 / 2.0).atan(), (s1 / 2.0).atan());
        // Right (u = 2, v = s), left (u = -2), top (v = 2, u = s), bottom (v = -2).
        // Row 0 is the top, so the side segment at s0..s1 is row n - 1 - k.
        let right_row = n - 1 - k;
        w[right_row * n + (n - 1)] += band;
        w[right_row * n] += band;
        w[k] += band;
        w[(n - 1) * n + k] += band;
    }
    w.into_iter().map(|x| x as f32).collect()
}

/// The hemisphere atlas and its pipeline.
pub struct HemispherePass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    sized: Option<Atlas>,
}

/// The atlas of one round's planes.
pub struct Atlas {
    /// Texels per plane side.
    pub resolution: u32,
    /// Planes per atlas row.
    pub per_row: u32,
    pub radiance: Target,
    pub surface: Target,
    depth: Target,
}

impl Atlas {
    /// Jobs one round can hold.
    pub fn capacity(&self) -> u32 {
        self.per_row * self.per_row
    }

    /// The first texel of plane `i`.
    pub fn origin(&self, i: u32) -> (u32, u32) {
        ((i % self.per_row) * self.resolution, (i / self.per_row) * self.resolution)
    }
}

/// The buffers the hemisphere render reads besides the frame's.
pub struct HemisphereInputs<'a> {
    pub jobs: &'a wgpu::Buffer,
    pub records: &'a wgpu::Buffer,
    pub grid_params: &'a wgpu::Buffer,
    pub grid_cells: &'a wgpu::Buffer,
    pub grid_items: &'a wgpu::Buffer,
}

impl HemispherePass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let f = wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs hemisphere layout"),
            entries: &[
                uniform_entry(0, vf, true),
                uniform_entry(1, f, false),
                storage_entry(2, f),
                storage_entry(3, f),
                depth_array_entry(4, f),
                comparison_sampler_entry(5, f),
                storage_entry(6, f),
                uniform_entry(7, f, false),
                storage_entry(8, f),
                storage_entry(9, f),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_hemisphere.wgsl")?;
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rcs hemisphere pipeline layout"),
            bind_group_layouts: &[Some(&layout), Some(&layouts.object), Some(&layouts.material)],
            immediate_size: 0,
        });
        let target = |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("rcs hemisphere pipeline"),
            layout: Some(&pl),
            vertex: Vertex::state(&module),
            // No culling: the nearest surface occludes even seen from behind (it then sends nothing).
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[target(RADIANCE_FORMAT), target(SURFACE_FORMAT)],
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline, layout, sampler: shadow_sampler(device, "rcs hemisphere shadow sampler"), sized: None })
    }

    /// Makes the atlas hold planes of `resolution` texels for rounds of up to `jobs` records.
    pub fn ensure(&mut self, device: &wgpu::Device, resolution: u32, jobs: u32) {
        let per_row = (jobs.max(1) as f32).sqrt().ceil() as u32;
        let per_row = per_row.min(ATLAS_LIMIT / resolution).max(1);
        if self.sized.as_ref().is_some_and(|a| a.resolution == resolution && a.per_row == per_row) {
            return;
        }
        use wgpu::TextureUsages as U;
        let side = per_row * resolution;
        let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        self.sized = Some(Atlas {
            resolution,
            per_row,
            radiance: Target::new(device, "rcs hemisphere radiance", (side, side), RADIANCE_FORMAT, usage),
            surface: Target::new(device, "rcs hemisphere surfaces", (side, side), SURFACE_FORMAT, usage),
            depth: Target::new(device, "rcs hemisphere depth", (side, side), wgpu::TextureFormat::Depth32Float, usage),
        });
    }

    /// The atlas of the last round.
    pub fn atlas(&self) -> Option<&Atlas> {
        self.sized.as_ref()
    }

    /// Renders `count` jobs' planes (the background cleared to `background`).
    pub fn record(&self, inputs: &mut GiInputs<'_>, buffers: &HemisphereInputs<'_>, count: u32, background: f64) {
        let Some(atlas) = &self.sized else { return };
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs hemisphere bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: buffers.jobs,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<GpuJob>() as u64),
                    }),
                },
                super::entry(1, inputs.frame_buffer),
                super::entry(2, inputs.lights.buffer),
                super::entry(3, inputs.lights.shadow_views),
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(inputs.lights.shadow_maps),
                },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::Sampler(&self.sampler) },
                super::entry(6, buffers.records),
                super::entry(7, buffers.grid_params),
                super::entry(8, buffers.grid_cells),
                super::entry(9, buffers.grid_items),
            ],
        });
        let ts = inputs.timer.scope("rcs hemispheres");
        let colour = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r: background, g: background, b: background, a: 0.0 }),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let mut pass = inputs.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("rcs hemispheres"),
            color_attachments: &[colour(&atlas.radiance.view), colour(&atlas.surface.view)],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &atlas.depth.view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Discard }),
                stencil_ops: None,
            }),
            timestamp_writes: ts.as_ref().map(|t| t.render_writes(true, true)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        let h = atlas.resolution;
        for i in 0..count.min(atlas.capacity()) {
            let (x, y) = atlas.origin(i);
            pass.set_viewport(x as f32, y as f32, h as f32, h as f32, 0.0, 1.0);
            pass.set_scissor_rect(x, y, h, h);
            pass.set_bind_group(0, &bind_group, &[i * std::mem::size_of::<GpuJob>() as u32]);
            inputs.scene_gpu.draw_objects(&mut pass);
        }
    }

    /// Frees the atlas.
    pub fn release(&mut self) {
        self.sized = None;
    }

    /// Bytes held.
    pub fn gpu_bytes(&self) -> u64 {
        self.sized.as_ref().map_or(0, |a| {
            texture_bytes(&a.radiance.texture) + texture_bytes(&a.surface.texture) + texture_bytes(&a.depth.texture)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The white furnace on the CPU: radiance 1 everywhere integrates to pi, the plane alone to
    /// about 83% of it (the cosine-weighted share a 126.87-degree plane sees), at every resolution.
    #[test]
    fn plane_weights_integrate_to_pi_and_the_plane_alone_to_83_percent() {
        for h in [8u32, 16, 32, 64] {
            let w = plane_weights(h);
            let total: f64 = w.iter().map(|&x| f64::from(x)).sum();
            assert!((total - std::f64::consts::PI).abs() < 1e-4, "h {h}: weights sum to {total}");
        }
        let plane = 4.0 * corner_integral(2.0, 2.0) / std::f64::consts::PI;
        assert!((plane - 0.831).abs() < 0.002, "the plane covers {plane} of the cosine-weighted hemisphere");
    }

    /// Texels are symmetric: the weight of (row, col) equals its mirrors', and border texels
    /// carry more than their inner neighbours (the band).
    #[test]
    fn plane_weights_are_symmetric_and_the_border_carries_the_band() {
        let h = 16usize;
        let w = plane_weights(h as u32);
        for r in 0..h {
            for c in 0..h {
                let x = w[r * h + c];
                for m in [w[r * h + (h - 1 - c)], w[(h - 1 - r) * h + c], w[c * h + r]] {
                    assert!((x - m).abs() < 1e-6, "({r},{c}) {x} vs mirror {m}");
                }
            }
        }
        assert!(w[h / 2] > w[h + h / 2], "the top border texel holds the band beyond it");
    }
}
