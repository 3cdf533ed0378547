//! The signed error heat map: red where the candidate is too bright, blue where it is too dark,
//! black where it matches. Intensity is the relative luminance error |c - r| / (r + 0.01),
//! saturating at `full_scale` (e.g. 0.5 = 50%).

use super::{MetricsError, check, luminance};
use crate::image_io::HdrImage;

/// RGBA8 heat map of candidate vs reference.
pub fn signed_heatmap(candidate: &HdrImage, reference: &HdrImage, full_scale: f32) -> Result<Vec<u8>, MetricsError> {
    check(candidate, reference)?;
    let scale = full_scale.max(1e-6);
    Ok(candidate
        .pixels
        .iter()
        .zip(&reference.pixels)
        .flat_map(|(a, b)| {
            let (la, lb) = (luminance(a), luminance(b));
            let e = ((la - lb) / (lb + 0.01) / scale).clamp(-1.0, 1.0);
            let v = (e.abs().sqrt() * 255.0 + 0.5) as u8;
            if e >= 0.0 { [v, 0, 0, 255] } else { [0, 0, v, 255] }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn red_means_too_bright() {
        let r = HdrImage { width: 2, height: 1, pixels: vec![[0.5; 4], [0.5; 4]] };
        let c = HdrImage { width: 2, height: 1, pixels: vec![[1.0; 4], [0.1; 4]] };
        let m = signed_heatmap(&c, &r, 0.5).expect("same size");
        assert_eq!(&m[0..4], &[255, 0, 0, 255]);
        assert_eq!(&m[4..8], &[0, 0, 255, 255]);
        assert_eq!(signed_heatmap(&r, &r, 0.5).expect("same size")[0..3], [0, 0, 0]);
    }
}
