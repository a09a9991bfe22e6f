//! Several devices as one backend: one thread per device, each with its own device, pipelines and
//! accumulation buffer; the pass loop (`render::passes`) hands passes to whichever device is idle and the
//! accumulations are summed when read. A device that fails loses only the samples since its sums
//! were last read back (`schedule::Lost`); the others render them again.
use super::accumulation::Accumulation;
use super::schedule::{Lanes, Lost, SampleRange};
use super::Backend;
use anyhow::{anyhow, bail, Result};
use caustic_kernel::layout::FrameParams;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

enum Command {
    Pass(FrameParams),
    Read,
    Write(Accumulation),
}

enum Reply {
    Passed(Result<Duration>),
    Accum(Result<Accumulation>),
    Written(Result<()>),
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
}

pub struct Pool {
    lanes: Vec<Lane>,
    replies: Receiver<(usize, Reply)>,
    /// A resumed checkpoint's sums, kept on the host and added when the pool is read.
    base: Accumulation,
    /// A lane that could not be sent its pass: reported by the next `finish`.
    unsent: Vec<(usize, Error)>,
}

type Error = anyhow::Error;

/// Runs a backend call on the device's thread, turning a panic into an error.
fn guarded<T>(name: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| Err(anyhow!("{name}: the device's thread panicked")))
}

impl Pool {
    /// One lane per backend; `empty` is an empty accumulation of the render's size and kind.
    pub fn new(backends: Vec<Box<dyn Backend + Send>>, empty: Accumulation) -> Result<Pool> {
        if backends.is_empty() {
            bail!("no device to render on");
        }
        let (reply_tx, replies) = channel();
        let mut lanes = Vec::with_capacity(backends.len());
        for (index, mut backend) in backends.into_iter().enumerate() {
            let name = backend.describe();
            let (tx, rx) = channel::<Command>();
            let reply_tx: Sender<(usize, Reply)> = reply_tx.clone();
            let thread_name = name.clone();
            let thread =
                std::thread::Builder::new().name(format!("caustic-device-{index}")).spawn(move || {
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
            });
        }
        Ok(Pool { lanes, replies, base: empty, unsent: Vec::new() })
    }

    /// Sends `command` to every live lane and collects their replies (no pass may be running).
    fn each_live(&mut self, command: impl Fn() -> Command) -> Result<Vec<(usize, Reply)>> {
        let mut waiting = 0;
        for lane in &self.lanes {
            if let Some(tx) = &lane.commands {
                tx.send(command()).map_err(|_| anyhow!("{}: the device's thread has ended", lane.name))?;
                waiting += 1;
            }
        }
        (0..waiting)
            .map(|_| self.replies.recv().map_err(|_| anyhow!("every device thread has ended")))
            .collect()
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
        let lane =
            (0..self.lanes.len()).find(|&l| self.is_alive(l)).ok_or_else(|| anyhow!("no device left"))?;
        self.start(lane, params);
        match self.finish() {
            (_, Ok(_)) => Ok(()),
            (_, Err(lost)) => Err(lost.error),
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

    fn start(&mut self, index: usize, params: &FrameParams) {
        let lane = &mut self.lanes[index];
        lane.running = Some((params.sample_base, params.sample_count));
        let sent = lane.commands.as_ref().map(|tx| tx.send(Command::Pass(*params)).is_ok());
        if sent != Some(true) {
            self.unsent.push((index, anyhow!("the device's thread has ended")));
        }
    }

    fn finish(&mut self) -> (usize, Result<Duration, Lost>) {
        let (index, result) = match self.unsent.pop() {
            Some((index, e)) => (index, Err(e)),
            None => match self.replies.recv() {
                Ok((index, Reply::Passed(r))) => (index, r),
                Ok((index, _)) => (index, Err(anyhow!("unexpected reply to a pass"))),
                // Every lane thread holds a sender while it lives, and `finish` is called only with
                // a pass running, so the channel cannot close first; treat it as losing lane 0.
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
                (index, Ok(elapsed))
            }
            Err(error) => {
                // The device is gone with its sums since the last read: give those samples back.
                lane.commands = None;
                let mut ranges = std::mem::take(&mut lane.unbanked);
                ranges.extend(running);
                (index, Err(Lost { device: lane.name.clone(), error, ranges }))
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
    fn drop(&mut self) {
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
