//! Volumetric obscurance (Loos & Sloan 2010; Loos 2015 ch. 6): a screen-space
//! obscurance that the composite multiplies into the indirect term of the techniques it is on
//! for (`settings::VoSettings`). It exists because `mrt`'s lightmap (16 x 16 texels per block
//! face) and DRT's clutter operators cannot hold contact detail finer than a texel; the
//! dissertation pairs them the same way. Line sampling (`vo/vo.wgsl`) into the view target
//! `vo_raw`, then the separable bilateral blur (`vo/vo_blur.wgsl`, rows into `vo_rows`, columns
//! into `vo`).

pub mod samples;

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::layouts::{compute_pipeline, storage_texture_entry, texture_entry, uniform_entry, view_entry};
use super::shaders::{self, ShaderError};
use super::targets::{ViewTargets, formats};
use super::timing::{GpuTimer, TimestampPair};
use crate::settings::VoSettings;

/// `VoParams` in `vo/vo.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct VoParams {
    /// Per sample: x, y in the unit disk, weight, unused.
    pub samples: [[f32; 4]; 12],
    /// Sample count, normal clamp (1/0), thickness model (1/0), unused.
    pub counts: [u32; 4],
    /// Radius (m), thickness (m), unused x2.
    pub params: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<VoParams>() == 224);

/// `BlurParams` in `vo/vo_blur.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct BlurParams {
    /// Blur on (1) or off, direction (0 rows, 1 columns), unused x2.
    pub counts: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<BlurParams>() == 16);

/// Parameter blocks shared with WGSL (file, struct, bytes), checked against naga's layout by
/// the shader tests.
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/vo/vo.wgsl", "VoParams", std::mem::size_of::<VoParams>()),
    ("render/vo/vo_blur.wgsl", "BlurParams", std::mem::size_of::<BlurParams>()),
];

/// The parameter block for `settings`.
pub fn params(settings: &VoSettings) -> VoParams {
    let set = samples::sample_set(settings.samples as usize, settings.samples != 12);
    let mut out = VoParams { samples: [[0.0; 4]; 12], counts: [0; 4], params: [0.0; 4] };
    for (slot, s) in out.samples.iter_mut().zip(&set) {
        *slot = [s[0], s[1], s[2], 0.0];
    }
    out.counts = [set.len().min(12) as u32, u32::from(settings.normal_clamp), u32::from(settings.thickness > 0.0), 0];
    out.params = [settings.radius, settings.thickness, 0.0, 0.0];
    out
}

/// The bind groups of one set of view targets.
pub struct VoGroups {
    vo: wgpu::BindGroup,
    rows: wgpu::BindGroup,
    columns: wgpu::BindGroup,
    size: (u32, u32),
}

/// The two pipelines and their parameter blocks.
pub struct VoPass {
    vo: (wgpu::BindGroupLayout, wgpu::ComputePipeline),
    blur: (wgpu::BindGroupLayout, wgpu::ComputePipeline),
    params: wgpu::Buffer,
    /// The blur's row and column passes.
    blur_params: [wgpu::Buffer; 2],
    /// The settings the parameter block holds (sample sets are relaxed only when they change).
    uploaded: Option<VoSettings>,
}

impl VoPass {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let make = |name: &str, entries: &[wgpu::BindGroupLayoutEntry]| -> Result<_, ShaderError> {
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{name} layout")),
                entries,
            });
            let module = shaders::module(device, &format!("render/vo/{name}.wgsl"))?;
            let pipeline = compute_pipeline(device, &format!("{name} pipeline"), &layout, &module, "cs_main");
            Ok((layout, pipeline))
        };
        let vo = make(
            "vo",
            &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                texture_entry(3, c, unfilterable),
                storage_texture_entry(4, formats::HDR),
            ],
        )?;
        let blur = make(
            "vo_blur",
            &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                texture_entry(3, c, unfilterable),
                texture_entry(4, c, unfilterable),
                storage_texture_entry(5, formats::HDR),
            ],
        )?;
        let uniform = |label: &str, bytes: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            })
        };
        let params = uniform("vo params", bytemuck::bytes_of(&self::params(&VoSettings::default())));
        let blur_params = [
            uniform("vo blur rows params", bytemuck::bytes_of(&BlurParams::default())),
            uniform("vo blur columns params", bytemuck::bytes_of(&BlurParams { counts: [0, 1, 0, 0] })),
        ];
        Ok(Self { vo, blur, params, blur_params, uploaded: None })
    }

    /// Uploads `settings` where they changed (the sample set is relaxed then).
    pub fn set(&mut self, queue: &wgpu::Queue, settings: &VoSettings) {
        if self.uploaded.as_ref() != Some(settings) {
            queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params(settings)));
            for (k, buffer) in self.blur_params.iter().enumerate() {
                let blur = BlurParams { counts: [u32::from(settings.blur), k as u32, 0, 0] };
                queue.write_buffer(buffer, 0, bytemuck::bytes_of(&blur));
            }
            self.uploaded = Some(settings.clone());
        }
    }

    /// The three passes' bind groups over the view targets `t` (made when the targets are,
    /// like the composite's).
    pub fn bind_groups(&self, device: &wgpu::Device, frame: &wgpu::Buffer, t: &ViewTargets) -> VoGroups {
        let group = |layout: &wgpu::BindGroupLayout, name: &str, entries: &[wgpu::BindGroupEntry<'_>]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{name} bind group")),
                layout,
                entries,
            })
        };
        let vo = group(
            &self.vo.0,
            "vo",
            &[
                wgpu::BindGroupEntry { binding: 0, resource: frame.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.params.as_entire_binding() },
                view_entry(2, &t.depth.view),
                view_entry(3, &t.normal.view),
                view_entry(4, &t.vo_raw.view),
            ],
        );
        let blur = |k: usize, from: &wgpu::TextureView, to: &wgpu::TextureView| {
            group(
                &self.blur.0,
                "vo_blur",
                &[
                    wgpu::BindGroupEntry { binding: 0, resource: frame.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.blur_params[k].as_entire_binding() },
                    view_entry(2, &t.depth.view),
                    view_entry(3, &t.normal.view),
                    view_entry(4, from),
                    view_entry(5, to),
                ],
            )
        };
        let rows = blur(0, &t.vo_raw.view, &t.vo_rows.view);
        let columns = blur(1, &t.vo_rows.view, &t.vo.view);
        VoGroups { vo, rows, columns, size: t.size }
    }

    /// Records the passes (with the settings last [`Self::set`]) over the targets `groups` bind.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, groups: &VoGroups, timer: &mut GpuTimer) {
        for (name, pipeline, bind) in [
            ("vo", &self.vo.1, &groups.vo),
            ("vo blur rows", &self.blur.1, &groups.rows),
            ("vo blur columns", &self.blur.1, &groups.columns),
        ] {
            let ts = timer.scope(name);
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes: ts.as_ref().map(TimestampPair::compute_writes),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(groups.size.0.div_ceil(8), groups.size.1.div_ceil(8), 1);
        }
    }
}
