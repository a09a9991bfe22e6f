//! Dielectrics: the smooth and thin dielectrics' lobe probabilities and energy (R + T, with the
//! radiance rescaling by 1/η²), and the rough dielectric's sampling against its pdf (χ², from outside
//! and inside, beyond the critical angle, nearly matched indices, narrow lobes).
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use common::bsdf_checks::{chi2_model, mirror_grid, sphere_grid};
use common::models::*;
use common::*;

/// With unit reflectance and transmittance the smooth dielectric's lobes carry R + T = 1 (importance),
/// or R + T/η² (radiance), and the mirror is chosen with probability F.
#[test]
fn dielectric_energy_and_lobe_probabilities() {
    for eta in [1.0001f32, 1.5, 2.42] {
        for cos in [1.0f32, 0.9, 0.3, 0.01, 0.0, -0.01, -0.5, -0.9, -1.0] {
            for adjoint in [false, true] {
                let b = Model::new(&Material { eta, ..material(BSDF_DIELECTRIC) }, adjoint);
                let wo = polar(cos, 0.8);
                let fr = fresnel(wo.z, eta);
                let n = 4000;
                let (mut energy, mut reflected) = (0.0f64, 0);
                for i in 0..n {
                    let s = b.sample(wo, (i as f32 + 0.5) / n as f32, Vec2::new(0.5, 0.5));
                    assert!(
                        s.delta && s.pdf > 0.0 && s.weight.is_finite(),
                        "eta {eta} cos {cos}: invalid sample"
                    );
                    if s.eta == 1.0 && close3(s.wi, reflect(wo), 1e-6, 1e-6) {
                        reflected += 1;
                        assert!(close(s.pdf, fr.f, 1e-6, 1e-7));
                    } else {
                        assert!(close(s.pdf, 1.0 - fr.f, 1e-6, 1e-7) && s.eta == fr.eta_it);
                        assert!(close3(s.wi, refract(wo, fr.cos_theta_t, fr.eta_ti), 1e-6, 1e-6));
                    }
                    energy += s.weight.x as f64;
                }
                let energy = energy / n as f64;
                let want = fr.f as f64
                    + (1.0 - fr.f as f64) * if adjoint { 1.0 } else { (fr.eta_ti * fr.eta_ti) as f64 };
                assert!(
                    (energy - want).abs() < 1e-3,
                    "eta {eta} cos {cos} adjoint {adjoint}: sampled energy {energy}, R+T {want}"
                );
                assert!(
                    ((reflected as f32 / n as f32) - fr.f).abs() <= 1.0 / n as f32 + 1e-6,
                    "eta {eta} cos {cos}: mirror chosen {reflected}/{n}, F = {}",
                    fr.f
                );
            }
        }
    }
    // Total internal reflection: always the mirror, with all the energy.
    let b = Model::new(&material(BSDF_DIELECTRIC), false);
    let wo = polar(-0.5, 0.0);
    for i in 0..100 {
        let s = b.sample(wo, i as f32 / 100.0, Vec2::ZERO);
        assert!(s.pdf == 1.0 && s.weight == Vec3::ONE && close3(s.wi, reflect(wo), 1e-7, 1e-7));
    }
}

#[test]
fn thin_dielectric_energy() {
    for eta in [1.0001f32, 1.5, 2.42] {
        let b = Model::new(&Material { eta, ..material(BSDF_THIN_DIELECTRIC) }, false);
        for cos in [1.0f32, 0.4, 0.01, 0.0, -0.3, -1.0] {
            let wo = polar(cos, 2.5);
            let r = fresnel(cos.abs(), eta).f;
            let r = 2.0 * r / (1.0 + r);
            let n = 2000;
            let (mut energy, mut reflected) = (0.0f32, 0);
            for i in 0..n {
                let s = b.sample(wo, (i as f32 + 0.5) / n as f32, Vec2::ZERO);
                assert!(s.delta && s.eta == 1.0 && s.pdf > 0.0);
                if close3(s.wi, reflect(wo), 1e-7, 1e-7) && r > 0.0 && s.pdf == r {
                    reflected += 1;
                } else {
                    assert!(s.wi == -wo && close(s.pdf, 1.0 - r, 1e-6, 1e-7), "straight through");
                }
                energy += s.weight.x;
            }
            assert!(
                close(energy / n as f32, 1.0, 1e-5, 1e-5),
                "eta {eta} cos {cos}: R + T = {}",
                energy / n as f32
            );
            assert!(((reflected as f32 / n as f32) - r).abs() <= 1.0 / n as f32 + 1e-6);
        }
    }
}

#[test]
fn rough_dielectric_chi2() {
    // (alpha_u, alpha_v, eta, cos θo): outside, inside, inside beyond the critical angle, grazing,
    // anisotropic, nearly matched indices from both sides, and a narrow lobe.
    let cases = [
        (0.1f32, 0.1f32, 1.5f32, 0.6f32),
        (0.5, 0.5, 1.5, -0.8),
        (0.3, 0.3, 1.5, -0.5),
        (1.0, 1.0, 2.42, 0.01),
        (0.05, 0.3, 2.42, 0.4),
        (0.1, 0.1, 1.0001, 0.7),
        (0.2, 0.2, 1.0001, -0.3),
        (0.01, 0.01, 1.5, 0.8),
    ];
    for beckmann in [false, true] {
        for (k, (au, av, eta, cos)) in cases.iter().enumerate() {
            let m = Material { eta: *eta, ..rough(BSDF_ROUGH_DIELECTRIC, *au, *av, beckmann) };
            let wo = polar(*cos, 1.1);
            // Nearly matched indices pass light almost straight through: a lobe of width ~(η - 1), where
            // the half vector `wo + η·wi` is tiny and the single-precision pdf is good to only ~1e-4 in
            // total, so that the shape of the lobe is tested.
            let grid = if *eta < 1.01 {
                let mut g = Grid::around(-wo, 8.0);
                g.mass_tolerance = 5e-3;
                g.conditional = true;
                g
            } else if *au < 0.05 {
                // Two narrow lobes, and bins fine around only one of them: the quadrature's total is
                // good to ~1e-4, too coarse for the expected count of rejections, so test the shape.
                let mut g = mirror_grid(wo);
                g.conditional = true;
                g
            } else {
                sphere_grid()
            };
            let b = Model::new(&m, false);
            chi2_model(
                &format!(
                    "roughdielectric {} αu={au} αv={av} η={eta} wo={wo}",
                    if beckmann { "beckmann" } else { "ggx" }
                ),
                &b,
                wo,
                &grid,
                k as u32,
            );
        }
    }
}
