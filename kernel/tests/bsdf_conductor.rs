//! Conductors: the smooth conductor is a Fresnel-weighted mirror; the rough conductor's sampling
//! follows its pdf (χ², GGX and Beckmann, isotropic and anisotropic, normal to grazing incidence).
//! Agreement with Mitsuba's values is in `bsdf_mitsuba.rs`, energy and reciprocity in
//! `bsdf_reciprocity_energy.rs`.
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use common::bsdf_checks::{chi2_model, mirror_grid, sphere_grid};
use common::mitsuba::reference_material;
use common::models::*;

#[test]
fn conductor_is_a_fresnel_mirror() {
    let m = reference_material("conductor");
    let b = Model::new(&m, false);
    for cos in [1.0f32, 0.5, 0.01] {
        let wo = polar(cos, 0.2);
        let s = b.sample(wo, 0.5, Vec2::new(0.1, 0.9));
        assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0 && close3(s.wi, reflect(wo), 1e-7, 1e-7));
        assert!(close3(
            s.weight,
            rgb(m.specular_reflectance)
                * fresnel_conductor_rgb(cos, rgb(m.conductor_eta), rgb(m.conductor_k)),
            1e-6,
            1e-7
        ));
        assert_eq!(b.eval(wo, reflect(wo)), Vec3::ZERO);
        assert_eq!(b.pdf(wo, reflect(wo)), 0.0);
    }
    assert_eq!(b.sample(polar(-0.5, 0.0), 0.5, Vec2::splat(0.5)).pdf, 0.0, "one-sided");
}

#[test]
fn rough_conductor_chi2() {
    let cases = [
        (0.01f32, 0.01f32, 0.7f32),
        (0.1, 0.1, 1.0),
        (0.1, 0.1, 0.01),
        (0.5, 0.5, 0.6),
        (1.0, 1.0, 0.01),
        (0.05, 0.3, 0.5),
    ];
    for beckmann in [false, true] {
        for (k, (au, av, cos)) in cases.iter().enumerate() {
            let m = Material {
                conductor_eta: c4(0.2, 0.9, 1.1),
                conductor_k: c4(3.9, 2.4, 2.2),
                ..rough(BSDF_ROUGH_CONDUCTOR, *au, *av, beckmann)
            };
            let wo = polar(*cos, 0.3);
            let grid = if *au < 0.05 { mirror_grid(wo) } else { sphere_grid() };
            chi2_model(
                &format!(
                    "roughconductor {} αu={au} αv={av} wo={wo}",
                    if beckmann { "beckmann" } else { "ggx" }
                ),
                &Model::new(&m, false),
                wo,
                &grid,
                k as u32,
            );
        }
    }
}
