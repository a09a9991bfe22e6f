//! Checks that more than one test file runs on BSDF models: reciprocity, the albedo by quadrature and
//! by the mean sampling weight (energy conservation), and the χ² fit of a model's sampling to its pdf.
//! Each check takes the tolerances of its callers as arguments: the files test different models at
//! different precisions, and one copy of the logic keeps them testing the same thing.
use super::chi2::{chi2_grid, integrate_grid, Grid};
use super::models::Model;
use caustic_kernel::bsdf::fresnel::reflect;
use caustic_kernel::bsdf::microfacet::Microfacet;
use caustic_kernel::bsdf::pplastic::PPlastic;
use caustic_kernel::bsdf::rough_conductor::RoughConductor;
use caustic_kernel::bsdf::rough_dielectric::RoughDielectric;
use caustic_kernel::bsdf::rough_plastic::RoughPlastic;
use caustic_kernel::bsdf::TransportMode;
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;

// ---------------------------------------------------------------------------------------------------
// Reciprocity.

/// `f(wo, wi)` of `b`: `eval` without the `|cos θi|` it includes.
fn f(b: &Model, wo: Vec3, wi: Vec3) -> Vec3 {
    b.eval(wo, wi) / wi.z.abs().max(1e-8)
}

/// Reciprocity of `b` (its transport mode is ignored) on the pairs `(wo, wi)` of `dirs`, taken two by
/// two, except those `skip` names:
/// - the radiance BSDF is the importance BSDF with its arguments swapped (pbrt's and Mitsuba's
///   definition of the adjoint, which holds for refraction too);
/// - on the same side of the surface, and for models that never transmit, `f` itself is symmetric —
///   except for fuzzy metal, the book's model, which is not reciprocal: there `f·cos θi` (the density
///   of the displaced mirror direction) is the symmetric quantity.
///
/// `same(a, b)` is the caller's tolerance. Returns how many pairs had a non-zero value, so that the
/// caller can require enough of them to have tested something.
pub fn check_reciprocity(
    name: &str,
    b: &Model,
    dirs: &[Vec3],
    same: impl Fn(Vec3, Vec3) -> bool,
    skip: impl Fn(Vec3, Vec3) -> bool,
) -> u32 {
    let rad = b.in_mode(TransportMode::Radiance);
    let imp = b.in_mode(TransportMode::Importance);
    let transmits = b.bsdf.flags().has_transmission();
    let mut nonzero = 0;
    for pair in dirs.chunks(2) {
        let (wo, wi) = (pair[0], pair[1]);
        if skip(wo, wi) {
            continue;
        }
        let f1 = f(&rad, wo, wi);
        let f2 = f(&imp, wi, wo);
        assert!(same(f1, f2), "{name}: f({wo}, {wi}) = {f1} but adjoint f({wi}, {wo}) = {f2}");
        if b.kind() == BSDF_FUZZY_METAL {
            let (c1, c3) = (rad.eval(wo, wi), rad.eval(wi, wo));
            assert!(same(c1, c3), "{name}: f·cos not symmetric: {c1} vs {c3}");
        } else if wo.z * wi.z > 0.0 || !transmits {
            let f3 = f(&rad, wi, wo);
            assert!(same(f1, f3), "{name}: f({wo}, {wi}) = {f1} but f({wi}, {wo}) = {f3}");
        }
        nonzero += (f1.max_element() > 0.0) as u32;
    }
    nonzero
}

// ---------------------------------------------------------------------------------------------------
// Energy.

/// Directional albedo `∫ f·cos dωi` of `b` seen from `wo`, per channel, by adaptive quadrature over
/// `grid` (a grid crowded around the mirror direction resolves narrow lobes).
pub fn albedo(b: &Model, wo: Vec3, grid: &Grid) -> Vec3 {
    let channel =
        |c: usize| -> f32 { integrate_grid(grid, &|wi| b.eval(wo, wi)[c] as f64).iter().sum::<f64>() as f32 };
    Vec3::new(channel(0), channel(1), channel(2))
}

/// A grid crowded around the mirror direction of `wo`, for `albedo` of narrow reflection lobes.
pub fn mirror_albedo_grid(wo: Vec3) -> Grid {
    Grid::around(reflect(wo), 3.0)
}

/// Mean sampling weight `f·cos/pdf` of `n` samples from `wo` (failed samples count as zero), and its
/// standard error (the largest channel's). Every weight must be finite and non-negative.
pub fn sampled_albedo(b: &Model, wo: Vec3, n: usize, mut rng: Sampler) -> (Vec3, f32) {
    let (mut sum, mut sq) = (Vec3::ZERO, Vec3::ZERO);
    for _ in 0..n {
        let ul = rng.next_1d();
        let s = b.sample(wo, ul, rng.next_2d());
        if s.pdf > 0.0 {
            assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0, "weight {}", s.weight);
            sum += s.weight;
            sq += s.weight * s.weight;
        }
    }
    let mean = sum / n as f32;
    let var = (sq / n as f32 - mean * mean).max(Vec3::ZERO) / n as f32;
    (mean, var.max_element().sqrt())
}

