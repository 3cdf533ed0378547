//! The ISM passes' shader parameter blocks as `Pod` structs, one per WGSL struct, with their
//! sizes checked at compile time here and against the WGSL layout (naga) in `tests/integration/shaders.rs`
//! through [`PARAM_BLOCKS`].

use bytemuck::{Pod, Zeroable};

use super::emitter_points::GpuEmitterPoint;
use crate::render::uniforms::GpuLight;

/// `SelectParams` in `ism_select.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SelectParams {
    /// VPLs per set, points per ISM P, clusters, first VPL of the set.
    pub counts: [u32; 4],
    /// Pool area per point at weight 1 (m^2), unused x3.
    pub params: [f32; 4],
    /// Frame seed, unused x3.
    pub seed: [u32; 4],
}

/// `Cluster` in `ism_select.wgsl`: pool points `first..first + count` (consecutive in Morton
/// order), their bounding sphere and total area.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCluster {
    /// Centre xyz, radius (m).
    pub sphere: [f32; 4],
    /// First pool point.
    pub first: u32,
    /// Points in the cluster.
    pub count: u32,
    /// Sum of the points' areas (m^2).
    pub area: f32,
    /// The points' plane: octahedral mean normal and thickness bound (`clusters::plane_code`).
    pub plane: u32,
}

/// `SplatParams` in `ism_splat.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SplatParams {
    /// VPL count, points per ISM P, tile side r, tiles per row C.
    pub counts: [u32; 4],
    /// 1 / d_max (normalised distance), splat radius^2 / pi (a splat's radius^2 per m^2 of the
    /// area its point stands for), max splat half-extent in texels, unused.
    pub params: [f32; 4],
    /// First VPL (and atlas tile) of the set being splatted, unused x3.
    pub sets: [u32; 4],
}

/// `BounceParams` in `ism_bounce.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct BounceParams {
    /// VPLs per set, points per ISM P, tile side r, tiles per row C.
    pub counts: [u32; 4],
    /// Source set's first VPL, destination set's first VPL, frame seed, pick
    /// ([`crate::settings::BouncePick`] as u32).
    pub sets: [u32; 4],
    /// 1 / d_max, clamp factor on the disks' radii squared (1: energy-conserving), d_min^2,
    /// interleave n^2.
    pub params: [f32; 4],
    /// Sum over the scene of area x weight, unused x3.
    pub area: [f32; 4],
    /// ISM lookup: neighbour reach (`ism_lit`), normal-offset constant and slope factors (`ism_offset_point`), the
    /// relative depth margin of texels without a point (`ism_lit`).
    pub bias: [f32; 4],
}

/// `PullPushParams` in `pull_push.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct PullPushParams {
    /// Fine side (texels), level of the fine side (0 = finest), first fine row, unused.
    pub counts: [u32; 4],
    /// Relative threshold tau (two depths more than tau x depth x 2^level apart are two
    /// surfaces), unused x3.
    pub params: [f32; 4],
}

/// `SplitParams` in `ism_split.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SplitParams {
    /// Interleave n, gathering step s (1 or 2), unused x2.
    pub counts: [u32; 4],
}

/// `UpsampleParams` in `ism_upsample.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct UpsampleParams {
    /// Interleave n, gathering step s, gathered samples along x and y.
    pub counts: [u32; 4],
    /// Alpha (normalised depth), beta (min cosine), depth range (metres), unused.
    pub params: [f32; 4],
}

/// `ShadeParams` in `ism_shade.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct ShadeParams {
    /// VPL count, tile side r, tiles per row C, interleave n.
    pub counts: [u32; 4],
    /// 1 / d_max, unused, d_min^2, clamp factor on the VPL's disk radius squared.
    pub params: [f32; 4],
    /// VPL sets (bounces), view width, view height, points per ISM.
    pub sets: [u32; 4],
    /// ISM lookup: neighbour reach (`ism_lit`), normal-offset constant and slope factors (`ism_offset_point`), the
    /// relative depth margin of texels without a point (`ism_lit`).
    pub bias: [f32; 4],
}

/// `TemporalParams` in `ism_temporal.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct TemporalParams {
    /// Reset (1 = ignore history), n when the input is in the split layout (0: full), unused x2.
    pub flags: [u32; 4],
    /// c_base, w_pos, w_normal, w_illum.
    pub weights: [f32; 4],
    /// Depth range (metres), exposure multiplier, the confidence's cap (`c_base`, or
    /// 1 - 1 / `still_frames` while nothing moves), unused.
    pub params: [f32; 4],
}

/// `FilterParams` in `ism_filter.wgsl` (and `ShFilterParams` in `ism_sh_filter.wgsl`, which
/// has the same layout and uses only the first count).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct FilterParams {
    /// Interleave n, n when the input is in the split layout (0: full layout), unused x2.
    pub counts: [u32; 4],
    /// Alpha (normalised depth), beta (min cosine), depth range (metres), unused.
    pub params: [f32; 4],
}

/// `GenParams` in `vpl_generate.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GenParams {
    /// VPL count, frame index, interleave n, pyramid levels K (finest side = 2^K).
    pub counts: [u32; 4],
    /// Tiles per row, tile side in texels, tile count, unused.
    pub tiles: [u32; 4],
}

