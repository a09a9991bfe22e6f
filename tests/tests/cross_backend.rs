//! The GPU (wgpu; lavapipe in CI) and CPU (rayon) backends run the same kernel: with the same seed they
//! must agree up to float rounding, and with different seeds statistically.
use caustic::backend::BackendChoice;
use caustic::compare::compare;
use caustic_tests::*;

#[test]
fn gpu_and_cpu_agree_on_the_cornell_box() {
    let scene = caustic::load_scene(&mitsuba_scene("scenes/cbox/cbox.xml"), &defines(&[("res", "96")])).expect("cbox loads");
    let cpu = render_scene(&scene, BackendChoice::Cpu, 32, 11);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 32, 11);

    let diffs: Vec<f32> = cpu.rgb.iter().zip(&gpu.rgb).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs())).collect();
    let max = diffs.iter().cloned().fold(0.0f32, f32::max);
    let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let divergent = cpu.rgb.iter().zip(&gpu.rgb).filter(|(a, b)| (0..3).any(|c| (a[c] - b[c]).abs() > 1e-3 * (1.0 + a[c].abs()))).count();
    println!("same seed: max |cpu - gpu| = {max:.3e}, mean = {mean:.3e}, pixels differing by > 1e-3: {divergent} of {}", cpu.rgb.len());
    // Rounding differences can send a few paths different ways; nearly all pixels must be equal.
    assert!(mean < 1e-4, "mean difference {mean:.3e} is more than rounding");
    assert!((divergent as f64) < 0.01 * cpu.rgb.len() as f64, "{divergent} pixels differ");

    // Independent seeds: statistically indistinguishable.
    let gpu2 = render_scene(&scene, BackendChoice::Gpu, 32, 12);
    let c = compare(&cpu, &gpu2, 1.0).expect("same size");
    println!("independent seeds: pass fraction {:.4}, luminance z {:+.2}", c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    assert!(c.pass_fraction.unwrap() >= 0.99);
    assert!(c.luminance_z.unwrap().abs() < 4.0);
}
