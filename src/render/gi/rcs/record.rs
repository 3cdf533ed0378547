//! The GPU layouts that cross between the rcs passes and the CPU: a record (what the cache
//! stores), a job (one record to compute this round) and a candidate (an uncovered pixel the
//! coverage pass proposes), and how a candidate becomes a job.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// `Record` in `rcs_common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuRecord {
    /// xyz P_k, w = R_k clamped (0: free slot).
    pub position: [f32; 4],
    /// xyz n_k, w = times computed.
    pub normal: [f32; 4],
    /// rgb E_k, w = the harmonic mean distance before the clamp.
    pub irradiance: [f32; 4],
    /// Rotational gradient per channel.
    pub grad_r: [[f32; 4]; 3],
    /// Translational gradient per channel.
    pub grad_t: [[f32; 4]; 3],
    /// x = the light check's stored sum, yzw = the hemisphere camera's tangent.
    pub check: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuRecord>() == 160);

/// `Job` in `rcs_job.wgsl`: a 256-byte slot (uniform dynamic offsets and array stride alike).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuJob {
    /// xyz P_k, w = the near plane (m).
    pub position: [f32; 4],
    /// xyz n_k, w = the slot as bits.
    pub normal: [f32; 4],
    /// xyz tangent, w = smallest R_k.
    pub tangent: [f32; 4],
    /// xyz bitangent, w = largest R_k.
    pub bitangent: [f32; 4],
    /// x = furnace, y = cache lookup, zw = first atlas texel.
    pub params: [f32; 4],
    /// x = times computed before.
    pub extra: [f32; 4],
    /// Padding to 256 bytes.
    pub pad: [[f32; 4]; 10],
}

const _: () = assert!(std::mem::size_of::<GpuJob>() == 256);

/// `Candidate` in `rcs_coverage.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Candidate {
    /// xyz world position, w = distance to the camera.
    pub position: [f32; 4],
    /// xyz geometric normal, w = tile index as bits.
    pub normal: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<Candidate>() == 32);

impl Candidate {
    /// The site.
    pub fn point(&self) -> Vec3 {
        Vec3::new(self.position[0], self.position[1], self.position[2])
    }

    /// The unit geometric normal.
    pub fn direction(&self) -> Vec3 {
        Vec3::new(self.normal[0], self.normal[1], self.normal[2]).normalize_or(Vec3::Z)
    }

    /// The 8 x 8 tile it came from.
    pub fn tile(&self) -> u32 {
        self.normal[3].to_bits()
    }
}

/// What a job does besides rendering the direct light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JobFlags {
    /// Every surface and the background emit 1 (the white furnace).
    pub furnace: bool,
    /// Look the cache up at the surfaces seen (later bounces).
    pub lookup: bool,
    /// Propose secondary records where the lookup misses.
    pub propose: bool,
}

/// A record's site and the bounds of its R, fixed when it is made (renewals reuse them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Site {
    pub position: Vec3,
    pub normal: Vec3,
    /// Near plane of the hemisphere camera (m).
    pub near: f32,
    /// Smallest and largest R_k (m).
    pub radius_bounds: (f32, f32),
}

impl Site {
    /// The site of a candidate seen from `distance` metres with `pixel_angle` radians per
    /// pixel: R_k clamped so that a x R_k spans `zone_pixels` (min, max; max 0 = up to
    /// `largest`) pixels at that distance, and a near plane of a quarter pixel's footprint.
    pub fn new(
        position: Vec3,
        normal: Vec3,
        footprint: f32,
        accuracy: f32,
        zone_pixels: (f32, f32),
        largest: f32,
    ) -> Self {
        let footprint = footprint.max(1e-6);
        let lo = zone_pixels.0 * footprint / accuracy;
        let hi = if zone_pixels.1 > 0.0 { zone_pixels.1 * footprint / accuracy } else { largest };
        Self { position, normal, near: 0.25 * footprint, radius_bounds: (lo, hi.max(lo)) }
    }

    /// The job computing this site into `slot`, its plane at atlas texel `origin`; `propose`:
    /// list secondary sites where its bounce lookups miss.
    pub fn job(&self, slot: u32, origin: (u32, u32), flags: JobFlags, computed: u32) -> GpuJob {
        let (t, b) = crate::scene::basis::basis(self.normal);
        let v = |v: Vec3, w: f32| [v.x, v.y, v.z, w];
        GpuJob {
            position: v(self.position, self.near),
            normal: v(self.normal, f32::from_bits(slot)),
            tangent: v(t, self.radius_bounds.0),
            bitangent: v(b, self.radius_bounds.1),
            params: [
                f32::from(u8::from(flags.furnace)),
                f32::from(u8::from(flags.lookup)),
                origin.0 as f32,
                origin.1 as f32,
            ],
            extra: [computed as f32, f32::from(u8::from(flags.propose)), 0.0, 0.0],
            pad: [[0.0; 4]; 10],
        }
    }
}
