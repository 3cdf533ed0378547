//! The `sshgi` technique behind the GI seam: asks the frame for the shared voted depth/normal
//! pyramid, runs [`super::passes`] and returns E / pi for the composite to multiply by albedo.

use super::passes::{Plan, SshgiPasses};
use crate::image_io::HdrImage;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::{
    BufferInfo, BufferView, GiOutput, GiTechnique, Needs, Readiness, ResetReason, SupportQuery, TechniqueStatus,
    note_reset,
};
use crate::render::{RenderError, readback};
use crate::scene::Scene;
use crate::settings::RenderSettings;

/// An inspector entry of one level's buffer.
const fn level(name: &'static str, description: &'static str) -> BufferInfo {
    BufferInfo { name, description, format: "rgba32f", view: BufferView::Colour }
}

/// The inspector's buffers: per gather level k (0 = the start level) its illumination, its
/// gather and the up-sampled sum, and each bounce's E / pi.
pub const BUFFERS: &[BufferInfo] = &[
    level("sshgi_illumination_0", "outgoing radiance of the start level (box average of the direct term)"),
    level("sshgi_illumination_1", "outgoing radiance of level 1 (2x2 box average)"),
    level("sshgi_illumination_2", "outgoing radiance of level 2"),
    level("sshgi_illumination_3", "outgoing radiance of level 3"),
    level("sshgi_gather_0", "E / pi gathered on the start level over the full disc: local colour bleeding"),
    level("sshgi_gather_1", "E / pi gathered on level 1 over its ring: broad ring-shaped blobs are right"),
    level("sshgi_gather_2", "E / pi gathered on level 2 over its ring"),
    level("sshgi_gather_3", "E / pi gathered on level 3 over its ring"),
    level("sshgi_sum_0", "levels 0.. summed by joint bilateral up-sampling: smooth, no halos at edges"),
    level("sshgi_sum_1", "levels 1.. summed by joint bilateral up-sampling"),
    level("sshgi_sum_2", "levels 2.. summed by joint bilateral up-sampling"),
    level("sshgi_bounce_1", "first bounce's E / pi at the start level"),
    level("sshgi_bounce_2", "second bounce's E / pi (albedo x the first, gathered again)"),
    level("sshgi_bounce_3", "third bounce's E / pi"),
    level("sshgi_bounce_4", "fourth bounce's E / pi"),
];

/// Screen-space hierarchical GI.
pub struct SshgiTechnique {
    passes: SshgiPasses,
    status: TechniqueStatus,
}

impl SshgiTechnique {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        Ok(Self { passes: SshgiPasses::new(device)?, status: TechniqueStatus::default() })
    }

    /// Needs compute with storage textures only, which every adapter the renderer runs on has.
    pub fn support(_query: &SupportQuery<'_>) -> Result<(), String> {
        Ok(())
    }
}

impl GiTechnique for SshgiTechnique {
    fn needs(&self) -> Needs {
        Needs { pyramid: true, ..Needs::default() }
    }

    fn prepare(&mut self, _scene: &Scene, _settings: &RenderSettings, _size: (u32, u32)) -> Readiness {
        Readiness::Ready
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        let Some(pyramid) = inputs.pyramid.as_ref().map(|p| p.levels) else {
            return Ok(GiOutput::Nothing);
        };
        if pyramid.is_empty() {
            return Ok(GiOutput::Nothing);
        }
        let plan = Plan::new(&inputs.settings.sshgi, inputs.targets.size, pyramid.len() as u32);
        self.passes.record(inputs, pyramid, plan);
        self.status.history_frames = self.status.history_frames.saturating_add(1);
        Ok(GiOutput::IrradianceOverPi)
    }

    fn buffers(&self) -> &'static [BufferInfo] {
        BUFFERS
    }

    fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>> {
        if !BUFFERS.iter().any(|b| b.name == name) {
            return None;
        }
        let Some(texture) = self.passes.buffer(name) else {
            return Some(Err(RenderError::UnknownBuffer {
                name: name.into(),
                known: "render sshgi first (with enough levels and bounces for this buffer)".into(),
            }));
        };
        Some(readback::read_as_rgba_f32(device, queue, texture).map_err(Into::into).map(|pixels| HdrImage {
            width: texture.width(),
            height: texture.height(),
            pixels,
        }))
    }

    fn reset(&mut self, reason: ResetReason) {
        note_reset(&mut self.status, reason);
        self.status.history_frames = 0;
    }

    fn release(&mut self) {
        self.passes.release();
    }

    fn gpu_bytes(&self) -> u64 {
        self.passes.gpu_bytes()
    }

    fn limitations(&self, _scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        vec![
            "only surfaces on screen send indirect light: off-screen and hidden senders are missing".to_owned(),
            "no indirect visibility yet: light gathered from a surface passes through whatever lies between".to_owned(),
            "senders are diffuse: they send the direct term's outgoing radiance".to_owned(),
        ]
    }

    fn status(&self) -> TechniqueStatus {
        self.status.clone()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
