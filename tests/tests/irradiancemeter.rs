//! Mitsuba's `irradiancemeter` sensor: the irradiance averaged over the shape it is nested in.
//! Against Mitsuba 3.9.1 with the meter on a rectangle and on a sphere under an area light, a sky and
//! an occluder (`tests/data/irradiancemeter.xml`, references written by `irradiancemeter.py`) on both
//! backends, with a negative control (a weight 3% off); against the exact πL under a constant sky
//! (irradiance, not flux: shapes of any area read the same); and the inputs refused.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic_tests::replicas::image_mean;
use caustic_tests::*;

/// The references' samples: 64 Mitsuba renders of 2^16 spp.
const REFERENCE_SPP: f64 = 4_194_304.0;

/// Renders the meter on `meter` (rectangle or sphere), scales the image by `scale` (a negative
/// control's wrong weight) and compares it with Mitsuba's: (pass fraction, luminance z).
fn check(choice: BackendChoice, meter: &str, spp: u32, scale: f32) -> (f64, f64) {
    let scene = caustic::load::load_scene(&test_data("irradiancemeter.xml"), &defines(&[("meter", meter)]))
        .expect("loads");
    let mut film = render_scene(&scene, choice, spp, 5);
    for p in &mut film.rgb {
        p.iter_mut().for_each(|c| *c *= scale);
    }
    for v in film.variance.iter_mut().flatten() {
        v.iter_mut().for_each(|c| *c *= (scale * scale) as f64);
    }
    let reference =
        Film::load_exr(&test_data(&format!("irradiancemeter_{meter}.exr"))).expect("reference loads");
    let c =
        caustic::output::compare::compare(&film, &reference, spp as f64 / REFERENCE_SPP).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!(
        "irradiancemeter on a {meter} ×{scale}, {choice:?} {spp} spp: {:?} for Mitsuba's {:?}, z {z:+.2}, pass {pass}",
        film.rgb[0], reference.rgb[0]
    );
    (pass, z)
}

#[test]
fn irradiancemeter_matches_mitsuba() {
    for (choice, spp) in [(BackendChoice::Cpu, 1 << 18), (BackendChoice::Gpu, 1 << 16)] {
        for meter in ["rectangle", "sphere"] {
            let (pass, z) = check(choice, meter, spp, 1.0);
            assert!(
                pass == 1.0 && z.abs() < 4.0,
                "{choice:?}, {meter}: the meter differs from Mitsuba's (z {z:+.2})"
            );
        }
    }
    // Negative control: a weight 3% low (as 0.97π for π) must be caught.
    for meter in ["rectangle", "sphere"] {
        let (pass, z) = check(BackendChoice::Cpu, meter, 1 << 18, 0.97);
        assert!(pass < 1.0 || z.abs() >= 4.0, "{meter}: a weight 3% low went unnoticed (z {z:+.2})");
    }
}

/// A scene of one shape carrying the meter (`shape`: the shape's type and its children before the
/// sensor), lit by a constant sky.
fn meter_scene(shape: &str, sensor: &str, integrator: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"/>
    <shape type={shape}
        <sensor type="irradiancemeter">{sensor}
            <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film></sensor>
    </shape>
    <emitter type="constant"><rgb name="radiance" value="1, 2, 0.5"/></emitter>
</scene>"#
    )
}

/// Under a constant sky of radiance L, every ray leaving a convex shape (or a flat one, on its front
/// side) sees L: the meter reads πL exactly, whatever the shape's area (Mitsuba reports irradiance,
/// not flux: a 6×6 rectangle and a sphere of radius 2 read as a unit one), for a rectangle, a disk,
/// a sphere, a cube (a mesh of twelve triangles in six orientations) and a flipped rectangle, on both
/// backends.
#[test]
fn irradiancemeter_reads_a_sky_exactly() {
    let shapes = [
        r#""rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="30"/><translate x="1" y="2" z="3"/></transform>"#,
        r#""rectangle"><boolean name="flip_normals" value="true"/>"#,
        r#""disk"><transform name="to_world"><scale value="0.2"/><rotate y="1" angle="-70"/></transform>"#,
        r#""sphere"><float name="radius" value="2"/><point name="center" x="0" y="1" z="0"/>"#,
        r#""cube"><transform name="to_world"><scale x="2" y="0.5" z="1"/></transform>"#,
    ];
    let expected = [1.0, 2.0, 0.5].map(|l: f64| std::f64::consts::PI * l);
    for shape in shapes {
        let scene = load_xml(&meter_scene(shape, "", "path"), "meter-sky");
        for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
            let film = render_scene(&scene, choice, 4096, 2);
            println!("{choice:?}, {shape}: {:?}, expected {expected:?}", film.rgb[0]);
            for (c, want) in expected.iter().enumerate() {
                let v = film.rgb[0][c] as f64;
                assert!((v - want).abs() < 1e-4 * want, "{choice:?}, {shape}: channel {c} {v}");
            }
        }
    }
}

