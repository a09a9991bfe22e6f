//! Mitsuba's `principled` BSDF in whole images and in the loader: four spheres of different
//! parameter sets (coat and sheen, tinted metal, rough glass, textured base colour and roughness)
//! against Mitsuba 3.9.1's render on both backends, with a negative control; Mitsuba's defaults and
//! refusals, with file and line. (The BSDF itself: `kernel/tests/bsdf_principled.rs`.)
use caustic::backend::BackendChoice;
use caustic_kernel::bsdf::principled::PrincipledParams;
use caustic_kernel::layout::*;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 65536.0;

fn check(choice: BackendChoice, red: &str) -> (f64, f64) {
    let label = format!("principled spheres, the first one's red {red}");
    // Lavapipe is several times slower than the CPU backend here: fewer samples there.
    let spp = if choice == BackendChoice::Cpu { 1024 } else { 256 };
    against_mitsuba_reference(
        "principled.xml",
        &[("red", red)],
        "principled.exr",
        REFERENCE_SPP,
        choice,
        spp,
        5,
        &label,
    )
}

#[test]
fn principled_spheres_match_mitsuba() {
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        let (pass, z) = check(choice, "0.8");
        assert_agrees_with_reference((pass, z), &format!("{choice:?}"));
    }
    // Negative control: the first sphere's base colour red 0.6 for 0.8 must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "0.6");
    assert_disagrees_with_reference((pass, z), "red 0.6 for 0.8");
}

fn principled(body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"principled\">{body}</bsdf>\n</shape></scene>"
    )
}

/// Mitsuba's defaults (base 0.5, roughness 0.5, specular 0.5 = η 1.5, sampling rates 1) and its
/// `eta` nudges: a transmissive material's `eta` 1 becomes 1.001 and its `specular` 0 becomes 1e-3.
#[test]
fn defaults_and_nudges_are_mitsubas() {
    let m = load_xml(&principled(""), "principled-defaults").materials[0];
    assert_eq!(m.kind, BSDF_PRINCIPLED);
    assert_eq!((m.reflectance[0], m.alpha_u, m.alpha_v, m.specular_reflectance[0]), (0.5, 0.5, 0.0, 0.0));
    assert!((m.eta - 1.5).abs() < 1e-6, "default eta {}", m.eta);
    let p = PrincipledParams::unpack(&m);
    assert_eq!((p.spec_rate, p.clearcoat_rate, p.diffuse_rate), (1.0, 1.0, 1.0));
    assert_eq!((p.spec_trans, p.clearcoat, p.sheen, p.flatness), (0.0, 0.0, 0.0, 0.0));
    let eta = |body: &str| load_xml(&principled(body), "principled-eta").materials[0].eta;
    assert_eq!(eta(r#"<float name="eta" value="1"/>"#), 1.0);
    assert_eq!(eta(r#"<float name="eta" value="1"/><float name="spec_trans" value="0.5"/>"#), 1.001);
    assert_eq!(eta(r#"<float name="specular" value="0"/>"#), 1.0);
    let nudged = eta(r#"<float name="specular" value="0"/><float name="spec_trans" value="0.5"/>"#);
    assert_eq!(nudged, caustic_kernel::bsdf::principled::eta_from_specular(1e-3));
}

/// What Mitsuba refuses is refused, naming the file and line: `eta` with `specular`; a transmissive
/// principled inside `twosided`. A textured weight is read as a texture, not a substitution.
#[test]
fn principled_refuses_what_mitsuba_refuses() {
    let both = principled(r#"<float name="eta" value="1.5"/><float name="specular" value="0.5"/>"#);
    let e = format!("{:#}", try_load_xml(&both, "principled-both", &[]).expect_err("eta and specular"));
    assert!(e.contains("scene.xml:3:") && e.contains("not both"), "{e}");
    let twosided = r#"<scene version="3.0.0"><shape type="sphere"><bsdf type="twosided">
        <bsdf type="principled"><float name="spec_trans" value="0.5"/></bsdf></bsdf></shape></scene>"#;
    let e = format!("{:#}", try_load_xml(twosided, "principled-twosided", &[]).expect_err("twosided"));
    assert!(e.contains("scene.xml:1:") && e.contains("transmissive"), "{e}");
    // Without transmission twosided is fine, as in Mitsuba (what Blender exporters write).
    let opaque = twosided.replace("spec_trans", "sheen");
    let materials = load_xml(&opaque, "principled-twosided-ok").materials;
    assert!(materials.iter().any(|m| m.kind == BSDF_PRINCIPLED && m.flags & MATERIAL_TWO_SIDED != 0));

    // A textured weight beyond the record's slots is read, not replaced (`principled_weights.rs`):
    // no substitution, so `--strict` loads it.
    let textured = principled(
        r#"<texture type="checkerboard" name="sheen"><float name="color0" value="0.2"/><float name="color1" value="0.6"/></texture>"#,
    );
    let scene = try_load_xml_strict(&textured, "principled-sheen").expect("--strict loads a textured sheen");
    let m = scene.materials[0];
    assert!((PrincipledParams::unpack(&m).sheen - 0.4).abs() < 1e-6, "the record keeps the mean sheen");
    let sheen_slot = scene.weight_tables[m.table as usize][2];
    assert!(sheen_slot >= 0.0, "sheen's texture is listed: {:?}", scene.weight_tables);
}
