//! Textured emitters against Mitsuba 3.9.1: `area` with a textured `radiance` (a bitmap nested, a
//! checkerboard by `<ref>` on a disk and a sphere), `spot` with a `texture`, `projector`, and
//! `directionalarea` (`tests/data/emitter_*.xml`; `emitters.py` writes the textures and the
//! references). The first three are rendered with max_depth 2, where path, direct, ptracer and IBPT
//! all estimate the reference's image (`directionalarea` under light tracing alone):
//! per-pixel z-test and mean-luminance z-score, on the CPU and the GPU backend, with a negative
//! control each (the image replaced by a uniform one of the same mean must fail). Also: the
//! specialization bit is set only for scenes with textured emission, and bad input is refused with
//! file and line.
//!
//! Besides the negative controls, the comparisons catch these mistakes (measured on the CPU, 1024 spp,
//! one seed; pixels passing, 99% needed): next-event estimation without the texture 62.6% (path); a
//! triangle's barycentrics swapped in the emitting point's uv 98.7% (path) and 82% (ptracer); the
//! spot image's v flipped 72%; the projector image's u flipped 91% (path and ptracer alike).
use caustic::backend::BackendChoice;
use caustic_kernel::features;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 8192.0;

fn check(scene: &str, defines_: &[(&str, &str)], choice: BackendChoice, spp: u32, label: &str) -> (f64, f64) {
    let reference = scene.replace(".xml", ".exr");
    against_mitsuba_reference(scene, defines_, &reference, REFERENCE_SPP, choice, spp, 3, label)
}

fn assert_matches(scene: &str, defines_: &[(&str, &str)], choice: BackendChoice, spp: u32) {
    let label = format!("{scene} {defines_:?}");
    let (pass, z) = check(scene, defines_, choice, spp, &label);
    assert_agrees_with_reference((pass, z), &format!("{label} {choice:?}"));
}

fn assert_caught(scene: &str, defines_: &[(&str, &str)]) {
    let label = format!("{scene} {defines_:?} (negative control)");
    let (pass, z) = check(scene, defines_, BackendChoice::Cpu, 1024, &label);
    assert_disagrees_with_reference((pass, z), &label);
}

#[test]
fn textured_area_emitters_match_mitsuba() {
    let scene = "emitter_area.xml";
    assert_matches(scene, &[], BackendChoice::Cpu, 1024);
    assert_matches(scene, &[], BackendChoice::Gpu, 256);
    assert_caught(scene, &[("radiance", "emitter_area_flat.exr")]);
}

/// What `direct` (its own loop over the strategies), light tracing (emission sampled from a textured
/// emitter, its points connected to the camera) and IBPT carry from a textured area emitter.
#[test]
fn textured_area_emitters_under_every_integrator() {
    for integrator in ["direct", "ptracer", "ibpt"] {
        assert_matches("emitter_area.xml", &[("integrator", integrator)], BackendChoice::Cpu, 1024);
    }
    assert_matches("emitter_area.xml", &[("integrator", "ptracer")], BackendChoice::Gpu, 256);
}

#[test]
fn textured_spots_match_mitsuba() {
    let scene = "emitter_spot.xml";
    assert_matches(scene, &[], BackendChoice::Cpu, 1024);
    assert_matches(scene, &[], BackendChoice::Gpu, 256);
    for integrator in ["ptracer", "ibpt"] {
        assert_matches(scene, &[("integrator", integrator)], BackendChoice::Cpu, 1024);
    }
    assert_caught(scene, &[("texture", "emitter_flat.exr")]);
}

#[test]
fn projectors_match_mitsuba() {
    let scene = "emitter_projector.xml";
    assert_matches(scene, &[], BackendChoice::Cpu, 1024);
    assert_matches(scene, &[], BackendChoice::Gpu, 256);
    for integrator in ["ptracer", "ibpt"] {
        assert_matches(scene, &[("integrator", integrator)], BackendChoice::Cpu, 1024);
    }
    assert_matches(scene, &[("integrator", "ptracer")], BackendChoice::Gpu, 256);
    assert_caught(scene, &[("irradiance", "emitter_flat.exr")]);
}

