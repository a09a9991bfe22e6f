//! Integrators and the per-pixel driver both backends call.
pub mod bdpt;
pub mod bdpt_mis;
pub mod direct;
pub mod mis;
pub mod nee;
pub mod pass_wavelength;
pub mod path;
pub mod ptracer;
pub mod vcm_grid;

use crate::bsdf::perturb::{self, Perturbation, Shading};
use crate::camera::{Ray, CAMERA_IRRADIANCE_METER};
use crate::features;
use crate::film;
use crate::film_splat::{self, FilmCells, MAX_REACH};
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::irradiance_meter;
pub use crate::layout::SceneView;
use crate::layout::{
    FrameParams, Material, PixelAccum, Primitive, INTEGRATOR_BDPT, INTEGRATOR_IBPT, INTEGRATOR_PTRACER,
    INTEGRATOR_VCM, MATERIAL_TWO_SIDED, TILE,
};
use crate::math::is_finite3;
use crate::rng::{hash2, u32_to_unit_f32, Sampler};
use crate::shape::{Hit, SurfacePoint};
use crate::spectrum::Rgb;
use crate::splat::AtomicWords;
use crate::wavelength;
use bdpt::LightVertex;

/// What one dispatch adds to a pixel.
#[derive(Clone, Copy)]
pub struct PixelSums {
    pub sum: Rgb,
    /// Sum of the squares of the samples scaled by `layout::square_scale`.
    pub sum_sq: Rgb,
    /// Samples whose estimate was NaN or infinite, or that the driver cut short (`render_pixel`); they
    /// are counted as black so that the image stays finite and unbiased estimates elsewhere are
    /// unaffected.
    pub invalid: u32,
}

/// The dimensions an irradiance meter's ray draws its direction from (its point takes the lens's).
const DIM_METER_DIRECTION: u32 = u32::MAX - 3;

/// Whether the camera is an irradiance meter (compiled in only for scenes with one).
#[inline]
fn is_irradiance_meter(scene: &SceneView, params: &FrameParams) -> bool {
    params.camera.kind == CAMERA_IRRADIANCE_METER && features::has(scene.features, features::IRRADIANCE_METER)
}

/// A camera sample of pixel (`px`, `py`): its sampler (keyed by seed, pixel and sample), the film
/// sample (where it lands, in fractions of the full image, and its filter weight) and the primary ray
/// (whose radiance an irradiance meter weights by `irradiance_meter::WEIGHT`). (The tuple is built
/// in one place: returning it from two branches, or with the weight as a fourth value, made naga
/// reject the SPIR-V: "member at 52 overlaps the previous".)
#[inline]
fn camera_sample(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    sample_index: u32,
) -> (Sampler, film::FilmSample, Ray) {
    let (px, py) = (pixel % params.width, pixel / params.width);
    let mut sampler = Sampler::new(params.seed, pixel, sample_index);
    let film_sample = film::sample_position(params, scene.tables, px, py, sample_index, &mut sampler);
    let u_lens = sampler.next_2d();
    let ray = primary_ray(scene, params, film_sample.pos, u_lens, &mut sampler);
    (sampler, film_sample, ray)
}

/// The camera's ray through `film` (`u_lens` picks a thin lens's aperture point); an irradiance
/// meter's ray from its shape instead (its point drawn from `u_lens`, its direction from
/// `DIM_METER_DIRECTION`).
#[inline]
fn primary_ray(
    scene: &SceneView,
    params: &FrameParams,
    film: Vec2,
    u_lens: Vec2,
    sampler: &mut Sampler,
) -> Ray {
    if is_irradiance_meter(scene, params) {
        sampler.set_dimension(DIM_METER_DIRECTION);
        let u_dir = sampler.next_2d();
        return irradiance_meter::generate_ray(scene, params.camera.meter_table, u_lens, u_dir);
    }
    params.camera.generate_ray(film, u_lens)
}

