//! The reference path tracer's random numbers: an Owen-scrambled Sobol sequence per pixel,
//! padded by shuffling (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)).
//!
//! Independent random numbers leave a pixel's samples clumped; a low-discrepancy sequence
//! spreads each decision of a path (the jitter in the pixel, the light sample, the bounce
//! direction) evenly over the pixel's samples, so the error falls faster than 1/sqrt(spp)
//! where the integrand is smooth. Each decision takes a *pattern* of up to four dimensions: the
//! first four Sobol dimensions of a sample index shuffled per (pixel, pattern) by a nested
//! uniform scramble, each dimension then Owen-scrambled by its own hash. Patterns are
//! independent of each other, so a path may take as many as it likes, and every sample stays
//! unbiased (an Owen-scrambled point is uniform on its own). Deterministic for (seed, pixel,
//! sample), whatever the thread scheduling.

use super::rng::{Pcg32, hash64};

/// The four Sobol dimensions' direction numbers, most significant bit first (Joe & Kuo 2008's
/// primitive polynomials for dimensions 2-4: x+1, x^2+x+1, x^3+x+1).
const DIRECTIONS: [[u32; 32]; 4] =
    [van_der_corput(), directions(1, 0, &[1]), directions(2, 1, &[1, 3]), directions(3, 1, &[1, 3, 1])];

const fn van_der_corput() -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        v[k] = 1 << (31 - k);
        k += 1;
    }
    v
}

/// Direction numbers of a dimension with a primitive polynomial of degree `s`, inner
/// coefficients `a` and initial numbers `m` (Bratley & Fox's recurrence).
const fn directions(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        if k < s {
            v[k] = m[k] << (31 - k);
        } else {
            let mut x = v[k - s] ^ (v[k - s] >> s);
            let mut j = 1;
            while j < s {
                if (a >> (s - 1 - j)) & 1 == 1 {
                    x ^= v[k - j];
                }
                j += 1;
            }
            v[k] = x;
        }
        k += 1;
    }
    v
}

/// Each dimension's Sobol matrix applied to every value of each byte of an index: a point is
/// the XOR of four lookups instead of up to 32 steps (a shuffled index has all 32 bits in use).
const BYTE_TABLES: [[[u32; 256]; 4]; 4] = byte_tables();

const fn byte_tables() -> [[[u32; 256]; 4]; 4] {
    let mut t = [[[0u32; 256]; 4]; 4];
    let mut d = 0;
    while d < 4 {
        let mut byte = 0;
        while byte < 4 {
            let mut value = 0;
            while value < 256 {
                let mut x = 0;
                let mut bit = 0;
                while bit < 8 {
                    if (value >> bit) & 1 == 1 {
                        x ^= DIRECTIONS[d][8 * byte + bit];
                    }
                    bit += 1;
                }
                t[d][byte][value] = x;
                value += 1;
            }
            byte += 1;
        }
        d += 1;
    }
    t
}

/// Dimension `dim` (0-3) of Sobol point `index`, as 32 fixed-point bits.
fn sobol(index: u32, dim: usize) -> u32 {
    let t = &BYTE_TABLES[dim];
    let [b0, b1, b2, b3] = index.to_le_bytes();
    t[0][usize::from(b0)] ^ t[1][usize::from(b1)] ^ t[2][usize::from(b2)] ^ t[3][usize::from(b3)]
}

/// [`sobol`] the long way, bit by bit (the tables' twin in the tests).
#[cfg(test)]
fn sobol_bitwise(index: u32, dim: usize) -> u32 {
    (0..32).filter(|bit| (index >> bit) & 1 == 1).fold(0, |x, bit| x ^ DIRECTIONS[dim][bit])
}

/// A hash in which each output bit depends only on the same and less significant input bits,
/// so applied to bit-reversed numbers it is a nested uniform (Owen) scramble (Vegdahl's
/// improvement of Laine & Karras's hash).
fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3d20_adea);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6c56);
    x ^= x.wrapping_mul(0x53a2_2864);
    x
}

