//! The `caustic` command line: render, compare, bench, convergence.
use anyhow::{bail, Context, Result};
use caustic::backend::{self, BackendChoice, GpuSelection};
use caustic::error_chain;
use caustic::load::LoadOptions;
use caustic::output::compare;
use caustic::output::film::{variance_path, Film};
use caustic::prepare::buffers;
use caustic::render::passes;
use caustic::render::session::{self, RenderJob};
use caustic::scene::{FilmMode, IntegratorChoice};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

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
    /// Render a scene (Mitsuba 3 XML or OBJ/MTL) to an image; or several scenes, or variants, one
    /// image each (spread over the ranks under mpirun).
    Render {
        /// The scenes: Mitsuba 3 XML or OBJ (with its MTL).
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        #[command(flatten)]
        run: RunArgs,
        /// One image per value (and per combination, repeated): `--vary res=256,512`.
        #[arg(long, value_parser = caustic::render::batch::parse_vary)]
        vary: Vec<(String, Vec<String>)>,
        /// Output image: .exr (linear float), .png or .ppm (sRGB). Default: SCENE's name with .exr.
        /// With several images, a folder for them (named SCENE-name=value….exr).
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
        /// The scene: Mitsuba 3 XML or OBJ (with its MTL).
        scene: PathBuf,
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
        /// Another renderer's curve beside caustic's: a CSV of its renders of the scene (`spp,seconds,image`,
        /// image paths relative to the CSV's folder; `scripts/time-to-error.py --peer-curve` writes one for
        /// Mitsuba), compared with the same reference and labelled by the file's name. Repeatable.
        #[arg(long)]
        peer: Vec<PathBuf>,
    },
    /// Measure rendering throughput (Msamples/s) per backend.
    Bench {
        scene: PathBuf,
        #[arg(short = 'D', value_parser = parse_define)]
        define: Vec<(String, String)>,
        /// Backends to measure, one after the other (comma-separated).
        #[arg(long, value_enum, value_delimiter = ',', default_value = "cpu,gpu")]
        backend: Vec<BackendChoice>,
        #[arg(long, default_value_t = 64)]
        spp: u32,
        /// GPUs to measure on (as for `render`).
        #[arg(long, default_value = "all")]
        gpus: GpuSelection,
        /// Measure the GPU backend on the first 1, 2, 4, … of the selected GPUs and all of them, and
        /// print the speed-up over one GPU and each GPU's share of the samples.
        #[arg(long)]
        scaling: bool,
        /// Refuse a scene that would not render as written (as `render --strict`).
        #[arg(long)]
        strict: bool,
        /// Measure this integrator instead of the scene's (as `render --integrator`).
        #[arg(long, value_enum)]
        integrator: Option<IntegratorChoice>,
        /// The film (as `render --film`).
        #[arg(long, value_enum, default_value = "splat")]
        film: FilmMode,
    },
    /// Print what the GPU driver compiled a scene's kernel to (its own statistics: on NVIDIA,
    /// registers per thread and spilled bytes), for each pipeline `render` would build.
    KernelStats {
        scene: PathBuf,
        #[arg(short = 'D', value_parser = parse_define)]
        define: Vec<(String, String)>,
        /// Also write each pipeline's SPIR-V, as the driver gets it from wgpu, into this folder.
        #[arg(long)]
        write_spirv: Option<PathBuf>,
    },
}

