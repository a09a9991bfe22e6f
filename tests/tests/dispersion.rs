//! Dispersion (`caustic_kernel::wavelength`): a prism fans white light into ordered colours and
//! recombines it to the RGB image's energy (light tracing, BDPT and VCM), a dispersive glass keeps a
//! white furnace white, light tracing, IBPT, BDPT and VCM agree with path tracing through dispersive
//! glass, and the GPU splats the same signed sums as the CPU.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::{IntegratorKind, Scene};
use caustic_kernel::layout::MATERIAL_DISPERSIVE;
use caustic_tests::replicas::*;
use caustic_tests::*;
use std::path::PathBuf;

/// The prism scene at 48×48 without its ceiling light (only the beam lights it), rendered by `kind`;
/// `disperse: false` renders its glass as plain RGB glass.
fn prism(disperse: bool, kind: IntegratorKind) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes/prism.xml");
    let mut scene = caustic::load::load_scene(&path, &defines(&[("res", "48"), ("ceiling", "0")]))
        .unwrap_or_else(|e| panic!("{e:#}"));
    scene.integrator.kind = kind;
    for m in scene.materials.iter_mut().filter(|_| !disperse) {
        m.flags &= !MATERIAL_DISPERSIVE;
    }
    scene
}

/// Per channel: the image's sum and the x and y coordinates of its intensity-weighted centroid.
fn sums_and_centroids(f: &Film) -> [[f64; 3]; 3] {
    let (mut sum, mut mx, mut my) = ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
    for (i, p) in f.rgb.iter().enumerate() {
        let (x, y) = ((i as u32 % f.width) as f64, (i as u32 / f.width) as f64);
        for c in 0..3 {
            sum[c] += p[c] as f64;
            mx[c] += x * p[c] as f64;
            my[c] += y * p[c] as f64;
        }
    }
    [sum, [0, 1, 2].map(|c| mx[c] / sum[c]), [0, 1, 2].map(|c| my[c] / sum[c])]
}

/// Mean and standard error over independent renders of `f(image)`.
fn over_replicas(scene: &Scene, seed: u32, f: impl Fn(&Film) -> [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let n = 8;
    let values: Vec<[f64; 3]> =
        (0..n).map(|r| f(&render_scene(scene, BackendChoice::Cpu, 32, seed * 100 + r))).collect();
    let mean = [0, 1, 2].map(|c| values.iter().map(|v| v[c]).sum::<f64>() / n as f64);
    let se = [0, 1, 2].map(|c| {
        let ss: f64 = values.iter().map(|v| (v[c] - mean[c]).powi(2)).sum();
        (ss / (n - 1) as f64 / n as f64).sqrt()
    });
    (mean, se)
}

/// The prism scene with and without dispersion: with it, red, green and blue land in order at
/// separate places on the screen (the channels' centroids); and the light is the same in both (white
/// recombines: each channel's total agrees with the RGB render's). By light tracing, where each path
/// draws its wavelength, and by BDPT and VCM, where each pass refracts at one.
#[test]
fn a_prism_fans_white_light_into_its_spectrum() {
    for kind in [IntegratorKind::Ptracer, IntegratorKind::Bdpt, IntegratorKind::Vcm] {
        println!("{kind:?}:");
        fans_into_its_spectrum(&prism(true, kind), &prism(false, kind));
    }
}

fn fans_into_its_spectrum(dispersed: &Scene, plain: &Scene) {
    // The centroids along the axis the spectrum spreads on in this view.
    let (cx, _) = over_replicas(dispersed, 4, |f| sums_and_centroids(f)[1]);
    let (cy, _) = over_replicas(dispersed, 5, |f| sums_and_centroids(f)[2]);
    let axis = if (cx[0] - cx[2]).abs() > (cy[0] - cy[2]).abs() { 1 } else { 2 };
    let (centre, centre_se) = over_replicas(dispersed, 1, |f| sums_and_centroids(f)[axis]);
    let (sum_d, se_d) = over_replicas(dispersed, 2, |f| sums_and_centroids(f)[0]);
    let (sum_p, se_p) = over_replicas(plain, 3, |f| sums_and_centroids(f)[0]);
    println!("dispersed: centroids x {centre:.2?} ± {centre_se:.2?}; sums {sum_d:.2?} ± {se_d:.2?}");
    println!("RGB glass: sums {sum_p:.2?} ± {se_p:.2?}");
    let spread = centre[0] - centre[2];
    let spread_se = (centre_se[0].powi(2) + centre_se[2].powi(2)).sqrt();
    assert!(spread.abs() > 1.0 && spread.abs() > 5.0 * spread_se, "red and blue do not separate: {centre:?}");
    assert!((centre[1] - centre[0]) * (centre[1] - centre[2]) < 0.0, "green is not between: {centre:?}");
    for c in 0..3 {
        let z = (sum_d[c] - sum_p[c]) / (se_d[c].powi(2) + se_p[c].powi(2)).sqrt();
        assert!(
            z.abs() < 4.5,
            "channel {c}: dispersion changed the light ({} vs {}, z {z:+.2})",
            sum_d[c],
            sum_p[c]
        );
    }
}

/// A dispersive glass sphere in a white furnace (a closed environment of radiance 1): glass without
/// absorption sends on all it receives, at every wavelength, so every pixel is 1 in every channel.
#[test]
fn dispersive_glass_keeps_the_furnace_white() {
    let xml = r#"<scene version="3.0.0">
    <integrator type="path"><integer name="rr_depth" value="1000"/><integer name="max_depth" value="64"/></integrator>
    <sensor type="perspective"><float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film></sensor>
    <shape type="sphere"><bsdf type="dielectric"><float name="int_ior" value="1.6"/><float name="abbe_number" value="15"/></bsdf></shape>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>"#;
    let scene = load_xml(xml, "dispersive-furnace");
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        let film = render_scene(&scene, choice, 256, 3);
        let var = film.variance.as_ref().unwrap();
        let n = film.rgb.len() as f64;
        for c in 0..3 {
            let mean = film.rgb.iter().map(|p| p[c] as f64).sum::<f64>() / n;
            let se = var.iter().map(|v| v[c]).sum::<f64>().sqrt() / n;
            println!("{choice:?} channel {c}: mean {mean:.5} ± {se:.5}");
            assert!(
                (mean - 1.0).abs() < 4.0 * se + 1e-4,
                "{choice:?} channel {c}: furnace mean {mean} ± {se}"
            );
        }
        assert_eq!(film.invalid_samples, 0);
    }
}

