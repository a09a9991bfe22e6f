//! The GPU backend: the kernel's SPIR-V run as a wgpu compute pipeline.
//!
//! The module is consumed through naga with runtime bounds checks off (`create_shader_module_trusted`
//! with unchecked runtime checks): measured fastest on the H100 (../shared/notes/rust-gpu-0.11.md;
//! BENCHMARKS.md, "How the kernel's design was chosen"), and safe because the kernel's own indexing
//! is bounds-checked Rust.
use super::accumulation::{Accumulation, Folding};
use super::device::Backend;
use super::module_cache::ModuleCache;
use super::path_loop::PathLoop;
use super::spirv::{declares_spec_constant, set_workgroup_size, KERNEL_SPV};
use super::step_times::{self, StepTimes};
use super::variant::{self, Decisions, Trial, Variant, DEFAULT_WORKGROUP};
use crate::prepare::buffers::SceneBuffers;
use anyhow::{anyhow, bail, Context, Result};
use caustic_kernel::integrator::{merges, traces_cached, traces_camera_paths, traces_light_paths};
use caustic_kernel::layout::{
    binding, FrameParams, PixelAccum, INTEGRATOR_PATH, SPEC_FEATURES, SPEC_REGENERATE,
};
use std::time::Instant;
use wgpu::util::DeviceExt;

/// Camera paths (and IBPT's camera half); light paths (ptracer, IBPT's light half).
const CAMERA_ENTRY: &str = "entry::render";
const LIGHT_ENTRY: &str = "entry::light";
/// Folds a splatting pass's words into the accumulator (and clears them).
const RESOLVE_ENTRY: &str = "entry::resolve";
/// BDPT's and VCM's passes over the light vertex cache: light paths into it, VCM's grid over it,
/// camera paths from it (`caustic_kernel::integrator::bdpt`).
pub(crate) const CACHE_LIGHT_ENTRY: &str = "entry::cache_light";
const GRID_LINK_ENTRY: &str = "entry::grid_link";
const CACHE_CAMERA_ENTRY: &str = "entry::cache_camera";

/// The entry point that traces integrator `kind`'s camera paths.
pub(crate) fn camera_entry(kind: u32) -> &'static str {
    if traces_cached(kind) {
        CACHE_CAMERA_ENTRY
    } else {
        CAMERA_ENTRY
    }
}

pub struct GpuBackend {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// The camera entry point, one pipeline per candidate `Variant` (path loop and workgroup size:
    /// `variant`), and the light entry point, as the integrator needs them.
    camera_pipelines: Vec<(Variant, wgpu::ComputePipeline)>,
    /// Which camera pipeline runs: measured on the first passes where several are built.
    trial: Trial,
    /// Where the trial's outcome is kept (`variant::Decisions`) and under which key, while one runs.
    decision: Option<(Decisions, u64)>,
    /// Whether the one candidate is a decision an earlier render kept (for `describe`).
    kept: bool,
    /// Every candidate, in the trial's order; `camera_pipelines` holds the first of them until the
    /// trial begins, then all.
    candidates: Vec<Variant>,
    /// What builds the rest, until the trial begins (`begin_building`).
    factory: Option<PipelineFactory>,
    /// The rest, building on a thread of their own once the trial begins: passes meanwhile run
    /// the first candidate, unmeasured (`pass`).
    building: Option<std::thread::JoinHandle<Vec<Result<wgpu::ComputePipeline, String>>>>,
    light_pipeline: Option<wgpu::ComputePipeline>,
    /// BDPT and VCM: the light paths into the cache, and VCM's grid over it with the buffer to clear
    /// before it (`cached_dispatch`).
    cache_light_pipeline: Option<wgpu::ComputePipeline>,
    grid: Option<(wgpu::ComputePipeline, wgpu::Buffer)>,
    /// VCM's first radius and its shrinking (`SceneBuffers::merge_radius`).
    merge: (f32, f32),
    /// The same buffers in the three layouts (`on_adapter`): the light and resolve entry points',
    /// the grid's, the camera entry points'.
    bind_groups: [wgpu::BindGroup; 3],
    params_buffer: wgpu::Buffer,
    /// The parameters of a submission's dispatches, copied into `params_buffer` one before each.
    params_ring: wgpu::Buffer,
    accum_buffer: wgpu::Buffer,
    accum_size: u64,
    /// The host's f64 totals that `accum_buffer`'s f32 sums are read back into and cleared, every
    /// `accumulation::FOLD_SAMPLES` samples per pixel and at every read (with the batch count of
    /// splatted sums).
    folding: Folding,
    /// Splatting integrators: the pipeline that resolves each pass's splat words into `accum_buffer`
    /// and clears them. `None` otherwise.
    resolve_pipeline: Option<wgpu::ComputePipeline>,
    adapter_name: String,
    /// Samples per pixel one dispatch may take (a longer pass is several dispatches).
    max_dispatch_samples: u32,
    width: u32,
    height: u32,
    /// `CAUSTIC_STEP_TIMES`: each step's GPU time (`step_times`), printed when the backend ends.
    step_times: Option<StepTimes>,
}

