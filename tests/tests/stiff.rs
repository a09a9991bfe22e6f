//! Stiff and extreme scenes (issue 10, section 2): whole scenes at the edges of float precision and of
//! light transport, each judged by the statistic its physics fixes (an image equal to a reference, an
//! exact value, a bound), and each required to produce no NaN/Inf sample (`film.invalid_samples`).
//! The measured figures are tabled in BENCHMARKS.md ("Stiff and extreme cases").
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::{Geometry, Scene};
use caustic_tests::replicas::image_mean;
use caustic_tests::*;
use glam::Vec3;

/// A small closed-on-five-sides Cornell-like box (2 × 2 × 2, open towards the camera) with a glossy
/// sphere, a diffuse cube corner of walls and a rectangle lamp under the ceiling; `emitter` replaces
/// the lamp when given. Everything is a rectangle, a sphere or a triangle, so the whole scene can be
/// scaled and moved by `transformed`.
fn cornell(res: u32, lamp_radiance: &str, max_depth: i32) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="{max_depth}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, -3.4, 1" target="0, 0, 1" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="180"/><translate z="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="1" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.15, 0.15"/></bsdf></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.15, 0.7, 0.15"/></bsdf></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.35"/><point name="center" x="0.35" y="0.25" z="0.35"/>
        <bsdf type="roughplastic"><float name="alpha" value="0.15"/><rgb name="diffuse_reflectance" value="0.3, 0.4, 0.6"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1.98"/></transform>
        <emitter type="area"><rgb name="radiance" value="{lamp_radiance}"/></emitter></shape>
</scene>"#
    )
}

/// `scene` with every point p moved to `scale · p + offset` (shapes, the camera and its clip range).
/// Radiance is invariant under this map, so the image must not change.
fn transformed(scene: &Scene, scale: f32, offset: Vec3) -> Scene {
    let mut out = scene.clone();
    let map = |p: Vec3| p * scale + offset;
    for shape in &mut out.shapes {
        match &mut shape.geometry {
            Geometry::Triangles { triangles, .. } => {
                for t in triangles.iter_mut() {
                    *t = t.map(map);
                }
            }
            Geometry::Sphere { center, radius, .. } => {
                *center = map(*center);
                *radius *= scale;
            }
            Geometry::Disk { center, u, v } => {
                *center = map(*center);
                *u *= scale;
                *v *= scale;
            }
        }
    }
    let s = &mut out.sensor;
    s.to_world.w_axis = map(s.to_world.w_axis.truncate()).extend(1.0);
    s.near_clip *= scale;
    s.far_clip *= scale;
    out
}

/// Two independent renders compared: the whole image's z-score (means of all values) and the worst
/// per-value |z| (each film's variance pooled over neighbours, as `compare` pools it).
fn z_scores(a: &Film, b: &Film) -> (f64, f64) {
    let pooled =
        |f: &Film| caustic::output::compare::pooled_variance(f.variance.as_ref().unwrap(), f.width, f.height);
    let (va, vb) = (pooled(a), pooled(b));
    let (mut worst, mut diff, mut var) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..a.rgb.len() {
        for c in 0..3 {
            let d = a.rgb[i][c] as f64 - b.rgb[i][c] as f64;
            let v = va[i][c] + vb[i][c];
            diff += d;
            var += a.variance.as_ref().unwrap()[i][c] + b.variance.as_ref().unwrap()[i][c];
            worst = worst.max(d.abs() / (v.sqrt() + 1e-7 * b.rgb[i][c].abs() as f64 + 1e-30));
        }
    }
    (diff / var.sqrt().max(1e-30), worst)
}

/// Fails on any NaN/Inf sample or non-finite value (pixel or variance) in `film`.
fn assert_clean(film: &Film, what: &str) {
    assert_eq!(
        film.invalid_samples, 0,
        "{what}: {} invalid samples (NaN/Inf or cut short)",
        film.invalid_samples
    );
    assert!(film.rgb.iter().flatten().all(|c| c.is_finite() && *c >= 0.0), "{what}: a bad pixel");
    assert!(
        film.variance.as_ref().unwrap().iter().flatten().all(|v| v.is_finite()),
        "{what}: a non-finite variance"
    );
}

const BACKENDS: [BackendChoice; 2] = [BackendChoice::Cpu, BackendChoice::Gpu];

