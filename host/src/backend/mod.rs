//! Rendering backends: the same kernel on the GPU (wgpu compute) or the CPU (rayon), and several
//! GPUs as one backend (`pool`), all of them a `Backend` (`device`). This module picks and creates
//! one for a render (`create_on`, `create_starting`).
//!
//! Uses `prepare` (the buffers it renders) and `system` (the machine's memory); its tests load
//! scenes (`load`).
pub mod accumulation;
pub mod cpu;
pub mod device;
pub mod gpu;
pub mod kernel_stats;
pub mod limits;
pub mod memory;
pub mod module_cache;
pub mod path_loop;
pub mod pool;
pub mod prune;
pub mod readback;
pub mod runtime_dir;
pub mod schedule;
pub mod spirv;
pub mod stand_in;
pub mod step_times;
pub mod variant;

use accumulation::Accumulation;
use anyhow::{bail, Result};
pub use device::Backend;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendChoice {
    /// The GPU when a hardware adapter exists, else the CPU. The `render` command starts on the CPU
    /// while the GPU's pipelines are built (`create_starting`).
    Auto,
    /// wgpu (Vulkan); accepts software adapters such as lavapipe.
    Gpu,
    /// The rayon CPU runner.
    Cpu,
}

/// Which GPUs to render on (`--gpus`): every hardware adapter, the first N, or adapters by index
/// in `gpu::adapters()`'s order (an index may repeat: two devices on one adapter).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum GpuSelection {
    #[default]
    All,
    First(usize),
    List(Vec<usize>),
}

impl std::str::FromStr for GpuSelection {
    type Err = String;
    /// `all`, `N` (the first N adapters) or a comma-separated list of indices with at least two
    /// entries or a trailing comma (`0,1`, `1,`).
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("'{s}' is not all, a count or a comma-separated list of adapter indices");
        if s == "all" {
            return Ok(GpuSelection::All);
        }
        if !s.contains(',') {
            return match s.parse::<usize>() {
                Ok(0) => Err("--gpus 0: at least one GPU is needed (use --backend cpu for none)".into()),
                Ok(n) => Ok(GpuSelection::First(n)),
                Err(_) => Err(bad()),
            };
        }
        let list: Result<Vec<usize>, _> =
            s.split(',').filter(|p| !p.is_empty()).map(|p| p.trim().parse::<usize>()).collect();
        match list {
            Ok(l) if !l.is_empty() => Ok(GpuSelection::List(l)),
            _ => Err(bad()),
        }
    }
}

/// The adapter indices `selection` names among adapters of these types (best first), or why not.
/// `All` and `First` take hardware adapters; with none, `All` takes the best software one unless
/// `hardware_only`.
pub fn resolve_gpus(
    selection: &GpuSelection,
    adapters: &[(String, wgpu::DeviceType)],
    hardware_only: bool,
) -> Result<Vec<usize>> {
    let listing = || {
        let lines: Vec<String> =
            adapters.iter().enumerate().map(|(i, (name, ty))| format!("  {i}: {name} ({ty:?})")).collect();
        if lines.is_empty() {
            "no Vulkan adapter found (install a Vulkan driver, e.g. mesa-vulkan-drivers for lavapipe)".into()
        } else {
            format!("the Vulkan adapters are:\n{}", lines.join("\n"))
        }
    };
    let hardware: Vec<usize> =
        (0..adapters.len()).filter(|&i| adapters[i].1 != wgpu::DeviceType::Cpu).collect();
    let usable =
        if hardware.is_empty() && !hardware_only && !adapters.is_empty() { vec![0] } else { hardware };
    match selection {
        GpuSelection::All if usable.is_empty() => bail!("no hardware GPU; {}", listing()),
        GpuSelection::All => Ok(usable),
        GpuSelection::First(n) if *n > usable.len() => {
            bail!("--gpus {n}: only {} suitable GPU(s); {}", usable.len(), listing())
        }
        GpuSelection::First(n) => Ok(usable[..*n].to_vec()),
        GpuSelection::List(list) => match list.iter().find(|&&i| i >= adapters.len()) {
            Some(i) => bail!("--gpus: no adapter {i}; {}", listing()),
            None => Ok(list.clone()),
        },
    }
}

