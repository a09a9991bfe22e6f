//! Plastic (a diffuse base under a dielectric coating): the smooth plastic's diffuse part against its
//! pdf and its mirror lobe's probability and weight, the rough plastic's sampling (χ²), and the rough
//! plastic's precomputed tables.
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::bsdf::plastic::Plastic;
use caustic_kernel::bsdf::rough_plastic;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use common::bsdf_checks::{chi2_model, mirror_grid, sphere_grid};
use common::models::*;

/// The smooth part is fitted by χ² (mirror samples counted as "no direction", whose expected share is
/// what the smooth pdf leaves over); the mirror's probability mass is checked on its own.
#[test]
fn plastic_smooth_part_chi2_and_delta_mass() {
    for (k, (eta, cos, diffuse)) in
        [(1.5f32, 1.0f32, 0.5f32), (1.5, 0.1, 0.8), (2.42, 0.6, 0.2), (1.0001, 0.3, 0.5)].iter().enumerate()
    {
        let m =
            Material { eta: *eta, reflectance: c4(*diffuse, *diffuse, *diffuse), ..material(BSDF_PLASTIC) };
        let b = Model::new(&m, false);
        let wo = polar(*cos, 0.5);
        chi2_model(&format!("plastic η={eta} wo={wo}"), &b, wo, &sphere_grid(), k as u32);
        // Mirror samples: exact direction, and a frequency that matches the lobe probability.
        let p: Plastic = b.concrete();
        let f = fresnel(wo.z, *eta).f;
        let (ps, pd) = (f * p.specular_weight, (1.0 - f) * (1.0 - p.specular_weight));
        let prob = ps / (ps + pd);
        let n = 20000;
        let mut hits = 0;
        for i in 0..n {
            let s = b.sample(wo, (i as f32 + 0.5) / n as f32, Vec2::new(0.3, 0.6));
            if s.delta {
                hits += 1;
                assert!(close3(s.wi, reflect(wo), 1e-6, 1e-6) && close(s.pdf, prob, 1e-5, 1e-7));
                // The weight carries the lobe's energy F·specular over its probability.
                assert!(close3(s.weight * s.pdf, Vec3::splat(f), 1e-4, 1e-7));
            }
        }
        assert!(
            ((hits as f32 / n as f32) - prob).abs() <= 1.0 / n as f32 + 1e-6,
            "mirror chosen {hits}/{n}, probability {prob}"
        );
    }
}

#[test]
fn rough_plastic_chi2() {
    let cases = [(0.1f32, 1.0f32, 1.5f32), (0.5, 0.01, 1.5), (1.0, 0.6, 2.42), (0.01, 0.5, 1.5)];
    for beckmann in [false, true] {
        for (k, (alpha, cos, eta)) in cases.iter().enumerate() {
            let m = Material {
                eta: *eta,
                reflectance: c4(0.3, 0.5, 0.7),
                ..rough(BSDF_ROUGH_PLASTIC, *alpha, *alpha, beckmann)
            };
            let wo = polar(*cos, 2.0);
            let grid = if *alpha < 0.05 { mirror_grid(wo) } else { sphere_grid() };
            chi2_model(
                &format!(
                    "roughplastic {} α={alpha} η={eta} wo={wo}",
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

#[test]
fn rough_plastic_precomputation() {
    for (alpha, eta, beckmann) in
        [(1e-4f32, 1.5f32, true), (0.1, 1.5, true), (0.5, 1.9, false), (1.0, 2.42, false)]
    {
        let mut m = Material {
            reflectance: c4(0.2, 0.4, 0.6),
            specular_reflectance: c4(1.0, 0.5, 0.0),
            ..rough(BSDF_ROUGH_PLASTIC, alpha, alpha, beckmann)
        };
        let table = rough_plastic::precompute(&mut m);
        assert_eq!(table.len(), rough_plastic::TRANSMITTANCE_RES as usize);
        assert!(table.iter().all(|t| t.is_finite() && (0.0..=1.0).contains(t)), "{table:?}");
        // Mitsuba's lobe prior: mean specular / (mean diffuse + mean specular).
        assert!(close(m.params[1], 0.5 / (0.4 + 0.5), 1e-6, 0.0));
        let ri = m.params[0];
        assert!(ri > 0.0 && ri < 1.0);
        if alpha < 1e-3 {
            // A smooth coating transmits 1 - F, and reflects Fdr of the diffuse light inside (up to
            // Mitsuba's coarse 64-point estimate of that integral).
            for (j, t) in table.iter().enumerate().skip(1) {
                let mu = j as f32 / 63.0;
                assert!(close(*t, 1.0 - fresnel(mu, eta).f, 2e-3, 2e-3), "T({mu}) = {t}");
            }
            let fdr = fresnel_diffuse_reflectance(1.0 / eta);
            assert!(close(ri, fdr, 0.03, 0.0), "internal reflectance {ri} vs Fdr {fdr}");
        }
    }
}
