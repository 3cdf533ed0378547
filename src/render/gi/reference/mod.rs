//! `reference`: the progressive CPU path tracer (`precompute::pathtracer`) behind the same seam
//! as the GPU techniques. It renders on a background thread at half the view resolution (the
//! editor's preview; the inspector's comparison runs its own full-resolution job), restarts
//! whenever the scene, its settings or the size change, and hands the latest accumulated image
//! to the composite as the complete radiance. It never blocks a frame: until the first pass
//! lands it reports [`Readiness::Pending`] and the frame shows direct light.

pub mod job;

use super::inputs::GiInputs;
use super::technique::{GiOutput, GiTechnique, Readiness, ResetReason, SupportQuery, TechniqueStatus, note_reset};
use crate::image_io::HdrImage;
use crate::render::RenderError;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use job::ReferenceJob;

/// The preview renders at 1 / PREVIEW_DIVISOR of the view per axis.
pub const PREVIEW_DIVISOR: u32 = 2;

/// The latest preview image upsampled to the view: its spp, the view size and the pixels.
struct Shown {
    spp: u32,
    size: (u32, u32),
    pixels: Vec<[f32; 4]>,
}

/// The reference path tracer as a technique.
#[derive(Default)]
pub struct ReferenceTechnique {
    job: Option<ReferenceJob>,
    shown: Option<Shown>,
    /// The spp of the image last written to `indirect` (written again only when it changes,
    /// or after a frame that wrote nothing, which clears the target).
    uploaded: Option<u32>,
    status: TechniqueStatus,
    restarts: u64,
    view: (u32, u32),
}

/// Nearest-neighbour upsampling of `img` to `size`.
fn upsample(img: &HdrImage, size: (u32, u32)) -> Vec<[f32; 4]> {
    let (w, h) = (img.width.max(1), img.height.max(1));
    let mut out = Vec::with_capacity(size.0 as usize * size.1 as usize);
    for y in 0..size.1 {
        let sy = ((u64::from(y) * u64::from(h)) / u64::from(size.1.max(1))).min(u64::from(h - 1)) as usize;
        for x in 0..size.0 {
            let sx = ((u64::from(x) * u64::from(w)) / u64::from(size.0.max(1))).min(u64::from(w - 1)) as usize;
            out.push(img.pixels.get(sy * w as usize + sx).copied().unwrap_or([0.0; 4]));
        }
    }
    out
}

impl ReferenceTechnique {
    /// Runs everywhere (on the CPU).
    pub fn support(_query: &SupportQuery<'_>) -> Result<(), String> {
        Ok(())
    }

    fn preview_size(view: (u32, u32)) -> (u32, u32) {
        ((view.0 / PREVIEW_DIVISOR).max(1), (view.1 / PREVIEW_DIVISOR).max(1))
    }
}

impl GiTechnique for ReferenceTechnique {
    fn prepare(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Readiness {
        self.view = size;
        let size = Self::preview_size(size);
        if self.job.as_ref().is_none_or(|j| !j.matches(scene, &settings.reference, size)) {
            self.job = Some(ReferenceJob::start(scene, &settings.reference, size));
            self.shown = None;
            self.restarts += 1;
            self.status.history_frames = 0;
        }
        let latest = self.job.as_ref().and_then(ReferenceJob::latest);
        match latest {
            Some((img, progress)) => {
                if self.shown.as_ref().is_none_or(|s| s.spp != progress.spp || s.size != self.view) {
                    self.shown = Some(Shown { spp: progress.spp, size: self.view, pixels: upsample(&img, self.view) });
                }
                self.status.history_frames = progress.spp;
                self.status.refining = progress.spp < settings.reference.spp;
                self.status.refine_target = settings.reference.spp;
                self.status.progress = Some(format!(
                    "reference: {} / {} spp, {:.1} Mrays/s",
                    progress.spp,
                    settings.reference.spp,
                    progress.rays_per_second * 1e-6
                ));
                Readiness::Ready
            }
            None => {
                self.uploaded = None;
                self.status.progress = Some("reference: first pass".to_owned());
                self.status.refining = true;
                Readiness::Pending { progress: 0.0, what: "reference: first pass".to_owned() }
            }
        }
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        let size = inputs.targets.size;
        let Some(Shown { size: shown_size, pixels, .. }) = &self.shown else { return Ok(GiOutput::Nothing) };
        if *shown_size != size {
            self.uploaded = None;
            return Ok(GiOutput::Nothing);
        }
        let spp = self.shown.as_ref().map(|s| s.spp);
        if self.uploaded == spp {
            // `indirect` still holds this image: the view targets were not recreated (that
            // changes the size, caught above) and no other technique ran.
            return Ok(GiOutput::Complete);
        }
        self.uploaded = spp;
        let texture = &inputs.targets.indirect.texture;
        inputs.queue.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(pixels),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(size.0 * 16), rows_per_image: Some(size.1) },
            texture.size(),
        );
        Ok(GiOutput::Complete)
    }

    fn read_buffer(&self, _: &wgpu::Device, _: &wgpu::Queue, _: &str) -> Option<Result<HdrImage, RenderError>> {
        None
    }

    fn reset(&mut self, reason: ResetReason) {
        // Every edit restarts the accumulation: `prepare` compares the scene revision, which
        // changes on any edit (camera moves included), so nothing else to drop here.
        note_reset(&mut self.status, reason);
    }

    fn release(&mut self) {
        self.job = None;
        self.shown = None;
        self.uploaded = None;
    }

    fn gpu_bytes(&self) -> u64 {
        0
    }

    fn status(&self) -> TechniqueStatus {
        let mut s = self.status.clone();
        s.counters = vec![("restarts", self.restarts)];
        s
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn upsampling_repeats_each_preview_pixel() {
        let img = HdrImage { width: 2, height: 1, pixels: vec![[1.0; 4], [2.0; 4]] };
        let up = upsample(&img, (4, 2));
        assert_eq!(up.iter().map(|p| p[0]).collect::<Vec<_>>(), [1.0, 1.0, 2.0, 2.0, 1.0, 1.0, 2.0, 2.0]);
    }
}
