//! A render session: scene file in, image file out, with everything a long render needs around the
//! pass loop (progress bar, checkpoints and resuming, streaming to tev, saving the image somewhere
//! even when its path fails). One function that the command line and a Python binding call (and
//! MPI ranks through `ranked`, which shares the helpers here); `passes` below it owns only the pass
//! loop.
use crate::backend::{self, Backend, BackendChoice, GpuSelection};
use crate::output::film::{self, Film};
use crate::output::tev;
use crate::prepare::buffers;
use crate::render::checkpoint::{self, Checkpoint};
use crate::render::passes;
use crate::render::ranks;
use crate::scene::{FilmMode, IntegratorChoice, Scene};
use anyhow::{bail, Context, Result};
use std::cell::Cell;
use std::ops::ControlFlow::{self, Break, Continue};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How often the image goes to tev: often enough to watch, rarely enough that read-backs cost little.
const TEV_INTERVAL: Duration = Duration::from_millis(500);

/// What to render and how.
#[derive(Clone, Debug)]
pub struct RenderJob {
    /// Mitsuba 3 XML or OBJ (with its MTL).
    pub scene: PathBuf,
    /// `-D name=value` overrides of the scene's `$name` parameters.
    pub defines: Vec<(String, String)>,
    pub backend: BackendChoice,
    /// The GPUs to render on (several: passes spread over them, sums added).
    pub gpus: GpuSelection,
    /// Samples per pixel; `None` takes the scene's sampler's count.
    pub spp: Option<u32>,
    pub seed: u32,
    /// Refuse a scene that would not render as written (`LoadOptions::strict`).
    pub strict: bool,
    /// `.exr`, `.png` or `.ppm`.
    pub output: PathBuf,
    /// Also write the per-pixel variance of the estimate beside the image (`film::variance_path`).
    pub variance: bool,
    pub progress_bar: bool,
    /// Checkpoint file and the interval between writes: resumed from if it exists, deleted once the
    /// image is saved.
    pub checkpoint: Option<(PathBuf, Duration)>,
    /// Address of a tev viewer to stream the image to while rendering.
    pub tev: Option<String>,
    /// Replaces the scene's integrator.
    pub integrator: Option<IntegratorChoice>,
    /// How camera samples reach the film (`--film`).
    pub film: crate::scene::FilmMode,
    /// `Integrator::own_kernel` (`--own-kernel`).
    pub own_kernel: bool,
}

/// What a finished session did.
#[derive(Clone, Debug)]
pub struct RenderReport {
    /// Backend and adapter.
    pub backend: String,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    /// Samples per pixel a checkpoint held when the session started (0: a fresh render).
    pub resumed_at: u32,
    /// Seconds in the pass loop (loading, building and saving excluded).
    pub seconds: f64,
    /// Samples that were not finite, or that the GPU driver cut short, counted as black.
    pub invalid_samples: u64,
    /// The signal (SIGINT, SIGTERM) that stopped the render before `spp` samples: the image saved
    /// holds `spp_done` samples per pixel and says so (EXR comments), the checkpoint is kept.
    pub interrupted: Option<i32>,
    /// Samples per pixel in the image saved (`spp` unless interrupted).
    pub spp_done: u32,
}

impl RenderReport {
    /// Samples rendered by this session per second, in millions.
    pub fn msamples_per_second(&self) -> f64 {
        self.width as f64 * self.height as f64 * (self.spp_done - self.resumed_at) as f64
            / self.seconds.max(1e-9)
            / 1e6
    }
}

