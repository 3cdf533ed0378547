//! Temporal instability: how much a sequence of frames changes from frame to frame where the
//! reference sequence does not, and fails to change where it does. Per pixel and per pair of
//! consecutive frames, |candidate change - reference change|: flicker and noise (changes the
//! reference does not make) and lag (changes it makes that the candidate does not follow) both
//! score positive; a sequence that changes exactly as the reference scores 0.

use super::{MetricsError, check, luminance};
use crate::image_io::HdrImage;

/// The relative spread of a sequence of per-frame values (energies): population standard
/// deviation over mean; 0 for an empty sequence or a mean of 0.
pub fn relative_spread(values: &[f64]) -> f64 {
    let n = values.len() as f64;
    if values.is_empty() {
        return 0.0;
    }
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    if mean > 0.0 { var.sqrt() / mean } else { 0.0 }
}

/// Mean absolute luminance change between consecutive frames.
pub fn mean_frame_change(frames: &[HdrImage]) -> Result<f64, MetricsError> {
    if frames.len() < 2 {
        return Err(MetricsError::Frames(frames.len()));
    }
    let mut total = 0.0;
    for pair in frames.windows(2) {
        check(&pair[1], &pair[0])?;
        let sum: f64 = pair[1]
            .pixels
            .iter()
            .zip(&pair[0].pixels)
            .map(|(a, b)| f64::from((luminance(a) - luminance(b)).abs()))
            .sum();
        total += sum / pair[0].pixels.len().max(1) as f64;
    }
    Ok(total / (frames.len() - 1) as f64)
}

/// Mean over pixels and consecutive frame pairs of |candidate change - reference change| in
/// luminance. A reference shorter than the candidate repeats its last change: two copies of a
/// static frame stand for a static reference.
pub fn temporal_instability(candidate: &[HdrImage], reference: &[HdrImage]) -> Result<f64, MetricsError> {
    if candidate.len() < 2 {
        return Err(MetricsError::Frames(candidate.len()));
    }
    if reference.len() < 2 {
        return Err(MetricsError::Frames(reference.len()));
    }
    let mut total = 0.0;
    for (i, pair) in candidate.windows(2).enumerate() {
        let r = i.min(reference.len() - 2);
        let (r0, r1) = (&reference[r], &reference[r + 1]);
        check(&pair[1], &pair[0])?;
        check(&pair[0], r0)?;
        check(r1, r0)?;
        let sum: f64 = (0..pair[0].pixels.len())
            .map(|k| {
                let dc = luminance(&pair[1].pixels[k]) - luminance(&pair[0].pixels[k]);
                let dr = luminance(&r1.pixels[k]) - luminance(&r0.pixels[k]);
                f64::from((dc - dr).abs())
            })
            .sum();
        total += sum / pair[0].pixels.len().max(1) as f64;
    }
    Ok(total / (candidate.len() - 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_spread_is_the_population_standard_deviation_over_the_mean() {
        assert!((relative_spread(&[0.9, 1.1]) - 0.1).abs() < 1e-12);
        assert_eq!(relative_spread(&[1.0, 1.0, 1.0]), 0.0);
        assert_eq!(relative_spread(&[]), 0.0);
    }

    #[test]
    fn flicker_scores_positive() {
        let f = |v: f32| HdrImage { width: 1, height: 1, pixels: vec![[v, v, v, 1.0]] };
        let steady = vec![f(0.5), f(0.5), f(0.5)];
        let flicker = vec![f(0.4), f(0.6), f(0.4)];
        assert!((temporal_instability(&flicker, &steady).expect("frames") - 0.2).abs() < 1e-6);
        // Lag: the reference steps up and the candidate does not follow.
        let step = vec![f(0.4), f(0.6), f(0.6)];
        let lagging = vec![f(0.4), f(0.4), f(0.6)];
        assert!((temporal_instability(&lagging, &step).expect("frames") - 0.2).abs() < 1e-6);
        assert!(temporal_instability(&step, &step).expect("frames").abs() < 1e-9);
        assert!(mean_frame_change(&steady[..1]).is_err());
    }
}
