//! caustic against Mitsuba 3.9.1 on the Cornell box (`../shared`): per-pixel z-test and mean-luminance
//! z-score, on the CPU and on the GPU backend (lavapipe in CI), plus a negative control showing that
//! the test does catch a 3% error.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::BackendChoice;
use caustic::output::compare::compare;
use caustic::output::film::Film;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 2048.0;

fn check_cbox(choice: BackendChoice, spp: u32, radiance_scale: f32) -> (f64, f64) {
    let mut scene =
        caustic::load::load_scene(&mitsuba_scene("scenes/cbox/cbox.xml"), &[]).expect("cbox loads");
    for shape in &mut scene.shapes {
        if let Some(e) = shape.emission.as_mut() {
            *e = e.map(|c| c * radiance_scale);
        }
    }
    let film = render_scene(&scene, choice, spp, 7);
    let reference = Film::load_exr(&mitsuba_reference("cbox")).expect("reference loads");
    let c = compare(&film, &reference, spp as f64 / REFERENCE_SPP).expect("same size");
    let pass = c.pass_fraction.unwrap();
    let z = c.luminance_z.unwrap();
    println!("cbox {choice:?} {spp} spp (light ×{radiance_scale}): RMSE {:.5}, luminance ratio {:.4}, luminance z {z:+.2}, pass fraction {pass:.4}", c.rmse, c.luminance_ratio);
    (pass, z)
}

#[test]
fn cbox_cpu_matches_mitsuba() {
    assert_agrees_with_reference(check_cbox(BackendChoice::Cpu, 64, 1.0), "cbox on the CPU");
}

#[test]
fn cbox_gpu_matches_mitsuba() {
    assert_agrees_with_reference(check_cbox(BackendChoice::Gpu, 16, 1.0), "cbox on the GPU");
}

/// The comparison must be able to fail: a light 3% too bright is caught.
#[test]
fn comparison_detects_a_three_percent_error() {
    assert_disagrees_with_reference(check_cbox(BackendChoice::Cpu, 64, 1.03), "a 3% brighter light");
}

/// Light tracing and IBPT on the Cornell box (Gaussian filter, so the splats cover 5×5 pixels) against
/// Mitsuba's path-traced reference, over the central 64×64 pixels: per-pixel z-test and the mean
/// luminance ratio (the luminance z-score sums per-pixel variances, which splats correlate, so it is
/// not used for these).
#[test]
fn cbox_ptracer_and_ibpt_match_mitsuba() {
    use caustic::scene::IntegratorChoice::{Ibpt, Ptracer};
    // The last run, a 3% brighter light, must fail the same checks.
    for (choice, radiance_scale) in [(Ptracer, 1.0), (Ibpt, 1.0), (Ptracer, 1.03)] {
        let mut scene =
            caustic::load::load_scene(&mitsuba_scene("scenes/cbox/cbox.xml"), &[]).expect("cbox loads");
        scene.integrator = scene.integrator.overridden(choice);
        for shape in &mut scene.shapes {
            if let Some(e) = shape.emission.as_mut() {
                *e = e.map(|c| c * radiance_scale);
            }
        }
        let window = caustic::scene::Crop { x: 96, y: 96, width: 64, height: 64 };
        let spp = 64;
        let film = render_window(&scene, window, BackendChoice::Cpu, spp, 9);
        let reference = Film::load_exr(&mitsuba_reference("cbox")).expect("reference loads").crop(
            window.x,
            window.y,
            window.width,
            window.height,
        );
        let c = compare(&film, &reference, spp as f64 / REFERENCE_SPP).expect("same size");
        let pass = c.pass_fraction.unwrap();
        println!(
            "cbox {choice:?} {spp} spp (light ×{radiance_scale}): luminance ratio {:.4}, pass fraction {pass:.4}",
            c.luminance_ratio
        );
        let matches = pass >= 0.99 && (c.luminance_ratio - 1.0).abs() < 0.01;
        if radiance_scale == 1.0 {
            assert!(
                matches,
                "{choice:?}: pass fraction {pass:.4}, mean luminance ratio {:.4}",
                c.luminance_ratio
            );
        } else {
            assert!(!matches, "a 3% brighter light went unnoticed (ratio {:.4})", c.luminance_ratio);
        }
    }
}
