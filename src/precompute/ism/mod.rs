//! ISM's CPU side (Ritschel et al. 2008, Knecht 2009): the math the GPU passes in
//! `render::gi::ism` compute, written once more on the CPU as their test oracles.
//! - [`halton`]: the per-frame-shifted Halton sample set (P4);
//! - [`warp`]: hierarchical warping of samples to an importance map, with the pdf (P3, P5);
//! - [`paraboloid`]: the VPL frame and paraboloid map of the ISM splat and lookup (P7, P10);
//! - [`power`]: the unbiased VPL power the thesis leaves out (Knecht 2009 section 4.4 and
//!   Eq. 4.7-4.9 give no 1/N, pdf or pi);
//! - [`atlas_word`]: the ISM atlas word, the atlas's level layout, and the lookup made of them
//!   (P7, P8, P10);
//! - [`slab`]: the lookups' test of the solid behind a point's face (P10).
//!
//! The P-labels name passes: docs/ARCHITECTURE.md, "ISM pass labels".

pub mod atlas_word;
pub mod halton;
pub mod paraboloid;
pub mod power;
pub mod slab;
pub mod warp;
