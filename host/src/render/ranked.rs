//! A render session over several MPI ranks: every rank loads the scene and renders the chunks of
//! samples rank 0 hands it (`shares.rs`), the accumulations are summed on rank 0 at each checkpoint
//! (which rank 0 writes, in the one-process format) and at the end (the image). If the render
//! cannot finish (a rank fails, stops responding, or mpirun ends the job), rank 0 writes the image
//! of what it last summed, marked partial, and names the rank.
//!
//! For tests only: `CAUSTIC_MPI_TEST_SLOW=R:MS` makes rank R sleep MS milliseconds per sample per
//! pixel it renders (a slow rank); `CAUSTIC_MPI_TEST_EXIT=R` makes rank R exit at once, without
//! telling MPI, when it receives its first chunk after its second checkpoint (a rank that dies;
//! after the second, so that rank 0 has written the first); `CAUSTIC_MPI_TEST_FAIL=R` makes that
//! chunk's render fail with an error instead (a rank whose device fails).
use crate::backend::accumulation::Accumulation;
use crate::backend::{self, Backend};
use crate::output::film::{self, Film};
use crate::output::tev;
use crate::render::checkpoint::{self, Checkpoint};
use crate::render::passes::{self, PassObserver, Span};
use crate::render::ranks::{Plan, Ranks};
use crate::render::session::{self, RenderJob, RenderReport};
use crate::render::shares::Work;
use anyhow::Result;
use std::ops::ControlFlow::{self, Continue};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// What rank 0 has summed: `[0, done)` of all ranks (at the last checkpoint).
struct Summed {
    accum: Option<Accumulation>,
    done: u32,
}

/// One rank's render, ready to go.
struct Prepared {
    buffers: crate::prepare::buffers::SceneBuffers,
    spp: u32,
    backend: Box<dyn Backend>,
    fingerprint: Option<u64>,
    /// Rank 0: the samples a resumed checkpoint holds (then in its backend), and those sums.
    start: u32,
    resumed: Option<Accumulation>,
}

fn prepare(job: &RenderJob, rank: usize) -> Result<Prepared> {
    if rank == 0 {
        film::check_output_path(&job.output)?;
        film::check_writable(&job.output)?;
        if let Some((path, _)) = &job.checkpoint {
            session::check_checkpoint_path(path, &job.output)?;
        }
    }
    let (buffers, spp) = session::prepare_scene(job)?;
    if rank == 0 {
        session::check_outputs(job)?;
    }
    let gpus = session::rank_gpus(job, rank)?;
    let mut backend = backend::create_on(job.backend, &gpus, &buffers)?;
    let fingerprint = job.checkpoint.as_ref().map(|_| checkpoint::fingerprint(&buffers, job.seed, spp));
    let (mut start, mut resumed) = (0, None);
    if let (Some((path, _)), Some(fingerprint), 0) = (&job.checkpoint, fingerprint, rank) {
        start = session::resume(path, backend.as_mut(), fingerprint, spp)?;
        if start > 0 {
            resumed = Some(backend.read_accum()?);
        }
    }
    Ok(Prepared { buffers, spp, backend, fingerprint, start, resumed })
}

/// `session::render_to_file` as one of several processes (`ranks`: MPI): this one renders the
/// chunks of samples it is handed and rank 0 sums them and writes the image (`Some` report there,
/// `None` elsewhere). One process renders alone.
pub fn render_share(job: &RenderJob, ranks: Option<&dyn Ranks>) -> Result<Option<RenderReport>> {
    match ranks.filter(|r| r.size() > 1) {
        Some(ranks) => render_ranked(job, ranks),
        None => session::render_to_file(job).map(Some),
    }
}

