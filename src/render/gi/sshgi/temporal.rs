//! sshgi's temporal filter (Soler et al. 2010 Eq. 6; `sshgi_temporal.wgsl`): blends this frame's
//! E / pi with the history warped through the motion buffer where the surface agrees, and keeps
//! the history and the surfaces it belongs to for the next frame (ping-pong).

use bytemuck::{Pod, Zeroable};

use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{compute_pipeline, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, formats};

/// `TemporalParams` in `sshgi_temporal.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct TemporalParams {
    /// a, 2-tap, history valid, unused.
    pub p: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<TemporalParams>() == 16);

struct Sized {
    size: (u32, u32),
    current: Target,
    history: [Target; 2],
    geometry: [Target; 2],
    accept: Target,
    /// Per history slot read (0, 1): the bind group, for the view targets and frame buffer it
    /// names ([`Key`]).
    groups: Option<(Key, [wgpu::BindGroup; 2])>,
}

/// The frame's textures and buffer the bind groups name.
#[derive(PartialEq)]
struct Key {
    views: [wgpu::TextureView; 4],
    frame: wgpu::Buffer,
}

/// The temporal pass and its history.
pub struct TemporalPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    sized: Option<Sized>,
    /// Which history slot the last frame wrote.
    latest: usize,
    /// Whether that slot holds a usable history.
    valid: bool,
}

impl TemporalPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi temporal layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                texture_entry(3, c, float),
                texture_entry(4, c, float),
                texture_entry(5, c, float),
                texture_entry(6, c, float),
                texture_entry(7, c, float),
                storage_texture_entry(8, formats::HDR),
                storage_texture_entry(9, formats::HDR),
                storage_texture_entry(10, formats::HDR),
                storage_texture_entry(11, formats::HDR),
            ],
        });
        let module = shaders::module(device, "render/gi/sshgi/sshgi_temporal.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "sshgi temporal", &layout, &module, "temporal"),
            layout,
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sshgi temporal params"),
                size: std::mem::size_of::<TemporalParams>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            sized: None,
            latest: 0,
            valid: false,
        })
    }

    /// Makes the targets for a view of `size` (a new size drops the history).
    pub fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if self.sized.as_ref().is_some_and(|s| s.size == size) {
            return;
        }
        use wgpu::TextureUsages as U;
        let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let t = |label| Target::new(device, label, size, formats::HDR, usage);
        self.sized = Some(Sized {
            size,
            current: t("sshgi current"),
            history: [t("sshgi history"), t("sshgi history")],
            geometry: [t("sshgi history surfaces"), t("sshgi history surfaces")],
            accept: t("sshgi temporal acceptance"),
            groups: None,
        });
        self.valid = false;
    }

    /// The full-resolution target the gather chain writes this frame's E / pi into.
    pub fn current(&self) -> Option<&Target> {
        self.sized.as_ref().map(|s| &s.current)
    }

    /// Blends [`Self::current`] with the history into `inputs.targets.indirect`.
    pub fn record(&mut self, inputs: &mut GiInputs<'_>, weight: f32, two_tap: bool) {
        let Some(s) = &mut self.sized else { return };
        let (read, write) = (self.latest, 1 - self.latest);
        let p = TemporalParams { p: [weight, f32::from(u8::from(two_tap)), f32::from(u8::from(self.valid)), 0.0] };
        inputs.queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&p));
        let t = inputs.targets;
        let key = Key {
            views: [t.depth.view.clone(), t.normal.view.clone(), t.motion.view.clone(), t.indirect.view.clone()],
            frame: inputs.frame_buffer.clone(),
        };
        if s.groups.as_ref().is_none_or(|(k, _)| *k != key) {
            let group = |read: usize| {
                let write = 1 - read;
                let views: [&wgpu::TextureView; 10] = [
                    &key.views[0],
                    &key.views[1],
                    &key.views[2],
                    &s.current.view,
                    &s.history[read].view,
                    &s.geometry[read].view,
                    &key.views[3],
                    &s.history[write].view,
                    &s.geometry[write].view,
                    &s.accept.view,
                ];
                let mut entries = vec![
                    wgpu::BindGroupEntry { binding: 0, resource: key.frame.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.params.as_entire_binding() },
                ];
                entries.extend(views.iter().enumerate().map(|(i, v)| wgpu::BindGroupEntry {
                    binding: 2 + i as u32,
                    resource: wgpu::BindingResource::TextureView(v),
                }));
                inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("sshgi temporal bind group"),
                    layout: &self.layout,
                    entries: &entries,
                })
            };
            let groups = [group(0), group(1)];
            s.groups = Some((key, groups));
        }
        let Some((_, groups)) = &s.groups else { return };
        let group = &groups[read];
        let ts = inputs.timer.scope("sshgi temporal");
        let mut pass = inputs.encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sshgi temporal"),
            timestamp_writes: ts.as_ref().map(|t| t.compute_writes()),
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(s.size.0.div_ceil(8), s.size.1.div_ceil(8), 1);
        self.latest = write;
        self.valid = true;
    }

    /// Forgets the history (the next frame starts afresh).
    pub fn reset(&mut self) {
        self.valid = false;
    }

    /// The acceptance mask of the last frame (r = the history's weight, g = taps kept).
    pub fn acceptance(&self) -> Option<&wgpu::Texture> {
        self.sized.as_ref().map(|s| &s.accept.texture)
    }

    /// The last frame's E / pi before the blend.
    pub fn raw(&self) -> Option<&wgpu::Texture> {
        self.sized.as_ref().map(|s| &s.current.texture)
    }

    /// Frees the targets and the history.
    pub fn release(&mut self) {
        self.sized = None;
        self.valid = false;
    }

    /// Bytes of the targets.
    pub fn gpu_bytes(&self) -> u64 {
        let Some(s) = &self.sized else { return 0 };
        let all = [&s.current, &s.history[0], &s.history[1], &s.geometry[0], &s.geometry[1], &s.accept];
        all.iter().map(|t| crate::render::gi::technique::texture_bytes(&t.texture)).sum()
    }
}
