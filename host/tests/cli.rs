//! The command line: errors exit non-zero with a message and no panic; a render writes a finite image.
//!
//! host/tests holds the host's own behaviour: loading scenes, meshes and images, and the command
//! line. Kernel math (sampling, BSDFs, lights) is tested in kernel/tests; rendered images as a whole in
//! tests/tests.
use std::ops::ControlFlow::{Break, Continue};
use std::process::Command;

fn caustic(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_caustic"))
        .args(args)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .expect("runs")
}

/// Runs caustic with `args` and `more`, sends it `signal` once the render is under way (the handler
/// is installed first thing), and returns what it did.
fn signalled(args: &[&str], more: &[&str], signal: i32) -> std::process::Output {
    let child = Command::new(env!("CARGO_BIN_EXE_caustic"))
        .args(args)
        .args(more)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    std::thread::sleep(std::time::Duration::from_secs(2));
    // SAFETY: kill(2) on the child's own process id.
    assert_eq!(unsafe { libc::kill(child.id() as i32, signal) }, 0);
    child.wait_with_output().expect("exits")
}

#[test]
fn missing_scene_is_a_clean_error() {
    let out = caustic(&["render", "/nonexistent/scene.xml", "--backend", "cpu", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("error:") && err.contains("/nonexistent/scene.xml"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn renders_the_default_scene_on_the_cpu() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out_path = dir.join("cb.exr");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let out = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "2",
        "-D",
        "res=32",
        "-o",
        out_path.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("32x32") && summary.contains("Msamples/s"), "{summary}");
    let film = caustic::output::film::Film::load_exr(&out_path).unwrap();
    assert!(film.rgb.iter().flatten().all(|c| c.is_finite() && *c >= 0.0));
    assert!(film.rgb.iter().map(|p| p[1]).sum::<f32>() > 0.0, "the image is black");
}

#[test]
fn unknown_output_format_fails_before_rendering() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let out = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "1",
        "-D",
        "res=8",
        "-o",
        "/tmp/x.tiff",
        "-q",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains(".tiff"), "{err}");
}

