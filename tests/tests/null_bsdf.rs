//! Mitsuba's `null` BSDF against Mitsuba 3.9.1: a null sphere between an area light and a floor (no
//! shadow) and a glowing null sphere (seen, lighting the floor, casting no shadow) beside a diffuse
//! one (`tests/data/null.xml`; the reference `null.exr` is Mitsuba's `volpath`, written by
//! `null.py`: Mitsuba's `path` stops shadow rays at null surfaces and renders this image 1.2–4.6%
//! darker per channel, measured at 16384 spp). caustic loads `null` as a mask of opacity 0 (`kernel/src/mask.rs`).
//! Per-pixel z-test and mean-luminance z-score on the CPU and the GPU backend and under light tracing,
//! with a negative control (the occluder diffuse).
use caustic::backend::BackendChoice;
use caustic::scene::IntegratorChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(choice: BackendChoice, spp: u32, occluder: &str) -> (f64, f64) {
    let label = format!("null spheres, occluder {occluder}");
    against_mitsuba_reference(
        "null.xml",
        &[("integrator", "path"), ("occluder", occluder)],
        "null.exr",
        REFERENCE_SPP,
        choice,
        spp,
        3,
        &label,
    )
}

fn assert_agrees((pass, z): (f64, f64), what: &str) {
    assert!(pass >= 0.99, "{what}: only {:.2}% of pixels agree with Mitsuba", pass * 100.0);
    assert!(z.abs() < 4.0, "{what}: mean luminance differs from Mitsuba by {z:.2} standard errors");
}

#[test]
fn null_cpu_matches_mitsuba_volpath() {
    assert_agrees(check(BackendChoice::Cpu, 1024, "null"), "CPU");
    // Negative control: a diffuse occluder's shadow must be caught.
    let (pass, z) = check(BackendChoice::Cpu, 1024, "diffuse");
    assert!(pass < 0.99 || z.abs() >= 4.0, "a diffuse occluder went unnoticed (pass {pass:.4}, z {z:+.2})");
}

#[test]
fn null_gpu_matches_mitsuba_volpath() {
    assert_agrees(check(BackendChoice::Gpu, 256, "null"), "GPU");
}

/// Light paths leave the glowing null sphere and cross the other one as null events.
#[test]
fn null_under_light_tracing_matches_mitsuba_volpath() {
    let mut scene =
        caustic::load_scene(&test_data("null.xml"), &defines(&[("integrator", "path")])).expect("loads");
    scene.integrator = scene.integrator.overridden(IntegratorChoice::Ptracer);
    let film = render_scene(&scene, BackendChoice::Cpu, 1024, 9);
    let reference = caustic::film::Film::load_exr(&test_data("null.exr")).expect("reference loads");
    let c = caustic::compare::compare(&film, &reference, 1024.0 / REFERENCE_SPP).expect("same size");
    println!(
        "ptracer: luminance ratio {:.4}, z {:+.2}, pass {:.4}",
        c.luminance_ratio,
        c.luminance_z.unwrap(),
        c.pass_fraction.unwrap()
    );
    assert_agrees((c.pass_fraction.unwrap(), c.luminance_z.unwrap()), "ptracer");
}
