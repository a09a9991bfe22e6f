//! Textured roughness (`alpha`, `alpha_u`, `alpha_v` of rough conductors and dielectrics) against
//! Mitsuba 3.9.1: checkerboard roughness on a conductor floor, a dielectric sphere (coloured checks,
//! which Mitsuba reads as their channel mean) and a conductor card with textured `alpha_u` and
//! `alpha_v` (equal, so that the orientation of caustic's shading frame does not matter)
//! (`tests/data/rough_textures.xml`; the reference `rough_textures.exr` is written by
//! `rough_textures.py`), per-pixel z-test and mean-luminance z-score on the CPU and the GPU backend,
//! with a negative control (the floor's rough checks at 0.3 for 0.4).
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(choice: BackendChoice, spp: u32, alpha1: &str) -> (f64, f64) {
    let label = format!("rough textures, alpha1 {alpha1}");
    let (scene, reference) = ("rough_textures.xml", "rough_textures.exr");
    against_mitsuba_reference(scene, &[("alpha1", alpha1)], reference, REFERENCE_SPP, choice, spp, 7, &label)
}

#[test]
fn textured_roughness_matches_mitsuba_on_the_cpu() {
    let (pass, z) = check(BackendChoice::Cpu, 1024, "0.4");
    assert_agrees_with_reference((pass, z), "textured roughness");
    let (pass, z) = check(BackendChoice::Cpu, 1024, "0.3");
    assert_disagrees_with_reference((pass, z), "alpha 0.3 for 0.4");
}

#[test]
fn textured_roughness_matches_mitsuba_on_the_gpu() {
    let (pass, z) = check(BackendChoice::Gpu, 256, "0.4");
    assert_agrees_with_reference((pass, z), "textured roughness");
}

/// roughplastic's precomputed table holds one roughness: a textured alpha is replaced by its mean and
/// counted as a substitution (which `--strict` refuses).
#[test]
fn textured_roughplastic_alpha_is_a_substitution() {
    let xml = r#"<scene version="3.0.0"><shape type="sphere"><bsdf type="roughplastic">
        <texture type="checkerboard" name="alpha"><float name="color0" value="0.1"/><float name="color1" value="0.3"/></texture>
        </bsdf></shape></scene>"#;
    let scene = load_xml(xml, "roughplastic-alpha");
    let m = &scene.materials[0];
    assert_eq!(
        (m.alpha_u_texture, m.alpha_v_texture),
        (caustic_kernel::layout::NONE, caustic_kernel::layout::NONE)
    );
    assert!((m.alpha_u - 0.2).abs() < 1e-6, "mean alpha {}", m.alpha_u);
    let strict = try_load_xml_strict(xml, "rough-textures-strict");
    let Err(e) = strict else { panic!("--strict accepted a substituted roughplastic alpha") };
    let message = format!("{e:#}");
    assert!(message.contains("roughplastic"), "{message}");
}