/// What `render` and `convergence` share: the scene and how to render it.
#[derive(clap::Args)]
struct RunArgs {
    #[arg(long, value_enum, default_value = "auto")]
    backend: BackendChoice,
    /// GPUs to render on: `all` hardware adapters, the first N, or adapter indices (`0,2`; an index
    /// twice opens two devices on one adapter). Passes go to whichever GPU is idle.
    #[arg(long, default_value = "all")]
    gpus: GpuSelection,
    /// Samples per pixel (for `convergence`, the largest count; default: the scene's sampler).
    #[arg(long)]
    spp: Option<u32>,
    /// Scene parameter overrides, `-D name=value` (Mitsuba's `$name`).
    #[arg(short = 'D', value_parser = parse_define)]
    define: Vec<(String, String)>,
    /// Random seed; different seeds give statistically independent images.
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Render with this integrator instead of the scene's (its max_depth, rr_depth, hide_emitters kept);
    /// `convergence` takes several, comma-separated, and measures one curve each.
    #[arg(long, value_enum, value_delimiter = ',')]
    integrator: Vec<IntegratorChoice>,
    /// How camera samples reach the film: `splat` adds each to every pixel its filter covers, as
    /// Mitsuba does; `fis` draws its offset from the filter and gives it to its own pixel
    /// (uncorrelated noise between pixels, more of it per sample). The bidirectional integrators'
    /// camera samples follow it; `ptracer` has none.
    #[arg(long, value_enum, default_value = "splat")]
    film: FilmMode,
    /// Run ibpt's, bdpt's or vcm's own kernel even where no light path can start (every emitter at
    /// infinity); by default path's kernel renders them there, being the same estimator.
    #[arg(long)]
    own_kernel: bool,
    /// Refuse a scene that would not render as written (an unsupported plugin replaced or left out,
    /// a property not read) instead of warning.
    #[arg(long)]
    strict: bool,
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
    // Before any thread starts (it changes the environment); `compare` opens no GPU.
    if !matches!(cli.command, Command::Compare { .. }) {
        backend::runtime_dir::ensure_xdg_runtime_dir();
    }
    caustic::system::files::write_errors_are_errors();
    // A render saves what it has on SIGINT/SIGTERM; the other commands stop as by default.
    if matches!(cli.command, Command::Render { .. }) {
        if let Err(e) = caustic::system::interrupt::install() {
            eprintln!("warning: {e:#}; an interrupt will lose the render");
        }
    }
    let result = match cli.command {
        Command::Render { scenes, run, vary, output, variance, quiet, checkpoint, checkpoint_every, tev } => {
            // An interval too long for a Duration (`inf`) means: never between passes.
            let every = Duration::try_from_secs_f64(checkpoint_every.max(0.0)).unwrap_or(Duration::MAX);
            // Under mpirun (an MPI build): this process renders its share, rank 0 writes the image.
            #[cfg(feature = "mpi")]
            let world = match caustic::render::ranks::launched()
                .then(caustic::render::mpi::World::init)
                .transpose()
            {
                Ok(w) => w,
                Err(e) => {
                    eprintln!("error: {e:#}");
                    std::process::exit(1);
                }
            };
            #[cfg(feature = "mpi")]
            let ranks = world.as_ref().map(|w| w as &dyn caustic::render::ranks::Ranks);
            #[cfg(not(feature = "mpi"))]
            let ranks = None;
            #[cfg(not(feature = "mpi"))]
            if caustic::render::ranks::launched() {
                eprintln!(
                    "warning: started by an MPI launcher, but this caustic was built without \
                     --features mpi: every process renders the whole image"
                );
            }
            let template = RenderJob {
                scene: PathBuf::new(),
                defines: run.define,
                backend: run.backend,
                gpus: run.gpus,
                spp: run.spp,
                seed: run.seed,
                strict: run.strict,
                output: PathBuf::new(),
                variance,
                progress_bar: !quiet,
                checkpoint: checkpoint.map(|path| (path, every)),
                tev,
                film: run.film,
                own_kernel: run.own_kernel,
                integrator: match run.integrator.as_slice() {
                    [] => None,
                    [one] => Some(*one),
                    _ => {
                        eprintln!("error: render takes one --integrator (convergence compares several)");
                        std::process::exit(2);
                    }
                },
            };
            match caustic::render::batch::jobs(&template, &scenes, &vary, output.as_deref()) {
                Ok(jobs) if jobs.len() == 1 => cmd_render(ranks, &jobs[0]),
                Ok(jobs) => cmd_batch(ranks, &jobs),
                Err(e) => Err(e),
            }
        }
        Command::Convergence { scene, run, reference, csv, plot, peer } => {
            cmd_convergence(&scene, &run, &reference, csv.as_deref(), plot.as_deref(), &peer)
        }
        Command::Compare { image, reference, image_spp, reference_spp, error_image } => {
            cmd_compare(&image, &reference, image_spp, reference_spp, error_image.as_deref())
        }
        Command::Bench { scene, define, backend, spp, gpus, scaling, strict, integrator, film } => {
            let asked = BenchScene {
                path: &scene,
                defines: &define,
                options: LoadOptions { strict },
                integrator,
                film,
            };
            if scaling {
                cmd_bench_scaling(&asked, &gpus, spp)
            } else {
                cmd_bench(&asked, &backend, &gpus, spp)
            }
        }
        Command::KernelStats { scene, define, write_spirv } => {
            cmd_kernel_stats(&scene, &define, write_spirv.as_deref())
        }
    };
    if let Err(e) = result {
        eprintln!("error: {}", error_chain(&e));
        // Stopped by a signal (while loading, say): the status says which, as for a render.
        std::process::exit(
            caustic::system::interrupt::requested().map_or(1, caustic::system::interrupt::exit_code),
        );
    }
}

