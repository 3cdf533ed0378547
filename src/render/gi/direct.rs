//! `direct`: the technique that adds nothing. It exists so that the frame treats every mode
//! the same way (the composite then shows the shadowed direct light alone) and so that a
//! switch to `direct` releases the previous technique's memory like any other switch.

use super::inputs::GiInputs;
use super::technique::{GiOutput, GiTechnique, Readiness, ResetReason, SupportQuery, TechniqueStatus};
use crate::image_io::HdrImage;
use crate::render::RenderError;
use crate::scene::Scene;
use crate::settings::RenderSettings;

/// Direct light only.
#[derive(Default)]
pub struct DirectTechnique {
    status: TechniqueStatus,
}

impl DirectTechnique {
    /// Runs everywhere.
    pub fn support(_query: &SupportQuery<'_>) -> Result<(), String> {
        Ok(())
    }
}

impl GiTechnique for DirectTechnique {
    fn prepare(&mut self, _scene: &Scene, _settings: &RenderSettings, _size: (u32, u32)) -> Readiness {
        Readiness::Ready
    }

    fn render(&mut self, _inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        Ok(GiOutput::Nothing)
    }

    fn read_buffer(&self, _: &wgpu::Device, _: &wgpu::Queue, _: &str) -> Option<Result<HdrImage, RenderError>> {
        None
    }

    fn reset(&mut self, reason: ResetReason) {
        super::technique::note_reset(&mut self.status, reason);
    }

    fn release(&mut self) {}

    fn gpu_bytes(&self) -> u64 {
        0
    }

    fn limitations(&self, _scene: &Scene, _settings: &RenderSettings) -> Vec<String> {
        vec!["no indirect light: direct light from every light only".to_owned()]
    }

    fn status(&self) -> TechniqueStatus {
        self.status.clone()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
