//! Progressive rendering: passes of a few samples per pixel until the budget is reached, each pass
//! short enough for GPU watchdogs, the image readable after any pass. With several devices
//! (`backend::pool`), every idle device takes the next pass (a fast device takes more of them), and
//! the image is read when the loop has brought all of them to rest.
use crate::backend::accumulation;
use crate::backend::device::{Backend, Event, Lanes, Lost};
use crate::backend::schedule::Samples;
use crate::output::film::Film;
use crate::prepare::buffers::SceneBuffers;
use anyhow::{bail, Result};
use caustic_kernel::layout::FrameParams;
use std::ops::ControlFlow::{self, Continue};
use std::time::{Duration, Instant};

/// How long one pass should take: long enough that the slowest paths of a pass leave the GPU idle
/// for a small part of it, short enough that no dispatch nears a watchdog (Windows' default is 2 s).
/// Every pass waits for its longest paths: in the diamond (`bsdf_dielectric_diamond`), where total
/// internal reflection keeps some paths bouncing for hundreds of vertices, 150 ms passes (1 spp
/// each) ran at 7.35 Msamples/s and 1 s passes at 9.47 on the H100 (2026-11-24, same run); the
/// other scenes gained 0–1%. (On software adapters the GPU backend splits a pass into dispatches of
/// a few samples: llvmpipe cuts long-running invocations short, `backend::gpu`.)
pub const TARGET_PASS: Duration = Duration::from_millis(1000);
/// The pass length while a viewer shows the image as it converges (`--tev`), so that it updates
/// several times a second.
pub const INTERACTIVE_PASS: Duration = Duration::from_millis(250);

/// `default`, or `CAUSTIC_PASS_MS` milliseconds where that is set (for measurements).
fn target_pass(default: Duration) -> Result<Duration> {
    match std::env::var("CAUSTIC_PASS_MS") {
        Err(_) => Ok(default),
        Ok(v) => match v.trim().parse::<u64>() {
            Ok(ms) if ms > 0 => Ok(Duration::from_millis(ms)),
            _ => bail!("CAUSTIC_PASS_MS must be a positive whole number of milliseconds, not {v:?}"),
        },
    }
}

const MAX_SAMPLES_PER_PASS: u32 = 256;
/// Splatting integrators (ptracer, ibpt) and the splatting film estimate each pixel's variance from
/// batch means over passes:
/// at least this many passes make that estimate trustworthy (with the 8 or so passes that pass-size
/// doubling gives a small image, the z-scores of light-traced images were t-distributed with 8 degrees
/// of freedom, and tests comparing them saw |z| of 3.5 from noise alone).
const MIN_BATCHES: u32 = 32;

pub struct RenderStats {
    pub spp: u32,
    pub seconds: f64,
    pub passes: u32,
}

/// What the pass loop tells its caller, and when it stops for it.
pub trait PassObserver {
    /// After every pass: samples per pixel finished so far (with several devices, not necessarily
    /// the samples `[0, n)`).
    fn progress(&mut self, _finished: u32) {}
    /// Asked after every pass while several devices run: whether to bring them to rest for
    /// `at_rest` (a checkpoint or an image update is due). Each rest idles every device for part
    /// of a pass, so ask only as often as needed.
    fn wants_rest(&mut self, _seconds: f64) -> bool {
        false
    }
    /// No pass is running and the accumulation holds exactly the samples `[0, done)`: after every
    /// pass with one device; with several at `checkpoints`, at the end and when `wants_rest`.
    /// `Break` stops the render (the samples done stay in the backend).
    fn at_rest(&mut self, done: u32, seconds: f64, backend: &mut dyn Backend) -> Result<ControlFlow<()>>;
    /// How long a pass should take (`TARGET_PASS`; shorter where someone watches the image).
    fn pass_target(&self) -> Duration {
        TARGET_PASS
    }
    /// Whether the image's variance will be read. Batch means (light tracing, the splatting film)
    /// then need `MIN_BATCHES` passes; without it, passes grow as they would for any render (at 64
    /// spp, 32 passes of 2 spp each waited on the GPU in turn).
    fn needs_variance(&self) -> bool {
        true
    }
}

