//! The depth/normal pyramid shared by techniques that gather over screen space at several
//! scales (`shaders/render/pyramid.wgsl`): level 0 is the view's linear distance and geometric
//! normal, each coarser level picks one of its 2x2 children by vote, never an average, so every
//! texel of every level is a real surface. Built only when the active technique asks for it.

use super::layouts::{compute_pipeline, storage_texture_entry, texture_entry, uniform_entry};
use super::shaders::{self, ShaderError};
use super::targets::{Target, ViewTargets, formats};
use super::timing::TimestampPair;

/// Most levels built (level 0 included): enough for sshgi's four levels from a sixteenth of a
/// 4K view (`SshgiSettings::max_start_texels`); the levels past the sixth are a few texels on
/// views below 1280x720.
pub const MAX_LEVELS: u32 = 8;

struct Sized {
    size: (u32, u32),
    levels: Vec<Target>,
    groups: Vec<wgpu::BindGroup>,
}

/// The pyramid's pipelines and levels.
pub struct ViewPyramid {
    layout: wgpu::BindGroupLayout,
    seed: wgpu::ComputePipeline,
    reduce: wgpu::ComputePipeline,
    sized: Option<Sized>,
}

/// Levels for a view of `size`: halve until a side would drop below 1, at most [`MAX_LEVELS`].
pub fn level_count(size: (u32, u32)) -> u32 {
    (32 - size.0.min(size.1).max(1).leading_zeros()).min(MAX_LEVELS)
}

impl ViewPyramid {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("pyramid layout"),
            entries: &[
                uniform_entry(0, c, false),
                texture_entry(1, c, wgpu::TextureSampleType::Depth),
                texture_entry(2, c, unfilterable),
                texture_entry(3, c, unfilterable),
                storage_texture_entry(4, formats::HDR),
            ],
        });
        let module = shaders::module(device, "render/pyramid.wgsl")?;
        Ok(Self {
            seed: compute_pipeline(device, "pyramid seed", &layout, &module, "seed"),
            reduce: compute_pipeline(device, "pyramid reduce", &layout, &module, "reduce"),
            layout,
            sized: None,
        })
    }

    fn ensure(&mut self, device: &wgpu::Device, frame: &wgpu::Buffer, t: &ViewTargets) {
        if self.sized.as_ref().is_some_and(|s| s.size == t.size) {
            return;
        }
        use wgpu::TextureUsages as U;
        let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let levels: Vec<Target> = (0..level_count(t.size))
            .map(|l| {
                let size = ((t.size.0 >> l).max(1), (t.size.1 >> l).max(1));
                Target::new(device, "depth normal pyramid level", size, formats::HDR, usage)
            })
            .collect();
        let groups = (0..levels.len())
            .map(|l| {
                // Level 0 reads the G-buffer; the source binding then only needs a valid view.
                let source = if l == 0 { &t.albedo.view } else { &levels[l - 1].view };
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("pyramid bind group"),
                    layout: &self.layout,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: frame.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(&t.depth.view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::TextureView(&t.normal.view),
                        },
                        wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(source) },
                        wgpu::BindGroupEntry {
                            binding: 4,
                            resource: wgpu::BindingResource::TextureView(&levels[l].view),
                        },
                    ],
                })
            })
            .collect();
        self.sized = Some(Sized { size: t.size, levels, groups });
    }

    /// Builds every level from this frame's G-buffer.
    pub fn record(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        frame: &wgpu::Buffer,
        targets: &ViewTargets,
        timestamps: Option<TimestampPair<'_>>,
    ) {
        self.ensure(device, frame, targets);
        let Some(s) = &self.sized else { return };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("depth normal pyramid"),
            timestamp_writes: timestamps.as_ref().map(TimestampPair::compute_writes),
        });
        for (l, (level, group)) in s.levels.iter().zip(&s.groups).enumerate() {
            pass.set_pipeline(if l == 0 { &self.seed } else { &self.reduce });
            pass.set_bind_group(0, group, &[]);
            let (w, h) = (level.texture.width(), level.texture.height());
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
    }

    /// The levels of the last build.
    pub fn levels(&self) -> Option<&[Target]> {
        self.sized.as_ref().map(|s| s.levels.as_slice())
    }

    /// Frees the levels (no active technique needs them).
    pub fn release(&mut self) {
        self.sized = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_counts_stop_at_one_texel_or_the_cap() {
        assert_eq!(level_count((1, 1)), 1);
        assert_eq!(level_count((64, 36)), 6);
        assert_eq!(level_count((8, 3)), 2);
        assert_eq!(level_count((1920, 1080)), 8);
        assert_eq!(level_count((3840, 2160)), 8);
    }
}
