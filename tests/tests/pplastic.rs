//! Mitsuba's `pplastic` (unpolarized) in whole images and in the loader: three spheres (defaults with a
//! coloured base, an anisotropic GGX coat with a tinted specular, a rough coat over a checkerboard)
//! against Mitsuba 3.9.1's scalar_rgb render on both backends, with a negative control; Mitsuba's
//! defaults and refusals, with file and line. (The BSDF itself: `kernel/tests/bsdf_pplastic.rs`.)
use caustic::backend::BackendChoice;
use caustic_kernel::bsdf::pplastic::PARAM_SPECULAR_WEIGHT;
use caustic_kernel::layout::*;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 65536.0;

fn check(choice: BackendChoice, red: &str, spp: u32) -> (f64, f64) {
    let label = format!("pplastic spheres, the first one's red {red}");
    against_mitsuba_reference(
        "pplastic.xml",
        &[("red", red)],
        "pplastic.exr",
        REFERENCE_SPP,
        choice,
        spp,
        5,
        &label,
    )
}

#[test]
fn pplastic_spheres_match_mitsuba() {
    // Lavapipe is several times slower than the CPU backend: fewer samples there.
    for (choice, spp) in [(BackendChoice::Cpu, 1024), (BackendChoice::Gpu, 256)] {
        let (pass, z) = check(choice, "0.8", spp);
        assert_agrees_with_reference((pass, z), &format!("{choice:?}"));
    }
    // Negative control: the first sphere's red 0.6 for 0.8 must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "0.6", 1024);
    assert_disagrees_with_reference((pass, z), "red 0.6 for 0.8");
}

fn pplastic(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"pplastic\">{body}</bsdf>\n</shape></scene>")
}

/// Mitsuba's defaults: Beckmann, α 0.1, polypropylene over air, diffuse 0.5, specular 1, so the
/// glossy lobe is sampled with probability 1 / (0.5 + 1).
#[test]
fn defaults_are_mitsubas() {
    let m = load_xml(&pplastic(""), "pplastic-defaults").materials[0];
    assert_eq!(m.kind, BSDF_PPLASTIC);
    assert!(m.flags & MATERIAL_BECKMANN != 0 && (m.alpha_u, m.alpha_v) == (0.1, 0.1));
    assert!((m.eta - 1.49 / 1.000277).abs() < 1e-5, "eta {}", m.eta);
    assert_eq!((m.reflectance[0], m.specular_reflectance[0]), (0.5, 1.0));
    assert!((m.params[PARAM_SPECULAR_WEIGHT] - 1.0 / 1.5).abs() < 1e-6);
}

/// Mitsuba refuses `eta` with `int_ior`/`ext_ior` and equal indices; caustic also a non-positive
/// `eta` and two black reflectances; each names the line.
#[test]
fn pplastic_refuses_with_file_and_line() {
    for (body, words) in [
        (r#"<float name="eta" value="1.4"/><float name="int_ior" value="1.5"/>"#, "not both"),
        (r#"<float name="eta" value="1.4"/><float name="ext_ior" value="1.1"/>"#, "not both"),
        (r#"<float name="int_ior" value="1.2"/><float name="ext_ior" value="1.2"/>"#, "differ"),
        (r#"<float name="eta" value="-1"/>"#, "positive"),
        (
            r#"<rgb name="diffuse_reflectance" value="0"/><rgb name="specular_reflectance" value="0"/>"#,
            "black",
        ),
    ] {
        let e = format!("{:#}", try_load_xml(&pplastic(body), "pplastic-refused", &[]).expect_err(body));
        assert!(e.contains("scene.xml:3:") && e.contains(words), "{body}: {e}");
    }
}
