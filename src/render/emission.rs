//! The emission pass: after the G-buffer, the objects whose material emits are drawn again over
//! its depth (compare Equal, invariant positions) into the `emission` target, which the lighting
//! pass adds to the direct term. A separate pass rather than a sixth G-buffer target: the five
//! targets already take 28 of the 32 bytes a sample WebGPU guarantees, and a scene without
//! emissive materials pays only the target's clear.

use super::gbuffer::view_pipeline;
use super::layouts::Layouts;
use super::scene_gpu::SceneGpu;
use super::shaders::{self, ShaderError};
use super::targets::{ViewTargets, formats};

/// The emission pipeline.
pub struct EmissionPass {
    pipeline: wgpu::RenderPipeline,
}

impl EmissionPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let module = shaders::module(device, "render/emission.wgsl")?;
        let target =
            Some(wgpu::ColorTargetState { format: formats::EMISSION, blend: None, write_mask: wgpu::ColorWrites::ALL });
        // Over the G-buffer's depth, not writing it: only the surfaces it kept.
        let depth = (false, wgpu::CompareFunction::Equal);
        let pipeline = view_pipeline(device, layouts, "emission", &module, depth, &[target]);
        Ok(Self { pipeline })
    }

    /// Records the pass (a clear alone when nothing emits).
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &ViewTargets,
        frame_bind_group: &wgpu::BindGroup,
        gpu: &SceneGpu,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("emission pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &targets.emission.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth.view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if gpu.has_emissive() {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, frame_bind_group, &[]);
            gpu.draw_emissive(&mut pass);
        }
    }
}