/// Renders the box scaled by `scale` and moved by `offset` on each case and backend, against the unit
/// box on the CPU; panics listing every case whose image changed (|image z| ≥ 4.5 or a value's
/// |z| ≥ 5: the Šidák-corrected 0.1% two-sided bound per value of 24×24×3).
fn assert_invariant(cases: &[(f32, f32)]) {
    let base = load_xml(&cornell(24, "15", 5), "cornell-unit");
    let reference = render_scene(&base, BackendChoice::Cpu, 256, 1);
    assert_clean(&reference, "unit box");
    assert!(image_mean(&reference) > 0.05, "the box is dark");
    let mut failures = Vec::new();
    for choice in BACKENDS {
        for (i, &(scale, offset)) in cases.iter().enumerate() {
            let scene = transformed(&base, scale, Vec3::splat(offset));
            let film = render_scene(&scene, choice, 256, 10 + i as u32);
            let (z, worst) = z_scores(&film, &reference);
            println!(
                "{choice:?} scale {scale:e} offset {offset:e}: mean {:.5} (unit {:.5}), image z {z:+.2}, worst |z| {worst:.2}, invalid {}",
                image_mean(&film),
                image_mean(&reference),
                film.invalid_samples
            );
            assert_clean(&film, &format!("{choice:?} scale {scale:e} offset {offset:e}"));
            if !(z.abs() < 4.5 && worst < 5.0) {
                failures.push(format!(
                    "{choice:?} scale {scale:e} offset {offset:e} (z {z:+.2}, worst {worst:.2})"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "the image changed: {failures:?}");
}

/// Scale and position invariance where it holds: the 2-unit box scaled by 1e-4 … 1e4 and moved by up
/// to 1e3 renders the image of the unit box, on both backends. Before the ray offset lost its
/// absolute term (`kernel/src/shape/mod.rs`), the box scaled by 1e-3 or 1e-4 had single pixels off
/// by |z| 5.5 and 29 (and before NEE's shadow rays ended at the light point, means 17–22% dark).
#[test]
fn scale_and_position_invariance() {
    assert_invariant(&[
        (1e-4, 0.0),
        (1e-3, 0.0),
        (1e-2, 0.0),
        (1e2, 0.0),
        (1e4, 0.0),
        (1.0, 1e2),
        (1.0, 1e3),
        (1e4, 1e5),
    ]);
    for (scale, offset) in [(1e-4, 0.0), (1.0, 1e3), (1e4, 1e5)] {
        let scene =
            transformed(&load_xml(&cornell(24, "15", 5), "cornell-quiet"), scale, Vec3::splat(offset));
        assert_eq!(caustic::scene::precision::warning(&scene), None, "scale {scale:e} offset {offset:e}");
    }
}

/// Where invariance ends: the box moved by 1e4 or 1e5, or scaled by 1e-2 and moved by 1e3, puts the
/// ray offset (`RAY_EPSILON · |p|`: 0.89 at 1e4) past the lamp's 0.02 gap under the ceiling and near
/// the sphere's radius (measured on the CPU: worst |z| 30, 16 and 14). f32 itself ends there too for
/// the gap at 1e5 (an ulp is 0.0078). The loader warns, naming the ratio of the smallest shape to the
/// scene's extent; this checks that it does for each of them.
#[test]
fn loading_warns_where_float_precision_ends() {
    for (scale, offset) in [(1.0f32, 1e4f32), (1.0, 1e5), (1e-2, 1e3)] {
        let scene = transformed(&load_xml(&cornell(24, "15", 5), "cornell-far"), scale, Vec3::splat(offset));
        let warning = caustic::scene::precision::warning(&scene);
        println!("scale {scale:e} offset {offset:e}: {warning:?}");
        let warning = warning.unwrap_or_else(|| panic!("no warning at scale {scale:e} offset {offset:e}"));
        assert!(warning.contains("ratio"), "{warning}");
    }
}

/// A sphere light of radius 1e-5 a thousand units above a diffuse floor of albedo ρ: a sphere of
/// radiance L seen fully above the horizon gives the irradiance π L (r/D)² cos θ, so the floor under
/// it has the radiance ρ L r² h / D³ = ρ L r²/h² to 2e-6 over the visible patch (D ≈ h = 1e3).
#[test]
fn tiny_distant_sphere_light() {
    let (rho, radius, height, radiance) = (0.5f64, 1e-5f64, 1e3f64, 1e16f64);
    let scene = floor_under_sphere_light(rho, radius, height, radiance, "tiny-light");
    assert_floor_radiance(&scene, rho * radiance * radius * radius / (height * height), "tiny light");
}

/// A sun: a sphere light of the sun's radius (7e8) at its distance (1.5e11) straight above a diffuse
/// floor of albedo ρ. A sphere of radiance L whose centre is D along the normal gives the irradiance
/// π L (r/D)² exactly, so the floor has the radiance ρ L (r/D)² (to 1e-11 over the visible patch).
/// The sphere's cone is 0.27° across: 1 − cos α = 1.1e-5, where an f32 cosine keeps three digits.
#[test]
fn sun_sized_sphere_light() {
    let (rho, radius, distance, radiance) = (0.5f64, 7e8f64, 1.5e11f64, 4e4f64);
    let scene = floor_under_sphere_light(rho, radius, distance, radiance, "sun");
    assert_eq!(
        caustic::scene::precision::warning(&scene),
        None,
        "the sun is well resolved at its own distance"
    );
    assert_floor_radiance(&scene, rho * radiance * (radius / distance).powi(2), "sun");
}

/// A diffuse floor of albedo `rho` seen from 3 above, under a sphere light of `radius` and
/// `radiance` centred `distance` straight above it.
fn floor_under_sphere_light(rho: f64, radius: f64, distance: f64, radiance: f64, tag: &str) -> Scene {
    let xml = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="-1"/></integrator>
    <sensor type="perspective"><float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rho}"/></bsdf></shape>
    <shape type="sphere"><float name="radius" value="{radius:e}"/><point name="center" x="0" y="0" z="{distance:e}"/>
        <emitter type="area"><rgb name="radiance" value="{radiance:e}"/></emitter></shape>
</scene>"#
    );
    load_xml(&xml, tag)
}

/// On both backends the image's mean is `expected` within four standard errors (and 1e-3 relative),
/// with no invalid sample.
fn assert_floor_radiance(scene: &Scene, expected: f64, label: &str) {
    for choice in BACKENDS {
        let film = render_scene(scene, choice, 64, 3);
        let mean = image_mean(&film);
        let n = (3 * film.rgb.len()) as f64;
        let se = film.variance.as_ref().unwrap().iter().flatten().copied().sum::<f64>().sqrt() / n;
        println!(
            "{choice:?}: {label}: mean {mean:.6} ± {se:.2e}, expected {expected:.6} (relative {:+.2e}), invalid {}",
            mean / expected - 1.0,
            film.invalid_samples
        );
        assert_clean(&film, &format!("{choice:?} {label}"));
        assert!(
            (mean - expected).abs() < 4.0 * se + 1e-3 * expected,
            "{choice:?}: {label}: mean {mean} ± {se}, expected {expected}"
        );
    }
}

/// Radiance 1e30: each sample's square (1e60) overflows f32, and the variance of the image must stay
/// finite and right. Same seed as a lamp of radiance 15: the same paths, so the image scales by
/// 1e30/15 and its variance by (1e30/15)², both exactly up to rounding. Before the kernel scaled its
/// squares (`FrameParams::square_scale_log2`) and the film kept its variance in f64, every variance
/// was +Inf (the image itself was right, 2.9e-7 relative).
#[test]
fn radiance_1e30_keeps_a_finite_variance() {
    let unit = render_scene(&load_xml(&cornell(16, "15", 5), "lamp-15"), BackendChoice::Cpu, 64, 4);
    let ratio = 1e30 / 15.0;
    let worst_of = |a: &[[f64; 3]], b: &[[f64; 3]], scale: f64, floor: f64| {
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .map(|(&a, &b)| (a / scale - b).abs() / b.max(floor))
            .fold(0.0, f64::max)
    };
    let wide = |f: &Film| -> Vec<[f64; 3]> { f.rgb.iter().map(|p| p.map(f64::from)).collect() };
    for choice in BACKENDS {
        let film = render_scene(&load_xml(&cornell(16, "1e30", 5), "lamp-1e30"), choice, 64, 4);
        let worst = worst_of(&wide(&film), &wide(&unit), ratio, 1e-3);
        let (v, unit_v) = (film.variance.as_ref().unwrap(), unit.variance.as_ref().unwrap());
        let worst_variance = worst_of(v, unit_v, ratio * ratio, 1e-8);
        println!(
            "{choice:?}: radiance 1e30: mean {:e}, largest variance {:e}, worst relative difference from the scaled radiance-15 image {worst:.2e}, variance {worst_variance:.2e}, invalid {}",
            image_mean(&film),
            v.iter().flatten().fold(0.0f64, |m, &x| m.max(x)),
            film.invalid_samples
        );
        assert_clean(&film, &format!("{choice:?} radiance 1e30"));
        assert!(worst < 1e-3, "{choice:?}: the 1e30 image is not the scaled radiance-15 image ({worst:e})");
        assert!(
            worst_variance < 1e-3,
            "{choice:?}: the 1e30 variance is not the scaled radiance-15 variance ({worst_variance:e})"
        );
    }
}

/// Two parallel mirrors (reflectance 1) facing each other with a sphere lamp of `lamp` and a diffuse
/// floor between them, `max_depth` -1: only Russian roulette ends the paths.
fn facing_mirrors(lamp: f32) -> Scene {
    let xml = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="-1"/><integer name="rr_depth" value="5"/></integrator>
    <sensor type="perspective"><float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0.1, -0.9, 0.3" target="0.15, 1, 0.2" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="20"/><rotate x="1" angle="90"/><translate y="1"/></transform>
        <bsdf type="conductor"><string name="material" value="none"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="20"/><rotate x="1" angle="-90"/><translate y="-1"/></transform>
        <bsdf type="conductor"><string name="material" value="none"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="20"/><translate z="-1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8"/></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.2"/><point name="center" x="0" y="0" z="0.5"/>
        <emitter type="area"><rgb name="radiance" value="{lamp}"/></emitter></shape>
</scene>"#
    );
    load_xml(&xml, "mirrors")
}

/// The facing mirrors: every value finite, no pixel brighter than the lamp (albedos ≤ 1 bound the
/// radiance by the brightest emitter), and the two backends agree.
#[test]
fn facing_mirrors_with_russian_roulette() {
    let lamp = 4.0f32;
    let scene = facing_mirrors(lamp);
    let films: Vec<Film> = BACKENDS.iter().map(|&c| render_scene(&scene, c, 256, 5)).collect();
    for (choice, film) in BACKENDS.iter().zip(&films) {
        let var = film.variance.as_ref().unwrap();
        let brightest = film
            .rgb
            .iter()
            .zip(var)
            .map(|(p, v)| (0..3).map(|c| p[c] as f64 - 5.0 * v[c].sqrt()).fold(f64::MIN, f64::max))
            .fold(f64::MIN, f64::max);
        println!(
            "{choice:?}: mirrors: mean {:.4}, brightest pixel less 5σ {brightest:.4} (lamp {lamp}), invalid {}",
            image_mean(film),
            film.invalid_samples
        );
        assert_clean(film, &format!("{choice:?} mirrors"));
        assert!(image_mean(film) > 0.05, "{choice:?}: the mirrors are dark");
        assert!(brightest <= lamp as f64, "{choice:?}: a pixel is brighter than the lamp ({brightest})");
    }
    let (z, worst) = z_scores(&films[1], &films[0]);
    println!("mirrors: GPU vs CPU: image z {z:+.2}, worst |z| {worst:.2}");
    assert!(z.abs() < 4.5 && worst < 5.0, "mirrors: GPU and CPU disagree (z {z:+.2}, worst {worst:.2})");
}

/// One pass of 256 samples per pixel through the facing mirrors, handed to each backend whole (as
/// long passes on a fast GPU hand them): the GPU's image equals the CPU's and no sample is lost.
/// Regression: llvmpipe ends an invocation's loops after 65535 iterations in all, and such a pass lost
/// up to half of some pixels' samples (mean 1.4% low, image z −5.2), unreported; the GPU backend now
/// splits passes on software adapters, and the kernel counts samples cut short as invalid.
#[test]
fn facing_mirrors_in_one_long_pass() {
    let buffers = caustic::prepare::buffers::build(&facing_mirrors(4.0)).expect("scene builds");
    let films: Vec<Film> = BACKENDS
        .iter()
        .map(|&choice| {
            let mut backend = caustic::backend::create(choice, &buffers).expect("backend starts");
            let mut params = buffers.params;
            (params.seed, params.sample_base, params.sample_count, params.spp_total) = (5, 0, 256, 256);
            backend.pass(&params).expect("the pass runs");
            let accum = backend.read_accum().expect("the sums read back");
            let film = Film::from_accum(params.width, params.height, &accum);
            println!("{choice:?}: one pass: mean {:.4}, invalid {}", image_mean(&film), film.invalid_samples);
            assert_clean(&film, &format!("{choice:?} mirrors in one pass"));
            film
        })
        .collect();
    let (z, worst) = z_scores(&films[1], &films[0]);
    println!("mirrors in one pass: GPU vs CPU: image z {z:+.2}, worst |z| {worst:.2}");
    assert!(
        z.abs() < 4.5 && worst < 5.0,
        "mirrors in one pass: GPU and CPU disagree (z {z:+.2}, worst {worst:.2})"
    );
}

/// A sphere of `bsdf` in a unit constant environment (a furnace): the image mean over a frame the
/// sphere fills, with its standard error.
fn furnace_mean(bsdf: &str, res: u32, spp: u32, choice: BackendChoice, tag: &str) -> (f64, f64, Film) {
    let xml = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="-1"/></integrator>
    <sensor type="perspective"><float name="fov" value="25"/>
        <transform name="to_world"><lookat origin="0, -4, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
    </sensor>
    <shape type="sphere">{bsdf}</shape>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>"#
    );
    let film = render_scene(&load_xml(&xml, tag), choice, spp, 6);
    let n = film.rgb.len() as f64;
    let mean = film.rgb.iter().map(|p| p[1] as f64).sum::<f64>() / n;
    let se = film.variance.as_ref().unwrap().iter().map(|v| v[1]).sum::<f64>().sqrt() / n;
    (mean, se, film)
}

