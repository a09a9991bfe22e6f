//! The CPU backend as a GPU's stand-in while the GPU's pipelines are built (`pool::Pool::starting`):
//! it renders on a thread pool of its own that leaves two cores free, since the build runs beside it
//! on the host (`backend::prune` prunes the path loops on threads of its own, and the driver compiles
//! on others): on the global pool it would take every core and slow the build it stands in for.
use super::accumulation::Accumulation;
use super::cpu::CpuBackend;
use super::device::Backend;
use crate::prepare::buffers::SceneBuffers;
use anyhow::Result;
use caustic_kernel::layout::FrameParams;

/// Cores left to the build beside the stand-in.
const LEFT_TO_THE_BUILD: usize = 2;

pub struct StandIn {
    cpu: CpuBackend,
    threads: rayon::ThreadPool,
}

impl StandIn {
    pub fn new(buffers: SceneBuffers) -> Result<Self> {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let threads = rayon::ThreadPoolBuilder::new()
            .num_threads(cores.saturating_sub(LEFT_TO_THE_BUILD).max(1))
            .thread_name(|i| format!("caustic-stand-in-{i}"))
            .build()?;
        Ok(StandIn { cpu: CpuBackend::new(buffers), threads })
    }
}

impl Backend for StandIn {
    fn describe(&self) -> String {
        self.threads.install(|| self.cpu.describe())
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        let cpu = &mut self.cpu;
        self.threads.install(|| cpu.pass(params))
    }

    fn read_accum(&mut self) -> Result<Accumulation> {
        self.cpu.read_accum()
    }

    fn write_accum(&mut self, accum: &Accumulation) -> Result<()> {
        self.cpu.write_accum(accum)
    }
}