/// A floor and a back wall coloured `floor` and `wall` (RGB), a glass sphere (`glass`: its shape
/// with its BSDF) and a sphere light (`light`), seen by a `res`² box-filtered camera.
fn glass_corner(integrator: &str, res: u32, floor: &str, wall: &str, glass: &str, light: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><integer name="max_depth" value="8"/></integrator>
    <sensor type="perspective"><float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, -3, 1.6" target="0, 0, 0.4" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film></sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="{floor}"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="90"/><translate y="1.5" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="{wall}"/></bsdf></bsdf></shape>
    {glass}
    {light}
</scene>"#
    )
}

/// A corner lit by a small sphere light through a dispersive glass sphere (dispersed caustics on the
/// floor): light tracing and IBPT estimate the image path tracing does.
fn dispersive_corner(integrator: &str) -> Scene {
    let glass = r#"<shape type="sphere"><float name="radius" value="0.4"/><point name="center" x="0.2" y="0.2" z="0.5"/>
        <bsdf type="roughdielectric"><float name="alpha" value="0.3"/><float name="int_ior" value="1.6"/><float name="abbe_number" value="12"/></bsdf></shape>"#;
    let light = r#"<shape type="sphere"><float name="radius" value="0.25"/><point name="center" x="0.6" y="0.4" z="1.7"/>
        <emitter type="area"><rgb name="radiance" value="20"/></emitter></shape>"#;
    let xml = glass_corner(integrator, 20, "0.7", "0.3, 0.6, 0.5", glass, light);
    load_xml(&xml, &format!("dispersive-corner-{integrator}"))
}

#[test]
fn light_tracing_and_ibpt_agree_with_path_through_dispersive_glass() {
    agree_with_path_through_dispersive_glass(&[("ptracer", 12), ("ibpt", 13)]);
}

/// BDPT and VCM refract every path of a pass at the pass's wavelength (`pass_wavelength`), so their
/// connections and merges join paths of one wavelength: they estimate path tracing's image too.
#[test]
fn bdpt_and_vcm_agree_with_path_through_dispersive_glass() {
    agree_with_path_through_dispersive_glass(&[("bdpt", 14), ("vcm", 15)]);
}