/// Creates the chosen backend for a scene's buffers: every GPU `gpus` selects (several become one
/// `pool::Pool`), or the CPU.
pub fn create_on(
    choice: BackendChoice,
    gpus: &GpuSelection,
    buffers: &crate::prepare::buffers::SceneBuffers,
) -> Result<Box<dyn Backend + Send>> {
    checked(buffers)?;
    let cpu = || -> Box<dyn Backend + Send> { Box::new(cpu::CpuBackend::new(buffers.clone())) };
    let hardware_only = match choice {
        BackendChoice::Cpu => return Ok(cpu()),
        BackendChoice::Gpu => false,
        BackendChoice::Auto => true,
    };
    let indices = match resolve_gpus(gpus, &gpu::adapter_types(), hardware_only) {
        Ok(i) => i,
        // Auto falls back to the CPU only when it was not asked for particular GPUs.
        Err(_) if choice == BackendChoice::Auto && *gpus == GpuSelection::All => return Ok(cpu()),
        Err(e) => return Err(e),
    };
    let mut devices: Vec<Box<dyn Backend + Send>> = Vec::with_capacity(indices.len());
    for i in indices {
        match gpu::GpuBackend::on_adapter(buffers, i) {
            Ok(g) => devices.push(Box::new(g)),
            // A scene this GPU cannot hold: `auto` renders it on the CPU.
            Err(e) if choice == BackendChoice::Auto && e.is::<limits::OverLimit>() => {
                eprintln!("warning: {e:#}; rendering on the CPU");
                return Ok(cpu());
            }
            Err(e) => return Err(e),
        }
    }
    if devices.len() == 1 {
        return Ok(devices.pop().expect("one device"));
    }
    Ok(Box::new(pool::Pool::new(devices, empty(buffers))?))
}

/// Checks what every backend needs before it is built: the render's memory on the host (returned,
/// in bytes), and the environment's settings (a bad CAUSTIC_PATH_LOOP, CAUSTIC_WORKGROUP or
/// CAUSTIC_CPU_BVH is an error on every backend).
fn checked(buffers: &crate::prepare::buffers::SceneBuffers) -> Result<u64> {
    let need = memory::render_need(buffers);
    let (w, h) = (buffers.params.width, buffers.params.height);
    crate::system::memory::check(need, crate::system::memory::available(), &format!("a {w}×{h} render"))?;
    path_loop::requested()?;
    variant::requested_workgroups()?;
    cpu::wide_requested()?;
    Ok(need)
}

/// An empty accumulation of the render's size and kind, what a pool sums its devices' into.
fn empty(buffers: &crate::prepare::buffers::SceneBuffers) -> Accumulation {
    let pixels = (buffers.params.width * buffers.params.height) as usize;
    Accumulation::new(pixels, accumulation::batch_means(&buffers.params))
}

