//! MPI (`--features mpi`): `mpirun -n N caustic render …` (or `srun` under Slurm) renders one image
//! with the ranks taking chunks of the samples as they become free (`shares.rs` decides, a thread
//! of rank 0 answers), summed on rank 0 by `MPI_Reduce` at checkpoints and at the end. Also what a
//! rank's failure or silence turns into: a message naming it, and what rank 0 had summed written out.
use crate::backend::accumulation::Accumulation;
use crate::render::ranks::{Plan, Ranks};
use crate::render::shares::{Dispatcher, Work};
use anyhow::{anyhow, bail, Result};
use mpi::point_to_point::MatchedReceiveVec;
use mpi::traits::*;
use std::cell::RefCell;
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// A rank that finished its chunk asks for work; a rank whose render failed sends its error.
const TAG_READY: i32 = 1;
const TAG_FAILED: i32 = 2;
/// Rank 0's answer to `TAG_READY`: `[kind, a, b]` (`encode`).
const TAG_WORK: i32 = 3;
/// Longest a rank may be silent while the render waits for it, unless `CAUSTIC_MPI_STALL` (seconds)
/// says otherwise: scene loading and pipeline compilation of a large scene take minutes.
const STALL: Duration = Duration::from_secs(600);
/// Bytes of a host name exchanged at start.
const NAME: usize = 64;

/// A communicator used by rank 0's dispatcher thread. MPI handles are plain pointers to Rust; MPI
/// itself allows any thread to use them once initialised with `MPI_THREAD_MULTIPLE` (`World::init`
/// refuses less), and only that thread uses this one.
struct ThreadComm(mpi::topology::SimpleCommunicator);
// SAFETY: see above: MPI_THREAD_MULTIPLE, and one thread at a time uses the communicator.
unsafe impl Send for ThreadComm {}

/// The dispatcher's state, shared by its thread (the other ranks' requests) and rank 0's own
/// render loop (its requests, made directly).
struct Shared {
    dispatcher: Dispatcher,
    progress: indicatif::ProgressBar,
    start: u32,
    /// Set once rank 0 has the final sum: the thread, which until then watches for signals and
    /// silent ranks (a rank may die in the final sum), ends.
    closed: bool,
}

impl Shared {
    fn request(&mut self, rank: usize) -> Work {
        let work = self.dispatcher.request(rank, Instant::now());
        self.progress.set_position(self.start as u64 + self.dispatcher.finished_total());
        work
    }
}

/// The world communicator; MPI is finalised when it is dropped.
pub struct World {
    // Dropped last (fields drop in order): MPI_Finalize after everything else.
    world: mpi::topology::SimpleCommunicator,
    /// A duplicate for the work requests, so that they never mix with the collectives.
    work: RefCell<Option<ThreadComm>>,
    hosts: Vec<String>,
    shared: RefCell<Option<Arc<Mutex<Shared>>>>,
    /// Rank 0: what writes out the sums when the render cannot finish (`Plan::lost`).
    lost: RefCell<Option<crate::render::ranks::Lost>>,
    thread: RefCell<Option<JoinHandle<()>>>,
    _universe: mpi::environment::Universe,
}

impl World {
    pub fn init() -> Result<World> {
        use mpi::Threading;
        let (universe, threading) = mpi::initialize_with_threading(Threading::Multiple)
            .ok_or_else(|| anyhow!("MPI was already initialised"))?;
        if threading != Threading::Multiple {
            bail!(
                "this MPI library offers {threading:?} threading, and caustic needs MPI_THREAD_MULTIPLE \
                 (rank 0 answers the other ranks' requests for samples from a thread of its own)"
            );
        }
        let world = universe.world();
        let work = world.duplicate();
        let mut mine = [b' '; NAME];
        let host = mpi::environment::processor_name().unwrap_or_else(|_| "an unnamed host".into());
        for (m, b) in mine.iter_mut().zip(host.bytes()) {
            *m = b;
        }
        let mut all = vec![b' '; NAME * world.size() as usize];
        world.all_gather_into(&mine[..], &mut all[..]);
        let hosts = all.chunks(NAME).map(|c| String::from_utf8_lossy(c).trim_end().to_string()).collect();
        Ok(World {
            world,
            work: RefCell::new(Some(ThreadComm(work))),
            hosts,
            shared: RefCell::new(None),
            lost: RefCell::new(None),
            thread: RefCell::new(None),
            _universe: universe,
        })
    }

