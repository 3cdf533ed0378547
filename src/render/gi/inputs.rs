//! The one inputs struct every technique's `render` receives: the device, this frame's encoder,
//! the scene (CPU and GPU), the frame uniforms, the lights with their shadow maps, the view
//! targets (G-buffer, direct light, previous frame, pyramid) and the timer. Techniques read what
//! they need and write `targets.indirect`.

use glam::Mat4;

use crate::render::layouts::Layouts;
use crate::render::scene_gpu::SceneGpu;
use crate::render::targets::{Target, ViewTargets};
use crate::render::timing::GpuTimer;
use crate::render::uniforms::{FrameUniforms, GpuLight};
use crate::scene::Scene;
use crate::settings::{GiMode, RenderSettings};

/// The lights of this frame as every pass sees them.
pub struct GpuLights<'a> {
    /// Packed lights in scene order (with their first shadow layer).
    pub packed: &'a [GpuLight],
    /// The same as a storage buffer (`array<GpuLight>`).
    pub buffer: &'a wgpu::Buffer,
    /// Clip-from-world per shadow layer (`array<mat4x4<f32>>`).
    pub shadow_views: &'a wgpu::Buffer,
    /// The shadow map array (`texture_depth_2d_array`).
    pub shadow_maps: &'a wgpu::TextureView,
    /// The CPU copy of the shadow layers' matrices.
    pub shadow_matrices: &'a [Mat4],
}

/// The shared depth/normal pyramid (built only for techniques whose [`super::Needs`] ask).
pub struct PyramidView<'a> {
    /// Per level: linear view distance (r) and octahedral geometric normal (gb), a = 1 + the
    /// copied view pixel's row-major index where geometry (0 where none; `pyramid_point` in
    /// `common/frame.wgsl` rebuilds its point); level 0 is the view resolution.
    pub levels: &'a [Target],
}

/// Everything a technique's `render` reads.
pub struct GiInputs<'a> {
    pub device: &'a wgpu::Device,
    pub queue: &'a wgpu::Queue,
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub scene: &'a Scene,
    pub scene_gpu: &'a SceneGpu,
    pub layouts: &'a Layouts,
    /// The active mode (one technique may serve several, e.g. `ism` and `ism-ritschel`).
    pub mode: GiMode,
    pub settings: &'a RenderSettings,
    /// The frame uniforms on the GPU (`common/frame.wgsl`) and their CPU copy.
    pub frame_buffer: &'a wgpu::Buffer,
    pub frame: &'a FrameUniforms,
    pub lights: GpuLights<'a>,
    /// G-buffer, `direct` (shadowed direct radiance), `indirect` (the output) and the rest.
    pub targets: &'a ViewTargets,
    /// The previous frame's final HDR image, when [`super::Needs::previous_frame`].
    pub previous: Option<&'a Target>,
    /// The depth/normal pyramid, when [`super::Needs::pyramid`].
    pub pyramid: Option<PyramidView<'a>>,
    /// Frames rendered so far (seeds per-frame sample sets).
    pub frame_index: u32,
    pub timer: &'a mut GpuTimer,
    /// The environment's uniforms and image (`render::sky`), for techniques that see the sky.
    pub sky: &'a crate::render::sky::SkyGpu,
}

impl GiInputs<'_> {
    /// A compute pass named and timed `name`, detached from the encoder's borrow (it must end
    /// before the encoder records anything else).
    pub fn compute_pass(&mut self, name: &str) -> wgpu::ComputePass<'static> {
        let ts = self.timer.scope(name);
        self.encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes: ts.as_ref().map(|t| t.compute_writes()),
            })
            .forget_lifetime()
    }
}
