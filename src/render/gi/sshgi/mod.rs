//! `sshgi`: screen-space hierarchical indirect light (Soler, Hoel, Rochet and Holzschuch 2010). A purely deferred technique: its cost does
//! not depend on the scene's geometry or lights, every light type feeds it through the direct
//! term, and it adds several bounces, but in the paper only surfaces on screen send light; the
//! panorama ([`panorama`], not in the paper) adds the surfaces around the camera off screen, and
//! the hidden senders ([`hidden`], not in the paper) those the camera's position does not see.

pub mod hidden;
pub mod oracle;
pub mod panorama;
pub mod passes;
pub mod technique;
pub mod temporal;
pub mod voxels;
pub mod world_grid;

/// This technique's entry shaders (its registry row lists them).
pub const SHADERS: &[&str] = &[
    "render/gi/sshgi/sshgi_gather.wgsl",
    "render/gi/sshgi/sshgi_hidden_pack.wgsl",
    "render/gi/sshgi/sshgi_mip.wgsl",
    "render/gi/sshgi/sshgi_panorama_gather.wgsl",
    "render/gi/sshgi/sshgi_panorama_pack.wgsl",
    "render/gi/sshgi/sshgi_panorama_receive.wgsl",
    "render/gi/sshgi/sshgi_sky.wgsl",
    "render/gi/sshgi/sshgi_tail.wgsl",
    "render/gi/sshgi/sshgi_upsample.wgsl",
    "render/gi/sshgi/sshgi_voxel_mip.wgsl",
    "render/gi/sshgi/sshgi_voxelize.wgsl",
    "render/gi/sshgi/sshgi_temporal.wgsl",
];

use std::mem::size_of;

/// (shader file, WGSL struct, size of the Rust mirror) for every sshgi parameter block, checked
/// against naga's layout by `tests/integration/shaders.rs`.
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/gi/sshgi/sshgi_mip.wgsl", "MipParams", size_of::<passes::Counts>()),
    ("render/gi/sshgi/sshgi_upsample.wgsl", "UpParams", size_of::<passes::UpParams>()),
    ("render/gi/sshgi/sshgi_gather.wgsl", "GatherParams", size_of::<passes::GatherParams>()),
    ("render/gi/sshgi/sshgi_voxelize.wgsl", "VoxelParams", size_of::<voxels::VoxelParams>()),
    ("render/gi/sshgi/sshgi_voxel_mip.wgsl", "VoxelMipParams", size_of::<voxels::MipParams>()),
    ("render/gi/sshgi/sshgi_temporal.wgsl", "TemporalParams", size_of::<temporal::TemporalParams>()),
    ("render/gi/sshgi/sshgi_panorama_pack.wgsl", "PackParams", size_of::<panorama::PackParams>()),
    ("render/gi/sshgi/sshgi_panorama_gather.wgsl", "PanoramaParams", size_of::<panorama::PanoramaParams>()),
    ("render/gi/sshgi/sshgi_panorama_receive.wgsl", "PanoramaParams", size_of::<panorama::PanoramaParams>()),
    ("render/gi/sshgi/sshgi_sky.wgsl", "SkyRayParams", size_of::<passes::SkyRayParams>()),
    ("render/gi/sshgi/sshgi_hidden_pack.wgsl", "HiddenParams", size_of::<hidden::HiddenParams>()),
    ("render/gi/sshgi/sshgi_hidden_pack.wgsl", "Surfel", size_of::<hidden::GpuSurfel>()),
];