    fn with_work<T>(&self, f: impl FnOnce(&mpi::topology::SimpleCommunicator) -> T) -> T {
        f(&self.work.borrow().as_ref().expect("the work communicator (rank 0 gave it to its thread)").0)
    }
}

impl World {
    /// Ends rank 0's dispatcher thread (after the final sum, or on the way out).
    fn close(&self) {
        if let Some(shared) = self.shared.borrow().as_ref() {
            shared.lock().unwrap_or_else(PoisonError::into_inner).closed = true;
        }
        if let Some(thread) = self.thread.borrow_mut().take() {
            thread.join().ok();
        }
    }
}

impl Drop for World {
    fn drop(&mut self) {
        // The dispatcher's thread uses MPI: it ends before MPI_Finalize.
        self.close();
    }
}

fn encode(work: Work) -> [u32; 3] {
    match work {
        Work::Chunk { first, count } => [0, first, count],
        Work::Checkpoint { done } => [1, done, 0],
        Work::Finish { done } => [2, done, 0],
    }
}

fn decode(words: &[u32]) -> Result<Work> {
    Ok(match words {
        [0, first, count] => Work::Chunk { first: *first, count: *count },
        [1, done, _] => Work::Checkpoint { done: *done },
        [2, done, _] => Work::Finish { done: *done },
        _ => bail!("rank 0 sent a message this rank does not understand: {words:?}"),
    })
}

/// `rank R on HOST`, for messages (`hosts`: every rank's host name, gathered at start).
fn rank_name(hosts: &[String], rank: usize) -> String {
    format!("rank {rank} on {}", hosts.get(rank).map_or("?", String::as_str))
}

/// How long a rank may be silent before the render gives up on it (`STALL`).
fn stall_limit() -> Duration {
    std::env::var("CAUSTIC_MPI_STALL")
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .unwrap_or(STALL)
}

/// Rank 0's dispatcher thread: answers requests for work until every rank has been told to finish;
/// ends the job, after `plan.lost` has written what was summed, when a rank fails, stays silent
/// past the stall limit, or a signal arrives (Open MPI's mpirun sends SIGTERM to every rank when
/// one dies, and SIGKILL a second later).
fn serve(comm: ThreadComm, shared: Arc<Mutex<Shared>>, hosts: Vec<String>, lost: crate::render::ranks::Lost) {
    let comm = comm.0;
    let lock = || shared.lock().unwrap_or_else(PoisonError::into_inner);
    let name = |rank: usize| rank_name(&hosts, rank);
    let stall = stall_limit();
    loop {
        if lock().closed {
            return;
        }
        if let Some((message, status)) = comm.any_process().immediate_matched_probe() {
            let from = status.source_rank() as usize;
            match status.tag() {
                TAG_READY => {
                    let _: (Vec<u32>, _) = (message, status).matched_receive_vec();
                    let work = lock().request(from);
                    comm.process_at_rank(from as i32).send_with_tag(&encode(work)[..], TAG_WORK);
                }
                TAG_FAILED => {
                    let (text, _): (Vec<u8>, _) = (message, status).matched_receive_vec();
                    lost(&format!("{} failed: {}", name(from), String::from_utf8_lossy(&text)));
                    comm.abort(1);
                }
                _ => {
                    let _: (Vec<u8>, _) = (message, status).matched_receive_vec();
                }
            }
            continue;
        }
        if let Some(signal) = crate::system::interrupt::requested() {
            let held: Vec<String> = lock()
                .dispatcher
                .held()
                .filter(|&(rank, _)| rank != 0)
                .map(|(rank, h)| format!("{} (samples {}..{})", name(rank), h.first, h.first + h.count))
                .collect();
            let when = match (held.is_empty(), lock().dispatcher.finished()) {
                (false, _) => format!("while {} rendered", held.join(", ")),
                (true, true) => "in the final sum".to_string(),
                (true, false) => "while no other rank held samples".to_string(),
            };
            lost(&format!(
                "signal {signal} {when}: mpirun sends it to every rank when one dies (its own message \
                 names that rank) or on an interrupt"
            ));
            std::process::exit(crate::system::interrupt::exit_code(signal));
        }
        let stalled = lock().dispatcher.stalled(Instant::now(), stall);
        if let Some((rank, held)) = stalled {
            let what = match held {
                Some(h) => format!("rendering samples {}..{}", h.first, h.first + h.count),
                None => "waited for".to_string(),
            };
            lost(&format!(
                "{} stopped responding ({what}, silent for over {:.0} s: set CAUSTIC_MPI_STALL=SECONDS \
                 to wait longer)",
                name(rank),
                stall.as_secs_f64()
            ));
            comm.abort(1);
        }
        // A request waits at most this long for an answer; a pass takes ~150 ms.
        std::thread::sleep(Duration::from_millis(1));
    }
}

