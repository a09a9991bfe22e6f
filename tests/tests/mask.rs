//! Mitsuba's `mask` BSDF against Mitsuba 3.9.1: two cards of opacity 0.3 and 0.7 between an area light
//! and a floor (`tests/data/mask_cards.xml`; the reference `mask_cards.exr` is Mitsuba's `volpath`,
//! written by `mask_cards.py`), seen directly and through their shadows, on the CPU and the GPU
//! backend; per-pixel z-test and mean-luminance z-score, with a negative control (opacity 0.25 for
//! 0.3). `direct` against Mitsuba's `volpath` at `max_depth` 2, its estimand: Mitsuba's own `direct`
//! stops camera rays at masks and rendered 12.6% darker (mean 0.1462 against 0.1672, 32×32). Light
//! tracing: `mask_light_tracing.rs`.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::IntegratorChoice;
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
    assert_agrees_with_reference(check(BackendChoice::Cpu, 1024, "0.3"), "CPU");
    // Negative control: the first card 0.05 less opaque must be caught.
    let (pass, z) = check(BackendChoice::Cpu, 1024, "0.25");
    assert_disagrees_with_reference((pass, z), "opacity 0.25 for 0.3");
}

#[test]
fn mask_gpu_matches_mitsuba_volpath() {
    assert_agrees_with_reference(check(BackendChoice::Gpu, 256, "0.3"), "GPU");
}

/// `mask_cards.xml` at `opacity` rendered by `direct` on `choice`, compared with Mitsuba's `volpath`
/// at `max_depth` 2: (fraction of pixels passing the z-test, mean-luminance z-score).
fn check_direct(choice: BackendChoice, spp: u32, opacity: &str) -> (f64, f64) {
    let mut scene =
        caustic::load::load_scene(&test_data("mask_cards.xml"), &defines(&[("opacity", opacity)]))
            .expect("loads");
    scene.integrator = scene.integrator.overridden(IntegratorChoice::Direct);
    let film = render_scene(&scene, choice, spp, 7);
    let reference = Film::load_exr(&test_data("mask_cards_direct.exr")).expect("reference loads");
    let c =
        caustic::output::compare::compare(&film, &reference, spp as f64 / REFERENCE_SPP).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!(
        "direct, opacity {opacity}, {choice:?} {spp} spp: luminance ratio {:.4}, z {z:+.2}, pass {pass:.4}",
        c.luminance_ratio
    );
    (pass, z)
}

#[test]
fn direct_cpu_matches_mitsuba_volpath_at_depth_2() {
    assert_agrees_with_reference(check_direct(BackendChoice::Cpu, 4096, "0.3"), "direct, CPU");
    // Negative control: the first card 10% less opaque must be caught.
    let (pass, z) = check_direct(BackendChoice::Cpu, 4096, "0.27");
    assert_disagrees_with_reference((pass, z), "opacity 0.27 for 0.3");
}

#[test]
fn direct_gpu_matches_mitsuba_volpath_at_depth_2() {
    assert_agrees_with_reference(check_direct(BackendChoice::Gpu, 256, "0.3"), "direct, GPU");
}