/// Samples per pixel in one dispatch on a software adapter. llvmpipe (lavapipe) ends all of an
/// invocation's loops once they have run 65535 iterations together (Mesa's
/// `LP_MAX_TGSI_LOOP_ITERATIONS`): one dispatch of 128 samples through `stiff.rs`'s facing mirrors
/// (Russian roulette alone ends the paths) lost up to half of some pixels' samples, 64 lost none; 16
/// lost 1.9% of a random scene's (seed 9 of `scripts/random-scenes.py`: unbounded depth, two null
/// interfaces, every crossing a traversal), 4 none, at 6% of the Cornell box's time (128×128, 64
/// spp) for the extra dispatches. The kernel counts samples cut short as invalid, so a scene whose
/// single samples run that long is reported, not silently darker.
const SOFTWARE_DISPATCH_SAMPLES: u32 = 4;

/// Dispatches in one submission, waited for once: BDPT's and VCM's passes are one sample each, and
/// a wait for every one of them left the GPU idle between them on small images.
const SUBMITTED_DISPATCHES: usize = 16;

fn adapter_rank(info: &wgpu::AdapterInfo) -> u32 {
    match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}

/// The machine's Vulkan adapters, best first (discrete, integrated, virtual, other, software; the
/// driver's order within a kind): `--gpus` indices count in this order. Each call enumerates
/// afresh, so one adapter can be opened twice (two devices on one GPU).
pub fn adapters() -> Vec<wgpu::Adapter> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::VULKAN,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let mut adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
    adapters.sort_by_key(|a| adapter_rank(&a.get_info()));
    adapters
}

/// Each adapter's name and kind, in `adapters()`'s order.
pub fn adapter_types() -> Vec<(String, wgpu::DeviceType)> {
    adapters().iter().map(|a| a.get_info()).map(|i| (i.name, i.device_type)).collect()
}

