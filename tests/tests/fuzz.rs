//! A mutation fuzzer for the loaders, on stable Rust: the corpus in tests/fuzz/corpus (a Mitsuba
//! scene with OBJ/MTL, PLY, PNG and EXR files it uses, and a checkpoint made here) is mutated byte by
//! byte (flips, random bytes, insertions, deletions, truncation, splices of the file into itself,
//! interesting numbers) and every mutant is loaded: a loader must return Ok or an error, never panic.
//! A short run (CAUSTIC_FUZZ_SECONDS, default 10) belongs to the normal test suite; set it higher
//! for a longer one. A panicking mutant is kept in the temporary folder named in the failure.
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

// A deterministic stream per seed, so a failure reproduces with CAUSTIC_FUZZ_SEED.
use caustic_tests::Xorshift as Rng;

const INTERESTING: &[&[u8]] = &[
    b"0",
    b"-1",
    b"nan",
    b"inf",
    b"1e39",
    b"-1e19",
    b"4294967295",
    b"65536",
    b"\xff\xff\xff\x7f",
    b"\0\0\0\0",
];

fn mutate(data: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut d = data.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(d.len() + 1);
        match rng.below(7) {
            0 if !d.is_empty() => {
                let i = at.min(d.len() - 1);
                d[i] ^= 1 << rng.below(8);
            }
            1 if !d.is_empty() => {
                let i = at.min(d.len() - 1);
                d[i] = rng.next_u64() as u8;
            }
            2 => d.insert(at, rng.next_u64() as u8),
            3 if at < d.len() => {
                let end = (at + 1 + rng.below(16)).min(d.len());
                d.drain(at..end);
            }
            4 => d.truncate(at),
            5 if !d.is_empty() => {
                let from = rng.below(d.len());
                let piece: Vec<u8> = d[from..(from + 1 + rng.below(32)).min(d.len())].to_vec();
                d.splice(at..at, piece);
            }
            _ => {
                let word = INTERESTING[rng.below(INTERESTING.len())];
                let end = (at + word.len()).min(d.len());
                d.splice(at..end, word.iter().copied());
            }
        }
    }
    d
}

/// Loads `file` (in `dir`) the way the renderer would.
fn load(dir: &Path, file: &str) -> Result<(), String> {
    fn e(e: impl std::fmt::Display) -> String {
        format!("{e:#}")
    }
    match file {
        // The scene loads the PLY mesh (the PLY reader is the mesh module's own).
        "scene.xml" | "mesh.ply" => {
            let scene = caustic::load::load_scene(&dir.join("scene.xml"), &[]).map_err(e)?;
            caustic::prepare::buffers::build(&scene).map_err(e)?;
        }
        "mesh.obj" | "mesh.mtl" => {
            let scene = caustic::load::load_scene(&dir.join("mesh.obj"), &[]).map_err(e)?;
            caustic::prepare::buffers::build(&scene).map_err(e)?;
        }
        "env.exr" | "texture.png" => {
            drop(caustic::load::image_io::load_linear_rgb(&dir.join(file), false).map_err(e)?)
        }
        "checkpoint" => drop(caustic::render::checkpoint::Checkpoint::load(&dir.join(file)).map_err(e)?),
        other => panic!("no loader for {other}"),
    }
    Ok(())
}

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus")
}

