//! Thin dielectrics as null interfaces, against Mitsuba 3.9.1's `volpath` (`tests/data/thin_null.xml`,
//! references by `thin_null.py`): a tinted pane between the lamp and the floor, whose shadow is the
//! light next-event estimation reaches through it, and a tinted thin-dielectric sphere before a wall,
//! at `max_depth` 3, which crossings must not use up (`kernel/src/mask.rs`). Mitsuba's `path` counts a
//! crossing as a bounce and stops shadow rays at panes; caustic renders what `volpath` renders under
//! every integrator: `path` and `ibpt` against `volpath` at the same depth, `direct` against `volpath`
//! at depth 2, `ptracer` with panes that reflect nothing (light tracing cannot connect a Dirac
//! reflection to the camera). Per-pixel z-test and mean-luminance z-score, with a negative control.
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(
    choice: BackendChoice,
    defines: &[(&str, &str)],
    reference: &str,
    spp: u32,
    label: &str,
) -> (f64, f64) {
    against_mitsuba_reference("thin_null.xml", defines, reference, REFERENCE_SPP, choice, spp, 5, label)
}

#[test]
fn thin_dielectrics_cross_as_volpath_on_the_cpu() {
    for integrator in ["path", "ibpt"] {
        let defines = [("integrator", integrator)];
        let figures = check(BackendChoice::Cpu, &defines, "thin_null.exr", 1024, integrator);
        assert_agrees_with_reference(figures, integrator);
    }
    let defines = [("integrator", "direct")];
    assert_agrees_with_reference(
        check(BackendChoice::Cpu, &defines, "thin_null_depth2.exr", 1024, "direct"),
        "direct",
    );
    // Negative control: one bounce less (as when a crossing counted one) must be caught.
    let defines = [("integrator", "path"), ("max_depth", "2")];
    let figures = check(BackendChoice::Cpu, &defines, "thin_null.exr", 1024, "path at max_depth 2");
    assert_disagrees_with_reference(figures, "a bounce lost to the crossings");
}

#[test]
fn thin_dielectrics_cross_as_volpath_under_light_tracing() {
    let defines = [("integrator", "ptracer"), ("pane_ior", "1"), ("ball_ior", "1")];
    assert_agrees_with_reference(
        check(BackendChoice::Cpu, &defines, "thin_null_clear.exr", 1024, "ptracer"),
        "ptracer",
    );
}

#[test]
fn thin_dielectrics_cross_as_volpath_on_the_gpu() {
    let defines = [("integrator", "path")];
    assert_agrees_with_reference(check(BackendChoice::Gpu, &defines, "thin_null.exr", 256, "path"), "GPU");
}
