//! ISM temporal GI (Knecht 2009; digest `technique-ism-temporal.md`). This module holds the
//! technique's CPU-side math, the test oracle for the WGSL passes:
//! - [`halton`]: the per-frame-shifted Halton sample set (P4);
//! - [`warp`]: hierarchical warping of samples to an importance map, with the pdf (P3, P5);
//! - [`paraboloid`]: the VPL frame and paraboloid map used by the ISM splat and lookup (P7, P10);
//! - [`power`]: the unbiased VPL power the thesis leaves out (digest section 7.3).
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