/// A closure as an observer that only rests (`render_with_checkpoints`).
struct AtRest<F>(F);

impl<F: FnMut(u32, f64, &mut dyn Backend) -> Result<ControlFlow<()>>> PassObserver for AtRest<F> {
    fn at_rest(&mut self, done: u32, seconds: f64, backend: &mut dyn Backend) -> Result<ControlFlow<()>> {
        (self.0)(done, seconds, backend)
    }
}

/// Renders `spp` samples per pixel with `seed`, calling `progress(samples finished)` after each pass.
pub fn render(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    spp: u32,
    seed: u32,
    progress: impl FnMut(u32),
) -> Result<(Film, RenderStats)> {
    struct Progress<P>(P);
    impl<P: FnMut(u32)> PassObserver for Progress<P> {
        fn progress(&mut self, finished: u32) {
            (self.0)(finished)
        }
        fn at_rest(&mut self, _: u32, _: f64, _: &mut dyn Backend) -> Result<ControlFlow<()>> {
            Ok(Continue(()))
        }
    }
    let stats = render_observed(backend, buffers, 0, spp, seed, &[], Progress(progress))?;
    let accum = backend.read_accum()?;
    Ok((Film::develop(buffers, &accum), stats))
}

/// One device as a lane: `start` keeps the pass, `finish` runs it.
struct One<'a> {
    backend: &'a mut dyn Backend,
    pending: Option<FrameParams>,
    alive: bool,
}

impl Lanes for One<'_> {
    fn count(&self) -> usize {
        1
    }
    fn is_alive(&self, _: usize) -> bool {
        self.alive
    }
    fn start(&mut self, _: usize, params: &FrameParams) {
        self.pending = Some(*params);
    }
    fn finish(&mut self) -> Event {
        let params = self.pending.take().expect("a pass was started");
        let t = Instant::now();
        match self.backend.pass(&params) {
            Ok(()) => Event::Passed(0, t.elapsed()),
            Err(error) => {
                self.alive = false;
                Event::Lost(0, Lost { device: self.backend.describe(), error, ranges: Vec::new() })
            }
        }
    }
    fn shares(&self) -> Vec<u64> {
        Vec::new()
    }
    fn backend(&mut self) -> &mut dyn Backend {
        self.backend
    }
}

/// The pass loop, from sample `start` (a resumed render's accumulation buffer already holds the
/// samples before it: the counter-based random numbers make the continuation exactly what an
/// uninterrupted render would have drawn). Passes never run past a sample count listed in
/// `checkpoints`; the observer's `at_rest` runs untimed (so a caller may read the image back at
/// checkpoints without charging the render for it); `after_pass` is the observer's `at_rest`: after
/// every pass with one device, at `checkpoints` and the end with several.
pub fn render_with_checkpoints(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    start: u32,
    spp: u32,
    seed: u32,
    checkpoints: &[u32],
    after_pass: impl FnMut(u32, f64, &mut dyn Backend) -> Result<ControlFlow<()>>,
) -> Result<RenderStats> {
    render_observed(backend, buffers, start, spp, seed, checkpoints, AtRest(after_pass))
}

/// `render_with_checkpoints` with an observer that also follows progress and asks for rests.
pub fn render_observed(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    start: u32,
    spp: u32,
    seed: u32,
    checkpoints: &[u32],
    observer: impl PassObserver,
) -> Result<RenderStats> {
    let span = Span { start, end: spp, spp };
    render_span(backend, buffers, span, seed, checkpoints, &mut Vec::new(), observer)
}

/// The samples `[start, end)` of a render of `spp` samples per pixel (an MPI rank's chunk).
#[derive(Clone, Copy, Debug)]
pub struct Span {
    pub start: u32,
    pub end: u32,
    pub spp: u32,
}