/// GGX at alpha 1e-4 (a mirror: the furnace is exactly 1) and 1 (single scattering loses energy: below
/// 1, never above), as a conductor of reflectance 1 and as glass. At alpha 1 the furnace is Mitsuba
/// 3.9.1's (scalar_rgb, this scene, 8 seeds × 256 spp, green channel's image mean ± standard error):
/// conductor 0.40689 ± 0.00028, dielectric 0.35658 ± 0.00045.
#[test]
fn ggx_alpha_extremes_in_a_furnace() {
    for choice in BACKENDS {
        for (name, model, mitsuba) in [
            (
                "conductor",
                r#"type="roughconductor"><string name="material" value="none"/>"#,
                (0.40689, 0.00028),
            ),
            (
                "dielectric",
                r#"type="roughdielectric"><float name="int_ior" value="1.5"/>"#,
                (0.35658, 0.00045),
            ),
        ] {
            for alpha in ["1e-4", "1"] {
                let bsdf = format!(
                    r#"<bsdf {model}<string name="distribution" value="ggx"/><float name="alpha" value="{alpha}"/></bsdf>"#
                );
                let (mean, se, film) = furnace_mean(&bsdf, 16, 128, choice, &format!("ggx-{name}-{alpha}"));
                println!(
                    "{choice:?}: GGX {name} alpha {alpha}: furnace {mean:.5} ± {se:.5}, invalid {}",
                    film.invalid_samples
                );
                assert_clean(&film, &format!("{choice:?} GGX {name} alpha {alpha}"));
                assert!(
                    mean <= 1.0 + 4.0 * se + 1e-4,
                    "{choice:?}: GGX {name} alpha {alpha} creates energy: {mean} ± {se}"
                );
                if alpha == "1e-4" {
                    assert!(
                        (mean - 1.0).abs() < 4.0 * se + 1e-3,
                        "{choice:?}: GGX {name} alpha 1e-4: {mean} ± {se}, not 1"
                    );
                } else {
                    let (m, m_se) = mitsuba;
                    assert!(
                        (mean - m).abs() < 4.0 * (se * se + m_se * m_se).sqrt(),
                        "{choice:?}: GGX {name} alpha 1: {mean} ± {se}, Mitsuba {m} ± {m_se}"
                    );
                }
            }
        }
    }
}

