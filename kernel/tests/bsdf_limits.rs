//! Limits and stiff inputs of every model: the rough models at α → 0 become their smooth counterparts,
//! and grazing or degenerate directions, extreme roughness and IOR produce no NaN or ±∞.
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::bsdf::TransportMode;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use common::bsdf_checks::sampled_albedo;
use common::models::*;

/// At alpha → 0 the rough models become their smooth counterparts.
#[test]
fn rough_models_approach_smooth_ones() {
    for beckmann in [false, true] {
        // Dielectric: mirror chosen with probability F, directions of the smooth interface, all energy kept.
        for cos in [0.7f32, 0.2, -0.9, -0.5] {
            for adjoint in [false, true] {
                let b = Model::new(&rough(BSDF_ROUGH_DIELECTRIC, 1e-4, 1e-4, beckmann), adjoint);
                let wo = polar(cos, 0.1);
                let fr = fresnel(cos, 1.5);
                let n = 20000;
                let mut rng = Sampler::new(1, 2, 3);
                let (mut reflected, mut energy, mut off) = (0, 0.0f64, 0);
                for i in 0..n {
                    let s = b.sample(wo, (i as f32 + 0.5) / n as f32, rng.next_2d());
                    if s.pdf <= 0.0 {
                        continue;
                    }
                    let smooth = if s.wi.z * wo.z > 0.0 {
                        reflected += 1;
                        reflect(wo)
                    } else {
                        refract(wo, fr.cos_theta_t, fr.eta_ti)
                    };
                    // GGX's long tail sends a few samples further off.
                    off += (!close3(s.wi, smooth, 0.0, 2e-3)) as u32;
                    energy += s.weight.x as f64;
                }
                let want = fr.f as f64
                    + (1.0 - fr.f as f64) * if adjoint { 1.0 } else { (fr.eta_ti * fr.eta_ti) as f64 };
                assert!(
                    (energy / n as f64 - want).abs() < 2e-3,
                    "roughdielectric α→0 cos {cos}: energy {} vs {want}",
                    energy / n as f64
                );
                assert!(
                    ((reflected as f32 / n as f32) - fr.f).abs() < 2e-3,
                    "roughdielectric α→0 cos {cos}: reflected {reflected}/{n}, F {}",
                    fr.f
                );
                assert!(
                    off < n / 100,
                    "roughdielectric α→0 cos {cos}: {off} of {n} samples off the smooth directions"
                );
            }
        }
        // Conductor: the mirror with the Fresnel weight.
        let m = Material {
            conductor_eta: c4(0.2, 0.9, 1.1),
            conductor_k: c4(3.9, 2.4, 2.2),
            ..rough(BSDF_ROUGH_CONDUCTOR, 1e-4, 1e-4, beckmann)
        };
        let b = Model::new(&m, false);
        for cos in [1.0f32, 0.5, 0.05] {
            let wo = polar(cos, 1.0);
            let (mean, _) = sampled_albedo(&b, wo, 20000, Sampler::new(9, 77, 1));
            let f = fresnel_conductor_rgb(cos, rgb(m.conductor_eta), rgb(m.conductor_k));
            assert!(close3(mean, f, 3e-3, 1e-4), "roughconductor α→0 cos {cos}: {mean} vs F {f}");
        }
        // Plastic: the same albedo as the smooth model.
        let rp = Model::new(
            &Material { reflectance: c4(0.3, 0.5, 0.7), ..rough(BSDF_ROUGH_PLASTIC, 1e-4, 1e-4, beckmann) },
            false,
        );
        let sp = Model::new(&Material { reflectance: c4(0.3, 0.5, 0.7), ..material(BSDF_PLASTIC) }, false);
        for cos in [1.0f32, 0.5, 0.1] {
            let wo = polar(cos, 0.0);
            let (a, _) = sampled_albedo(&rp, wo, 50000, Sampler::new(4, 77, 1));
            let (b, _) = sampled_albedo(&sp, wo, 50000, Sampler::new(4, 77, 1));
            assert!(close3(a, b, 0.02, 2e-3), "roughplastic α→0 cos {cos}: albedo {a} vs plastic {b}");
        }
    }
}

