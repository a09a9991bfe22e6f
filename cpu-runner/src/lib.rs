//! The CPU backend: the kernel's per-pixel function, called natively on every core.
use caustic_kernel::film_splat::{gather, resolved, words_per_pixel, CellReader, FilmCells};
use caustic_kernel::integrator::bdpt::{CacheSlots, LightVertex, MAX_LIGHT_VERTICES};
use caustic_kernel::integrator::{
    accumulated, merges, render_pixel, splat_cached_camera_path, splat_camera_paths, splats_camera_paths,
    trace_cached_light_path, trace_light_paths, traces_light_paths, vcm_grid, SceneView,
};
use caustic_kernel::layout::{square_scale, FrameParams, PixelAccum};
use caustic_kernel::splat::AtomicWords;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// Adds `params.sample_count` samples to every pixel of `accum` (one `PixelAccum` per pixel), exactly
/// as one GPU dispatch does; the path tracer by its regenerating loop or its plain one (the same
/// image either way: `render_pixel`).
pub fn render_pass(scene: &SceneView, params: &FrameParams, accum: &mut [PixelAccum], regenerate: bool) {
    let pixels = (params.width * params.height) as usize;
    assert_eq!(accum.len(), pixels, "accumulation buffer does not match the image size");
    tiles(accum, params.width as usize, 1).into_par_iter().for_each(|tile| {
        tile.each_pixel(params.width, |pixel, slot| {
            // (No cells: the film does not splat in this pass.)
            let sums = render_pixel(scene, params, pixel, regenerate, &mut PixelCells(&mut []));
            slot[0] = accumulated(slot[0], &sums, params.sample_count);
        });
    });
}

/// One TILE × TILE tile of the image (cut short at its right and bottom edges): its rows' slices of
/// a per-pixel buffer, `per_pixel` values a pixel.
struct Tile<'a, T> {
    x0: usize,
    y0: usize,
    per_pixel: usize,
    rows: Vec<&'a mut [T]>,
}

impl<T> Tile<'_, T> {
    /// Calls `f` with each pixel's index and values, row by row: neighbouring pixels' rays one
    /// after the other, as the GPU's workgroups run them.
    fn each_pixel(mut self, width: u32, mut f: impl FnMut(u32, &mut [T])) {
        let per_pixel = self.per_pixel;
        for (dy, row) in self.rows.iter_mut().enumerate() {
            for (dx, values) in row.chunks_mut(per_pixel).enumerate() {
                f(((self.y0 + dy) * width as usize + self.x0 + dx) as u32, values);
            }
        }
    }
}

/// A row-major per-pixel buffer (`per_pixel` values a pixel) cut into the image's tiles, the work
/// items of a pass. Tiles, not bands of TILE rows: a 256-pixel-high image has only 32 bands, too
/// few for 16 threads to share evenly (the Cornell box ran at 64% of linear speed-up on 16 threads
/// with bands; BENCHMARKS.md, "CPU threads").
fn tiles<T: Send>(buffer: &mut [T], width: usize, per_pixel: usize) -> Vec<Tile<'_, T>> {
    let tile = caustic_kernel::layout::TILE as usize;
    let across = width.div_ceil(tile);
    let mut out: Vec<Tile<'_, T>> = Vec::new();
    for (y, row) in buffer.chunks_mut(width * per_pixel).enumerate() {
        if y % tile == 0 {
            out.extend((0..across).map(|i| Tile { x0: i * tile, y0: y, per_pixel, rows: Vec::new() }));
        }
        let band = out.len() - across;
        for (i, segment) in row.chunks_mut(tile * per_pixel).enumerate() {
            out[band + i].rows.push(segment);
        }
    }
    out
}

/// One pixel's cells of the splatting film (its slots, consecutive).
struct PixelCells<'a>(&'a mut [f32]);

impl CellReader for PixelCells<'_> {
    #[inline]
    fn get(&self, _: &FrameParams, _: u32, slot: u32) -> f32 {
        self.0[slot as usize]
    }
}

impl FilmCells for PixelCells<'_> {
    #[inline]
    fn set(&mut self, _: &FrameParams, _: u32, slot: u32, value: f32) {
        self.0[slot as usize] = value;
    }
}

/// Every pixel's cells, pixel after pixel, `stride` slots each.
struct AllCells<'a> {
    values: &'a [f32],
    stride: usize,
}

impl CellReader for AllCells<'_> {
    #[inline]
    fn get(&self, _: &FrameParams, pixel: u32, slot: u32) -> f32 {
        self.values[pixel as usize * self.stride + slot as usize]
    }
}

/// A pass of the splatting film (`caustic_kernel::film_splat`), exactly as the GPU's `render` and
/// `resolve` dispatches run it: every pixel's samples into the cells it owns, then every pixel's
/// sums gathered from its neighbourhood into `accum`. `cells` is scratch kept between passes.
pub fn film_pass(
    scene: &SceneView,
    params: &FrameParams,
    accum: &mut [PixelAccum],
    regenerate: bool,
    cells: &mut Vec<f32>,
) {
    let pixels = (params.width * params.height) as usize;
    assert_eq!(accum.len(), pixels, "accumulation buffer does not match the image size");
    let stride = words_per_pixel(params) as usize;
    cells.resize(pixels * stride, 0.0);
    tiles(cells, params.width as usize, stride).into_par_iter().for_each(|tile| {
        tile.each_pixel(params.width, |pixel, own| {
            render_pixel(scene, params, pixel, regenerate, &mut PixelCells(own));
        });
    });
    let all = AllCells { values: cells, stride };
    let q = square_scale(params);
    accum.par_iter_mut().enumerate().for_each(|(pixel, a)| {
        let g = gather(&all, params, pixel as u32 % params.width, pixel as u32 / params.width);
        *a = resolved(*a, &g, q);
    });
}