impl GpuBackend {
    /// A device, pipelines and buffers on adapter `index` of `adapters()`.
    pub fn on_adapter(buffers: &SceneBuffers, index: usize) -> Result<Self> {
        let clock = Instant::now();
        let adapter =
            adapters().into_iter().nth(index).ok_or_else(|| anyhow!("no Vulkan adapter {index}"))?;
        let info = adapter.get_info();
        if trial_log() {
            eprintln!("build: Vulkan adapters in {:.2} s", clock.elapsed().as_secs_f64());
        }
        // Before any GPU call that could panic on a buffer this device cannot hold.
        super::limits::check(buffers, &adapter.limits(), &info.name)?;
        let words = kernel_words()?;
        let integrator = buffers.params.integrator;
        let software = info.device_type == wgpu::DeviceType::Cpu;
        // The camera pipelines to build and time (`variant`): on a hardware GPU the path tracer's two
        // loops by three workgroup sizes; on a software adapter (the tests' lavapipe) one.
        let path_tracer = integrator == INTEGRATOR_PATH;
        let mut candidates = variant::candidates(path_tracer, software)?;
        if !traces_camera_paths(integrator) {
            candidates.truncate(1); // (light tracing alone: no camera pipeline to choose)
        }
        // A trial of this setup decided before: that candidate alone.
        let decision_key = (candidates.len() > 1)
            .then(|| Decisions::key(&words, variant::scene_fingerprint(buffers), &info.name, &candidates));
        let decisions = Decisions::in_cache();
        let kept = decision_key.filter(|_| variant::unrequested()).and_then(|key| decisions.load(key));
        let kept = kept.filter(|v| candidates.contains(v));
        if let Some(v) = kept {
            candidates = vec![v];
        }
        // Else the measurements of earlier renders too short to decide, if any.
        let resumed = decision_key
            .filter(|_| variant::unrequested() && candidates.len() > 1)
            .and_then(|key| decisions.load_partial(key, candidates.len()));
        let trial = resumed.unwrap_or_else(|| Trial::new(candidates.len()));
        // The entry points this integrator runs: the modules keep those alone.
        let cached = traces_cached(integrator);
        let batched = super::accumulation::batch_means(&buffers.params);
        let entries: Vec<&str> = [
            (traces_camera_paths(integrator), camera_entry(integrator)),
            (traces_light_paths(integrator), LIGHT_ENTRY),
            (cached, CACHE_LIGHT_ENTRY),
            (merges(integrator), GRID_LINK_ENTRY),
            (batched, RESOLVE_ENTRY),
        ]
        .into_iter()
        .filter_map(|(runs, entry)| runs.then_some(entry))
        .collect();
        // The light and resolve entry points take the first loop's module, in the kernel's own
        // workgroup size. Pruned while the driver opens the device.
        let timed = step_times::wanted_on(&adapter);
        let (opened, loops) = std::thread::scope(|threads| {
            let pruning = threads.spawn(|| LoopModules::of(&words, buffers.features, &candidates, &entries));
            let clock = Instant::now();
            let opened = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("caustic"),
                required_features: if timed {
                    wgpu::Features::TIMESTAMP_QUERY
                } else {
                    wgpu::Features::empty()
                },
                required_limits: adapter.limits(),
                ..Default::default()
            }));
            if trial_log() {
                eprintln!("build: device opened in {:.2} s", clock.elapsed().as_secs_f64());
            }
            (opened, pruning.join())
        });
        let loops = loops.map_err(|_| anyhow!("pruning the kernel for {} failed (a panic)", info.name))?;
        let (device, queue) = opened.context("cannot open the GPU device")?;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        // One explicit layout for both entry points (each uses a subset of the bindings).
        let entry = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        // wgpu matches each binding's access exactly, and the light vertex cache's entry points differ:
        // `cache_light` writes the cache, `grid_link` reads it and writes the grid, `cache_camera` reads
        // both. So three layouts of the same buffers, by whether the cache and the grid are read-only;
        // the other entry points use neither, and take the first.
        let access = |cache_read_only: bool, grid_read_only: bool| {
            let entries: Vec<wgpu::BindGroupLayoutEntry> = BINDINGS
                .iter()
                .map(|&b| {
                    let read_only = match b {
                        binding::ACCUM | binding::SPLAT => false,
                        binding::CACHE => cache_read_only,
                        binding::GRID => grid_read_only,
                        _ => true,
                    };
                    entry(b, read_only)
                })
                .collect();
            let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("scene"),
                entries: &entries,
            });
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("scene"),
                bind_group_layouts: &[Some(&bind_group_layout)],
                immediate_size: 0,
            });
            (bind_group_layout, pipeline_layout)
        };
        let writes_cache = access(false, false);
        let links_grid = access(true, false);
        let reads_cache = access(true, true);
        let camera_layout = if cached { &reads_cache } else { &writes_cache };
        let factory = PipelineFactory {
            device: device.clone(),
            layout: camera_layout.1.clone(),
            features: buffers.features,
            loops,
            camera_entry: camera_entry(integrator),
        };
        // The first candidate now; the others once the trial reaches them (`build_candidates`): a
        // render too short for a trial compiles one pipeline, not six.
        let camera_pipelines: Vec<(Variant, wgpu::ComputePipeline)> = if traces_camera_paths(integrator) {
            vec![(
                candidates[0],
                factory.build(candidates[0].path_loop, candidates[0].workgroup, factory.camera_entry),
            )]
        } else {
            Vec::new()
        };
        let first_loop = candidates[0].path_loop;
        let light_pipeline = traces_light_paths(integrator)
            .then(|| factory.build_in(&writes_cache.1, first_loop, DEFAULT_WORKGROUP, LIGHT_ENTRY));
        let cache_light_pipeline = cached
            .then(|| factory.build_in(&writes_cache.1, first_loop, DEFAULT_WORKGROUP, CACHE_LIGHT_ENTRY));
        let grid_pipeline = merges(integrator)
            .then(|| factory.build_in(&links_grid.1, first_loop, DEFAULT_WORKGROUP, GRID_LINK_ENTRY));
        // (Also the splatting film's gather.)
        let resolve_pipeline =
            batched.then(|| factory.build_in(&writes_cache.1, first_loop, DEFAULT_WORKGROUP, RESOLVE_ENTRY));
        if let Some(e) = pollster::block_on(scope.pop()) {
            bail!("the GPU rejected the kernel on {}: {e}", info.name);
        }

        let storage = |label: &str, bytes: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let params_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("params"),
            contents: bytemuck::bytes_of(&buffers.params),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        });
        let params_ring = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("params of a submission"),
            size: (SUBMITTED_DISPATCHES * std::mem::size_of::<FrameParams>()) as u64,
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let nodes = storage("nodes", bytemuck::cast_slice(&buffers.nodes));
        let prims = storage("prims", bytemuck::cast_slice(&buffers.prims));
        let attributes = storage("attributes", bytemuck::cast_slice(&buffers.attributes));
        let materials = storage("materials", bytemuck::cast_slice(&buffers.materials));
        let lights = storage("lights", bytemuck::cast_slice(&buffers.lights));
        let tables = storage("tables", bytemuck::cast_slice(&buffers.tables));
        let textures = storage("textures", bytemuck::cast_slice(&buffers.textures));
        let pixels = buffers.params.width as u64 * buffers.params.height as u64;
        let accum_size = pixels * std::mem::size_of::<PixelAccum>() as u64;
        let accum_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("accum"),
            size: accum_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Light tracing's fixed-point words or the splatting film's cells; else a placeholder word.
        let per_pixel = caustic_kernel::film_splat::words_per_pixel(&buffers.params) as u64;
        let splat_size = (pixels * per_pixel).max(1) * 4;
        let splat_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("splat"),
            size: splat_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let scratch = |label: &str, size: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let cache_buffer = scratch("light vertex cache", super::limits::cache_bytes(buffers));
        let grid_buffer = scratch("merging grid", super::limits::grid_bytes(buffers));
        let entries: Vec<wgpu::BindGroupEntry> = [
            (binding::PARAMS, &params_buffer),
            (binding::NODES, &nodes),
            (binding::PRIMS, &prims),
            (binding::ATTRIBUTES, &attributes),
            (binding::MATERIALS, &materials),
            (binding::LIGHTS, &lights),
            (binding::TABLES, &tables),
            (binding::ACCUM, &accum_buffer),
            (binding::TEXTURES, &textures),
            (binding::SPLAT, &splat_buffer),
            (binding::CACHE, &cache_buffer),
            (binding::GRID, &grid_buffer),
        ]
        .iter()
        .map(|(binding, b)| wgpu::BindGroupEntry { binding: *binding, resource: b.as_entire_binding() })
        .collect();
        let bind_group_of = |layout: &wgpu::BindGroupLayout| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scene"),
                layout,
                entries: &entries,
            })
        };
        // The light paths', the grid's and the camera paths' (the camera pipelines' layout).
        let bind_groups =
            [bind_group_of(&writes_cache.0), bind_group_of(&links_grid.0), bind_group_of(&camera_layout.0)];
        let adapter_name = format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend);
        let step_times = timed.then(|| StepTimes::on(&device, &queue));
        Ok(GpuBackend {
            device,
            queue,
            decision: decision_key.filter(|_| candidates.len() > 1).map(|key| (decisions, key)),
            kept: kept.is_some(),
            factory: (camera_pipelines.len() < candidates.len()).then_some(factory),
            building: None,
            candidates,
            camera_pipelines,
            trial,
            light_pipeline,
            cache_light_pipeline,
            grid: grid_pipeline.map(|p| (p, grid_buffer)),
            merge: (buffers.params.merge_radius, buffers.merge_alpha),
            bind_groups,
            params_buffer,
            params_ring,
            accum_buffer,
            accum_size,
            folding: Folding::new(pixels as usize, batched, buffers.params.square_scale_log2),
            resolve_pipeline,
            adapter_name,
            // (BDPT and VCM: one sample a dispatch, the cache holding one light path a pixel.)
            max_dispatch_samples: if cached {
                1
            } else if info.device_type == wgpu::DeviceType::Cpu {
                SOFTWARE_DISPATCH_SAMPLES
            } else {
                u32::MAX
            },
            width: buffers.params.width,
            height: buffers.params.height,
            step_times,
        })
    }

    /// A copy of `buffer`'s first `size` bytes.
    fn read_buffer(&self, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>> {
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([encoder.finish()]);
        super::readback::map_read(&self.device, staging.slice(..), "a GPU buffer")
    }

    fn wait(&self) -> Result<()> {
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| anyhow!("GPU wait failed: {e}"))?;
        Ok(())
    }
}

