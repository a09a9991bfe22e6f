//! Reconstruction filters with negative lobes (`mitchell`, `catmullrom`, `lanczos`) against Mitsuba
//! 3.9.1: a checkered floor and a sphere under a uniform sky (`tests/data/filters.xml`, sharp edges
//! everywhere; the references `filters_<name>.exr` are written by `filters.py`), per-pixel z-test and
//! mean-luminance z-score on the CPU and the GPU backend, with a negative control (the Gaussian
//! filter's image against the Lanczos reference). The sampling itself is checked in
//! `caustic::prepare::filter_table`'s unit tests; light tracing's signed splats in `ptracer.rs`.
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

/// caustic's render with `filter` against Mitsuba's with `reference`: (pass fraction, luminance z).
fn check(choice: BackendChoice, spp: u32, filter: &str, reference_name: &str) -> (f64, f64) {
    let label = format!("{filter} against Mitsuba's {reference_name}");
    let reference = format!("filters_{reference_name}.exr");
    against_mitsuba_reference(
        "filters.xml",
        &[("filter", filter)],
        &reference,
        REFERENCE_SPP,
        choice,
        spp,
        3,
        &label,
    )
}

fn assert_agrees(choice: BackendChoice, spp: u32, filter: &str) {
    assert_agrees_with_reference(check(choice, spp, filter, filter), filter);
}

#[test]
fn negative_lobed_filters_match_mitsuba_on_the_cpu() {
    for filter in ["mitchell", "catmullrom", "lanczos"] {
        assert_agrees(BackendChoice::Cpu, 1024, filter);
    }
    // Negative control: the Gaussian filter's softer image must not pass for Lanczos'.
    let (pass, z) = check(BackendChoice::Cpu, 1024, "gaussian", "lanczos");
    assert!(
        pass < 0.99 || z.abs() >= 4.0,
        "the Gaussian filter passed for Lanczos (pass {pass:.4}, z {z:+.2})"
    );
}

#[test]
fn negative_lobed_filters_match_mitsuba_on_the_gpu() {
    assert_agrees(BackendChoice::Gpu, 256, "lanczos");
    assert_agrees(BackendChoice::Gpu, 256, "mitchell");
}

/// Mitsuba accepts `lobes` = 0 and then renders black (its filter is zero everywhere); caustic refuses
/// it, naming the file and line.
#[test]
fn lanczos_without_lobes_is_refused() {
    let dir = std::env::temp_dir().join(format!("caustic-filters-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("lobes.xml");
    std::fs::write(
        &path,
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">\n\
         <rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"0\"/></rfilter></film></sensor>\n</scene>\n",
    )
    .unwrap();
    let Err(e) = caustic::load::load_scene(&path, &[]) else { panic!("lanczos with lobes = 0 loaded") };
    let message = format!("{e:#}");
    std::fs::remove_dir_all(&dir).ok();
    assert!(message.contains("lobes.xml:3") && message.contains("lobes"), "{message}");
}