/// A million samples per pixel of a white furnace (a Lambertian sphere of albedo 1 in a unit
/// environment: every pixel's expected value is 1) on a 2×2 film: f32 sums of a million samples
/// must keep the mean at 1 to 1e-5 plus the statistical error.
fn million_sample_furnace(choice: BackendChoice) {
    let spp = 1_000_000;
    let start = std::time::Instant::now();
    let bsdf = r#"<bsdf type="diffuse"><rgb name="reflectance" value="1"/></bsdf>"#;
    let (mean, se, film) = furnace_mean(bsdf, 2, spp, choice, "million");
    println!(
        "{choice:?}: {spp} spp furnace: mean {mean:.7} ± {se:.2e} (|mean − 1| = {:.2e}), pixels {:?}, {:.1} s",
        (mean - 1.0).abs(),
        film.rgb,
        start.elapsed().as_secs_f64()
    );
    assert_clean(&film, &format!("{choice:?} million-sample furnace"));
    assert!((mean - 1.0).abs() < 4.0 * se + 1e-5, "{choice:?}: furnace {mean} ± {se} after {spp} spp");
}

/// A million samples per pixel that are all 0.1 (the camera sees a constant environment of radiance
/// 0.1 and nothing else): no statistics at all, so the mean must be 0.1 to the accumulator's own
/// rounding, here required to be 1e-5 relative. With f32 sums alone: 0.10000376 on the CPU,
/// 0.10000375 on lavapipe (3.8e-5 relative: each pass of 256 samples added 25.6 to an f32 sum near
/// 1e5, whose ulp is 0.0078, and the rounding had the same sign pass after pass); the host now folds
/// the sums into f64 every `accumulation::FOLD_SAMPLES` samples.
fn million_constant_samples(choice: BackendChoice) {
    let xml = r#"<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="20"/>
        <transform name="to_world"><lookat origin="0, 0, 0" target="0, 1, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="2"/><integer name="height" value="2"/><rfilter type="box"/></film>
    </sensor>
    <shape type="sphere"><float name="radius" value="0.1"/><point name="center" x="0" y="-5" z="0"/></shape>
    <emitter type="constant"><rgb name="radiance" value="0.1"/></emitter>
</scene>"#;
    let film = render_scene(&load_xml(xml, "constant-million"), choice, 1_000_000, 2);
    let worst =
        film.rgb.iter().flatten().map(|&c| (c as f64 / 0.1f32 as f64 - 1.0).abs()).fold(0.0, f64::max);
    println!("{choice:?}: 1e6 samples of 0.1: pixels {:?}, worst relative error {worst:.2e}", film.rgb);
    assert_clean(&film, &format!("{choice:?} constant samples"));
    assert!(
        worst < 1e-5,
        "{choice:?}: a million samples of 0.1 average to {:?} (relative error {worst:e})",
        film.rgb
    );
}

