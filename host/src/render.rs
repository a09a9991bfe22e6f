//! Progressive rendering: passes of a few samples per pixel until the budget is reached, each pass
//! short enough for GPU watchdogs, the image readable after any pass.
use crate::backend::Backend;
use crate::buffers::SceneBuffers;
use crate::film::Film;
use anyhow::Result;
use std::time::{Duration, Instant};

/// How long one pass should take: long enough to amortise dispatch overhead, short enough that no
/// single GPU dispatch comes near a watchdog limit and progress stays responsive.
const TARGET_PASS: Duration = Duration::from_millis(150);
const MAX_SAMPLES_PER_PASS: u32 = 256;

pub struct RenderStats {
    pub spp: u32,
    pub seconds: f64,
    pub passes: u32,
}

/// Renders `spp` samples per pixel with `seed`, calling `progress(samples done)` after each pass.
pub fn render(backend: &mut dyn Backend, buffers: &SceneBuffers, spp: u32, seed: u32, mut progress: impl FnMut(u32)) -> Result<(Film, RenderStats)> {
    let start = Instant::now();
    let mut done = 0u32;
    let mut per_pass = 1u32;
    let mut passes = 0u32;
    while done < spp {
        let count = per_pass.min(spp - done);
        let mut params = buffers.params;
        params.seed = seed;
        params.sample_base = done;
        params.sample_count = count;
        params.spp_total = spp;
        let t = Instant::now();
        backend.pass(&params)?;
        let elapsed = t.elapsed();
        done += count;
        passes += 1;
        progress(done);
        // Grow (at most doubling) or shrink the pass towards the target duration.
        let ratio = TARGET_PASS.as_secs_f64() / elapsed.as_secs_f64().max(1e-6);
        per_pass = ((count as f64 * ratio.min(2.0)) as u32).clamp(1, MAX_SAMPLES_PER_PASS);
    }
    let accum = backend.read_accum()?;
    let film = Film::from_accum(buffers.params.width, buffers.params.height, accum);
    Ok((film, RenderStats { spp, seconds: start.elapsed().as_secs_f64(), passes }))
}
