//! ISM temporal GI (Knecht 2009). This module holds the technique's CPU-side math, the test oracle
//! for the WGSL passes (the P-labels name passes: docs/ARCHITECTURE.md, "ISM pass labels"):
//! - [`halton`]: the per-frame-shifted Halton sample set (P4);
//! - [`warp`]: hierarchical warping of samples to an importance map, with the pdf (P3, P5);
//! - [`paraboloid`]: the VPL frame and paraboloid map used by the ISM splat and lookup (P7, P10);
//! - [`power`]: the unbiased VPL power the thesis leaves out (Knecht 2009 section 4.4 and
//!   Eq. 4.7-4.9 give no 1/N, pdf or pi).
//!
//! - [`light_tiles`]: where every light's view lives in the light G-buffer atlas;
//! - [`atlas_word`]: the ISM atlas word and the lookup made of it (P7, P10).
//!
//! The GPU passes: [`vpl_pass`] (light G-buffer of every light, importance, VPLs), [`gather`]
//! (ISM atlas and further bounces), [`screen`] (split G-buffer, shading, temporal merge,
//! filter) and [`sh_filter`] (Segovia & Wald's SH filter), with their parameter blocks in
//! [`params`]. [`technique`] puts them behind the GI seam; [`points`] builds the sample points'
//! per-point data.

pub mod atlas_word;
pub mod clusters;
pub mod gather;
pub mod halton;
pub mod light_tiles;
pub mod paraboloid;
pub mod params;
pub mod points;
pub mod power;
pub mod screen;
pub mod sh_filter;
pub mod technique;
pub mod vpl_pass;
pub mod warp;

/// This technique's entry shaders (its registry row lists them).
pub const SHADERS: &[&str] = &[
    "render/gi/ism/importance.wgsl",
    "render/gi/ism/ism_bounce.wgsl",
    "render/gi/ism/ism_filter.wgsl",
    "render/gi/ism/ism_shade.wgsl",
    "render/gi/ism/ism_sh_filter.wgsl",
    "render/gi/ism/ism_select.wgsl",
    "render/gi/ism/ism_splat.wgsl",
    "render/gi/ism/ism_split.wgsl",
    "render/gi/ism/ism_temporal.wgsl",
    "render/gi/ism/ism_view_importance.wgsl",
    "render/gi/ism/pull_push.wgsl",
    "render/gi/ism/light_gbuffer.wgsl",
    "render/gi/ism/vpl_generate.wgsl",
];