/// Owen-scrambles the 32 fixed-point bits of `x` with `seed`.
fn owen(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

fn to_unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The random numbers of one path: its pixel's Owen-scrambled Sobol sequence at one sample index.
#[derive(Clone, Debug)]
pub struct PathSampler {
    pixel_seed: u64,
    index: u32,
    pattern: u32,
}

impl PathSampler {
    /// The numbers of sample `sample` of pixel `pixel` of a render with seed `seed`.
    pub fn new(seed: u64, pixel: u64, sample: u32) -> Self {
        Self { pixel_seed: hash64(seed ^ hash64(pixel.wrapping_add(0x2545_f491_4f6c_dd1d))), index: sample, pattern: 0 }
    }

    /// The next pattern's first `N` (at most 4) dimensions, each uniform in [0, 1).
    fn next<const N: usize>(&mut self) -> [f32; N] {
        let h = hash64(self.pixel_seed ^ u64::from(self.pattern));
        self.pattern += 1;
        let index = owen(self.index, h as u32);
        // The dimensions' scramble seeds: the halves of one more hash, then h's upper half.
        let g = hash64(h ^ 0x9e37_79b9_7f4a_7c15);
        let seeds = [g as u32, (g >> 32) as u32, (h >> 32) as u32, hash64(g) as u32];
        std::array::from_fn(|d| to_unit(owen(sobol(index, d), seeds[d])))
    }
}

/// What a path draws its decisions from: the tracer's low-discrepancy [`PathSampler`] (whose
/// 2D draws are spread jointly over a pixel's samples), or a plain random stream (probes that
/// trace many paths from one point). Every number is uniform in [0, 1).
pub trait Sampler {
    /// One number.
    fn next_1d(&mut self) -> f32;
    /// Two numbers (a 2D decision: a direction, a point).
    fn next_2d(&mut self) -> (f32, f32);
    /// Three numbers: put a 2D decision on the first two, a discrete choice on the third.
    fn next_3d(&mut self) -> [f32; 3];
}

impl Sampler for PathSampler {
    fn next_1d(&mut self) -> f32 {
        self.next::<1>()[0]
    }

    fn next_2d(&mut self) -> (f32, f32) {
        let [a, b] = self.next::<2>();
        (a, b)
    }

    fn next_3d(&mut self) -> [f32; 3] {
        self.next::<3>()
    }
}

impl Sampler for Pcg32 {
    fn next_1d(&mut self) -> f32 {
        self.next_f32()
    }

    fn next_2d(&mut self) -> (f32, f32) {
        (self.next_f32(), self.next_f32())
    }

    fn next_3d(&mut self) -> [f32; 3] {
        [self.next_f32(), self.next_f32(), self.next_f32()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sobol_dimensions_match_the_published_sequence() {
        // SciPy's unscrambled `qmc.Sobol(d=4)` (Joe & Kuo's numbers, Gray-code order: its
        // point i is our point i ^ (i >> 1)), first 16 points in sixteenths.
        let expect: [[u32; 16]; 4] = [
            [0, 8, 12, 4, 6, 14, 10, 2, 3, 11, 15, 7, 5, 13, 9, 1],
            [0, 8, 4, 12, 6, 14, 2, 10, 5, 13, 1, 9, 3, 11, 7, 15],
            [0, 8, 4, 12, 10, 2, 14, 6, 15, 7, 11, 3, 5, 13, 1, 9],
            [0, 8, 4, 12, 14, 6, 10, 2, 7, 15, 3, 11, 9, 1, 13, 5],
        ];
        for (d, row) in expect.iter().enumerate() {
            let got: Vec<u32> = (0..16u32).map(|i| sobol(i ^ (i >> 1), d) >> 28).collect();
            assert_eq!(got, row, "dimension {d}");
        }
    }

    #[test]
    fn byte_tables_give_the_bitwise_points() {
        let mut rng = Pcg32::new(5, 6, 7);
        for _ in 0..10_000 {
            let i = rng.next_u32();
            for d in 0..4 {
                assert_eq!(sobol(i, d), sobol_bitwise(i, d), "index {i}, dimension {d}");
            }
        }
    }

    /// Each of a pixel's first 2^k samples falls in its own cell of every 2^k-cell elementary
    /// interval grid (a (0, 2)-net), for every pattern: the property that makes the error fall
    /// faster than independent samples'.
    #[test]
    fn every_pattern_is_a_stratified_net_over_a_pixels_samples() {
        let n = 64u32;
        for pattern in 0..5 {
            let points: Vec<(f32, f32)> = (0..n)
                .map(|i| {
                    let mut s = PathSampler::new(9, 1234, i);
                    for _ in 0..pattern {
                        s.next_2d();
                    }
                    s.next_2d()
                })
                .collect();
            for log_x in 0..=6 {
                let (nx, ny) = (1u32 << log_x, n >> log_x);
                let mut cells = vec![0u32; n as usize];
                for &(x, y) in &points {
                    let (cx, cy) = ((x * nx as f32) as u32, (y * ny as f32) as u32);
                    cells[(cy * nx + cx) as usize] += 1;
                }
                assert!(cells.iter().all(|&c| c == 1), "pattern {pattern}, {nx}x{ny} cells: {cells:?}");
            }
        }
    }

    /// Different pixels and different patterns of one path are scrambled apart: their first
    /// sample differs, and a dimension's mean over many pixels is a half.
    #[test]
    fn pixels_and_patterns_are_decorrelated() {
        let mut a = PathSampler::new(1, 10, 0);
        let mut b = PathSampler::new(1, 11, 0);
        let (a0, a1) = (a.next_2d(), a.next_2d());
        assert_ne!(a0, b.next_2d());
        assert_ne!(a0, a1);
        let mean = (0..20_000u64).map(|p| f64::from(PathSampler::new(3, p, 0).next_1d())).sum::<f64>() / 20_000.0;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
    }
}