/// Where one of `pixel`'s camera samples goes: its own sums (filter importance sampling,
/// `film_reach` 0) or the cells of the splatting film that it owns (`film_splat`), chosen at run
/// time, so that the GPU's `render` instantiates `render_samples` once (a sink type for each made the
/// SPIR-V module 34 MB instead of 18 and `spirv-opt -O` ran past 80 CPU-minutes). The sums and the
/// cells are passed separately, never wrapped in a struct: naga rejected a struct holding the cells'
/// slice ("Type '*mut [u32]' is invalid", `film_splat::WordCells`) and one nesting `PixelSums`
/// before another field (naga lays the vec3 members out to 32 bytes, against the struct's 28).
#[inline]
#[allow(clippy::too_many_arguments)]
fn take_sample<C: FilmCells>(
    sums: &mut PixelSums,
    cells: &mut C,
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    film: film::FilmSample,
    l: Rgb,
) {
    if params.film_reach != 0 {
        // (The host splats neither an irradiance meter's samples nor a signed weight: `film_reach`
        // is 0 for the meter, and splatted samples carry weight 1.)
        film_splat::add(cells, scene.tables, params, pixel, film, l);
    } else {
        add_sample(sums, scene, params, l, film.weight);
    }
}

/// Renders `params.sample_count` samples of one pixel (row-major index): under filter importance
/// sampling into the sums it returns, for the splatting film into the cells the pixel owns (cleared
/// first; the sums it returns are then zero).
pub fn render_pixel<C: FilmCells>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    regenerate: bool,
    cells: &mut C,
) -> PixelSums {
    if params.film_reach != 0 {
        film_splat::clear(cells, params, pixel);
    }
    let mut sums = PixelSums { sum: Rgb::ZERO, sum_sq: Rgb::ZERO, invalid: 0 };
    render_samples(scene, params, pixel, regenerate, &mut sums, cells);
    sums
}

/// Renders `params.sample_count` samples of one pixel (row-major index) into `sums` or `cells`: the
/// path tracer one path after the other, or, with `regenerate`, as one loop of bounces over all the
/// samples (a path that ends hands its lane the next sample at once: `path::CameraPath`). Each sample
/// draws the same random numbers either way and the sums add in the same order, so the two give the
/// same image to the bit; which runs faster depends on the scene, and the GPU backend measures it
/// (`host`'s `backend::path_loop`). `direct` has one loop.
fn render_samples<C: FilmCells>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    regenerate: bool,
    sums: &mut PixelSums,
    cells: &mut C,
) {
    let mut s = 0;
    // The bit, not `params.integrator`: it is set exactly for `direct` (`features::DIRECT_INTEGRATOR`).
    let direct = features::has(scene.features, features::DIRECT_INTEGRATOR);
    if direct || !regenerate {
        while s < params.sample_count {
            let (mut sampler, film_sample, ray) = camera_sample(scene, params, pixel, params.sample_base + s);
            let l = if direct {
                direct::li(scene, params, ray, &mut sampler)
            } else {
                path::li(scene, params, ray, &mut sampler, 1.0)
            };
            take_sample(sums, cells, scene, params, pixel, film_sample, l);
            s += 1;
        }
    } else if params.sample_count > 0 {
        let (mut sampler, mut film_sample, ray) = camera_sample(scene, params, pixel, params.sample_base);
        let mut path = path::CameraPath::new(ray, 1.0);
        loop {
            if !path.bounce(scene, params, &mut sampler) {
                take_sample(sums, cells, scene, params, pixel, film_sample, path.result);
                s += 1;
                if s >= params.sample_count {
                    break;
                }
                let ray;
                (sampler, film_sample, ray) = camera_sample(scene, params, pixel, params.sample_base + s);
                path = path::CameraPath::new(ray, 1.0);
            }
        }
    }
    // Zero, unless the driver cut a loop short: llvmpipe (lavapipe) ends every loop of an invocation
    // once all its loops together have run 65535 iterations (Mesa's `LP_MAX_TGSI_LOOP_ITERATIONS`),
    // and a pass of 128 samples through the facing mirrors of `stiff.rs` lost up to half of some
    // pixels' samples that way without a trace. Counted as invalid they are reported; the GPU backend
    // splits passes on software adapters so that it rarely happens.
    let cut = params.sample_count - s;
    if params.film_reach != 0 {
        film_splat::add_invalid(cells, params, pixel, cut);
    } else {
        sums.invalid += cut;
    }
}

