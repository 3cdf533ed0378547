//! The first VPL set's view weight (P3, `seed_viewed` in `importance.wgsl`): the importance
//! pyramid's finest level seeded with each light-G-buffer texel's importance times `1 + s`
//! where the camera sees the texel's surface (its front faces the camera and its depth matches
//! the view's; s = `first_set_seen_weight`), times 1 elsewhere. Knecht 2009 draws the first set
//! by power alone; a sun on a roof or a sky around a building then spends most of the VPLs where
//! the camera cannot see, and the few on the lit surfaces in view change in number from frame to
//! frame (`ism-ritschel` on the suite's sun-and-sky window room: single frames read 0.86-1.18 of
//! the reference, 0.95-1.15 with the weight at 1). The warp divides every VPL's power by its
//! texel's probability, so the set's expected light is unchanged.
//!
//! This pass owns its pipeline, its parameter block and its bind group of the view and the
//! atlas (made anew when any of them is a new object); the VPL pass binds group 0, the
//! pyramid's.

use super::params::SeedParams;
use crate::render::layouts::{compute_pipeline_with, storage_entry, texture_entry, uniform_entry, view_entry};
use crate::render::shaders::{self, ShaderError};

/// The `seed_viewed` pipeline, its layout of the view and atlas resources, and its parameters.
pub struct FirstSetView {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// The bind group and the resources it was made of (equal when the same objects).
    group: Option<(wgpu::BindGroup, Bound)>,
}

/// The atlas's resources the weight reads: tile records, light depth and normals, emitter
/// candidates.
pub struct AtlasInputs<'a> {
    pub tiles: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    pub normal: &'a wgpu::TextureView,
    pub emitters: &'a wgpu::Buffer,
}

/// The camera's view: the frame uniforms and the depth of this frame's G-buffer.
pub struct ViewInputs<'a> {
    pub frame: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
}

/// The objects a bind group was made of: frame, view depth, tiles, light depth, normal,
/// emitters (wgpu's handles compare by identity).
type Bound = (wgpu::Buffer, wgpu::TextureView, wgpu::Buffer, wgpu::TextureView, wgpu::TextureView, wgpu::Buffer);

impl FirstSetView {
    /// The pipeline over `pyramid` (group 0: the power texture and the finest level).
    pub fn new(device: &wgpu::Device, pyramid: &wgpu::BindGroupLayout) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism first-set view layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                storage_entry(3, c),
                texture_entry(4, c, wgpu::TextureSampleType::Depth),
                texture_entry(5, c, wgpu::TextureSampleType::Float { filterable: false }),
                storage_entry(6, c),
            ],
        });
        let module = shaders::module(device, "render/gi/ism/importance.wgsl")?;
        let pipeline =
            compute_pipeline_with(device, "ism importance seed viewed", &[pyramid, &layout], &module, "seed_viewed");
        let params = super::screen::uniform(device, "ism first-set view params", SeedParams::SIZE);
        Ok(Self { layout, pipeline, params, group: None })
    }

    /// Writes the parameters and binds the pipeline and the view's group (group 1) on `pass`,
    /// making the group anew when the view or the atlas changed.
    pub fn bind(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        pass: &mut wgpu::ComputePass<'_>,
        params: &SeedParams,
        view: &ViewInputs<'_>,
        atlas: &AtlasInputs<'_>,
    ) {
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(params));
        let key: Bound = (
            view.frame.clone(),
            view.depth.clone(),
            atlas.tiles.clone(),
            atlas.depth.clone(),
            atlas.normal.clone(),
            atlas.emitters.clone(),
        );
        if self.group.as_ref().is_none_or(|(_, k)| *k != key) {
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("ism first-set view bind group"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: self.params.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: view.frame.as_entire_binding() },
                    view_entry(2, view.depth),
                    wgpu::BindGroupEntry { binding: 3, resource: atlas.tiles.as_entire_binding() },
                    view_entry(4, atlas.depth),
                    view_entry(5, atlas.normal),
                    wgpu::BindGroupEntry { binding: 6, resource: atlas.emitters.as_entire_binding() },
                ],
            });
            self.group = Some((group, key));
        }
        pass.set_pipeline(&self.pipeline);
        if let Some((group, _)) = &self.group {
            pass.set_bind_group(1, group, &[]);
        }
    }

    /// Drops the view's group (its resources are about to go).
    pub fn release(&mut self) {
        self.group = None;
    }
}
