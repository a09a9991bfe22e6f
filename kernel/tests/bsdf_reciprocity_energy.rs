//! Reciprocity and energy conservation of the models with smooth lobes (rough conductor, dielectric
//! and plastic, plastic, fuzzy metal): the radiance BSDF is the adjoint one with its arguments swapped,
//! and in a white furnace no model reflects more than it receives while its mean sampling weight
//! estimates the same albedo as the quadrature of `eval`. (Lambert and Phong: `bsdf_diffuse_phong.rs`,
//! through the same checks in `common::bsdf_checks`.)
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::bsdf::plastic::Plastic;
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use common::bsdf_checks::{albedo, check_energy, check_reciprocity};
use common::models::*;
use common::Grid;

#[test]
fn reciprocity() {
    let dirs = random_dirs(4000, 5);
    for (name, m) in smooth_models() {
        // Refraction within a few degrees of the critical angle is skipped (see `near_critical`).
        let checked = check_reciprocity(
            &name,
            &Model::new(&m, false),
            &dirs,
            |a, b| close3(a, b, 2e-3, 1e-6),
            |wo, wi| wo.z * wi.z < 0.0 && near_critical(&m, wo, wi),
        );
        assert!(checked > 20, "{name}: too few non-zero pairs ({checked})");
    }
}

/// Whether the refraction between `wo` and `wi` runs within a few degrees of the critical angle, where
/// `1 - F` is so steep that single-precision rounding of the half vector shows in the value.
fn near_critical(m: &Material, wo: Vec3, wi: Vec3) -> bool {
    let (n_o, n_i) = if wo.z > 0.0 { (1.0, m.eta) } else { (m.eta, 1.0) };
    let h = (wo * n_o + wi * n_i).normalize();
    let h = if h.z < 0.0 { -h } else { h };
    fresnel(wo.dot(h), m.eta).cos_theta_t.abs() < 0.1
}

/// White furnace: with white parameters no model reflects more than it receives (importance
/// transport for the refracting ones, whose radiance is rescaled by 1/η², radiance for fuzzy metal),
/// and the mean sampling weight estimates the same albedo as the quadrature of `eval` (plus the mirror
/// lobe's F for plastic).
#[test]
fn white_furnace() {
    let mut cases: Vec<(String, Material, f32)> = Vec::new();
    for beckmann in [false, true] {
        for alpha in [0.1f32, 0.5, 1.0] {
            cases.push((
                format!("roughconductor {alpha} {beckmann}"),
                rough(BSDF_ROUGH_CONDUCTOR, alpha, alpha, beckmann),
                0.0,
            ));
            cases.push((
                format!("roughdielectric {alpha} {beckmann}"),
                rough(BSDF_ROUGH_DIELECTRIC, alpha, alpha, beckmann),
                0.0,
            ));
            cases.push((
                format!("roughplastic {alpha} {beckmann}"),
                Material { reflectance: [1.0; 4], ..rough(BSDF_ROUGH_PLASTIC, alpha, alpha, beckmann) },
                0.01,
            ));
        }
        cases.push((
            format!("roughconductor aniso {beckmann}"),
            rough(BSDF_ROUGH_CONDUCTOR, 0.1, 0.6, beckmann),
            0.0,
        ));
        cases.push((
            format!("roughdielectric aniso {beckmann}"),
            Material { eta: 2.42, ..rough(BSDF_ROUGH_DIELECTRIC, 0.1, 0.6, beckmann) },
            0.0,
        ));
    }
    for fuzz in [0.3f32, 1.0] {
        cases.push((format!("fuzzymetal {fuzz}"), Material { reflectance: [1.0; 4], ..fuzzy(fuzz) }, 0.0));
    }
    // The diffuse Fresnel fits make white plastic come out a fraction of a percent off 1.
    cases.push(("plastic".into(), Material { reflectance: [1.0; 4], ..material(BSDF_PLASTIC) }, 0.01));
    for (k, (name, m, extra)) in cases.iter().enumerate() {
        // Fuzzy metal conserves energy in radiance transport only: its adjoint `f(wi, wo)·cos θi`
        // carries a `cos θi / cos θo` that exceeds 1 towards grazing `wo` (it is not reciprocal).
        let b = Model::new(m, m.kind != BSDF_FUZZY_METAL);
        for cos in [1.0f32, 0.5, 0.05, -0.7] {
            if cos < 0.0 && m.kind != BSDF_ROUGH_DIELECTRIC {
                continue;
            }
            let wo = polar(cos, 0.9);
            let mut a = albedo(&b, wo, &Grid::coarse(Vec3::Z));
            if m.kind == BSDF_PLASTIC {
                let p: Plastic = b.concrete();
                a += p.specular * fresnel(cos, p.eta).f;
            }
            println!("{name} cos θo={cos}: albedo {a:.4}");
            check_energy(name, &b, wo, a, *extra, 50_000, Sampler::new(k as u32, 77, 1));
        }
    }
}