/// Adds one sample's estimate (an irradiance meter's times its weight, any under a signed filter
/// times its filter weight) to the sums, or counts it as invalid.
#[inline]
fn add_sample(sums: &mut PixelSums, scene: &SceneView, params: &FrameParams, l: Rgb, filter_weight: f32) {
    let l = if is_irradiance_meter(scene, params) { l * irradiance_meter::WEIGHT } else { l };
    let l = if params.filter_signed != 0 { l * filter_weight } else { l };
    if is_finite3(l) {
        sums.sum += l;
        let scaled = l * crate::layout::square_scale(params);
        sums.sum_sq += scaled * scaled;
    } else {
        sums.invalid += 1;
    }
}

/// Light paths draw their random numbers from a stream of their own, so that under IBPT the camera
/// path and the light path of one pixel sample are independent.
const LIGHT_PATH_STREAM: u32 = 0x9e37_79b9;

/// A splatted camera sample of `pixel` (IBPT's camera half, BDPT, VCM): its sampler, film sample and
/// ray, and the density with which camera samples land where the ray crosses the film, as the MIS
/// against light tracing weighs it (`film::camera_density`).
#[inline]
fn splatted_camera_sample(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    sample_index: u32,
) -> (Sampler, film::FilmSample, Ray, f32) {
    let (px, py) = (pixel % params.width, pixel / params.width);
    // (The splatting integrators refuse the irradiance meter: no weight here.)
    let (sampler, film_sample, ray) = camera_sample(scene, params, pixel, sample_index);
    let pos = film_position(params, &film_sample);
    let density = film::camera_density(scene.tables, params, pos, params.crop_x + px, params.crop_y + py);
    (sampler, film_sample, ray, density)
}

/// Where a film sample lies, in pixels of the full image.
#[inline]
fn film_position(params: &FrameParams, film_sample: &film::FilmSample) -> Vec2 {
    Vec2::new(film_sample.pos.x * params.full_width as f32, film_sample.pos.y * params.full_height as f32)
}

/// Adds a camera path's estimate `l` (weighted against light tracing) where light tracing's splats
/// go, so that camera and light paths resolve together, through the camera cells `pixel` owns
/// (`film_splat::camera_cells`): under filter importance sampling to the pixel itself; with the
/// splatting film (`film_reach` > 0) to every pixel of the rendered window that the filter reaches
/// from the sample's place, times the filter's weight there (`film::pixel_weight`, which a
/// light-tracing connection at that point would carry too), each pixel's sums divided by its samples
/// as before. A non-finite estimate is counted as invalid and adds nothing. `first`: the pass's first
/// sample of the pixel, which writes the cells over the last pass's.
#[inline]
fn splat_camera_estimate<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    film_sample: &film::FilmSample,
    l: Rgb,
    first: bool,
    words: &mut W,
) {
    let l = if is_finite3(l) {
        l
    } else {
        crate::splat::count_invalid(words, pixel);
        Rgb::ZERO
    };
    if params.film_reach == 0 {
        let l = if params.filter_signed != 0 { l * film_sample.weight } else { l };
        film_splat::add_camera_cell(words, params, pixel, 0, l, first);
        return;
    }
    let pos = film_position(params, film_sample);
    let (px, py) = (pixel % params.width, pixel / params.width);
    let r = params.film_reach as i32;
    // `film::pixel_weight` separably: each column's filter and mass along x once, each row's along y
    // once (per pixel, the weights' table lookups made the CPU's `ibpt` samples 53% dearer than
    // under `--film fis` on bsdf_dielectric_glass; separably, 17%).
    let span = (2 * r + 1) as u32;
    let (x0, y0) = (px as i32 - r, py as i32 - r);
    let columns = axis_weights(scene, params, pos.x, x0, span, true);
    let rows = axis_weights(scene, params, pos.y, y0, span, false);
    // The control variate (`film_splat::control_variate`): the mean of the pixel's earlier samples
    // and each neighbour's mean weight from a sample of this pixel.
    let cv = film_splat::control_variate(params);
    let beta = if cv { film_splat::camera_mean(words, params, pixel) } else { Rgb::ZERO };
    // (Zeros without it; filled in the loops rather than merged from two branches, which naga has
    // rejected for composites: `film::sample_position`.)
    let count = if cv { span } else { 0 };
    let mean_x = axis_means(scene.tables, params, px, (x0, count), true);
    let mean_y = axis_means(scene.tables, params, py, (y0, count), false);
    // Every cell, those of pixels outside the window (weight 0) too, so that none keeps the last
    // pass's sums.
    let mut j = 0;
    while j < span {
        let mut i = 0;
        while i < span {
            let mass = columns.mass[i as usize] * rows.mass[j as usize];
            let w =
                if mass > 0.0 { columns.filter[i as usize] * rows.filter[j as usize] / mass } else { 0.0 };
            // (The mean weight, not this sample's: nonzero also where this sample is beyond the
            // radius but others of its pixel are not.)
            let value = l * w - beta * (w - mean_x[i as usize] * mean_y[j as usize]);
            film_splat::add_camera_cell(words, params, pixel, j * span + i, value, first);
            i += 1;
        }
        j += 1;
    }
    if cv {
        film_splat::add_to_camera_mean(words, params, pixel, l);
    }
}

