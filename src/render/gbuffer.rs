//! The G-buffer pass: rasterises every visible object into the view targets (back faces culled:
//! surfaces are one-sided, CCW front; reversed depth, cleared to 0, nearest wins).

use super::layouts::Layouts;
use super::scene_gpu::{SceneGpu, Vertex};
use super::shaders::{self, ShaderError};
use super::targets::{ViewTargets, formats};

/// A pipeline that draws the scene's objects from the view camera (frame, object and material
/// groups; one-sided CCW front faces; reversed depth with `depth` = (write, compare)) into
/// `targets` with `fs_main`: the G-buffer's and the emission pass's.
pub fn view_pipeline(
    device: &wgpu::Device,
    layouts: &Layouts,
    label: &str,
    module: &wgpu::ShaderModule,
    depth: (bool, wgpu::CompareFunction),
    targets: &[Option<wgpu::ColorTargetState>],
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&format!("{label} pipeline layout")),
        bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.object), Some(&layouts.material)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&format!("{label} pipeline")),
        layout: Some(&layout),
        vertex: Vertex::state(module),
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: Some(wgpu::Face::Back),
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: formats::DEPTH,
            depth_write_enabled: Some(depth.0),
            depth_compare: Some(depth.1),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The G-buffer pipeline.
pub struct GbufferPass {
    pipeline: wgpu::RenderPipeline,
}

impl GbufferPass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let module = shaders::module(device, "render/gbuffer.wgsl")?;
        let target = |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
        let targets = [
            target(formats::ALBEDO),
            target(formats::NORMAL),
            target(formats::MATERIAL),
            target(formats::MOTION),
            target(formats::OBJECT_ID),
        ];
        let depth = (true, wgpu::CompareFunction::Greater);
        let pipeline = view_pipeline(device, layouts, "gbuffer", &module, depth, &targets);
        Ok(Self { pipeline })
    }

    /// Records the pass.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &ViewTargets,
        frame_bind_group: &wgpu::BindGroup,
        gpu: &SceneGpu,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        use crate::render::targets::cleared as color;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer pass"),
            color_attachments: &[
                color(&targets.albedo.view),
                color(&targets.normal.view),
                color(&targets.material.view),
                color(&targets.motion.view),
                color(&targets.object_id.view),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth.view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, frame_bind_group, &[]);
        gpu.draw_objects(&mut pass);
    }
}
