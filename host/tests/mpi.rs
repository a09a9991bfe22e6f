//! `mpirun -n N caustic render …` (built with `--features mpi`) writes the image one process
//! writes with the same seed: the ranks' chunks of samples sum to the same estimator, so only the
//! order of the float sums differs; also with a slow rank, across checkpoints, when a rank dies,
//! and for a batch of variants. Runs when the crate is built with the feature and `mpirun` is
//! on the PATH (CI installs Open MPI and runs it: `.ci/run`).
#![cfg(feature = "mpi")]
use caustic::output::film::Film;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Relative tolerance per pixel value: a pixel's mean sums at most 48 samples (or 48 batches of
/// resolved splats), each sum of positive f32 terms exact to (terms)·2⁻²⁴ ≈ 2.9e-6 in any order.
const TOLERANCE: f32 = 1e-5;

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cornell-box.xml")
}

/// The launcher and its options, or `None` without one. Open MPI refuses root without
/// `--allow-run-as-root`, and more ranks than cores without `--oversubscribe`.
fn mpirun() -> Option<Vec<String>> {
    let version = Command::new("mpirun").arg("--version").output().ok()?;
    let mut cmd = vec!["mpirun".to_string()];
    if String::from_utf8_lossy(&version.stdout).contains("Open MPI") {
        cmd.extend(["--allow-run-as-root", "--oversubscribe"].map(String::from));
    }
    Some(cmd)
}

/// The shared arguments: the Cornell box at 24×24, 48 spp, seed 3, on the CPU.
fn args(integrator: &str, out: &Path) -> Vec<String> {
    let scene = scene();
    let args = ["render", scene.to_str().unwrap(), "-D", "res=24", "--backend", "cpu", "--spp", "48"];
    args.iter()
        .copied()
        .chain(["--integrator", integrator, "--seed", "3", "-q", "-o", out.to_str().unwrap()])
        .map(String::from)
        .collect()
}

/// Runs `caustic` under `launcher` (none: one process) with `args`, `env` set (and passed to
/// every rank).
fn run(launcher: &[String], args: &[String], env: &[(&str, &str)]) -> Output {
    let exe = env!("CARGO_BIN_EXE_caustic");
    let mut rest: Vec<String> = launcher.iter().skip(1).cloned().collect();
    if !launcher.is_empty() {
        for (name, _) in env {
            rest.extend(["-x".to_string(), name.to_string()]);
        }
        rest.push(exe.to_string());
    }
    // Open MPI 4's mpirun races another one starting at the same moment for its session folder
    // (`/tmp/ompi.HOST.UID`: "mkdir … File exists", seen once in 10 runs of these tests): one at a time.
    static ONE_MPIRUN: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = (!launcher.is_empty()).then(|| ONE_MPIRUN.lock().unwrap_or_else(|e| e.into_inner()));
    let program = launcher.first().map_or(exe, String::as_str);
    let mut command = Command::new(program);
    command.args(rest).args(args).env("XDG_RUNTIME_DIR", "/tmp");
    for (name, value) in env {
        command.env(name, value);
    }
    command.output().expect("the render starts")
}