/// The CPU's splat words: `u32` atomics shared by every thread.
struct CpuWords<'a>(&'a [AtomicU32]);

impl AtomicWords for CpuWords<'_> {
    #[inline]
    fn fetch_add(&mut self, index: u32, value: u32) -> u32 {
        // Relaxed: the sums are read only after the pass has joined every thread.
        self.0[index as usize].fetch_add(value, Ordering::Relaxed)
    }

    #[inline]
    fn exchange(&mut self, index: u32, value: u32) -> u32 {
        self.0[index as usize].swap(value, Ordering::Relaxed)
    }

    #[inline]
    fn load(&self, index: u32) -> u32 {
        self.0[index as usize].load(Ordering::Relaxed)
    }

    #[inline]
    fn store(&mut self, index: u32, value: u32) {
        self.0[index as usize].store(value, Ordering::Relaxed)
    }
}

/// The splat words of a pass (`caustic_kernel::splat` layout, then the camera cells:
/// `film_splat::camera_cells`), kept between passes as the GPU keeps its `SPLAT` buffer: resolving a
/// pass clears the light words and the next pass writes every camera cell over, while the camera
/// estimates' persisting words (`film_splat::camera_mean`) carry on. Zeroed where their size changes.
fn pass_words<'a>(words: &'a mut Vec<u32>, params: &FrameParams) -> &'a [AtomicU32] {
    let len = (params.width * params.height * words_per_pixel(params)) as usize;
    if words.len() != len {
        words.clear();
        words.resize(len, 0);
    }
    as_atomic(words)
}

/// Traces `params.sample_count` light paths per pixel (IBPT: and camera paths), exactly as the GPU's
/// dispatches do, into `words` (`pass_words`) for the host to resolve.
pub fn light_pass(scene: &SceneView, params: &FrameParams, words: &mut Vec<u32>) {
    let pixels = params.width * params.height;
    let words = pass_words(words, params);
    let camera_half = splats_camera_paths(scene, params);
    let light_half = traces_light_paths(params.integrator);
    (0..pixels).into_par_iter().for_each(|pixel| {
        let mut words = CpuWords(words);
        if camera_half {
            splat_camera_paths(scene, params, pixel, &mut words);
        }
        if light_half {
            trace_light_paths(scene, params, pixel, &mut words);
        }
    });
}

/// BDPT's and VCM's memory kept between passes: the light vertex cache (`MAX_LIGHT_VERTICES` slots a
/// pixel) and VCM's hash grid words (`caustic_kernel::integrator::vcm_grid`).
#[derive(Default)]
pub struct CacheScratch {
    cache: Vec<LightVertex>,
    grid: Vec<u32>,
}

impl CacheScratch {
    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.cache.len() * std::mem::size_of::<LightVertex>() + self.grid.len() * 4
    }
}

/// One BDPT or VCM sample a pixel (`params.sample_base`; VCM's radius `params.merge_radius`), exactly
/// as the GPU's dispatches run it: every pixel's light path into the cache (its camera connections
/// splatted), for VCM the grid linked over the cache, then every pixel's camera
/// path, into `words` (`pass_words`) for the host to resolve.
pub fn cached_pass(
    scene: &SceneView,
    params: &FrameParams,
    scratch: &mut CacheScratch,
    words: &mut Vec<u32>,
) {
    let pixels = params.width * params.height;
    let words = pass_words(words, params);
    let grid = vcm_grid::Grid::of(params);
    scratch.cache.resize(vcm_grid::slots(params) as usize, LightVertex::EMPTY);
    scratch.cache.par_chunks_mut(MAX_LIGHT_VERTICES as usize).enumerate().for_each(|(pixel, own)| {
        let mut slots = CacheSlots { cache: own, base: 0 };
        trace_cached_light_path(scene, params, pixel as u32, &mut slots, &mut CpuWords(words));
    });
    scratch.grid.clear();
    let cache = &scratch.cache;
    if merges(params.integrator) {
        scratch.grid.resize(grid.words() as usize, 0);
        let atomic = as_atomic(&mut scratch.grid);
        (0..cache.len() as u32).into_par_iter().for_each(|slot| {
            vcm_grid::link(cache, &grid, slot, &mut CpuWords(atomic));
        });
    }
    let grid_words = &scratch.grid;
    (0..pixels).into_par_iter().for_each(|pixel| {
        splat_cached_camera_path(scene, params, pixel, cache, grid_words, &mut CpuWords(words));
    });
}

/// `words` as atomics, for the grid's step that links vertices into it from every thread.
fn as_atomic(words: &mut [u32]) -> &[AtomicU32] {
    // SAFETY: `AtomicU32` has the size, alignment and bit validity of `u32`, and the exclusive borrow
    // makes the atomics the only access for as long as they live (what the unstable
    // `AtomicU32::from_mut_slice` does).
    unsafe { &*(words as *mut [u32] as *const [AtomicU32]) }
}
