//! The splatting film: each camera sample adds w·L and w to every pixel its reconstruction filter
//! covers, and a pixel develops to Σw·L / Σw, as Mitsuba's `hdrfilm` does (its default
//! `sample_border = false`: samples are drawn inside the rendered window only, and a pixel near its
//! edge sums the weights it got).
//!
//! Without atomics, so that one seed gives one image on both backends, run after run: the pixel that
//! draws the samples owns a neighbourhood of (2r+1)² cells (r = `FrameParams::film_reach`), one per
//! pixel its samples can reach, and adds each sample's w·L and w to them (`add`); after the
//! camera pass, each pixel gathers the cells that its neighbours hold for it (`gather`) and adds them
//! to its accumulator (`resolved`). Only the invocation that owns a cell writes it, and the gather
//! runs as a dispatch of its own, so no two invocations touch one word at once.
//!
//! The cells live in the `SPLAT` buffer (light tracing's fixed-point words, which the path and direct
//! integrators do not use), as f32 bits: slot `s` of pixel `p` at word `s · pixels + p`, so that the
//! threads of a workgroup touch consecutive words. Slots: four per cell (w·R, w·G, w·B, w), then one
//! counting the pixel's invalid samples.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::film::{filter_weight, FilmSample};
use crate::layout::{FrameParams, PixelAccum};
use crate::math::is_finite3;
use crate::spectrum::Rgb;
use crate::splat::{AtomicWords, SPLAT_STRIDE};

/// The widest neighbourhood the film splats into: r = 4 (81 cells, 1.3 KB a pixel) covers Mitsuba's
/// filters up to a gaussian of stddev 1 (radius 4); a wider filter falls back to filter importance
/// sampling (the host decides: `reach_for_radius`).
pub const MAX_REACH: u32 = 4;

/// How many pixels on each side of its own a sample drawn uniformly in a pixel can reach with a
/// filter of radius `radius` (a pixel centre is within `radius` of some point of the pixel), or 0
/// where only its own pixel can be reached (a box of radius ½ or less: splatting is then the same as
/// filter importance sampling).
pub fn reach_for_radius(radius: f32) -> u32 {
    // Pixel i's centre lies i + ½ − u from a sample at u ∈ [0, 1) of pixel 0: reachable while i − ½
    // < radius.
    let r = (radius + 0.5).ceil() - 1.0;
    if r > 0.0 {
        r as u32
    } else {
        0
    }
}

/// Cells a pixel owns: (2r+1)².
#[inline]
pub fn cells(params: &FrameParams) -> u32 {
    let side = 2 * params.film_reach + 1;
    side * side
}

/// The slot counting a pixel's invalid samples (after its cells').
#[inline]
fn invalid_slot(params: &FrameParams) -> u32 {
    4 * cells(params)
}

/// `u32` words per pixel of the `SPLAT` buffer for these parameters: light tracing's fixed-point
/// sums (and the camera cells of the integrators that splat camera paths too), the splatting film's
/// cells, or none.
pub fn words_per_pixel(params: &FrameParams) -> u32 {
    let kind = params.integrator;
    if crate::layout::splats(kind) {
        SPLAT_STRIDE + camera_cells(params)
    } else if params.film_reach > 0 {
        invalid_slot(params) + 1
    } else {
        0
    }
}

/// Where the cells live, slot by slot for each pixel; implemented by each backend (the GPU's
/// `SPLAT` buffer, the CPU's per-pixel arrays). `gather` only reads them.
pub trait CellReader {
    fn get(&self, params: &FrameParams, pixel: u32, slot: u32) -> f32;
}

/// Cells a pixel's samples are added to.
pub trait FilmCells: CellReader {
    fn set(&mut self, params: &FrameParams, pixel: u32, slot: u32, value: f32);
}

/// The GPU's layout: slot `s` of pixel `p` at word `s · pixels + p` of a buffer of f32 bits. A
/// newtype of the slice alone, as `splat::GpuWords`, and never stored in another struct: a struct
/// holding the slice beside other fields, or a sink holding a reference to it across the sample
/// loop, put a pointer type inside a struct, which naga rejects ("Type '*mut [u32]' is invalid").
pub struct WordCells<'a>(pub &'a mut [u32]);

/// Word of slot `slot` of pixel `pixel` in the GPU's layout.
#[inline]
fn word(params: &FrameParams, pixel: u32, slot: u32) -> usize {
    (slot * (params.width * params.height) + pixel) as usize
}

