//! Light tracing (`ptracer`) and IBPT (path + light tracing by MIS) against path tracing: they estimate
//! the same image, statistically, on scenes lit by each emitter kind light tracing supports and on a
//! caustic; the GPU and the CPU splat the same sums.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic_tests::corner::{corner_sized, EMITTERS, ROUGH_PLASTIC};
use caustic_tests::replicas::*;
use caustic_tests::*;

/// The shared corner (`caustic_tests::corner`) with a glossy sphere at `max_depth` 5, `res`×`res`
/// pixels (light tracing splats with its box filter).
fn corner(integrator: &str, emitter: &str, res: u32) -> String {
    corner_with(integrator, emitter, res, ROUGH_PLASTIC)
}

/// `corner` with the sphere's BSDF given.
fn corner_with(integrator: &str, emitter: &str, res: u32, sphere_bsdf: &str) -> String {
    corner_sized(integrator, emitter, "5", res, sphere_bsdf)
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
        let light =
            render_replicated(&load_xml(&corner("ptracer", emitter, 24), &format!("{name}-pt")), 512, 2);
        let (z, worst) = agreement(&light, &path);
        println!(
            "{name}: ptracer mean {:.5}, path mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            image_mean(&light.film),
            image_mean(&path)
        );
        assert!(image_mean(&path) > 1e-3 / 3.0, "{name}: the scene is dark");
        // 24×24×3 values: |z| ≤ 5.0 is the Šidák-corrected 0.1% two-sided bound per value.
        assert!(
            z.abs() < 4.5 && worst < 5.0,
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
    let light = render_replicated(&load_xml(&corner("ptracer", &brighter, 24), "neg-pt"), 512, 2);
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
    let max_diff = max_abs_difference(&cpu, &gpu);
    let total: f64 = cpu.rgb.iter().flatten().map(|&c| c as f64).sum();
    println!("ptracer GPU vs CPU: max |difference| {max_diff:e}, image sum {total:.4}");
    assert!(total > 0.1, "the light-traced image is dark");
    assert!(max_diff < 1e-3, "GPU and CPU light tracing differ by {max_diff}");
}

#[test]
fn ibpt_and_path_agree() {
    for (name, emitter) in [EMITTERS[0], EMITTERS[2]] {
        let path = render_scene(
            &load_xml(&corner("path", emitter, 24), &format!("{name}-ipath")),
            BackendChoice::Cpu,
            512,
            3,
        );
        let ibpt =
            render_replicated(&load_xml(&corner("ibpt", emitter, 24), &format!("{name}-ibpt")), 256, 4);
        let (z, worst) = agreement(&ibpt, &path);
        println!("{name}: ibpt vs path: image z {z:+.2}, worst pixel |z| {worst:.2}");
        assert!(z.abs() < 4.5 && worst < 5.0, "{name}: ibpt and path disagree (z {z:+.2}, worst {worst:.2})");
    }
}

/// A caustic: a glass sphere focusing a small light onto the floor (L S S D E paths, which only the
/// light path can connect); IBPT must agree with path tracing there too, and be far less noisy.
#[test]
fn ibpt_renders_a_caustic_like_path_tracing() {
    let glass = r#"<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>"#;
    let light = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.5" y="0.3" z="1.6"/>
            <emitter type="area"><rgb name="radiance" value="400"/></emitter></shape>"#;
    let scene = |integrator: &str| {
        load_xml(&corner_with(integrator, light, 24, glass), &format!("caustic-{integrator}"))
    };
    let path = render_scene(&scene("path"), BackendChoice::Cpu, 2048, 5);
    let ibpt = render_replicated(&scene("ibpt"), 256, 6);
    let (z, worst) = agreement(&ibpt, &path);
    let noise = |f: &Film| f.variance.as_ref().unwrap().iter().flatten().copied().sum::<f64>();
    println!("caustic: ibpt vs path: image z {z:+.2}, worst pixel |z| {worst:.2}; summed variance path {:.3e} (2048 spp), ibpt {:.3e} (256 spp)", noise(&path), noise(&ibpt.film));
    assert!(z.abs() < 4.5 && worst < 5.0, "caustic: ibpt and path disagree (z {z:+.2}, worst {worst:.2})");
    assert!(
        noise(&ibpt.film) < noise(&path),
        "IBPT at 256 spp is not less noisy than path at 2048 spp on a caustic"
    );
}

#[test]
fn ibpt_gpu_matches_cpu() {
    let scene = load_xml(&corner("ibpt", EMITTERS[0].1, 12), "ibpt-gpu-cpu");
    let cpu = render_scene(&scene, BackendChoice::Cpu, 2, 5);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 2, 5);
    let max_diff = max_abs_difference(&cpu, &gpu);
    println!("ibpt GPU vs CPU: max |difference| {max_diff:e}");
    assert!(max_diff < 1e-3, "GPU and CPU IBPT differ by {max_diff}");
}