/// A render's summary line: backend, size, samples (partial or resumed ones said so), time,
/// throughput and the image written.
fn summary(r: &session::RenderReport, output: &Path) -> String {
    let resumed = if r.resumed_at > 0 { format!(" (resumed at {})", r.resumed_at) } else { String::new() };
    let spp = match r.interrupted {
        Some(_) => format!("partial: {} of {} spp (interrupted)", r.spp_done, r.spp),
        None => format!("{} spp", r.spp),
    };
    format!(
        "{} | {}x{} | {spp}{resumed} | {:.2} s | {:.2} Msamples/s | {}",
        r.backend,
        r.width,
        r.height,
        r.seconds,
        r.msamples_per_second(),
        output.display()
    )
}

fn cmd_render(ranks: Option<&dyn caustic::render::ranks::Ranks>, job: &RenderJob) -> Result<()> {
    let Some(r) = caustic::render::ranked::render_share(job, ranks)? else { return Ok(()) };
    say!("{}", summary(&r, &job.output));
    if let Some(signal) = r.interrupted {
        std::process::exit(caustic::system::interrupt::exit_code(signal));
    }
    Ok(())
}

/// Several images: this process renders its share of them (every n-th under mpirun), one line each.
/// A failed image is reported and the others still rendered; the ranks wait for each other before
/// exiting, so that one rank's failure does not make mpirun end the others' renders.
fn cmd_batch(ranks: Option<&dyn caustic::render::ranks::Ranks>, jobs: &[RenderJob]) -> Result<()> {
    let (rank, size) = ranks.map_or((0, 1), |r| (r.rank(), r.size()));
    let who = ranks.filter(|_| size > 1).map(|r| format!("{}: ", r.name(rank))).unwrap_or_default();
    let mut failed = 0;
    for i in caustic::render::batch::mine(jobs.len(), rank, size) {
        let mut job = jobs[i].clone();
        if size > 1 {
            match session::rank_gpus(&job, rank) {
                Ok(gpus) => job.gpus = gpus,
                Err(e) => {
                    eprintln!("error: {who}{}: {}", job.output.display(), error_chain(&e));
                    failed += 1;
                    continue;
                }
            }
        }
        match session::render_to_file(&job) {
            Ok(r) => say!("{who}{}", summary(&r, &job.output)),
            Err(e) => {
                eprintln!("error: {who}{}: {}", job.output.display(), error_chain(&e));
                failed += 1;
            }
        }
        // A signal ends the batch: the image under way was saved as partial, the rest are not
        // started.
        if let Some(signal) = caustic::system::interrupt::requested() {
            if let Some(ranks) = ranks {
                ranks.barrier();
            }
            std::process::exit(caustic::system::interrupt::exit_code(signal));
        }
    }
    if let Some(ranks) = ranks {
        ranks.barrier();
    }
    if failed > 0 {
        anyhow::bail!("{who}{failed} of this process's images failed (above)");
    }
    Ok(())
}

fn cmd_compare(
    image: &Path,
    reference: &Path,
    image_spp: u32,
    reference_spp: u32,
    error_image: Option<&Path>,
) -> Result<()> {
    if let Some(path) = error_image {
        if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
            bail!("{}: the error image is a PNG file (name it .png)", path.display());
        }
        caustic::output::film::check_writable(path)?;
    }
    let a = Film::load_with_variance(image)?;
    let b = Film::load_exr(reference)?;
    if let Some(path) = error_image {
        caustic::system::files::check_output(path)?;
    }
    compare::check_finite(&a, image)?;
    compare::check_finite(&b, reference)?;
    let ratio = compare::samples_ratio(image_spp, reference_spp);
    let c = compare::compare(&a, &b, ratio)
        .with_context(|| format!("{} against {}", image.display(), reference.display()))?;
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

