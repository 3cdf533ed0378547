//! Hierarchical warping (Clarberg et al. 2005, as used in Knecht 2009 section 3.3): a uniform
//! point descends an importance mip pyramid from the 2x2 level to the finest, splitting its
//! interval first vertically by row sums, then horizontally within the chosen row. The result
//! lies in one finest texel, chosen with probability importance(texel) / total.

/// A square importance map with its sum pyramid (level 0 = 1x1 total, level K = finest).
#[derive(Clone, Debug)]
pub struct ImportancePyramid {
    /// `levels[l]` is 2^l x 2^l, row-major; each texel is the sum of its four children.
    pub levels: Vec<Vec<f64>>,
}

/// A warped sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Warped {
    /// Position in [0, 1)^2 (texture coordinates of the finest level).
    pub uv: [f64; 2],
    /// The finest texel it landed in.
    pub texel: [usize; 2],
    /// Probability of that texel: importance / total (uniform when the map is all zero).
    pub pdf: f64,
}

impl ImportancePyramid {
    /// Builds the pyramid of a `size` x `size` map (`size` a power of two); negative and
    /// non-finite values count as zero.
    pub fn new(finest: &[f64], size: usize) -> Option<Self> {
        if !size.is_power_of_two() || finest.len() != size * size {
            return None;
        }
        let mut levels = vec![finest.iter().map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 }).collect::<Vec<_>>()];
        let mut s = size;
        while s > 1 {
            let fine = levels.last()?;
            let h = s / 2;
            let coarse = (0..h * h)
                .map(|i| {
                    let (x, y) = (2 * (i % h), 2 * (i / h));
                    fine[y * s + x] + fine[y * s + x + 1] + fine[(y + 1) * s + x] + fine[(y + 1) * s + x + 1]
                })
                .collect();
            levels.push(coarse);
            s = h;
        }
        levels.reverse();
        Some(Self { levels })
    }

    /// Side of the finest level.
    pub fn size(&self) -> usize {
        1 << (self.levels.len() - 1)
    }

    /// Warps a uniform sample in [0, 1)^2 (mirrors the WGSL `warp`; zero cells split evenly).
    pub fn warp(&self, s: [f64; 2]) -> Warped {
        let (mut x, mut y) = (s[0].clamp(0.0, 1.0 - 1e-12), s[1].clamp(0.0, 1.0 - 1e-12));
        let (mut lo, mut hi) = ([0.0f64, 0.0], [1.0f64, 1.0]);
        let mut cell = [0usize, 0];
        for l in 1..self.levels.len() {
            let size = 1 << l;
            let at = |cx: usize, cy: usize| self.levels[l][cy * size + cx];
            let c = [cell[0] * 2, cell[1] * 2];
            let (q00, q10, q01, q11) = (at(c[0], c[1]), at(c[0] + 1, c[1]), at(c[0], c[1] + 1), at(c[0] + 1, c[1] + 1));
            let sum = q00 + q10 + q01 + q11;
            let p_row0 = if sum > 0.0 { (q00 + q10) / sum } else { 0.5 };
            let mid = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
            let t = (y - lo[1]) / (hi[1] - lo[1]);
            let dy;
            let t = if t < p_row0 {
                hi[1] = mid[1];
                dy = 0;
                t / p_row0
            } else {
                lo[1] = mid[1];
                dy = 1;
                (t - p_row0) / (1.0 - p_row0)
            };
            y = lo[1] + t * (hi[1] - lo[1]);
            let (a, b) = if dy == 0 { (q00, q10) } else { (q01, q11) };
            let p_col0 = if a + b > 0.0 { a / (a + b) } else { 0.5 };
            let u = (x - lo[0]) / (hi[0] - lo[0]);
            let dx;
            let u = if u < p_col0 {
                hi[0] = mid[0];
                dx = 0;
                u / p_col0
            } else {
                lo[0] = mid[0];
                dx = 1;
                (u - p_col0) / (1.0 - p_col0)
            };
            x = lo[0] + u * (hi[0] - lo[0]);
            cell = [c[0] + dx, c[1] + dy];
        }
        let size = self.size();
        let total = self.levels[0][0];
        let pdf = if total > 0.0 {
            self.levels[self.levels.len() - 1][cell[1] * size + cell[0]] / total
        } else {
            1.0 / (size * size) as f64
        };
        Warped { uv: [x, y], texel: cell, pdf }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::ism::halton::sample_set;

    #[test]
    fn samples_follow_the_importance() {
        let size = 8;
        let map: Vec<f64> =
            (0..size * size).map(|i| ((i % size) + 2 * (i / size)) as f64 + if i == 9 { 40.0 } else { 0.0 }).collect();
        let pyr = ImportancePyramid::new(&map, size).expect("power of two");
        let total: f64 = map.iter().sum();
        let n = 64 * 1024;
        let mut hist = vec![0usize; size * size];
        for s in sample_set(n, 0) {
            let w = pyr.warp([f64::from(s[0]), f64::from(s[1])]);
            let i = w.texel[1] * size + w.texel[0];
            hist[i] += 1;
            assert!((w.pdf - map[i] / total).abs() < 1e-12, "pdf is the texel's share");
            let (tx, ty) = ((w.uv[0] * size as f64) as usize, (w.uv[1] * size as f64) as usize);
            assert_eq!([tx, ty], w.texel, "the warped point lies in its texel");
        }
        for (i, &h) in hist.iter().enumerate() {
            let want = n as f64 * map[i] / total;
            assert!((h as f64 - want).abs() <= 2.0 + 0.01 * want, "texel {i}: {h} samples, want {want:.1}");
        }
    }

    #[test]
    fn zero_cells_are_never_chosen_and_empty_maps_are_uniform() {
        let mut map = vec![1.0; 16];
        map[5] = 0.0;
        let pyr = ImportancePyramid::new(&map, 4).expect("pyramid");
        assert!(sample_set(4096, 2).iter().all(|s| pyr.warp([f64::from(s[0]), f64::from(s[1])]).texel != [1, 1]));
        let empty = ImportancePyramid::new(&[0.0; 16], 4).expect("pyramid");
        assert!((empty.warp([0.3, 0.7]).pdf - 1.0 / 16.0).abs() < 1e-12);
        assert!(ImportancePyramid::new(&[1.0; 12], 3).is_none());
    }
}
