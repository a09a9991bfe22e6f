//! Rendering backends: the same kernel on the GPU (wgpu compute) or the CPU (rayon).
pub mod cpu;
pub mod gpu;
pub mod limits;
pub mod runtime_dir;

use crate::film::Accumulation;
use anyhow::Result;
use caustic_kernel::layout::FrameParams;

/// A device that can add samples to an accumulation buffer (one `PixelAccum` per pixel). Light
/// tracing splats into fixed-point sums that the backend resolves into it after every pass.
pub trait Backend {
    /// A short description: backend and adapter.
    fn describe(&self) -> String;
    /// Adds `params.sample_count` samples per pixel, starting at sample `params.sample_base`.
    fn pass(&mut self, params: &FrameParams) -> Result<()>;
    /// A copy of the accumulation buffer.
    fn read_accum(&mut self) -> Result<Accumulation>;
    /// Replaces the accumulation buffer (resuming from a checkpoint); `accum` has its exact size.
    fn write_accum(&mut self, accum: &Accumulation) -> Result<()>;
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendChoice {
    /// The GPU when a hardware adapter exists, else the CPU.
    Auto,
    /// wgpu (Vulkan); accepts software adapters such as lavapipe.
    Gpu,
    /// The rayon CPU runner.
    Cpu,
}

/// Creates the chosen backend for a scene's buffers.
pub fn create(choice: BackendChoice, buffers: &crate::buffers::SceneBuffers) -> Result<Box<dyn Backend>> {
    let (w, h) = (buffers.params.width, buffers.params.height);
    crate::memory::check(
        crate::memory::render_need(buffers),
        crate::memory::available(),
        &format!("a {w}×{h} render"),
    )?;
    match choice {
        BackendChoice::Cpu => Ok(Box::new(cpu::CpuBackend::new(buffers.clone()))),
        BackendChoice::Gpu => Ok(Box::new(gpu::GpuBackend::new(buffers, false)?)),
        BackendChoice::Auto => match gpu::GpuBackend::new(buffers, true) {
            Ok(g) => Ok(Box::new(g)),
            Err(e) if e.is::<limits::OverLimit>() => {
                eprintln!("warning: {e:#}; rendering on the CPU");
                Ok(Box::new(cpu::CpuBackend::new(buffers.clone())))
            }
            Err(_) => Ok(Box::new(cpu::CpuBackend::new(buffers.clone()))),
        },
    }
}