impl Backend for GpuBackend {
    fn describe(&self) -> String {
        // Always the pipeline that runs, and why it: a kept decision builds it alone, so without
        // this a render's log could not tell which loop a figure timed (2026-11-27: the diamond's
        // tables timed its plain loop at 12.0 Msamples/s, its regenerating loop ran 16.9).
        let name =
            |v: &Variant| format!("{} loop in {}x{}", v.path_loop.name(), v.workgroup[0], v.workgroup[1]);
        let Some(&(first, _)) = self.camera_pipelines.first() else {
            return format!("gpu: {}", self.adapter_name);
        };
        match self.trial.decided() {
            Some(choice) if self.camera_pipelines.len() > 1 => {
                let timed: Vec<String> = (self.camera_pipelines.iter().zip(self.trial.per_sample()))
                    .map(|((v, _), s)| format!("{} {:.2}", name(v), s * 1e3))
                    .collect();
                format!(
                    "gpu: {}, {} (trial, ms per spp: {})",
                    self.adapter_name,
                    name(&self.camera_pipelines[choice].0),
                    timed.join(", ")
                )
            }
            Some(_) if self.kept => {
                format!("gpu: {}, {} (kept from a trial)", self.adapter_name, name(&first))
            }
            Some(_) => format!("gpu: {}, {}", self.adapter_name, name(&first)),
            None => {
                format!("gpu: {}, trial of {} pipelines undecided", self.adapter_name, self.candidates.len())
            }
        }
    }

    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        if self.trial.running() && self.factory.is_some() {
            self.begin_building();
        }
        if self.building.as_ref().is_some_and(|b| b.is_finished()) {
            self.finish_building()?;
        }
        // (While the others build, the first candidate renders and the trial waits.)
        let waiting = self.building.is_some();
        let choice = if waiting { 0 } else { self.trial.next() };
        let mut chunk = *params;
        let end = chunk.sample_base + chunk.sample_count;
        let clock = Instant::now();
        let mut chunks = Vec::new();
        while chunk.sample_base < end {
            chunk.sample_count = (end - chunk.sample_base).min(self.max_dispatch_samples);
            chunks.push(chunk);
            chunk.sample_base += chunk.sample_count;
        }
        for submission in chunks.chunks(SUBMITTED_DISPATCHES) {
            self.dispatch(submission, choice)?;
        }
        // (`dispatch` waits for the GPU: the clock measures the samples alone.)
        let elapsed = clock.elapsed();
        let undecided = self.trial.decided().is_none() && !waiting;
        if !waiting {
            self.trial.record(choice, params.sample_count, elapsed);
        }
        if undecided && trial_log() {
            eprintln!(
                "trial: #{choice} {} spp {:.1} ms -> {:?}",
                params.sample_count,
                elapsed.as_secs_f64() * 1e3,
                self.trial.decided()
            );
        }
        if let (true, Some((decisions, key))) = (undecided, &self.decision) {
            match self.trial.decided() {
                Some(choice) => decisions.store(*key, self.camera_pipelines[choice].0),
                None if variant::unrequested() => decisions.store_partial(*key, &self.trial),
                None => {}
            }
        }
        Ok(())
    }

    fn settled(&self) -> bool {
        self.trial.decided().is_some()
    }

    fn write_accum(&mut self, accum: &Accumulation) -> Result<()> {
        self.folding.replace(accum)?;
        self.clear_accum()
    }

    fn read_accum(&mut self) -> Result<Accumulation> {
        self.fold()?;
        Ok(self.folding.total.clone())
    }
}

