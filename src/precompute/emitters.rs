//! The emissive triangles of a scene as lights for the reference path tracer: chosen in
//! proportion to their power (area x the luminance of `emissive_color x emissive_strength`),
//! then a uniform point on the triangle (Shirley's square-root warp), so next-event estimation
//! finds a small bright panel that BRDF sampling alone would hit once in thousands of paths.
//! Textured emission is evaluated at the sampled point; the choice ignores the texture (every
//! texel it can show is reachable, so the estimate stays unbiased).

use glam::Vec3;

use super::bvh::{SceneBvh, Tri};
use super::sky_sampler::luminance;
use crate::scene::{Image, Material};

/// A point chosen on an emissive triangle.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    /// The triangle (index into the BVH's triangles).
    pub tri: u32,
    /// The point and its barycentrics (weights `1-u-v`, `u`, `v`).
    pub p: Vec3,
    pub u: f32,
    pub v: f32,
    /// Probability density per unit area of choosing this point.
    pub pdf_area: f32,
}

/// The emissive triangles and their power distribution.
#[derive(Default)]
pub struct Emitters {
    /// BVH triangle index of each emitter.
    tris: Vec<u32>,
    /// Cumulative power (last = the total).
    cdf: Vec<f32>,
    /// Per BVH triangle: its emitter index, or `u32::MAX`.
    index_of: Vec<u32>,
    /// Per emitter: its area.
    areas: Vec<f32>,
}

fn area(tri: &Tri) -> f32 {
    0.5 * (tri.p[1] - tri.p[0]).cross(tri.p[2] - tri.p[0]).length()
}

impl Emitters {
    /// Every triangle of `bvh` whose material emits.
    pub fn new(bvh: &SceneBvh, materials: &[Material]) -> Self {
        let mut out = Self { index_of: vec![u32::MAX; bvh.tris.len()], ..Self::default() };
        let mut total = 0.0f64;
        for (i, tri) in bvh.tris.iter().enumerate() {
            let Some(m) = materials.get(tri.material as usize).filter(|m| m.emits()) else { continue };
            let a = area(tri);
            let power = a * luminance(m.emission()).max(1e-6 * m.emission().max_element());
            if a <= 0.0 || power <= 0.0 || !power.is_finite() {
                continue;
            }
            total += f64::from(power);
            out.index_of[i] = out.tris.len() as u32;
            out.tris.push(i as u32);
            out.cdf.push(total as f32);
            out.areas.push(a);
        }
        out
    }

    /// The sum over the emitters of area x luminance of their untextured emission (their
    /// luminous power over pi).
    pub fn total(&self) -> f32 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    /// Whether the scene has any emissive triangle.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Probability of choosing emitter `e`.
    fn choice(&self, e: usize) -> f32 {
        let total = *self.cdf.last().unwrap_or(&1.0);
        (self.cdf[e] - if e == 0 { 0.0 } else { self.cdf[e - 1] }) / total
    }

    /// The density per unit area of [`Self::sample`] choosing a point of BVH triangle `tri`
    /// (0 for a triangle that does not emit).
    pub fn pdf_area(&self, tri: u32) -> f32 {
        match self.index_of.get(tri as usize) {
            Some(&e) if e != u32::MAX => self.choice(e as usize) / self.areas[e as usize],
            _ => 0.0,
        }
    }

    /// A point on an emitter from three uniform numbers, or `None` without emitters.
    pub fn sample(&self, bvh: &SceneBvh, u: [f32; 3]) -> Option<EmitterSample> {
        let total = *self.cdf.last()?;
        let e = self.cdf.partition_point(|c| *c <= u[0] * total).min(self.tris.len() - 1);
        let tri_index = self.tris[e];
        let tri = &bvh.tris[tri_index as usize];
        let r = u[1].sqrt();
        let (b1, b2) = (r * (1.0 - u[2]), r * u[2]);
        let p = tri.p[0] * (1.0 - b1 - b2) + tri.p[1] * b1 + tri.p[2] * b2;
        Some(EmitterSample { tri: tri_index, p, u: b1, v: b2, pdf_area: self.choice(e) / self.areas[e] })
    }
}

/// The radiance the front of `tri` (material `m`) emits at barycentrics (`u`, `v`): emission
/// colour x strength x the emission texture (sRGB, bilinear) of `images` there.
pub fn emission_at(m: &Material, images: &[Image], tri: &Tri, u: f32, v: f32) -> Vec3 {
    let mut e = m.emission();
    if let Some(img) = m.emissive_texture.and_then(|t| images.get(t.image)) {
        let uv = tri.uv[0] * (1.0 - u - v) + tri.uv[1] * u + tri.uv[2] * v;
        e *= super::pathtracer::sample_image(img, uv, true);
    }
    e
}

/// The power heuristic (β = 2) weight of a strategy with density `a` against one with `b`.
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 <= 0.0 || !(a2 + b2).is_finite() { if a > b { 1.0 } else { 0.0 } } else { a2 / (a2 + b2) }
}
