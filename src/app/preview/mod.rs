//! The viewport preview: the interface never waits for GI.
//!
//! Decision (measured on lavapipe, 2 cores, `ism` on the default project at 1000x760, release):
//! submitting a frame costs the CPU about 1 ms, the GPU work 5.5 s (`ism maps` 0.9 s, `ism
//! shade` 4.5 s; `direct` 0.23 s). When the viewport rendered on eframe's own device, egui's
//! next present queued behind that work, so every click waited for the whole GI frame. Time
//! slicing would have to split each technique's passes; a render thread would have to move the
//! renderer and every reader of it (inspector, GI panel) across threads. Instead the viewport
//! renders on a **second device** of the same adapter ([`frames::AsyncView`]): one frame in
//! flight, its display image copied back without blocking and uploaded as an egui texture
//! (4 MB at 1000x760), while eframe keeps presenting on its own queue. The copy is
//! recorded into the frame's own command buffer: on lavapipe a second submission blocks the
//! caller until the first has finished (6.4 s after an `ism` frame). A waiter thread blocks on
//! the device and wakes egui when the frame is done, so the interface repaints only on input
//! and finished frames: painting the 1400x860 window costs lavapipe about 110 ms of the same
//! two rasteriser threads the frame needs, and with continuous repaints a full `ism` frame took
//! 13 s in the editor instead of 4 s. Picking casts a ray against the scene's BVH
//! ([`super::pick`]), overlays and the gizmo are painted by egui at full resolution, so both
//! stay exact at any render scale. Figures per mode: `examples/ui_bench.rs`, docs/BENCHMARKS.md.
//!
//! The render scale follows a frame budget while something moves and returns to full
//! resolution when nothing does ([`budget::ScaleController`]); temporal techniques keep their
//! history while the scale holds, and a scale change is a resize (they restart, as for a
//! window resize). What cannot be hidden: a frame already in flight runs to its end, so a drag
//! that starts during a full-resolution refinement shows its first preview after that frame.
//!
//! GPU errors on the viewport's device are shown once each; a lost device (driver reset, GPU
//! removed) is reported and replaced by a new device and renderer ([`health`]).

pub mod budget;
pub mod frames;
pub mod health;

pub use budget::{LADDER, PreviewSettings, ScaleController, scaled_size};
pub use frames::{AsyncView, Finished, PreviewError};
pub use health::{GpuMemory, GpuProblem};
