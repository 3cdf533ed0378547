//! `sshgi`'s sky pass (not in Soler et al. 2010): its layouts and pipelines, the start level's
//! rays (`sky_light`) and the panorama senders' (`sender_sky`), both in `sshgi_sky.wgsl`.

use crate::render::layouts::{compute_pipeline, storage_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::formats;

/// The sky pass's layouts and pipelines (`sshgi_sky.wgsl`): the start level's (`sky_light`) and
/// the panorama senders' (`sender_sky`).
pub(super) type SkyPipelines = [(wgpu::BindGroupLayout, wgpu::ComputePipeline); 2];

pub(super) fn pipelines(device: &wgpu::Device) -> Result<SkyPipelines, ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let float = wgpu::TextureSampleType::Float { filterable: false };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sshgi sky layout"),
        entries: &[
            uniform_entry(0, c, false),
            uniform_entry(1, c, true),
            texture_entry(2, c, float),
            storage_texture_entry(3, formats::HDR),
            storage_entry(4, c),
            texture_entry(5, c, float),
            uniform_entry(6, c, false),
            storage_entry(9, c),
        ],
    });
    let module = shaders::module(device, "render/gi/sshgi/sshgi_sky.wgsl")?;
    let pipeline = compute_pipeline(device, "sshgi sky", &layout, &module, "sky_light");
    let sender_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sshgi sender sky layout"),
        entries: &[
            uniform_entry(0, c, false),
            uniform_entry(1, c, true),
            storage_entry(4, c),
            texture_entry(5, c, float),
            uniform_entry(6, c, false),
            storage_entry(7, c),
            crate::render::layouts::storage_rw_entry(8),
            storage_entry(9, c),
        ],
    });
    let sender = compute_pipeline(device, "sshgi sender sky", &sender_layout, &module, "sender_sky");
    Ok([(layout, pipeline), (sender_layout, sender)])
}
