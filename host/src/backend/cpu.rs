//! The CPU backend: the kernel linked natively, over all cores.
use super::Backend;
use crate::buffers::SceneBuffers;
use crate::film::Accumulation;
use anyhow::Result;
use caustic_kernel::layout::FrameParams;

pub struct CpuBackend {
    buffers: SceneBuffers,
    accum: Accumulation,
}

impl CpuBackend {
    pub fn new(buffers: SceneBuffers) -> Self {
        let pixels = (buffers.params.width * buffers.params.height) as usize;
        let splatted = caustic_kernel::integrator::splats(buffers.params.integrator);
        CpuBackend { buffers, accum: Accumulation::new(pixels, splatted) }
    }
}

impl Backend for CpuBackend {
    fn describe(&self) -> String {
        format!("cpu ({} threads)", rayon::current_num_threads())
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        if self.accum.batches.is_some() {
            let words = caustic_cpu::light_pass(&self.buffers.view(), params);
            self.accum.add_splats(&words, params.sample_count);
        } else {
            caustic_cpu::render_pass(&self.buffers.view(), params, &mut self.accum.pixels);
        }
        Ok(())
    }

    fn read_accum(&mut self) -> Result<Accumulation> {
        Ok(self.accum.clone())
    }

    fn write_accum(&mut self, accum: &Accumulation) -> Result<()> {
        anyhow::ensure!(
            accum.pixels.len() == self.accum.pixels.len()
                && accum.batches.is_some() == self.accum.batches.is_some(),
            "accumulation buffer of {} pixels ({}), expected {}",
            accum.pixels.len(),
            if accum.batches.is_some() { "splatted" } else { "per sample" },
            self.accum.pixels.len()
        );
        self.accum = accum.clone();
        Ok(())
    }
}
