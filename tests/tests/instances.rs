//! Mitsuba's `shapegroup` and `instance` (flattened: each instance's geometry is stored) and
//! `merge`. Against Mitsuba 3.9.1 on a group of a mesh, a sphere and a disk placed three times
//! (rotated and scaled, and mirrored: Mitsuba keeps a mirrored instance's normals facing out), on
//! both backends, with a negative control; and what Mitsuba refuses, refused with file and line.
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(choice: BackendChoice, red: &str) -> (f64, f64) {
    let label = format!("instances, the cubes' red {red}");
    // Lavapipe runs this scene ten times slower than the CPU backend: fewer samples there.
    let spp = if choice == BackendChoice::Cpu { 1024 } else { 256 };
    against_mitsuba_reference(
        "instances.xml",
        &[("red", red)],
        "instances.exr",
        REFERENCE_SPP,
        choice,
        spp,
        4,
        &label,
    )
}

#[test]
fn instances_match_mitsuba() {
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        let (pass, z) = check(choice, "0.7");
        assert!(pass >= 0.99, "{choice:?}: only {:.2}% of pixels agree with Mitsuba", pass * 100.0);
        assert!(z.abs() < 4.0, "{choice:?}: mean luminance differs from Mitsuba by {z:.2} standard errors");
    }
    // Negative control: the three instanced cubes' red 0.4 for 0.7 must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "0.4");
    assert!(pass < 0.99 || z.abs() >= 4.0, "red 0.4 for 0.7 went unnoticed (pass {pass:.4}, z {z:+.2})");
}

/// A `merge` renders the shapes it holds, as if they stood alone.
#[test]
fn merge_holds_its_shapes() {
    let shapes = r#"<shape type="sphere"><float name="radius" value="0.5"/></shape>
        <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform></shape>"#;
    let rest = r#"<emitter type="constant"/>
        <sensor type="perspective"><transform name="to_world"><lookat origin="0, -4, 1" target="0, 0, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film></sensor>"#;
    let scene = |body: &str| load_xml(&format!(r#"<scene version="3.0.0">{body}{rest}</scene>"#), "merge");
    let merged = scene(&format!(r#"<shape type="merge">{shapes}</shape>"#));
    let alone = scene(shapes);
    let (a, b) =
        (render_scene(&merged, BackendChoice::Cpu, 4, 1), render_scene(&alone, BackendChoice::Cpu, 4, 1));
    assert!(caustic_tests::replicas::image_mean(&b) > 0.0, "the test scene is black");
    assert_eq!(max_abs_difference(&a, &b), 0.0, "a merge renders other than its shapes alone");
}

#[test]
fn instancing_refuses_what_mitsuba_refuses() {
    let group = |inner: &str| format!(r#"<shape type="shapegroup" id="g">{inner}</shape>"#);
    let sphere = r#"<shape type="sphere"/>"#;
    let instance = |t: &str| {
        format!(r#"<shape type="instance"><ref id="g"/><transform name="to_world">{t}</transform></shape>"#)
    };
    let cases = [
        (group(r#"<shape type="sphere"><emitter type="area"/></shape>"#), "cannot be instanced"),
        (
            format!("{}\n{}", group(sphere), r#"<shape type="instance"><ref id="h"/></shape>"#),
            "no shapegroup 'h'",
        ),
        (
            group(r#"<shape type="shapegroup" id="inner"><shape type="sphere"/></shape>"#),
            "cannot hold a shapegroup",
        ),
        (format!("{}\n{}", group(sphere), instance(r#"<scale x="1" y="2" z="1"/>"#)), "scaled uniformly"),
        (r#"<shape type="instance"/>"#.to_string(), "names one shapegroup"),
    ];
    for (i, (body, expected)) in cases.iter().enumerate() {
        let xml = format!("<scene version=\"3.0.0\">\n{}\n</scene>\n", body.replace('\n', " "));
        let error =
            format!("{:#}", try_load_xml(&xml, &format!("instance-refuse-{i}"), &[]).expect_err(expected));
        println!("case {i}: {error}");
        assert!(error.contains(expected), "case {i}: {error}");
        assert!(error.contains(".xml:2"), "case {i} names no file and line: {error}");
    }
}
