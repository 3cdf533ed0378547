//! The wgpu renderer (no egui): device context, scene upload, G-buffer, shadow maps, deferred
//! lighting, tonemapping, GPU timings and readback.
//!
//! [`Renderer::render`] is the one readable frame function (docs/ARCHITECTURE.md, "The frame"):
//! G-buffer -> emission -> shadow maps -> direct light (+ what the camera sees of emitters) -> [depth/normal pyramid] -> the active GI technique
//! (through the seam in [`gi`]) -> composite -> tonemap.

mod composite;
mod context;
mod emission;
mod frame;
mod gbuffer;
pub mod gi;
pub mod harness;
pub(crate) mod layouts;
mod lighting;
pub mod obscurance;
pub mod octahedral;
pub mod pyramid;
pub mod readback;
pub(crate) mod scene_gpu;
pub mod shaders;
pub(crate) mod shadows;
pub mod sky;
pub mod targets;
pub(crate) mod timing;
mod tonemap;
pub(crate) mod uniforms;

pub use context::{ContextError, GpuContext, device_descriptor, log_device_errors, wanted_features};
pub use frame::{RenderError, Renderer, area_light_shortfall};
pub use timing::PassTiming;