/// A convergence curve as the table `convergence` prints.
fn say_points(points: &[caustic::render::convergence::ConvergencePoint]) {
    // Where the reference has a variance: also the error against the truth, its noise taken out.
    let net = points.iter().all(|p| p.net_mse.is_some());
    let (head, rule) = if net { (" net MSE | net relative MSE |", "---|---|") } else { ("", "") };
    say!("| spp | seconds | RMSE | relative MSE | mean-luminance ratio |{head}");
    say!("|---|---|---|---|---|{rule}");
    for p in points {
        let tail = match (p.net_mse, p.net_rel_mse) {
            (Some(m), Some(r)) if net => format!(" {m:.6e} | {r:.6e} |"),
            _ => String::new(),
        };
        say!(
            "| {} | {:.4} | {:.6} | {:.6e} | {:.5} |{tail}",
            p.spp,
            p.seconds,
            p.rmse,
            p.rel_mse,
            p.luminance_ratio
        );
    }
}

fn cmd_convergence(
    scene_path: &Path,
    run: &RunArgs,
    reference: &Path,
    csv: Option<&Path>,
    plot: Option<&Path>,
    peers: &[PathBuf],
) -> Result<()> {
    use caustic::render::convergence;
    let RunArgs { backend: choice, gpus, spp, define: defines, seed, integrator, strict, film, own_kernel } =
        run;
    let (choice, seed) = (*choice, *seed);
    for path in [csv, plot].into_iter().flatten() {
        caustic::output::film::check_writable(path)?;
    }
    let loaded = caustic::load::load_scene_with(scene_path, defines, LoadOptions { strict: *strict })?;
    // With its variance where `render --variance` wrote one: the curves then also say the error
    // against the truth (`ConvergencePoint::net_mse`).
    let reference_film = Film::load_with_variance(reference)?;
    compare::check_finite(&reference_film, reference)?;
    // No output may be an input (the scene, the reference), found before rendering.
    for path in [csv, plot].into_iter().flatten() {
        caustic::system::files::check_output(path)?;
    }
    // The scene's own integrator, or each one asked for: one curve each, measured one after the other.
    let choices: Vec<Option<IntegratorChoice>> =
        if integrator.is_empty() { vec![None] } else { integrator.iter().copied().map(Some).collect() };
    let mut curves = Vec::new();
    for integrator in choices {
        let kind = loaded.integrator.kind_under(integrator);
        let name = integrator_name(&kind);
        let spp = spp.unwrap_or(loaded.sensor.spp);
        let buffers = session::build_scene(loaded.clone(), scene_path, integrator, *film, *own_kernel)?;
        convergence::check_reference_size(&reference_film, reference, &buffers, scene_path)?;
        let (backend, points) =
            convergence::measure_warmed_up(choice, gpus, &buffers, &reference_film, spp, seed)?;
        say!("{name} | {backend} | {}x{} | independent sampler", buffers.params.width, buffers.params.height);
        say_points(&points);
        if let Some(slope) = convergence::log_log_slope(&points) {
            say!(
                "log-log slope of relative MSE against seconds: {slope:.3} (−1: unbiased at constant throughput)"
            );
        }
        let label =
            format!("{} {name} ({backend})", scene_path.file_stem().unwrap_or_default().to_string_lossy());
        curves.push((label, name, points));
    }
    let peer_names: Vec<String> =
        peers.iter().map(|p| p.file_stem().unwrap_or_default().to_string_lossy().into_owned()).collect();
    for (path, name) in peers.iter().zip(&peer_names) {
        let points = convergence::peer_curve(path, &reference_film)?;
        say!("{name} | {} | renders listed there", path.display());
        say_points(&points);
        curves.push((name.clone(), name.as_str(), points));
    }
    if let Some(path) = csv {
        let named: Vec<(&str, &[convergence::ConvergencePoint])> =
            curves.iter().map(|(_, name, points)| (*name, points.as_slice())).collect();
        convergence::write_csv(path, &named)?;
    }
    if let Some(path) = plot {
        let plotted: Vec<(String, Vec<convergence::ConvergencePoint>)> =
            curves.into_iter().map(|(label, _, points)| (label, points)).collect();
        convergence::write_plot(path, &plotted)?;
    }
    Ok(())
}

