//! Halton points (bases 2 and 3) in [0, 1)^2. The window advances by N every frame so that
//! consecutive frames use different VPLs and the temporal blend integrates them (pass P4 of
//! docs/ARCHITECTURE.md, "ISM pass labels"; Knecht 2009 §3.3 does not say whether the window
//! moves).

/// Radical inverse of `i` in `base`.
pub fn radical_inverse(mut i: u64, base: u64) -> f64 {
    let inv = 1.0 / base as f64;
    let (mut f, mut r) = (inv, 0.0);
    while i > 0 {
        r += f * (i % base) as f64;
        i /= base;
        f *= inv;
    }
    r
}

/// The `n` points of frame `frame`: Halton indices `frame * n + 1 ..= frame * n + n`.
pub fn sample_set(n: usize, frame: u64) -> Vec<[f32; 2]> {
    let start = frame * n as u64 + 1;
    (0..n as u64).map(|k| [radical_inverse(start + k, 2) as f32, radical_inverse(start + k, 3) as f32]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_and_frame_shift() {
        assert_eq!(radical_inverse(1, 2), 0.5);
        assert_eq!(radical_inverse(3, 2), 0.75);
        assert!((radical_inverse(4, 3) - 4.0 / 9.0).abs() < 1e-12);
        let a = sample_set(16, 0);
        let b = sample_set(16, 1);
        assert_ne!(a, b, "a new window each frame");
        // Low discrepancy: each quarter of the square gets exactly N/4 of 256 points.
        let pts = sample_set(256, 3);
        for q in 0..4 {
            let (x0, y0) = ((q % 2) as f32 * 0.5, (q / 2) as f32 * 0.5);
            let c = pts.iter().filter(|p| p[0] >= x0 && p[0] < x0 + 0.5 && p[1] >= y0 && p[1] < y0 + 0.5).count();
            assert!((60..=68).contains(&c), "quadrant {q}: {c}");
        }
    }
}
