//! Textured parameters read per hit (`Material::param_texture`), against Mitsuba 3.9.1: the
//! `specular_transmittance` of `dielectric`, `roughdielectric` and `thindielectric`, the `eta` and `k`
//! of `conductor` and `roughconductor`, and `pplastic`'s `eta` (`tests/data/textured_params.xml`; the
//! bitmaps and the reference `textured_params.exr` are written by `textured_params.py`), per-pixel
//! z-test and mean-luminance z-score on the CPU and the GPU backend. Negative controls: each texture
//! replaced by its mean (what caustic did before) must be caught.
use caustic::backend::BackendChoice;
use caustic_kernel::layout::*;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

/// The transmittance checks' mean, and the `tex` define of the bitmaps' 1x1 means.
const MEAN_T: (&str, &str) = ("0.6, 0.525, 0.575", "0.6, 0.525, 0.575");
const MEAN_BITMAPS: (&str, &str) = ("tex", "mean");

fn check(choice: BackendChoice, spp: u32, defines: &[(&str, &str)], label: &str) -> (f64, f64) {
    let (scene, reference) = ("textured_params.xml", "textured_params.exr");
    against_mitsuba_reference(scene, defines, reference, REFERENCE_SPP, choice, spp, 11, label)
}

#[test]
fn textured_parameters_match_mitsuba_on_the_cpu() {
    assert_agrees_with_reference(check(BackendChoice::Cpu, 1024, &[], "textured parameters"), "CPU");
    let (t0, t1) = MEAN_T;
    let means = check(BackendChoice::Cpu, 1024, &[("t0", t0), ("t1", t1)], "mean transmittance");
    assert_disagrees_with_reference(means, "the transmittance's mean for its checks");
    let means = check(BackendChoice::Cpu, 1024, &[MEAN_BITMAPS], "mean eta and k");
    assert_disagrees_with_reference(means, "the means of eta and k for their checks");
}

#[test]
fn textured_parameters_match_mitsuba_on_the_gpu() {
    assert_agrees_with_reference(check(BackendChoice::Gpu, 256, &[], "textured parameters"), "GPU");
    let (t0, t1) = MEAN_T;
    let means = check(BackendChoice::Gpu, 256, &[("t0", t0), ("t1", t1), MEAN_BITMAPS], "all means");
    assert_disagrees_with_reference(means, "every texture's mean for its checks");
}

/// The loader keeps each texture in the slot the kernel reads (and no longer counts a substitution:
/// `--strict` accepts the scene).
#[test]
fn textures_go_to_their_slots() {
    let xml = r#"<scene version="3.0.0">
        <shape type="sphere"><bsdf type="dielectric"><texture type="checkerboard" name="specular_transmittance"/></bsdf></shape>
        <shape type="sphere"><bsdf type="conductor">
            <texture type="checkerboard" name="eta"/><texture type="checkerboard" name="k"/></bsdf></shape>
        <shape type="sphere"><bsdf type="pplastic"><texture type="checkerboard" name="eta">
            <float name="color0" value="1.2"/><float name="color1" value="0.9"/></texture></bsdf></shape>
        </scene>"#;
    let scene = load_xml(xml, "textured-params-slots");
    let m = &scene.materials;
    assert_eq!((m[0].kind, m[0].param_texture, m[0].reflectance_texture), (BSDF_DIELECTRIC, 0, NONE));
    assert_eq!((m[1].kind, m[1].param_texture, m[1].reflectance_texture), (BSDF_CONDUCTOR, 1, 2));
    // pplastic's eta is read as a number: the loader's grey copy of the checkerboard (`scalar_texture`).
    assert_eq!((m[2].kind, m[2].param_texture), (BSDF_PPLASTIC, 4));
    assert!((m[2].eta - 1.05).abs() < 1e-6, "mean eta {}", m[2].eta);
    let strict = try_load_xml_strict(xml, "textured-params-strict");
    if let Err(e) = strict {
        panic!("--strict refused textured parameters that are supported: {e:#}");
    }
}

/// A pplastic `eta` texture with a value that is not positive is refused, naming the line.
#[test]
fn a_pplastic_eta_texture_must_be_positive() {
    let xml = r#"<scene version="3.0.0"><shape type="sphere"><bsdf type="pplastic">
        <texture type="checkerboard" name="eta"><float name="color0" value="1.5"/><float name="color1" value="0"/></texture>
        </bsdf></shape></scene>"#;
    let Err(e) = try_load_xml(xml, "pplastic-eta-zero", &[]) else { panic!("a zero eta was accepted") };
    let message = format!("{e:#}");
    assert!(message.contains("positive") && message.contains(":1"), "{message}");
}
