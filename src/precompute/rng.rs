//! Deterministic random numbers: PCG32 streams seeded by hashing (seed, pixel, sample), so a
//! render is identical for a given seed whatever the thread scheduling.

/// PCG-XSH-RR 32-bit generator (O'Neill 2014).
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

/// A 64-bit mix (splitmix64 finaliser).
pub fn hash64(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

impl Pcg32 {
    /// A stream for one (seed, pixel, sample) triple.
    pub fn new(seed: u64, pixel: u64, sample: u64) -> Self {
        let s = hash64(seed ^ hash64(pixel.wrapping_add(0x9e37_79b9_7f4a_7c15) ^ hash64(sample)));
        let mut rng = Self { state: 0, inc: (hash64(s ^ 0x5851_f42d_4c95_7f2d) << 1) | 1 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(s);
        rng.next_u32();
        rng
    }

    /// Next 32 random bits.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_uniform() {
        let mut a = Pcg32::new(7, 3, 1);
        let mut b = Pcg32::new(7, 3, 1);
        assert_eq!(a.next_u32(), b.next_u32());
        assert_ne!(Pcg32::new(7, 3, 1).next_u32(), Pcg32::new(7, 4, 1).next_u32());
        let mean = (0..100_000).map(|_| a.next_f32() as f64).sum::<f64>() / 100_000.0;
        assert!((mean - 0.5).abs() < 0.01);
    }
}
