//! Masks under light tracing (`ptracer`) and IBPT: light paths pass through `mask_cards.xml`'s two
//! cards (opacity 0.3 and a checkerboard of 0.9 and 0.2) and their camera connections are attenuated
//! by them, so the images must agree with `path`'s (the image z-score from replicas, as in
//! ptracer.rs); a card 0.05 less opaque in the light-traced image is caught; GPU and CPU splat the same;
//! with `hide_emitters` too (connections then pass the emitters; treating the masks as opaque there,
//! as before, gave z −135).
use caustic::backend::BackendChoice;
use caustic::scene::{IntegratorChoice, Scene};
use caustic_tests::replicas::*;
use caustic_tests::*;

fn cards(opacity: &str, integrator: IntegratorChoice) -> Scene {
    let mut scene =
        caustic::load::load_scene(&test_data("mask_cards.xml"), &defines(&[("opacity", opacity)]))
            .expect("loads");
    scene.integrator = scene.integrator.overridden(integrator);
    scene
}

/// (image z-score, worst pixel |z|) of `integrator` at `opacity` against `path` at 0.3.
fn against_path(integrator: IntegratorChoice, opacity: &str) -> (f64, f64) {
    let path = render_scene(&cards("0.3", IntegratorChoice::Path), BackendChoice::Cpu, 4096, 1);
    let light = render_replicated(&cards(opacity, integrator), 8192, 2);
    let (z, worst) = agreement(&light, &path);
    println!(
        "{integrator:?}, opacity {opacity}: mean {:.5} against path's {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
        image_mean(&light.film),
        image_mean(&path)
    );
    (z, worst)
}

#[test]
fn ptracer_and_ibpt_agree_with_path_through_masks() {
    for integrator in [IntegratorChoice::Ptracer, IntegratorChoice::Ibpt] {
        let (z, worst) = against_path(integrator, "0.3");
        // 32×32×3 values: |z| ≤ 5.2 is the Šidák-corrected 0.1% two-sided bound per value.
        assert!(
            z.abs() < 4.5 && worst < 5.2,
            "{integrator:?} and path disagree (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// Negative control: the first card 0.05 less opaque under light tracing is caught (as in mask.rs;
/// at 0.27 the image z-score was +3.76, short of the bound: the mean moves little when a card thins).
#[test]
fn light_tracing_mask_agreement_detects_a_changed_opacity() {
    let (z, worst) = against_path(IntegratorChoice::Ptracer, "0.25");
    assert!(
        z.abs() >= 4.5 || worst >= 5.2,
        "opacity 0.25 for 0.3 went unnoticed (z {z:+.2}, worst {worst:.2})"
    );
}

#[test]
fn masks_gpu_match_cpu_under_light_tracing() {
    for integrator in [IntegratorChoice::Ptracer, IntegratorChoice::Ibpt] {
        let scene = cards("0.3", integrator);
        let cpu = render_scene(&scene, BackendChoice::Cpu, 4, 5);
        let gpu = render_scene(&scene, BackendChoice::Gpu, 4, 5);
        let max_diff = max_abs_difference(&cpu, &gpu);
        let total: f64 = cpu.rgb.iter().flatten().map(|&c| c as f64).sum();
        println!("{integrator:?} GPU vs CPU: max |difference| {max_diff:e}, image sum {total:.4}");
        assert!(total > 0.1, "the image is dark");
        assert!(max_diff < 1e-3, "GPU and CPU differ by {max_diff}");
    }
}

/// With `hide_emitters`, camera rays pass through the light and masks both; light tracing's
/// connections to the camera must too (emitters skipped, masks attenuating), or the cards seen
/// against the hidden light would differ from `path`'s.
#[test]
fn light_tracing_agrees_with_path_through_masks_with_hidden_emitters() {
    let hidden = |integrator| {
        let mut scene = cards("0.3", integrator);
        scene.integrator.hide_emitters = true;
        scene
    };
    let path = render_scene(&hidden(IntegratorChoice::Path), BackendChoice::Cpu, 4096, 1);
    for integrator in [IntegratorChoice::Ptracer, IntegratorChoice::Ibpt] {
        let light = render_replicated(&hidden(integrator), 8192, 2);
        let (z, worst) = agreement(&light, &path);
        println!(
            "{integrator:?}, hidden emitters: mean {:.5} against path's {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            image_mean(&light.film),
            image_mean(&path)
        );
        assert!(
            z.abs() < 4.5 && worst < 5.2,
            "{integrator:?} and path disagree with hidden emitters (z {z:+.2}, worst {worst:.2})"
        );
    }
}
