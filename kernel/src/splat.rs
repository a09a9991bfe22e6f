//! Splatting: adding a light path's contribution to an arbitrary pixel from any thread, so that one
//! seed gives one image on every backend, run after run.
//!
//! Each channel is a 64-bit signed (two's complement) fixed-point sum with `SPLAT_FRACTION_BITS`
//! fractional bits, kept as two `u32` words (low, high) and added with 32-bit integer atomics only
//! (core SPIR-V; no 64-bit or float atomics needed). Integer sums do not depend on the order of the
//! additions, unlike float atomics. Values are rounded stochastically with the path's own random
//! number, so the rounding is unbiased. Resolution 2⁻²⁴ ≈ 6e-8 per splat; range ±2³⁹ ≈ ±5.5e11 per
//! pixel and pass (the sums are folded into the float accumulator and cleared after every pass).
//! Signed because a path that carries a wavelength has signed colour weights (`wavelength`).
//! Non-finite or out-of-range contributions are never added: they are counted in the pixel's
//! `invalid` word. After each pass `resolved` folds the words into the pixel's float accumulator and
//! the words are cleared.

use crate::layout::PixelAccum;
use crate::math::is_finite3;
use crate::spectrum::Rgb;

/// `u32` words per pixel: (low, high) for R, G, B, then the invalid count and one spare.
pub const SPLAT_STRIDE: u32 = 8;
pub const SPLAT_INVALID: u32 = 6;
/// Fractional bits of the fixed-point sums.
pub const SPLAT_FRACTION_BITS: u32 = 24;
const SCALE: f32 = (1u32 << SPLAT_FRACTION_BITS) as f32;
const TWO_32: f32 = 4_294_967_296.0;
/// The largest magnitude one splat may add (2³⁹: the top of the signed range).
pub const SPLAT_MAX: f32 = 1_099_511_627_776.0 / 2.0;

/// A buffer of `u32` words with an atomic add and exchange, implemented by each backend, and plain
/// reads and writes of words that one invocation alone touches in a dispatch (the camera cells of
/// `film_splat`, which their owner writes and `resolve` reads after it).
pub trait AtomicWords {
    /// Adds `value` to word `index` and returns the word's previous value.
    fn fetch_add(&mut self, index: u32, value: u32) -> u32;
    /// Writes `value` to word `index` and returns the word's previous value.
    fn exchange(&mut self, index: u32, value: u32) -> u32;
    /// Word `index`, read by the one invocation that writes it in this dispatch (or after it).
    fn load(&self, index: u32) -> u32;
    /// Writes word `index`, which no other invocation touches in this dispatch.
    fn store(&mut self, index: u32, value: u32);
}

/// The GPU's storage buffer of splat words.
#[cfg(target_arch = "spirv")]
pub struct GpuWords<'a>(pub &'a mut [u32]);

#[cfg(target_arch = "spirv")]
impl AtomicWords for GpuWords<'_> {
    #[inline]
    fn fetch_add(&mut self, index: u32, value: u32) -> u32 {
        use spirv_std::memory::{Scope, Semantics};
        // Queue-family scope: device scope needs a capability (VulkanMemoryModelDeviceScope) that naga
        // does not take; for one dispatch on one device the two are the same.
        // SAFETY: an atomic add on a word of a storage buffer; relaxed ordering suffices because the
        // sums are read only after the dispatch has completed.
        unsafe {
            spirv_std::arch::atomic_i_add::<u32, { Scope::QueueFamily as u32 }, { Semantics::NONE.bits() }>(
                &mut self.0[index as usize],
                value,
            )
        }
    }

    #[inline]
    fn exchange(&mut self, index: u32, value: u32) -> u32 {
        use spirv_std::memory::{Scope, Semantics};
        // SAFETY: as `fetch_add`: an atomic exchange on a word of a storage buffer, read only after
        // the dispatch has completed.
        unsafe {
            spirv_std::arch::atomic_exchange::<u32, { Scope::QueueFamily as u32 }, { Semantics::NONE.bits() }>(
                &mut self.0[index as usize],
                value,
            )
        }
    }

    #[inline]
    fn load(&self, index: u32) -> u32 {
        self.0[index as usize]
    }

    #[inline]
    fn store(&mut self, index: u32, value: u32) {
        self.0[index as usize] = value;
    }
}

/// Words owned by one thread, added without atomics: for tests on the CPU.
#[cfg(not(target_arch = "spirv"))]
pub struct OwnWords<'a>(pub &'a mut [u32]);

#[cfg(not(target_arch = "spirv"))]
impl AtomicWords for OwnWords<'_> {
    fn fetch_add(&mut self, index: u32, value: u32) -> u32 {
        let old = self.0[index as usize];
        self.0[index as usize] = old.wrapping_add(value);
        old
    }

    fn exchange(&mut self, index: u32, value: u32) -> u32 {
        core::mem::replace(&mut self.0[index as usize], value)
    }

    fn load(&self, index: u32) -> u32 {
        self.0[index as usize]
    }

    fn store(&mut self, index: u32, value: u32) {
        self.0[index as usize] = value;
    }
}

