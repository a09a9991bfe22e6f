//! Bidirectional path tracing (`bdpt`) against path tracing: the same image, statistically, under each
//! emitter kind it starts light paths from, with Dirac lobes, through a thin lens, with hidden
//! emitters and masks, past the light path's reach and on the caustic seen through glass that only
//! its connections make cheaply; GPU against CPU; no NaN or Inf on stiff cases.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::IntegratorKind;
use caustic_tests::corner::*;
use caustic_tests::replicas::*;
use caustic_tests::*;

/// `bdpt` against `path` on `xml(kind)` (`corner::agrees_with_path`).
fn agrees_with_path(
    what: &str,
    xml: impl Fn(&str) -> String,
    spp: u32,
    path_spp: u32,
    seed: u32,
) -> (Replicated, Film) {
    caustic_tests::corner::agrees_with_path("bdpt", what, xml, spp, path_spp, seed)
}

#[test]
fn bdpt_and_path_agree_on_every_emitter_kind() {
    for (i, (name, emitter)) in EMITTERS.into_iter().enumerate() {
        agrees_with_path(name, |k| corner(k, emitter, "5", ROUGH_PLASTIC), 256, 1024, 10 + 2 * i as u32);
    }
}

/// Shares other than the default (0.5, which the tests above render): each camera vertex joining
/// every vertex of its light path (0) under an area light and through glass at any depth, and one
/// drawn uniformly, the connections counted 0.4 in the weights (`bdpt_mis::Connections`), under a
/// spot (a Dirac position): the same image as `path`.
#[test]
fn bdpt_at_other_connection_shares_agrees_with_path() {
    let share = |c: &'static str| {
        move |xml: String| {
            xml.replace(
                r#"type="bdpt">"#,
                &format!(r#"type="bdpt"><float name="connection_share" value="{c}"/>"#),
            )
        }
    };
    let cases = [(EMITTERS[0], "0", "every vertex", 70), (EMITTERS[3], "0.4", "one drawn", 72)];
    for ((name, emitter), c, how, seed) in cases {
        let with = share(c);
        agrees_with_path(
            &format!("{name}, {how}"),
            |k| with(corner(k, emitter, "5", ROUGH_PLASTIC)),
            256,
            1024,
            seed,
        );
    }
    let every = share("0");
    agrees_with_path("glass, every vertex", |k| every(corner(k, EMITTERS[1].1, "-1", GLASS)), 256, 2048, 80);
}

