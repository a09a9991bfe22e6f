//! The GPU time of each step of a pass (`CAUSTIC_STEP_TIMES=1`): the light paths, VCM's grid, the
//! camera paths and the splat words' resolve, timed by the device's timestamps around each
//! dispatch, summed over the render and printed when the backend ends. It answers where a
//! bidirectional sample's time goes, which `ncu` cannot (it does not see wgpu's Vulkan dispatches)
//! and the host's clock cannot (one submission holds every step of 16 passes).
//!
//! Off by default: timed, each step is a compute pass of its own and every submission's
//! timestamps are read back before the next, which costs a little of the time it measures.

use anyhow::Result;

/// Dispatches one submission may time (the backend's submissions hold at most 16 passes of at most
/// four steps).
const CAPACITY: u32 = 128;

/// Whether the user asked for step times and `adapter` can give them (said once where it cannot).
pub fn wanted_on(adapter: &wgpu::Adapter) -> bool {
    if std::env::var_os("CAUSTIC_STEP_TIMES").is_none_or(|v| v == "0") {
        return false;
    }
    let has = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
    if !has {
        eprintln!("note: CAUSTIC_STEP_TIMES: this adapter has no timestamp queries; no step times");
    }
    has
}

/// The timestamps of one submission's dispatches and the totals of every step so far.
pub struct StepTimes {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    staging: wgpu::Buffer,
    /// Nanoseconds a timestamp tick (`Queue::get_timestamp_period`).
    period: f64,
    /// Each timed dispatch of the current submission: its step's name.
    pending: Vec<&'static str>,
    /// Each step's name, seconds and dispatches, in the order steps first ran.
    totals: Vec<(&'static str, f64, u64)>,
}

impl StepTimes {
    /// The query set and buffers on `device`, opened with `TIMESTAMP_QUERY` (`wanted_on`).
    pub fn on(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let bytes = u64::from(CAPACITY) * 2 * 8;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        StepTimes {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("step times"),
                ty: wgpu::QueryType::Timestamp,
                count: CAPACITY * 2,
            }),
            resolved: buffer("step times", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            staging: buffer("step times read", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            period: f64::from(queue.get_timestamp_period()),
            pending: Vec::new(),
            totals: Vec::new(),
        }
    }

    /// The timestamp writes around the next dispatch, step `name`'s (`None` past the capacity).
    pub fn around(&mut self, name: &'static str) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let index = self.pending.len() as u32;
        if index >= CAPACITY {
            return None;
        }
        self.pending.push(name);
        Some(wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * index),
            end_of_pass_write_index: Some(2 * index + 1),
        })
    }

    /// Copies the submission's timestamps out (recorded at its end).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let count = 2 * self.pending.len() as u32;
        if count > 0 {
            encoder.resolve_query_set(&self.queries, 0..count, &self.resolved, 0);
            encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.staging, 0, u64::from(count) * 8);
        }
    }

    /// Adds the submission's timestamps to the totals, once the GPU has finished it.
    pub fn collect(&mut self, device: &wgpu::Device) -> Result<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let size = self.pending.len() as u64 * 16;
        let bytes = super::readback::map_read(device, self.staging.slice(..size), "the step times")?;
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        for (name, pair) in self.pending.drain(..).zip(ticks.chunks_exact(2)) {
            let seconds = pair[1].saturating_sub(pair[0]) as f64 * self.period * 1e-9;
            match self.totals.iter_mut().find(|t| t.0 == name) {
                Some(t) => (t.1, t.2) = (t.1 + seconds, t.2 + 1),
                None => self.totals.push((name, seconds, 1)),
            }
        }
        Ok(())
    }

    /// One line a step: its total, its share of all steps' and its mean per dispatch.
    pub fn report(&self) -> String {
        let all: f64 = self.totals.iter().map(|t| t.1).sum();
        let lines: Vec<String> = (self.totals.iter())
            .map(|(name, seconds, count)| {
                format!(
                    "steps: {name:<20} {:>9.2} ms {:>5.1}% {count:>6} dispatches, {:.3} ms each",
                    seconds * 1e3,
                    100.0 * seconds / all.max(f64::MIN_POSITIVE),
                    seconds * 1e3 / *count as f64
                )
            })
            .collect();
        lines.join("\n")
    }
}
