//! FLIP (Andersson et al. 2020, NVIDIA's reference implementation through the `nv-flip` crate).
//! FLIP is defined on display images, so linear radiance is first exposed by `2^ev`, clamped and
//! sRGB-encoded to 8 bits; both images get the same transform.

use super::{MetricsError, check};
use crate::image_io::HdrImage;

/// Observer setting: 0.7 m from a 0.7 m wide 4K monitor (FLIP's default, 67 pixels per degree).
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

fn encode(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

/// The 8-bit sRGB RGB bytes FLIP sees for `img` at exposure `ev`.
pub fn ldr_srgb8(img: &HdrImage, ev: f32) -> Vec<u8> {
    let k = ev.exp2();
    img.pixels.iter().flat_map(|p| [encode(p[0] * k), encode(p[1] * k), encode(p[2] * k)]).collect()
}

/// Mean FLIP error and the per-pixel error map (0..1, row-major).
pub fn flip(candidate: &HdrImage, reference: &HdrImage, exposure_ev: f32) -> Result<(f32, Vec<f32>), MetricsError> {
    check(candidate, reference)?;
    let (w, h) = (candidate.width, candidate.height);
    let r = nv_flip::FlipImageRgb8::with_data(w, h, &ldr_srgb8(reference, exposure_ev));
    let t = nv_flip::FlipImageRgb8::with_data(w, h, &ldr_srgb8(candidate, exposure_ev));
    let map = nv_flip::flip(r, t, FLIP_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    Ok((mean, map.to_vec()))
}