/// Energy conservation seen from `wo`: the albedo `a` (by quadrature, plus any Dirac lobe's energy)
/// is at most `1 + 2e-3 + excess` in every channel, and the mean of `n` sampling weights (`rng`)
/// agrees with it to 5 standard errors + 2e-3 (sampling weights and `eval` describe the same BSDF).
pub fn check_energy(name: &str, b: &Model, wo: Vec3, a: Vec3, excess: f32, n: usize, rng: Sampler) {
    assert!(a.max_element() <= 1.0 + 2e-3 + excess, "{name} wo={wo}: albedo {a} > 1");
    let (mean, se) = sampled_albedo(b, wo, n, rng);
    assert!(
        (mean - a).abs().max_element() <= 5.0 * se + 2e-3,
        "{name} wo={wo}: sampled albedo {mean} ± {se} vs quadrature {a}"
    );
}

// ---------------------------------------------------------------------------------------------------
// χ² fits of the models' sampling against their pdfs.

/// Smith's exact `G1` for the Beckmann distribution, `1 / (1 + Λ)`, where the models (like Mitsuba)
/// use Walter et al.'s rational fit.
pub fn beckmann_g1_exact(d: &Microfacet, w: Vec3) -> f64 {
    let xy = ((d.alpha_u * w.x).powi(2) + (d.alpha_v * w.y).powi(2)) as f64;
    if xy == 0.0 {
        return 1.0;
    }
    let a = w.z.abs() as f64 / xy.sqrt();
    let lambda = (statrs::function::erf::erf(a) - 1.0) / 2.0
        + (-a * a).exp() / (2.0 * a * std::f64::consts::PI.sqrt());
    1.0 / (1.0 + lambda)
}

/// The factor between the density of the visible normals the Beckmann sampler draws (normalised by the
/// exact `G1`) and the reported pdf (which uses the fit): a constant for a given view direction.
pub fn beckmann_correction(d: &Microfacet, w: Vec3) -> f64 {
    if !d.beckmann {
        return 1.0;
    }
    let w = w * w.z.signum();
    beckmann_g1_exact(d, w) / d.smith_g1(w, Vec3::Z) as f64
}

/// The density `b.sample(wo, ·)` draws directions with: `b.pdf`, with the microfacet lobes rescaled
/// by `beckmann_correction`.
pub fn sampling_density(b: &Model, wo: Vec3, wi: Vec3) -> f64 {
    let pdf = b.pdf(wo, wi) as f64;
    match b.kind() {
        BSDF_ROUGH_CONDUCTOR => pdf * beckmann_correction(&b.concrete::<RoughConductor>().distr, wo),
        BSDF_ROUGH_DIELECTRIC => pdf * beckmann_correction(&b.concrete::<RoughDielectric>().distr, wo),
        BSDF_ROUGH_PLASTIC if wo.z > 0.0 && wi.z > 0.0 => {
            let r = b.concrete::<RoughPlastic>();
            let h = (wo + wi).normalize();
            let glossy =
                r.specular_probability(r.transmittance(wo.z)) * r.distr.d(h) * r.distr.smith_g1(wo, h)
                    / (4.0 * wo.z);
            pdf + (beckmann_correction(&r.distr, wo) - 1.0) * glossy as f64
        }
        BSDF_PPLASTIC if wo.z > 0.0 && wi.z > 0.0 => {
            let p = b.concrete::<PPlastic>();
            let h = (wo + wi).normalize();
            let glossy = p.specular_probability * p.distr.d(h) * p.distr.smith_g1(wo, h) / (4.0 * wo.z);
            pdf + (beckmann_correction(&p.distr, wo) - 1.0) * glossy as f64
        }
        _ => pdf,
    }
}

/// Runs the χ² test of `b` seen from `wo` on `grid` (Dirac-delta samples count as "no direction").
pub fn chi2_model(name: &str, b: &Model, wo: Vec3, grid: &Grid, seed: u32) {
    chi2_grid(
        name,
        grid,
        seed,
        |ul, u| {
            let s = b.sample(wo, ul, u);
            (s.pdf > 0.0 && !s.delta).then_some(s.wi)
        },
        |wi| sampling_density(b, wo, wi),
    );
}

/// The mirror direction of `wo` as the grid axis, for narrow reflection lobes.
pub fn mirror_grid(wo: Vec3) -> Grid {
    let mut g = Grid::around(reflect(wo), 3.0);
    g.mass_tolerance = 5e-3;
    g
}

pub fn sphere_grid() -> Grid {
    let mut g = Grid::sphere();
    g.mass_tolerance = 5e-3;
    g
}
