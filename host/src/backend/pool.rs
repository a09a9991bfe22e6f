//! Several devices as one backend: one thread per device, each with its own device, pipelines and
//! accumulation buffer; the pass loop (`render::passes`) hands passes to whichever device is idle and the
//! accumulations are summed when read. A device that fails loses only the samples since its sums
//! were last read back (`device::Lost`); the others render them again.
//!
//! A device may also be built on its thread while the others render (`Pool::starting`): a GPU
//! meeting a scene whose kernel it has not compiled spends tens of seconds building its pipelines
//! (`backend::prune`, the driver), and a CPU stand-in renders meanwhile, so that the first image
//! comes at the CPU's pace instead of after the build. Once a built device joins, the stand-in
//! takes no more passes (unless every built device is lost); what it rendered stays in the sum. A
//! render the stand-in completes is written before the pool waits for the build to end (`Drop`).
use super::accumulation::Accumulation;
use super::device::Backend;
use super::device::{Event, Lanes, Lost, SampleRange};
use anyhow::{anyhow, bail, Result};
use caustic_kernel::layout::FrameParams;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

enum Command {
    /// Boxed: the frame's parameters are most of the enum's size (240 bytes against 32).
    Pass(Box<FrameParams>),
    Read,
    Write(Accumulation),
}

enum Reply {
    Passed(Result<Duration>),
    Accum(Result<Accumulation>),
    Written(Result<()>),
    /// A device built on its lane's thread: its description, or why it could not be built.
    Built(Result<String>),
}

/// A device for a lane: one that exists, or one to build on the lane's thread.
pub enum Device {
    Ready(Box<dyn Backend + Send>),
    Build { name: String, build: Box<dyn FnOnce() -> Result<Box<dyn Backend + Send>> + Send> },
}

struct Lane {
    name: String,
    /// `None` once the lane is lost (its thread then ends).
    commands: Option<Sender<Command>>,
    thread: Option<JoinHandle<()>>,
    /// Its accumulation when last read back: what survives if the device is lost.
    banked: Accumulation,
    /// Ranges finished since, and the one running.
    unbanked: Vec<SampleRange>,
    running: Option<SampleRange>,
    /// Samples per pixel this device rendered (statistics).
    samples: u64,
    /// Its device exists (false while it is built on the lane's thread).
    ready: bool,
    /// It renders only while no other lane's device is ready (`Pool::starting`).
    stand_in: bool,
}

pub struct Pool {
    lanes: Vec<Lane>,
    replies: Receiver<(usize, Reply)>,
    /// A resumed checkpoint's sums, kept on the host and added when the pool is read.
    base: Accumulation,
    /// A lane that could not be sent its pass: reported by the next `finish`.
    unsent: Vec<(usize, Error)>,
    /// Lanes whose device was built (or failed to be) since the last `finish`: reported by it.
    built: Vec<Result<usize, (usize, Error)>>,
}

type Error = anyhow::Error;

/// Runs a backend call on the device's thread, turning a panic into an error.
fn guarded<T>(name: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| Err(anyhow!("{name}: the device's thread panicked")))
}

impl Pool {
    /// One lane per backend; `empty` is an empty accumulation of the render's size and kind.
    pub fn new(backends: Vec<Box<dyn Backend + Send>>, empty: Accumulation) -> Result<Pool> {
        Self::with_devices(backends.into_iter().map(|b| (Device::Ready(b), false)).collect(), empty)
    }

    /// `stand_in` renders at once while each of `devices` is built on its lane's thread; once one is
    /// built the stand-in stops taking passes.
    pub fn starting(
        stand_in: Box<dyn Backend + Send>,
        devices: Vec<Device>,
        empty: Accumulation,
    ) -> Result<Pool> {
        let mut lanes = vec![(Device::Ready(stand_in), true)];
        lanes.extend(devices.into_iter().map(|d| (d, false)));
        Self::with_devices(lanes, empty)
    }