impl CellReader for WordCells<'_> {
    #[inline]
    fn get(&self, params: &FrameParams, pixel: u32, slot: u32) -> f32 {
        f32::from_bits(self.0[word(params, pixel, slot)])
    }
}

impl FilmCells for WordCells<'_> {
    #[inline]
    fn set(&mut self, params: &FrameParams, pixel: u32, slot: u32, value: f32) {
        self.0[word(params, pixel, slot)] = value.to_bits();
    }
}

/// Clears the cells `pixel` owns (they still hold the last pass's sums).
pub fn clear<C: FilmCells>(cells: &mut C, params: &FrameParams, pixel: u32) {
    let mut slot = 0;
    while slot <= invalid_slot(params) {
        cells.set(params, pixel, slot, 0.0);
        slot += 1;
    }
}

/// Counts `n` of `pixel`'s samples that gave no finite estimate (or were cut short) as black.
pub fn add_invalid<C: FilmCells>(cells: &mut C, params: &FrameParams, pixel: u32, n: u32) {
    accumulate(cells, params, pixel, invalid_slot(params), n as f32);
}

/// Adds estimate `l` of one of `pixel`'s samples, which landed at `film` (`film::sample_position`),
/// with the filter's weight to each pixel of the rendered window that it reaches, in the cells
/// `pixel` owns.
pub fn add<C: FilmCells>(
    cells: &mut C,
    tables: &[f32],
    params: &FrameParams,
    pixel: u32,
    film: FilmSample,
    l: Rgb,
) {
    if !is_finite3(l) {
        add_invalid(cells, params, pixel, 1);
        return;
    }
    let (px, py) = (pixel % params.width, pixel / params.width);
    // The sample's place in its pixel, recovered from its film position (to within 2⁻¹² of a
    // pixel at 4096 pixels, where the filter's table has bins of 1/16 pixel).
    let ox = film.pos.x * params.full_width as f32 - (params.crop_x + px) as f32;
    let oy = film.pos.y * params.full_height as f32 - (params.crop_y + py) as f32;
    let r = params.film_reach as i32;
    let side = 2 * r + 1;
    // The weights along x, once per column (zero for a column outside the window): evaluated
    // per cell instead, the filter's table lookups took 10% of `direct`'s time on the CPU.
    let mut wx = [0.0f32; (2 * MAX_REACH + 1) as usize];
    let mut i = -r;
    while i <= r {
        let x = px as i32 + i;
        if x >= 0 && x < params.width as i32 {
            wx[(i + r) as usize] = filter_weight(tables, params, i as f32 + 0.5 - ox);
        }
        i += 1;
    }
    let mut j = -r;
    while j <= r {
        let y = py as i32 + j;
        let wy = filter_weight(tables, params, j as f32 + 0.5 - oy);
        if y >= 0 && y < params.height as i32 && wy != 0.0 {
            let mut i = -r;
            while i <= r {
                let w = wy * wx[(i + r) as usize];
                if w != 0.0 {
                    let base = 4 * ((j + r) * side + (i + r)) as u32;
                    accumulate(cells, params, pixel, base, l.x * w);
                    accumulate(cells, params, pixel, base + 1, l.y * w);
                    accumulate(cells, params, pixel, base + 2, l.z * w);
                    accumulate(cells, params, pixel, base + 3, w);
                }
                i += 1;
            }
        }
        j += 1;
    }
}

#[inline]
fn accumulate<C: FilmCells>(cells: &mut C, params: &FrameParams, pixel: u32, slot: u32, value: f32) {
    let v = cells.get(params, pixel, slot);
    cells.set(params, pixel, slot, v + value);
}

/// What a pass's camera samples gave pixel (`px`, `py`): Σw·L, Σw and the invalid count, gathered
/// from the cells its neighbours (and it) hold for it.
pub struct Gathered {
    pub sum: Rgb,
    pub weight: f32,
    pub invalid: f32,
}

/// Calls `f(owner, cell)` for each pixel `owner` within the film's reach of pixel (`px`, `py`) in the
/// window, in one fixed order, with the index of the cell (`(j + r) · (2r + 1) + (i + r)` for the
/// offset (`i`, `j`) from `owner` to this pixel) that `owner` holds for it.
#[inline]
fn each_owner<F: FnMut(u32, u32)>(params: &FrameParams, px: u32, py: u32, mut f: F) {
    let r = params.film_reach as i32;
    let side = 2 * r + 1;
    // Offset (i, j) from the owning pixel to this one.
    let mut j = -r;
    while j <= r {
        let y = py as i32 - j;
        if y >= 0 && y < params.height as i32 {
            let mut i = -r;
            while i <= r {
                let x = px as i32 - i;
                if x >= 0 && x < params.width as i32 {
                    f(y as u32 * params.width + x as u32, ((j + r) * side + (i + r)) as u32);
                }
                i += 1;
            }
        }
        j += 1;
    }
}