/// The control variate's mean weights along one axis (`film_splat::control_variate`): for each of
/// the `count` (at most `SPAN`) pixels from `first` (window coordinates, as `axis_weights` counts
/// them), the mean of its filter weight over the sample's own pixel `own`, `film::axis_pixel_mean`
/// to the bit; zero for those outside the window. Adjacent pixels' integrals over `own` share an
/// end, and inside the window a pixel's mass is the frame's whole mass (`film::axis_window_mass`),
/// so a row of 5 (the gaussian's) takes 6 running sums instead of `axis_pixel_mean`'s 20: the
/// variate's cost on the Cornell box's `bdpt` pass was 8% with 20.
#[inline]
pub fn axis_means(
    tables: &[f32],
    params: &FrameParams,
    own: u32,
    (first, count): (i32, u32),
    x_axis: bool,
) -> [f32; SPAN] {
    let (crop, size) = film::rendered_axis(params, x_axis);
    let at = (crop + own) as f32;
    let mut means = [0.0f32; SPAN];
    if count == 0 {
        return means;
    }
    // The running sum at the far end of the first pixel's integral (`at + 1 − c`), then at each
    // pixel's near end (`at − c`), which is the next pixel's far end.
    let mut upper = film::axis_running_sum(tables, params, at + 1.0 - ((crop as i32 + first) as f32 + 0.5));
    let mut i = 0;
    while i < count && i < SPAN as u32 {
        let q = first + i as i32;
        let c = (crop as i32 + q) as f32 + 0.5;
        let lower = film::axis_running_sum(tables, params, at - c);
        if q >= 0 && q < size as i32 {
            let mass = film::axis_window_mass(tables, params, c, x_axis);
            if mass > 0.0 {
                means[i as usize] = (upper - lower) / mass;
            }
        }
        upper = lower;
        i += 1;
    }
    means
}

/// The share of the footprint's largest filter weight below which a pixel's splat is decided by
/// chance (`splat_footprint`). Mitsuba's default gaussian (stddev ½, radius 2) covers 16 pixels; with
/// 1/16 a splat reaches 6.4 of them on average and adds 0.2% to the footprint's sum of squared weights
/// as variance, 1/8 5.3 and 0.9% (averaged over positions uniform in the pixel).
pub const FOOTPRINT_FLOOR: f32 = 1.0 / 16.0;