#[test]
fn million_constant_samples_cpu() {
    million_constant_samples(BackendChoice::Cpu);
}

#[test]
fn million_constant_samples_gpu() {
    million_constant_samples(BackendChoice::Gpu);
}

#[test]
fn million_sample_furnace_cpu() {
    million_sample_furnace(BackendChoice::Cpu);
}

#[test]
fn million_sample_furnace_gpu() {
    million_sample_furnace(BackendChoice::Gpu);
}

/// Writes an OBJ of `vertices` and triangles `faces` (0-based) to a temporary folder; returns its path.
fn write_obj(tag: &str, vertices: &[Vec3], faces: &[[usize; 3]]) -> std::path::PathBuf {
    use std::fmt::Write;
    let dir = std::env::temp_dir().join(format!("caustic-stiff-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let mut text = String::new();
    for v in vertices {
        writeln!(text, "v {} {} {}", v.x, v.y, v.z).unwrap();
    }
    for f in faces {
        writeln!(text, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1).unwrap();
    }
    let path = dir.join("mesh.obj");
    std::fs::write(&path, text).expect("OBJ written");
    path
}

/// An icosphere of radius 1: the icosahedron with each triangle split in four `levels` times, the new
/// vertices shared between neighbours (so the mesh is closed) and pushed onto the sphere.
fn icosphere(levels: u32) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut midpoints = std::collections::HashMap::new();
        let mut mid = |a: usize, b: usize, v: &mut Vec<Vec3>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a] + v[b]) * 0.5).normalize());
                v.len() - 1
            })
        };
        f = f
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (mid(a, b, &mut v), mid(b, c, &mut v), mid(c, a, &mut v));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    (v, f)
}