fn agree_with_path_through_dispersive_glass(integrators: &[(&str, u32)]) {
    let path = render_scene(&dispersive_corner("path"), BackendChoice::Cpu, 2048, 11);
    for &(integrator, seed) in integrators {
        let other = render_replicated(&dispersive_corner(integrator), 512, seed);
        let (z, worst) = agreement(&other, &path);
        println!(
            "{integrator} vs path through dispersive glass: means {:.5} / {:.5}, image z {z:+.2}, worst pixel |z| {worst:.2}",
            other.mean,
            image_mean(&path)
        );
        // 20×20×3 values: |z| ≤ 5.0 is below the Šidák-corrected 0.1% two-sided bound per value.
        assert!(z.abs() < 4.5 && worst < 5.0, "{integrator} and path disagree (z {z:+.2}, worst {worst:.2})");
    }
}

/// The GPU draws the same wavelengths and splats the same signed sums as the CPU (IBPT's per path,
/// VCM's per pass).
#[test]
fn dispersion_gpu_matches_cpu() {
    for integrator in ["ibpt", "vcm"] {
        let scene = dispersive_corner(integrator);
        let cpu = render_scene(&scene, BackendChoice::Cpu, 4, 5);
        let gpu = render_scene(&scene, BackendChoice::Gpu, 4, 5);
        let max_diff = max_abs_difference(&cpu, &gpu);
        let negative = cpu.rgb.iter().flatten().filter(|&&c| c < 0.0).count();
        println!("dispersive {integrator} GPU vs CPU: max |difference| {max_diff:e}; {negative} negative CPU values");
        assert!(max_diff < 1e-3, "{integrator}: GPU and CPU differ by {max_diff}");
    }
}

/// The dielectric of `<string name="glass" value="NAME"/>` in vacuum.
fn named_glass(name: &str) -> caustic_kernel::layout::Material {
    let xml = format!(
        r#"<scene version="3.0.0"><sensor type="perspective"/><shape type="sphere"><bsdf type="dielectric"><string name="glass" value="{name}"/><float name="ext_ior" value="1"/></bsdf></shape></scene>"#
    );
    let m = load_xml(&xml, name).materials[0];
    assert!(m.flags & MATERIAL_DISPERSIVE != 0, "{name} disperses");
    m
}

/// The named glasses have the catalogue's index at the d line and Abbe number (Schott; fused silica:
/// Malitson), which checks their Sellmeier coefficients and the kernel's evaluation of them.
#[test]
fn named_glasses_have_their_catalogue_index_and_abbe_number() {
    use caustic_kernel::wavelength::{eta_at, LAMBDA_C, LAMBDA_D, LAMBDA_F};
    for (name, n_d, v_d) in [
        ("bk7", 1.5168, 64.17),
        ("fused silica", 1.45846, 67.82),
        ("f2", 1.62004, 36.37),
        ("SF11", 1.78472, 25.68),
        ("sf66", 1.92286, 20.88),
    ] {
        let m = named_glass(name);
        let n = eta_at(&m, LAMBDA_D);
        let v = (n - 1.0) / (eta_at(&m, LAMBDA_F) - eta_at(&m, LAMBDA_C));
        println!("{name}: n_d {n:.5} (catalogue {n_d}), V_d {v:.2} (catalogue {v_d})");
        assert!((n - n_d).abs() < 2e-5 && (v - v_d).abs() < 0.02, "{name}: n_d {n}, V_d {v}");
        assert!((m.eta - n_d).abs() < 2e-5, "{name}: the material's index without a wavelength is n_d");
    }
}

/// A ray through a 60° prism of SF11, traced with the kernel's dielectric at the glass's index at 450
/// and 650 nm, is deviated by the angles Snell's law predicts for those indices, blue more than red.
#[test]
fn prism_deviation_follows_snell_with_the_glass_index() {
    use caustic_kernel::bsdf::{Bsdf, TransportMode};
    use caustic_kernel::glam::{Vec2, Vec3};
    use caustic_kernel::wavelength::eta_at;
    let glass = named_glass("sf11");
    let (apex, theta1) = (60f64.to_radians(), 65f64.to_radians());
    let mut deviations = vec![];
    for lambda in [450.0f32, 650.0] {
        let mut m = glass;
        m.eta = eta_at(&glass, lambda);
        let bsdf = Bsdf::from_material(&m, &[], &[]);
        // First face (normal +z, viewer outside): refraction is the lobe sampled with u_lobe → 1.
        let wo = Vec3::new(theta1.sin() as f32, 0.0, theta1.cos() as f32);
        let inside = bsdf.sample(wo, 0.99999, Vec2::splat(0.5), TransportMode::Radiance);
        assert!(inside.wi.z < 0.0, "refracted into the glass");
        let theta2 = (-inside.wi.z as f64).acos();
        // Second face: the ray meets it at A − θ2 from the inside.
        let theta3 = apex - theta2;
        let wo2 = Vec3::new(-theta3.sin() as f32, 0.0, -theta3.cos() as f32);
        let out = bsdf.sample(wo2, 0.99999, Vec2::splat(0.5), TransportMode::Radiance);
        assert!(out.wi.z > 0.0, "leaves the glass");
        let deviation = theta1 + (out.wi.z as f64).acos() - apex;
        let n = m.eta as f64;
        let snell = theta1 + (n * (apex - (theta1.sin() / n).asin()).sin()).asin() - apex;
        println!(
            "λ {lambda} nm: index {n:.5}; deviation {:.4}° (Snell {:.4}°)",
            deviation.to_degrees(),
            snell.to_degrees()
        );
        assert!((deviation - snell).abs().to_degrees() < 0.01, "deviation {deviation} vs {snell}");
        deviations.push(deviation);
    }
    // SF11 between 450 and 650 nm: 5.4° apart at this incidence.
    assert!(deviations[0] > deviations[1] + 5f64.to_radians(), "blue is not bent more than red");
}