/// Gathers pixel (`px`, `py`)'s sums from its neighbourhood's cells, in one fixed order.
pub fn gather<C: CellReader>(cells: &C, params: &FrameParams, px: u32, py: u32) -> Gathered {
    let mut g = Gathered { sum: Rgb::ZERO, weight: 0.0, invalid: 0.0 };
    each_owner(params, px, py, |owner, cell| {
        let base = 4 * cell;
        g.sum += Rgb::new(
            cells.get(params, owner, base),
            cells.get(params, owner, base + 1),
            cells.get(params, owner, base + 2),
        );
        g.weight += cells.get(params, owner, base + 3);
    });
    g.invalid = cells.get(params, py * params.width + px, invalid_slot(params));
    g
}

/// A pixel's accumulator with one pass's gathered sums added: Σw·L to `sum`, Σw to `count` (the
/// host develops `sum / count`), and `(q·S)²/W` to `sum_sq` for the pass's sum `S` and weight `W`
/// (`q`: `layout::square_scale`), so that the host estimates the variance from batch means weighted
/// by `W`, as it does for light tracing's splats. A pass whose weights sum to zero or less (a
/// negative lobe at a handful of samples) adds its sums but no square.
#[inline]
pub fn resolved(a: PixelAccum, g: &Gathered, q: f32) -> PixelAccum {
    let w = g.weight;
    let sq = g.sum * q;
    let sq = if w > 0.0 { sq * sq / w } else { Rgb::ZERO };
    PixelAccum {
        sum: [a.sum[0] + g.sum.x, a.sum[1] + g.sum.y, a.sum[2] + g.sum.z],
        count: a.count + w,
        sum_sq: [a.sum_sq[0] + sq.x, a.sum_sq[1] + sq.y, a.sum_sq[2] + sq.z],
        invalid: a.invalid + g.invalid,
    }
}

/// Words per pixel of the camera cells: IBPT's, BDPT's and VCM's camera samples add their estimates
/// to the (2r+1)² pixels around their own (one under filter importance sampling, `film_reach` 0),
/// each times that pixel's share of the filter (`film::pixel_weight`, as light tracing's splats
/// carry), in cells their own pixel owns: R, G, B a cell, past the light words (`camera_word`). So no
/// camera sample needs an atomic add: its pixel's invocation alone writes them, and `resolve` adds the
/// cells that its neighbours hold for a pixel to that pixel's light sums (`gather_camera`). Through
/// the light words' atomics instead, the camera splats of a `bdpt` pass of the Cornell box cost 0.72
/// ms a sample on an H200, a quarter of its camera pass (BENCHMARKS.md, "Where a bidirectional
/// sample's time goes").
///
/// Under the splatting film with independent samples, four more words a pixel persist from pass to
/// pass: the sum of the pixel's own camera samples' estimates so far and their count, whose mean
/// `camera_mean` is the control variate's coefficient (`control_variate`).
#[inline]
pub fn camera_cells(params: &FrameParams) -> u32 {
    let kind = params.integrator;
    if crate::layout::splats(kind) && kind != crate::layout::INTEGRATOR_PTRACER {
        3 * cells(params) + if control_variate(params) { MEAN_SLOTS } else { 0 }
    } else {
        0
    }
}

/// The persisting words of a pixel's camera estimates (`camera_cells`): R, G, B, count.
const MEAN_SLOTS: u32 = 4;

/// Whether the splatting integrators' camera samples carry a control variate: each sample adds
/// `w·L − (w − ω)·β` to a neighbour's cell, where `w` is its filter weight there, `ω` that weight's
/// mean over the sample's pixel (`film::axis_pixel_mean`) and `β` the mean of the estimates of the
/// pixel's earlier samples (`camera_mean`). Since `β` does not depend on this sample and `w − ω`
/// averages to zero, the sum stays unbiased, while the noise of Σw (the samples' positions under the
/// filter) cancels wherever the camera strategy's estimate is even over a pixel: a light seen
/// directly returns its radiance without noise, as the weight-normalised film of `path` does. `β`
/// is the mean of the pixel's own samples, the estimate each of them is drawn around, rather than the
/// pixel's gathered value, which blurs its neighbours' in and so differs beside an edge. Light
/// tracing's splats divide by no weight sum and have no such term. Only with the splatting film (filter
/// importance sampling has no weights to vary) and independent samples (a stratified sample is not
/// uniform over its pixel alone, so `ω` would not be its mean).
#[inline]
pub fn control_variate(params: &FrameParams) -> bool {
    params.film_reach > 0 && params.sampler != crate::layout::SAMPLER_STRATIFIED
}