/// A closed icosphere mesh (5120 triangles, 2562 shared vertices) around a sphere lamp, seen from
/// outside: camera rays, shadow rays towards the lamp and bounced rays all meet the mesh first, so
/// any light in the image leaked through a crack between triangles. 32×32 pixels × 1024 spp, over
/// a million camera rays on the mesh (and as many shadow rays): a leak rate of 1e-6 would show.
/// Flat shading (`face_normals`): with the smooth vertex normals Mitsuba's OBJ loading computes, a
/// BSDF sample below the facet (within the interpolated normal's hemisphere) goes in through the
/// mesh (not compared with Mitsuba); measured, 120 of the 1024 pixels lit at `max_depth` 3 (none at 1 or 2).
#[test]
fn closed_mesh_leaks_no_light() {
    let (v, f) = icosphere(4);
    for offset in [0.0f32, 100.0] {
        let moved: Vec<Vec3> = v.iter().map(|&p| p + Vec3::splat(offset)).collect();
        let obj = write_obj(&format!("ico-{offset}"), &moved, &f);
        let xml = format!(
            r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective"><float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="{o}, {back}, {o}" target="{o}, {o}, {o}" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/></film>
    </sensor>
    <shape type="obj"><string name="filename" value="{}"/><boolean name="face_normals" value="true"/>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.6"/><point name="center" x="{o}" y="{o}" z="{o}"/>
        <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
</scene>"#,
            obj.display(),
            o = offset,
            back = offset - 3.2,
        );
        let scene = load_xml(&xml, &format!("ico-{offset}"));
        std::fs::remove_dir_all(obj.parent().unwrap()).ok();
        for choice in BACKENDS {
            let spp = 1024;
            let film = render_scene(&scene, choice, spp, 7);
            let lit = film.rgb.iter().filter(|p| p.iter().any(|&c| c != 0.0)).count();
            // A leaking sample adds at least radiance × (albedo 0.5)² / spp to its pixel's mean.
            let leaked_energy = film.rgb.iter().map(|p| p[1] as f64).sum::<f64>() * spp as f64;
            println!(
                "{choice:?}: closed mesh at offset {offset}: {lit} lit pixels, {:.3e} rays, leaked energy × spp {leaked_energy:.3e}, invalid {}",
                (film.rgb.len() * spp as usize) as f64,
                film.invalid_samples
            );
            assert_clean(&film, &format!("{choice:?} closed mesh"));
            assert_eq!(lit, 0, "{choice:?}: light leaks out of the closed mesh at offset {offset}");
        }
    }
}

