//! Image-error metrics between a candidate and a reference render (no GPU types): RMSE, relMSE,
//! FLIP, mean-luminance ratio, a signed error heat map, per-object error and temporal
//! instability. Used by `bouncelab compare`, the tests and the editor's comparison view.

mod flip;
mod heatmap;
mod temporal;

pub use flip::{FLIP_PIXELS_PER_DEGREE, flip, ldr_srgb8};
pub use heatmap::signed_heatmap;
pub use temporal::{mean_frame_change, relative_spread, temporal_instability};

use serde::Serialize;

use crate::image_io::HdrImage;

/// Why two images cannot be compared.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MetricsError {
    /// Different sizes.
    #[error("image sizes differ: {0}x{1} vs {2}x{3}")]
    Size(u32, u32, u32, u32),
    /// A value is NaN or infinite.
    #[error("{0} image has NaN or infinite values")]
    NonFinite(&'static str),
    /// Too few frames for a temporal measure.
    #[error("need at least two frames, got {0}")]
    Frames(usize),
}

/// Rec. 709 luminance.
pub fn luminance(c: &[f32; 4]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

fn check(a: &HdrImage, b: &HdrImage) -> Result<(), MetricsError> {
    if (a.width, a.height) != (b.width, b.height) || a.pixels.len() != b.pixels.len() {
        return Err(MetricsError::Size(a.width, a.height, b.width, b.height));
    }
    if !a.pixels.iter().flatten().all(|v| v.is_finite()) {
        return Err(MetricsError::NonFinite("candidate"));
    }
    if !b.pixels.iter().flatten().all(|v| v.is_finite()) {
        return Err(MetricsError::NonFinite("reference"));
    }
    Ok(())
}

/// Root-mean-square error over the RGB channels of every pixel.
pub fn rmse(candidate: &HdrImage, reference: &HdrImage) -> Result<f64, MetricsError> {
    check(candidate, reference)?;
    let sum: f64 = candidate
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(a, b)| (0..3).map(|c| f64::from(a[c] - b[c]).powi(2)).sum::<f64>())
        .sum();
    Ok((sum / (3 * candidate.pixels.len().max(1)) as f64).sqrt())
}

/// Relative MSE: mean of (c - r)^2 / (r^2 + epsilon) over RGB, with the reference in the
/// denominator (epsilon 0.01 keeps black pixels from dominating).
pub fn relmse(candidate: &HdrImage, reference: &HdrImage, epsilon: f64) -> Result<f64, MetricsError> {
    check(candidate, reference)?;
    let sum: f64 = candidate
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(a, b)| (0..3).map(|c| f64::from(a[c] - b[c]).powi(2) / (f64::from(b[c]).powi(2) + epsilon)).sum::<f64>())
        .sum();
    Ok(sum / (3 * candidate.pixels.len().max(1)) as f64)
}

/// Mean luminance of an image.
pub fn mean_luminance(img: &HdrImage) -> f64 {
    img.pixels.iter().map(|p| f64::from(luminance(p))).sum::<f64>() / img.pixels.len().max(1) as f64
}

/// The exposure (stops) that puts `reference`'s mean luminance at 0.18, so dim scenes (the
/// unlit room, the diorama) are judged as a user would look at them: the quality matrix's and
/// `compare --exposure-auto`'s exposure, and the tests'.
pub fn judging_exposure(reference: &HdrImage) -> f32 {
    (0.18 / mean_luminance(reference).max(1e-6)).log2() as f32
}

/// Mean luminance of the candidate over that of the reference (1 = same energy).
pub fn luminance_ratio(candidate: &HdrImage, reference: &HdrImage) -> Result<f64, MetricsError> {
    check(candidate, reference)?;
    Ok(mean_luminance(candidate) / mean_luminance(reference).max(1e-12))
}

/// All scalar metrics of one comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    pub rmse: f64,
    pub relmse: f64,
    pub flip: f64,
    pub luminance_ratio: f64,
}

