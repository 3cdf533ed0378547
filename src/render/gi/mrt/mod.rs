//! `mrt`: modular radiance transfer over proxy blocks (Loos 2015) at run time. The precompute
//! (dictionary, interfaces, level assembly, fitting) lives in `precompute::mrt`; this folder
//! packs a level for the GPU ([`pack`]), prepares it off the frame ([`job`]), records the
//! per-frame passes ([`passes`]), draws its inspector images ([`inspect`]) and plugs into the
//! GI seam ([`technique`]).

pub mod drt_pack;
pub mod drt_passes;
pub mod inspect;
pub mod job;
pub mod pack;
pub mod passes;
pub mod technique;

/// This technique's entry shaders (its registry row lists them).
pub const SHADERS: &[&str] = &[
    "render/gi/mrt/mrt_apply.wgsl",
    "render/gi/mrt/mrt_direct.wgsl",
    "render/gi/mrt/mrt_interface.wgsl",
    "render/gi/mrt/mrt_reconstruct.wgsl",
    "render/gi/mrt/mrt_reduce.wgsl",
    "render/gi/mrt/mrt_sides.wgsl",
    "render/gi/mrt/drt_patches.wgsl",
    "render/gi/mrt/drt_rows.wgsl",
];

/// Parameter blocks and records shared with WGSL (file, struct, bytes), checked by the shader
/// tests against naga's layout.
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/gi/mrt/mrt_direct.wgsl", "MrtParams", std::mem::size_of::<passes::MrtParams>()),
    ("render/gi/mrt/mrt_direct.wgsl", "Texel", std::mem::size_of::<pack::GpuTexel>()),
    ("render/gi/mrt/mrt_apply.wgsl", "Block", std::mem::size_of::<pack::GpuBlock>()),
    ("render/gi/mrt/mrt_apply.wgsl", "Clutter", std::mem::size_of::<drt_pack::GpuClutter>()),
    ("render/gi/mrt/drt_rows.wgsl", "DrtParams", std::mem::size_of::<drt_pack::DrtGpuParams>()),
];
