//! Steele, Lea and Flood's splitmix64 generator (the seeding generator of Java's
//! `SplittableRandom`): tiny, deterministic, and good enough for the ocean's Gaussian draws and the
//! references' jitter.

pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// `x` hashed to `[0, 1)`: the first draw of the stream it seeds, to 53 bits.
pub(crate) fn hash01(x: u64) -> f64 {
    (SplitMix64(x).next() >> 11) as f64 / (1u64 << 53) as f64
}
