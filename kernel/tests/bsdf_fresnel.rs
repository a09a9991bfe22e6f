//! The Fresnel terms every model builds on (`bsdf::fresnel`): the dielectric's limits, Snell's law
//! and reciprocity across the interface; the conductor's limits (k = 0 is a dielectric, eta 0 k 1 a
//! perfect mirror); the fits of the diffuse Fresnel reflectance against quadrature.
mod common;
use caustic_kernel::bsdf::fresnel::*;
use common::models::{close, close3, polar};

#[test]
fn dielectric_fresnel_limits_and_snell() {
    for eta in [1.0001f32, 1.33, 1.5, 2.42] {
        let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!(
            close(fresnel(1.0, eta).f, f0, 1e-5, 1e-9) && close(fresnel(-1.0, eta).f, f0, 1e-5, 1e-9),
            "normal incidence, eta {eta}"
        );
        assert_eq!(fresnel(0.0, eta).f, 1.0, "grazing incidence reflects everything");
        for i in 0..=200 {
            let c = i as f32 / 200.0;
            for cos_i in [c, -c] {
                let fr = fresnel(cos_i, eta);
                assert!(fr.f.is_finite() && (0.0..=1.0).contains(&fr.f), "F({cos_i}, {eta}) = {}", fr.f);
                let w = polar(cos_i, 0.7);
                let (n_i, n_t) = if cos_i >= 0.0 { (1.0, eta) } else { (eta, 1.0) };
                assert_eq!(fr.eta_it, n_t / n_i);
                if n_i * (1.0 - cos_i * cos_i).sqrt() > n_t * (1.0 + 1e-5) {
                    assert!(
                        fr.f == 1.0 && fr.cos_theta_t == 0.0,
                        "total internal reflection at cos {cos_i}, eta {eta}"
                    );
                    continue;
                }
                let wt = refract(w, fr.cos_theta_t, fr.eta_ti);
                assert!(close(wt.length(), 1.0, 1e-5, 1e-5), "refracted direction is not unit");
                assert!(wt.z * cos_i <= 0.0, "refraction must cross the interface");
                // Snell's law, and the same reflectance seen from the other side.
                let (sin_i, sin_t) = (w.truncate().length(), wt.truncate().length());
                assert!(close(n_i * sin_i, n_t * sin_t, 1e-5, 1e-6));
                if fr.cos_theta_t.abs() > 1e-2 && c > 1e-2 {
                    assert!(
                        close(fresnel(wt.z, eta).f, fr.f, 1e-3, 1e-6),
                        "Fresnel is not reciprocal at cos {cos_i}, eta {eta}"
                    );
                }
            }
        }
    }
    // Matched indices: nothing reflects, the ray passes straight through.
    let w = polar(0.3, 1.0);
    let fr = fresnel(w.z, 1.0);
    assert_eq!(fr.f, 0.0);
    assert!(close3(refract(w, fr.cos_theta_t, fr.eta_ti), -w, 1e-6, 1e-6));
}

#[test]
fn conductor_fresnel_limits() {
    // k = 0 is a dielectric.
    for eta in [1.2f32, 1.5, 2.42] {
        for i in 1..=100 {
            let c = i as f32 / 100.0;
            assert!(
                close(fresnel_conductor(c, eta, 0.0), fresnel(c, eta).f, 2e-4, 1e-6),
                "k = 0, eta {eta}, cos {c}"
            );
        }
    }
    for (n, k) in [
        (0.2f32, 3.9f32),
        (1.1, 2.2),
        (0.0, 1.0),
        (1.0, 1000.0),
        (3.0, 0.5),
        (1.0, 0.0),
        (0.0, 0.0),
        (1e-3, 1e-3),
    ] {
        let normal = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
        assert!(close(fresnel_conductor(1.0, n, k), normal, 1e-5, 1e-6), "normal incidence ({n}, {k})");
        for i in 0..=100 {
            let f = fresnel_conductor(i as f32 / 100.0, n, k);
            assert!(
                f.is_finite() && (0.0..=1.0 + 1e-6).contains(&f),
                "F({}, {n}, {k}) = {f}",
                i as f32 / 100.0
            );
            if k >= 1000.0 {
                assert!(f > 0.99, "a strong absorber is a mirror");
            }
        }
    }
    // eta = 0, k = 1 (Mitsuba's default) is a perfect mirror.
    assert!(close(fresnel_conductor(0.37, 0.0, 1.0), 1.0, 1e-6, 1e-6));
}

/// Fdr = 2∫F(μ)μ dμ; the fits Mitsuba uses are good to well under 1 % in this range.
#[test]
fn diffuse_fresnel_reflectance_fits_quadrature() {
    for eta in [1.1f32, 1.33, 1.5, 2.0, 2.42, 1.0 / 1.1, 1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.0] {
        let n = 20000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let mu = (i as f64 + 0.5) / n as f64;
            sum += fresnel(mu as f32, eta).f as f64 * mu;
        }
        let quad = 2.0 * sum / n as f64;
        let fit = fresnel_diffuse_reflectance(eta) as f64;
        assert!((fit - quad).abs() <= 0.01 * quad + 1e-3, "Fdr({eta}) fit {fit} vs quadrature {quad}");
    }
}
