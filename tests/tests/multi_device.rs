//! Several devices render one image: passes handed out by sample index to whichever device is idle,
//! accumulations summed. Random numbers are a function of (seed, pixel, sample, dimension), so the
//! union of the devices' passes is the single-device estimator and the sums may differ only by the
//! order of float additions. Without multi-GPU hardware: two CPU backends, and two logical devices
//! on one Vulkan adapter (lavapipe in CI).
use caustic::backend::accumulation::Accumulation;
use caustic::backend::pool::{Device, Pool};
use caustic::backend::schedule::Lanes;
use caustic::backend::stand_in::StandIn;
use caustic::backend::{cpu::CpuBackend, Backend, BackendChoice, GpuSelection};
use caustic::prepare::buffers::{self, SceneBuffers};
use caustic::render::passes::render_with_checkpoints;
use caustic::scene::IntegratorChoice;
use caustic_kernel::layout::FrameParams;
use caustic_tests::*;
use std::ops::ControlFlow::Continue;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

/// Relative tolerance on each pixel's sums. Each sum adds at most a few hundred positive f32 terms
/// (samples, or a splatting pass's resolved sums), so regrouping them changes it by at most
/// (terms)·2⁻²⁴ relative: ≤ 64 terms here, 3.8e-6; 1e-5 leaves a margin and still catches one lost
/// or doubled sample in 64 (1.6e-2).
const SUM_TOLERANCE: f64 = 1e-5;

fn cornell_box(integrator: IntegratorChoice) -> SceneBuffers {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml"));
    let mut scene =
        caustic::load::load_scene(path, &defines(&[("res", "12")])).expect("the Cornell box loads");
    scene.integrator = scene.integrator.overridden(integrator);
    buffers::build(&scene).expect("the Cornell box builds")
}

/// Renders `spp` samples with seed 5, reading the sums back at every checkpoint (as convergence
/// does; for a pool, what a device that fails later keeps).
fn render(backend: &mut dyn Backend, buffers: &SceneBuffers, spp: u32, checkpoints: &[u32]) -> Accumulation {
    render_with_checkpoints(backend, buffers, 0, spp, 5, checkpoints, |done, _, backend| {
        if checkpoints.contains(&done) {
            backend.read_accum()?;
        }
        Ok(Continue(()))
    })
    .unwrap_or_else(|e| panic!("{}: {e:#}", backend.describe()));
    backend.read_accum().expect("the sums read back")
}

/// Invalid samples exactly, counts and sums to `SUM_TOLERANCE` (a count is the splatting film's
/// summed filter weights, whose f32 rounding depends on how passes were grouped on each device, or a
/// number of samples, where the tolerance is still far below one sample); squares too for
/// per-sample sums (batch means' squares are over batches, whose boundaries depend on timing).
fn assert_same_sums(what: &str, a: &Accumulation, b: &Accumulation) {
    assert_eq!(a.pixels.len(), b.pixels.len());
    let close = |x: f64, y: f64| (x - y).abs() <= SUM_TOLERANCE * x.abs().max(y.abs()) + 1e-30;
    for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        assert_eq!(p.invalid, q.invalid, "{what}: pixel {i}");
        assert!(close(p.count, q.count), "{what}: pixel {i}: count {} vs {}", p.count, q.count);
        for c in 0..3 {
            assert!(close(p.sum[c], q.sum[c]), "{what}: pixel {i}: sum {:?} vs {:?}", p.sum, q.sum);
            if a.batches.is_none() {
                assert!(
                    close(p.sum_sq[c], q.sum_sq[c]),
                    "{what}: pixel {i}: {:?} vs {:?}",
                    p.sum_sq,
                    q.sum_sq
                );
            }
        }
    }
    assert!(a.pixels.iter().any(|p| p.sum[0] > 0.0), "{what}: a black image proves nothing");
}

fn cpu_pool(buffers: &SceneBuffers, devices: Vec<Box<dyn Backend + Send>>) -> Pool {
    let pixels = (buffers.params.width * buffers.params.height) as usize;
    Pool::new(
        devices,
        Accumulation::new(pixels, caustic::backend::accumulation::batch_means(&buffers.params)),
    )
    .unwrap()
}

fn cpu(buffers: &SceneBuffers) -> Box<dyn Backend + Send> {
    Box::new(CpuBackend::new(buffers.clone()))
}

/// A device that fails, as a lost GPU does, on its `fail_at`-th pass (counting from 1) or on the
/// first pass from sample `fail_from` on.
struct Failing {
    inner: CpuBackend,
    /// Passes asked of it (shared with the test, which checks that the failure happened).
    passes: Arc<AtomicU32>,
    fail_at: u32,
    fail_from: u32,
}

