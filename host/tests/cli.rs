//! The command line: errors exit non-zero with a message and no panic; a render writes a finite image.
use std::process::Command;

fn caustic(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_caustic")).args(args).env("XDG_RUNTIME_DIR", "/tmp").output().expect("runs")
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
    let out = caustic(&["render", scene, "--backend", "cpu", "--spp", "2", "-D", "res=32", "-o", out_path.to_str().unwrap(), "-q"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("32x32") && summary.contains("Msamples/s"), "{summary}");
    let film = caustic::film::Film::load_exr(&out_path).unwrap();
    assert!(film.rgb.iter().flatten().all(|c| c.is_finite() && *c >= 0.0));
    assert!(film.rgb.iter().map(|p| p[1]).sum::<f32>() > 0.0, "the image is black");
}

#[test]
fn unknown_output_format_fails_before_rendering() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml");
    let out = caustic(&["render", scene, "--backend", "cpu", "--spp", "1", "-D", "res=8", "-o", "/tmp/x.tiff", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains(".tiff"), "{err}");
}