/// `run` that must succeed with one line on stdout (rank 0 alone reports); that line.
fn render(launcher: &[String], args: &[String], env: &[(&str, &str)]) -> String {
    let output = run(launcher, args, env);
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(output.status.success(), "{launcher:?}: {stdout}{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(stdout.lines().count(), 1, "{launcher:?}: {stdout}");
    stdout
}

fn ranks(mpirun: &[String], n: usize) -> Vec<String> {
    mpirun.iter().cloned().chain(["-n".into(), n.to_string()]).collect()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("caustic-mpi-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every pixel within `TOLERANCE` of the reference's.
fn assert_same(got: &Path, want: &Film, what: &str) {
    let got = Film::load_exr(got).unwrap();
    assert_eq!((got.width, got.height), (want.width, want.height), "{what}");
    for (i, (p, q)) in got.rgb.iter().zip(&want.rgb).enumerate() {
        for c in 0..3 {
            assert!(
                (p[c] - q[c]).abs() <= TOLERANCE * p[c].abs().max(q[c].abs()),
                "{what}: pixel {i}: {p:?} vs one process {q:?}"
            );
        }
    }
}

/// The one-process image of `args(integrator, …)`, rendered into `dir`.
fn one_process(dir: &Path, integrator: &str) -> Film {
    let single = dir.join(format!("{integrator}-1.exr"));
    render(&[], &args(integrator, &single), &[]);
    let want = Film::load_exr(&single).unwrap();
    assert!(want.rgb.iter().flatten().any(|&c| c > 0.0), "{integrator}: a black image proves nothing");
    want
}

#[test]
fn mpi_ranks_render_the_one_process_image() {
    let Some(mpirun) = mpirun() else {
        eprintln!("no mpirun on the PATH: the MPI render is not tested here");
        return;
    };
    let dir = temp_dir("equal");
    for integrator in ["path", "ptracer"] {
        let want = one_process(&dir, integrator);
        for n in [2, 3] {
            let out = dir.join(format!("{integrator}-{n}.exr"));
            render(&ranks(&mpirun, n), &args(integrator, &out), &[]);
            assert_same(&out, &want, &format!("{integrator}, {n} ranks"));
        }
        if integrator == "path" {
            // On lavapipe against one process on lavapipe: the one software adapter shared by both
            // ranks (`--gpus 0,`: as given).
            let on_gpu = |out: &Path| {
                let mut a = args(integrator, out);
                let at = a.iter().position(|a| a == "cpu").unwrap();
                a[at] = "gpu".into();
                a.extend(["--gpus", "0,"].map(String::from));
                a
            };
            let (one, two) = (dir.join("lavapipe-1.exr"), dir.join("lavapipe-2.exr"));
            render(&[], &on_gpu(&one), &[]);
            render(&ranks(&mpirun, 2), &on_gpu(&two), &[]);
            assert_same(&two, &Film::load_exr(&one).unwrap(), "path, 2 ranks on lavapipe");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The samples per pixel each rank rendered, from rank 0's line (`spp by rank: 40 + 8`).
fn spp_by_rank(line: &str) -> Vec<u64> {
    let at = line.find("spp by rank: ").unwrap_or_else(|| panic!("no shares in {line}")) + 13;
    let end = at + line[at..].find(')').unwrap();
    line[at..end].split(" + ").map(|n| n.parse().unwrap()).collect()
}

/// Rank 1 slowed down (`CAUSTIC_MPI_TEST_SLOW`: 30 ms per sample per pixel, a 24×24 CPU sample
/// per pixel takes well under 1 ms) takes fewer chunks: the fast rank renders most samples, and the
/// image is still the one-process image.
#[test]
fn a_slow_rank_takes_fewer_samples() {
    let Some(mpirun) = mpirun() else { return };
    let dir = temp_dir("slow");
    let want = one_process(&dir, "path");
    let out = dir.join("slow.exr");
    let line = render(&ranks(&mpirun, 2), &args("path", &out), &[("CAUSTIC_MPI_TEST_SLOW", "1:30")]);
    let shares = spp_by_rank(&line);
    assert_eq!(shares.iter().sum::<u64>(), 48, "{line}");
    assert!(shares[0] >= 3 * shares[1], "the fast rank did not take more: {line}");
    assert_same(&out, &want, "one slow rank");
    std::fs::remove_dir_all(&dir).ok();
}

/// Checkpoints cross between one process and MPI ranks, both ways, and a rank that dies
/// (`CAUSTIC_MPI_TEST_EXIT`: rank 1 exits after its second checkpoint without telling MPI) or
/// fails (`CAUSTIC_MPI_TEST_FAIL`) is named with its host; rank 0 writes the partial image of what
/// it had summed, and the checkpoint left behind resumes in one process to the one-process image.
#[test]
fn checkpoints_cross_between_one_process_and_ranks() {
    use caustic::render::checkpoint::{fingerprint, Checkpoint};
    use std::ops::ControlFlow::{Break, Continue};
    let Some(mpirun) = mpirun() else { return };
    let dir = temp_dir("checkpoint");
    let want = one_process(&dir, "path");
    let ckpt = dir.join("render.ckpt");
    let with_ckpt = |out: &Path| -> Vec<String> {
        let mut a = args("path", out);
        a.extend(["--checkpoint", ckpt.to_str().unwrap(), "--checkpoint-every", "0"].map(String::from));
        a
    };

    // One process's checkpoint at 12 of 48 spp (written through the library), resumed by 2 ranks.
    let defines = vec![("res".to_string(), "24".to_string())];
    let mut scene = caustic::load::load_scene(&scene(), &defines).unwrap();
    scene.integrator = scene.integrator.overridden(caustic::scene::IntegratorChoice::Path);
    let buffers = caustic::prepare::buffers::build(&scene).unwrap();
    let mut backend = caustic::backend::create(caustic::backend::BackendChoice::Cpu, &buffers).unwrap();
    caustic::render::passes::render_with_checkpoints(
        backend.as_mut(),
        &buffers,
        0,
        48,
        3,
        &[12],
        |done, _, _| Ok(if done == 12 { Break(()) } else { Continue(()) }),
    )
    .unwrap();
    let accum = backend.read_accum().unwrap();
    Checkpoint { scene: fingerprint(&buffers, 3, 48), seed: 3, spp_total: 48, spp_done: 12, accum }
        .save(&ckpt)
        .unwrap();
    let out = dir.join("resumed-by-ranks.exr");
    let line = render(&ranks(&mpirun, 2), &with_ckpt(&out), &[]);
    assert!(line.contains("resumed at 12"), "{line}");
    assert_eq!(spp_by_rank(&line).iter().sum::<u64>(), 36, "{line}");
    assert!(!ckpt.exists(), "the checkpoint outlived the finished render");
    assert_same(&out, &want, "a one-process checkpoint resumed by 2 ranks");

    // Two ranks checkpoint at every chance; rank 1 dies.
    let partial = dir.join("partial.exr");
    // Rank 0 slowed a little (5 ms per sample per pixel), so that after a checkpoint rank 1 asks
    // before rank 0 has finished its next chunk, and gets one: rank 0's request after a finished
    // chunk would start the next checkpoint instead.
    let slow_0 = ("CAUSTIC_MPI_TEST_SLOW", "0:5");
    let output = run(&ranks(&mpirun, 2), &with_ckpt(&partial), &[("CAUSTIC_MPI_TEST_EXIT", "1"), slow_0]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "the job survived its rank's death: {stderr}");
    let host = mpi_host();
    assert!(stderr.contains(&format!("rank 1 on {host}")), "the lost rank is not named: {stderr}");
    assert!(stderr.contains("partial.exr holds the"), "{stderr}");
    let saved = Checkpoint::load(&ckpt).expect("the checkpoint is kept");
    assert!(saved.spp_done > 0 && saved.spp_done < 48, "{}", saved.spp_done);
    let image = Film::load_exr(&partial).expect("the partial image is written");
    assert!(image.rgb.iter().flatten().all(|c| c.is_finite()));

    // Rank 1's render fails instead: it is named with its error, rank 0 writes what it summed.
    let failed = dir.join("failed.exr");
    let ckpt_failed = dir.join("failed.ckpt");
    let mut failing = args("path", &failed);
    failing
        .extend(["--checkpoint", ckpt_failed.to_str().unwrap(), "--checkpoint-every", "0"].map(String::from));
    let output = run(&ranks(&mpirun, 2), &failing, &[("CAUSTIC_MPI_TEST_FAIL", "1"), slow_0]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "the job survived its rank's failure: {stderr}");
    assert!(
        stderr.contains(&format!("rank 1 on {host} failed: the device failed"))
            && stderr.contains("failed.exr holds the"),
        "{stderr}"
    );
    assert!(Checkpoint::load(&ckpt_failed).is_ok_and(|c| c.spp_done > 0));
    assert!(Film::load_exr(&failed).is_ok());

    // Resumed in one process: the one-process image.
    let out = dir.join("resumed-by-one.exr");
    let line = render(&[], &with_ckpt(&out), &[]);
    assert!(line.contains(&format!("resumed at {}", saved.spp_done)), "{line}");
    assert_same(&out, &want, "a 2-rank checkpoint resumed by one process");
    std::fs::remove_dir_all(&dir).ok();
}

/// The host name MPI gives this machine (`MPI_Get_processor_name`: the host name on Open MPI).
fn mpi_host() -> String {
    let out = Command::new("hostname").output().expect("hostname runs");
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// A batch of 3 `--vary` variants over 2 ranks: every image is written once, by the rank that
/// took it, and equals the image one process renders of that variant.
#[test]
fn a_batch_of_variants_spreads_over_ranks() {
    let Some(mpirun) = mpirun() else { return };
    let dir = temp_dir("batch");
    let exe = env!("CARGO_BIN_EXE_caustic");
    let scene = scene();
    let batch: Vec<String> = [
        "render",
        scene.to_str().unwrap(),
        "--vary",
        "res=16,20,24",
        "--backend",
        "cpu",
        "--spp",
        "16",
        "--seed",
        "5",
        "-q",
        "-o",
        dir.join("batch").to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec();
    let output = run(&ranks(&mpirun, 2), &batch, &[]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}{}", String::from_utf8_lossy(&output.stderr));
    let host = mpi_host();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 3, "{stdout}");
    for res in [16, 20, 24] {
        let name = format!("cornell-box-res={res}.exr");
        let by: Vec<&&str> = lines.iter().filter(|l| l.ends_with(&name)).collect();
        assert_eq!(by.len(), 1, "{name}: {stdout}");
        // Rank 0 takes variants 0 and 2, rank 1 variant 1.
        let rank = if res == 20 { 1 } else { 0 };
        assert!(by[0].starts_with(&format!("rank {rank} on {host}: ")), "{stdout}");
        let single = dir.join(format!("single-{res}.exr"));
        let out = Command::new(exe)
            .args(["render", scene.to_str().unwrap(), "-D", &format!("res={res}")])
            .args(["--backend", "cpu", "--spp", "16", "--seed", "5", "-q", "-o", single.to_str().unwrap()])
            .env("XDG_RUNTIME_DIR", "/tmp")
            .output()
            .unwrap();
        assert!(out.status.success());
        let want = Film::load_exr(&single).unwrap();
        assert_eq!(want.width, res);
        assert_same(&dir.join("batch").join(&name), &want, &name);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A rank that cannot start (here rank 0: it cannot write the image's format) says why with its
/// name, and every rank ends instead of waiting for it.
#[test]
fn a_rank_that_cannot_start_is_named() {
    let Some(mpirun) = mpirun() else { return };
    let out = std::env::temp_dir().join(format!("caustic-mpi-{}.tiff", std::process::id()));
    let output = run(&ranks(&mpirun, 2), &args("path", &out), &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    let named = format!("rank 0 on {}", mpi_host());
    assert!(stderr.contains(&format!("error: {named}:")) && stderr.contains(".tiff"), "{stderr}");
    assert!(stderr.contains(&format!("{named} could not start")), "{stderr}");
}

/// A rank silent past `CAUSTIC_MPI_STALL` (here 1 s; rank 1 sleeps 20 s on its first chunk) is
/// named with its host and the samples it holds, and the job ends without waiting for it.
#[test]
fn a_silent_rank_is_named_and_not_waited_for() {
    let Some(mpirun) = mpirun() else { return };
    let dir = temp_dir("stall");
    let clock = std::time::Instant::now();
    let env = [("CAUSTIC_MPI_TEST_SLOW", "1:20000"), ("CAUSTIC_MPI_STALL", "1")];
    let output = run(&ranks(&mpirun, 2), &args("path", &dir.join("stall.exr")), &env);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    assert!(clock.elapsed().as_secs() < 15, "the job waited for the silent rank: {stderr}");
    let named = format!("rank 1 on {} stopped responding (rendering samples ", mpi_host());
    assert!(stderr.contains(&named) && stderr.contains("CAUSTIC_MPI_STALL"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}