/// `TileRecord` in `vpl_generate.wgsl`: one light-G-buffer tile.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct TileRecord {
    /// World-from-clip of the tile's view.
    pub world_from_clip: [[f32; 4]; 4],
    /// xyz light position (w = 0), the unit direction towards a directional light (w = 1), or
    /// x = the first emitter candidate of an emitter tile (w = 2).
    pub light: [f32; 4],
}

/// `EmitterTile` in `ism_emitter_tiles.wgsl`: where an emitter tile lies and which candidates
/// it holds.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct EmitterTileUniforms {
    /// x, y of the tile's top-left atlas texel, tile side in texels, first candidate.
    pub origin: [u32; 4],
}

/// `LightView` in `light_gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct LightViewUniforms {
    /// Clip-from-world of the tile.
    pub clip_from_world: [[f32; 4]; 4],
    /// The light.
    pub light: GpuLight,
    /// tan(half fov), texels per tile side, world area of a texel (orthographic tiles; 0 for
    /// perspective ones), unused.
    pub params: [f32; 4],
    /// The tile's view axis (xyz).
    pub axis: [f32; 4],
}

/// `SeedParams` in `importance.wgsl` (the first set's view weight, [`super::first_view`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SeedParams {
    /// Tiles per row, tile side in texels, tile count, unused.
    pub tiles: [u32; 4],
    /// x = the seen weight s (`first_set_seen_weight`), unused x3.
    pub weight: [f32; 4],
}

impl SeedParams {
    /// Bytes of the block.
    pub const SIZE: u64 = std::mem::size_of::<Self>() as u64;
}

impl GenParams {
    /// Bytes of the block.
    pub const SIZE: u64 = std::mem::size_of::<Self>() as u64;
}

const _: () = assert!(std::mem::size_of::<SelectParams>() == 48);
const _: () = assert!(std::mem::size_of::<GpuCluster>() == 32);
const _: () = assert!(std::mem::size_of::<SplatParams>() == 48);
const _: () = assert!(std::mem::size_of::<BounceParams>() == 80);
const _: () = assert!(std::mem::size_of::<PullPushParams>() == 32);
const _: () = assert!(std::mem::size_of::<SplitParams>() == 16);
const _: () = assert!(std::mem::size_of::<ShadeParams>() == 64);
const _: () = assert!(std::mem::size_of::<UpsampleParams>() == 32);
const _: () = assert!(std::mem::size_of::<TemporalParams>() == 48);
const _: () = assert!(std::mem::size_of::<FilterParams>() == 32);
const _: () = assert!(std::mem::size_of::<GenParams>() == 32);
const _: () = assert!(std::mem::size_of::<SeedParams>() == 32);
const _: () = assert!(std::mem::size_of::<TileRecord>() == 80);
const _: () = assert!(std::mem::size_of::<LightViewUniforms>() == 160);

/// (shader file, WGSL struct, size of the Rust mirror) for every ISM parameter block.
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/gi/ism/ism_select.wgsl", "SelectParams", std::mem::size_of::<SelectParams>()),
    ("render/gi/ism/ism_select.wgsl", "Cluster", std::mem::size_of::<GpuCluster>()),
    ("render/gi/ism/ism_splat.wgsl", "SplatParams", std::mem::size_of::<SplatParams>()),
    ("render/gi/ism/ism_bounce.wgsl", "BounceParams", std::mem::size_of::<BounceParams>()),
    ("render/gi/ism/pull_push.wgsl", "PullPushParams", std::mem::size_of::<PullPushParams>()),
    ("render/gi/ism/ism_split.wgsl", "SplitParams", std::mem::size_of::<SplitParams>()),
    ("render/gi/ism/ism_shade.wgsl", "ShadeParams", std::mem::size_of::<ShadeParams>()),
    ("render/gi/ism/ism_temporal.wgsl", "TemporalParams", std::mem::size_of::<TemporalParams>()),
    ("render/gi/ism/ism_filter.wgsl", "FilterParams", std::mem::size_of::<FilterParams>()),
    ("render/gi/ism/ism_upsample.wgsl", "UpsampleParams", std::mem::size_of::<UpsampleParams>()),
    ("render/gi/ism/ism_sh_filter.wgsl", "ShFilterParams", std::mem::size_of::<FilterParams>()),
    ("render/gi/ism/vpl_generate.wgsl", "GenParams", std::mem::size_of::<GenParams>()),
    ("render/gi/ism/vpl_generate.wgsl", "TileRecord", std::mem::size_of::<TileRecord>()),
    ("render/gi/ism/light_gbuffer.wgsl", "LightView", std::mem::size_of::<LightViewUniforms>()),
    ("render/gi/ism/ism_emitter_tiles.wgsl", "EmitterTile", std::mem::size_of::<EmitterTileUniforms>()),
    ("render/gi/ism/ism_emitter_tiles.wgsl", "EmitterPoint", std::mem::size_of::<GpuEmitterPoint>()),
    ("render/gi/ism/vpl_generate.wgsl", "EmitterPoint", std::mem::size_of::<GpuEmitterPoint>()),
];