impl Failing {
    fn device(
        buffers: &SceneBuffers,
        fail_at: u32,
        fail_from: u32,
    ) -> (Box<dyn Backend + Send>, Arc<AtomicU32>) {
        let passes = Arc::new(AtomicU32::new(0));
        let inner = CpuBackend::new(buffers.clone());
        let device = Failing { inner, passes: passes.clone(), fail_at, fail_from };
        (Box::new(device), passes)
    }
}

impl Backend for Failing {
    fn describe(&self) -> String {
        "failing test device".into()
    }
    fn pass(&mut self, params: &FrameParams) -> anyhow::Result<()> {
        let pass = self.passes.fetch_add(1, Ordering::Relaxed) + 1;
        anyhow::ensure!(pass < self.fail_at && params.sample_base < self.fail_from, "device lost (injected)");
        self.inner.pass(params)
    }
    fn read_accum(&mut self) -> anyhow::Result<Accumulation> {
        self.inner.read_accum()
    }
    fn write_accum(&mut self, accum: &Accumulation) -> anyhow::Result<()> {
        self.inner.write_accum(accum)
    }
}

#[test]
fn two_cpu_devices_give_the_one_device_sums() {
    for integrator in [IntegratorChoice::Path, IntegratorChoice::Ptracer, IntegratorChoice::Ibpt] {
        let buffers = cornell_box(integrator);
        let one = render(&mut CpuBackend::new(buffers.clone()), &buffers, 48, &[]);
        let mut pool = cpu_pool(&buffers, vec![cpu(&buffers), cpu(&buffers)]);
        // With stops (rests, reads in between) as convergence makes them.
        let two = render(&mut pool, &buffers, 48, &[3, 20]);
        assert_same_sums(&format!("{integrator:?}"), &two, &one);
        if let Some(b) = two.batches {
            assert!(b >= 32, "{integrator:?}: {b} batches, fewer than the variance estimate needs");
        }
    }
}

/// A device lost mid-render: its unsaved passes go back to the queue and the survivor renders them.
/// Lost on its second pass, or on its first after the rest at 4 spp (its sums read back then: what
/// it had done is kept, and a sample counted twice or lost would show in the counts).
#[test]
fn a_lost_device_costs_only_its_unsaved_passes() {
    for integrator in [IntegratorChoice::Path, IntegratorChoice::Ptracer] {
        let buffers = cornell_box(integrator);
        let one = render(&mut CpuBackend::new(buffers.clone()), &buffers, 40, &[]);
        for (fail_at, fail_from, stops) in [(2, u32::MAX, vec![]), (u32::MAX, 4, vec![4, 9])] {
            let (failing, passes) = Failing::device(&buffers, fail_at, fail_from);
            let mut pool = cpu_pool(&buffers, vec![cpu(&buffers), failing]);
            let two = render(&mut pool, &buffers, 40, &stops);
            let what = format!("{integrator:?}, stops {stops:?}");
            // Both lanes start at once, and every idle lane is handed a pass after each rest.
            assert!(passes.load(Ordering::Relaxed) >= 2, "{what}: the device never failed");
            assert_same_sums(&what, &two, &one);
        }
    }
}

#[test]
fn losing_every_device_is_an_error_naming_it() {
    let buffers = cornell_box(IntegratorChoice::Path);
    let failing = || Failing::device(&buffers, 2, u32::MAX).0;
    let mut pool = cpu_pool(&buffers, vec![failing(), failing()]);
    let e = render_with_checkpoints(&mut pool, &buffers, 0, 16, 5, &[], |_, _, _| Ok(Continue(())))
        .err()
        .expect("no device is left");
    let message = format!("{e:#}");
    assert!(message.contains("failing test device") && message.contains("injected"), "{message}");
}

/// Two logical devices on one Vulkan adapter (`--gpus 0,0`) against one, for path tracing and both
/// splatting integrators (light-path ranges per device, resolved splats summed).
#[test]
fn two_devices_on_one_gpu_give_the_one_device_sums() {
    // The software adapter when no hardware one exists, as `--backend gpu` does.
    let first = caustic::backend::resolve_gpus(
        &GpuSelection::First(1),
        &caustic::backend::gpu::adapter_types(),
        false,
    )
    .expect("a Vulkan adapter (lavapipe in CI)")[0];
    for integrator in [IntegratorChoice::Path, IntegratorChoice::Ptracer, IntegratorChoice::Ibpt] {
        let buffers = cornell_box(integrator);
        let on = |list: Vec<usize>| {
            caustic::backend::create_on(BackendChoice::Gpu, &GpuSelection::List(list), &buffers)
        };
        let one = render(on(vec![first]).unwrap().as_mut(), &buffers, 32, &[]);
        let mut two = on(vec![first, first]).unwrap();
        assert!(two.describe().starts_with("2 devices"), "{}", two.describe());
        let sums = render(two.as_mut(), &buffers, 32, &[]);
        let shares = two.lanes().expect("a pool").shares();
        println!("{integrator:?}: samples per device {shares:?}");
        assert!(shares.iter().all(|&s| s > 0), "{integrator:?}: a device took no pass: {shares:?}");
        assert_same_sums(&format!("{integrator:?} on two GPU devices"), &sums, &one);
    }
}