/// Stiff cases of the light-tracing code: a lamp sealed inside a glass ball (unbounded depth, total
/// internal reflection), index-matched glass (η = 1 + 1e-6), a camera inside glass, a floor seen at a
/// grazing angle. No sample may be NaN or infinite; ibpt must still agree with path tracing.
#[test]
fn light_tracing_stiff_cases_stay_finite_and_agree() {
    let lamp_in_glass = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.3" y="0.2" z="0.4"/>
            <emitter type="area"><rgb name="radiance" value="50"/></emitter></shape>"#;
    let cases = [
        (
            "lamp sealed in glass",
            r#"<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>"#,
            lamp_in_glass,
            "-1",
            "0, -3, 1.6",
        ),
        (
            "index-matched glass",
            r#"<bsdf type="dielectric"><float name="int_ior" value="1.000001"/><float name="ext_ior" value="1"/></bsdf>"#,
            EMITTERS[0].1,
            "8",
            "0, -3, 1.6",
        ),
        (
            "camera inside glass",
            r#"<bsdf type="roughdielectric"><float name="alpha" value="0.05"/><float name="int_ior" value="1.33"/></bsdf>"#,
            EMITTERS[0].1,
            "8",
            "0.3, 0.2, 0.45",
        ),
        ("grazing floor", r#"<bsdf type="diffuse"/>"#, EMITTERS[0].1, "8", "0, -3, 0.02"),
    ];
    for (name, sphere_bsdf, emitter, depth, origin) in cases {
        let scene_for = |integrator: &str| {
            let xml = corner_with(integrator, emitter, 16, sphere_bsdf)
                .replace(
                    r#"<integer name="max_depth" value="5"/>"#,
                    &format!(r#"<integer name="max_depth" value="{depth}"/>"#),
                )
                .replace("0, -3, 1.6", origin);
            load_xml(&xml, &format!("stiff-{integrator}-{}", name.replace(' ', "-")))
        };
        // Through the sealed glass, path tracing finds the lamp by BSDF sampling alone: heavy-tailed,
        // so it needs many more samples before its variance estimate can be trusted.
        let path_spp = if name == "lamp sealed in glass" { 8192 } else { 512 };
        let path = render_scene(&scene_for("path"), BackendChoice::Cpu, path_spp, 7);
        for integrator in ["ptracer", "ibpt"] {
            let film = render_replicated(&scene_for(integrator), 256, 8);
            assert_eq!(
                film.film.invalid_samples, 0,
                "{name}, {integrator}: {} NaN/Inf samples",
                film.film.invalid_samples
            );
            assert!(
                film.film.rgb.iter().flatten().all(|c| c.is_finite() && *c >= 0.0),
                "{name}, {integrator}: bad pixel"
            );
            if integrator == "ibpt" {
                let (z, worst) = agreement(&film, &path);
                println!(
                    "{name}: ibpt mean {:.5}, path mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
                    image_mean(&film.film),
                    image_mean(&path)
                );
                assert!(
                    z.abs() < 4.5 && worst < 5.5,
                    "{name}: ibpt and path disagree (z {z:+.2}, worst {worst:.2})"
                );
            }
        }
        assert_eq!(path.invalid_samples, 0, "{name}, path: {} NaN/Inf samples", path.invalid_samples);
    }
}

/// Light paths splat into every pixel their reconstruction filter covers, weighted as the pixel's camera
/// samples are (truncated at the image border), so ptracer and ibpt estimate the same filtered image as
/// path tracing with Mitsuba's default Gaussian filter, also in a crop window, and where the
/// principal point is moved (`principal_point_offset_x/y`: connections land where camera rays leave).
#[test]
fn light_tracing_matches_path_with_a_gaussian_filter_and_a_crop() {
    const FOV: &str = r#"<float name="fov" value="50"/>"#;
    const OFFSET: &str = r#"<float name="principal_point_offset_x" value="0.12"/><float name="principal_point_offset_y" value="-0.08"/>"#;
    // Lanczos (negative lobes): splats weighted by the signed filter, camera samples by its sign.
    for (filter, crop, offset) in [
        ("gaussian", false, false),
        ("gaussian", true, false),
        ("lanczos", true, false),
        ("gaussian", true, true),
    ] {
        let film = if crop {
            format!(
                r#"<rfilter type="{filter}"/><integer name="crop_offset_x" value="5"/><integer name="crop_offset_y" value="3"/><integer name="crop_width" value="14"/><integer name="crop_height" value="16"/>"#
            )
        } else {
            format!(r#"<rfilter type="{filter}"/>"#)
        };
        let scene = |integrator: &str| {
            load_xml(
                &corner(integrator, EMITTERS[0].1, 24)
                    .replace(r#"<rfilter type="box"/>"#, &film)
                    .replace(FOV, &if offset { format!("{FOV}{OFFSET}") } else { FOV.to_string() }),
                &format!("{filter}-{integrator}-{crop}-{offset}"),
            )
        };
        let path = render_scene(&scene("path"), BackendChoice::Cpu, 512, 11);
        for integrator in ["ptracer", "ibpt"] {
            let film = render_replicated(&scene(integrator), 256, 12);
            let (z, worst) = agreement(&film, &path);
            let case = format!("{filter} filter, crop {crop}, principal point moved {offset}");
            println!("{case}: {integrator} vs path: image z {z:+.2}, worst pixel |z| {worst:.2}");
            assert!(
                z.abs() < 4.5 && worst < 5.0,
                "{integrator} ({case}): disagrees with path (z {z:+.2}, worst {worst:.2})"
            );
        }
    }
}

/// `hide_emitters`: camera rays pass through area emitters, and so must light tracing's connections to
/// the camera (a rectangle lamp hangs between the camera and the scene, facing the camera; a point
/// light lights the scene).
#[test]
fn ibpt_sees_through_hidden_emitters_like_path() {
    let lamp = r#"<shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="100"/><translate y="-1.8" z="1.3"/></transform>
            <emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>"#;
    let emitters = format!("{}\n{lamp}", EMITTERS[2].1);
    let scene = |integrator: &str| {
        let xml = corner(integrator, &emitters, 24).replace(
            r#"<integer name="max_depth" value="5"/>"#,
            r#"<integer name="max_depth" value="5"/><boolean name="hide_emitters" value="true"/>"#,
        );
        load_xml(&xml, &format!("hidden-{integrator}"))
    };
    let path = render_scene(&scene("path"), BackendChoice::Cpu, 512, 13);
    let ibpt = render_replicated(&scene("ibpt"), 256, 14);
    let (z, worst) = agreement(&ibpt, &path);
    println!("hidden emitters: ibpt vs path: image z {z:+.2}, worst pixel |z| {worst:.2}");
    assert!(
        z.abs() < 4.5 && worst < 5.0,
        "hidden emitters: ibpt and path disagree (z {z:+.2}, worst {worst:.2})"
    );
}

/// Infinite emitters in light tracing, as Mitsuba's `ptracer` traces them (light paths from a disk
/// covering the scene; the environment seen directly as directions drawn from the eye): a constant
/// environment, a directional light and (where the shared data are present) an envmap give the image
/// path tracing gives, the sky seen around the corner included.
#[test]
fn ptracer_traces_infinite_emitters_like_path() {
    let mut cases = vec![
        ("constant", r#"<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>"#.to_string()),
        (
            "directional",
            r#"<emitter type="directional"><vector name="direction" value="0.3, 0.5, -1"/><rgb name="irradiance" value="2"/></emitter>"#
                .to_string(),
        ),
    ];
    if let Some(shared) = shared_dir_if_present() {
        let museum = shared.join("scenes/mitsuba/common/textures/museum.exr");
        cases.push((
            "envmap",
            format!(
                r#"<emitter type="envmap"><string name="filename" value="{}"/><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>"#,
                museum.display()
            ),
        ));
    }
    for (name, emitter) in &cases {
        let path = render_scene(
            &load_xml(&corner("path", emitter, 24), &format!("{name}-inf-path")),
            BackendChoice::Cpu,
            512,
            41,
        );
        let light =
            render_replicated(&load_xml(&corner("ptracer", emitter, 24), &format!("{name}-inf-pt")), 512, 42);
        let (z, worst) = agreement(&light, &path);
        println!(
            "{name}: ptracer mean {:.5}, path mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            light.mean,
            image_mean(&path)
        );
        assert!(image_mean(&path) > 1e-2, "{name}: the scene is dark");
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{name}: ptracer and path disagree (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// The GPU light-traces an environment as the CPU does (same seed, same sums to rounding).
#[test]
fn ptracer_environment_gpu_matches_cpu() {
    let sky = r#"<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>"#;
    let scene = load_xml(&corner("ptracer", sky, 12), "env-gpu-cpu");
    let cpu = render_scene(&scene, BackendChoice::Cpu, 4, 5);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 4, 5);
    let max_diff = max_abs_difference(&cpu, &gpu);
    println!(
        "environment ptracer GPU vs CPU: max |difference| {max_diff:e}, CPU mean {:.4}",
        image_mean(&cpu)
    );
    assert!(image_mean(&cpu) > 0.05, "the light-traced environment is dark");
    assert!(max_diff < 1e-3, "GPU and CPU light tracing differ by {max_diff}");
}

/// `ptracer` and `ibpt` (seeds `seeds`, 512 spp replicated) against path tracing (`path_spp`, seed
/// `path_seed`) on the corner scene under the area light, changed by `variant`.
fn light_tracing_agrees_with_path(
    what: &str,
    variant: impl Fn(String) -> String,
    path_spp: u32,
    path_seed: u32,
    seeds: [u32; 2],
) -> Film {
    let emitter = EMITTERS[0].1;
    let path = render_scene(
        &load_xml(&variant(corner("path", emitter, 24)), &format!("{what}-path")),
        BackendChoice::Cpu,
        path_spp,
        path_seed,
    );
    for (integrator, seed) in [("ptracer", seeds[0]), ("ibpt", seeds[1])] {
        let scene = load_xml(&variant(corner(integrator, emitter, 24)), &format!("{what}-{integrator}"));
        let other = render_replicated(&scene, 512, seed);
        let (z, worst) = agreement(&other, &path);
        println!(
            "{what}, {integrator}: mean {:.5}, path {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            other.mean,
            image_mean(&path)
        );
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{what}: {integrator} and path disagree (z {z:+.2}, worst {worst:.2})"
        );
    }
    path
}

/// A thin-lens camera (strongly defocused: aperture radius 0.4, focus 6 units away, behind the scene;
/// the sphere's edge blurs over about 3 pixels): light tracing connects to points of the aperture and IBPT weighs through the aperture point
/// its camera ray used; both give path tracing's image.
#[test]
fn ptracer_and_ibpt_see_through_a_thin_lens_like_path() {
    let thin_lens = |xml: String| {
        xml.replace(
            r#"<sensor type="perspective">"#,
            r#"<sensor type="thinlens"><float name="aperture_radius" value="0.4"/><float name="focus_distance" value="6"/>"#,
        )
    };
    light_tracing_agrees_with_path("thin lens", thin_lens, 4096, 61, [52, 53]);
}

/// Camera rays start at the near clip plane, so a surface between it and the lens hides nothing;
/// light tracing's connections to the camera stop at that plane too, and agree with path tracing.
/// Here a wall 0.5 in front of the camera, inside a near clip of 1, covers the whole view (before
/// connections stopped at the plane, the light-traced image was black behind it, z −3028; a random
/// scene's clipped cylinder gave z −36).
#[test]
fn ptracer_and_ibpt_see_past_the_near_clip_plane_like_path() {
    let clipped = |xml: String| {
        xml.replace(r#"<float name="fov" value="50"/>"#, r#"<float name="fov" value="50"/><float name="near_clip" value="1"/>"#)
            .replace(
                "</scene>",
                r#"<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="-2.5" z="1.6"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
</scene>"#,
            )
    };
    // The GPU's connections stop there too: same seed, the same splats as the CPU's.
    let scene = load_xml(&clipped(corner("ptracer", EMITTERS[0].1, 12)), "clip-gpu");
    let (cpu, gpu) =
        (render_scene(&scene, BackendChoice::Cpu, 4, 5), render_scene(&scene, BackendChoice::Gpu, 4, 5));
    let max_diff = max_abs_difference(&cpu, &gpu);
    println!(
        "near clip, ptracer: GPU vs CPU: max |difference| {max_diff:e}, CPU mean {:.5}",
        image_mean(&cpu)
    );
    assert!(
        image_mean(&cpu) > 1e-2 && max_diff < 1e-3,
        "near clip: GPU and CPU light tracing differ by {max_diff}"
    );
    let path = light_tracing_agrees_with_path("near clip", clipped, 1024, 71, [72, 73]);
    assert!(image_mean(&path) > 1e-2, "path tracing does not see past the clipped wall");
}
