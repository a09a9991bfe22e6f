//! Mitsuba's `mask` BSDF against Mitsuba 3.9.1: two cards of opacity 0.3 and 0.7 between an area light
//! and a floor (`tests/data/mask_cards.xml`; the reference `mask_cards.exr` is Mitsuba's `volpath`,
//! written by `mask_cards.py`), seen directly and through their shadows, on the CPU and the GPU
//! backend; per-pixel z-test and mean-luminance z-score, with a negative control (opacity 0.25 for
//! 0.3). Integrators other than `path` refuse masks for now.
use caustic::backend::BackendChoice;
use caustic::compare::compare;
use caustic::film::Film;
use caustic_tests::*;
use std::path::PathBuf;

const REFERENCE_SPP: f64 = 16384.0;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data").join(name)
}

fn check(choice: BackendChoice, spp: u32, opacity: &str) -> (f64, f64) {
    let scene =
        caustic::load_scene(&data("mask_cards.xml"), &defines(&[("opacity", opacity)])).expect("loads");
    let film = render_scene(&scene, choice, spp, 5);
    let reference = Film::load_exr(&data("mask_cards.exr")).expect("reference loads");
    let c = compare(&film, &reference, spp as f64 / REFERENCE_SPP).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!(
        "mask cards {choice:?} {spp} spp, opacity {opacity}: RMSE {:.5}, luminance ratio {:.4}, z {z:+.2}, pass {pass:.4}",
        c.rmse, c.luminance_ratio
    );
    (pass, z)
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
    let mut scene = caustic::load_scene(&data("mask_cards.xml"), &[]).expect("loads");
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
