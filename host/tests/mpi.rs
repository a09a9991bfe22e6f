//! `mpirun -n N caustic render …` (built with `--features mpi`) writes the image one process
//! writes with the same seed: the ranks' sample shares sum to the same estimator, so only the
//! order of the float sums differs. Runs when the crate is built with the feature and `mpirun` is
//! on the PATH (CI installs Open MPI and runs it: `.ci/run`).
#![cfg(feature = "mpi")]
use caustic::film::Film;
use std::path::{Path, PathBuf};
use std::process::Command;

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

fn render(launcher: &[String], integrator: &str, out: &Path) {
    let exe = env!("CARGO_BIN_EXE_caustic");
    let scene = scene();
    let args = ["render", scene.to_str().unwrap(), "-D", "res=24", "--backend", "cpu", "--spp", "48"];
    let args: Vec<&str> =
        args.iter().copied().chain(["--integrator", integrator, "--seed", "3", "-q", "-o"]).collect();
    let (program, rest) = match launcher.split_first() {
        Some((p, rest)) => (p.as_str(), rest.iter().map(String::as_str).chain([exe]).collect::<Vec<_>>()),
        None => (exe, vec![]),
    };
    let output = Command::new(program)
        .args(rest)
        .args(&args)
        .arg(out)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .expect("the render starts");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{launcher:?}: {stdout}{}", String::from_utf8_lossy(&output.stderr));
    // Rank 0 alone reports.
    assert_eq!(stdout.lines().count(), 1, "{launcher:?}: {stdout}");
}

#[test]
fn mpi_ranks_render_the_one_process_image() {
    let Some(mpirun) = mpirun() else {
        eprintln!("no mpirun on the PATH: the MPI render is not tested here");
        return;
    };
    let dir = std::env::temp_dir().join(format!("caustic-mpi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for integrator in ["path", "ptracer"] {
        let single = dir.join(format!("{integrator}-1.exr"));
        render(&[], integrator, &single);
        let want = Film::load_exr(&single).unwrap();
        assert!(want.rgb.iter().flatten().any(|&c| c > 0.0), "{integrator}: a black image proves nothing");
        for ranks in [2, 3] {
            let out = dir.join(format!("{integrator}-{ranks}.exr"));
            let launcher: Vec<String> =
                mpirun.iter().cloned().chain(["-n".into(), ranks.to_string()]).collect();
            render(&launcher, integrator, &out);
            let got = Film::load_exr(&out).unwrap();
            for (i, (p, q)) in got.rgb.iter().zip(&want.rgb).enumerate() {
                for c in 0..3 {
                    assert!(
                        (p[c] - q[c]).abs() <= TOLERANCE * p[c].abs().max(q[c].abs()),
                        "{integrator}, {ranks} ranks: pixel {i}: {p:?} vs one process {q:?}"
                    );
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