impl GpuBackend {
    /// Starts compiling the camera pipelines of the candidates not built yet (once the trial
    /// begins) on a thread, which builds each on a thread of its own: the driver compiles them side
    /// by side where it can (wgpu's error scopes are per thread, so each thread checks its own), and
    /// the render goes on meanwhile (a driver may take 20 s a pipeline: BENCHMARKS.md, "Pruning
    /// without spirv-opt").
    fn begin_building(&mut self) {
        let Some(factory) = self.factory.take() else { return };
        let todo = self.candidates[self.camera_pipelines.len()..].to_vec();
        let clock = Instant::now();
        self.building = Some(std::thread::spawn(move || {
            let built = std::thread::scope(|threads| {
                let factory = &factory;
                let handles: Vec<_> = todo
                    .iter()
                    .map(|&v| {
                        threads.spawn(move || {
                            let scope = factory.device.push_error_scope(wgpu::ErrorFilter::Validation);
                            let pipeline = factory.build(v.path_loop, v.workgroup, factory.camera_entry);
                            match pollster::block_on(scope.pop()) {
                                Some(e) => Err(e.to_string()),
                                None => Ok(pipeline),
                            }
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().unwrap_or_else(|_| Err("a pipeline's build panicked".to_string())))
                    .collect()
            });
            if trial_log() {
                eprintln!("trial: built the candidates in {:.2} s", clock.elapsed().as_secs_f64());
            }
            built
        }));
    }

    /// Takes the candidates' pipelines once built (waiting for them, if they are not).
    fn finish_building(&mut self) -> Result<()> {
        let Some(building) = self.building.take() else { return Ok(()) };
        let built = building.join().map_err(|_| anyhow!("the pipelines' build panicked"))?;
        let todo = self.candidates[self.camera_pipelines.len()..].to_vec();
        for (v, pipeline) in todo.into_iter().zip(built) {
            match pipeline {
                Ok(p) => self.camera_pipelines.push((v, p)),
                Err(e) => bail!("the GPU rejected the kernel on {}: {e}", self.adapter_name),
            }
        }
        Ok(())
    }

    /// Dispatches of the kernel, one submission: each `params.sample_count` samples per pixel (at most
    /// `max_dispatch_samples`; BDPT and VCM: one, whose radius VCM takes from `merge`), in order, each
    /// seeing the one before; then one wait for the GPU. Several (BDPT's and VCM's one-sample passes)
    /// take their parameters from `params_ring`, copied into the parameters' binding before each.
    fn dispatch(&mut self, params: &[FrameParams], choice: usize) -> Result<()> {
        let (first_radius, alpha) = self.merge;
        let params: Vec<FrameParams> = params
            .iter()
            .map(|p| FrameParams {
                merge_radius: crate::prepare::buffers::merge_radius(first_radius, alpha, p.sample_base),
                ..*p
            })
            .collect();
        let size = std::mem::size_of::<FrameParams>() as u64;
        if let [one] = params.as_slice() {
            self.queue.write_buffer(&self.params_buffer, 0, bytemuck::bytes_of(one));
        } else {
            self.queue.write_buffer(&self.params_ring, 0, bytemuck::cast_slice(&params));
        }
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("pass") });
        let mut fold = false;
        for (k, p) in params.iter().enumerate() {
            if params.len() > 1 {
                encoder.copy_buffer_to_buffer(
                    &self.params_ring,
                    k as u64 * size,
                    &self.params_buffer,
                    0,
                    size,
                );
            }
            if let Some((_, grid)) = &self.grid {
                encoder.clear_buffer(grid, 0, None);
            }
            // Each dispatch sees the previous one's writes (wgpu orders dispatches that share a
            // buffer). Camera paths, light paths, then (splatting) the words folded into the
            // accumulator; BDPT and VCM (`caustic_cpu::cached_pass`): the light paths into the cache,
            // VCM's grid over it, the camera paths from it, then the words.
            let camera = self.camera_pipelines.get(choice).map(|(v, p)| ("camera paths", p, v.workgroup, 2));
            let resolve = step("resolve", self.resolve_pipeline.as_ref(), 0);
            let steps = if self.cache_light_pipeline.is_some() {
                vec![
                    step("light paths (cache)", self.cache_light_pipeline.as_ref(), 0),
                    step("grid", self.grid.as_ref().map(|g| &g.0), 1),
                    camera,
                    resolve,
                ]
            } else {
                vec![camera, step("light paths", self.light_pipeline.as_ref(), 0), resolve]
            };
            // One compute pass for all steps; timed, one each (`step_times`).
            let mut pass = None;
            for (name, pipeline, [w, h], group) in steps.into_iter().flatten() {
                if pass.is_none() || self.step_times.is_some() {
                    drop(pass.take());
                    let timestamp_writes = self.step_times.as_mut().and_then(|t| t.around(name));
                    // (`forget_lifetime`: the passes of a loop would each borrow the encoder.)
                    pass = Some(
                        encoder
                            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                                label: Some(name),
                                timestamp_writes,
                            })
                            .forget_lifetime(),
                    );
                }
                let pass = pass.as_mut().expect("a compute pass");
                pass.set_bind_group(0, &self.bind_groups[group], &[]);
                pass.set_pipeline(pipeline);
                pass.dispatch_workgroups(self.width.div_ceil(w), self.height.div_ceil(h), 1);
            }
            drop(pass);
            // (Folded after the submission: at most `SUBMITTED_DISPATCHES` - 1 dispatches later than
            // `FOLD_SAMPLES`, a few samples against thousands, which leaves the sums' precision.)
            fold |= self.folding.passed(p.sample_count);
        }
        if let Some(times) = &self.step_times {
            times.resolve(&mut encoder);
        }
        self.queue.submit([encoder.finish()]);
        if fold {
            self.fold()?;
        } else {
            self.wait()?;
        }
        match &mut self.step_times {
            Some(times) => times.collect(&self.device),
            None => Ok(()),
        }
    }

    /// Reads the device's f32 sums back into the host's f64 totals and clears them.
    fn fold(&mut self) -> Result<()> {
        let bytes = self.read_buffer(&self.accum_buffer, self.accum_size)?;
        let device: Vec<PixelAccum> = bytemuck::pod_collect_to_vec(&bytes);
        self.folding.fold(&device);
        self.clear_accum()
    }

    fn clear_accum(&mut self) -> Result<()> {
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("clear") });
        encoder.clear_buffer(&self.accum_buffer, 0, None);
        self.queue.submit([encoder.finish()]);
        self.wait()
    }
}