impl Ranks for World {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn name(&self, rank: usize) -> String {
        rank_name(&self.hosts, rank)
    }

    fn reduce(&self, accum: &Accumulation) -> Result<Option<Accumulation>> {
        use mpi::collective::SystemOperation;
        let root = self.world.process_at_rank(0);
        let sums: &[f64] = bytemuck::cast_slice(&accum.pixels);
        let batches = [accum.batches.unwrap_or(0)];
        if self.world.rank() != 0 {
            root.reduce_into(sums, SystemOperation::sum());
            root.reduce_into(&batches[..], SystemOperation::sum());
            return Ok(None);
        }
        let mut total = vec![0f64; sums.len()];
        let mut total_batches = [0u32];
        root.reduce_into_root(sums, &mut total[..], SystemOperation::sum());
        root.reduce_into_root(&batches[..], &mut total_batches[..], SystemOperation::sum());
        Ok(Some(Accumulation {
            pixels: bytemuck::pod_collect_to_vec(&total),
            batches: accum.batches.map(|_| total_batches[0]),
        }))
    }

    fn agree(&self, start: Option<u32>) -> Result<u32> {
        let mine = [start.is_some() as u32, start.unwrap_or(0)];
        let mut all = vec![0u32; 2 * self.size()];
        self.world.all_gather_into(&mine[..], &mut all[..]);
        let failed: Vec<String> =
            all.chunks(2).enumerate().filter(|(_, c)| c[0] == 0).map(|(r, _)| self.name(r)).collect();
        if !failed.is_empty() {
            bail!("{} could not start (its message above says why)", failed.join(", "));
        }
        Ok(all[1])
    }

    fn dispatch(&self, plan: Plan) -> Result<()> {
        let now = Instant::now();
        let shared = Arc::new(Mutex::new(Shared {
            dispatcher: Dispatcher::new(plan.start, plan.spp, self.size(), plan.every, now),
            progress: plan.progress,
            start: plan.start,
            closed: false,
        }));
        let comm = self.work.borrow_mut().take().ok_or_else(|| anyhow!("the render was dispatched twice"))?;
        let (hosts, theirs, lost) = (self.hosts.clone(), shared.clone(), plan.lost.clone());
        let thread = std::thread::Builder::new()
            .name("caustic-dispatch".into())
            .spawn(move || serve(comm, theirs, hosts, lost))?;
        *self.lost.borrow_mut() = Some(plan.lost);
        *self.shared.borrow_mut() = Some(shared);
        *self.thread.borrow_mut() = Some(thread);
        Ok(())
    }

    fn next_work(&self) -> Result<Work> {
        if let Some(shared) = self.shared.borrow().as_ref() {
            return Ok(shared.lock().unwrap_or_else(PoisonError::into_inner).request(0));
        }
        self.with_work(|comm| {
            let root = comm.process_at_rank(0);
            root.send_with_tag(&[0u32][..], TAG_READY);
            let (words, _) = root.receive_vec_with_tag::<u32>(TAG_WORK);
            decode(&words)
        })
    }

    fn shares(&self) -> Vec<u64> {
        self.close();
        self.shared.borrow().as_ref().map_or_else(Vec::new, |s| {
            s.lock().unwrap_or_else(PoisonError::into_inner).dispatcher.samples().to_vec()
        })
    }

    fn fail(&self, error: &anyhow::Error) -> ! {
        let text = format!("{error:#}");
        if self.rank() == 0 {
            // Rank 0 itself: write what was summed, name it and end the job from here.
            match self.lost.borrow().as_ref() {
                Some(lost) => lost(&format!("{} failed: {text}", self.name(0))),
                None => eprintln!("error: {} failed: {text}", self.name(0)),
            }
            self.world.abort(1);
        }
        self.with_work(|comm| comm.process_at_rank(0).send_with_tag(text.as_bytes(), TAG_FAILED));
        // Rank 0 writes what it had summed and aborts the job, which ends this process too.
        loop {
            std::thread::sleep(Duration::from_secs(60));
        }
    }

    fn barrier(&self) {
        self.world.barrier();
    }
}