    fn with_devices(devices: Vec<(Device, bool)>, empty: Accumulation) -> Result<Pool> {
        if devices.is_empty() {
            bail!("no device to render on");
        }
        let (reply_tx, replies) = channel();
        let mut lanes = Vec::with_capacity(devices.len());
        for (index, (device, stand_in)) in devices.into_iter().enumerate() {
            let (name, ready) = match &device {
                Device::Ready(b) => (b.describe(), true),
                Device::Build { name, .. } => (name.clone(), false),
            };
            let (tx, rx) = channel::<Command>();
            let reply_tx: Sender<(usize, Reply)> = reply_tx.clone();
            let thread_name = name.clone();
            let thread =
                std::thread::Builder::new().name(format!("caustic-device-{index}")).spawn(move || {
                    let mut backend = match device {
                        Device::Ready(b) => b,
                        Device::Build { build, .. } => match guarded(&thread_name, build) {
                            Ok(b) => {
                                if reply_tx.send((index, Reply::Built(Ok(b.describe())))).is_err() {
                                    return;
                                }
                                b
                            }
                            Err(e) => {
                                let _ = reply_tx.send((index, Reply::Built(Err(e))));
                                return;
                            }
                        },
                    };
                    for command in rx {
                        let reply = match command {
                            Command::Pass(params) => Reply::Passed(guarded(&thread_name, || {
                                let t = Instant::now();
                                backend.pass(&params)?;
                                Ok(t.elapsed())
                            })),
                            Command::Read => Reply::Accum(guarded(&thread_name, || backend.read_accum())),
                            Command::Write(a) => {
                                Reply::Written(guarded(&thread_name, || backend.write_accum(&a)))
                            }
                        };
                        if reply_tx.send((index, reply)).is_err() {
                            break;
                        }
                    }
                })?;
            lanes.push(Lane {
                name,
                commands: Some(tx),
                thread: Some(thread),
                banked: empty.clone(),
                unbanked: Vec::new(),
                running: None,
                samples: 0,
                ready,
                stand_in,
            });
        }
        Ok(Pool { lanes, replies, base: empty, unsent: Vec::new(), built: Vec::new() })
    }

    /// Records that lane `index`'s device was built (or not: the lane is then lost, which the next
    /// `finish` reports).
    fn on_built(&mut self, index: usize, result: Result<String>) {
        let lane = &mut self.lanes[index];
        match result {
            Ok(description) => {
                lane.ready = true;
                lane.name = description;
                self.built.push(Ok(index));
            }
            Err(e) => {
                lane.commands = None;
                self.built.push(Err((index, e.context(format!("{}: could not be started", lane.name)))));
            }
        }
    }

    /// Sends `command` to every live lane whose device is built and collects their replies (no pass
    /// may be running). Lanes still being built hold nothing yet.
    fn each_live(&mut self, command: impl Fn() -> Command) -> Result<Vec<(usize, Reply)>> {
        let mut waiting = 0;
        for lane in self.lanes.iter().filter(|l| l.ready) {
            if let Some(tx) = &lane.commands {
                tx.send(command()).map_err(|_| anyhow!("{}: the device's thread has ended", lane.name))?;
                waiting += 1;
            }
        }
        let mut replies = Vec::with_capacity(waiting);
        while replies.len() < waiting {
            match self.replies.recv().map_err(|_| anyhow!("every device thread has ended"))? {
                (index, Reply::Built(result)) => self.on_built(index, result),
                reply => replies.push(reply),
            }
        }
        Ok(replies)
    }
}

impl Backend for Pool {
    fn describe(&self) -> String {
        let names: Vec<&str> = self.lanes.iter().map(|l| l.name.as_str()).collect();
        format!("{} devices: {}", names.len(), names.join(" + "))
    }

    /// The pass loop spreads passes over the devices itself; a pass asked for directly runs on the
    /// first live device.
    fn pass(&mut self, params: &FrameParams) -> Result<()> {
        let lane = (0..self.lanes.len())
            .find(|&l| self.takes_passes(l))
            .or_else(|| (0..self.lanes.len()).find(|&l| self.lanes[l].ready && self.is_alive(l)))
            .ok_or_else(|| anyhow!("no device left"))?;
        self.start(lane, params);
        loop {
            match self.finish() {
                Event::Passed(..) => return Ok(()),
                Event::Lost(l, lost) if l == lane => return Err(lost.error),
                // Another lane's build ended meanwhile: noted, and reported by the pass loop's rounds.
                Event::Joined(_) | Event::Lost(..) => {}
            }
        }
    }

    /// Reads every device back and sums: the devices' sums at this point become what survives a
    /// later loss. Only while no pass runs (the pass loop reads at rest).
    fn read_accum(&mut self) -> Result<Accumulation> {
        for (index, reply) in self.each_live(|| Command::Read)? {
            let lane = &mut self.lanes[index];
            match reply {
                Reply::Accum(Ok(a)) => {
                    lane.banked = a;
                    lane.unbanked.clear();
                }
                Reply::Accum(Err(e)) => return Err(e.context(format!("{}: cannot read its sums", lane.name))),
                _ => bail!("{}: unexpected reply to a read", lane.name),
            }
        }
        let mut total = self.base.clone();
        for lane in &self.lanes {
            total.add(&lane.banked);
        }
        Ok(total)
    }

