//! CPU-side heavy work that never touches the GPU: the ray-tracing BVH of the scene and the
//! reference path tracer, the ISM sample points and which faces see anything, and MRT's
//! dictionary operators. Uses rayon; never imports wgpu/egui.

#[cfg(test)]
mod area_light_tests;
pub mod brdf;
pub mod bvh;
pub mod drt;
pub mod emitters;
pub mod facing;
pub mod guiding;
#[cfg(test)]
mod guiding_tests;
pub mod ism;
pub mod mrt;
pub mod open_edges;
pub mod pathtracer;
pub mod rng;
pub mod sample_points;
pub mod sampler;
pub mod sky_sampler;
pub mod surface_voxels;
#[cfg(test)]
pub(crate) mod test_scenes;
pub mod unseen;
pub mod wide_bvh;