/// Mitsuba's `directionalarea` (along the normal only, textured or not) under light tracing, which
/// alone carries its light; path tracing renders it black, as Mitsuba's, and IBPT is refused.
#[test]
fn directional_area_emitters_match_mitsuba_light_tracing() {
    let scene = "emitter_directionalarea.xml";
    assert_matches(scene, &[], BackendChoice::Cpu, 1024);
    assert_matches(scene, &[], BackendChoice::Gpu, 256);
    assert_caught(scene, &[("tilt", "0")]);
    let path = caustic::load::load_scene(&test_data(scene), &defines(&[("integrator", "path")])).unwrap();
    let film = render_scene(&path, BackendChoice::Cpu, 16, 1);
    assert!(film.rgb.iter().flatten().all(|&c| c == 0.0), "path tracing saw a directionalarea's light");
    let ibpt = caustic::load::load_scene(&test_data(scene), &defines(&[("integrator", "ibpt")])).unwrap();
    let Err(e) = caustic::prepare::buffers::build(&ibpt) else { panic!("ibpt rendered a directionalarea") };
    let message = format!("{e:#}");
    assert!(message.contains("emitter_directionalarea.xml:") && message.contains("ibpt"), "{message}");
}

/// Only scenes that use textured emission compile its lookups in.
#[test]
fn the_textured_emission_bit_follows_the_scene() {
    let bits = |xml: &str, tag: &str| caustic::prepare::buffers::build(&load_xml(xml, tag)).unwrap().features;
    let plain = r#"<scene version="3.0.0"><shape type="sphere"><emitter type="area"/></shape>
        <emitter type="spot"/><emitter type="projector"/></scene>"#;
    assert!(!features::has(bits(plain, "plain-emitters"), features::TEXTURED_EMISSION));
    let textured = r#"<scene version="3.0.0"><shape type="sphere"><emitter type="area">
        <texture type="checkerboard" name="radiance"/></emitter></shape></scene>"#;
    assert!(features::has(bits(textured, "textured-area"), features::TEXTURED_EMISSION));
    let projector = r#"<scene version="3.0.0"><emitter type="projector">
        <texture type="checkerboard" name="irradiance"/></emitter></scene>"#;
    let f = bits(projector, "textured-projector");
    assert!(features::has(f, features::TEXTURED_EMISSION));
    assert!(features::has(f, features::light(caustic_kernel::layout::LIGHT_PROJECTOR)));
}

/// A missing image, a texture of an unknown type, a constant spot `texture`, a `<ref>` to nothing and
/// a `directionalarea` outside a shape are refused with the file and line.
#[test]
fn bad_emitter_textures_are_refused_with_file_and_line() {
    let cases = [
        (
            r#"<scene version="3.0.0"><shape type="sphere"><emitter type="area">
            <texture type="bitmap" name="radiance"><string name="filename" value="missing.exr"/></texture>
            </emitter></shape></scene>"#,
            "missing.exr",
        ),
        (
            r#"<scene version="3.0.0"><emitter type="projector">
            <texture type="noise" name="irradiance"/></emitter></scene>"#,
            "noise",
        ),
        (
            r#"<scene version="3.0.0"><emitter type="spot">
            <rgb name="texture" value="0.5"/></emitter></scene>"#,
            "spatially varying",
        ),
        (
            r#"<scene version="3.0.0"><shape type="sphere"><emitter type="area">
            <ref name="radiance" id="nothing"/></emitter></shape></scene>"#,
            "nothing",
        ),
        (r#"<scene version="3.0.0"><emitter type="directionalarea"/></scene>"#, "nested in a <shape>"),
    ];
    for (i, (xml, needle)) in cases.iter().enumerate() {
        let Err(e) = try_load_xml(xml, &format!("bad-emitter-texture-{i}"), &[]) else {
            panic!("case {i} loaded")
        };
        let message = format!("{e:#}");
        assert!(message.contains("scene.xml:"), "case {i}: no file and line in: {message}");
        assert!(message.contains(needle), "case {i}: '{needle}' not in: {message}");
    }
}