/// Loads the scene, renders it and writes the image (and variance) to `job.output`. Several
/// processes share a render through `ranked::render_share`.
pub fn render_to_file(job: &RenderJob) -> Result<RenderReport> {
    let output = job.output.as_path();
    film::check_output_path(output)?;
    film::check_writable(output)?;
    if let Some((path, _)) = &job.checkpoint {
        check_checkpoint_path(path, output)?;
    }
    let (buffers, spp) = prepare_scene(job)?;
    check_outputs(job)?;
    let mut backend = backend::create_starting(job.backend, &job.gpus, &buffers, spp)
        .with_context(|| format!("{}: its sensor's film", job.scene.display()))?;
    let seed = job.seed;
    // Hashing every scene buffer is only worth it when there is a checkpoint to match.
    let checkpoint = job
        .checkpoint
        .as_ref()
        .map(|(path, every)| (path, *every, checkpoint::fingerprint(&buffers, seed, spp)));
    // The samples to render: all of them, less a checkpoint's.
    let start = match checkpoint {
        Some((path, _, fingerprint)) => resume(path, backend.as_mut(), fingerprint, spp)?,
        None => 0,
    };
    let bar = progress_bar(job.progress_bar, spp, start);
    let (width, height) = (buffers.params.width, buffers.params.height);
    let name = output.file_name().unwrap_or_default().to_string_lossy().to_string();
    let viewer = match job
        .tev
        .as_deref()
        .map(|address| tev::TevStream::connect(address, &name, width, height))
        .transpose()
    {
        Ok(v) => v,
        Err(e) => {
            eprintln!("warning: {e:#}; rendering without the viewer");
            None
        }
    };
    let done_at = Cell::new(start);
    let observer = Observer {
        bar: &bar,
        viewer,
        checkpoint,
        last_save: Instant::now(),
        last_view: Instant::now(),
        seed,
        spp,
        size: (width, height),
        done_at: &done_at,
        variance: job.variance,
    };
    let mut seconds = 0.0;
    if start < spp {
        seconds =
            passes::render_observed(backend.as_mut(), &buffers, start, spp, seed, &[], observer)?.seconds;
    }
    bar.finish_and_clear();
    let accum = backend.read_accum()?;
    // A signal stopped the render before its end (the image says so; the checkpoint is kept).
    let interrupted = crate::system::interrupt::requested().filter(|_| done_at.get() < spp);
    let spp_done = if interrupted.is_some() { done_at.get() } else { spp };
    if buffers.aovs.is_some() && job.progress_bar {
        eprintln!("tracing the AOVs ({spp_done} spp, on the CPU)");
    }
    let mut film = develop(&buffers, &accum, spp_done, seed);
    if interrupted.is_some() {
        film.comment = Some(format!("caustic: partial render, {spp_done} of {spp} spp (interrupted)"));
    }
    save_film(&mut film, job)?;
    if let Some((path, _, _)) = checkpoint.filter(|_| interrupted.is_none()) {
        // The image is safe on disk: the checkpoint has served.
        std::fs::remove_file(path).ok();
    }
    Ok(RenderReport {
        backend: backend.describe(),
        width,
        height,
        spp,
        resumed_at: start,
        seconds,
        invalid_samples: film.invalid_samples,
        interrupted,
        spp_done,
    })
}

/// Refuses, before rendering, any output of `job` that is one of the files its scene was loaded
/// from (through any link), naming both: the image, its variance file and its checkpoint.
pub(crate) fn check_outputs(job: &RenderJob) -> Result<()> {
    crate::system::files::check_output(&job.output)?;
    if job.variance {
        crate::system::files::check_output(&film::variance_path(&job.output))?;
    }
    if let Some((path, _)) = &job.checkpoint {
        crate::system::files::check_output(path)?;
    }
    Ok(())
}

/// Loads the scene with the job's overrides and builds its buffers; the samples per pixel to render.
pub(crate) fn prepare_scene(job: &RenderJob) -> Result<(buffers::SceneBuffers, u32)> {
    let options = crate::load::LoadOptions { strict: job.strict };
    let scene = crate::load::load_scene_with(&job.scene, &job.defines, options)?;
    let spp = samples_per_pixel(&scene, job.spp)?;
    let buffers = build_scene(scene, &job.scene, job.integrator, job.film, job.own_kernel)?;
    Ok((buffers, spp))
}

/// The samples per pixel to render: `spp`, or the scene's sampler's count; at least one.
pub fn samples_per_pixel(scene: &Scene, spp: Option<u32>) -> Result<u32> {
    let spp = spp.unwrap_or(scene.sensor.spp);
    if spp == 0 {
        bail!("--spp must be at least 1");
    }
    Ok(spp)
}

/// Builds the buffers of a loaded scene (read from `path`, which errors name) for a render with
/// `integrator` in place of the scene's own, `film` and `own_kernel` (`--integrator`, `--film`,
/// `--own-kernel`).
pub fn build_scene(
    mut scene: Scene,
    path: &Path,
    integrator: Option<IntegratorChoice>,
    film: FilmMode,
    own_kernel: bool,
) -> Result<buffers::SceneBuffers> {
    if let Some(choice) = integrator {
        scene.integrator = scene.integrator.overridden(choice);
    }
    scene.sensor.film = film;
    scene.integrator.own_kernel = own_kernel;
    buffers::build(&scene).with_context(|| format!("{}: cannot build the scene", path.display()))
}