/// `render_observed` over a span of the samples. `per_pass` holds each device's pass size and is
/// carried from one span to the next (empty at first), so that a rank rendering many chunks does
/// not start every chunk again at one sample per pass.
pub fn render_span(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    span: Span,
    seed: u32,
    checkpoints: &[u32],
    per_pass: &mut Vec<u32>,
    mut observer: impl PassObserver,
) -> Result<RenderStats> {
    let Span { start, end, spp } = span;
    let mut one;
    // (Asked twice: a borrow returned from one arm of a match cannot be reused in the other.)
    let lanes: &mut dyn Lanes = if backend.lanes().is_some() {
        backend.lanes().expect("several devices")
    } else {
        one = One { backend, pending: None, alive: true };
        &mut one
    };
    let n = lanes.count();
    let max_per_pass = if accumulation::batch_means(&buffers.params) && observer.needs_variance() {
        (spp / MIN_BATCHES).clamp(1, MAX_SAMPLES_PER_PASS)
    } else {
        MAX_SAMPLES_PER_PASS
    };
    let target = target_pass(observer.pass_target())?;
    let mut samples = Samples::new(start);
    if per_pass.len() != n {
        *per_pass = vec![1u32; n];
    }
    let mut running: Vec<Option<(u32, u32)>> = vec![None; n];
    let (clock, mut untimed) = (Instant::now(), Duration::ZERO);
    let mut passes = 0u32;
    let mut resting = false;
    while samples.prefix() < end {
        let stop =
            checkpoints.iter().copied().filter(|&c| c > samples.prefix()).min().unwrap_or(end).min(end);
        if !resting {
            for lane in 0..n {
                if running[lane].is_some() || !lanes.takes_passes(lane) {
                    continue;
                }
                let Some((first, count)) = samples.claim(per_pass[lane], stop) else { break };
                let mut params = buffers.params;
                params.seed = seed;
                params.sample_base = first;
                params.sample_count = count;
                params.spp_total = spp;
                lanes.start(lane, &params);
                running[lane] = Some((first, count));
            }
        }
        if running.iter().all(Option::is_none) && !lanes.pending() {
            bail!("no pass to run at {} of {end} spp (internal error)", samples.prefix());
        }
        match lanes.finish() {
            Event::Passed(lane, elapsed) => {
                let range = running[lane].take().expect("the lane was running");
                samples.finish(range);
                passes += 1;
                observer.progress(samples.finished_total());
                // Grow (at most doubling) or shrink the pass towards the target duration; a pass cut
                // short by a checkpoint says little about the right size, so only full passes adjust it.
                if range.1 == per_pass[lane] {
                    let ratio = target.as_secs_f64() / elapsed.as_secs_f64().max(1e-6);
                    per_pass[lane] = ((range.1 as f64 * ratio.min(2.0)) as u32).clamp(1, max_per_pass);
                }
            }
            // A device built while the others rendered: the next round starts a pass on it.
            Event::Joined(_) => {}
            Event::Lost(lane, lost) if (0..n).any(|l| lanes.is_alive(l)) => {
                running[lane] = None;
                eprintln!(
                    "warning: {} failed ({:#}); the other devices render its {} unsaved pass(es) again",
                    lost.device,
                    lost.error,
                    lost.ranges.len()
                );
                samples.give_back(&lost.ranges);
            }
            Event::Lost(_, lost) => return Err(lost.error.context(format!("{} failed", lost.device))),
        }
        let seconds = (clock.elapsed() - untimed).as_secs_f64();
        if n > 1 && !resting && observer.wants_rest(seconds) {
            resting = true;
        }
        let idle = running.iter().all(Option::is_none);
        let at_stop = samples.prefix() == stop;
        if idle && (n == 1 || resting || at_stop) {
            resting = false;
            let t = Instant::now();
            let flow = observer.at_rest(samples.prefix(), seconds, lanes.backend())?;
            untimed += t.elapsed();
            if flow.is_break() {
                break;
            }
        }
    }
    Ok(RenderStats { spp, seconds: (clock.elapsed() - untimed).as_secs_f64(), passes })
}
