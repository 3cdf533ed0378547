//! The renderer's side of the technique seam that the editor, the CLI and tests use: the
//! active technique, its status, limitations, overlays and GPU memory, and the inspected buffer.

use super::Renderer;
use crate::render::gi::{GiTechnique, Overlay, TechniqueStatus};
use crate::scene::Scene;
use crate::settings::{GiMode, RenderSettings};

impl Renderer {
    /// The active technique (after the first frame).
    pub fn technique(&self) -> Option<&dyn GiTechnique> {
        self.techniques.active()
    }

    /// The active technique, downcast to its concrete type (tests and tools).
    pub fn technique_as<T: 'static>(&self) -> Option<&T> {
        self.techniques.active()?.as_any().downcast_ref::<T>()
    }

    /// The active mode's status (history length, resets, progress).
    pub fn technique_status(&self) -> Option<TechniqueStatus> {
        self.techniques.active().map(GiTechnique::status)
    }

    /// What the technique for `settings.mode` ignores in `scene` (sentences for the GI panel
    /// and the CLI); empty before it was first used.
    pub fn limitations(&self, scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        self.techniques.get(settings.mode).map_or_else(Vec::new, |t| t.limitations(scene, settings))
    }

    /// Why the technique for `settings.mode` could not do its work (see
    /// [`GiTechnique::shortfalls`]); empty before it was first used.
    pub fn shortfalls(&self, scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        self.techniques.get(settings.mode).map_or_else(Vec::new, |t| t.shortfalls(scene, settings))
    }

    /// The active technique's viewport overlays (reads back from the GPU: call sparingly).
    pub fn overlays(&self) -> Vec<Overlay> {
        self.techniques.active().map_or_else(Vec::new, |t| t.overlays(&self.device, &self.queue))
    }

    /// GPU bytes held by each technique created so far (released ones hold none).
    pub fn technique_gpu_bytes(&self) -> Vec<(GiMode, u64)> {
        self.techniques.gpu_bytes()
    }

    /// Tells the renderer which buffer the inspector shows (techniques keep debug copies, and
    /// the depth/normal pyramid is built, only while shown).
    pub fn set_inspected(&mut self, name: Option<&str>) {
        self.inspected = name.map(str::to_owned);
    }

    /// The device this renderer draws with.
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The queue this renderer submits to.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }
}