/// Renders `job` as one of `ranks` (more than one); rank 0 writes the image and returns `Some`.
pub fn render_ranked(job: &RenderJob, ranks: &dyn Ranks) -> Result<Option<RenderReport>> {
    let (rank, size) = (ranks.rank(), ranks.size());
    // Rank 0 alone speaks of a signal (every rank gets one when mpirun ends the job).
    crate::system::interrupt::set_note(if rank == 0 {
        "rank 0 writes what the ranks last summed"
    } else {
        ""
    });
    let prepared = prepare(job, rank);
    if let Err(e) = &prepared {
        eprintln!("error: {}: {e:#}", ranks.name(rank));
    }
    let start = ranks.agree(prepared.as_ref().ok().map(|p| p.start))?;
    let Prepared { buffers, spp, mut backend, fingerprint, resumed, .. } =
        prepared.expect("agree refuses a rank that could not start");
    let (width, height) = (buffers.params.width, buffers.params.height);
    let bar = session::progress_bar(job.progress_bar && rank == 0, spp, start);
    let summed = Arc::new(Mutex::new(Summed { accum: resumed, done: start }));
    if rank == 0 {
        let sum_variance_factor =
            crate::output::film::splat_sum_variance_factor(&buffers.params, &buffers.tables);
        let out = Out { job: job.clone(), spp, size: (width, height), sum_variance_factor };
        let summed = summed.clone();
        ranks.dispatch(Plan {
            start,
            spp,
            every: job.checkpoint.as_ref().map(|(_, every)| *every),
            progress: bar.clone(),
            lost: Arc::new(move |why: &str| out.write_lost(why, &summed)),
        })?;
    }
    // The viewer shows what rank 0 holds of all ranks: the sums at each checkpoint and the end.
    let name = job.output.file_name().unwrap_or_default().to_string_lossy().to_string();
    let viewer = std::cell::RefCell::new(match job.tev.as_deref().filter(|_| rank == 0) {
        Some(address) => tev::TevStream::connect(address, &name, width, height)
            .map_err(|e| eprintln!("warning: {e:#}; rendering without the viewer"))
            .ok(),
        None => None,
    });
    let show = |accum: &Accumulation| {
        let mut viewer = viewer.borrow_mut();
        if let Some(Err(e)) = viewer.as_mut().map(|v| v.update(&Film::from_accum(width, height, accum))) {
            eprintln!("warning: {e:#}; no more updates to the viewer");
            *viewer = None;
        }
    };
    let clock = Instant::now();
    let hooks = TestHooks::from_env(rank);
    let chunk = |backend: &mut dyn Backend| -> Result<()> {
        let mut per_pass = Vec::new();
        let mut checkpoints = 0;
        loop {
            match ranks.next_work()? {
                Work::Chunk { first, count } => {
                    if checkpoints >= 2 && hooks.exit {
                        // Test only: a rank that dies without a word (`CAUSTIC_MPI_TEST_EXIT`).
                        std::process::exit(9);
                    }
                    if checkpoints >= 2 && hooks.fail {
                        anyhow::bail!("the device failed (CAUSTIC_MPI_TEST_FAIL)");
                    }
                    let span = Span { start: first, end: first + count, spp };
                    let observer = Chunk { rank };
                    passes::render_span(backend, &buffers, span, job.seed, &[], &mut per_pass, observer)?;
                    std::thread::sleep(hooks.slow * count);
                }
                Work::Checkpoint { done } => {
                    let total = ranks.reduce(&backend.read_accum()?)?;
                    checkpoints += 1;
                    if let Some(total) = total {
                        show(&total);
                        let mut s = summed.lock().unwrap_or_else(PoisonError::into_inner);
                        *s = Summed { accum: Some(total), done };
                        if let (Some((path, _)), Some(scene)) = (&job.checkpoint, fingerprint) {
                            let accum = s.accum.clone().expect("just summed");
                            let c =
                                Checkpoint { scene, seed: job.seed, spp_total: spp, spp_done: done, accum };
                            if let Err(e) = c.save(path) {
                                eprintln!("warning: {e:#}; the render goes on");
                            }
                        }
                    }
                }
                Work::Finish { .. } => return Ok(()),
            }
        }
    };
    if let Err(e) = chunk(backend.as_mut()) {
        ranks.fail(&e);
    }
    bar.finish_and_clear();
    let mine = match backend.read_accum() {
        Ok(a) => a,
        Err(e) => ranks.fail(&e),
    };
    let Some(accum) = ranks.reduce(&mine)? else { return Ok(None) };
    let seconds = clock.elapsed().as_secs_f64();
    let shares: Vec<String> = ranks.shares().iter().map(u64::to_string).collect();
    show(&accum);
    let mut film = session::develop(&buffers, &accum, spp, job.seed);
    session::save_film(&mut film, job)?;
    if let Some((path, _)) = &job.checkpoint {
        // The image is safe on disk: the checkpoint has served.
        std::fs::remove_file(path).ok();
    }
    Ok(Some(RenderReport {
        backend: format!(
            "{size} MPI ranks (spp by rank: {}), rank 0 on {}",
            shares.join(" + "),
            backend.describe()
        ),
        width,
        height,
        spp,
        resumed_at: start,
        seconds,
        invalid_samples: film.invalid_samples,
        interrupted: None,
        spp_done: spp,
    }))
}

