//! The `caustic` command line: render, compare, bench, convergence.
use anyhow::{bail, Context, Result};
use caustic::backend::{self, BackendChoice};
use caustic::film::{variance_path, Film};
use caustic::{buffers, compare, render};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};

#[derive(Parser)]
#[command(
    name = "caustic",
    version,
    about = "A physically based renderer whose one kernel runs on the GPU and the CPU"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene (Mitsuba 3 XML or OBJ/MTL) to an image.
    Render {
        #[command(flatten)]
        run: RunArgs,
        /// Output image: .exr (linear float), .png or .ppm (sRGB). Default: SCENE's name with .exr.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Also write the per-pixel variance of the estimate to OUTPUT.variance.exr.
        #[arg(long)]
        variance: bool,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
        /// Checkpoint file: resume from it if it exists (same scene, seed and spp), write it while
        /// rendering, delete it once the image is saved.
        #[arg(long)]
        checkpoint: Option<PathBuf>,
        /// Seconds between checkpoint writes (0: after every pass).
        #[arg(long, default_value_t = 60.0)]
        checkpoint_every: f64,
        /// Stream the image to the tev viewer listening at HOST:PORT (tev's default: 127.0.0.1:14158).
        #[arg(long)]
        tev: Option<String>,
    },
    /// Compare an EXR render with a reference EXR.
    Compare {
        image: PathBuf,
        reference: PathBuf,
        /// Samples per pixel of the render and the reference, to account for the reference's noise.
        #[arg(long, default_value_t = 0)]
        image_spp: u32,
        #[arg(long, default_value_t = 0)]
        reference_spp: u32,
        /// Where to write the false-colour error image (PNG).
        #[arg(long)]
        error_image: Option<PathBuf>,
    },
    /// Error against render time: render progressively and compare with a reference at 1, 2, 4, …
    /// samples per pixel; prints a table, optionally writes CSV and an SVG plot (log–log).
    Convergence {
        #[command(flatten)]
        run: RunArgs,
        /// Reference image (EXR) of the same size.
        reference: PathBuf,
        /// Write the curve as CSV.
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Write a log–log plot of relative MSE against seconds (SVG).
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// Measure rendering throughput (Msamples/s) per backend.
    Bench {
        scene: PathBuf,
        #[arg(short = 'D', value_parser = parse_define)]
        define: Vec<(String, String)>,
        #[arg(long, default_value = "all")]
        backend: String,
        #[arg(long, default_value_t = 64)]
        spp: u32,
    },
}

/// What `render` and `convergence` share: the scene and how to render it.
#[derive(clap::Args)]
struct RunArgs {
    /// The scene: Mitsuba 3 XML or OBJ (with its MTL).
    scene: PathBuf,
    #[arg(long, value_enum, default_value = "auto")]
    backend: BackendChoice,
    /// Samples per pixel (for `convergence`, the largest count; default: the scene's sampler).
    #[arg(long)]
    spp: Option<u32>,
    /// Scene parameter overrides, `-D name=value` (Mitsuba's `$name`).
    #[arg(short = 'D', value_parser = parse_define)]
    define: Vec<(String, String)>,
    /// Random seed; different seeds give statistically independent images.
    #[arg(long, default_value_t = 0)]
    seed: u32,
}

/// `println!` that ends the program quietly when stdout is closed (`caustic compare … | head`), as
/// command-line tools do, instead of panicking.
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write;
        if writeln!(std::io::stdout(), $($t)*).is_err() {
            std::process::exit(0);
        }
    }};
}

fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((k, v)) if !k.is_empty() => Ok((k.to_string(), v.to_string())),
        _ => Err(format!("'{s}' is not name=value")),
    }
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render { run, output, variance, quiet, checkpoint, checkpoint_every, tev } => {
            let output = output.unwrap_or_else(|| {
                PathBuf::from(run.scene.file_stem().unwrap_or_default()).with_extension("exr")
            });
            let checkpoint =
                checkpoint.map(|path| (path, std::time::Duration::from_secs_f64(checkpoint_every.max(0.0))));
            cmd_render(&run, &output, variance, quiet, checkpoint.as_ref(), tev.as_deref())
        }
        Command::Compare { image, reference, image_spp, reference_spp, error_image } => {
            cmd_compare(&image, &reference, image_spp, reference_spp, error_image.as_deref())
        }
        Command::Bench { scene, define, backend, spp } => cmd_bench(&scene, &define, &backend, spp),
        Command::Convergence { run, reference, csv, plot } => {
            cmd_convergence(&run, &reference, csv.as_deref(), plot.as_deref())
        }
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

/// How often the image goes to tev: often enough to watch, rarely enough that read-backs cost little.
const TEV_INTERVAL: std::time::Duration = std::time::Duration::from_millis(500);

