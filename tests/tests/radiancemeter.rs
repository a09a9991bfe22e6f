//! Mitsuba's `radiancemeter` sensor: the radiance along one ray. Against Mitsuba 3.9.1 on a lit
//! sphere (`tests/data/radiancemeter.xml`, reference written by `radiancemeter.py`) on both backends,
//! with a negative control; against the exact value over a diffuse floor under a constant sky; and
//! the inputs Mitsuba refuses.
use caustic::backend::BackendChoice;
use caustic_tests::replicas::image_mean;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 1_048_576.0;

fn check(choice: BackendChoice, rho: &str) -> (f64, f64) {
    let label = format!("radiancemeter, sphere reflectance {rho}");
    let defines = [("rho", rho)];
    against_mitsuba_reference(
        "radiancemeter.xml",
        &defines,
        "radiancemeter.exr",
        REFERENCE_SPP,
        choice,
        1 << 16,
        3,
        &label,
    )
}

#[test]
fn radiancemeter_matches_mitsuba() {
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        let (pass, z) = check(choice, "0.6");
        assert!(pass == 1.0 && z.abs() < 4.0, "{choice:?}: the meter differs from Mitsuba's (z {z:+.2})");
    }
    // Negative control: a sphere 5% less red must be caught.
    let (pass, z) = check(BackendChoice::Cpu, "0.57");
    assert!(pass < 1.0 || z.abs() >= 4.0, "reflectance 0.57 for 0.6 went unnoticed (z {z:+.2})");
}

fn meter(sensor: &str, film: &str, integrator: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"/>
    <sensor type="radiancemeter">{sensor}
        <film type="hdrfilm">{film}<rfilter type="box"/></film></sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <emitter type="constant"><rgb name="radiance" value="2"/></emitter>
</scene>"#
    )
}

const ONE_PIXEL: &str = r#"<integer name="width" value="1"/><integer name="height" value="1"/>"#;

/// A one-sided diffuse floor of albedo ρ under a sky of radiance L has the radiance ρL everywhere;
/// the meter is given by `to_world` and by `origin`/`direction`, looking down, on both backends.
#[test]
fn radiancemeter_reads_a_lit_floor_exactly() {
    let sensors = [
        r#"<transform name="to_world"><lookat origin="0.3, 0.2, 2" target="0.3, 0.2, 0" up="0, 1, 0"/></transform>"#,
        r#"<point name="origin" x="-1" y="0" z="1"/><vector name="direction" x="1" y="0.2" z="-1"/>"#,
    ];
    for sensor in sensors {
        let scene = load_xml(&meter(sensor, ONE_PIXEL, "path"), "meter-floor");
        for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
            let film = render_scene(&scene, choice, 4096, 2);
            let mean = image_mean(&film);
            let se =
                (film.variance.as_ref().unwrap().iter().flatten().sum::<f64>() / 3.0).sqrt() / 3f64.sqrt();
            println!("{choice:?}: meter over the floor: {mean:.5} ± {se:.1e}, expected 1");
            assert!((mean - 1.0).abs() < 4.0 * se + 1e-4, "{choice:?}: {mean} ± {se}, expected 1");
        }
    }
}

/// What Mitsuba refuses is refused, naming the file and line: a film neither one pixel wide nor
/// high, `origin` without `direction`, a zero direction; light tracing cannot reach a single ray.
#[test]
fn radiancemeter_refuses_what_mitsuba_refuses() {
    let cases = [
        (
            meter("", r#"<integer name="width" value="4"/><integer name="height" value="4"/>"#, "path"),
            "1 pixel wide or high",
        ),
        (
            meter(r#"<point name="origin" x="0" y="0" z="1"/>"#, ONE_PIXEL, "path"),
            "both 'origin' and 'direction'",
        ),
        (
            meter(
                r#"<point name="origin" x="0" y="0" z="1"/><vector name="direction" x="0" y="0" z="0"/>"#,
                ONE_PIXEL,
                "path",
            ),
            "must not be zero",
        ),
        (meter("", ONE_PIXEL, "ptracer"), "single ray"),
    ];
    for (i, (xml, expected)) in cases.iter().enumerate() {
        let result = try_load_xml(xml, &format!("meter-refuse-{i}"), &[])
            .and_then(|scene| caustic::prepare::buffers::build(&scene).map(|_| ()));
        let error = format!("{:#}", result.expect_err(expected));
        println!("case {i}: {error}");
        assert!(error.contains(expected), "case {i}: {error}");
        if i < 3 {
            assert!(error.contains(".xml:3: "), "case {i} names no file and line: {error}");
        }
    }
    // A 1×5 film is allowed (Mitsuba refuses only films wider and higher than one pixel).
    load_xml(
        &meter("", r#"<integer name="width" value="1"/><integer name="height" value="5"/>"#, "path"),
        "meter-strip",
    );
}
