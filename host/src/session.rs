//! A render session: scene file in, image file out, with everything a long render needs around the
//! pass loop (progress bar, checkpoints and resuming, streaming to tev, saving the image somewhere
//! even when its path fails). One function that the command line, a Python binding or an MPI runner
//! all call; `render.rs` below it owns only the pass loop.
use crate::backend::{self, Backend, BackendChoice};
use crate::checkpoint::{self, Checkpoint};
use crate::film::{self, Film};
use crate::scene::IntegratorChoice;
use crate::{buffers, render, tev};
use anyhow::{bail, Context, Result};
use std::ops::ControlFlow::{Break, Continue};
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
    /// Samples per pixel; `None` takes the scene's sampler's count.
    pub spp: Option<u32>,
    pub seed: u32,
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
    /// Samples that were not finite and were counted as black.
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

/// Loads the scene, renders it and writes the image (and variance) to `job.output`.
pub fn render_to_file(job: &RenderJob) -> Result<RenderReport> {
    let output = job.output.as_path();
    film::check_output_path(output)?;
    film::check_writable(output)?;
    if let Some((path, _)) = &job.checkpoint {
        check_checkpoint_path(path, output)?;
    }
    let mut scene = crate::load_scene(&job.scene, &job.defines)?;
    if let Some(choice) = job.integrator {
        scene.integrator = scene.integrator.overridden(choice);
    }
    let spp = job.spp.unwrap_or(scene.sensor.spp);
    if spp == 0 {
        bail!("--spp must be at least 1");
    }
    let buffers =
        buffers::build(&scene).with_context(|| format!("{}: cannot build the scene", job.scene.display()))?;
    let mut backend = backend::create(job.backend, &buffers)?;
    let seed = job.seed;
    // Hashing every scene buffer is only worth it when there is a checkpoint to match.
    let checkpoint = job
        .checkpoint
        .as_ref()
        .map(|(path, every)| (path, *every, checkpoint::fingerprint(&buffers, seed, spp)));
    let start = match checkpoint {
        Some((path, _, fingerprint)) => resume(path, backend.as_mut(), fingerprint, spp)?,
        None => 0,
    };
    let bar = if job.progress_bar {
        indicatif::ProgressBar::new(spp as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} spp ({eta} left)")
            .expect("a valid progress template")
            .progress_chars("=> "),
    );
    bar.set_position(start as u64);
    let (width, height) = (buffers.params.width, buffers.params.height);
    let name = output.file_name().unwrap_or_default().to_string_lossy().to_string();
    let mut viewer = match job
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
    let mut last_save = Instant::now();
    let mut last_view = Instant::now();
    let mut done_at = start;
    let stats = render::render_with_checkpoints(
        backend.as_mut(),
        &buffers,
        start,
        spp,
        seed,
        &[],
        |done, _, backend| {
            bar.set_position(done as u64);
            done_at = done;
            let interrupted = crate::interrupt::requested().is_some() && done < spp;
            if let Some(stream) =
                viewer.as_mut().filter(|_| last_view.elapsed() >= TEV_INTERVAL || done == spp)
            {
                if let Err(e) = stream.update(&Film::from_accum(width, height, &backend.read_accum()?)) {
                    eprintln!("warning: {e:#}; no more updates to the viewer");
                    viewer = None;
                }
                last_view = Instant::now();
            }
            if let Some((path, every, fingerprint)) = checkpoint {
                if done < spp && (last_save.elapsed() >= every || interrupted) {
                    let c = Checkpoint {
                        scene: fingerprint,
                        seed,
                        spp_total: spp,
                        spp_done: done,
                        accum: backend.read_accum()?,
                    };
                    // A checkpoint that cannot be written must not cost the render itself.
                    if let Err(e) = c.save(path) {
                        eprintln!("warning: {e:#}; the render goes on");
                    }
                    last_save = Instant::now();
                }
            }
            Ok(if interrupted { Break(()) } else { Continue(()) })
        },
    )?;
    bar.finish_and_clear();
    let interrupted = crate::interrupt::requested().filter(|_| done_at < spp);
    let mut film = Film::from_accum(width, height, &backend.read_accum()?);
    if interrupted.is_some() {
        film.comment = Some(format!("caustic: partial render, {done_at} of {spp} spp (interrupted)"));
    }
    sanitize(&mut film);
    save_or_recover(&film, output)?;
    if job.variance {
        film.save_variance(&film::variance_path(output))?;
    }
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
        seconds: stats.seconds,
        invalid_samples: film.invalid_samples,
        interrupted,
        spp_done: done_at,
    })
}

/// Refuses a checkpoint file that is also the image or its variance file: the finished render is
/// saved there and then the checkpoint is deleted, which would delete the image just written. The
/// variance file is refused even without `--variance`, since `compare` reads it beside the image.
fn check_checkpoint_path(checkpoint: &Path, output: &Path) -> Result<()> {
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

/// Writes the finished image; if `output` cannot be written, keeps the render in the temporary
/// directory and says where in the error.
fn save_or_recover(film: &Film, output: &Path) -> Result<()> {
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
fn resume(path: &Path, backend: &mut dyn Backend, fingerprint: u64, spp: u32) -> Result<u32> {
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
fn sanitize(film: &mut Film) {
    if film.invalid_samples > 0 {
        eprintln!("warning: {} samples were not finite and were counted as black", film.invalid_samples);
    }
    for p in film.rgb.iter_mut().flatten() {
        if !p.is_finite() {
            *p = 0.0;
        }
    }
}