/// Under a hemisphere of light cut by a large black occluder, the flat meter's value is exactly π L
/// times the unoccluded share of the cosine-weighted hemisphere: a black disk of radius R at height h
/// over a tiny meter hides sin²(atan(R/h)) of it. (With a constant sky of radiance 1, R = h: half.)
#[test]
fn irradiancemeter_sees_an_occluder() {
    let xml = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <shape type="disk"><transform name="to_world"><scale value="0.001"/></transform>
        <sensor type="irradiancemeter"><film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film></sensor></shape>
    <shape type="disk"><transform name="to_world"><scale value="10"/><translate z="10"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf></shape>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>"#;
    let scene = load_xml(xml, "meter-occluder");
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        let film = render_scene(&scene, choice, 1 << 16, 3);
        let mean = image_mean(&film);
        // The channels are equal (a grey sky, a black occluder): the mean's error is one channel's.
        let se = (film.variance.as_ref().unwrap().iter().flatten().sum::<f64>() / 3.0).sqrt();
        let expected = std::f64::consts::PI * 0.5;
        println!("{choice:?}: meter under a black disk: {mean:.5} ± {se:.1e}, expected {expected:.5}");
        assert!((mean - expected).abs() < 4.0 * se + 1e-3 * expected, "{choice:?}: {mean} ± {se}");
        // Negative control: the unoccluded πL lies far outside the tolerance.
        assert!((std::f64::consts::PI - expected).abs() > 20.0 * (4.0 * se + 1e-3 * expected));
    }
}

/// What cannot be measured is refused, naming the file and line: a meter outside a shape, with a
/// `to_world` (Mitsuba refuses it too), another sensor type in a shape, a meter in a shapegroup, in
/// an unsupported shape, two sensors in a shape; light tracing does not support it yet.
#[test]
fn irradiancemeter_refuses_what_it_cannot_measure() {
    let top_level = r#"<scene version="3.0.0">
    <sensor type="irradiancemeter"/>
</scene>"#
        .to_string();
    let in_group = r#"<scene version="3.0.0">
    <shape type="shapegroup" id="g">
        <shape type="rectangle"><sensor type="irradiancemeter"/></shape>
    </shape>
</scene>"#
        .to_string();
    let cases = [
        (top_level, "nest it in the <shape>", ".xml:2: "),
        (
            meter_scene(
                r#""rectangle">"#,
                r#"<transform name="to_world"><translate z="1"/></transform>"#,
                "path",
            ),
            "'to_world' is not allowed",
            ".xml:4: ",
        ),
        (
            meter_scene(r#""rectangle">"#, "", "path").replace("irradiancemeter", "perspective"),
            "must be an irradiancemeter",
            ".xml:4: ",
        ),
        (in_group, "inside a shapegroup", ".xml:3: "),
        (meter_scene(r#""heightfield">"#, "", "path"), "is left out", ".xml:4: "),
        (
            meter_scene(r#""rectangle"><sensor type="irradiancemeter"/>"#, "", "path"),
            "takes one sensor",
            ".xml:4: ",
        ),
        (meter_scene(r#""rectangle">"#, "", "ptracer"), "not supported by light tracing", ""),
        (meter_scene(r#""rectangle">"#, "", "ibpt"), "not supported by light tracing", ""),
    ];
    for (i, (xml, expected, location)) in cases.iter().enumerate() {
        let result = try_load_xml(xml, &format!("meter-refuse-{i}"), &[])
            .and_then(|scene| caustic::prepare::buffers::build(&scene).map(|_| ()));
        let error = format!("{:#}", result.expect_err(expected));
        println!("case {i}: {error}");
        assert!(error.contains(expected), "case {i}: {error}");
        assert!(error.contains(location), "case {i} names no file and line: {error}");
    }
}

/// Like Mitsuba, the meter fills a film of any size with its one value (its documentation asks for
/// 1×1 but nothing refuses more), and a scene's first sensor in document order is the one rendered.
#[test]
fn irradiancemeter_films_and_sensor_order() {
    let film = r#"<integer name="width" value="3"/><integer name="height" value="2"/>"#;
    let xml = meter_scene(r#""rectangle">"#, "", "path")
        .replace(r#"<integer name="width" value="1"/><integer name="height" value="1"/>"#, film);
    let scene = load_xml(&xml, "meter-film");
    let image = render_scene(&scene, BackendChoice::Cpu, 64, 1);
    assert_eq!((image.width, image.height), (3, 2));
    for p in &image.rgb {
        assert!((p[1] as f64 - 2.0 * std::f64::consts::PI).abs() < 1e-4, "{p:?}");
    }
    // A perspective sensor after the meter: the meter is rendered, with a warning.
    let later = xml.replace("</scene>", r#"<sensor type="perspective"/></scene>"#);
    let scene = load_xml(&later, "meter-first");
    assert!(matches!(scene.sensor.projection, caustic::scene::Projection::IrradianceMeter { .. }));
    assert!(scene.warnings.iter().any(|w| w.contains("a second sensor")), "{:?}", scene.warnings);
    // And before it: the perspective camera.
    let earlier = xml.replace("<integrator", r#"<sensor type="perspective"/><integrator"#);
    let scene = load_xml(&earlier, "meter-second");
    assert!(matches!(scene.sensor.projection, caustic::scene::Projection::Perspective));
}