/// Splats `value` times the filter's weight into each pixel of a footprint: the `count`×`count` (at
/// most `SPAN`) pixels from (`x0`, `y0`) in the window, the filter and its mass along each axis from
/// `axis_weights` (zero outside the window), the weight `fx·fy / (mx·my)` (`film::pixel_weight`).
/// A pixel whose weight is below `FOOTPRINT_FLOOR` of the footprint's largest (the product of the
/// axes' peaks) gets the floor's weight (its sign kept) with probability weight / floor, so its
/// expectation is unchanged: the atomics go where the filter's mass is (most of the footprint of a
/// gaussian is its tail), each pixel deciding by a hash of the rounding number `u` and its index.
/// One call of `splat::splat` in the loop, so the GPU inlines its atomics once.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn splat_footprint<W: AtomicWords>(
    words: &mut W,
    width: u32,
    (x0, y0): (i32, i32),
    x: &AxisWeights,
    y: &AxisWeights,
    count: (u32, u32),
    value: Rgb,
    u: f32,
) {
    let (columns, rows) = count;
    let floor = FOOTPRINT_FLOOR * x.peak * y.peak;
    let mut j = 0;
    while j < rows {
        let mut i = 0;
        while y.filter[j as usize] != 0.0 && i < columns {
            let mass = x.mass[i as usize] * y.mass[j as usize];
            if x.filter[i as usize] != 0.0 && mass > 0.0 {
                let w = x.filter[i as usize] * y.filter[j as usize] / mass;
                let pixel = (y0 + j as i32) as u32 * width + (x0 + i as i32) as u32;
                let kept = if w.abs() >= floor {
                    w
                } else if u32_to_unit_f32(hash2(u.to_bits(), pixel)) * floor < w.abs() {
                    if w < 0.0 {
                        -floor
                    } else {
                        floor
                    }
                } else {
                    0.0
                };
                if kept != 0.0 {
                    crate::splat::splat(words, pixel, value * kept, u);
                }
            }
            i += 1;
        }
        j += 1;
    }
}

/// The most pixels `axis_weights` covers along an axis: a light-tracing connection's footprint,
/// `floor(pos ± filter radius)` with the radius at most `MAX_REACH + 0.5`.
pub const SPAN: usize = (2 * MAX_REACH + 2) as usize;

/// A footprint's filter along one axis (`axis_weights`): each pixel's filter and mass, and the
/// largest |filter| / mass among them, so `splat_footprint` needs no pass of its own for the floor.
pub struct AxisWeights {
    pub filter: [f32; SPAN],
    pub mass: [f32; SPAN],
    pub peak: f32,
}

/// The filter at `pos` and its mass in the rendered window along one axis (`film::axis_pixel_weight`)
/// for the `count` (at most `SPAN`) pixels from `first`, counted from the window's start (`x_axis`:
/// columns, else rows); zero for those outside the window.
#[inline]
pub fn axis_weights(
    scene: &SceneView,
    params: &FrameParams,
    pos: f32,
    first: i32,
    count: u32,
    x_axis: bool,
) -> AxisWeights {
    let (crop, size) = film::rendered_axis(params, x_axis);
    let mut weights = AxisWeights { filter: [0.0f32; SPAN], mass: [0.0f32; SPAN], peak: 0.0 };
    let mut i = 0;
    while i < count && i < SPAN as u32 {
        let q = first + i as i32;
        if q >= 0 && q < size as i32 {
            let c = (crop + q as u32) as f32 + 0.5;
            let (a, b) = film::axis_pixel_weight(scene.tables, params, pos, c, x_axis);
            weights.filter[i as usize] = a;
            weights.mass[i as usize] = b;
            if b > 0.0 {
                weights.peak = weights.peak.max(a.abs() / b);
            }
        }
        i += 1;
    }
    weights
}

/// IBPT's camera half: `params.sample_count` camera paths of `pixel`, weighted against light tracing,
/// splatted into the pixel's own sums.
pub fn splat_camera_paths<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    words: &mut W,
) {
    let mut s = 0;
    while s < params.sample_count {
        let (mut sampler, film_sample, ray, density) =
            splatted_camera_sample(scene, params, pixel, params.sample_base + s);
        let l = path::li(scene, params, ray, &mut sampler, density);
        splat_camera_estimate(scene, params, pixel, &film_sample, l, s == 0, words);
        s += 1;
    }
}

/// BDPT's and VCM's first step of a pass: the light path of index `pixel` (one a pixel, the pass's
/// sample `params.sample_base`), its camera connections splatted into `words`, its vertices into its
/// slots of the light vertex cache (`slots`: the cache from the path's first slot, `pixel ·
/// MAX_LIGHT_VERTICES`, or its own slots).
pub fn trace_cached_light_path<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    slots: &mut bdpt::CacheSlots,
    words: &mut W,
) {
    let mut sampler = light_path_sampler(params, pixel, params.sample_base);
    let to_camera = ptracer::connects_to_camera(params, pixel, params.sample_base);
    bdpt::trace_light_path(scene, params, &mut sampler, words, slots, to_camera);
}

