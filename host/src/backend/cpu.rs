//! The CPU backend: the kernel linked natively, over all cores, into f32 sums that fold into the
//! host's f64 totals on the GPU's schedule (`film::Folding`).
use super::Backend;
use crate::buffers::SceneBuffers;
use crate::film::{Accumulation, Folding};
use anyhow::Result;
use caustic_kernel::layout::{FrameParams, PixelAccum};

pub struct CpuBackend {
    buffers: SceneBuffers,
    /// The f32 sums the kernel adds to, as the GPU's accumulation buffer.
    device: Vec<PixelAccum>,
    folding: Folding,
    /// The path tracer's loop (`path_loop`): the regenerating one only where `CAUSTIC_PATH_LOOP` asks
    /// for it; a CPU core has no warp for it to keep busy.
    regenerate: bool,
}

impl CpuBackend {
    pub fn new(buffers: SceneBuffers) -> Self {
        let pixels = (buffers.params.width * buffers.params.height) as usize;
        let splatted = caustic_kernel::integrator::splats(buffers.params.integrator);
        let folding = Folding::new(pixels, splatted, buffers.params.square_scale_log2);
        use super::path_loop::{requested, PathLoop, Request};
        let regenerate = requested().ok() == Some(Request::Fixed(PathLoop::Regenerate));
        CpuBackend { buffers, device: vec![PixelAccum::default(); pixels], folding, regenerate }
    }

    fn fold(&mut self) {
        self.folding.fold(&self.device);
        self.device.fill(PixelAccum::default());
    }
}

impl Backend for CpuBackend {
    fn describe(&self) -> String {
        format!("cpu ({} threads)", rayon::current_num_threads())
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        if self.folding.total.batches.is_some() {
            use caustic_kernel::splat::{resolved, SPLAT_STRIDE};
            let words = caustic_cpu::light_pass(&self.buffers.view(), params);
            let q = caustic_kernel::layout::square_scale(params);
            for (px, w) in self.device.iter_mut().zip(words.chunks_exact(SPLAT_STRIDE as usize)) {
                *px = resolved(*px, w.try_into().expect("a pixel's words"), params.sample_count, q);
            }
        } else {
            caustic_cpu::render_pass(&self.buffers.view(), params, &mut self.device, self.regenerate);
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