    /// Keeps `accum` on the host and clears every device.
    fn write_accum(&mut self, accum: &Accumulation) -> Result<()> {
        anyhow::ensure!(
            accum.pixels.len() == self.base.pixels.len()
                && accum.batches.is_some() == self.base.batches.is_some(),
            "accumulation buffer of {} pixels, expected {}",
            accum.pixels.len(),
            self.base.pixels.len()
        );
        let empty = accum.empty_like();
        for (index, reply) in self.each_live(|| Command::Write(empty.clone()))? {
            let lane = &mut self.lanes[index];
            match reply {
                Reply::Written(r) => r?,
                _ => bail!("{}: unexpected reply to a write", lane.name),
            }
            lane.banked = empty.clone();
            lane.unbanked.clear();
        }
        self.base = accum.clone();
        Ok(())
    }

    fn lanes(&mut self) -> Option<&mut dyn Lanes> {
        Some(self)
    }
}

impl Lanes for Pool {
    fn count(&self) -> usize {
        self.lanes.len()
    }

    fn is_alive(&self, lane: usize) -> bool {
        self.lanes[lane].commands.is_some()
    }

    fn takes_passes(&self, lane: usize) -> bool {
        let l = &self.lanes[lane];
        let relieved = || self.lanes.iter().any(|o| !o.stand_in && o.ready && o.commands.is_some());
        l.commands.is_some() && l.ready && !(l.stand_in && relieved())
    }

    fn pending(&self) -> bool {
        self.lanes.iter().any(|l| !l.ready && l.commands.is_some())
    }

    fn start(&mut self, index: usize, params: &FrameParams) {
        let lane = &mut self.lanes[index];
        lane.running = Some((params.sample_base, params.sample_count));
        let sent = lane.commands.as_ref().map(|tx| tx.send(Command::Pass(Box::new(*params))).is_ok());
        if sent != Some(true) {
            self.unsent.push((index, anyhow!("the device's thread has ended")));
        }
    }

    fn finish(&mut self) -> Event {
        if let Some(built) = self.built.pop() {
            return match built {
                Ok(index) => Event::Joined(index),
                Err((index, error)) => {
                    let device = self.lanes[index].name.clone();
                    Event::Lost(index, Lost { device, error, ranges: Vec::new() })
                }
            };
        }
        let (index, result) = match self.unsent.pop() {
            Some((index, e)) => (index, Err(e)),
            None => match self.replies.recv() {
                Ok((index, Reply::Passed(r))) => (index, r),
                Ok((index, Reply::Built(result))) => {
                    self.on_built(index, result);
                    return self.finish();
                }
                Ok((index, _)) => (index, Err(anyhow!("unexpected reply to a pass"))),
                // Every lane thread holds a sender while it lives, and `finish` is called only with
                // a pass running or a lane being built, so the channel cannot close first; treat it
                // as losing lane 0.
                Err(_) => (0, Err(anyhow!("every device thread has ended"))),
            },
        };
        let lane = &mut self.lanes[index];
        let running = lane.running.take();
        match result {
            Ok(elapsed) => {
                if let Some(r) = running {
                    lane.unbanked.push(r);
                    lane.samples += r.1 as u64;
                }
                Event::Passed(index, elapsed)
            }
            Err(error) => {
                // The device is gone with its sums since the last read: give those samples back.
                lane.commands = None;
                let mut ranges = std::mem::take(&mut lane.unbanked);
                ranges.extend(running);
                Event::Lost(index, Lost { device: lane.name.clone(), error, ranges })
            }
        }
    }

    fn shares(&self) -> Vec<u64> {
        self.lanes.iter().map(|l| l.samples).collect()
    }

    fn backend(&mut self) -> &mut dyn Backend {
        self
    }
}

impl Drop for Pool {
    /// Ends every lane's thread. A lane still building its device is waited for (the render it was
    /// built for is complete and written by now): a process that exits with a thread inside the
    /// GPU driver's compiler crashed there on an H200 (2026-11-29), and the finished build leaves the
    /// driver's pipeline cache on disk, so that the scene's next render starts on the GPU.
    fn drop(&mut self) {
        if self.pending() {
            eprintln!(
                "note: waiting for the GPU's pipelines to finish building (cached for the next render)"
            );
        }
        for lane in &mut self.lanes {
            lane.commands = None;
        }
        for lane in &mut self.lanes {
            if let Some(t) = lane.thread.take() {
                let _ = t.join();
            }
        }
    }
}