impl Drop for GpuBackend {
    /// A build of the trial's candidates still running ends first: a process that exited while
    /// its build thread was inside the NVIDIA driver's compiler crashed there (as `pool`'s `Drop`
    /// says).
    fn drop(&mut self) {
        if let Some(building) = self.building.take() {
            let _ = building.join();
        }
        if let Some(times) = &self.step_times {
            eprintln!("{}", times.report());
        }
    }
}

/// What building a pipeline of the scene's kernel needs, kept while the trial's later candidates
/// are not built yet.
struct PipelineFactory {
    device: wgpu::Device,
    layout: wgpu::PipelineLayout,
    features: u32,
    loops: LoopModules,
    /// The integrator's camera entry point (`camera_entry`).
    camera_entry: &'static str,
}

impl PipelineFactory {
    /// Entry point `entry` of path loop `path_loop`'s module in workgroups of `size`, in the camera
    /// pipelines' layout.
    fn build(&self, path_loop: PathLoop, size: [u32; 2], entry: &str) -> wgpu::ComputePipeline {
        self.build_in(&self.layout, path_loop, size, entry)
    }

    /// `build` in pipeline layout `layout`.
    fn build_in(
        &self,
        layout: &wgpu::PipelineLayout,
        path_loop: PathLoop,
        size: [u32; 2],
        entry: &str,
    ) -> wgpu::ComputePipeline {
        let (words, specialisable) = self.loops.module(path_loop, size);
        let (clock, length) = (Instant::now(), words.len());
        // SAFETY: the module is rust-gpu output of our kernel, whose array accesses are
        // bounds-checked in the source, but for the BVH walk's, whose indices the host checks
        // when it builds the tree (`prepare::bvh::inside_buffers`); dropping naga's runtime checks is
        // what makes this path fast.
        let module = unsafe {
            self.device.create_shader_module_trusted(
                wgpu::ShaderModuleDescriptor {
                    label: Some("caustic-kernel"),
                    source: wgpu::ShaderSource::SpirV(words.into()),
                },
                wgpu::ShaderRuntimeChecks::unchecked(),
            )
        };
        // The scene's feature mask specialises the kernel (spec constant 0): unused paths fold
        // away; spec constant 1 picks the path loop. A module built with the scene's mask already
        // frozen in (pruned, or CAUSTIC_KERNEL_SPV, e.g. spirv-opt --freeze-spec-const) has no
        // constant left to set.
        let spec_constants = [
            (SPEC_FEATURES.to_string(), self.features as f64),
            (SPEC_REGENERATE.to_string(), path_loop.spec_value() as f64),
        ];
        let constants: &[(&str, f64)] = &spec_constants.each_ref().map(|(k, v)| (k.as_str(), *v));
        let read = clock.elapsed().as_secs_f64();
        let pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: Some(layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: if specialisable { constants } else { &[] },
                ..Default::default()
            },
            cache: None,
        });
        if trial_log() {
            let total = clock.elapsed().as_secs_f64();
            eprintln!(
                "build: {entry} {path_loop:?} {}x{}: module of {length} words read in {read:.2} s, pipeline in {:.2} s",
                size[0],
                size[1],
                total - read
            );
        }
        pipeline
    }
}