/// The image of an accumulation of samples `[0, spp_done)` rendered with `seed`, with the scene's
/// AOVs (traced on the CPU: `aov::add_to`) where it has any.
pub fn develop(
    buffers: &buffers::SceneBuffers,
    accum: &crate::backend::accumulation::Accumulation,
    spp_done: u32,
    seed: u32,
) -> Film {
    let mut film = Film::develop(buffers, accum);
    crate::output::aov::add_to(&mut film, buffers, spp_done, seed);
    film
}

/// The progress bar (hidden unless `show`), counting samples per pixel to `len` from `position`.
pub fn progress_bar(show: bool, len: u32, position: u32) -> indicatif::ProgressBar {
    let bar = if show { indicatif::ProgressBar::new(len as u64) } else { indicatif::ProgressBar::hidden() };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} spp ({eta} left)")
            .expect("a valid progress template")
            .progress_chars("=> "),
    );
    bar.set_position(position as u64);
    bar
}

/// The GPUs a rank uses: with `--gpus all` and several ranks on a node, every n-th GPU of the node
/// (one rank per GPU, or one rank per node with all of them); an explicit `--gpus` as given.
pub fn rank_gpus(job: &RenderJob, rank: usize) -> Result<GpuSelection> {
    let (local_rank, local_size) = ranks::local_rank();
    if job.gpus != GpuSelection::All || job.backend == BackendChoice::Cpu || local_size == 1 {
        return Ok(job.gpus.clone());
    }
    let hardware_only = job.backend == BackendChoice::Auto;
    let Ok(all) = backend::resolve_gpus(&GpuSelection::All, &backend::gpu::adapter_types(), hardware_only)
    else {
        return Ok(GpuSelection::All); // no GPU: `auto` renders on the CPU, `gpu` says why not
    };
    let mine = ranks::local_gpus(&all, local_rank, local_size);
    if mine.is_empty() {
        bail!(
            "rank {rank}: {local_size} ranks on this node share {} GPU(s), none left for local rank \
             {local_rank}: start at most one rank per GPU (or --backend cpu)",
            all.len()
        );
    }
    Ok(GpuSelection::List(mine))
}

/// The session's side of the pass loop: the progress bar after every pass; the image to tev and the
/// checkpoint when due, each needing the devices at rest.
struct Observer<'a> {
    bar: &'a indicatif::ProgressBar,
    viewer: Option<tev::TevStream>,
    /// Path, interval and the render's fingerprint.
    checkpoint: Option<(&'a PathBuf, Duration, u64)>,
    last_save: Instant,
    last_view: Instant,
    seed: u32,
    spp: u32,
    size: (u32, u32),
    /// The samples per pixel done at the last rest (what an interrupted render's image holds).
    done_at: &'a Cell<u32>,
    /// `--variance`: the variance file is written.
    variance: bool,
}

impl Observer<'_> {
    fn view_due(&self) -> bool {
        self.viewer.is_some() && self.last_view.elapsed() >= TEV_INTERVAL
    }
    fn save_due(&self) -> bool {
        self.checkpoint.is_some_and(|(_, every, _)| self.last_save.elapsed() >= every)
    }
}

impl passes::PassObserver for Observer<'_> {
    fn needs_variance(&self) -> bool {
        self.variance
    }

    fn pass_target(&self) -> Duration {
        if self.viewer.is_some() {
            passes::INTERACTIVE_PASS
        } else {
            passes::TARGET_PASS
        }
    }

    fn progress(&mut self, finished: u32) {
        self.bar.set_position(finished as u64);
    }

    fn wants_rest(&mut self, _seconds: f64) -> bool {
        self.view_due() || self.save_due() || crate::system::interrupt::requested().is_some()
    }

    fn at_rest(&mut self, done: u32, _: f64, backend: &mut dyn Backend) -> Result<ControlFlow<()>> {
        let (width, height) = self.size;
        self.bar.set_position(done as u64);
        self.done_at.set(done);
        // SIGINT or SIGTERM: stop here, saving the checkpoint now (`interrupt`).
        let interrupted = crate::system::interrupt::requested().is_some() && done < self.spp;
        if self.view_due() || (self.viewer.is_some() && done == self.spp) {
            let film = Film::from_accum(width, height, &backend.read_accum()?);
            if let Some(Err(e)) = self.viewer.as_mut().map(|stream| stream.update(&film)) {
                eprintln!("warning: {e:#}; no more updates to the viewer");
                self.viewer = None;
            }
            self.last_view = Instant::now();
        }
        if let Some((path, _, fingerprint)) =
            self.checkpoint.filter(|_| done < self.spp && (self.save_due() || interrupted))
        {
            let c = Checkpoint {
                scene: fingerprint,
                seed: self.seed,
                spp_total: self.spp,
                spp_done: done,
                accum: backend.read_accum()?,
            };
            // A checkpoint that cannot be written must not cost the render itself.
            if let Err(e) = c.save(path) {
                eprintln!("warning: {e:#}; the render goes on");
            }
            self.last_save = Instant::now();
        }
        // The loop ends by itself at `spp`.
        Ok(if interrupted { Break(()) } else { Continue(()) })
    }
}