/// BDPT's and VCM's last step of a pass (after the light paths and, for VCM, the grid: `vcm_grid`):
/// the camera path of `pixel`'s sample `params.sample_base`, connected to its own light path's
/// vertices and merged with every light vertex within the radius, splatted into the pixel's own sums.
pub fn splat_cached_camera_path<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    cache: &[LightVertex],
    grid_words: &[u32],
    words: &mut W,
) {
    let (mut sampler, film_sample, ray, density) =
        splatted_camera_sample(scene, params, pixel, params.sample_base);
    let vertices = bdpt::CacheView { cache, base: pixel * bdpt::MAX_LIGHT_VERTICES };
    let grid = vcm_grid::GridView { cache, words: grid_words, grid: vcm_grid::Grid::of(params) };
    let l = bdpt::camera_path(scene, params, pixel, ray, &mut sampler, density, &vertices, &grid);
    // (One sample a pass: each writes its cells over the last pass's.)
    splat_camera_estimate(scene, params, pixel, &film_sample, l, true, words);
}

/// Traces the light paths of `params.sample_count` samples of path index `pixel` (one light path per
/// pixel and sample, whichever pixels they reach) and splats their camera connections into `words`
/// (weighted against the camera strategies under IBPT).
pub fn trace_light_paths<W: AtomicWords>(scene: &SceneView, params: &FrameParams, pixel: u32, words: &mut W) {
    if !traces_light_paths(params.integrator) {
        return;
    }
    let mut s = 0;
    while s < params.sample_count {
        // (A path not connected to the camera adds nothing here: it is not traced.)
        if ptracer::connects_to_camera(params, pixel, params.sample_base + s) {
            let mut sampler = light_path_sampler(params, pixel, params.sample_base + s);
            ptracer::trace(scene, params, &mut sampler, words);
        }
        s += 1;
    }
}

/// A number in [0, 1) for the `TILE`² tile of pixel (or path index) `index`, sample `sample` and
/// `stream`: what a GPU workgroup decides together, so that its invocations skip work together
/// rather than diverge (`ptracer::connects_to_camera`, `bdpt::connection_rate`). Drawn apart from the
/// paths' own numbers, so that a path is the same whichever way it goes.
#[inline]
pub(crate) fn tile_draw(params: &FrameParams, index: u32, sample: u32, stream: u32) -> f32 {
    let (x, y) = (index % params.width, index / params.width);
    let tile = (y / TILE) * params.width.div_ceil(TILE) + x / TILE;
    u32_to_unit_f32(hash2(hash2(params.seed ^ stream, sample), tile))
}

/// A share of `FrameParams` (`light_tracing_share`, `connection_rate`) in (0, 1]: 1 where it is 0,
/// 1 or more, or not a number.
#[inline]
pub(crate) fn share_in_unit(x: f32) -> f32 {
    if x > 0.0 && x < 1.0 {
        x
    } else {
        1.0
    }
}

/// The sampler of light path `index`'s sample `sample`.
#[inline]
fn light_path_sampler(params: &FrameParams, index: u32, sample: u32) -> Sampler {
    Sampler::new(params.seed ^ LIGHT_PATH_STREAM, index, sample)
}

/// Whether the camera entry point splats IBPT's camera paths rather than accumulating camera paths.
#[inline]
pub fn splats_camera_paths(scene: &SceneView, params: &FrameParams) -> bool {
    params.integrator == INTEGRATOR_IBPT && features::has(scene.features, features::LIGHT_TRACER)
}

/// Whether integrator `kind` runs the light vertex cache's passes (BDPT, VCM: light paths into the
/// cache, for VCM the grid, then camera paths) in place of the camera and light entry points, one
/// sample a pass.
#[inline]
pub fn traces_cached(kind: u32) -> bool {
    kind == INTEGRATOR_BDPT || kind == INTEGRATOR_VCM
}

/// Whether integrator `kind` merges (VCM), so that its passes build the grid.
#[inline]
pub fn merges(kind: u32) -> bool {
    kind == INTEGRATOR_VCM
}

