//! The CPU backend: the kernel linked natively, over all cores.
use super::Backend;
use crate::buffers::SceneBuffers;
use anyhow::Result;
use caustic_kernel::layout::{FrameParams, PixelAccum};

pub struct CpuBackend {
    buffers: SceneBuffers,
    accum: Vec<PixelAccum>,
}

impl CpuBackend {
    pub fn new(buffers: SceneBuffers) -> Self {
        let pixels = (buffers.params.width * buffers.params.height) as usize;
        CpuBackend { buffers, accum: vec![PixelAccum::default(); pixels] }
    }
}

impl Backend for CpuBackend {
    fn describe(&self) -> String {
        format!("cpu ({} threads)", rayon::current_num_threads())
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        caustic_cpu::render_pass(&self.buffers.view(), params, &mut self.accum);
        Ok(())
    }

    fn read_accum(&mut self) -> Result<Vec<PixelAccum>> {
        Ok(self.accum.clone())
    }

    fn write_accum(&mut self, accum: &[PixelAccum]) -> Result<()> {
        anyhow::ensure!(
            accum.len() == self.accum.len(),
            "accumulation buffer of {} pixels, expected {}",
            accum.len(),
            self.accum.len()
        );
        self.accum.copy_from_slice(accum);
        Ok(())
    }
}