/// A CPU device that counts its passes (shared with the test), each made to last at least 20 ms (so
/// that a build polling the count sees it before the next pass starts).
struct Counted {
    inner: Box<dyn Backend + Send>,
    passes: Arc<AtomicU32>,
}

impl Backend for Counted {
    fn describe(&self) -> String {
        self.inner.describe()
    }
    fn pass(&mut self, params: &FrameParams) -> anyhow::Result<()> {
        self.passes.fetch_add(1, Ordering::SeqCst);
        std::thread::sleep(std::time::Duration::from_millis(20));
        self.inner.pass(params)
    }
    fn read_accum(&mut self) -> anyhow::Result<Accumulation> {
        self.inner.read_accum()
    }
    fn write_accum(&mut self, accum: &Accumulation) -> anyhow::Result<()> {
        self.inner.write_accum(accum)
    }
}

fn starting_pool(buffers: &SceneBuffers, stand_in: Box<dyn Backend + Send>, device: Device) -> Pool {
    let pixels = (buffers.params.width * buffers.params.height) as usize;
    let empty = Accumulation::new(pixels, caustic::backend::accumulation::batch_means(&buffers.params));
    Pool::starting(stand_in, vec![device], empty).unwrap()
}

/// A device built while a stand-in renders (a GPU compiling its pipelines): the stand-in renders
/// until the device joins, then takes no more passes (one may be in flight at the join), and the
/// sums are the one device's. The build waits for the stand-in's third pass, so both render.
#[test]
fn a_device_built_during_the_render_relieves_the_stand_in() {
    let buffers = cornell_box(IntegratorChoice::Path);
    let one = render(&mut CpuBackend::new(buffers.clone()), &buffers, 48, &[]);
    let stand_in_passes = Arc::new(AtomicU32::new(0));
    let stand_in = Box::new(Counted {
        inner: Box::new(StandIn::new(buffers.clone()).unwrap()),
        passes: stand_in_passes.clone(),
    });
    let (seen, scene) = (stand_in_passes.clone(), buffers.clone());
    let build = move || -> anyhow::Result<Box<dyn Backend + Send>> {
        let t = std::time::Instant::now();
        while seen.load(Ordering::SeqCst) < 3 && t.elapsed().as_secs() < 60 {
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
        Ok(Box::new(CpuBackend::new(scene)))
    };
    let device = Device::Build { name: "built later".into(), build: Box::new(build) };
    let mut pool = starting_pool(&buffers, stand_in, device);
    let sums = render(&mut pool, &buffers, 48, &[]);
    assert_same_sums("stand-in, then the built device", &sums, &one);
    let shares = pool.shares();
    let by_stand_in = stand_in_passes.load(Ordering::SeqCst);
    assert!((3..=4).contains(&by_stand_in), "the stand-in ran {by_stand_in} passes (shares {shares:?})");
    assert!(shares[1] > 0, "the built device rendered nothing (shares {shares:?})");
}

/// A device that cannot be built (a GPU that fails to start) leaves the stand-in rendering, and a
/// render the stand-in completes does not wait for a build still running (the pool waits for it
/// when dropped, after the image is read).
#[test]
fn the_stand_in_renders_alone_when_the_device_fails_or_is_late() {
    let buffers = cornell_box(IntegratorChoice::Path);
    let one = render(&mut CpuBackend::new(buffers.clone()), &buffers, 16, &[]);
    let failed =
        Device::Build { name: "broken".into(), build: Box::new(|| anyhow::bail!("no pipeline (injected)")) };
    let mut pool = starting_pool(&buffers, cpu(&buffers), failed);
    assert_same_sums("a failed build", &render(&mut pool, &buffers, 16, &[]), &one);
    let late = Device::Build {
        name: "late".into(),
        build: Box::new(|| {
            std::thread::sleep(std::time::Duration::from_secs(8));
            anyhow::bail!("too late")
        }),
    };
    let t = std::time::Instant::now();
    let mut pool = starting_pool(&buffers, cpu(&buffers), late);
    assert_same_sums("a late build", &render(&mut pool, &buffers, 16, &[]), &one);
    assert!(t.elapsed().as_secs() < 6, "the render waited {:?} for the build", t.elapsed());
    drop(pool);
    assert!(t.elapsed().as_secs() >= 8, "the pool was dropped with its build running ({:?})", t.elapsed());
}
