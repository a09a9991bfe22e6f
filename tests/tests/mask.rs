//! Mitsuba's `mask` BSDF against Mitsuba 3.9.1: two cards of opacity 0.3 and 0.7 between an area light
//! and a floor (`tests/data/mask_cards.xml`; the reference `mask_cards.exr` is Mitsuba's `volpath`,
//! written by `mask_cards.py`), seen directly and through their shadows, on the CPU and the GPU
//! backend; per-pixel z-test and mean-luminance z-score, with a negative control (opacity 0.25 for
//! 0.3). Integrators other than `path` refuse masks for now.
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(choice: BackendChoice, spp: u32, opacity: &str) -> (f64, f64) {
    let label = format!("mask cards, opacity {opacity}");
    let defines = [("opacity", opacity)];
    against_mitsuba_reference(
        "mask_cards.xml",
        &defines,
        "mask_cards.exr",
        REFERENCE_SPP,
        choice,
        spp,
        5,
        &label,
    )
}

#[test]
fn mask_cpu_matches_mitsuba_volpath() {
    let (pass, z) = check(BackendChoice::Cpu, 1024, "0.3");
    assert!(pass >= 0.99, "only {:.2}% of pixels agree with Mitsuba", pass * 100.0);
    assert!(z.abs() < 4.0, "mean luminance differs from Mitsuba by {z:.2} standard errors");
    // Negative control: the first card 0.05 less opaque must be caught.
    let (pass, z) = check(BackendChoice::Cpu, 1024, "0.25");
    assert!(pass < 0.99 || z.abs() >= 4.0, "opacity 0.25 for 0.3 went unnoticed (pass {pass:.4}, z {z:+.2})");
}

#[test]
fn mask_gpu_matches_mitsuba_volpath() {
    let (pass, z) = check(BackendChoice::Gpu, 256, "0.3");
    assert!(pass >= 0.99, "only {:.2}% of pixels agree with Mitsuba", pass * 100.0);
    assert!(z.abs() < 4.0, "mean luminance differs from Mitsuba by {z:.2} standard errors");
}

#[test]
fn integrators_other_than_path_refuse_masks() {
    let mut scene = caustic::load_scene(&test_data("mask_cards.xml"), &[]).expect("loads");
    for choice in [
        caustic::scene::IntegratorChoice::Direct,
        caustic::scene::IntegratorChoice::Ptracer,
        caustic::scene::IntegratorChoice::Ibpt,
    ] {
        scene.integrator = scene.integrator.overridden(choice);
        let Err(e) = caustic::buffers::build(&scene) else { panic!("{choice:?} renders masks") };
        assert!(format!("{e:#}").contains("mask"), "{e:#}");
    }
}
