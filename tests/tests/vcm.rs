//! Vertex connection and merging (`vcm`) against path tracing: the same image, statistically, at the
//! default radius under each emitter kind and through Dirac lobes; on a caustic seen through glass
//! (light → glass → floor → glass → camera), the paths that only its merges make cheaply, its error
//! falls as the radius shrinks from pass to pass, and does not without the shrinking; no NaN or Inf
//! on stiff cases or at extreme radii; what it refuses; GPU against CPU.
use caustic::backend::BackendChoice;
use caustic::output::compare::compare;
use caustic_tests::corner::*;
use caustic_tests::replicas::image_mean;
use caustic_tests::*;

/// `corner` under `vcm` with the integrator's extra properties `merging` (radius, alpha).
fn with_merging(xml: String, merging: &str) -> String {
    xml.replace(r#"<integrator type="vcm">"#, &format!(r#"<integrator type="vcm">{merging}"#))
}

/// A small bright lamp above a glass sphere that focuses it onto the floor, the whole seen through a
/// glass slab: the caustic reaches the camera only through Dirac lobes on both sides.
fn caustic_through_glass(kind: &str) -> String {
    let light = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.5" y="0.3" z="1.6"/>
            <emitter type="area"><rgb name="radiance" value="400"/></emitter></shape>"#;
    let slab = r#"<shape type="cube"><transform name="to_world"><scale x="1.2" y="0.05" z="1.2"/><translate y="-1.6" z="0.8"/></transform>
            <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>"#;
    corner(kind, &format!("{light}{slab}"), "-1", GLASS)
}

#[test]
fn vcm_and_path_agree_on_every_emitter_kind() {
    for (i, (name, emitter)) in EMITTERS.into_iter().enumerate() {
        agrees_with_path(
            "vcm",
            name,
            |k| corner(k, emitter, "5", ROUGH_PLASTIC),
            256,
            1024,
            110 + 2 * i as u32,
        );
    }
}

/// Glass and a mirror at unbounded depth: merges only at the diffuse walls, never at a Dirac vertex.
#[test]
fn vcm_and_path_agree_through_dirac_lobes() {
    let mirror = r#"<bsdf type="conductor"><string name="material" value="none"/></bsdf>"#;
    for (name, bsdf) in [("glass", GLASS), ("mirror", mirror)] {
        agrees_with_path("vcm", name, |k| corner(k, EMITTERS[1].1, "-1", bsdf), 256, 2048, 130);
    }
}

/// The caustic seen through glass agrees with path tracing at the default radius.
#[test]
fn vcm_renders_a_caustic_seen_through_glass() {
    agrees_with_path("vcm", "caustic through glass", caustic_through_glass, 512, 8192, 150);
}

/// Consistency: with a wide first radius (0.4 in a 2.6-unit scene) the merged estimate is blurred;
/// as the radius shrinks (`alpha` 0.5: its square as the passes' inverse square root) the error
/// against path tracing falls with the passes, and with the radius held (`alpha` 1, the negative
/// control) it stays many times larger.
#[test]
fn vcm_converges_as_its_radius_shrinks() {
    let reference = render_scene(
        &load_xml(&caustic_through_glass("path"), "vcm-consistency-ref"),
        BackendChoice::Cpu,
        32768,
        1,
    );
    let error = |alpha: &str, passes: u32| {
        let merging = format!(r#"<float name="radius" value="0.4"/><float name="alpha" value="{alpha}"/>"#);
        let xml = with_merging(caustic_through_glass("vcm"), &merging);
        let film =
            render_scene(&load_xml(&xml, &format!("vcm-consistency-{alpha}")), BackendChoice::Cpu, passes, 2);
        assert_eq!(film.invalid_samples, 0, "alpha {alpha}: NaN or infinite samples");
        compare(&film, &reference, 1.0).expect("same size").rel_mse
    };
    let (early, late, held) = (error("0.5", 64), error("0.5", 4096), error("1", 4096));
    println!(
        "relative MSE: alpha 0.5 at 64 passes {early:.3e}, at 4096 {late:.3e}; alpha 1 at 4096 {held:.3e}"
    );
    assert!(late < 0.5 * early, "the error did not fall with the passes: {early:.3e} then {late:.3e}");
    assert!(
        held > 4.0 * late,
        "a radius held fixed converged as well as a shrinking one ({held:.3e} against {late:.3e})"
    );
}

/// Stiff cases (a lamp sealed in glass, index-matched glass, a camera inside glass, and inside glass
/// whose index runs from 2.5 to 1.7 over 380-780 nm) and the radius at its extremes (a millionth and
/// ten times the scene): finite samples, and agreement with path tracing where the radius is small.
#[test]
fn vcm_stiff_cases_and_extreme_radii_stay_finite() {
    let lamp_in_glass = r#"<shape type="sphere"><float name="radius" value="0.05"/><point name="center" x="0.3" y="0.2" z="0.4"/>
            <emitter type="area"><rgb name="radiance" value="50"/></emitter></shape>"#;
    agrees_with_path(
        "vcm",
        "lamp sealed in glass",
        |k| corner(k, lamp_in_glass, "-1", GLASS),
        256,
        4096,
        170,
    );
    let matched = r#"<bsdf type="dielectric"><float name="int_ior" value="1.000001"/><float name="ext_ior" value="1"/></bsdf>"#;
    agrees_with_path(
        "vcm",
        "index-matched glass",
        |k| corner(k, EMITTERS[0].1, "8", matched),
        256,
        2048,
        172,
    );
    let inside = |k: &str| {
        corner(k, EMITTERS[0].1, "8", r#"<bsdf type="roughdielectric"><float name="alpha" value="0.05"/><float name="int_ior" value="1.33"/></bsdf>"#)
            .replace(r#"origin="0, -3, 1.6""#, r#"origin="0.3, 0.2, 0.45""#)
    };
    agrees_with_path("vcm", "camera inside glass", inside, 256, 4096, 174);
    let dispersive = |k: &str| {
        corner(k, EMITTERS[0].1, "8", r#"<bsdf type="roughdielectric"><float name="alpha" value="0.05"/><float name="int_ior" value="1.9"/><float name="abbe_number" value="3"/></bsdf>"#)
            .replace(r#"origin="0, -3, 1.6""#, r#"origin="0.3, 0.2, 0.45""#)
    };
    agrees_with_path("vcm", "camera inside glass of extreme dispersion", dispersive, 256, 4096, 178);
    let tiny = |k: &str| {
        with_merging(corner(k, EMITTERS[0].1, "5", ROUGH_PLASTIC), r#"<float name="radius" value="1e-6"/>"#)
    };
    agrees_with_path("vcm", "radius 1e-6", tiny, 256, 1024, 176);
    for radius in ["26", "1e-30"] {
        let xml = with_merging(
            caustic_through_glass("vcm"),
            &format!(r#"<float name="radius" value="{radius}"/>"#),
        );
        let film = render_scene(&load_xml(&xml, "vcm-extreme-radius"), BackendChoice::Cpu, 16, 3);
        let finite = film.rgb.iter().flatten().all(|c| c.is_finite());
        println!(
            "radius {radius}: image mean {:.4}, invalid samples {}",
            image_mean(&film),
            film.invalid_samples
        );
        assert!(finite && film.invalid_samples == 0, "radius {radius}: NaN or infinite samples");
    }
}

/// Refused with the file and line where it can be named: a `directionalarea` emitter, a radius that
/// is not positive, an `alpha` outside (0, 1], a `connection_share` outside [0, 1], a
/// `light_tracing_share` or `connection_rate` outside (0, 1].
#[test]
fn vcm_refuses_what_it_does_not_render() {
    let directional = r#"<shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1.9"/></transform>
            <emitter type="directionalarea"><rgb name="radiance" value="12"/></emitter></shape>"#;
    let plain = corner("vcm", EMITTERS[0].1, "5", ROUGH_PLASTIC);
    let cases = [
        (corner("vcm", directional, "5", ROUGH_PLASTIC), "not by vcm"),
        (with_merging(plain.clone(), r#"<float name="radius" value="0"/>"#), "radius must be positive"),
        (with_merging(plain.clone(), r#"<float name="alpha" value="1.5"/>"#), "alpha must be in (0, 1]"),
        (
            with_merging(plain.clone(), r#"<float name="connection_share" value="-0.5"/>"#),
            "connection_share must be from 0 to 1",
        ),
        (
            with_merging(plain.clone(), r#"<float name="light_tracing_share" value="0"/>"#),
            "light_tracing_share must be above 0 and at most 1",
        ),
        (
            with_merging(plain.clone(), r#"<float name="connection_rate" value="1.5"/>"#),
            "connection_rate must be above 0 and at most 1",
        ),
    ];
    for (i, (xml, expected)) in cases.iter().enumerate() {
        let result = try_load_xml(xml, &format!("vcm-refuse-{i}"), &[])
            .and_then(|scene| caustic::prepare::buffers::build(&scene).map(|_| ()));
        let error = format!("{:#}", result.expect_err(expected));
        println!("case {i}: {error}");
        assert!(error.contains(expected) && error.contains(".xml:"), "case {i}: {error}");
    }
}

/// The GPU runs the same kernel: same seed, the same image to float rounding (the merges add in
/// the order their lists were linked, which the GPU's atomics choose).
#[test]
fn vcm_gpu_matches_cpu() {
    let scene = load_xml(&corner("vcm", EMITTERS[0].1, "5", GLASS), "vcm-gpu-cpu");
    // 64 spp: passes of several one-sample dispatches (at most 64 / `MIN_BATCHES` for the variance),
    // each with its own radius, in one submission.
    let cpu = render_scene(&scene, BackendChoice::Cpu, 64, 5);
    let gpu = render_scene(&scene, BackendChoice::Gpu, 64, 5);
    let max_diff = max_abs_difference(&cpu, &gpu);
    let total: f64 = cpu.rgb.iter().flatten().map(|&c| c as f64).sum();
    println!("vcm GPU vs CPU: max |difference| {max_diff:e}, image sum {total:.4}");
    assert!(total > 0.1, "the image is dark");
    assert!(max_diff < 1e-3, "GPU and CPU VCM differ by {max_diff}");
}
