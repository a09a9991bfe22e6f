//! Microfacet distributions (`bsdf::microfacet`, GGX and Beckmann, isotropic and anisotropic) on their
//! own: erf/erfinv, normalisation of `D` and of the visible normals' density, and χ² of the visible
//! normal sampling. The rough models built on them are tested in their own files.
mod common;
use caustic_kernel::bsdf::microfacet::{erf, erfinv, Microfacet};
use caustic_kernel::glam::Vec3;
use common::bsdf_checks::beckmann_correction;
use common::models::{close, polar};
use common::*;

fn distributions() -> Vec<Microfacet> {
    let mut v = Vec::new();
    for beckmann in [false, true] {
        for (au, av) in [(0.05f32, 0.05f32), (0.1, 0.1), (0.5, 0.5), (1.0, 1.0), (0.05, 0.4), (0.6, 0.1)] {
            v.push(Microfacet::new(au, av, beckmann));
        }
    }
    v
}

fn name_of(d: &Microfacet) -> String {
    format!("{} αu={} αv={}", if d.beckmann { "beckmann" } else { "ggx" }, d.alpha_u, d.alpha_v)
}

#[test]
fn erf_and_erfinv() {
    for (x, want) in [
        (0.1f32, 0.112_462_92f32),
        (0.5, 0.520_499_9),
        (1.0, 0.842_700_8),
        (2.0, 0.995_322_3),
        (3.0, 0.999_977_9),
    ] {
        assert!(
            close(erf(x), want, 1e-5, 2e-7) && close(erf(-x), -want, 1e-5, 2e-7),
            "erf({x}) = {}",
            erf(x)
        );
    }
    for i in -99..=99 {
        let x = i as f32 / 100.0;
        assert!(close(erf(erfinv(x)), x, 1e-5, 3e-7), "erf(erfinv({x})) = {}", erf(erfinv(x)));
    }
    assert!(erfinv(1.0).is_finite() && erfinv(-1.0).is_finite());
}

/// `∫ D(m) cos θm dm = 1` and the visible normals' density integrates to 1 for every view.
#[test]
fn microfacet_densities_are_normalised() {
    let grid = Grid::coarse(Vec3::Z);
    for d in distributions() {
        let d_mass: f64 = integrate_grid(&grid, &|m| (d.d(m) * m.z.max(0.0)) as f64).iter().sum();
        assert!((d_mass - 1.0).abs() < 2e-3, "{}: ∫D cos = {d_mass}", name_of(&d));
        for w in [Vec3::Z, polar(0.5, 0.3), polar(0.01, 2.0)] {
            let mass: f64 = integrate_grid(&grid, &|m| d.pdf(w, m) as f64).iter().sum();
            // Beckmann's G1 is Walter et al.'s rational fit (< 0.35 % off), as in Mitsuba.
            let tol = if d.beckmann { 5e-3 } else { 2e-3 };
            assert!((mass - 1.0).abs() < tol, "{} w={w}: visible normals integrate to {mass}", name_of(&d));
        }
    }
}

#[test]
fn microfacet_visible_normal_sampling_chi2() {
    let cases = [
        ((0.1f32, 0.1f32), 1.0f32),
        ((0.5, 0.5), 0.5),
        ((1.0, 1.0), 0.01),
        ((0.05, 0.4), 0.3),
        ((0.3, 0.3), 0.01),
    ];
    for beckmann in [false, true] {
        for (k, ((au, av), cos)) in cases.iter().enumerate() {
            let d = Microfacet::new(*au, *av, beckmann);
            let w = polar(*cos, 0.4);
            let mut grid = Grid::sphere();
            grid.mass_tolerance = 5e-3;
            let c = beckmann_correction(&d, w);
            chi2_grid(
                &format!("normals {} w={w}", name_of(&d)),
                &grid,
                k as u32,
                |_, u| {
                    let s = d.sample(w, u);
                    (s.pdf > 0.0).then_some(s.m)
                },
                |m| d.pdf(w, m) as f64 * c,
            );
        }
    }
}
