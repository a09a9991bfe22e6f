//! Mitsuba's `twosided` with two BSDFs (`caustic_kernel::two_sided`): four squares, each pair's
//! front and back (two diffuse colours; a diffuse and a rough gold), against Mitsuba 3.9.1's render
//! on both backends and with light tracing, IBPT and `direct`, with negative controls (either pair's sides
//! swapped); the `albedo` AOV by the side; the records the loader writes; the nestings it refuses,
//! with file and line.
use caustic::backend::BackendChoice;
use caustic_kernel::layout::*;
use caustic_kernel::two_sided::back_plus_one;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

/// The scene's defines: as written, or one pair swapped, the first's colours (`Colours`, front and
/// back exchanged in the record) or the second's turns (`Turns`: each square shows its other side).
#[derive(Clone, Copy, Debug)]
enum Swap {
    None,
    Colours,
    Turns,
}

fn check(choice: BackendChoice, integrator: &str, swap: Swap, spp: u32) -> (f64, f64) {
    let (red, blue) = ("0.8, 0.15, 0.1", "0.1, 0.2, 0.8");
    let mut defines = vec![("integrator", integrator)];
    match swap {
        Swap::None => {}
        Swap::Colours => defines.extend([("front1", blue), ("back1", red)]),
        Swap::Turns => defines.extend([("turn_left", "180"), ("turn_right", "0")]),
    }
    let label = format!("twosided pairs, {integrator}, swapped {swap:?}");
    against_mitsuba_reference(
        "twosided_pair.xml",
        &defines,
        "twosided_pair.exr",
        REFERENCE_SPP,
        choice,
        spp,
        7,
        &label,
    )
}

#[test]
fn twosided_pairs_match_mitsuba() {
    // Lavapipe is several times slower than the CPU backend: fewer samples there.
    for (choice, integrator, spp) in [
        (BackendChoice::Cpu, "path", 1024),
        (BackendChoice::Gpu, "path", 256),
        (BackendChoice::Cpu, "ptracer", 1024),
        (BackendChoice::Cpu, "ibpt", 512),
        // Nothing here lights a square indirectly: `direct` renders Mitsuba's path-traced image too.
        (BackendChoice::Cpu, "direct", 1024),
    ] {
        let (pass, z) = check(choice, integrator, Swap::None, spp);
        assert_agrees_with_reference((pass, z), &format!("{choice:?} {integrator}"));
    }
    // Negative controls: either pair's sides swapped must be caught, on both backends.
    for (choice, spp) in [(BackendChoice::Cpu, 1024), (BackendChoice::Gpu, 256)] {
        for swap in [Swap::Colours, Swap::Turns] {
            let (pass, z) = check(choice, "path", swap, spp);
            assert_disagrees_with_reference((pass, z), &format!("{choice:?}: {swap:?} swapped"));
        }
    }
}

fn scene(bsdf: &str) -> String {
    format!("<scene version=\"3.0.0\">\n<shape type=\"rectangle\">\n{bsdf}\n</shape></scene>")
}

const RED: &str = r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>"#;
const GOLD: &str = r#"<bsdf type="roughconductor"/>"#;