/// Grazing and degenerate directions, extreme roughness and IOR: nothing may produce NaN or ±∞.
#[test]
fn stiff_inputs_are_finite() {
    let mut materials = Vec::new();
    for beckmann in [false, true] {
        for (au, av) in [(1e-4f32, 1e-4f32), (1.0, 1.0), (1e-4, 1.0), (0.0, 0.0), (2.0, 2.0)] {
            for eta in [1.0001f32, 1.5, 2.42] {
                materials.push(Material { eta, ..rough(BSDF_ROUGH_DIELECTRIC, au, av, beckmann) });
                if eta != 1.5 {
                    materials.push(Material { eta, ..rough(BSDF_ROUGH_PLASTIC, au, au, beckmann) });
                }
            }
            for (n, k) in [(0.0f32, 0.0f32), (1.0, 0.0), (0.2, 1e3), (1.5, 0.0)] {
                materials.push(Material {
                    conductor_eta: c4(n, n, n),
                    conductor_k: c4(k, k, k),
                    ..rough(BSDF_ROUGH_CONDUCTOR, au, av, beckmann)
                });
            }
        }
    }
    for eta in [1.0f32, 1.0001, 1.5, 2.42] {
        materials.push(Material { eta, ..material(BSDF_DIELECTRIC) });
        materials.push(Material { eta, ..material(BSDF_THIN_DIELECTRIC) });
        materials.push(Material { eta, ..material(BSDF_PLASTIC) });
    }
    for (n, k) in [(0.0f32, 0.0f32), (1.0, 0.0), (0.2, 1e3)] {
        materials.push(Material {
            conductor_eta: c4(n, n, n),
            conductor_k: c4(k, k, k),
            ..material(BSDF_CONDUCTOR)
        });
    }
    let mut dirs = vec![
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        -Vec3::Y,
        dir(1.0, 1.0, 0.0),
        polar(1e-4, 0.3),
        polar(-1e-4, 0.3),
        polar(1e-7, 2.0),
        polar(0.01, 1.0),
        polar(-0.01, 4.0),
    ];
    dirs.extend(random_dirs(8, 21));
    let us = [
        Vec2::ZERO,
        Vec2::new(0.99999994, 0.99999994),
        Vec2::new(0.5, 0.5),
        Vec2::new(0.0, 0.99999994),
        Vec2::new(0.25, 0.7),
    ];
    for m in &materials {
        let base = Model::new(m, false);
        for adjoint in [false, true] {
            let mut b = base;
            b.mode = if adjoint { TransportMode::Importance } else { TransportMode::Radiance };
            for &wo in &dirs {
                let mut wis = dirs.clone();
                wis.extend([wo, -wo, reflect(wo), -reflect(wo)]);
                for &wi in &wis {
                    let (f, pdf) = (b.eval(wo, wi), b.pdf(wo, wi));
                    assert!(
                        f.is_finite() && f.min_element() >= 0.0 && pdf.is_finite() && pdf >= 0.0,
                        "kind {} αu={} η={} wo={wo} wi={wi}: eval {f}, pdf {pdf}",
                        m.kind,
                        m.alpha_u,
                        m.eta
                    );
                }
                for &u in &us {
                    for ul in [0.0f32, 0.5, 0.99999994] {
                        let s = b.sample(wo, ul, u);
                        assert!(
                            s.pdf.is_finite()
                                && s.pdf >= 0.0
                                && s.weight.is_finite()
                                && s.weight.min_element() >= 0.0
                                && s.eta.is_finite(),
                            "kind {} αu={} η={} wo={wo} u={u}: sample {} {} {}",
                            m.kind,
                            m.alpha_u,
                            m.eta,
                            s.wi,
                            s.weight,
                            s.pdf
                        );
                        if s.pdf > 0.0 {
                            assert!(
                                s.wi.is_finite() && close(s.wi.length(), 1.0, 1e-3, 1e-3),
                                "kind {} wo={wo}: wi {}",
                                m.kind,
                                s.wi
                            );
                        }
                    }
                }
            }
        }
    }
}