/// A chunk's pass loop: nothing to show between passes. A signal ends a rank other than 0 at
/// once (rank 0's dispatcher writes what was summed; mpirun ends the ranks a second later anyway).
struct Chunk {
    rank: usize,
}

impl PassObserver for Chunk {
    fn wants_rest(&mut self, _: f64) -> bool {
        self.rank != 0 && crate::system::interrupt::requested().is_some()
    }
    fn at_rest(&mut self, _: u32, _: f64, _: &mut dyn Backend) -> Result<ControlFlow<()>> {
        if let Some(signal) = crate::system::interrupt::requested().filter(|_| self.rank != 0) {
            std::process::exit(crate::system::interrupt::exit_code(signal));
        }
        Ok(Continue(()))
    }
}

/// Where rank 0 writes what it has when the render cannot finish.
struct Out {
    job: RenderJob,
    spp: u32,
    size: (u32, u32),
    /// The film's `Film::sum_variance_factor`, which the partial image's variance file carries.
    sum_variance_factor: f64,
}

impl Out {
    fn write_lost(&self, why: &str, summed: &Mutex<Summed>) {
        let s = summed.lock().unwrap_or_else(PoisonError::into_inner);
        let output = &self.job.output;
        let Some(accum) = &s.accum else {
            eprintln!(
                "error: {why}; nothing had been summed on rank 0 yet (the ranks' sums meet at \
                 checkpoints and at the end: use --checkpoint for long renders), so no image was written"
            );
            return;
        };
        let mut film = Film::from_accum(self.size.0, self.size.1, accum);
        film.sum_variance_factor = self.sum_variance_factor;
        film.comment =
            Some(format!("caustic: partial render, {} of {} spp (a rank was lost)", s.done, self.spp));
        let saved = session::save_film(&mut film, &self.job).map(|()| output.clone());
        let resume = match &self.job.checkpoint {
            Some((path, _)) => format!("; the same command with --checkpoint {} resumes", path.display()),
            None => String::new(),
        };
        match saved {
            Ok(path) => eprintln!(
                "error: {why}; {} holds the {} of {} spp summed at the last checkpoint{resume}",
                path.display(),
                s.done,
                self.spp
            ),
            Err(e) => {
                eprintln!("error: {why}; the {} spp summed could not be written: {e:#}{resume}", s.done)
            }
        }
    }
}

/// The test-only behaviours (module doc).
struct TestHooks {
    /// Sleep per sample per pixel rendered.
    slow: Duration,
    exit: bool,
    fail: bool,
}

impl TestHooks {
    fn from_env(rank: usize) -> TestHooks {
        let slow = std::env::var("CAUSTIC_MPI_TEST_SLOW").ok().and_then(|v| {
            let (r, ms) = v.split_once(':')?;
            (r.parse::<usize>().ok()? == rank).then_some(Duration::from_millis(ms.parse().ok()?))
        });
        let this_rank =
            |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<usize>().ok()) == Some(rank);
        TestHooks {
            slow: slow.unwrap_or(Duration::ZERO),
            exit: this_rank("CAUSTIC_MPI_TEST_EXIT"),
            fail: this_rank("CAUSTIC_MPI_TEST_FAIL"),
        }
    }
}