/// Refuses a checkpoint file that is also the image or its variance file: the finished render is
/// saved there and then the checkpoint is deleted, which would delete the image just written. The
/// variance file is refused even without `--variance`, since `compare` reads it beside the image.
pub(crate) fn check_checkpoint_path(checkpoint: &Path, output: &Path) -> Result<()> {
    for (what, other) in
        [("output image", output.to_path_buf()), ("variance file", film::variance_path(output))]
    {
        if same_file(checkpoint, &other) {
            bail!(
                "--checkpoint {} is the {what} {}: the checkpoint is deleted once the image is saved; \
                 give it a name of its own",
                checkpoint.display(),
                other.display()
            );
        }
    }
    Ok(())
}

/// Whether two paths name one file: canonical paths where the files exist, else the canonical
/// folder and the file name (the output usually does not exist yet, and `./a.exr` is `a.exr`), else
/// the paths as given.
fn same_file(a: &Path, b: &Path) -> bool {
    if let (Ok(a), Ok(b)) = (a.canonicalize(), b.canonicalize()) {
        return a == b;
    }
    let in_folder = |p: &Path| -> Option<PathBuf> {
        let dir = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(dir.canonicalize().ok()?.join(p.file_name()?))
    };
    match (in_folder(a), in_folder(b)) {
        (Some(a), Some(b)) => a == b,
        _ => a == b,
    }
}

/// Writes the job's image (non-finite values zeroed: `sanitize`) and, when asked, its variance.
pub(crate) fn save_film(film: &mut Film, job: &RenderJob) -> Result<()> {
    sanitize(film);
    save_or_recover(film, &job.output)?;
    if job.variance {
        film.save_variance(&film::variance_path(&job.output))?;
    }
    Ok(())
}

/// Writes the finished image; if `output` cannot be written, keeps the render in the temporary
/// directory and says where in the error.
pub(crate) fn save_or_recover(film: &Film, output: &Path) -> Result<()> {
    if let Err(e) = film.save(output) {
        let fallback = std::env::temp_dir().join(format!("caustic-recovered-{}.exr", std::process::id()));
        match film.save(&fallback) {
            Ok(()) => bail!("{e:#}; the render was saved to {} instead", fallback.display()),
            Err(_) => return Err(e),
        }
    }
    Ok(())
}

/// Loads `path` into the backend if it exists and carries this render's `fingerprint` (scene, seed
/// and sample count); returns the samples per pixel it holds (0 without a checkpoint).
pub(crate) fn resume(path: &Path, backend: &mut dyn Backend, fingerprint: u64, spp: u32) -> Result<u32> {
    if !path.exists() {
        return Ok(0);
    }
    let c = Checkpoint::load(path)?;
    if c.scene != fingerprint || c.spp_done > spp {
        bail!(
            "{} was written for another scene, seed or sample count; remove it to start afresh",
            path.display()
        );
    }
    backend.write_accum(&c.accum)?;
    eprintln!("resuming from {} ({} of {spp} spp done)", path.display(), c.spp_done);
    Ok(c.spp_done)
}

/// Guarantees a finite image. The kernel already drops non-finite samples; report them.
pub fn sanitize(film: &mut Film) {
    if film.invalid_samples > 0 {
        eprintln!(
            "warning: {} samples were not finite or were cut short by the GPU driver (a software \
             adapter's loop limit), and were counted as black",
            film.invalid_samples
        );
    }
    for p in film.rgb.iter_mut().flatten() {
        if !p.is_finite() {
            *p = 0.0;
        }
    }
}
