//! Progressive rendering: passes of a few samples per pixel until the budget is reached, each pass
//! short enough for GPU watchdogs, the image readable after any pass.
use crate::backend::Backend;
use crate::buffers::SceneBuffers;
use crate::film::Film;
use anyhow::Result;
use std::ops::ControlFlow::{self, Continue};
use std::time::{Duration, Instant};

/// How long one pass should take: long enough to amortise dispatch overhead, short enough that no
/// single GPU dispatch comes near a watchdog limit and progress stays responsive.
const TARGET_PASS: Duration = Duration::from_millis(150);
const MAX_SAMPLES_PER_PASS: u32 = 256;
/// Splatting integrators (ptracer, ibpt) estimate each pixel's variance from batch means over passes:
/// at least this many passes make that estimate trustworthy (with the 8 or so passes that pass-size
/// doubling gives a small image, the z-scores of light-traced images were t-distributed with 8 degrees
/// of freedom, and tests comparing them saw |z| of 3.5 from noise alone).
const MIN_BATCHES: u32 = 32;

pub struct RenderStats {
    pub spp: u32,
    pub seconds: f64,
    pub passes: u32,
}

/// Renders `spp` samples per pixel with `seed`, calling `progress(samples done)` after each pass.
pub fn render(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    spp: u32,
    seed: u32,
    mut progress: impl FnMut(u32),
) -> Result<(Film, RenderStats)> {
    let stats = render_with_checkpoints(backend, buffers, 0, spp, seed, &[], |done, _, _| {
        progress(done);
        Ok(Continue(()))
    })?;
    let accum = backend.read_accum()?;
    Ok((Film::from_accum(buffers.params.width, buffers.params.height, &accum), stats))
}

/// The pass loop, from sample `start` (a resumed render's accumulation buffer already holds the
/// samples before it: the counter-based random numbers make the continuation exactly what an
/// uninterrupted render would have drawn). Passes never run past a sample count listed in
/// `checkpoints`; after every pass `after_pass(samples done, render seconds so far, backend)` runs,
/// untimed (so a caller may read the image back at checkpoints without charging the render for it),
/// and may stop the render early with `Break` (the samples done so far stay in the backend).
pub fn render_with_checkpoints(
    backend: &mut dyn Backend,
    buffers: &SceneBuffers,
    start: u32,
    spp: u32,
    seed: u32,
    checkpoints: &[u32],
    mut after_pass: impl FnMut(u32, f64, &mut dyn Backend) -> Result<ControlFlow<()>>,
) -> Result<RenderStats> {
    let mut rendering = Duration::ZERO;
    let mut done = start;
    let mut per_pass = 1u32;
    let max_per_pass = if caustic_kernel::integrator::splats(buffers.params.integrator) {
        (spp / MIN_BATCHES).clamp(1, MAX_SAMPLES_PER_PASS)
    } else {
        MAX_SAMPLES_PER_PASS
    };
    let mut passes = 0u32;
    while done < spp {
        let next_stop = checkpoints.iter().copied().filter(|&c| c > done).min().unwrap_or(spp).min(spp);
        let count = per_pass.min(next_stop - done);
        let mut params = buffers.params;
        params.seed = seed;
        params.sample_base = done;
        params.sample_count = count;
        params.spp_total = spp;
        let t = Instant::now();
        backend.pass(&params)?;
        let elapsed = t.elapsed();
        rendering += elapsed;
        done += count;
        passes += 1;
        if after_pass(done, rendering.as_secs_f64(), backend)?.is_break() {
            break;
        }
        // Grow (at most doubling) or shrink the pass towards the target duration; a pass cut short by
        // a checkpoint says little about the right size, so only full passes adjust it.
        if count == per_pass {
            let ratio = TARGET_PASS.as_secs_f64() / elapsed.as_secs_f64().max(1e-6);
            per_pass = ((count as f64 * ratio.min(2.0)) as u32).clamp(1, max_per_pass);
        }
    }
    Ok(RenderStats { spp, seconds: rendering.as_secs_f64(), passes })
}
