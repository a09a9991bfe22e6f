//! Mitsuba's `null` BSDF against Mitsuba 3.9.1: a null sphere between an area light and a floor (no
//! shadow) and a glowing null sphere (seen, lighting the floor, casting no shadow) beside a diffuse
//! one (`tests/data/null.xml`; the reference `null.exr` is Mitsuba's `volpath`, written by
//! `null.py`: Mitsuba's `path` stops shadow rays at null surfaces and renders this image 1.2–4.6%
//! darker per channel, measured at 16384 spp). caustic loads `null` as a mask of opacity 0 (`kernel/src/mask.rs`).
//! Per-pixel z-test and mean-luminance z-score on the CPU and the GPU backend and under light tracing,
//! with a negative control (the occluder diffuse).
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

/// `null.xml` under `integrator` (the scene's `$integrator`) with the occluder's BSDF `occluder`.
fn check(choice: BackendChoice, integrator: &str, spp: u32, occluder: &str) -> (f64, f64) {
    let label = format!("null spheres, {integrator}, occluder {occluder}");
    against_mitsuba_reference(
        "null.xml",
        &[("integrator", integrator), ("occluder", occluder)],
        "null.exr",
        REFERENCE_SPP,
        choice,
        spp,
        3,
        &label,
    )
}

#[test]
fn null_cpu_matches_mitsuba_volpath() {
    assert_agrees_with_reference(check(BackendChoice::Cpu, "path", 1024, "null"), "CPU");
    // Negative control: a diffuse occluder's shadow must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "path", 1024, "diffuse");
    assert_disagrees_with_reference((pass, z), "a diffuse occluder");
}

#[test]
fn null_gpu_matches_mitsuba_volpath() {
    assert_agrees_with_reference(check(BackendChoice::Gpu, "path", 256, "null"), "GPU");
}

/// Light paths leave the glowing null sphere and cross the other one as null events.
#[test]
fn null_under_light_tracing_matches_mitsuba_volpath() {
    assert_agrees_with_reference(check(BackendChoice::Cpu, "ptracer", 1024, "null"), "ptracer");
}
