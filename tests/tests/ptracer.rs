//! Light tracing (`ptracer`) against path tracing: the two estimate the same image, statistically,
//! on scenes lit by each emitter kind light tracing supports; the GPU and the CPU splat the same sums.
use caustic::backend::BackendChoice;
use caustic::film::Film;
use caustic_tests::*;

/// A diffuse box corner (floor, back wall, a red side wall) with a glossy sphere, lit by `emitter`,
/// seen through a box filter (light tracing splats with the box).
fn corner(integrator: &str, emitter: &str, res: u32) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><integer name="max_depth" value="5"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, -3, 1.6" target="0, 0, 0.5" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="90"/><translate y="1.5" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate y="1" angle="90"/><translate x="-1.5" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.2"/></bsdf></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.4"/><point name="center" x="0.3" y="0.2" z="0.4"/>
        <bsdf type="roughplastic"><float name="alpha" value="0.2"/><rgb name="diffuse_reflectance" value="0.3, 0.4, 0.6"/></bsdf></shape>
    {emitter}
</scene>"#
    )
}

const EMITTERS: [(&str, &str); 4] = [
    (
        "area",
        r#"<shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1.9"/></transform>
            <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>"#,
    ),
    (
        "sphere",
        r#"<shape type="sphere"><float name="radius" value="0.15"/><point name="center" x="-0.5" y="-0.3" z="1.4"/>
            <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>"#,
    ),
    (
        "point",
        r#"<emitter type="point"><point name="position" value="0.4, -0.6, 1.5"/><rgb name="intensity" value="4"/></emitter>"#,
    ),
    (
        "spot",
        r#"<emitter type="spot"><transform name="to_world"><lookat origin="-0.6, -1, 1.8" target="0.2, 0.3, 0"/></transform>
            <rgb name="intensity" value="8"/><float name="cutoff_angle" value="35"/></emitter>"#,
    ),
];

/// Pixel-wise and whole-image z-scores of `a - b` with each image's variance pooled over neighbours;
/// returns (image mean z, worst pixel |z|).
fn agreement(a: &Film, b: &Film) -> (f64, f64) {
    let pooled =
        |f: &Film| caustic::compare::pooled_variance(f.variance.as_ref().unwrap(), f.width, f.height);
    let (va, vb) = (pooled(a), pooled(b));
    let (mut diff, mut var, mut worst) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..a.rgb.len() {
        for c in 0..3 {
            let d = a.rgb[i][c] as f64 - b.rgb[i][c] as f64;
            let v = va[i][c] as f64 + vb[i][c] as f64;
            diff += d;
            var += v;
            worst = worst.max(d.abs() / (v.sqrt() + 1e-6));
        }
    }
    (diff / var.sqrt(), worst)
}

#[test]
fn ptracer_and_path_agree_on_every_supported_emitter() {
    for (name, emitter) in EMITTERS {
        let path = render_scene(
            &load_xml(&corner("path", emitter, 24), &format!("{name}-path")),
            BackendChoice::Cpu,
            512,
            1,
        );
        let light = render_scene(
            &load_xml(&corner("ptracer", emitter, 24), &format!("{name}-pt")),
            BackendChoice::Cpu,
            512,
            2,
        );
        let (z, worst) = agreement(&light, &path);
        let mean = |f: &Film| f.rgb.iter().flatten().map(|&c| c as f64).sum::<f64>() / f.rgb.len() as f64;
        println!(
            "{name}: ptracer mean {:.5}, path mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            mean(&light),
            mean(&path)
        );
        assert!(mean(&path) > 1e-3, "{name}: the scene is dark");
        // 24×24×3 values: |z| ≤ 5.0 is the Šidák-corrected 0.1% two-sided bound per value.
        assert!(
            z.abs() < 4.0 && worst < 5.0,
            "{name}: ptracer and path disagree (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// A 10% brighter emitter in the light-traced image is detected (the test above can fail).
#[test]
fn ptracer_agreement_detects_a_brighter_light() {
    let (_, emitter) = EMITTERS[0];
    let brighter = emitter.replace(r#"value="12""#, r#"value="13.2""#);
    let path = render_scene(&load_xml(&corner("path", emitter, 24), "neg-path"), BackendChoice::Cpu, 512, 1);
    let light =
        render_scene(&load_xml(&corner("ptracer", &brighter, 24), "neg-pt"), BackendChoice::Cpu, 512, 2);
    let (z, _) = agreement(&light, &path);
    println!("10% brighter light: image z {z:+.2}");
    assert!(z > 6.0, "a 10% brighter light went unnoticed (z {z:+.2})");
}

/// The GPU splats the same fixed-point sums as the CPU: same seed, same image to float rounding of
/// the path arithmetic (GPU compilers may fuse differently, which moves a few paths).
#[test]
fn ptracer_gpu_matches_cpu() {
    let scene = load_xml(&corner("ptracer", EMITTERS[0].1, 12), "gpu-cpu");
    let cpu = render_scene(&scene, BackendChoice::Cpu, 4, 5);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 4, 5);
    let (mut max_diff, mut total) = (0.0f32, 0.0f64);
    for (a, b) in cpu.rgb.iter().zip(&gpu.rgb) {
        for c in 0..3 {
            max_diff = max_diff.max((a[c] - b[c]).abs());
            total += a[c] as f64;
        }
    }
    println!("ptracer GPU vs CPU: max |difference| {max_diff:e}, image sum {total:.4}");
    assert!(total > 0.1, "the light-traced image is dark");
    assert!(max_diff < 1e-3, "GPU and CPU light tracing differ by {max_diff}");
}
