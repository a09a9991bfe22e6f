//! Film sampling: where in the image a camera sample lands. (The host's `film` module is the other
//! end: it develops the accumulated sums into an image and writes files.)
//!
//! Camera samples reach the film in one of two ways (`FrameParams::film_reach`). The default splats
//! each sample, drawn uniformly in its pixel (`sample_position`), into every pixel its filter covers
//! (`film_splat`), as Mitsuba's `hdrfilm` does: one sample serves several pixels, and negative lobes
//! cancel in the ratio of sums instead of adding noise. The other, kept for uncorrelated noise (a
//! denoiser's input) and for light tracing's MIS, is filter importance sampling (`sample_position` too):
//! each sample's offset from the pixel centre is drawn from the (separable) filter itself and the
//! sample goes to its own pixel alone. Measured on the Cornell box with the default gaussian filter,
//! its MSE at equal samples was 7x the splatting film's (BENCHMARKS.md, "The film").
//! In expectation this is the image Mitsuba's `hdrfilm` develops (sum of w·L over sum of w),
//! including at the border, where Mitsuba only draws samples inside the rendered window (the image,
//! or its crop window): the filter is truncated to that window there, as the splatting film's
//! samples are. The filter comes as a tabulated CDF over `[-radius, radius]` so
//! that every filter shares one code path.
//!
//! Filters with negative lobes (`mitchell`, `lanczos`) are sampled in proportion to |w|, and each
//! sample carries the weight sign(w)·∫|w|/∫w (both integrals over the truncated filter), so that its
//! expectation is ∫w·L/∫w as Mitsuba's ratio of sums converges to. Their table holds, after the CDF of
//! |w|, the running sum of w in the same units; every other filter has weight exactly 1.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::Vec2;
use crate::layout::{FrameParams, SAMPLER_STRATIFIED};
use crate::rng::Sampler;
use crate::sampling::sample_cdf;

/// Where the signed running sum of a filter with negative lobes starts in the table buffer (the CDF of
/// |w| itself where there are none: the two are then one table).
fn signed_table(params: &FrameParams) -> u32 {
    if params.filter_signed != 0 {
        params.filter_cdf_offset + params.filter_bins
    } else {
        params.filter_cdf_offset
    }
}

/// The untruncated mass along an axis of the table at `base` (the CDF of |w|, or the signed one):
/// `FrameParams::filter_abs_mass` or `filter_mass`, which the host takes from `whole_masses`.
fn whole_mass(params: &FrameParams, base: u32) -> f32 {
    if base == params.filter_cdf_offset {
        params.filter_abs_mass
    } else {
        params.filter_mass
    }
}

/// The filter's untruncated masses along an axis, of |w| and of the signed w, summed from the tables
/// as `axis_mass` would sum them for a pixel whose filter lies inside the rendered window: the host
/// writes them into `FrameParams::filter_abs_mass` and `filter_mass` once a frame.
pub fn whole_masses(tables: &[f32], params: &FrameParams) -> (f32, f32) {
    let r = params.filter_radius;
    let (abs, signed) = (params.filter_cdf_offset, signed_table(params));
    (
        running_sum_at(tables, params, abs, r) - running_sum_at(tables, params, abs, -r),
        running_sum_at(tables, params, signed, r) - running_sum_at(tables, params, signed, -r),
    )
}

/// The filter's CDF at `x` (piecewise linear between the tabulated bin edges).
fn filter_cdf_at(tables: &[f32], params: &FrameParams, x: f32) -> f32 {
    running_sum_at(tables, params, params.filter_cdf_offset, x)
}

