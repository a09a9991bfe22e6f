//! Mitsuba's `principledthin` in whole images and in the loader: three sheets (a leaf with diffuse
//! transmission, a glossy film, a textured sheet with every lobe) against Mitsuba 3.9.1's render on
//! both backends, with a negative control; Mitsuba's defaults and refusals, with file and line. (The
//! BSDF itself: `kernel/tests/bsdf_principled_thin.rs`.)
use caustic::backend::BackendChoice;
use caustic_kernel::bsdf::principled_thin::ThinParams;
use caustic_kernel::layout::*;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 65536.0;

fn check(choice: BackendChoice, green: &str, spp: u32) -> (f64, f64) {
    let label = format!("principledthin sheets, the leaf's green {green}");
    against_mitsuba_reference(
        "principled_thin.xml",
        &[("green", green)],
        "principled_thin.exr",
        REFERENCE_SPP,
        choice,
        spp,
        5,
        &label,
    )
}

#[test]
fn thin_sheets_match_mitsuba() {
    // Lavapipe is several times slower than the CPU backend: fewer samples there.
    for (choice, spp) in [(BackendChoice::Cpu, 1024), (BackendChoice::Gpu, 256)] {
        let (pass, z) = check(choice, "0.7", spp);
        assert_agrees_with_reference((pass, z), &format!("{choice:?}"));
    }
    // Negative control: the leaf's green 0.5 for 0.7 must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "0.5", 1024);
    assert_disagrees_with_reference((pass, z), "green 0.5 for 0.7");
}

fn thin(body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"principledthin\">{body}</bsdf>\n</shape></scene>"
    )
}

/// Mitsuba's defaults: base 0.5, roughness 0.5, eta 1.5, every other weight 0, sampling rates 1.
#[test]
fn defaults_are_mitsubas() {
    let m = load_xml(&thin(""), "thin-defaults").materials[0];
    assert_eq!(m.kind, BSDF_PRINCIPLED_THIN);
    assert_eq!((m.reflectance[0], m.alpha_u, m.alpha_v, m.eta), (0.5, 0.5, 0.0, 1.5));
    let p = ThinParams::unpack(&m);
    assert_eq!(
        (p.spec_refl_rate, p.spec_trans_rate, p.diff_refl_rate, p.diff_trans_rate),
        (1.0, 1.0, 1.0, 1.0)
    );
    assert_eq!((p.spec_trans, p.diff_trans, p.sheen, p.flatness, p.spec_tint), (0.0, 0.0, 0.0, 0.0, 0.0));
    let given = load_xml(
        &thin(r#"<float name="diff_trans" value="1.5"/><float name="eta" value="1.3"/>"#),
        "thin-given",
    );
    let m = given.materials[0];
    assert_eq!((ThinParams::unpack(&m).diff_trans, m.eta), (1.5, 1.3));
}

/// Mitsuba refuses `principledthin` inside `twosided` (it always has a transmission lobe); caustic
/// refuses what would make no sense (all sampling rates zero, a non-positive `eta`), naming the line;
/// a textured weight is read as a texture, no substitution.
#[test]
fn principled_thin_refuses_with_file_and_line() {
    let twosided = r#"<scene version="3.0.0"><shape type="sphere">
        <bsdf type="twosided"><bsdf type="principledthin"/></bsdf></shape></scene>"#;
    let e = format!("{:#}", try_load_xml(twosided, "thin-twosided", &[]).expect_err("twosided"));
    assert!(e.contains("scene.xml:2:") && e.contains("transmissive"), "{e}");
    let rates =
        ["specular_reflectance", "specular_transmittance", "diffuse_reflectance", "diffuse_transmittance"]
            .map(|r| format!(r#"<float name="{r}_sampling_rate" value="0"/>"#))
            .concat();
    let e = format!("{:#}", try_load_xml(&thin(&rates), "thin-rates", &[]).expect_err("rates"));
    assert!(e.contains("scene.xml:3:") && e.contains("sampling rates"), "{e}");
    let e = format!(
        "{:#}",
        try_load_xml(&thin(r#"<float name="eta" value="0"/>"#), "thin-eta", &[]).expect_err("eta")
    );
    assert!(e.contains("scene.xml:3:") && e.contains("eta"), "{e}");

    // A textured weight is read, not replaced (`principled_weights.rs`): `--strict` loads it.
    let textured = thin(
        r#"<texture type="checkerboard" name="diff_trans"><float name="color0" value="0.2"/><float name="color1" value="0.6"/></texture>"#,
    );
    let scene =
        try_load_xml_strict(&textured, "thin-diff-trans").expect("--strict loads a textured diff_trans");
    let m = scene.materials[0];
    assert!((ThinParams::unpack(&m).diff_trans - 0.4).abs() < 1e-6, "the record keeps the mean diff_trans");
    assert!(scene.weight_tables[m.table as usize][5] >= 0.0, "diff_trans's texture is listed");
}