/// The integrator's name as in scene files.
fn integrator_name(kind: &caustic::scene::IntegratorKind) -> &'static str {
    use caustic::scene::IntegratorKind::*;
    match kind {
        Path => "path",
        Direct { .. } => "direct",
        Ptracer => "ptracer",
        Ibpt => "ibpt",
        Bdpt => "bdpt",
        Vcm => "vcm",
    }
}

/// The scene a benchmark measures, as its command line names it.
struct BenchScene<'a> {
    path: &'a Path,
    defines: &'a [(String, String)],
    options: LoadOptions,
    /// `--integrator`: in place of the scene's.
    integrator: Option<IntegratorChoice>,
    film: FilmMode,
}

/// What both benchmarks start from: a sample count of at least one and the scene's buffers.
fn bench_buffers(asked: &BenchScene, spp: u32) -> Result<buffers::SceneBuffers> {
    if spp == 0 {
        anyhow::bail!("--spp must be at least 1");
    }
    let start = Instant::now();
    let scene = caustic::load::load_scene_with(asked.path, asked.defines, asked.options)?;
    let loaded = start.elapsed().as_secs_f64();
    let instances = scene.instancing.instances.len();
    let kind = scene.integrator.kind_under(asked.integrator);
    let buffers = session::build_scene(scene, asked.path, asked.integrator, asked.film, false)?;
    // What a large scene costs before its first sample (the large-scene table in BENCHMARKS.md).
    let scene_bytes = caustic::backend::memory::scene_bytes(&buffers);
    // With instances: the primitives stored (each group's once, and the instances themselves) and
    // the ones the instances place.
    let placed = match buffers.placed_prims {
        0 => String::new(),
        n => format!(" stored, {n} placed by {instances} instances"),
    };
    say!(
        "scene: {} primitives{placed} | load {loaded:.2} s | buffers and BVH {:.2} s | {:.1} MiB of scene buffers",
        buffers.prims.len(),
        start.elapsed().as_secs_f64() - loaded,
        scene_bytes as f64 / (1u64 << 20) as f64
    );
    say!("integrator {}, film {:?}", integrator_name(&kind), asked.film);
    Ok(buffers)
}

fn cmd_kernel_stats(
    scene_path: &Path,
    defines: &[(String, String)],
    write_spirv: Option<&Path>,
) -> Result<()> {
    let asked = BenchScene {
        path: scene_path,
        defines,
        options: LoadOptions::default(),
        integrator: None,
        film: FilmMode::default(),
    };
    let buffers = bench_buffers(&asked, 1)?;
    say!("kernel paths {} (feature mask)", buffers.features);
    let reports =
        backend::kernel_stats::scene(buffers.features, buffers.params.integrator, write_spirv.is_none())?;
    if let Some(dir) = write_spirv {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for r in &reports {
            let [w, h] = r.variant.workgroup;
            let name = format!("{}-{:?}-{w}x{h}.spv", r.entry.replace("::", "-"), r.variant.path_loop)
                .to_lowercase();
            let path = dir.join(name);
            caustic::system::files::write(&path, bytemuck::cast_slice::<u32, u8>(&r.module))?;
            say!("wrote {}", path.display());
        }
    }
    if let Some(first) = reports.first() {
        say!("adapter: {}", first.adapter);
    }
    say!("| entry point | path loop | workgroup | executable | statistic | value |");
    say!("|---|---|---|---|---|---|");
    for report in &reports {
        for executable in &report.executables {
            for stat in &executable.stats {
                say!(
                    "| {} | {:?} | {}x{} | {} | {} | {} |",
                    report.entry,
                    report.variant.path_loop,
                    report.variant.workgroup[0],
                    report.variant.workgroup[1],
                    executable.name,
                    stat.name,
                    stat.value
                );
            }
        }
    }
    Ok(())
}

/// How long `bench` warms up at most, waiting for the backend to settle.
const WARM_UP_LIMIT: Duration = Duration::from_secs(20);