fn cmd_render(
    run: &RunArgs,
    output: &Path,
    variance: bool,
    quiet: bool,
    checkpoint: Option<&(PathBuf, std::time::Duration)>,
    tev: Option<&str>,
) -> Result<()> {
    let RunArgs { scene: scene_path, backend: choice, spp, define: defines, seed } = run;
    let (choice, seed) = (*choice, *seed);
    caustic::film::check_output_path(output)?;
    let scene = caustic::load_scene(scene_path, defines)?;
    let spp = spp.unwrap_or(scene.sensor.spp);
    if spp == 0 {
        bail!("--spp must be at least 1");
    }
    let buffers = buffers::build(&scene)
        .with_context(|| format!("{}: cannot build the scene", scene_path.display()))?;
    let mut backend = backend::create(choice, &buffers)?;
    // Hashing every scene buffer is only worth it when there is a checkpoint to match.
    let fingerprint = checkpoint.map(|_| caustic::checkpoint::fingerprint(&buffers, seed, spp));
    let start = match (checkpoint, fingerprint) {
        (Some((path, _)), Some(fingerprint)) => resume(path, backend.as_mut(), fingerprint, spp)?,
        _ => 0,
    };
    let bar = if quiet { indicatif::ProgressBar::hidden() } else { indicatif::ProgressBar::new(spp as u64) };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} spp ({eta} left)")
            .unwrap()
            .progress_chars("=> "),
    );
    bar.set_position(start as u64);
    let (width, height) = (buffers.params.width, buffers.params.height);
    let name = output.file_name().unwrap_or_default().to_string_lossy().to_string();
    let mut viewer = match tev
        .map(|address| caustic::tev::TevStream::connect(address, &name, width, height))
        .transpose()
    {
        Ok(v) => v,
        Err(e) => {
            eprintln!("warning: {e:#}; rendering without the viewer");
            None
        }
    };
    let mut last_save = std::time::Instant::now();
    let mut last_view = std::time::Instant::now();
    let stats = render::render_with_checkpoints(
        backend.as_mut(),
        &buffers,
        start,
        spp,
        seed,
        &[],
        |done, _, backend| {
            bar.set_position(done as u64);
            if viewer.is_some() && (last_view.elapsed() >= TEV_INTERVAL || done == spp) {
                let film = Film::from_accum(width, height, &backend.read_accum()?);
                if let Err(e) = viewer.as_mut().unwrap().update(&film) {
                    eprintln!("warning: {e:#}; no more updates to the viewer");
                    viewer = None;
                }
                last_view = std::time::Instant::now();
            }
            if let (Some((path, every)), Some(fingerprint)) = (checkpoint, fingerprint) {
                if done < spp && last_save.elapsed() >= *every {
                    let c = caustic::checkpoint::Checkpoint {
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
                    last_save = std::time::Instant::now();
                }
            }
            Ok(std::ops::ControlFlow::Continue(()))
        },
    )?;
    bar.finish_and_clear();
    let mut film = Film::from_accum(buffers.params.width, buffers.params.height, &backend.read_accum()?);
    sanitize(&mut film);
    if let Err(e) = film.save(output) {
        // Keep the finished render: write it where it can be written, then report the failure.
        let fallback = std::env::temp_dir().join(format!("caustic-recovered-{}.exr", std::process::id()));
        match film.save(&fallback) {
            Ok(()) => bail!("{e:#}; the render was saved to {} instead", fallback.display()),
            Err(_) => return Err(e),
        }
    }
    if variance {
        film.save_variance(&variance_path(output))?;
    }
    if let Some((path, _)) = checkpoint {
        // The image is safe on disk: the checkpoint has served.
        std::fs::remove_file(path).ok();
    }
    let (w, h) = (film.width, film.height);
    let msps = w as f64 * h as f64 * (spp - start) as f64 / stats.seconds.max(1e-9) / 1e6;
    let resumed = if start > 0 { format!(" (resumed at {start})") } else { String::new() };
    say!(
        "{} | {w}x{h} | {spp} spp{resumed} | {:.2} s | {msps:.2} Msamples/s | {}",
        backend.describe(),
        stats.seconds,
        output.display()
    );
    Ok(())
}