#[test]
fn loaders_never_panic_on_mutated_files() {
    let seconds: u64 = std::env::var("CAUSTIC_FUZZ_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(10);
    let seed: u64 = std::env::var("CAUSTIC_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(0x5eed);
    let dir = std::env::temp_dir().join(format!("caustic-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files: Vec<String> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|f| f.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let pristine: Vec<(String, Vec<u8>)> =
        files.iter().map(|f| (f.clone(), std::fs::read(corpus().join(f)).unwrap())).collect();
    // A checkpoint of two pixels, made through the API (its format carries a checksum).
    let checkpoint = dir.join("checkpoint");
    caustic::render::checkpoint::Checkpoint {
        scene: 7,
        seed: 1,
        spp_total: 4,
        spp_done: 2,
        accum: caustic::backend::accumulation::Accumulation::new(2, false),
    }
    .save(&checkpoint)
    .unwrap();
    let mut targets = pristine.clone();
    targets.push(("checkpoint".into(), std::fs::read(&checkpoint).unwrap()));
    for (name, bytes) in &pristine {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    // Every pristine file loads: the corpus exercises the loaders past their first check.
    for (name, _) in &targets {
        load(&dir, name).unwrap_or_else(|e| panic!("the corpus's {name} does not load: {e}"));
    }
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng(seed | 1);
    let (start, mut runs, mut errors) = (Instant::now(), 0u64, 0u64);
    let mut panics = Vec::new();
    while start.elapsed() < Duration::from_secs(seconds) && panics.len() < 5 {
        let (name, bytes) = &targets[rng.below(targets.len())];
        let mutant = mutate(bytes, &mut rng);
        std::fs::write(dir.join(name), &mutant).unwrap();
        match std::panic::catch_unwind(|| load(&dir, name)) {
            Ok(Ok(())) => {}
            Ok(Err(_)) => errors += 1,
            Err(payload) => {
                let message = payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                let kept = dir.join(format!("panic-{}-{name}", panics.len()));
                std::fs::write(&kept, &mutant).unwrap();
                panics.push(format!("{name}: {message} (mutant kept as {})", kept.display()));
            }
        }
        std::fs::write(dir.join(name), bytes).unwrap();
        runs += 1;
    }
    let _ = std::panic::take_hook();
    println!(
        "{runs} mutants in {:.1} s, {errors} clean errors, {} panics",
        start.elapsed().as_secs_f64(),
        panics.len()
    );
    assert!(panics.is_empty(), "loaders panicked:\n{}", panics.join("\n"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The writers against misuse: after loading the corpus scene and OBJ (so that their files are
/// this process's inputs), every writer (the image as EXR, PNG and PPM, the variance file, a
/// checkpoint, a convergence curve and plot) is pointed at random targets: the inputs themselves,
/// symbolic and hard links to them, fresh names, a directory, a path through a file. No input may
/// change, no writer may panic, and a write either succeeds whole or leaves what was there.
#[test]
fn writers_never_overwrite_an_input_or_leave_half_a_file() {
    use caustic::output::film::Film;
    use caustic::render::convergence::ConvergencePoint;
    let seed: u64 = std::env::var("CAUSTIC_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(0x5eed);
    let dir = std::env::temp_dir().join(format!("caustic-fuzz-outputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut inputs = Vec::new();
    for f in std::fs::read_dir(corpus()).unwrap() {
        let name = f.unwrap().file_name().to_string_lossy().into_owned();
        std::fs::copy(corpus().join(&name), dir.join(&name)).unwrap();
        inputs.push(name);
    }
    inputs.sort();
    caustic::load::load_scene(&dir.join("scene.xml"), &[]).unwrap();
    caustic::load::load_scene(&dir.join("mesh.obj"), &[]).unwrap();
    caustic::load::image_io::load_linear_rgb(&dir.join("texture.png"), false).unwrap();
    let snapshot: Vec<Vec<u8>> = inputs.iter().map(|n| std::fs::read(dir.join(n)).unwrap()).collect();
    let film = Film {
        width: 3,
        height: 2,
        rgb: vec![[0.25, 0.5, 1.0]; 6],
        variance: Some(vec![[0.01; 3]; 6]),
        invalid_samples: 0,
        comment: None,
        aovs: Vec::new(),
        sum_variance_factor: 1.0,
    };
    let point = ConvergencePoint {
        spp: 4,
        seconds: 0.5,
        rmse: 0.1,
        rel_mse: 0.01,
        luminance_ratio: 1.0,
        net_mse: None,
        net_rel_mse: None,
    };
    let mut rng = Rng(seed | 1);
    let (mut written, mut refused) = (0, 0);
    for round in 0..300 {
        // The target: an input, a link to one, a fresh name, a directory, or through a file.
        let input = dir.join(&inputs[rng.below(inputs.len())]);
        let extension = ["exr", "png", "ppm", "ckpt", "csv", "svg"][rng.below(6)];
        let target = match rng.below(5) {
            0 => input.clone(),
            1 => {
                let link = dir.join(format!("soft-{round}.{extension}"));
                std::os::unix::fs::symlink(&input, &link).unwrap();
                link
            }
            2 => {
                let link = dir.join(format!("hard-{round}.{extension}"));
                std::fs::hard_link(&input, &link).unwrap();
                link
            }
            3 => dir.join(format!("fresh-{}.{extension}", rng.below(4))),
            _ => dir.join(["scene.xml", "texture.png"][rng.below(2)]).join(format!("x.{extension}")),
        };
        let before = std::fs::read(&target).ok();
        let writer = rng.below(5);
        let result = std::panic::catch_unwind(|| match writer {
            0 => film.save(&target),
            1 => film.save_variance(&target),
            2 => caustic::render::checkpoint::Checkpoint {
                scene: 1,
                seed: 2,
                spp_total: 8,
                spp_done: 4,
                accum: caustic::backend::accumulation::Accumulation::new(6, false),
            }
            .save(&target),
            3 => caustic::render::convergence::write_csv(&target, &[("path", &[point][..])]),
            _ => caustic::render::convergence::write_plot(&target, &[("path".to_string(), vec![point])]),
        });
        let result = result.unwrap_or_else(|_| panic!("a writer panicked on {}", target.display()));
        let after = std::fs::read(&target).ok();
        match result {
            Ok(()) => {
                written += 1;
                assert!(after.as_ref().is_some_and(|a| !a.is_empty()), "{} written empty", target.display());
            }
            Err(_) => {
                refused += 1;
                assert_eq!(before, after, "a failed write changed {}", target.display());
            }
        }
        for (name, bytes) in inputs.iter().zip(&snapshot) {
            assert_eq!(
                &std::fs::read(dir.join(name)).unwrap(),
                bytes,
                "{name} changed writing {}",
                target.display()
            );
        }
    }
    let partial = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".partial"));
    assert_eq!(partial.count(), 0, "temporary files left behind");
    println!("{written} writes, {refused} refused");
    assert!(written > 0 && refused > 0, "both outcomes exercised");
    std::fs::remove_dir_all(&dir).ok();
}