fn cmd_bench(asked: &BenchScene, choices: &[BackendChoice], gpus: &GpuSelection, spp: u32) -> Result<()> {
    let buffers = bench_buffers(asked, spp)?;
    // What the GPU kernel is specialised to (kernel/src/features.rs); scripts/specialization.sh reads it.
    say!("kernel paths {} (feature mask)", buffers.features);
    say!("| backend | resolution | spp | seconds | Msamples/s |");
    say!("|---|---|---|---|---|");
    for &choice in choices {
        let mut backend = match backend::create_on(choice, gpus, &buffers) {
            Ok(b) => b,
            Err(e) => {
                say!("| {choice:?} | unavailable: {e:#} | | | |");
                continue;
            }
        };
        // A warm-up (pipeline compilation, caches, and the GPU's choice among its candidate pipelines:
        // the render is repeated until the backend has settled on one, which it keeps on disk for the
        // next render of this setup, `backend::variant`), then the timed render: what a second render
        // of the scene runs at.
        passes::render(backend.as_mut(), &buffers, 1, 1, |_| {})?;
        let warm = Instant::now();
        while !backend.settled() && warm.elapsed() < WARM_UP_LIMIT {
            passes::render(backend.as_mut(), &buffers, spp, 1, |_| {})?;
        }
        if !backend.settled() {
            say!("(the GPU's trial of its candidate pipelines did not end within the warm-up)");
        }
        say!("warm-up: {}", backend.describe());
        // The timed render runs in a backend of its own, which builds the kept choice alone, after a
        // one-sample render there: its pipeline's first dispatch is not timed either (Mitsuba's side
        // of `scripts/speed-vs-mitsuba.py` times a render after one of the same scene). On 2026-11-27
        // a 0.24 s render timed without it ran at half the speed of the same scene's other renders,
        // once (BENCHMARKS.md, "All 23 scenes against Mitsuba, a BVH layout that lost").
        let mut backend = backend::create_on(choice, gpus, &buffers)?;
        passes::render(backend.as_mut(), &buffers, 1, 1, |_| {})?;
        let (film, stats) = passes::render(backend.as_mut(), &buffers, spp, 0, |_| {})?;
        let msps = film.width as f64 * film.height as f64 * spp as f64 / stats.seconds / 1e6;
        say!(
            "| {} | {}x{} | {spp} | {:.3} | {msps:.2} |",
            backend.describe(),
            film.width,
            film.height,
            stats.seconds
        );
    }
    if let Some(peak) = caustic::system::memory::peak_resident() {
        say!("peak host memory {:.1} MiB", peak as f64 / (1u64 << 20) as f64);
    }
    Ok(())
}

/// Multi-GPU scaling: the same render on the first 1, 2, 4, … of the selected GPUs (and all of
/// them), each after an untimed warm-up on its own devices.
fn cmd_bench_scaling(asked: &BenchScene, gpus: &GpuSelection, spp: u32) -> Result<()> {
    let buffers = bench_buffers(asked, spp)?;
    let scene_path = asked.path;
    let all = backend::resolve_gpus(gpus, &backend::gpu::adapter_types(), false)?;
    let mut counts: Vec<usize> = (0..).map(|k| 1usize << k).take_while(|&c| c < all.len()).collect();
    counts.push(all.len());
    let (w, h) = (buffers.params.width, buffers.params.height);
    say!("{} | {w}x{h} | {spp} spp", scene_path.display());
    say!("| GPUs | seconds | Msamples/s | speed-up | efficiency | samples per GPU |");
    say!("|---|---|---|---|---|---|");
    let (mut one_gpu, mut described) = (None, String::new());
    for count in counts {
        let selection = GpuSelection::List(all[..count].to_vec());
        let mut warm = backend::create_on(BackendChoice::Gpu, &selection, &buffers)?;
        passes::render(warm.as_mut(), &buffers, count as u32, 1, |_| {})?;
        drop(warm);
        let mut backend = backend::create_on(BackendChoice::Gpu, &selection, &buffers)?;
        let (_, stats) = passes::render(backend.as_mut(), &buffers, spp, 0, |_| {})?;
        let msps = w as f64 * h as f64 * spp as f64 / stats.seconds / 1e6;
        let base = *one_gpu.get_or_insert(msps);
        let shares = match backend.lanes() {
            Some(lanes) => lanes.shares().iter().map(|s| s.to_string()).collect::<Vec<_>>().join(" / "),
            None => spp.to_string(),
        };
        described = backend.describe();
        say!(
            "| {count} | {:.3} | {msps:.2} | {:.2} | {:.0}% | {shares} |",
            stats.seconds,
            msps / base,
            100.0 * msps / base / count as f64
        );
    }
    say!("devices: {described}");
    Ok(())
}
