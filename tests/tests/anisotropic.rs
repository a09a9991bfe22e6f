//! Anisotropic roughness oriented along dp/du as Mitsuba 3.9.1 orients it (its shading frame's
//! tangent is dp/du made orthogonal to the shading normal, on every shape): an OBJ sphere with texture
//! coordinates and no tangents under checkerboard `alpha_u`/`alpha_v` (Mitsuba's own
//! `test_textured_roughconductor` in small), an analytic sphere of anisotropic `principled` metal and a
//! turned floor of anisotropic `roughconductor` (`tests/data/anisotropic.xml`; the reference
//! `anisotropic.exr` and the mesh `uv_sphere.obj` are written by `anisotropic.py`). Per-pixel z-test
//! and mean-luminance z-score on both backends, with a negative control: the alphas swapped, which a
//! frame turned by 90° renders. (With a frame whose tangent ignored dp/du, 85% of the pixels passed
//! and the luminance was 28% off.)
use caustic::backend::BackendChoice;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 16384.0;

fn check(choice: BackendChoice, spp: u32, alphas: (&str, &str), label: &str) -> (f64, f64) {
    let defines = [("au", alphas.0), ("av", alphas.1)];
    against_mitsuba_reference(
        "anisotropic.xml",
        &defines,
        "anisotropic.exr",
        REFERENCE_SPP,
        choice,
        spp,
        7,
        label,
    )
}

#[test]
fn anisotropic_roughness_follows_dp_du_on_the_cpu() {
    assert_agrees_with_reference(check(BackendChoice::Cpu, 1024, ("0.04", "0.35"), "anisotropic"), "CPU");
    let swapped = check(BackendChoice::Cpu, 1024, ("0.35", "0.04"), "anisotropic, alphas swapped");
    assert_disagrees_with_reference(swapped, "alpha_u and alpha_v swapped");
}

#[test]
fn anisotropic_roughness_follows_dp_du_on_the_gpu() {
    assert_agrees_with_reference(check(BackendChoice::Gpu, 256, ("0.04", "0.35"), "anisotropic"), "GPU");
}