/// The module of each path loop that a list of candidates uses, pruned to the scene where it can be
/// (`scene_module`), and whether its specialization constants are still open (then a pipeline sets
/// them): what the backend and `kernel_stats` build their pipelines from.
pub(crate) struct LoopModules(Vec<(PathLoop, Vec<u32>, bool)>);

impl LoopModules {
    /// Each candidate loop's module with entry points `entries`, pruned on a thread of its own.
    pub(crate) fn of(words: &[u32], features: u32, candidates: &[Variant], entries: &[&str]) -> Self {
        let prune = super::prune::wanted();
        let digest = prune.then(|| ModuleCache::digest(words));
        let mut wanted: Vec<PathLoop> = Vec::new();
        for c in candidates {
            if !wanted.contains(&c.path_loop) {
                wanted.push(c.path_loop);
            }
        }
        let loops = std::thread::scope(|threads| {
            let handles: Vec<_> = wanted
                .iter()
                .map(|&l| {
                    threads.spawn(move || {
                        let clock = Instant::now();
                        let module = scene_module(words, digest, features, l, entries);
                        if trial_log() {
                            let seconds = clock.elapsed().as_secs_f64();
                            eprintln!(
                                "build: {l:?} loop's module, {} words, in {seconds:.2} s",
                                module.0.len()
                            );
                        }
                        module
                    })
                })
                .collect();
            let modules = handles.into_iter().map(|h| h.join().expect("pruning a loop's module panicked"));
            wanted.iter().zip(modules).map(|(&l, (module, open))| (l, module, open)).collect()
        });
        LoopModules(loops)
    }

