//! What a device is to the rest of the host: a `Backend` adds samples to its accumulation, and
//! `Lanes` are several devices that run passes at once, with what they report (`Event`, `Lost`, the
//! `SampleRange`s a lost device takes with it). The two name each other (a backend may have lanes,
//! lanes are one backend), so they live together.
use super::accumulation::Accumulation;
use anyhow::{Error, Result};
use caustic_kernel::layout::FrameParams;
use std::time::Duration;

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
    /// Whether the backend runs as it will from now on: false while it still times its candidate
    /// pipelines (`variant`). `bench` warms up until it is.
    fn settled(&self) -> bool {
        true
    }
    /// Several devices that run passes at once (`pool::Pool`); `None` for one device.
    fn lanes(&mut self) -> Option<&mut dyn Lanes> {
        None
    }
}

/// A range of sample indices: (first, count).
pub type SampleRange = (u32, u32);

/// Devices that run passes concurrently: the pass loop starts a pass on an idle lane and waits for
/// whichever lane finishes first, so a fast device takes more passes than a slow one. A lane may
/// join late (a GPU whose pipelines are still being built while a CPU renders: `pool::Pool::starting`).
pub trait Lanes {
    fn count(&self) -> usize;
    fn is_alive(&self, lane: usize) -> bool;
    /// Whether the pass loop may start a pass on `lane` (alive, its device built, and not a stand-in
    /// that a device built since has relieved).
    fn takes_passes(&self, lane: usize) -> bool {
        self.is_alive(lane)
    }
    /// Whether a lane is still being built: `finish` will report it, joined or lost.
    fn pending(&self) -> bool {
        false
    }
    /// Starts a pass on an idle, live lane.
    fn start(&mut self, lane: usize, params: &FrameParams);
    /// Waits for the next event: a running pass ended (its lane, how long it took), a lane was lost
    /// (a running pass's or a build's), or a lane's device was built.
    fn finish(&mut self) -> Event;
    /// Samples per pixel each lane has rendered.
    fn shares(&self) -> Vec<u64>;
    /// The devices as one backend (only read while no pass runs).
    fn backend(&mut self) -> &mut dyn Backend;
}

/// What `Lanes::finish` reports.
pub enum Event {
    Passed(usize, Duration),
    Lost(usize, Lost),
    Joined(usize),
}

/// A lane that failed: the error, and the sample ranges whose sums died with the device (the pass
/// it was running and every pass finished since its accumulation was last read back).
pub struct Lost {
    pub device: String,
    pub error: Error,
    pub ranges: Vec<SampleRange>,
}