/// Computes every scalar metric; FLIP is measured on the images exposed by `exposure_ev`.
pub fn compare(candidate: &HdrImage, reference: &HdrImage, exposure_ev: f32) -> Result<Comparison, MetricsError> {
    Ok(Comparison {
        rmse: rmse(candidate, reference)?,
        relmse: relmse(candidate, reference, 0.01)?,
        flip: f64::from(flip(candidate, reference, exposure_ev)?.0),
        luminance_ratio: luminance_ratio(candidate, reference)?,
    })
}

/// Error of one object (pixels whose object id is `id`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObjectError {
    /// Object id as stored in the G-buffer (object index + 1).
    pub id: u32,
    /// Pixels covered.
    pub pixels: usize,
    /// RMSE over those pixels.
    pub rmse: f64,
    /// relMSE over those pixels.
    pub relmse: f64,
    /// Mean luminance ratio over those pixels.
    pub luminance_ratio: f64,
}

/// Per-object errors using the object-id buffer (0 = background, skipped), sorted by id.
pub fn per_object(candidate: &HdrImage, reference: &HdrImage, ids: &[u32]) -> Result<Vec<ObjectError>, MetricsError> {
    check(candidate, reference)?;
    if ids.len() != candidate.pixels.len() {
        return Err(MetricsError::Size(candidate.width, candidate.height, ids.len() as u32, 1));
    }
    let mut acc: std::collections::BTreeMap<u32, (usize, f64, f64, f64, f64)> = std::collections::BTreeMap::new();
    for ((a, b), &id) in candidate.pixels.iter().zip(&reference.pixels).zip(ids) {
        if id == 0 {
            continue;
        }
        let e = acc.entry(id).or_default();
        e.0 += 1;
        for c in 0..3 {
            let d = f64::from(a[c] - b[c]);
            e.1 += d * d;
            e.2 += d * d / (f64::from(b[c]).powi(2) + 0.01);
        }
        e.3 += f64::from(luminance(a));
        e.4 += f64::from(luminance(b));
    }
    Ok(acc
        .into_iter()
        .map(|(id, (n, se, rel, la, lb))| ObjectError {
            id,
            pixels: n,
            rmse: (se / (3 * n) as f64).sqrt(),
            relmse: rel / (3 * n) as f64,
            luminance_ratio: la / lb.max(1e-12),
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(w: u32, h: u32, v: f32) -> HdrImage {
        HdrImage { width: w, height: h, pixels: vec![[v, v, v, 1.0]; (w * h) as usize] }
    }

    #[test]
    fn known_values() {
        let a = flat(4, 4, 0.6);
        let b = flat(4, 4, 0.5);
        assert!((rmse(&a, &b).expect("same size") - 0.1).abs() < 1e-6);
        assert!((relmse(&a, &b, 0.01).expect("same size") - 0.01 / 0.26).abs() < 1e-6);
        assert!((luminance_ratio(&a, &b).expect("same size") - 1.2).abs() < 1e-6);
        assert_eq!(rmse(&b, &b), Ok(0.0));
        assert!(rmse(&a, &flat(2, 2, 0.5)).is_err());
        let mut nan = flat(4, 4, 0.5);
        nan.pixels[3][1] = f32::NAN;
        assert_eq!(rmse(&nan, &b), Err(MetricsError::NonFinite("candidate")));
    }

    #[test]
    fn per_object_splits_by_id() {
        let a = HdrImage { width: 3, height: 1, pixels: vec![[1.0; 4], [0.5; 4], [0.0; 4]] };
        let b = HdrImage { width: 3, height: 1, pixels: vec![[1.0; 4], [0.25; 4], [9.0; 4]] };
        let errs = per_object(&a, &b, &[1, 2, 0]).expect("same size");
        assert_eq!(errs.len(), 2, "background skipped");
        assert_eq!(errs[0].rmse, 0.0);
        assert!((errs[1].rmse - 0.25).abs() < 1e-9 && (errs[1].luminance_ratio - 2.0).abs() < 1e-6);
    }
}