/// A coloured scene with a glass whose dispersion is negligible, rendered through the wavelength
/// machinery, equals the RGB render (white recombines exactly in expectation, colours included).
#[test]
fn negligible_dispersion_renders_the_rgb_image() {
    let scene = |b: &str| {
        let glass = format!(
            r#"<shape type="sphere"><float name="radius" value="0.5"/><point name="center" x="0" y="0" z="0.5"/>
        <bsdf type="roughdielectric"><float name="alpha" value="0.2"/><float name="int_ior" value="1.5"/>{b}</bsdf></shape>"#
        );
        let light = r#"<shape type="sphere"><float name="radius" value="0.4"/><point name="center" x="0.6" y="0.4" z="1.8"/>
        <emitter type="area"><rgb name="radiance" value="8"/></emitter></shape>"#;
        let xml = glass_corner("path", 16, "0.8, 0.3, 0.1", "0.1, 0.4, 0.8", &glass, light);
        load_xml(&xml, &format!("rgb-vs-spectral-{}", b.len()))
    };
    let spectral = scene(r#"<float name="cauchy_b" value="1e-7"/>"#);
    assert!(spectral.materials.iter().any(|m| m.flags & MATERIAL_DISPERSIVE != 0));
    let a = render_scene(&spectral, BackendChoice::Cpu, 1024, 31);
    let b = render_scene(&scene(""), BackendChoice::Cpu, 1024, 32);
    let (va, vb) = (a.variance.as_ref().unwrap(), b.variance.as_ref().unwrap());
    for c in 0..3 {
        let n = a.rgb.len() as f64;
        let (ma, mb) = [&a, &b].map(|f| f.rgb.iter().map(|p| p[c] as f64).sum::<f64>() / n).into();
        let se = (va.iter().chain(vb).map(|v| v[c]).sum::<f64>()).sqrt() / n;
        println!("channel {c}: spectral {ma:.5}, RGB {mb:.5} ± {se:.5}");
        assert!((ma - mb).abs() < 4.5 * se, "channel {c}: {ma} vs {mb} (se {se})");
    }
}

/// Unknown glasses, two dispersion laws at once and dispersion that makes the index non-positive are
/// errors naming the file and line.
#[test]
fn bad_dispersion_parameters_are_refused_with_their_line() {
    let dir = std::env::temp_dir().join(format!("caustic-dispersion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (bsdf, expected) in [
        (r#"<string name="glass" value="unobtainium"/>"#, "no glass is known by the name 'unobtainium'"),
        (r#"<string name="glass" value="bk7"/><float name="int_ior" value="1.5"/>"#, "not both"),
        (r#"<string name="glass" value="bk7"/><float name="abbe_number" value="30"/>"#, "give one of"),
        (r#"<float name="abbe_number" value="-3"/>"#, "positive"),
        (r#"<float name="cauchy_b" value="-1"/>"#, "index of refraction at"),
    ] {
        let path = dir.join("scene.xml");
        let xml = format!("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"dielectric\">{bsdf}</bsdf>\n</shape>\n</scene>");
        std::fs::write(&path, xml).unwrap();
        let message = match caustic::load::load_scene(&path, &[]) {
            Ok(_) => panic!("{bsdf}: accepted"),
            Err(e) => format!("{e:#}"),
        };
        println!("{message}");
        assert!(message.contains(expected) && message.contains("scene.xml:3"), "{bsdf}: {message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