    /// Path loop `path_loop`'s module in workgroups of `size`, and whether its constants are open.
    /// (Only asked for the candidates it was built for.)
    pub(crate) fn module(&self, path_loop: PathLoop, size: [u32; 2]) -> (Vec<u32>, bool) {
        let (_, words, open) = self.0.iter().find(|l| l.0 == path_loop).expect("a candidate's loop");
        let mut words = words.clone();
        set_workgroup_size(&mut words, size);
        (words, *open)
    }
}

/// The kernel's SPIR-V words. `CAUSTIC_KERNEL_SPV` runs another build of the kernel (driver
/// investigations, A/B timings).
pub(crate) fn kernel_words() -> Result<Vec<u32>> {
    Ok(match std::env::var_os("CAUSTIC_KERNEL_SPV") {
        Some(path) => {
            let bytes = std::fs::read(&path)
                .with_context(|| format!("cannot read CAUSTIC_KERNEL_SPV={}", path.to_string_lossy()))?;
            bytemuck::pod_collect_to_vec(&bytes)
        }
        None => bytemuck::pod_collect_to_vec(KERNEL_SPV),
    })
}

/// The module a scene's pipelines are built from, for path loop `choice`: pruned to the scene's
/// feature mask and to `entries` where pruning is wanted (`digest`: the kernel's, for the modules
/// kept between renders, `ModuleCache`) and can, else the kernel itself; and whether its
/// specialization constants are still open (then the pipeline sets them).
fn scene_module(
    words: &[u32],
    digest: Option<u64>,
    features: u32,
    choice: PathLoop,
    entries: &[&str],
) -> (Vec<u32>, bool) {
    let specialisable = declares_spec_constant(words, 0);
    if let (true, Some(digest)) = (specialisable, digest) {
        let (cache, key) =
            (ModuleCache::in_cache(), ModuleCache::key(digest, features, choice.spec_value(), entries));
        if let Some(kept) = cache.load(key) {
            let open = declares_spec_constant(&kept, 0);
            return (kept, open);
        }
        if let Some(pruned) = super::prune::pruned_to(words, features, choice.spec_value(), entries) {
            cache.store(key, &pruned);
            let open = declares_spec_constant(&pruned, 0);
            return (pruned, open);
        }
        // Once a process: both path loops' modules (and every device's) would say it again.
        static SAID: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
        if !SAID.swap(true, std::sync::atomic::Ordering::Relaxed) {
            eprintln!("note: caustic cannot prune this kernel module; it runs specialised, unpruned");
        }
    }
    (words.to_vec(), specialisable)
}

/// One dispatch of `dispatch`'s list, if its pipeline exists: its step's name, the pipeline, its
/// workgroup and its bind group's index.
fn step<'a>(
    name: &'static str,
    pipeline: Option<&'a wgpu::ComputePipeline>,
    group: usize,
) -> Option<(&'static str, &'a wgpu::ComputePipeline, [u32; 2], usize)> {
    pipeline.map(|p| (name, p, DEFAULT_WORKGROUP, group))
}

/// The camera, light and resolve entry points' names, for `kernel_stats` (its camera entry point by
/// integrator: `camera_entry`).
pub(crate) const ENTRY_POINTS: [&str; 3] = [CAMERA_ENTRY, LIGHT_ENTRY, RESOLVE_ENTRY];

/// The kernel's bindings (`entry.rs`), all storage buffers of descriptor set 0.
pub(crate) const BINDINGS: [u32; 12] = [
    binding::PARAMS,
    binding::NODES,
    binding::PRIMS,
    binding::ATTRIBUTES,
    binding::MATERIALS,
    binding::LIGHTS,
    binding::TABLES,
    binding::ACCUM,
    binding::TEXTURES,
    binding::SPLAT,
    binding::CACHE,
    binding::GRID,
];

/// `CAUSTIC_TRIAL_LOG` set: the trial's passes on standard error (each dispatch's candidate, samples
/// per pixel and time), to see what a choice was made from, and the time each module and pipeline
/// took to build.
pub(crate) fn trial_log() -> bool {
    std::env::var_os("CAUSTIC_TRIAL_LOG").is_some()
}