/// The running sum of the table at `base` (the CDF of |w|, or the signed one) at `x`.
fn running_sum_at(tables: &[f32], params: &FrameParams, base: u32, x: f32) -> f32 {
    let bins = params.filter_bins;
    let r = params.filter_radius;
    let t = ((x + r) / (2.0 * r) * bins as f32).clamp(0.0, bins as f32);
    let i = (t as u32).min(bins - 1);
    let frac = t - i as f32;
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

/// A camera sample on the film.
#[derive(Clone, Copy)]
pub struct FilmSample {
    /// Fractions of the full image's width and height.
    pub pos: Vec2,
    /// What the sample's estimate is multiplied by: 1 unless the filter has negative lobes.
    pub weight: f32,
}

/// The weight of a sample drawn at offset `d` from the pixel centre along one axis, the filter
/// truncated to `[lo, hi]`: the sign of w there (the bin's signed over absolute mass) times
/// ∫|w|/∫w over `[lo, hi]`; 0 where the truncated filter sums to nothing.
fn axis_weight(tables: &[f32], params: &FrameParams, d: f32, lo: f32, hi: f32) -> f32 {
    let signed = signed_table(params);
    let abs_density = filter_density(tables, params, params.filter_cdf_offset, d);
    let abs_mass = filter_cdf_at(tables, params, hi) - filter_cdf_at(tables, params, lo);
    let signed_mass = running_sum_at(tables, params, signed, hi) - running_sum_at(tables, params, signed, lo);
    if abs_density > 0.0 && signed_mass > 1e-6 * abs_mass {
        filter_density(tables, params, signed, d) / abs_density * (abs_mass / signed_mass)
    } else {
        0.0
    }
}

/// The reconstruction filter's weight at offset `d` (pixels) along one axis, in the table's units
/// (signed where the filter has negative lobes; zero outside the radius). The splatting film's
/// weights are products of two, and its ratio of sums cancels the units.
#[inline]
pub fn filter_weight(tables: &[f32], params: &FrameParams, d: f32) -> f32 {
    filter_density(tables, params, signed_table(params), d)
}

/// Film position and weight of sample `sample_index` in pixel (px, py): under filter importance
/// sampling its offset is drawn from the filter (and its weight is signed where the filter has
/// negative lobes); for the splatting film (`FrameParams::film_reach` > 0) it is uniform over the
/// pixel with weight 1, and `film_splat` weights it for each pixel it reaches.
pub fn sample_position(
    params: &FrameParams,
    tables: &[f32],
    px: u32,
    py: u32,
    sample_index: u32,
    sampler: &mut Sampler,
) -> FilmSample {
    let u = pixel_sample(params, sample_index, sampler);
    let r = params.filter_radius;
    // Pixel centre in the full image (the rendered pixels may be a crop of it).
    let cx = (params.crop_x + px) as f32 + 0.5;
    let cy = (params.crop_y + py) as f32 + 0.5;
    let (full_w, full_h) = (params.full_width as f32, params.full_height as f32);
    // (One FilmSample built after the branch, from scalars: naga has rejected structs merged from
    // two branches, `integrator::camera_sample`.)
    let (mut dx, mut dy, mut weight) = (u.x - 0.5, u.y - 0.5, 1.0);
    if params.film_reach == 0 {
        // The filter truncated to the rendered window, where Mitsuba (and the splatting film) draws
        // samples: at a crop window's edge as at the image's (a crop's edge pixels are not those of
        // the whole image; random scene 31's depth image, its crop's last row 0.7% apart).
        let (x0, x1) = window(params.crop_x, params.width);
        let (y0, y1) = window(params.crop_y, params.height);
        let (x_lo, x_hi) = ((x0 - cx).max(-r), (x1 - cx).min(r));
        let (y_lo, y_hi) = ((y0 - cy).max(-r), (y1 - cy).min(r));
        dx = sample_filter_1d(tables, params, u.x, x_lo, x_hi);
        dy = sample_filter_1d(tables, params, u.y, y_lo, y_hi);
        if params.filter_signed != 0 {
            weight =
                axis_weight(tables, params, dx, x_lo, x_hi) * axis_weight(tables, params, dy, y_lo, y_hi);
        }
    }
    FilmSample { pos: Vec2::new((cx + dx) / full_w, (cy + dy) / full_h), weight }
}

/// The filter's density at offset `x` (pixels) from a pixel centre, as `sample_position` draws it
/// (`base`: the CDF of |w|), or the signed filter in the same units (`base`: `signed_table`):
/// piecewise constant over the tabulated bins, zero outside the radius.
fn filter_density(tables: &[f32], params: &FrameParams, base: u32, x: f32) -> f32 {
    let r = params.filter_radius;
    if !(x > -r && x < r) {
        return 0.0;
    }
    let bins = params.filter_bins;
    let i = (((x + r) / (2.0 * r) * bins as f32) as u32).min(bins - 1);
    let prev = if i == 0 { 0.0 } else { tables[(base + i - 1) as usize] };
    (tables[(base + i) as usize] - prev) * bins as f32 / (2.0 * r)
}

/// The rendered window along one axis, `[start, start + size)` in pixels of the full image.
#[inline]
fn window(start: u32, size: u32) -> (f32, f32) {
    (start as f32, (start + size) as f32)
}

/// The rendered pixels along one axis (x where `x_axis`, else y): the first one's place in the full
/// image and their count.
#[inline]
pub fn rendered_axis(params: &FrameParams, x_axis: bool) -> (u32, u32) {
    if x_axis {
        (params.crop_x, params.width)
    } else {
        (params.crop_y, params.height)
    }
}

/// The filter's mass inside the rendered window `[lo, hi)` along one axis for a pixel centred at
/// `c`: what `sample_position` renormalises the truncated filter by (`base`: the CDF of |w|), or the
/// signed filter's (`base`: `signed_table`). Where the filter's radius lies inside the window (all
/// but the pixels within the radius of its edge) that is the table's whole mass, which the frame
/// carries (`whole_mass`), the same to the bit as the two running sums it saves.
fn axis_mass(tables: &[f32], params: &FrameParams, base: u32, c: f32, (lo, hi): (f32, f32)) -> f32 {
    let r = params.filter_radius;
    if hi - c >= r && lo - c <= -r {
        return whole_mass(params, base);
    }
    running_sum_at(tables, params, base, (hi - c).min(r))
        - running_sum_at(tables, params, base, (lo - c).max(-r))
}

/// The density (per unit of pixel area) with which camera samples of pixel (`px`, `py`) of the full
/// image land at film position `pos` (in pixels of the full image): the reconstruction filter's |w|
/// centred on the pixel, truncated to the rendered window and renormalised, exactly as
/// `sample_position` draws it. IBPT's MIS compares the camera and light-tracing strategies through it.
pub fn pixel_density(tables: &[f32], params: &FrameParams, pos: Vec2, px: u32, py: u32) -> f32 {
    filter_at(tables, params, params.filter_cdf_offset, pos, px, py)
}

/// The density (per unit of pixel area) with which camera samples land at `pos`, as the MIS between
/// the camera strategies and light tracing weighs a path reaching pixel (`px`, `py`) there: under
/// filter importance sampling the pixel's own (`pixel_density`); with the splatting film
/// (`FrameParams::film_reach` > 0) one anywhere in the rendered window, since every pixel draws its
/// samples uniformly over its own area and each reaches pixel (`px`, `py`) with the weight a
/// light-tracing connection landing at the same point has (`pixel_weight`).
pub fn camera_density(tables: &[f32], params: &FrameParams, pos: Vec2, px: u32, py: u32) -> f32 {
    if params.film_reach == 0 {
        return pixel_density(tables, params, pos, px, py);
    }
    let (x0, x1) = window(params.crop_x, params.width);
    let (y0, y1) = window(params.crop_y, params.height);
    if pos.x >= x0 && pos.x < x1 && pos.y >= y0 && pos.y < y1 {
        1.0
    } else {
        0.0
    }
}

/// What a light-tracing connection landing at `pos` (pixels of the full image) contributes to pixel
/// (`px`, `py`) per unit of its value: the filter w centred on the pixel, truncated to the rendered
/// window and divided by its sum there, so that splats and camera samples (`sample_position`)
/// estimate the same filtered pixel. Negative on a negative lobe; `pixel_density` where the filter has none.
pub fn pixel_weight(tables: &[f32], params: &FrameParams, pos: Vec2, px: u32, py: u32) -> f32 {
    filter_at(tables, params, signed_table(params), pos, px, py)
}

/// One axis of `pixel_weight` for the pixel centred at `c` (pixels of the full image) along x
/// (`x_axis`) or y: the filter at `pos` and, where that is not zero, its mass in the rendered window
/// along the axis. `pixel_weight` at a point of the window is the product of the two axes' filters
/// over the product of their masses, where that is positive: a neighbourhood needs each column's and
/// each row's once (`integrator::splat_camera_estimate`).
pub fn axis_pixel_weight(tables: &[f32], params: &FrameParams, pos: f32, c: f32, x_axis: bool) -> (f32, f32) {
    let f = filter_density(tables, params, signed_table(params), pos - c);
    if f == 0.0 {
        return (0.0, 0.0);
    }
    (f, axis_window_mass(tables, params, c, x_axis))
}

/// `axis_pixel_weight`'s filter integrated over the pixel `[at, at + 1)` of the full image along the
/// axis, for the pixel centred at `c`.
pub fn axis_pixel_integral(tables: &[f32], params: &FrameParams, at: f32, c: f32) -> f32 {
    let base = signed_table(params);
    running_sum_at(tables, params, base, at + 1.0 - c) - running_sum_at(tables, params, base, at - c)
}

/// One axis of the weight that a camera sample drawn uniformly in the pixel `[at, at + 1)` gives
/// the pixel centred at `c` on average (`film_splat`'s control variate): `axis_pixel_integral` over
/// the filter's mass in the rendered window along the axis (x where `x_axis`); zero where that mass
/// is not positive. The product of two axes' is the mean of `pixel_weight` over the pixel, whether or
/// not one sample's own place lies within the filter's radius.
pub fn axis_pixel_mean(tables: &[f32], params: &FrameParams, at: f32, c: f32, x_axis: bool) -> f32 {
    let mass = axis_window_mass(tables, params, c, x_axis);
    if mass > 0.0 {
        axis_pixel_integral(tables, params, at, c) / mass
    } else {
        0.0
    }
}

/// The signed filter's running sum along an axis at `x` pixels from a pixel centre: the difference
/// of two is its integral between them (`axis_pixel_integral`'s, where adjacent pixels share an end).
pub fn axis_running_sum(tables: &[f32], params: &FrameParams, x: f32) -> f32 {
    running_sum_at(tables, params, signed_table(params), x)
}

/// The signed filter's mass in the rendered window along one axis (x where `x_axis`) for the pixel
/// centred at `c`: what `axis_pixel_weight` and `axis_pixel_mean` divide by.
pub fn axis_window_mass(tables: &[f32], params: &FrameParams, c: f32, x_axis: bool) -> f32 {
    let (start, size) = rendered_axis(params, x_axis);
    axis_mass(tables, params, signed_table(params), c, window(start, size))
}

/// The filter of table `base` centred on pixel (`px`, `py`) at `pos`, over its truncated sum: zero
/// outside the rendered window, where no camera sample lands (a light path's connection landing
/// there reaches no pixel, or a crop's edge pixels would gain what its camera samples cannot).
fn filter_at(tables: &[f32], params: &FrameParams, base: u32, pos: Vec2, px: u32, py: u32) -> f32 {
    let (x0, x1) = window(params.crop_x, params.width);
    let (y0, y1) = window(params.crop_y, params.height);
    if !(pos.x >= x0 && pos.x < x1 && pos.y >= y0 && pos.y < y1) {
        return 0.0;
    }
    let (cx, cy) = (px as f32 + 0.5, py as f32 + 0.5);
    let fx = filter_density(tables, params, base, pos.x - cx);
    let fy = filter_density(tables, params, base, pos.y - cy);
    if fx == 0.0 || fy == 0.0 {
        return 0.0;
    }
    let mass = axis_mass(tables, params, base, cx, (x0, x1)) * axis_mass(tables, params, base, cy, (y0, y1));
    if mass > 0.0 {
        fx * fy / mass
    } else {
        0.0
    }
}
