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

/// The largest render a stand-in takes, in samples per thread of its own: one lent H200's host
/// (BENCHMARKS.md, "First image of a new scene beside Mitsuba"; 14 stand-in threads, every cache
/// cold, 64 spp) gave the Cornell box's 4.2 Msamples (256×256) its image 0.5 s sooner with a
/// stand-in than on the GPU alone (it rendered all of it before the GPU's 1-1.4 s build ended),
/// and the 960×720 scenes' 44 Msamples theirs 0.3-1.5 s later on three of four: their GPU build
/// (2-4 s) ran slower beside the stand-in than what the stand-in rendered meanwhile saved.
const SAMPLES_PER_THREAD: u64 = 1_000_000;

/// The stand-in's threads: all the cores but `LEFT_TO_THE_BUILD`.
fn threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    cores.saturating_sub(LEFT_TO_THE_BUILD).max(1)
}

/// Whether a stand-in is worth starting for a render of `samples` samples (pixels × spp).
pub fn worth_it(samples: u64) -> bool {
    samples <= threads() as u64 * SAMPLES_PER_THREAD
}

pub struct StandIn {
    cpu: CpuBackend,
    threads: rayon::ThreadPool,
}

impl StandIn {
    pub fn new(buffers: SceneBuffers) -> Result<Self> {
        let threads = rayon::ThreadPoolBuilder::new()
            .num_threads(threads())
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
