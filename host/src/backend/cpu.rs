//! The CPU backend: the kernel linked natively, over all cores, into f32 sums that fold into the
//! host's f64 totals on the GPU's schedule (`accumulation::Folding`).
use super::accumulation::{Accumulation, Folding};
use super::device::Backend;
use crate::prepare::buffers::SceneBuffers;
use anyhow::Result;
use caustic_kernel::layout::{FrameParams, PixelAccum, SceneView};

/// Whether the CPU walks a 4-wide BVH (`crate::prepare::wide_bvh`, the default) or the scene's BVH2
/// (`CAUSTIC_CPU_BVH=2`, for A/B timings and tests).
pub fn wide_requested() -> Result<bool> {
    match std::env::var("CAUSTIC_CPU_BVH").as_deref() {
        Err(_) | Ok("4") => Ok(true),
        Ok("2") => Ok(false),
        Ok(other) => anyhow::bail!("CAUSTIC_CPU_BVH must be 2 or 4, not {other:?}"),
    }
}

pub struct CpuBackend {
    /// The scene's buffers, with the nodes widened where `wide` (in place: no second tree in memory).
    buffers: SceneBuffers,
    wide: bool,
    /// The f32 sums the kernel adds to, as the GPU's accumulation buffer.
    device: Vec<PixelAccum>,
    folding: Folding,
    /// The path tracer's loop (`path_loop`): the regenerating one only where `CAUSTIC_PATH_LOOP` asks
    /// for it; a CPU core has no warp for it to keep busy.
    regenerate: bool,
    /// The splatting film's cells (`caustic_kernel::film_splat`), kept between passes.
    cells: Vec<f32>,
    /// BDPT's and VCM's light vertex cache and VCM's hash grid, kept between passes.
    cache: caustic_cpu::CacheScratch,
    /// The splatting integrators' words, kept between passes (`caustic_cpu::light_pass`).
    splat_words: Vec<u32>,
}

impl CpuBackend {
    pub fn new(buffers: SceneBuffers) -> Self {
        let pixels = (buffers.params.width * buffers.params.height) as usize;
        let batched = super::accumulation::batch_means(&buffers.params);
        let folding = Folding::new(pixels, batched, buffers.params.square_scale_log2);
        use super::path_loop::{requested, PathLoop, Request};
        let regenerate = requested().ok() == Some(Request::Fixed(PathLoop::Regenerate));
        let mut buffers = buffers;
        // Instances keep their two-level BVH2 (`instancing`), and a tree too deep for the wide
        // traversal's stack its BVH2.
        let widened = (wide_requested().unwrap_or(true)
            && !caustic_kernel::features::has(buffers.features, caustic_kernel::features::INSTANCING))
        .then(|| crate::prepare::wide_bvh::widen(&buffers.nodes))
        .flatten();
        let wide = widened.is_some();
        if let Some(nodes) = widened {
            buffers.nodes = nodes;
        }
        let device = vec![PixelAccum::default(); pixels];
        CpuBackend {
            buffers,
            wide,
            device,
            folding,
            regenerate,
            cells: Vec::new(),
            cache: Default::default(),
            splat_words: Vec::new(),
        }
    }

    fn view(buffers: &SceneBuffers, wide: bool) -> SceneView<'_> {
        SceneView { wide_bvh: wide, ..buffers.view() }
    }

    fn fold(&mut self) {
        self.folding.fold(&self.device);
        self.device.fill(PixelAccum::default());
    }
}

impl Backend for CpuBackend {
    fn describe(&self) -> String {
        let bvh = if self.wide { "4-wide BVH" } else { "BVH2" };
        format!("cpu ({} threads, {bvh})", rayon::current_num_threads())
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        let view = Self::view(&self.buffers, self.wide);
        if caustic_kernel::integrator::traces_cached(params.integrator) {
            // One pass of the light vertex cache (light paths, VCM's grid, camera paths) per sample,
            // each with VCM's radius for it.
            for i in 0..params.sample_count {
                let iteration = params.sample_base + i;
                let one = FrameParams {
                    sample_base: iteration,
                    sample_count: 1,
                    merge_radius: self.buffers.merge_radius(iteration),
                    ..*params
                };
                caustic_cpu::cached_pass(&view, &one, &mut self.cache, &mut self.splat_words);
                fold_splats(&mut self.device, &mut self.splat_words, &one);
            }
        } else if params.film_reach != 0 && !caustic_kernel::integrator::splats(params.integrator) {
            caustic_cpu::film_pass(&view, params, &mut self.device, self.regenerate, &mut self.cells);
        } else if caustic_kernel::integrator::splats(params.integrator) {
            caustic_cpu::light_pass(&view, params, &mut self.splat_words);
            fold_splats(&mut self.device, &mut self.splat_words, params);
        } else {
            caustic_cpu::render_pass(&view, params, &mut self.device, self.regenerate);
        }
        if self.folding.passed(params.sample_count) {
            self.fold();
        }
        Ok(())
    }

    fn read_accum(&mut self) -> Result<Accumulation> {
        self.fold();
        Ok(self.folding.total.clone())
    }

    fn write_accum(&mut self, accum: &Accumulation) -> Result<()> {
        self.folding.replace(accum)?;
        self.device.fill(PixelAccum::default());
        Ok(())
    }
}

/// Folds a splatting pass's words (`caustic_kernel::splat` layout, `SPLAT_STRIDE` a pixel, then the
/// camera cells: `film_splat::camera_cells`) into the accumulator, as the GPU's `entry::resolve` does:
/// `params.sample_count` samples a pixel.
fn fold_splats(device: &mut [PixelAccum], words: &mut [u32], params: &FrameParams) {
    use caustic_kernel::film_splat::resolved_splats;
    use caustic_kernel::splat::OwnWords;
    let q = caustic_kernel::layout::square_scale(params);
    let mut words = OwnWords(words);
    for (pixel, a) in device.iter_mut().enumerate() {
        let (x, y) = (pixel as u32 % params.width, pixel as u32 / params.width);
        *a = resolved_splats(*a, &mut words, params, x, y, q);
    }
}
