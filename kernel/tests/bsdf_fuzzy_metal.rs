//! Fuzzy metal (Ray Tracing in One Weekend's metal: the mirror direction displaced by a random point
//! in a ball): its sampling against the closed-form density, and that density's normalisation. Its
//! non-reciprocity is checked in `bsdf_reciprocity_energy.rs`.
mod common;
use caustic_kernel::glam::Vec3;
use common::bsdf_checks::{chi2_model, mirror_grid, sphere_grid};
use common::models::*;
use common::*;

/// The book's sampling procedure against the closed-form density, from narrow to the widest lobe and
/// from normal to grazing incidence (where most of the ball lies below the surface and is absorbed).
#[test]
fn fuzzy_metal_chi2() {
    let cases = [(0.002f32, 0.8f32), (0.05, 0.3), (0.3, 1.0), (0.5, 0.05), (1.0, 0.6), (1.0, 0.01)];
    for (k, (fuzz, cos)) in cases.iter().enumerate() {
        let wo = polar(*cos, 0.4);
        let grid = if *fuzz < 0.1 { mirror_grid(wo) } else { sphere_grid() };
        chi2_model(
            &format!("fuzzymetal fuzz={fuzz} wo={wo}"),
            &Model::new(&fuzzy(*fuzz), false),
            wo,
            &grid,
            k as u32,
        );
    }
}

/// At normal incidence the displaced ball lies wholly above the surface (it touches the origin only
/// for fuzz 1), so the density integrates to exactly 1.
#[test]
fn fuzzy_metal_density_is_normalised() {
    for fuzz in [0.01f32, 0.2, 0.7, 1.0] {
        let b = Model::new(&fuzzy(fuzz), false);
        // Bins crowded near the axis resolve narrow lobes (their edge is a square-root cusp).
        let grid = Grid::around(Vec3::Z, if fuzz < 0.1 { 6.0 } else { 1.0 });
        let mass: f64 = integrate_grid(&grid, &|wi| b.pdf(Vec3::Z, wi) as f64).iter().sum();
        assert!((mass - 1.0).abs() < 2e-4, "fuzzymetal {fuzz}: density integrates to {mass}");
    }
}
