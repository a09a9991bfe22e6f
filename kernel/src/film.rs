//! Film sampling: where in the image a camera sample lands. (The host's `film` module is the other
//! end: it develops the accumulated sums into an image and writes files.)
//!
//! Reconstruction filters are applied by filter importance sampling: each sample's offset from the
//! pixel centre is drawn from the (separable) filter itself, so every sample has weight 1 and no
//! splatting to neighbours is needed. In expectation this is the image Mitsuba's `hdrfilm` develops
//! (sum of w·L over sum of w), including at the border, where Mitsuba only draws samples inside the
//! image: the filter is truncated to the image there. The filter comes as a tabulated CDF over
//! `[-radius, radius]` so that every filter shares one code path.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::Vec2;
use crate::layout::{FrameParams, SAMPLER_STRATIFIED};
use crate::rng::Sampler;
use crate::sampling::sample_cdf;

/// The filter's CDF at `x` (piecewise linear between the tabulated bin edges).
fn filter_cdf_at(tables: &[f32], params: &FrameParams, x: f32) -> f32 {
    let bins = params.filter_bins;
    let r = params.filter_radius;
    let t = ((x + r) / (2.0 * r) * bins as f32).clamp(0.0, bins as f32);
    let i = (t as u32).min(bins - 1);
    let frac = t - i as f32;
    let base = params.filter_cdf_offset;
    let prev = if i == 0 { 0.0 } else { tables[(base + i - 1) as usize] };
    prev + frac * (tables[(base + i) as usize] - prev)
}

/// An offset from the pixel centre distributed as the filter truncated to `[lo, hi]`.
fn sample_filter_1d(tables: &[f32], params: &FrameParams, u: f32, lo: f32, hi: f32) -> f32 {
    let c_lo = filter_cdf_at(tables, params, lo);
    let c_hi = filter_cdf_at(tables, params, hi);
    let target = c_lo + u * (c_hi - c_lo);
    let s = sample_cdf(tables, params.filter_cdf_offset, params.filter_bins, target);
    let r = params.filter_radius;
    let x = -r + (s.index as f32 + s.remapped) * (2.0 * r / params.filter_bins as f32);
    x.clamp(lo, hi)
}

/// The primary sample of the pixel: stratified over `floor(√spp)²` strata when the stratified sampler is
/// chosen (later samples beyond the last full set of strata are independent).
fn pixel_sample(params: &FrameParams, sample_index: u32, sampler: &mut Sampler) -> Vec2 {
    let u = sampler.next_2d();
    if params.sampler != SAMPLER_STRATIFIED {
        return u;
    }
    let n = (params.spp_total as f32).sqrt() as u32;
    if n <= 1 || sample_index >= n * n {
        return u;
    }
    let sx = sample_index % n;
    let sy = sample_index / n;
    Vec2::new((sx as f32 + u.x) / n as f32, (sy as f32 + u.y) / n as f32)
}

/// Film position (fractions of width and height) of sample `sample_index` in pixel (px, py).
pub fn sample_position(
    params: &FrameParams,
    tables: &[f32],
    px: u32,
    py: u32,
    sample_index: u32,
    sampler: &mut Sampler,
) -> Vec2 {
    let u = pixel_sample(params, sample_index, sampler);
    let r = params.filter_radius;
    // Pixel centre in the full image (the rendered pixels may be a crop of it).
    let cx = (params.crop_x + px) as f32 + 0.5;
    let cy = (params.crop_y + py) as f32 + 0.5;
    let (full_w, full_h) = (params.full_width as f32, params.full_height as f32);
    let dx = sample_filter_1d(tables, params, u.x, (-cx).max(-r), (full_w - cx).min(r));
    let dy = sample_filter_1d(tables, params, u.y, (-cy).max(-r), (full_h - cy).min(r));
    Vec2::new((cx + dx) / full_w, (cy + dy) / full_h)
}