/// `create_on` for a render that someone waits on (the `render` command):
/// with `Auto` and a hardware GPU, the GPUs' devices are built on their own threads while a CPU
/// stand-in renders (`pool::Pool::starting`), so that a scene the GPU has never compiled shows its
/// first image at the CPU's pace rather than after the build (tens of seconds on an H200: README,
/// "What a first render costs"); the stand-in stops once a GPU is ready. The image is the same
/// estimator (samples are a function of their index, whichever device draws them) but not the same
/// bits from run to run; `--backend gpu` renders on the GPUs alone. Only a render of `spp` samples
/// per pixel small enough for the stand-in to matter gets one (`stand_in::worth_it`); larger ones
/// start on the GPUs alone. Measurements (`bench`, `convergence`) use `create_on`.
pub fn create_starting(
    choice: BackendChoice,
    gpus: &GpuSelection,
    buffers: &crate::prepare::buffers::SceneBuffers,
    spp: u32,
) -> Result<Box<dyn Backend + Send>> {
    let samples = buffers.params.width as u64 * buffers.params.height as u64 * spp as u64;
    let wanted = match std::env::var("CAUSTIC_CPU_START").as_deref() {
        Ok("0") => false,
        Ok("1") => true,
        _ => stand_in::worth_it(samples),
    };
    if choice != BackendChoice::Auto || !wanted {
        return create_on(choice, gpus, buffers);
    }
    let clock = std::time::Instant::now();
    let adapters = gpu::adapter_types();
    if gpu::trial_log() {
        eprintln!("build: Vulkan adapters listed in {:.2} s", clock.elapsed().as_secs_f64());
    }
    let Ok(indices) = resolve_gpus(gpus, &adapters, true) else {
        return create_on(choice, gpus, buffers);
    };
    let need = checked(buffers)?;
    // The stand-in holds a second copy of the scene: where that would crowd the host's memory, the
    // GPUs start alone.
    if crate::system::memory::available().is_none_or(|a| need.saturating_mul(3) > a) {
        return create_on(choice, gpus, buffers);
    }
    let devices = indices
        .into_iter()
        .map(|i| {
            let scene = buffers.clone();
            let build = move || -> Result<Box<dyn Backend + Send>> {
                Ok(Box::new(gpu::GpuBackend::on_adapter(&scene, i)?))
            };
            let name = adapters.get(i).map_or_else(|| format!("GPU {i}"), |a| a.0.clone());
            pool::Device::Build { name: format!("{name} (starting)"), build: Box::new(build) }
        })
        .collect();
    let stand_in = Box::new(stand_in::StandIn::new(buffers.clone())?);
    Ok(Box::new(pool::Pool::starting(stand_in, devices, empty(buffers))?))
}

/// `create_on` with every suitable GPU (today's single adapter where there is one).
pub fn create(
    choice: BackendChoice,
    buffers: &crate::prepare::buffers::SceneBuffers,
) -> Result<Box<dyn Backend + Send>> {
    create_on(choice, &GpuSelection::All, buffers)
}

#[cfg(test)]
mod tests {
    use super::*;
    use wgpu::DeviceType::{Cpu, DiscreteGpu};

    #[test]
    fn gpu_selections_parse() {
        let p = |s: &str| s.parse::<GpuSelection>();
        assert_eq!(p("all"), Ok(GpuSelection::All));
        assert_eq!(p("2"), Ok(GpuSelection::First(2)));
        assert_eq!(p("0,0"), Ok(GpuSelection::List(vec![0, 0])));
        assert_eq!(p("3,"), Ok(GpuSelection::List(vec![3])));
        assert!(p("0").unwrap_err().contains("at least one"));
        assert!(p("x").is_err() && p("1,x").is_err() && p(",").is_err());
    }

    #[test]
    fn gpu_selections_resolve() {
        let machine =
            [("H200".to_string(), DiscreteGpu), ("H200".into(), DiscreteGpu), ("llvmpipe".into(), Cpu)];
        let r = |s: GpuSelection, hw| resolve_gpus(&s, &machine, hw);
        assert_eq!(r(GpuSelection::All, true).unwrap(), vec![0, 1]);
        assert_eq!(r(GpuSelection::First(1), false).unwrap(), vec![0]);
        assert_eq!(r(GpuSelection::List(vec![2, 2]), false).unwrap(), vec![2, 2]);
        let e = format!("{:#}", r(GpuSelection::First(3), true).unwrap_err());
        assert!(e.contains("only 2") && e.contains("2: llvmpipe"), "{e}");
        assert!(format!("{:#}", r(GpuSelection::List(vec![5]), true).unwrap_err()).contains("no adapter 5"));
        // Software only: `all` takes it for --backend gpu, not for auto (which then uses the CPU).
        let soft = [("llvmpipe".to_string(), Cpu)];
        assert_eq!(resolve_gpus(&GpuSelection::All, &soft, false).unwrap(), vec![0]);
        assert!(resolve_gpus(&GpuSelection::All, &soft, true).is_err());
    }
}