/// Fewer light paths connected to the camera (`light_tracing_share`: their splats count `1 / share`,
/// light tracing counts `share` in the weights) and fewer camera vertices joining their light path
/// (`connection_rate`), each decided for a tile of pixels at once: the same image as `path`, under an
/// area light, a spot, and through glass at any depth with both; `ibpt` and `vcm` likewise.
#[test]
fn fewer_light_tracing_splats_and_connections_agree_with_path() {
    let with = |kind: &'static str, props: &'static str| {
        move |xml: String| xml.replace(&format!(r#"type="{kind}">"#), &format!(r#"type="{kind}">{props}"#))
    };
    let share = r#"<float name="light_tracing_share" value="0.3"/>"#;
    let rate = r#"<float name="connection_rate" value="0.4"/>"#;
    let both =
        r#"<float name="light_tracing_share" value="0.5"/><float name="connection_rate" value="0.5"/>"#;
    let (area, spot) = (EMITTERS[0], EMITTERS[3]);
    let cases = [
        ("bdpt", area, share, 90),
        ("bdpt", spot, rate, 92),
        ("vcm", area, both, 94),
        ("ibpt", area, share, 96),
    ];
    for (kind, (name, emitter), props, seed) in cases {
        let with = with(kind, props);
        caustic_tests::corner::agrees_with_path(
            kind,
            &format!("{name}, {props}"),
            |k| with(corner(k, emitter, "5", ROUGH_PLASTIC)),
            256,
            1024,
            seed,
        );
    }
    let both_glass = with("bdpt", both);
    agrees_with_path(
        "glass, both halves",
        |k| both_glass(corner(k, EMITTERS[1].1, "-1", GLASS)),
        256,
        2048,
        98,
    );
}

/// The check above can fail: a 10% brighter light in the bidirectional image is detected.
#[test]
fn bdpt_agreement_detects_a_brighter_light() {
    let emitter = EMITTERS[0].1;
    let brighter = emitter.replace(r#"value="12""#, r#"value="13.2""#);
    let path = render_scene(
        &load_xml(&corner("path", emitter, "5", ROUGH_PLASTIC), "neg-path"),
        BackendChoice::Cpu,
        1024,
        1,
    );
    let bdpt =
        render_replicated(&load_xml(&corner("bdpt", &brighter, "5", ROUGH_PLASTIC), "neg-bdpt"), 256, 2);
    let (z, _) = agreement(&bdpt, &path);
    println!("10% brighter light: image z {z:+.2}");
    assert!(z > 6.0, "a 10% brighter light went unnoticed (z {z:+.2})");
}

/// Dirac lobes at the sphere (glass and a mirror), unbounded depth: paths past the light path's reach
/// (`bdpt::bidirectional`) are weighted between the camera strategies alone.
#[test]
fn bdpt_and_path_agree_through_dirac_lobes_at_any_depth() {
    let mirror = r#"<bsdf type="conductor"><string name="material" value="none"/></bsdf>"#;
    for (name, bsdf, depth) in
        [("glass", GLASS, "-1"), ("mirror", mirror, "-1"), ("glass, depth 4", GLASS, "4")]
    {
        agrees_with_path(name, |k| corner(k, EMITTERS[1].1, depth, bsdf), 256, 2048, 30);
    }
}

/// Long paths: a box of mirrors facing each other (light bouncing tens of times), where most of the
/// image is made by paths longer than the light path's reach.
#[test]
fn bdpt_and_path_agree_on_long_paths() {
    let scene = |k: &str| {
        corner(k, EMITTERS[0].1, "-1", ROUGH_PLASTIC)
            .replace(r#"<rgb name="reflectance" value="0.7"/>"#, r#"<rgb name="reflectance" value="0.95"/>"#)
            .replace(r#"<rgb name="reflectance" value="0.6"/>"#, r#"<rgb name="reflectance" value="0.95"/>"#)
    };
    agrees_with_path("bright corner", scene, 256, 2048, 40);
}

/// A caustic seen through glass (light → glass → floor → glass → camera): a small light above a glass
/// sphere focusing onto the floor, seen through a glass slab. Path tracing finds these paths only by
/// hitting the small light; BDPT connects the floor's camera vertex to the light path's, and agrees.
#[test]
fn bdpt_renders_a_caustic_seen_through_glass_like_path() {
    let light = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.5" y="0.3" z="1.6"/>
            <emitter type="area"><rgb name="radiance" value="400"/></emitter></shape>"#;
    let slab = r#"<shape type="cube"><transform name="to_world"><scale x="1.2" y="0.05" z="1.2"/><translate y="-1.6" z="0.8"/></transform>
            <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>"#;
    let scene = |k: &str| corner(k, &format!("{light}{slab}"), "-1", GLASS);
    let (bdpt, path) = agrees_with_path("caustic through glass", scene, 512, 8192, 50);
    let noise = |f: &Film| f.variance.as_ref().unwrap().iter().flatten().copied().sum::<f64>();
    println!(
        "summed variance: path {:.3e} (8192 spp), bdpt {:.3e} (512 spp)",
        noise(&path),
        noise(&bdpt.film)
    );
}

/// A caustic under a stack of five glass slabs, seen directly (light → ten Dirac vertices → floor →
/// camera, twelve segments). A light path's reach is counted in the vertices it keeps (non-Dirac
/// ones), not in segments, so light tracing reaches the floor through the stack and carries the
/// caustic; with the reach counted in segments (eight) the light path stopped inside the stack, the
/// camera path's hits on the small lamp made these paths alone, as path tracing makes them. Path
/// tracing's variance per sample over bdpt's, summed over the image: 639 (seed 90, CPU); 8.2 with
/// `bdpt::MAX_LIGHT_SEGMENTS` set to 8 (above 1 there only because 256 samples rarely meet the rare
/// bright hits that 8192 of path tracing's do).
#[test]
fn bdpt_reaches_a_caustic_behind_many_dirac_vertices() {
    let light = r#"<shape type="sphere"><float name="radius" value="0.04"/><point name="center" x="0" y="0.8" z="1.9"/>
            <emitter type="area"><rgb name="radiance" value="800"/></emitter></shape>"#;
    let slabs: String = (0..5)
        .map(|i| {
            format!(
                r#"<shape type="cube"><transform name="to_world"><scale x="0.35" y="0.35" z="0.02"/><translate y="0.4" z="{}"/></transform>
            <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>"#,
                0.8 + 0.1 * i as f32
            )
        })
        .collect();
    let scene = |k: &str| corner(k, &format!("{light}{slabs}"), "-1", ROUGH_PLASTIC);
    let (spp, path_spp) = (256, 8192);
    let (bdpt, path) = agrees_with_path("caustic under five slabs", scene, spp, path_spp, 90);
    // Each image's summed variance of its mean, times its samples: the variance of one sample.
    let per_sample = |f: &Film, n: u32| f.variance.as_ref().unwrap().iter().flatten().sum::<f64>() * n as f64;
    let ratio = per_sample(&path, path_spp) / per_sample(&bdpt.film, spp);
    println!("per-sample variance, path over bdpt: {ratio:.1}");
    assert!(ratio > 50.0, "bdpt is as noisy as path tracing behind the slabs (ratio {ratio:.1})");
}

/// A thin lens, hidden emitters and a mask: what the camera side shares with `path` and the light side
/// with `ptracer`.
#[test]
fn bdpt_and_path_agree_with_a_thin_lens_hidden_emitters_and_a_mask() {
    let thin_lens = |xml: String| {
        xml.replace(
            r#"<sensor type="perspective">"#,
            r#"<sensor type="thinlens"><float name="aperture_radius" value="0.4"/><float name="focus_distance" value="6"/>"#,
        )
    };
    agrees_with_path("thin lens", |k| thin_lens(corner(k, EMITTERS[0].1, "5", ROUGH_PLASTIC)), 256, 2048, 60);
    let hidden = |k: &str| {
        corner(k, EMITTERS[1].1, "5", ROUGH_PLASTIC).replace(
            r#"<integer name="max_depth" value="5"/>"#,
            r#"<integer name="max_depth" value="5"/><boolean name="hide_emitters" value="true"/>"#,
        )
    };
    agrees_with_path("hidden emitters", hidden, 256, 2048, 62);
    let masked = r#"<bsdf type="mask"><float name="opacity" value="0.4"/><bsdf type="diffuse"><rgb name="reflectance" value="0.8"/></bsdf></bsdf>"#;
    agrees_with_path("mask", |k| corner(k, EMITTERS[0].1, "5", masked), 256, 2048, 64);
}

/// An environment (no light path starts there) beside an area light.
#[test]
fn bdpt_and_path_agree_under_an_environment() {
    let sky =
        format!(r#"{}<emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>"#, EMITTERS[0].1);
    agrees_with_path("constant sky", |k| corner(k, &sky, "5", ROUGH_PLASTIC), 256, 2048, 70);
}

/// Stiff cases: a lamp sealed in glass, index-matched glass, a camera inside glass, a grazing floor,
/// a camera inside glass whose index runs from 2.5 to 1.7 over 380-780 nm (each pass's wavelength
/// refracting every path). No sample may be NaN or infinite, and bdpt must agree with path tracing.
#[test]
fn bdpt_stiff_cases_stay_finite_and_agree() {
    let lamp_in_glass = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.3" y="0.2" z="0.4"/>
            <emitter type="area"><rgb name="radiance" value="50"/></emitter></shape>"#;
    let cases = [
        ("lamp sealed in glass", GLASS, lamp_in_glass, "-1", "0, -3, 1.6"),
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
        (
            "camera inside glass of extreme dispersion (Abbe number 3)",
            r#"<bsdf type="roughdielectric"><float name="alpha" value="0.05"/><float name="int_ior" value="1.9"/><float name="abbe_number" value="3"/></bsdf>"#,
            EMITTERS[0].1,
            "8",
            "0.3, 0.2, 0.45",
        ),
    ];
    for (i, (name, bsdf, emitter, depth, origin)) in cases.into_iter().enumerate() {
        let scene = |k: &str| {
            corner(k, emitter, depth, bsdf)
                .replace(r#"origin="0, -3, 1.6""#, &format!(r#"origin="{origin}""#))
        };
        agrees_with_path(name, scene, 256, 4096, 80 + 2 * i as u32);
    }
}

/// `bdpt` against `path` on whole scenes as users bring them: a 24×24 window at the centre of each
/// shared Mitsuba scene whose sensor, emitters and materials `bdpt` takes (area, point, spot and
/// environment emitters, every material family, textures, a thin lens, a PLY mesh), and the seed
/// scenes at 24×24 (caustics seen directly, a light guide).
#[test]
fn bdpt_and_path_agree_on_the_mitsuba_and_seed_scenes() {
    let mitsuba = [
        "scenes/cbox/cbox.xml",
        "docs/scenes/integrator_depth_inf.xml",
        "docs/scenes/bsdf_diffuse_textured.xml",
        "docs/scenes/bsdf_conductor_gold.xml",
        "docs/scenes/bsdf_roughconductor_copper.xml",
        "docs/scenes/bsdf_dielectric_glass.xml",
        "docs/scenes/bsdf_roughdielectric_glass.xml",
        "docs/scenes/bsdf_thindielectric_glass.xml",
        "docs/scenes/bsdf_roughplastic_ggx.xml",
        "docs/scenes/texture_checkerboard.xml",
        "docs/scenes/sensor_thinlens.xml",
        "docs/scenes/shape_ply_bunny.xml",
        "docs/scenes/emitter_spot_no_texture.xml",
    ]
    .map(|f| (mitsuba_scene(f), None));
    let own =
        |f: &str| (std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(f), Some("24"));
    let scenes = mitsuba.into_iter().chain(["caustic-sphere.xml", "glasses.xml", "lightguide.xml"].map(own));
    for (i, (file, res)) in scenes.enumerate() {
        let what = file.file_name().unwrap().to_string_lossy().to_string();
        let defined = match res {
            Some(r) => defines(&[("spp", "16"), ("res", r)]),
            None => defines(&[("spp", "16")]),
        };
        let mut scene = caustic::load::load_scene(&file, &defined).unwrap_or_else(|e| panic!("{e:#}"));
        let (w, h) = (scene.sensor.width, scene.sensor.height);
        if res.is_none() {
            scene.sensor.crop =
                Some(caustic::scene::Crop { x: w / 2 - 12, y: h / 2 - 12, width: 24, height: 24 });
        }
        let seed = 200 + 2 * i as u32;
        scene.integrator.kind = IntegratorKind::Path;
        // The seed scenes' caustics reach path tracing rarely: at 1024 spp its pixels there lack the
        // rare bright paths, and two of three seeds put a glasses pixel past |z| 5 against bdpt.
        let path_spp = if res.is_some() { 4096 } else { 1024 };
        let path = render_scene(&scene, BackendChoice::Cpu, path_spp, seed + 1);
        scene.integrator.kind = IntegratorKind::Bdpt;
        // Under an environment alone `path`'s kernel would render bdpt (`buffers::kernel_kind`):
        // bdpt's own is the one under test.
        scene.integrator.own_kernel = true;
        let bdpt = render_replicated(&scene, 256, seed);
        assert_agrees("bdpt", &what, &bdpt, &path);
    }
}

/// `ibpt`, `bdpt` and `vcm` in a scene where no light path can start (an environment, a sun) are
/// path tracing, and `path`'s kernel renders them; a finite emitter beside the sky, or `own_kernel`,
/// keeps their own; a scene they refuse stays refused.
#[test]
fn without_a_light_path_bdpt_is_rendered_by_paths_kernel() {
    use caustic_kernel::layout::{INTEGRATOR_BDPT, INTEGRATOR_IBPT, INTEGRATOR_PATH, INTEGRATOR_VCM};
    let sky = r#"<emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>"#;
    let sun = r#"<emitter type="directional"><vector name="direction" x="0.2" y="0.3" z="-1"/><rgb name="irradiance" value="2"/></emitter>"#;
    let lamp_and_sky = format!("{}{sky}", EMITTERS[0].1);
    let kernel = |integrator: &str, emitters: &str, own: bool| {
        let mut scene = load_xml(&corner(integrator, emitters, "5", ROUGH_PLASTIC), "kernel-kind");
        scene.integrator.own_kernel = own;
        caustic::prepare::buffers::build(&scene).unwrap().params.integrator
    };
    for (integrator, own_kernel) in
        [("ibpt", INTEGRATOR_IBPT), ("bdpt", INTEGRATOR_BDPT), ("vcm", INTEGRATOR_VCM)]
    {
        assert_eq!(kernel(integrator, sky, false), INTEGRATOR_PATH, "{integrator} under a sky");
        assert_eq!(
            kernel(integrator, &format!("{sky}{sun}"), false),
            INTEGRATOR_PATH,
            "{integrator}, sky and sun"
        );
        assert_eq!(kernel(integrator, sky, true), own_kernel, "{integrator}, own kernel");
        assert_eq!(kernel(integrator, &lamp_and_sky, false), own_kernel, "{integrator}, a lamp and a sky");
        for (_, emitter) in EMITTERS {
            assert_eq!(kernel(integrator, emitter, false), own_kernel, "{integrator}: {emitter}");
        }
    }
    let ortho = corner("bdpt", sky, "5", ROUGH_PLASTIC).replace(
        r#"<sensor type="perspective">
        <float name="fov" value="50"/>"#,
        r#"<sensor type="orthographic">"#,
    );
    let scene = load_xml(&ortho, "kernel-kind-ortho");
    let error = format!("{:#}", caustic::prepare::buffers::build(&scene).map(|_| ()).expect_err("refused"));
    assert!(error.contains("orthographic sensor is not supported"), "{error}");
}

/// What `bdpt` does not render is refused with the file and line where it can be named: a
/// `directionalarea` emitter, the orthographic camera.
#[test]
fn bdpt_refuses_what_it_does_not_render() {
    let directional = r#"<shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1.9"/></transform>
            <emitter type="directionalarea"><rgb name="radiance" value="12"/></emitter></shape>"#;
    let ortho = corner("bdpt", EMITTERS[0].1, "5", ROUGH_PLASTIC).replace(
        r#"<sensor type="perspective">
        <float name="fov" value="50"/>"#,
        r#"<sensor type="orthographic">"#,
    );
    let cases = [
        (corner("bdpt", directional, "5", ROUGH_PLASTIC), "not by bdpt", ".xml:"),
        (ortho, "orthographic sensor is not supported", "bdpt"),
    ];
    for (i, (xml, expected, location)) in cases.iter().enumerate() {
        let result = try_load_xml(xml, &format!("bdpt-refuse-{i}"), &[])
            .and_then(|scene| caustic::prepare::buffers::build(&scene).map(|_| ()));
        let error = format!("{:#}", result.expect_err(expected));
        println!("case {i}: {error}");
        assert!(error.contains(expected), "case {i}: {error}");
        assert!(error.contains(location), "case {i} says nowhere: {error}");
    }
}

/// The GPU runs the same kernel: same seed, the same image to float rounding (GPU compilers may fuse
/// differently, which moves a few paths).
#[test]
fn bdpt_gpu_matches_cpu() {
    let scene = load_xml(&corner("bdpt", EMITTERS[0].1, "5", ROUGH_PLASTIC), "bdpt-gpu-cpu");
    let cpu = render_scene(&scene, BackendChoice::Cpu, 2, 5);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 2, 5);
    let max_diff = max_abs_difference(&cpu, &gpu);
    let total: f64 = cpu.rgb.iter().flatten().map(|&c| c as f64).sum();
    println!("bdpt GPU vs CPU: max |difference| {max_diff:e}, image sum {total:.4}");
    assert!(total > 0.1, "the image is dark");
    assert!(max_diff < 1e-3, "GPU and CPU BDPT differ by {max_diff}");
}
