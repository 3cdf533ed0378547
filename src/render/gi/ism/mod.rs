//! ISM temporal GI (Knecht 2009) on the GPU; its CPU-side math, the test oracles of these
//! passes, is in `precompute::ism` (the P-labels name passes: docs/ARCHITECTURE.md, "ISM pass
//! labels"). [`light_tiles`] says where every light's view lives in the light G-buffer atlas,
//! [`emitter_points`] what its emitter tiles hold.
//!
//! The GPU passes: [`vpl_pass`] (light G-buffer of every light, importance, VPLs; the first
//! set's view weight in [`first_view`]), [`gather`]
//! (ISM atlas and further bounces), [`screen`] (split G-buffer, shading, temporal merge,
//! filter; [`upsample`] its filter when shading at half resolution) and [`sh_filter`] (Segovia
//! & Wald's SH filter), with their parameter blocks in
//! [`params`]. [`technique`] puts them behind the GI seam; [`points`] builds the sample points'
//! per-point data. [`oracle`] checks a rendered frame's maps, lookups and bounce against rays
//! through the scene (`bouncelab probe-ism`).

pub mod clusters;
pub mod emitter_points;
pub mod first_view;
pub mod gather;
pub mod light_tiles;
pub mod oracle;
pub mod params;
pub mod points;
pub mod screen;
pub mod sh_filter;
pub mod stillness;
pub mod technique;
pub mod upsample;
pub mod vpl_pass;

/// This technique's entry shaders (its registry row lists them).
pub const SHADERS: &[&str] = &[
    "render/gi/ism/importance.wgsl",
    "render/gi/ism/ism_bounce.wgsl",
    "render/gi/ism/ism_clear.wgsl",
    "render/gi/ism/ism_emitter_tiles.wgsl",
    "render/gi/ism/ism_filter.wgsl",
    "render/gi/ism/ism_shade.wgsl",
    "render/gi/ism/ism_sh_filter.wgsl",
    "render/gi/ism/ism_select.wgsl",
    "render/gi/ism/ism_splat.wgsl",
    "render/gi/ism/ism_split.wgsl",
    "render/gi/ism/ism_temporal.wgsl",
    "render/gi/ism/ism_upsample.wgsl",
    "render/gi/ism/ism_view_importance.wgsl",
    "render/gi/ism/pull_push.wgsl",
    "render/gi/ism/light_gbuffer.wgsl",
    "render/gi/ism/vpl_generate.wgsl",
];
