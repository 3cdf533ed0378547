//! Global-illumination techniques behind one seam (docs/ARCHITECTURE.md, "The GI seam").
//!
//! [`technique`] defines the seam: the [`GiTechnique`] trait, what a technique writes
//! ([`GiOutput`]), why its history resets ([`ResetReason`]), its inspector buffers and overlays.
//! [`inputs`] is the one struct every technique renders from; [`changes`] turns scene and
//! settings revisions into reset reasons; [`registry`] lists the techniques this build has and
//! keeps one active, releasing the others' GPU memory.
//!
//! One folder or file per technique: `direct` (adds nothing), `ism/` (Knecht 2009: instant
//! radiosity with imperfect shadow maps and temporal reuse; its pure math is written and tested
//! first on the CPU and the WGSL passes mirror it), `sshgi/` (Soler 2010), `mrt/` (Loos 2015's
//! modular radiance transfer on proxy blocks), `rcs/` (Gautron et al.'s radiance cache splatting)
//! and `reference/` (the CPU path tracer).

pub mod changes;
pub mod direct;
pub mod inputs;
pub mod ism;
pub mod mrt;
pub mod rcs;
pub mod reference;
pub mod registry;
pub mod sshgi;
pub mod technique;

pub use changes::ChangeDetector;
pub use technique::{
    BufferInfo, BufferView, GiOutput, GiTechnique, Needs, Overlay, OverlayPoint, Readiness, ResetReason, SupportQuery,
    TechniqueStatus,
};
