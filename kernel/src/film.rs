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

/// The filter's density at offset `x` (pixels) from a pixel centre, as `sample_position` draws it:
/// piecewise constant over the tabulated bins, zero outside the radius.
fn filter_density(tables: &[f32], params: &FrameParams, x: f32) -> f32 {
    let r = params.filter_radius;
    if !(x > -r && x < r) {
        return 0.0;
    }
    let bins = params.filter_bins;
    let i = (((x + r) / (2.0 * r) * bins as f32) as u32).min(bins - 1);
    let base = params.filter_cdf_offset;
    let prev = if i == 0 { 0.0 } else { tables[(base + i - 1) as usize] };
    (tables[(base + i) as usize] - prev) * bins as f32 / (2.0 * r)
}

/// The filter's mass inside the image along one axis for a pixel centred at `c` in an image `full`
/// pixels wide: what `sample_position` renormalises the truncated filter by.
fn axis_mass(tables: &[f32], params: &FrameParams, c: f32, full: f32) -> f32 {
    let r = params.filter_radius;
    filter_cdf_at(tables, params, (full - c).min(r)) - filter_cdf_at(tables, params, (-c).max(-r))
}

/// The density (per unit of pixel area) with which camera samples of pixel (`px`, `py`) of the full
/// image land at film position `pos` (in pixels of the full image): the reconstruction filter centred
/// on the pixel, truncated to the image and renormalised, exactly as `sample_position` draws it. Light
/// tracing splats a connection into each pixel with this weight, so both estimate the same filtered
/// pixel; IBPT's MIS compares the two strategies through it.
pub fn pixel_density(tables: &[f32], params: &FrameParams, pos: Vec2, px: u32, py: u32) -> f32 {
    let (cx, cy) = (px as f32 + 0.5, py as f32 + 0.5);
    let fx = filter_density(tables, params, pos.x - cx);
    let fy = filter_density(tables, params, pos.y - cy);
    if fx <= 0.0 || fy <= 0.0 {
        return 0.0;
    }
    let mass = axis_mass(tables, params, cx, params.full_width as f32)
        * axis_mass(tables, params, cy, params.full_height as f32);
    if mass > 0.0 {
        fx * fy / mass
    } else {
        0.0
    }
}