/// The front's record (the first BSDF) names the back's (the second, two-sided so that its frame is
/// mirrored); one BSDF names none; neither is a substitution any more, so `--strict` loads them.
#[test]
fn the_front_record_names_the_back() {
    let s = load_xml(&scene(&format!(r#"<bsdf type="twosided">{RED}{GOLD}</bsdf>"#)), "pair-record");
    let front = *s.materials.last().unwrap();
    assert_eq!(front.kind, BSDF_DIFFUSE);
    assert!(front.flags & MATERIAL_TWO_SIDED != 0);
    let back = s.materials[back_plus_one(&front) as usize - 1];
    assert_eq!(back.kind, BSDF_ROUGH_CONDUCTOR);
    assert!(back.flags & MATERIAL_TWO_SIDED != 0 && back_plus_one(&back) == 0);
    let one = load_xml(&scene(&format!(r#"<bsdf type="twosided">{RED}</bsdf>"#)), "pair-one");
    let m = *one.materials.last().unwrap();
    assert!(m.flags & MATERIAL_TWO_SIDED != 0 && back_plus_one(&m) == 0);

    let loaded =
        try_load_xml_strict(&scene(&format!(r#"<bsdf type="twosided">{RED}{GOLD}</bsdf>"#)), "pair-strict");
    loaded.map_err(|e| format!("{e:#}")).expect("--strict loads a twosided of two BSDFs");
}

fn refused(bsdf: &str, tag: &str) -> String {
    format!("{:#}", try_load_xml(&scene(bsdf), tag, &[]).expect_err(tag))
}

/// What the kernel could not shade by the side is refused, naming the line: a pair inside a blend, a
/// mask or a map around a pair, a mask inside one, three BSDFs, a transmissive back.
#[test]
fn pairs_refuse_what_they_cannot_shade_with_file_and_line() {
    let pair = format!("<bsdf type=\"twosided\">{RED}{GOLD}</bsdf>");
    let blend =
        format!("<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/>{RED}\n{pair}</bsdf>");
    let e = refused(&blend, "pair-in-blend");
    assert!(e.contains("scene.xml:4:") && e.contains("inside a blendbsdf"), "{e}");
    let mask = format!("<bsdf type=\"mask\">\n{pair}</bsdf>");
    let e = refused(&mask, "pair-in-mask");
    assert!(e.contains("scene.xml:3:") && e.contains("mask around"), "{e}");
    let map = format!(
        "<bsdf type=\"normalmap\"><texture type=\"bitmap\" name=\"normalmap\"><string name=\"filename\" value=\"{}\"/></texture>\n{pair}</bsdf>",
        test_data("normalmap_normals.png").display()
    );
    let e = refused(&map, "pair-in-map");
    assert!(e.contains("scene.xml:3:") && e.contains("around a twosided of two"), "{e}");
    let masked = format!("<bsdf type=\"twosided\">{RED}\n<bsdf type=\"mask\">{GOLD}</bsdf></bsdf>");
    let e = refused(&masked, "mask-in-pair");
    assert!(e.contains("scene.xml:4:") && e.contains("mask inside"), "{e}");
    let three = format!("<bsdf type=\"twosided\">{RED}{GOLD}{RED}</bsdf>");
    let e = refused(&three, "pair-three");
    assert!(e.contains("scene.xml:3:") && e.contains("one or two"), "{e}");
    let glass = format!("<bsdf type=\"twosided\">{RED}\n<bsdf type=\"roughdielectric\"/></bsdf>");
    let e = refused(&glass, "pair-glass");
    assert!(e.contains("scene.xml:3:") && e.contains("transmissive"), "{e}");
}

/// The `albedo` AOV picks the side as the integrators do (Mitsuba's `eval_diffuse_reflectance` of
/// `twosided` does): the first pair's front square is red, its turned-over square blue.
#[test]
fn the_albedo_aov_sees_the_back() {
    let xml = std::fs::read_to_string(test_data("twosided_pair.xml")).unwrap().replace(
        r#"<integrator type="$integrator"><integer name="max_depth" value="4"/></integrator>"#,
        r#"<integrator type="aov"><string name="aovs" value="a:albedo"/><integrator type="path"/></integrator>"#,
    );
    assert!(xml.contains(r#"type="aov""#), "the scene's integrator line changed");
    let scene = try_load_xml(&xml, "pair-albedo", &[]).expect("loads");
    let built = caustic::prepare::buffers::build(&scene).expect("builds");
    let mut film = render_buffers(&built, BackendChoice::Cpu, 4, 3);
    caustic::output::aov::add_to(&mut film, &built, 4, 3);
    let path = std::env::temp_dir().join(format!("caustic-pair-albedo-{}.exr", std::process::id()));
    film.save(&path).expect("EXR written");
    let (w, _, channels) = caustic::output::aov::exr::read_channels(&path).expect("EXR read back");
    let w = w as usize;
    std::fs::remove_file(&path).ok();
    let channel = |name: &str| &channels.iter().find(|(n, _)| n == name).expect(name).1;
    // Pixels in the middle of the top-left (front) and top-right (back) squares.
    let at = |x: usize, y: usize| {
        [channel("a.R")[y * w + x], channel("a.G")[y * w + x], channel("a.B")[y * w + x]]
    };
    let (front, back) = (at(10, 10), at(30, 10));
    let near = |a: [f32; 3], b: [f32; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 1e-3);
    assert!(near(front, [0.8, 0.15, 0.1]), "front albedo {front:?}");
    assert!(near(back, [0.1, 0.2, 0.8]), "back albedo {back:?}");
}