/// The mean estimate of `pixel`'s camera samples before this one (zero before the first): the
/// control variate's `β`.
#[inline]
pub fn camera_mean<W: AtomicWords>(words: &W, params: &FrameParams, pixel: u32) -> Rgb {
    let base = 3 * cells(params);
    let n = f32::from_bits(words.load(camera_word(params, pixel, base + 3)));
    if !(n > 0.0) {
        return Rgb::ZERO;
    }
    Rgb::new(
        f32::from_bits(words.load(camera_word(params, pixel, base))),
        f32::from_bits(words.load(camera_word(params, pixel, base + 1))),
        f32::from_bits(words.load(camera_word(params, pixel, base + 2))),
    ) / n
}

/// Adds one camera sample's estimate `l` to `pixel`'s persisting words (`camera_mean`); only the
/// pixel's own invocation writes them.
#[inline]
pub fn add_to_camera_mean<W: AtomicWords>(words: &mut W, params: &FrameParams, pixel: u32, l: Rgb) {
    let base = 3 * cells(params);
    let v = [l.x, l.y, l.z, 1.0];
    let mut c = 0;
    while c < MEAN_SLOTS {
        let at = camera_word(params, pixel, base + c);
        words.store(at, (f32::from_bits(words.load(at)) + v[c as usize]).to_bits());
        c += 1;
    }
}

/// Word of camera cell slot `slot` of `pixel`: slot after slot past the light words, each slot's words
/// pixel after pixel, so that a workgroup's invocations touch consecutive words.
#[inline]
fn camera_word(params: &FrameParams, pixel: u32, slot: u32) -> u32 {
    let pixels = params.width * params.height;
    pixels * SPLAT_STRIDE + slot * pixels + pixel
}

/// Writes (`first`: the pass's first sample of `pixel`) or adds `value` to camera cell `cell` of
/// `pixel` (0 for the pixel itself under filter importance sampling; `(j·(2r+1) + i)` for the pixel
/// at (i − r, j − r) from it under the splatting film).
#[inline]
pub fn add_camera_cell<W: AtomicWords>(
    words: &mut W,
    params: &FrameParams,
    pixel: u32,
    cell: u32,
    value: Rgb,
    first: bool,
) {
    let base = 3 * cell;
    let v = [value.x, value.y, value.z];
    let mut c = 0;
    while c < 3 {
        let at = camera_word(params, pixel, base + c);
        let sum = if first { v[c as usize] } else { f32::from_bits(words.load(at)) + v[c as usize] };
        words.store(at, sum.to_bits());
        c += 1;
    }
}

/// What pixel (`px`, `py`)'s neighbourhood's camera samples (and its own) left it in this pass: the
/// camera cells its neighbours hold for it, summed in one fixed order.
pub fn gather_camera<W: AtomicWords>(words: &W, params: &FrameParams, px: u32, py: u32) -> Rgb {
    let mut sum = Rgb::ZERO;
    each_owner(params, px, py, |owner, cell| {
        let base = 3 * cell;
        sum += Rgb::new(
            f32::from_bits(words.load(camera_word(params, owner, base))),
            f32::from_bits(words.load(camera_word(params, owner, base + 1))),
            f32::from_bits(words.load(camera_word(params, owner, base + 2))),
        );
    });
    sum
}

/// Pixel (`px`, `py`)'s accumulator with one splatting pass added (`splat::resolved_with`): its light
/// words, read and cleared for the next pass, and its camera cells gathered.
#[inline]
pub fn resolved_splats<W: AtomicWords>(
    a: PixelAccum,
    words: &mut W,
    params: &FrameParams,
    px: u32,
    py: u32,
    q: f32,
) -> PixelAccum {
    let extra = if camera_cells(params) > 0 { gather_camera(words, params, px, py) } else { Rgb::ZERO };
    let base = (py * params.width + px) * SPLAT_STRIDE;
    let mut w = [0u32; SPLAT_STRIDE as usize];
    let mut i = 0;
    while i < SPLAT_STRIDE {
        w[i as usize] = words.load(base + i);
        words.store(base + i, 0);
        i += 1;
    }
    crate::splat::resolved_with(a, w, extra, params.sample_count, q)
}