/// Whether integrator `kind` runs the light entry point (`ptracer`, IBPT's light half; BDPT traces its
/// light paths beside the camera paths).
#[inline]
pub fn traces_light_paths(kind: u32) -> bool {
    kind == INTEGRATOR_PTRACER || kind == INTEGRATOR_IBPT
}

/// Whether integrator `kind` runs the camera entry point (everything but plain light tracing; BDPT and
/// VCM run their own, `traces_cached`).
#[inline]
pub fn traces_camera_paths(kind: u32) -> bool {
    kind != INTEGRATOR_PTRACER
}

pub use crate::layout::splats;

/// A pixel's accumulator with one dispatch's sums added.
#[inline]
pub fn accumulated(a: PixelAccum, sums: &PixelSums, sample_count: u32) -> PixelAccum {
    PixelAccum {
        sum: [a.sum[0] + sums.sum.x, a.sum[1] + sums.sum.y, a.sum[2] + sums.sum.z],
        count: a.count + sample_count as f32,
        sum_sq: [a.sum_sq[0] + sums.sum_sq.x, a.sum_sq[1] + sums.sum_sq.y, a.sum_sq[2] + sums.sum_sq.z],
        invalid: a.invalid + sums.invalid as f32,
    }
}

/// The local shading frame at `sp` for a ray arriving along `dir`, the geometric normal on the same
/// side as the frame's, the outgoing direction in the frame, and the tilt of a normal or bump map
/// (`bsdf::perturb`; inactive without one) for `Bsdf::new`, as one `Shading`. Two-sided materials
/// seen from behind are shaded as if from the front. In scenes with `features::TANGENT_FRAMES` the
/// frame's tangent follows dp/du.
pub fn shading_frame(
    scene: &SceneView,
    material: &Material,
    prim: &Primitive,
    hit: &Hit,
    sp: &SurfacePoint,
    dir: Vec3,
) -> Shading {
    let two_sided = material.flags & MATERIAL_TWO_SIDED != 0;
    let tangent_frames = features::has(scene.features, features::TANGENT_FRAMES);
    let dp_du = if tangent_frames {
        let (dp_du, dp_dv) = crate::instancing::tangents(scene, prim, hit, sp);
        if material.perturb != 0 {
            let map = perturb::MapContext { textures: scene.textures, tables: scene.tables, dp_du, dp_dv };
            return perturb::shading_frame(material, &map, sp, dir);
        }
        dp_du
    } else {
        Vec3::ZERO
    };
    let (mut ns, mut ng) = (sp.ns, sp.ng);
    if two_sided && ng.dot(dir) > 0.0 {
        ns = -ns;
        ng = -ng;
    }
    // In a scene with anisotropic roughness every frame's tangent follows dp/du, as Mitsuba's
    // (`initialize_sh_frame`): the roughness along u is `alpha_u` (isotropic models do not see it).
    let frame = if tangent_frames { Frame::from_tangent(ns, dp_du) } else { Frame::from_normal(ns) };
    let wo = frame.to_local(-dir);
    Shading::new(frame, ng, wo, Perturbation::NONE)
}

/// A path's wavelength before it has one (`wavelength`: drawn at the first dispersive vertex).
pub const NO_WAVELENGTH: f32 = 0.0;

/// Dispersion at a vertex whose material is `material`: in a scene with dispersive materials, a path
/// that reaches one draws its wavelength there, unless it already carries one (`lambda`; the random
/// number from dimension `dim`, one no other decision of the vertex uses), and the material refracts
/// at that wavelength. Returns the factor of the path's throughput: `c(λ)/p(λ)` where a wavelength is
/// drawn, else one.
#[inline]
pub fn disperse(
    scene: &SceneView,
    params: &FrameParams,
    material: &mut Material,
    lambda: &mut f32,
    sampler: &Sampler,
    dim: u32,
) -> Rgb {
    let mut factor = Rgb::ONE;
    if features::has(scene.features, features::DISPERSION) && wavelength::disperses(material) {
        if *lambda == NO_WAVELENGTH {
            let mut s = *sampler;
            s.set_dimension(dim);
            let ws = wavelength::sample(scene.tables, params.wavelength_table, s.next_1d());
            *lambda = ws.lambda;
            factor = ws.weight;
        }
        material.eta = wavelength::eta_at(material, *lambda);
    }
    factor
}
