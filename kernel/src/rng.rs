//! Counter-based random numbers.
//!
//! Every random number is a pure function of (seed, pixel, sample index, dimension), so the CPU and
//! GPU backends draw identical samples, any sample of any pixel can be recomputed in isolation (which
//! progressive rendering, checkpointing and splitting work across devices rely on), and no generator
//! state has to be stored between dispatches.

/// A 32-bit integer finalizer with low bias ("lowbias32", C. Wellons' hash prospector).
#[inline]
pub fn hash_u32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Hashes two words into one; not symmetric, so (a, b) and (b, a) differ.
#[inline]
pub fn hash2(a: u32, b: u32) -> u32 {
    hash_u32(a ^ hash_u32(b.wrapping_add(0x9e37_79b9)))
}

/// Maps 32 random bits to a float in [0, 1) using the top 24 bits (exactly representable).
#[inline]
pub fn u32_to_unit_f32(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The random stream of one path: the key identifies (seed, pixel, sample), `dim` counts draws.
#[derive(Clone, Copy)]
pub struct Sampler {
    key: u32,
    dim: u32,
}

impl Sampler {
    pub fn new(seed: u32, pixel: u32, sample_index: u32) -> Self {
        let key = hash2(hash2(seed, pixel), sample_index);
        Sampler { key, dim: 0 }
    }

    /// Jumps to a fixed dimension, so that e.g. bounce `k` always uses the same dimensions whatever
    /// the earlier bounces consumed.
    #[inline]
    pub fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }

    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let r = hash2(self.key, self.dim);
        self.dim += 1;
        u32_to_unit_f32(r)
    }

    #[inline]
    pub fn next_2d(&mut self) -> crate::glam::Vec2 {
        let a = self.next_1d();
        let b = self.next_1d();
        crate::glam::Vec2::new(a, b)
    }
}