/// One channel's value (finite, `|value| < SPLAT_MAX`) as the words to add to its sum, (low, high): the
/// magnitude rounded to fixed point, a negative value as its 64-bit two's complement (the high word
/// wraps on purpose; the sum is read back as signed).
#[inline]
fn fixed_words(value: f32, u: f32) -> (u32, u32) {
    let scaled = value.abs() * SCALE;
    // Both quantities are non-negative (and the first below 2³¹), so truncation is their floor: a cast
    // instead of `floor`, which on baseline x86-64 is a call into libm (`floorf`: 6.6% of a `bdpt`
    // render of the Cornell box on the CPU, `perf`, six calls a splatted pixel). The same numbers.
    let mut high_f = ((scaled / TWO_32) as u32) as f32;
    let rest = scaled - high_f * TWO_32 + u;
    let mut low = 0u32;
    if rest >= TWO_32 {
        high_f += 1.0;
    } else {
        low = rest as u32;
    }
    let high = high_f as u32;
    if value < 0.0 {
        negated(low, high)
    } else {
        (low, high)
    }
}

/// Adds one channel's high word at `base + 1`, with the carry out of the add of `low` to its low word
/// (whose value before that add was `old`).
#[inline]
fn add_high<W: AtomicWords>(words: &mut W, base: u32, (low, high): (u32, u32), old: u32) {
    let high = if old > u32::MAX - low { high.wrapping_add(1) } else { high };
    if high != 0 {
        words.fetch_add(base + 1, high);
    }
}

/// The two's complement of the 64-bit number (`low`, `high`).
#[inline]
fn negated(low: u32, high: u32) -> (u32, u32) {
    let low_neg = (!low).wrapping_add(1);
    let high_neg = if low == 0 { (!high).wrapping_add(1) } else { !high };
    (low_neg, high_neg)
}

/// Adds `value` to `pixel`'s sums; `u` ∈ [0, 1) rounds stochastically.
pub fn splat<W: AtomicWords>(words: &mut W, pixel: u32, value: Rgb, u: f32) {
    let base = pixel * SPLAT_STRIDE;
    let valid = is_finite3(value) && value.abs().max_element() < SPLAT_MAX;
    if !valid {
        words.fetch_add(base + SPLAT_INVALID, 1);
        return;
    }
    let (r, g, b) = (fixed_words(value.x, u), fixed_words(value.y, u), fixed_words(value.z, u));
    // The three low words first, then the carries that their old values give: the GPU waits for
    // the three atomics' results together, where adding each channel's words in turn waited for
    // one atomic's round trip before the next channel's could start. (Adding a zero changes no sum.)
    let old_r = words.fetch_add(base, r.0);
    let old_g = words.fetch_add(base + 2, g.0);
    let old_b = words.fetch_add(base + 4, b.0);
    add_high(words, base, r, old_r);
    add_high(words, base + 2, g, old_g);
    add_high(words, base + 4, b, old_b);
}

/// Counts an invalid (non-finite) estimate at `pixel` without adding anything.
pub fn count_invalid<W: AtomicWords>(words: &mut W, pixel: u32) {
    words.fetch_add(pixel * SPLAT_STRIDE + SPLAT_INVALID, 1);
}

/// The value of one channel's (low, high) words, a signed 64-bit fixed-point number. A negative sum
/// is negated before the conversion so that small magnitudes keep their precision.
#[inline]
fn fixed_to_f32(low: u32, high: u32) -> f32 {
    if high & 0x8000_0000 != 0 {
        let (l, h) = negated(low, high);
        -(h as f32 * (TWO_32 / SCALE) + l as f32 / SCALE)
    } else {
        high as f32 * (TWO_32 / SCALE) + low as f32 / SCALE
    }
}

/// A pixel's accumulator with one pass of `sample_count` samples per pixel added from its splat
/// words: the pass's sum `S` to `sum`, `(qS)²/k` to `sum_sq` (`q`: `layout::square_scale`; the host
/// estimates the variance from these batch means), `k` to `count`, and the invalid count. Both
/// backends resolve with this, the GPU in its `resolve` entry point without reading the words back.
#[inline]
pub fn resolved(a: PixelAccum, w: [u32; SPLAT_STRIDE as usize], sample_count: u32, q: f32) -> PixelAccum {
    resolved_with(a, w, Rgb::ZERO, sample_count, q)
}

/// `resolved`, with `extra` (the pass's camera cells gathered for this pixel: `film_splat`) added to
/// the pass's sum.
#[inline]
pub fn resolved_with(
    a: PixelAccum,
    w: [u32; SPLAT_STRIDE as usize],
    extra: Rgb,
    sample_count: u32,
    q: f32,
) -> PixelAccum {
    let k = sample_count as f32;
    let s = [
        fixed_to_f32(w[0], w[1]) + extra.x,
        fixed_to_f32(w[2], w[3]) + extra.y,
        fixed_to_f32(w[4], w[5]) + extra.z,
    ];
    let sq = [s[0] * q, s[1] * q, s[2] * q];
    PixelAccum {
        sum: [a.sum[0] + s[0], a.sum[1] + s[1], a.sum[2] + s[2]],
        count: a.count + k,
        sum_sq: [
            a.sum_sq[0] + sq[0] * sq[0] / k,
            a.sum_sq[1] + sq[1] * sq[1] / k,
            a.sum_sq[2] + sq[2] * sq[2] / k,
        ],
        invalid: a.invalid + w[SPLAT_INVALID as usize] as f32,
    }
}
