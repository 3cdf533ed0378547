//! `rcs`: GPU irradiance caching by radiance cache splatting (Gautron, Krivanek, Bouatouch and
//! Pattanaik 2005, as Gautron's SIGGRAPH 2007 course notes give it). Sparse records of indirect irradiance, each computed by
//! rasterising the scene into a wide-angle plane at the record ([`hemisphere`], [`reduce`]),
//! placed where splatting leaves pixels uncovered ([`coverage`]), interpolated by splatting the
//! records with Ward's weight and gradients (a tiled compute pass: [`splat`]), and kept across frames in a
//! world-space cache ([`cache`]) that scene and light edits invalidate record by record
//! ([`light_check`], [`cache::Cache::invalidate_boxes`]).

pub mod cache;
pub mod coverage;
pub mod flight;
pub mod grid;
pub mod hemisphere;
pub mod inspect;
pub mod light_check;
pub mod record;
pub mod reduce;
pub mod splat;
pub mod staging;
pub mod store;
pub mod technique;

/// This technique's entry shaders (its registry row lists them).
pub const SHADERS: &[&str] = &[
    "render/gi/rcs/rcs_check.wgsl",
    "render/gi/rcs/rcs_coverage.wgsl",
    "render/gi/rcs/rcs_hemisphere.wgsl",
    "render/gi/rcs/rcs_reduce.wgsl",
    "render/gi/rcs/rcs_resolve.wgsl",
    "render/gi/rcs/rcs_splat.wgsl",
];

/// Every WGSL parameter block of these passes and its Rust size (tests/integration/shaders.rs checks them).
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/gi/rcs/rcs_hemisphere.wgsl", "Job", std::mem::size_of::<record::GpuJob>()),
    ("render/gi/rcs/rcs_hemisphere.wgsl", "Record", std::mem::size_of::<record::GpuRecord>()),
    ("render/gi/rcs/rcs_hemisphere.wgsl", "GridParams", std::mem::size_of::<grid::GridParams>()),
    ("render/gi/rcs/rcs_reduce.wgsl", "ReduceParams", std::mem::size_of::<reduce::ReduceParams>()),
    ("render/gi/rcs/rcs_check.wgsl", "CheckParams", std::mem::size_of::<light_check::CheckParams>()),
    ("render/gi/rcs/rcs_splat.wgsl", "SplatParams", std::mem::size_of::<splat::SplatParams>()),
    ("render/gi/rcs/rcs_resolve.wgsl", "ResolveParams", std::mem::size_of::<splat::ResolveParams>()),
    ("render/gi/rcs/rcs_coverage.wgsl", "CoverageParams", std::mem::size_of::<coverage::CoverageParams>()),
    ("render/gi/rcs/rcs_coverage.wgsl", "Candidate", std::mem::size_of::<record::Candidate>()),
];

/// A uniform buffer of `size` bytes (written per use).
pub(crate) fn uniform(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A storage buffer of `size` bytes (at least 16) that can be written and copied.
pub(crate) fn storage(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// A whole-buffer bind group entry.
pub(crate) fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: buffer.as_entire_binding() }
}