/// `convergence` against a reference rendered by caustic itself: a table row per power of two, a CSV
/// with the same rows, an SVG plot; and `compare` into a closed pipe ends quietly, without a panic.
#[test]
fn convergence_writes_its_curve_and_closed_stdout_is_not_a_panic() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-conv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let reference = dir.join("ref.exr");
    let out = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "64",
        "-D",
        "res=16",
        "-o",
        reference.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (csv, svg) = (dir.join("curve.csv"), dir.join("curve.svg"));
    let out = caustic(&[
        "convergence",
        scene,
        reference.to_str().unwrap(),
        "--backend",
        "cpu",
        "--spp",
        "8",
        "-D",
        "res=16",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
        "--integrator",
        "path,ibpt",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = String::from_utf8_lossy(&out.stdout);
    for spp in ["| 1 |", "| 2 |", "| 4 |", "| 8 |"] {
        assert_eq!(table.matches(spp).count(), 2, "one row per integrator: {table}");
    }
    assert!(table.contains("path |") && table.contains("ibpt |"), "{table}");
    let rows = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(rows.lines().count(), 9, "{rows}");
    assert_eq!(rows.lines().filter(|l| l.starts_with("ibpt,")).count(), 4, "{rows}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));

    let mut child = Command::new(env!("CARGO_BIN_EXE_caustic"))
        .args(["compare", reference.to_str().unwrap(), reference.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A render interrupted after 4 of 8 spp (its checkpoint written through the library) and resumed by
/// `render --checkpoint` gives the uninterrupted image (up to the rounding of differently split
/// passes) and removes the checkpoint; a checkpoint of other settings, a truncated one or one whose
/// sums are damaged (caught by its checksum) is refused with a message, not a panic.
#[test]
fn checkpointed_renders_resume_where_they_stopped() {
    use caustic::render::checkpoint::{fingerprint, Checkpoint};
    let dir = std::env::temp_dir().join(format!("caustic-cli-ckpt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene_path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let defines = vec![("res".to_string(), "16".to_string())];
    let buffers = caustic::prepare::buffers::build(
        &caustic::load::load_scene(std::path::Path::new(scene_path), &defines).unwrap(),
    )
    .unwrap();
    let (seed, spp) = (3u32, 8u32);
    let mut backend = caustic::backend::create(caustic::backend::BackendChoice::Cpu, &buffers).unwrap();
    // Interrupted at 4 of the 8 spp (passes stop at the listed count).
    caustic::render::passes::render_with_checkpoints(
        backend.as_mut(),
        &buffers,
        0,
        spp,
        seed,
        &[4],
        |done, _, _| Ok(if done == 4 { Break(()) } else { Continue(()) }),
    )
    .unwrap();
    let half = Checkpoint {
        scene: fingerprint(&buffers, seed, spp),
        seed,
        spp_total: spp,
        spp_done: 4,
        accum: backend.read_accum().unwrap(),
    };
    let ckpt = dir.join("render.ckpt");
    half.save(&ckpt).unwrap();
    assert_eq!(Checkpoint::load(&ckpt).unwrap(), half);

    let (resumed, whole) = (dir.join("resumed.exr"), dir.join("whole.exr"));
    let args = |out: &std::path::Path| {
        vec![
            "render".to_string(),
            scene_path.to_string(),
            "--backend".into(),
            "cpu".into(),
            "--spp".into(),
            "8".into(),
            "--seed".into(),
            "3".into(),
            "-D".into(),
            "res=16".into(),
            "-q".into(),
            "-o".into(),
            out.to_str().unwrap().to_string(),
        ]
    };
    let mut with_ckpt = args(&resumed);
    with_ckpt.extend(["--checkpoint".to_string(), ckpt.to_str().unwrap().to_string()]);
    let out = caustic(&with_ckpt.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("resumed at 4"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(!ckpt.exists(), "the checkpoint outlived the finished render");
    let out = caustic(&args(&whole).iter().map(String::as_str).collect::<Vec<_>>());
    assert!(out.status.success());
    let (a, b) = (
        caustic::output::film::Film::load_exr(&resumed).unwrap(),
        caustic::output::film::Film::load_exr(&whole).unwrap(),
    );
    for (p, q) in a.rgb.iter().zip(&b.rgb) {
        for c in 0..3 {
            assert!((p[c] - q[c]).abs() <= 1e-5 * (1.0 + q[c].abs()), "resumed {p:?} vs uninterrupted {q:?}");
        }
    }

    // Another seed's checkpoint, and a damaged file.
    Checkpoint { seed: 9, scene: fingerprint(&buffers, 9, spp), ..half.clone() }.save(&ckpt).unwrap();
    let out = caustic(&with_ckpt.iter().map(String::as_str).collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains("another scene, seed or sample count")
            && !err.contains("panicked"),
        "{err}"
    );
    std::fs::write(&ckpt, b"CAUSTCK1 but short").unwrap();
    let out = caustic(&with_ckpt.iter().map(String::as_str).collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("render.ckpt") && !err.contains("panicked"), "{err}");
    // A flipped bit in the sums: the checksum refuses what would resume into a wrong image.
    half.save(&ckpt).unwrap();
    let mut bytes = std::fs::read(&ckpt).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x40;
    std::fs::write(&ckpt, &bytes).unwrap();
    let out = caustic(&with_ckpt.iter().map(String::as_str).collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(1) && err.contains("render.ckpt") && err.contains("damaged"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `render --tev` speaks tev's protocol to whatever listens: a stand-in server records the packets
/// (each starts with its little-endian length); the image is created, then updated with all of its
/// pixels at least once. With nothing listening the render still succeeds, with a warning.
#[test]
fn render_streams_to_tev() {
    use std::io::Read;
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let server = std::thread::spawn(move || {
        let (mut socket, _) = listener.accept().unwrap();
        let mut bytes = Vec::new();
        socket.read_to_end(&mut bytes).unwrap();
        bytes
    });
    let dir = std::env::temp_dir().join(format!("caustic-cli-tev-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out_path = dir.join("tev.exr");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let out = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "4",
        "-D",
        "res=8",
        "-o",
        out_path.to_str().unwrap(),
        "-q",
        "--tev",
        &address,
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = server.join().unwrap();
    let mut packets = Vec::new();
    let mut at = 0;
    while at + 4 <= bytes.len() {
        let length = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        assert!(length >= 5 && at + length <= bytes.len(), "malformed packet at byte {at}");
        packets.push(length);
        at += length;
    }
    assert_eq!(at, bytes.len(), "trailing bytes");
    assert!(packets.len() >= 2, "{packets:?}");
    assert!(
        packets[1..].iter().any(|&l| l > 8 * 8 * 3 * 4),
        "no update carries the whole image: {packets:?}"
    );

    // Nobody listening: the render goes on.
    let closed = { std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().to_string() };
    let out = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "1",
        "-D",
        "res=8",
        "-o",
        out_path.to_str().unwrap(),
        "-q",
        "--tev",
        &closed,
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("without the viewer"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A checkpoint named like the image or its variance file is refused before rendering (exit code 1,
/// naming the file): the checkpoint is deleted once the image is saved, which would delete the image.
/// Spelt differently (`dir/./x`) it is still the same file.
#[test]
fn checkpoint_on_the_output_is_refused() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-ckpt-clash-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let image = dir.join("clash.exr");
    let (dotted_image, dotted_variance) = (dir.join(".").join("clash.exr"), dir.join("./clash.variance.exr"));
    let cases = [
        (image.clone(), image.clone(), false),
        (image.clone(), dotted_image.clone(), false),
        (image.clone(), dotted_variance.clone(), true),
        (dotted_image.clone(), dir.join("clash.variance.exr"), false),
    ];
    for (output, checkpoint, existing) in cases {
        std::fs::remove_file(&image).ok();
        if existing {
            std::fs::write(&image, b"an earlier render").unwrap();
        }
        let out = caustic(&[
            "render",
            scene,
            "--backend",
            "cpu",
            "--spp",
            "1",
            "-D",
            "res=8",
            "-q",
            "-o",
            output.to_str().unwrap(),
            "--checkpoint",
            checkpoint.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{output:?} with checkpoint {checkpoint:?}: {err}");
        assert!(err.contains("--checkpoint") && err.contains("clash") && !err.contains("panicked"), "{err}");
        if existing {
            assert_eq!(std::fs::read(&image).unwrap(), b"an earlier render", "the image was touched");
        } else {
            assert!(!image.exists(), "rendered although refused");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `compare` with a NaN or infinite pixel in either image is an error naming the file and the first
/// such pixel (x, y), not a NaN statistic with exit code 0.
#[test]
fn compare_refuses_non_finite_pixels() {
    use caustic::output::film::Film;
    let dir = std::env::temp_dir().join(format!("caustic-cli-nan-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let film = |bad: Option<(usize, f32)>| {
        let mut rgb = vec![[0.5f32; 3]; 4 * 3];
        if let Some((at, v)) = bad {
            rgb[at][1] = v;
        }
        Film::from_rgb(4, 3, rgb)
    };
    let (good, nan, inf) = (dir.join("good.exr"), dir.join("nan.exr"), dir.join("inf.exr"));
    film(None).save(&good).unwrap();
    film(Some((4 + 2, f32::NAN))).save(&nan).unwrap();
    film(Some((2 * 4 + 1, f32::INFINITY))).save(&inf).unwrap();
    for (image, reference, named, pixel) in
        [(&nan, &good, "nan.exr", "(2, 1)"), (&good, &inf, "inf.exr", "(1, 2)")]
    {
        let out = caustic(&["compare", image.to_str().unwrap(), reference.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{named}: {err}");
        assert!(err.contains(named) && err.contains(pixel) && !err.contains("panicked"), "{err}");
    }
    let out = caustic(&["compare", good.to_str().unwrap(), good.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).ok();
}

/// `bench --spp 0` is refused (it printed NaN throughput).
/// `render --strict`, `bench --strict` and `convergence --strict` refuse a scene with an unsupported
/// BSDF, naming file and line; without it `render` renders the scene with one warning about the
/// BSDF and a summary line.
#[test]
fn strict_refuses_what_would_be_substituted() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-strict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("hair.xml");
    std::fs::write(
        &scene,
        concat!(
            "<scene version=\"3.0.0\">\n",
            "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n",
            "<shape type=\"sphere\"><bsdf type=\"hair\"/></shape>\n",
            "<emitter type=\"constant\"/>\n",
            "</scene>\n"
        ),
    )
    .unwrap();
    let (scene, out_path) = (scene.to_str().unwrap(), dir.join("hair.exr"));
    let out_path = out_path.to_str().unwrap();
    let render = ["render", scene, "--backend", "cpu", "--spp", "1", "-o", out_path, "-q"];
    for args in [
        [&render[..], &["--strict"]].concat(),
        vec!["bench", scene, "--backend", "cpu", "--spp", "1", "--strict"],
        vec!["convergence", scene, out_path, "--backend", "cpu", "--spp", "1", "--strict"],
    ] {
        let out = caustic(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(
            err.contains("error:") && err.contains("hair.xml:3") && err.contains("'hair'"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!std::path::Path::new(out_path).exists(), "--strict wrote an image");
    let out = caustic(&render);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert_eq!(err.matches("'hair'").count(), 1, "{err}");
    assert!(err.contains("1 element substituted"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_refuses_zero_spp() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let out = caustic(&["bench", scene, "-D", "res=8", "--backend", "cpu", "--spp", "0"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("--spp") && !String::from_utf8_lossy(&out.stdout).contains("NaN"), "{err}");
}

/// `bench --integrator` measures that integrator instead of the scene's own, and says which.
#[test]
fn bench_measures_the_integrator_asked_for() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let bench = |extra: &[&str]| {
        let out =
            caustic(&[&["bench", scene, "-D", "res=8", "--backend", "cpu", "--spp", "1"], extra].concat());
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert!(stdout.lines().any(|l| l.starts_with("| cpu")), "no timed row: {stdout}");
        stdout
    };
    assert!(bench(&[]).contains("integrator path, film Splat"), "the scene's own");
    assert!(bench(&["--integrator", "bdpt"]).contains("integrator bdpt, film Splat"));
    assert!(bench(&["--integrator", "ibpt", "--film", "fis"]).contains("integrator ibpt, film Fis"));
}

/// Without a usable XDG_RUNTIME_DIR (unset, empty or relative: no display session) the Vulkan
/// loader's window-system code printed "XDG_RUNTIME_DIR is invalid or not set" on every GPU render;
/// caustic gives it a private directory of its own instead. Whether or not a Vulkan adapter exists,
/// the message must not appear.
#[test]
fn no_xdg_runtime_dir_message_without_a_display() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-xdg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out_path = dir.join("x.png");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    for value in [None, Some(""), Some("relative/dir")] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_caustic"));
        command.args([
            "render",
            scene,
            "--backend",
            "gpu",
            "--spp",
            "1",
            "-D",
            "res=8",
            "-q",
            "-o",
            out_path.to_str().unwrap(),
        ]);
        match value {
            None => command.env_remove("XDG_RUNTIME_DIR"),
            Some(v) => command.env("XDG_RUNTIME_DIR", v),
        };
        let out = command.output().expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("XDG_RUNTIME_DIR") && !err.contains("panicked"), "{value:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// SIGINT during a long render: the pass under way finishes, the image of the samples done so far is
/// written and marked partial (the summary line, the EXR's comments), the checkpoint is kept, and
/// the exit status is 130 (an interrupt lost every sample since the last checkpoint).
#[cfg(unix)]
#[test]
fn an_interrupted_render_saves_its_partial_image() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-sigint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (image, checkpoint) = (dir.join("partial.exr"), dir.join("partial.ck"));
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let (ck, im) = (checkpoint.to_str().unwrap(), image.to_str().unwrap());
    let out = signalled(
        &["render", scene, "--backend", "cpu", "--spp", "1000000", "-D", "res=32", "-q"],
        &["--checkpoint-every", "inf", "--checkpoint", ck, "-o", im],
        libc::SIGINT,
    );
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert_eq!(out.status.code(), Some(130), "{stdout}\n{stderr}");
    assert!(stdout.contains("partial:") && stdout.contains("of 1000000 spp (interrupted)"), "{stdout}");
    let comment = caustic::output::film::exr_comment(&image).unwrap().unwrap_or_default();
    assert!(comment.contains("partial render") && comment.contains("of 1000000 spp"), "{comment}");
    let film = caustic::output::film::Film::load_exr(&image).unwrap();
    assert!(film.rgb.iter().flatten().all(|c| c.is_finite()));
    assert!(film.rgb.iter().map(|p| p[1]).sum::<f32>() > 0.0, "the partial image is black");
    assert!(checkpoint.exists(), "the checkpoint of the samples done is kept");
    std::fs::remove_dir_all(&dir).ok();
}

/// An output path that cannot be written (here: inside a plain file) is an error naming it, given
/// before any rendering for `-o` (a long render was lost at the end), and for `--error-image`,
/// `--plot` and `--csv`; the OS's message appears once (it was printed twice).
#[test]
fn unwritable_outputs_are_named_before_rendering() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-unwritable-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let blocker = dir.join("a-file");
    std::fs::write(&blocker, "not a folder").unwrap();
    let image = dir.join("image.exr");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let ok = caustic(&[
        "render",
        scene,
        "--backend",
        "cpu",
        "--spp",
        "1",
        "-D",
        "res=8",
        "-q",
        "-o",
        image.to_str().unwrap(),
    ]);
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
    let inside = |name: &str| blocker.join(name).to_str().unwrap().to_string();
    let (exr, png, svg, csv) = (inside("out.exr"), inside("err.png"), inside("plot.svg"), inside("c.csv"));
    let image = image.to_str().unwrap();
    for (what, args) in [
        // A million samples per pixel: this fails in well under a second only if checked first.
        (
            "-o",
            vec!["render", scene, "--backend", "cpu", "--spp", "1000000", "-D", "res=64", "-q", "-o", &exr],
        ),
        ("--error-image", vec!["compare", image, image, "--error-image", &png]),
        (
            "--plot",
            vec![
                "convergence",
                scene,
                image,
                "--backend",
                "cpu",
                "--spp",
                "1000000",
                "-D",
                "res=8",
                "--plot",
                &svg,
            ],
        ),
        (
            "--csv",
            vec![
                "convergence",
                scene,
                image,
                "--backend",
                "cpu",
                "--spp",
                "1000000",
                "-D",
                "res=8",
                "--csv",
                &csv,
            ],
        ),
    ] {
        let start = std::time::Instant::now();
        let out = caustic(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains("a-file"), "{what}: {err}");
        assert!(start.elapsed().as_secs() < 20, "{what}: rendered before failing");
        let os = err.rsplit(": ").next().unwrap_or_default().trim();
        assert_eq!(err.matches(os).count(), 1, "{what}: the OS error twice: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// A batch in one process: two scenes × two `--vary` values give four images in the `-o` folder,
/// one summary line each, each the size its variant asks for; a failed one (a scene that does not
/// exist) is reported by name while the others are still written, and the exit status says so.
#[test]
fn a_batch_renders_every_scene_and_variant() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-batch-{}", std::process::id()));
    let cbox = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let copy = dir.join("box2.xml");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(cbox, &copy).unwrap();
    let out_dir = dir.join("out");
    let common =
        ["--vary", "res=8,12", "--backend", "cpu", "--spp", "2", "-q", "-o", out_dir.to_str().unwrap()];
    let out = caustic(&[&["render", cbox, copy.to_str().unwrap()][..], &common].concat());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(stdout.lines().count(), 4, "{stdout}");
    for (stem, res) in [("cornell-box", 8), ("cornell-box", 12), ("box2", 8), ("box2", 12)] {
        let film =
            caustic::output::film::Film::load_exr(&out_dir.join(format!("{stem}-res={res}.exr"))).unwrap();
        assert_eq!((film.width, film.height), (res, res), "{stem} at res={res}");
    }
    let missing = dir.join("missing.xml");
    let out = caustic(&[&["render", missing.to_str().unwrap(), cbox][..], &common].concat());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("missing-res=8.exr") && stderr.contains("2 of this process's images failed"),
        "{stderr}"
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

/// A scene with Mitsuba's `aov` integrator: `render -o x.exr` writes one EXR holding the image and
/// every AOV channel under Mitsuba's names (those of the reference Mitsuba wrote for the scene), all
/// finite; a render resumed from a checkpoint of half its samples writes the AOV channels of the
/// uninterrupted one (they are traced from the samples `[0, spp)` at the end); `-o x.png` writes the
/// image alone, and nothing else is written beside either.
#[test]
fn aov_scenes_write_one_exr_with_every_channel() {
    use caustic::output::aov::exr::read_channels;
    use caustic::render::checkpoint::{fingerprint, Checkpoint};
    let dir = std::env::temp_dir().join(format!("caustic-cli-aov-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/");
    let scene_path = format!("{data}aov.xml");
    let render = |out: &std::path::Path, extra: &[&str]| {
        let mut args =
            vec!["render", &scene_path, "--backend", "cpu", "--spp", "8", "--seed", "3", "-q", "-o"];
        args.push(out.to_str().unwrap());
        args.extend(extra);
        let out = caustic(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    };
    // Half of the samples through the library, as an interrupted render leaves them.
    let buffers = caustic::prepare::buffers::build(
        &caustic::load::load_scene(std::path::Path::new(&scene_path), &[]).unwrap(),
    )
    .unwrap();
    let (seed, spp) = (3u32, 8u32);
    let mut backend = caustic::backend::create(caustic::backend::BackendChoice::Cpu, &buffers).unwrap();
    caustic::render::passes::render_with_checkpoints(
        backend.as_mut(),
        &buffers,
        0,
        spp,
        seed,
        &[4],
        |done, _, _| Ok(if done == 4 { Break(()) } else { Continue(()) }),
    )
    .unwrap();
    let accum = backend.read_accum().unwrap();
    let ckpt = dir.join("aov.ckpt");
    Checkpoint { scene: fingerprint(&buffers, seed, spp), seed, spp_total: spp, spp_done: 4, accum }
        .save(&ckpt)
        .unwrap();

    let (whole, resumed, png) = (dir.join("whole.exr"), dir.join("resumed.exr"), dir.join("image.png"));
    render(&whole, &[]);
    render(&resumed, &["--checkpoint", ckpt.to_str().unwrap()]);
    render(&png, &[]);
    let (_, _, reference) = read_channels(std::path::Path::new(&format!("{data}aov.exr"))).unwrap();
    let (w, h, a) = read_channels(&whole).unwrap();
    let (_, _, b) = read_channels(&resumed).unwrap();
    assert_eq!((w, h), (64, 48));
    let names = |c: &[(String, Vec<f32>)]| c.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&a), names(&reference), "channel names differ from Mitsuba's");
    assert_eq!(names(&b), names(&a));
    for ((name, p), (_, q)) in a.iter().zip(&b) {
        assert!(p.iter().all(|v| v.is_finite()), "{name} has a non-finite value");
        let same = p.iter().zip(q).all(|(x, y)| (x - y).abs() <= 1e-5 * (1.0 + y.abs()));
        assert!(same, "{name}: the resumed render differs from the uninterrupted one");
    }
    let image = image::open(&png).unwrap();
    assert_eq!((image.width(), image.height(), image.color().channel_count()), (64, 48, 3));
    let mut written: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    written.sort();
    assert_eq!(written, ["image.png", "resumed.exr", "whole.exr"], "files written besides the images");
    std::fs::remove_dir_all(&dir).ok();
}

/// `kernel-stats` writes the modules the driver would compile, one per candidate pipeline; the
/// statistics need an adapter that reports them (NVIDIA's does, CI's lavapipe does not), and without
/// one the command says so and fails cleanly unless the modules alone were asked for.
#[test]
fn kernel_stats_writes_what_the_driver_gets_or_says_why_not() {
    let dir = std::env::temp_dir().join(format!("caustic-kernel-stats-{}", std::process::id()));
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let run = |extra: &[&str]| {
        let mut args = vec!["kernel-stats", scene, "-D", "res=32"];
        args.extend_from_slice(extra);
        Command::new(env!("CARGO_BIN_EXE_caustic"))
            .args(&args)
            .env("XDG_RUNTIME_DIR", "/tmp")
            .env("CAUSTIC_PATH_LOOP", "plain")
            .env("CAUSTIC_WORKGROUP", "8x8,32x16")
            .output()
            .expect("runs")
    };
    let out = run(&["--write-spirv", dir.to_str().unwrap()]);
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stdout}{stderr}");
    for size in ["8x8", "32x16"] {
        let bytes =
            std::fs::read(dir.join(format!("entry-render-plain-{size}.spv"))).expect("module written");
        assert_eq!(bytes[..4], 0x0723_0203u32.to_le_bytes(), "{size}: not SPIR-V");
    }
    let reported = stdout.contains("| entry::render | Plain | 8x8 |");
    assert!(reported || stdout.contains("reports pipeline statistics"), "{stdout}");
    let out = run(&[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.success(), reported, "{stderr}");
    assert!(
        reported || stderr.contains("error: no Vulkan adapter here reports pipeline statistics"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    std::fs::remove_dir_all(dir).unwrap();
}

/// The CPU walks the 4-wide BVH unless `CAUSTIC_CPU_BVH=2` asks for BVH2, and its closing line says
/// which; any other value is an error naming the variable.
#[test]
fn the_cpu_names_its_bvh_and_refuses_an_unknown_one() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let bench = |bvh: Option<&str>| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_caustic"));
        command.args(["bench", scene, "--backend", "cpu", "--spp", "1", "-D", "res=16"]);
        command.env("XDG_RUNTIME_DIR", "/tmp").env_remove("CAUSTIC_CPU_BVH");
        if let Some(v) = bvh {
            command.env("CAUSTIC_CPU_BVH", v);
        }
        let out = command.output().expect("runs");
        let text =
            format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        (out.status.success(), text)
    };
    for (bvh, named) in [(None, "4-wide BVH"), (Some("4"), "4-wide BVH"), (Some("2"), "BVH2")] {
        let (ok, text) = bench(bvh);
        assert!(ok && text.contains(&format!("threads, {named})")), "{bvh:?}: {text}");
    }
    // (`bench` prints the backend as unavailable, with the reason; `render` stops with it.)
    let (_, text) = bench(Some("8"));
    assert!(text.contains("unavailable: CAUSTIC_CPU_BVH must be 2 or 4, not \"8\""), "{text}");
    let image = std::env::temp_dir().join(format!("caustic-cpu-bvh-{}.exr", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_caustic"))
        .args(["render", scene, "--backend", "cpu", "--spp", "1", "-D", "res=16", "-q", "-o"])
        .arg(&image)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .env("CAUSTIC_CPU_BVH", "8")
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("CAUSTIC_CPU_BVH must be 2 or 4"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!image.exists(), "no image from a render that did not start");
}

/// No output may be one of the command's inputs, through a symbolic or a hard link or under the
/// name of a texture the scene reads: each is refused before rendering, naming both files, and the
/// input is left as it was.
#[test]
fn an_output_that_is_an_input_is_refused_and_the_input_kept() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-inputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let texture = dir.join("wall.png");
    image::RgbImage::from_pixel(2, 2, image::Rgb([200, 100, 50])).save(&texture).unwrap();
    let scene = dir.join("scene.xml");
    std::fs::write(
        &scene,
        r#"<scene version="3.0.0">
    <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    <shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="wall.png"/></texture></bsdf></shape>
    <emitter type="constant"/>
</scene>"#,
    )
    .unwrap();
    let (scene_text, texture_bytes) = (std::fs::read(&scene).unwrap(), std::fs::read(&texture).unwrap());
    let soft = dir.join("soft.exr");
    std::os::unix::fs::symlink(&scene, &soft).unwrap();
    let hard = dir.join("hard.png");
    std::fs::hard_link(&scene, &hard).unwrap();
    let render = |out: &std::path::Path, extra: &[&str]| {
        let mut args = vec!["render", scene.to_str().unwrap(), "--backend", "cpu", "--spp", "1", "-q"];
        args.extend_from_slice(extra);
        args.extend(["-o", out.to_str().unwrap()]);
        caustic(&args)
    };
    for out in [&soft, &hard, &texture] {
        let o = render(out, &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains("refusing to write"), "{}: {err}", out.display());
        assert!(err.contains(out.to_str().unwrap()), "names the output: {err}");
    }
    let o = render(&hard, &[]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("scene.xml"), "names the input");
    // The variance file and the checkpoint are outputs too.
    std::fs::hard_link(&scene, dir.join("v.variance.exr")).unwrap();
    let o = render(&dir.join("v.exr"), &["--variance"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("v.variance.exr"), "variance file refused");
    let o = render(&dir.join("c.exr"), &["--checkpoint", hard.to_str().unwrap()]);
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("refusing"));
    assert_eq!(std::fs::read(&scene).unwrap(), scene_text);
    assert_eq!(std::fs::read(&texture).unwrap(), texture_bytes);
    // A plain output beside them is written.
    let o = render(&dir.join("fine.exr"), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    // `compare`: an error image that is the reference (hard link) or not a PNG.
    let reference = dir.join("fine.exr");
    let reference_bytes = std::fs::read(&reference).unwrap();
    let alias = dir.join("alias.png");
    std::fs::hard_link(&reference, &alias).unwrap();
    let r = reference.to_str().unwrap();
    for error_image in [alias.to_str().unwrap(), r] {
        let o = caustic(&["compare", r, r, "--error-image", error_image]);
        assert!(!o.status.success(), "{error_image}");
    }
    assert_eq!(std::fs::read(&reference).unwrap(), reference_bytes);
    std::fs::remove_dir_all(&dir).ok();
}

/// A write that fails (here past the file-size limit) leaves the file it would have replaced as it
/// was, exits non-zero, and leaves no temporary file behind.
#[test]
fn a_failed_write_keeps_the_previous_image() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-fsize-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("image.ppm");
    std::fs::write(&out, b"the previous image").unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    // 64x64 sRGB bytes (12 KB) past a limit of 4 blocks (2-4 KB).
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -f 4 && exec \"$0\" render {scene} --backend cpu --spp 1 -D res=64 -q -o {}",
            out.display()
        ))
        .arg(env!("CARGO_BIN_EXE_caustic"))
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("image.ppm") && !err.contains("panicked"), "{err}");
    assert_eq!(std::fs::read(&out).unwrap(), b"the previous image");
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().all(|n| !n.contains(".partial")), "temporary left: {names:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// SIGTERM during a batch saves the image under way as partial and ends the batch with 143: the
/// next image is not started.
#[test]
fn a_signal_ends_a_batch() {
    let dir = std::env::temp_dir().join(format!("caustic-cli-batch-signal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let copy = dir.join("second.xml");
    std::fs::copy(scene, &copy).unwrap();
    let out = signalled(
        &["render", scene, copy.to_str().unwrap(), "--backend", "cpu", "--spp", "1000000"],
        &["-D", "res=32", "-q", "-o", dir.to_str().unwrap()],
        libc::SIGTERM,
    );
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert_eq!(out.status.code(), Some(143), "{stdout}\n{stderr}");
    assert!(stdout.contains("(interrupted)") && stdout.lines().count() == 1, "{stdout}");
    assert!(dir.join("cornell-box.exr").exists(), "the partial image is saved");
    assert!(!dir.join("second.exr").exists(), "the next image was started");
    std::fs::remove_dir_all(&dir).ok();
}

/// `CAUSTIC_STEP_TIMES=1` times each step of a GPU pass: a `bdpt` render names its light paths, its
/// camera paths and the splat words' resolve, each with one dispatch a pass; without it, no line.
#[test]
fn step_times_name_each_step_of_a_gpu_pass() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let dir = std::env::temp_dir().join(format!("caustic-steps-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out_path = dir.join("steps.exr");
    let run = |timed: &str| {
        Command::new(env!("CARGO_BIN_EXE_caustic"))
            .args(["render", scene, "-D", "res=16", "--integrator", "bdpt", "--backend", "gpu", "--spp", "3"])
            .args(["-o", out_path.to_str().unwrap()])
            .env("XDG_RUNTIME_DIR", "/tmp")
            .env("CAUSTIC_STEP_TIMES", timed)
            .output()
            .expect("runs")
    };
    let out = run("1");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    if stderr.contains("this adapter has no timestamp queries") {
        assert!(!stderr.contains("steps:"), "{stderr}");
    } else {
        for step in ["light paths (cache)", "camera paths", "resolve"] {
            let line =
                stderr.lines().find(|l| l.starts_with(&format!("steps: {step} "))).unwrap_or_else(|| {
                    panic!("no line for {step}: {stderr}");
                });
            assert!(line.contains(" 3 dispatches"), "{line}");
            let ms: f64 =
                line["steps: ".len() + step.len()..].split_whitespace().next().unwrap().parse().unwrap();
            assert!(ms > 0.0 && ms.is_finite(), "{line}");
        }
    }
    let out = run("0");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("steps:"), "{stderr}");
    std::fs::remove_dir_all(dir).unwrap();
}
