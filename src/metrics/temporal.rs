//! Temporal instability: how much a sequence of frames of a static camera changes from frame to
//! frame, compared with the reference sequence (which changes only where the lighting really
//! changes). Flicker, noise and lag show up as a positive score.

use super::{MetricsError, check, luminance};
use crate::image_io::HdrImage;

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

/// Mean frame-to-frame change of the candidate minus that of the reference sequence.
pub fn temporal_instability(candidate: &[HdrImage], reference: &[HdrImage]) -> Result<f64, MetricsError> {
    Ok(mean_frame_change(candidate)? - mean_frame_change(reference)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flicker_scores_positive() {
        let f = |v: f32| HdrImage { width: 1, height: 1, pixels: vec![[v, v, v, 1.0]] };
        let steady = vec![f(0.5), f(0.5), f(0.5)];
        let flicker = vec![f(0.4), f(0.6), f(0.4)];
        assert!((temporal_instability(&flicker, &steady).expect("frames") - 0.2).abs() < 1e-6);
        assert!(mean_frame_change(&steady[..1]).is_err());
    }
}