/// The box's floor triangulated into 2 × 16384 needles (1.2e-4 wide, 2 long: aspect 1.6e4) and a fan
/// of slivers, with zero-area triangles mixed in, renders the image of the plain rectangle.
#[test]
fn sliver_and_needle_triangles() {
    let strips = 16384;
    let mut v = Vec::new();
    let mut f = Vec::new();
    for i in 0..=strips {
        let x = -1.0 + 2.0 * i as f32 / strips as f32;
        v.push(Vec3::new(x, -1.0, 0.0));
        v.push(Vec3::new(x, 1.0, 0.0));
    }
    for i in 0..strips {
        let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
        f.push([a, b, c]);
        f.push([a, c, d]);
        // Zero-area: three points on one edge.
        f.push([a, d, d]);
    }
    let obj = write_obj("needles", &v, &f);
    let floor = r#"<shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>"#;
    let needles = format!(
        r#"<shape type="obj"><string name="filename" value="{}"/><bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>"#,
        obj.display()
    );
    let plain = cornell(24, "15", 5);
    assert!(plain.contains(floor));
    let scene = load_xml(&plain.replace(floor, &needles), "needles");
    std::fs::remove_dir_all(obj.parent().unwrap()).ok();
    let reference = render_scene(&load_xml(&plain, "needles-ref"), BackendChoice::Cpu, 256, 8);
    for choice in BACKENDS {
        let film = render_scene(&scene, choice, 256, 9);
        let (z, worst) = z_scores(&film, &reference);
        println!(
            "{choice:?}: needle floor vs rectangle: image z {z:+.2}, worst |z| {worst:.2}, invalid {}",
            film.invalid_samples
        );
        assert_clean(&film, &format!("{choice:?} needles"));
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{choice:?}: the needle floor differs (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// The box with its floor as one mesh of `triangles` (a grid of 2 triangles per cell over the
/// floor's square), built in memory.
fn box_with_meshed_floor(triangles: usize) -> Scene {
    let mut scene = load_xml(&cornell(16, "15", 5), "mesh-floor");
    let cells = ((triangles / 2) as f64).sqrt().round() as usize;
    let at = |i: usize| -1.0 + 2.0 * i as f32 / cells as f32;
    let mut grid = Vec::with_capacity(2 * cells * cells);
    for j in 0..cells {
        for i in 0..cells {
            let (a, b) = (Vec3::new(at(i), at(j), 0.0), Vec3::new(at(i + 1), at(j), 0.0));
            let (c, d) = (Vec3::new(at(i + 1), at(j + 1), 0.0), Vec3::new(at(i), at(j + 1), 0.0));
            grid.push([a, b, c]);
            grid.push([a, c, d]);
        }
    }
    let floor = &mut scene.shapes[0];
    assert!(!matches!(floor.geometry, Geometry::Sphere { .. }), "the first shape is the floor");
    floor.geometry =
        Geometry::Triangles { triangles: grid, normals: None, uvs: None, attributes: Vec::new() };
    scene
}

/// A floor of `triangles` triangles renders the plain box's image on the CPU; on the GPU it renders
/// the same or is refused naming the device limit it exceeds.
fn large_mesh(triangles: usize) {
    let start = std::time::Instant::now();
    let scene = box_with_meshed_floor(triangles);
    let buffers = caustic::prepare::buffers::build(&scene).expect("the mesh builds");
    println!("{} triangles: built in {:.1} s", buffers.prims.len(), start.elapsed().as_secs_f64());
    let reference =
        render_scene(&load_xml(&cornell(16, "15", 5), "mesh-floor-ref"), BackendChoice::Cpu, 64, 12);
    for choice in BACKENDS {
        let backend = caustic::backend::create(choice, &buffers);
        if let Err(e) = &backend {
            let message = format!("{e:#}");
            println!("{choice:?}: {triangles} triangles refused: {message}");
            assert!(
                choice == BackendChoice::Gpu && message.contains("max_") && message.contains("bytes"),
                "{choice:?}: {triangles} triangles: {message}"
            );
            continue;
        }
        let start = std::time::Instant::now();
        let film = caustic_tests::render_buffers(&buffers, choice, 64, 13);
        let (z, worst) = z_scores(&film, &reference);
        println!(
            "{choice:?}: {triangles}-triangle floor vs rectangle: image z {z:+.2}, worst |z| {worst:.2}, {:.1} s",
            start.elapsed().as_secs_f64()
        );
        assert_clean(&film, &format!("{choice:?} {triangles} triangles"));
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{choice:?}: the meshed floor differs (z {z:+.2}, worst {worst:.2})"
        );
    }
}

#[test]
fn a_million_triangle_mesh() {
    large_mesh(1_000_000);
}

/// Measured on the 2-core machine: BVH built in 21 s, rendered on the CPU in 6 s (z +0.59), refused by
/// lavapipe (its BVH nodes need 305 MiB against a 128 MiB binding limit), 7.3 GB resident at the peak.
#[test]
#[ignore = "7.3 GB resident at its peak: too much beside CI's parallel tests; a_million_triangle_mesh runs"]
fn ten_million_triangle_mesh() {
    large_mesh(10_000_000);
}

/// Two coplanar, overlapping floors of different albedo (z-fighting): every value finite, and the
/// image between that of the bright floor alone and that of a dark floor everywhere.
#[test]
fn coplanar_overlapping_faces() {
    let floor = r#"<shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>"#;
    let other = r#"<shape type="rectangle"><transform name="to_world"><scale x="0.8" y="1.3"/><rotate z="1" angle="30"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>"#;
    let plain = cornell(24, "15", 5);
    assert!(plain.contains(floor));
    let scenes = [
        plain.clone(),
        plain.replace(floor, &format!("{floor}{other}")),
        plain.replace(floor, &floor.replace("0.7", "0.2")),
    ];
    for choice in BACKENDS {
        let means: Vec<f64> = scenes
            .iter()
            .enumerate()
            .map(|(i, xml)| {
                let film = render_scene(&load_xml(xml, &format!("coplanar-{i}")), choice, 128, 10);
                assert_clean(&film, &format!("{choice:?} coplanar {i}"));
                image_mean(&film)
            })
            .collect();
        println!(
            "{choice:?}: coplanar: bright floor {:.4}, overlapping {:.4}, dark floor {:.4}",
            means[0], means[1], means[2]
        );
        assert!(
            means[0] > means[1] && means[1] > means[2],
            "{choice:?}: overlapping floors outside their bounds: {means:?}"
        );
    }
}

/// Coincident triangles: 100 copies of one rectangle, 200 triangles that no split can separate.
/// obvhs chains such primitives (100 copies of one triangle made it 93 levels deep, past the
/// kernel's 48-entry traversal stack, and the scene was refused); the loader now collapses what
/// reaches the stack's depth into one leaf. The image must be the single rectangle's.
#[test]
fn coincident_triangles_fit_the_traversal_stack() {
    let scene = |copies: usize| {
        let rectangles = r#"<shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.4, 0.2"/></bsdf></shape>"#.repeat(copies);
        format!(
            r#"<scene version="3.0.0"><integrator type="path"><integer name="max_depth" value="3"/></integrator>
            <sensor type="perspective"><float name="fov" value="50"/>
                <transform name="to_world"><lookat origin="0.3, 0.2, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
                <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film></sensor>
            <emitter type="constant"/>{rectangles}</scene>"#
        )
    };
    let one = render_scene(&load_xml(&scene(1), "coincident-1"), BackendChoice::Cpu, 32, 5);
    let many_scene = load_xml(&scene(100), "coincident-100");
    let many = render_scene(&many_scene, BackendChoice::Cpu, 32, 5);
    assert_clean(&many, "coincident triangles");
    let (a, b) = (image_mean(&one), image_mean(&many));
    assert!((a - b).abs() < 0.01 * a, "one rectangle {a}, a hundred in its place {b}");
}