/// Loads `path` into the backend if it exists and carries this render's `fingerprint` (scene, seed
/// and sample count); returns the samples per pixel it holds (0 without a checkpoint).
fn resume(path: &Path, backend: &mut dyn backend::Backend, fingerprint: u64, spp: u32) -> Result<u32> {
    if !path.exists() {
        return Ok(0);
    }
    let c = caustic::checkpoint::Checkpoint::load(path)?;
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

fn cmd_compare(
    image: &Path,
    reference: &Path,
    image_spp: u32,
    reference_spp: u32,
    error_image: Option<&Path>,
) -> Result<()> {
    let a = Film::load_with_variance(image)?;
    let b = Film::load_exr(reference)?;
    let ratio =
        if image_spp > 0 && reference_spp > 0 { image_spp as f64 / reference_spp as f64 } else { 0.0 };
    let c = compare::compare(&a, &b, ratio)?;
    say!("RMSE                 {:.6}", c.rmse);
    say!("relative MSE         {:.6}", c.rel_mse);
    say!("mean luminance ratio {:.5}", c.luminance_ratio);
    match c.pass_fraction {
        Some(f) => say!("z-test pass fraction {:.5} (|z| ≤ {:.2}, Šidák-corrected 1%)", f, c.z_critical),
        None => say!("z-test               n/a (no {} beside the image)", variance_path(image).display()),
    }
    if let Some(z) = c.luminance_z {
        say!("mean luminance z     {z:+.2} (standard errors)");
    }
    if let Some(path) = error_image {
        let scale = if c.pass_fraction.is_some() { c.z_critical as f32 } else { 1.0 };
        compare::save_error_image(path, a.width, a.height, &c.error_map, scale)?;
    }
    Ok(())
}

fn cmd_convergence(run: &RunArgs, reference: &Path, csv: Option<&Path>, plot: Option<&Path>) -> Result<()> {
    use caustic::convergence;
    let RunArgs { scene: scene_path, backend: choice, spp, define: defines, seed } = run;
    let (choice, seed) = (*choice, *seed);
    let scene = caustic::load_scene(scene_path, defines)?;
    let spp = spp.unwrap_or(scene.sensor.spp);
    let reference_film = Film::load_exr(reference)?;
    let buffers = buffers::build(&scene)
        .with_context(|| format!("{}: cannot build the scene", scene_path.display()))?;
    let mut backend = backend::create(choice, &buffers)?;
    // A one-sample warm-up (pipeline compilation, caches) on a backend of its own, untimed.
    render::render(backend.as_mut(), &buffers, 1, seed.wrapping_add(1), |_| {})?;
    let mut backend = backend::create(choice, &buffers)?;
    let points = convergence::measure(backend.as_mut(), &buffers, &reference_film, spp, seed)?;
    say!("{} | {}x{} | independent sampler", backend.describe(), buffers.params.width, buffers.params.height);
    say!("| spp | seconds | RMSE | relative MSE | mean-luminance ratio |");
    say!("|---|---|---|---|---|");
    for p in &points {
        say!(
            "| {} | {:.4} | {:.6} | {:.6e} | {:.5} |",
            p.spp,
            p.seconds,
            p.rmse,
            p.rel_mse,
            p.luminance_ratio
        );
    }
    if let Some(slope) = convergence::log_log_slope(&points) {
        say!(
            "log-log slope of relative MSE against seconds: {slope:.3} (−1: unbiased at constant throughput)"
        );
    }
    if let Some(path) = csv {
        convergence::write_csv(path, &points)?;
    }
    if let Some(path) = plot {
        let label = format!(
            "{} ({})",
            scene_path.file_stem().unwrap_or_default().to_string_lossy(),
            backend.describe()
        );
        convergence::write_plot(path, &[(label, points)])?;
    }
    Ok(())
}

fn cmd_bench(scene_path: &Path, defines: &[(String, String)], which: &str, spp: u32) -> Result<()> {
    let scene = caustic::load_scene(scene_path, defines)?;
    let buffers = buffers::build(&scene)?;
    let choices: Vec<BackendChoice> = match which {
        "all" => vec![BackendChoice::Cpu, BackendChoice::Gpu],
        "cpu" => vec![BackendChoice::Cpu],
        "gpu" => vec![BackendChoice::Gpu],
        other => bail!("--backend must be all, cpu or gpu, not '{other}'"),
    };
    say!("| backend | resolution | spp | seconds | Msamples/s |");
    say!("|---|---|---|---|---|");
    for choice in choices {
        let mut backend = match backend::create(choice, &buffers) {
            Ok(b) => b,
            Err(e) => {
                say!("| {choice:?} | unavailable: {e:#} | | | |");
                continue;
            }
        };
        // A short warm-up pass (pipeline compilation, caches), then the timed render.
        render::render(backend.as_mut(), &buffers, 1, 1, |_| {})?;
        let mut backend = backend::create(choice, &buffers)?;
        let (film, stats) = render::render(backend.as_mut(), &buffers, spp, 0, |_| {})?;
        let msps = film.width as f64 * film.height as f64 * spp as f64 / stats.seconds / 1e6;
        say!(
            "| {} | {}x{} | {spp} | {:.3} | {msps:.2} |",
            backend.describe(),
            film.width,
            film.height,
            stats.seconds
        );
    }
    Ok(())
}
