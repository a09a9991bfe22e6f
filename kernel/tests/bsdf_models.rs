//! Tests of the Mitsuba-style BSDF models: agreement with Mitsuba 3.9.1's own values, χ² fits of every
//! sampling routine against its pdf, reciprocity, energy conservation, the Fresnel terms' limits,
//! and finiteness at stiff inputs.
mod common;
use caustic_kernel::bsdf::fresnel::*;
use caustic_kernel::bsdf::microfacet::{erf, erfinv, Microfacet};
use caustic_kernel::bsdf::plastic::Plastic;
use caustic_kernel::bsdf::rough_conductor::RoughConductor;
use caustic_kernel::bsdf::rough_dielectric::RoughDielectric;
use caustic_kernel::bsdf::rough_plastic::{self, RoughPlastic};
use caustic_kernel::bsdf::{Bsdf, BsdfSample, Bxdf, TransportMode};
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use caustic_kernel::sampling::square_to_uniform_sphere;
use common::*;

// ---------------------------------------------------------------------------------------------------
// The models behind one interface.

/// A model as the integrators see it: `Bsdf` (the one dispatch) in a transport mode.
#[derive(Clone, Copy)]
struct Model {
    bsdf: Bsdf<'static>,
    mode: TransportMode,
}

impl Model {
    /// Builds the model of `m` as the host would: precomputes what it needs, evaluates no textures.
    fn new(m: &Material, adjoint: bool) -> Model {
        let mut m = *m;
        // Behind some unrelated data, as in the host's table buffer.
        let mut tables = vec![7.0f32; 5];
        if let Some(table) = caustic_kernel::bsdf::precompute(&mut m) {
            m.table = tables.len() as u32;
            tables.extend(table);
        }
        let tables: &'static [f32] = Box::leak(tables.into_boxed_slice());
        let mode = if adjoint { TransportMode::Importance } else { TransportMode::Radiance };
        Model { bsdf: Bsdf::from_material(&m, tables), mode }
    }

    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.bsdf.eval(wo, wi, self.mode)
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.bsdf.pdf(wo, wi, self.mode)
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> BsdfSample {
        self.bsdf.sample(wo, u_lobe, u, self.mode)
    }

    /// The concrete model, for tests that look inside it.
    fn concrete<M: Bxdf<'static>>(&self) -> M {
        M::from_material(&self.bsdf.material, self.bsdf.reflectance, self.bsdf.specular, self.bsdf.tables)
    }
}

fn rgb(c: [f32; 4]) -> Vec3 {
    Vec3::new(c[0], c[1], c[2])
}

fn c4(r: f32, g: f32, b: f32) -> [f32; 4] {
    [r, g, b, 0.0]
}

/// A material of `kind` with Mitsuba's defaults where the host would fill them in: unit specular
/// reflectance and transmittance, a perfect-mirror conductor (eta 0, k 1), diffuse 0.5, IOR 1.5.
fn material(kind: u32) -> Material {
    Material {
        kind,
        eta: 1.5,
        alpha_u: 0.1,
        alpha_v: 0.1,
        reflectance: c4(0.5, 0.5, 0.5),
        specular_reflectance: c4(1.0, 1.0, 1.0),
        specular_transmittance: c4(1.0, 1.0, 1.0),
        conductor_eta: c4(0.0, 0.0, 0.0),
        conductor_k: c4(1.0, 1.0, 1.0),
        ..Default::default()
    }
}

fn rough(kind: u32, alpha_u: f32, alpha_v: f32, beckmann: bool) -> Material {
    Material { alpha_u, alpha_v, flags: if beckmann { MATERIAL_BECKMANN } else { 0 }, ..material(kind) }
}

fn dir(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z).normalize()
}

/// A unit direction with cosine `cos_theta` and azimuth `phi`.
fn polar(cos_theta: f32, phi: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta)
}

fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= abs + rel * a.abs().max(b.abs())
}

fn close3(a: Vec3, b: Vec3, rel: f32, abs: f32) -> bool {
    close(a.x, b.x, rel, abs) && close(a.y, b.y, rel, abs) && close(a.z, b.z, rel, abs)
}

// ---------------------------------------------------------------------------------------------------
// Agreement with Mitsuba 3.9.1. `EVAL_REFS` and `SAMPLE_REFS` (at the end of the file) were produced by
// its Python bindings (`pip install mitsuba==3.9.1`, variant `scalar_rgb`) from the dictionaries that
// `reference_material` mirrors, with `ext_ior = 1`: for random `wo` (Mitsuba's `si.wi`) and `wi`
// (its `wo`; half of them near a sampled direction), `bsdf.eval(ctx, si, wi)` and `bsdf.pdf(ctx, si,
// wi)`, and `bsdf.sample(ctx, si, u_lobe, u)` for random numbers, with `ctx` in `Radiance` or
// `Importance` mode (`adjoint`).

struct EvalRef {
    model: &'static str,
    adjoint: bool,
    wo: [f32; 3],
    wi: [f32; 3],
    f: [f32; 3],
    pdf: f32,
}

struct SampleRef {
    model: &'static str,
    adjoint: bool,
    wo: [f32; 3],
    u_lobe: f32,
    u: [f32; 2],
    wi: [f32; 3],
    weight: [f32; 3],
    pdf: f32,
    eta: f32,
}

/// The materials of the reference values (the same parameters as the Mitsuba dictionaries that
/// produced them; `ext_ior` was 1 there).
fn reference_material(name: &str) -> Material {
    let (eta, k) = (c4(0.2, 0.9, 1.1), c4(3.9, 2.4, 2.2));
    let (sr, st) = (c4(0.9, 0.8, 0.7), c4(0.6, 0.7, 0.8));
    match name {
        "conductor" => Material {
            conductor_eta: eta,
            conductor_k: k,
            specular_reflectance: c4(1.0, 0.8, 0.6),
            ..material(BSDF_CONDUCTOR)
        },
        "rough_conductor_ggx_aniso" => Material {
            conductor_eta: eta,
            conductor_k: k,
            specular_reflectance: c4(1.0, 0.8, 0.6),
            ..rough(BSDF_ROUGH_CONDUCTOR, 0.1, 0.4, false)
        },
        "rough_conductor_beckmann" => {
            Material { conductor_eta: eta, conductor_k: k, ..rough(BSDF_ROUGH_CONDUCTOR, 0.3, 0.3, true) }
        }
        "dielectric" => {
            Material { specular_reflectance: sr, specular_transmittance: st, ..material(BSDF_DIELECTRIC) }
        }
        "thin_dielectric" => Material {
            specular_reflectance: sr,
            specular_transmittance: st,
            ..material(BSDF_THIN_DIELECTRIC)
        },
        "rough_dielectric_ggx" => Material {
            specular_reflectance: sr,
            specular_transmittance: st,
            ..rough(BSDF_ROUGH_DIELECTRIC, 0.2, 0.2, false)
        },
        "rough_dielectric_beckmann_aniso" => {
            Material { eta: 2.42, ..rough(BSDF_ROUGH_DIELECTRIC, 0.05, 0.3, true) }
        }
        "plastic" => Material { reflectance: c4(0.3, 0.5, 0.7), ..material(BSDF_PLASTIC) },
        "plastic_nonlinear" => Material {
            eta: 1.9,
            flags: MATERIAL_NONLINEAR,
            reflectance: c4(0.8, 0.4, 0.1),
            specular_reflectance: c4(0.9, 0.7, 0.9),
            ..material(BSDF_PLASTIC)
        },
        "rough_plastic_beckmann" => {
            Material { reflectance: c4(0.3, 0.5, 0.7), ..rough(BSDF_ROUGH_PLASTIC, 0.1, 0.1, true) }
        }
        "rough_plastic_ggx_nonlinear" => Material {
            eta: 1.9,
            flags: MATERIAL_NONLINEAR,
            reflectance: c4(0.8, 0.4, 0.1),
            specular_reflectance: c4(0.9, 0.7, 0.9),
            ..rough(BSDF_ROUGH_PLASTIC, 0.4, 0.4, false)
        },
        _ => panic!("unknown reference model {name}"),
    }
}

/// The reference models, built once (rough plastic's precomputation is not free).
fn reference_model(name: &str, adjoint: bool) -> Model {
    use std::collections::HashMap;
    use std::sync::Mutex;
    static CACHE: Mutex<Option<HashMap<(String, bool), Model>>> = Mutex::new(None);
    let mut cache = CACHE.lock().unwrap();
    *cache
        .get_or_insert_with(HashMap::new)
        .entry((name.to_string(), adjoint))
        .or_insert_with(|| Model::new(&reference_material(name), adjoint))
}

#[test]
fn eval_and_pdf_match_mitsuba() {
    let mut worst = 0.0f32;
    for r in EVAL_REFS {
        let b = reference_model(r.model, r.adjoint);
        let (wo, wi) = (Vec3::from(r.wo), Vec3::from(r.wi));
        let f = b.eval(wo, wi);
        let pdf = b.pdf(wo, wi);
        let want = Vec3::from(r.f);
        let scale = want.max_element().max(1e-3);
        worst = worst.max((f - want).abs().max_element() / scale);
        assert!(
            close3(f, want, 2e-3, 1e-6),
            "{} adjoint={}: eval({wo}, {wi}) = {f}, Mitsuba {want}",
            r.model,
            r.adjoint
        );
        assert!(
            close(pdf, r.pdf, 2e-3, 1e-6),
            "{} adjoint={}: pdf({wo}, {wi}) = {pdf}, Mitsuba {}",
            r.model,
            r.adjoint,
            r.pdf
        );
    }
    let nonzero = EVAL_REFS.iter().filter(|r| r.pdf > 0.0).count();
    println!(
        "{} references ({nonzero} with pdf > 0), largest relative eval difference {worst:.2e}",
        EVAL_REFS.len()
    );
}

#[test]
fn samples_match_mitsuba() {
    for r in SAMPLE_REFS {
        let b = reference_model(r.model, r.adjoint);
        let wo = Vec3::from(r.wo);
        let s = b.sample(wo, r.u_lobe, Vec2::from(r.u));
        let want_w = Vec3::from(r.weight);
        // Mitsuba returns zero-weight samples where caustic reports none (pdf 0): both end the path.
        if r.pdf == 0.0 || want_w == Vec3::ZERO {
            assert!(
                s.pdf == 0.0 || s.weight == Vec3::ZERO,
                "{}: Mitsuba's sample is void, ours {} {}",
                r.model,
                s.wi,
                s.weight
            );
            continue;
        }
        let ctx = format!("{} adjoint={} wo={wo} u=({}, {:?})", r.model, r.adjoint, r.u_lobe, r.u);
        assert!(close3(s.wi, Vec3::from(r.wi), 1e-3, 1e-4), "{ctx}: wi {} vs Mitsuba {:?}", s.wi, r.wi);
        assert!(close3(s.weight, want_w, 3e-3, 1e-5), "{ctx}: weight {} vs Mitsuba {want_w}", s.weight);
        assert!(close(s.pdf, r.pdf, 3e-3, 1e-6), "{ctx}: pdf {} vs Mitsuba {}", s.pdf, r.pdf);
        assert_eq!(s.eta, r.eta, "{ctx}: eta");
    }
}
// ---------------------------------------------------------------------------------------------------
// Fresnel terms.

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

// ---------------------------------------------------------------------------------------------------
// Microfacet distributions.

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

// ---------------------------------------------------------------------------------------------------
// χ² fits of the models' sampling against their pdfs.

/// Smith's exact `G1` for the Beckmann distribution, `1 / (1 + Λ)`, where the models (like Mitsuba)
/// use Walter et al.'s rational fit.
fn beckmann_g1_exact(d: &Microfacet, w: Vec3) -> f64 {
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
fn beckmann_correction(d: &Microfacet, w: Vec3) -> f64 {
    if !d.beckmann {
        return 1.0;
    }
    let w = w * w.z.signum();
    beckmann_g1_exact(d, w) / d.smith_g1(w, Vec3::Z) as f64
}

/// The density `b.sample(wo, ·)` draws directions with: `b.pdf`, with the microfacet lobes rescaled
/// by `beckmann_correction`.
fn sampling_density(b: &Model, wo: Vec3, wi: Vec3) -> f64 {
    let pdf = b.pdf(wo, wi) as f64;
    match b.bsdf.material.kind {
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
        _ => pdf,
    }
}

/// Runs the χ² test of `b` seen from `wo` on `grid` (Dirac-delta samples count as "no direction").
fn chi2_model(name: &str, b: &Model, wo: Vec3, grid: &Grid, seed: u32) {
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
fn mirror_grid(wo: Vec3) -> Grid {
    let mut g = Grid::around(reflect(wo), 3.0);
    g.mass_tolerance = 5e-3;
    g
}

fn sphere_grid() -> Grid {
    let mut g = Grid::sphere();
    g.mass_tolerance = 5e-3;
    g
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

// ---------------------------------------------------------------------------------------------------
// Dirac-delta models.

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

// ---------------------------------------------------------------------------------------------------
// Reciprocity, energy, weights.

fn random_dirs(n: usize, seed: u32) -> Vec<Vec3> {
    let mut rng = Sampler::new(seed, 3, 4);
    (0..n).map(|_| square_to_uniform_sphere(rng.next_2d())).collect()
}

/// Models with smooth lobes over a range of parameters (radiance transport).
fn smooth_models() -> Vec<(String, Material)> {
    let mut v = Vec::new();
    for beckmann in [false, true] {
        let d = if beckmann { "beckmann" } else { "ggx" };
        for (au, av) in [(0.05f32, 0.05f32), (0.3, 0.3), (1.0, 1.0), (0.1, 0.5)] {
            v.push((
                format!("roughconductor {d} {au}/{av}"),
                Material {
                    conductor_eta: c4(0.2, 0.9, 1.1),
                    conductor_k: c4(3.9, 2.4, 2.2),
                    ..rough(BSDF_ROUGH_CONDUCTOR, au, av, beckmann)
                },
            ));
            for eta in [1.5f32, 2.42] {
                v.push((
                    format!("roughdielectric {d} {au}/{av} η={eta}"),
                    Material { eta, ..rough(BSDF_ROUGH_DIELECTRIC, au, av, beckmann) },
                ));
            }
        }
        for alpha in [0.05f32, 0.4, 1.0] {
            v.push((
                format!("roughplastic {d} {alpha}"),
                Material {
                    reflectance: c4(0.3, 0.5, 0.7),
                    ..rough(BSDF_ROUGH_PLASTIC, alpha, alpha, beckmann)
                },
            ));
        }
    }
    v.push(("plastic".into(), Material { reflectance: c4(0.3, 0.5, 0.7), ..material(BSDF_PLASTIC) }));
    v.push((
        "plastic nonlinear".into(),
        Material {
            flags: MATERIAL_NONLINEAR,
            eta: 2.0,
            reflectance: c4(0.9, 0.5, 0.1),
            ..material(BSDF_PLASTIC)
        },
    ));
    // Lobes wide enough for random direction pairs to land in them; narrow ones are fitted by χ².
    for fuzz in [0.3f32, 0.6, 1.0] {
        v.push((format!("fuzzymetal {fuzz}"), fuzzy(fuzz)));
    }
    v
}

fn fuzzy(fuzz: f32) -> Material {
    Material { alpha_u: fuzz, reflectance: c4(0.9, 0.6, 0.3), ..material(BSDF_FUZZY_METAL) }
}

#[test]
fn reciprocity() {
    let dirs = random_dirs(4000, 5);
    for (name, m) in smooth_models() {
        let rad = Model::new(&m, false);
        let mut imp = rad;
        imp.mode = TransportMode::Importance;
        let mut checked = 0;
        for pair in dirs.chunks(2) {
            let (wo, wi) = (pair[0], pair[1]);
            // The radiance BSDF is the adjoint (importance) BSDF with its arguments swapped; for
            // reflection both are symmetric.
            if wo.z * wi.z < 0.0 && near_critical(&m, wo, wi) {
                continue;
            }
            let f1 = rad.eval(wo, wi) / wi.z.abs();
            let f2 = imp.eval(wi, wo) / wo.z.abs();
            let f3 = rad.eval(wi, wo) / wo.z.abs();
            assert!(
                close3(f1, f2, 2e-3, 1e-6),
                "{name}: f({wo}, {wi}) = {f1} but adjoint f({wi}, {wo}) = {f2}"
            );
            if m.kind == BSDF_FUZZY_METAL {
                // The book's model is not reciprocal: `f·cos θi`, the density of the displaced mirror
                // direction, is the symmetric quantity.
                let (c1, c3) = (rad.eval(wo, wi), rad.eval(wi, wo));
                assert!(close3(c1, c3, 2e-3, 1e-6), "{name}: f·cos not symmetric: {c1} vs {c3}");
            } else if wo.z * wi.z > 0.0 {
                assert!(close3(f1, f3, 2e-3, 1e-6), "{name}: reflection not symmetric: {f1} vs {f3}");
            }
            checked += (f1.max_element() > 0.0) as u32;
        }
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

/// Albedo `∫ f cos dωi` by quadrature over the sphere (first channel: the furnace materials are grey).
fn albedo(b: &Model, wo: Vec3) -> f32 {
    integrate_grid(&Grid::coarse(Vec3::Z), &|wi| b.eval(wo, wi).x as f64).iter().sum::<f64>() as f32
}

/// Mean sampling weight and its standard error.
fn sampled_albedo(b: &Model, wo: Vec3, n: usize, seed: u32) -> (Vec3, f32) {
    let mut rng = Sampler::new(seed, 77, 1);
    let (mut sum, mut sq) = (Vec3::ZERO, Vec3::ZERO);
    for _ in 0..n {
        let ul = rng.next_1d();
        let s = b.sample(wo, ul, rng.next_2d());
        if s.pdf > 0.0 {
            assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0);
            sum += s.weight;
            sq += s.weight * s.weight;
        }
    }
    let mean = sum / n as f32;
    let var = (sq / n as f32 - mean * mean).max(Vec3::ZERO) / n as f32;
    (mean, var.max_element().sqrt())
}

/// White furnace: with white parameters no model reflects more than it receives (importance
/// transport for the refracting ones, whose radiance is rescaled by 1/η², radiance for fuzzy metal), and the mean sampling
/// weight estimates the same albedo as the quadrature of `eval` (plus the mirror lobe's F for
/// plastic).
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
            let mut a = albedo(&b, wo);
            if m.kind == BSDF_PLASTIC {
                let p: Plastic = b.concrete();
                a += p.specular.x * fresnel(cos, p.eta).f;
            }
            println!("{name} cos θo={cos}: albedo {a:.4}");
            assert!(a <= 1.0 + 2e-3 + extra, "{name} wo={wo}: albedo {a} > 1");
            let (mean, se) = sampled_albedo(&b, wo, 50_000, k as u32);
            assert!(
                (mean.x - a).abs() <= 5.0 * se + 2e-3,
                "{name} wo={wo}: sampled albedo {} ± {se} vs quadrature {a}",
                mean.x
            );
        }
    }
}

#[test]
fn sample_weights_equal_eval_over_pdf() {
    let wos = random_dirs(40, 11);
    for (name, m) in smooth_models() {
        let base = Model::new(&m, false);
        for adjoint in [false, true] {
            let mut b = base;
            b.mode = if adjoint { TransportMode::Importance } else { TransportMode::Radiance };
            let mut rng = Sampler::new(3, 3, 3);
            let mut checked = 0;
            for wo in &wos {
                for _ in 0..50 {
                    let ul = rng.next_1d();
                    let s = b.sample(*wo, ul, rng.next_2d());
                    if s.pdf <= 0.0 || s.delta {
                        continue;
                    }
                    let (f, pdf) = (b.eval(*wo, s.wi), b.pdf(*wo, s.wi));
                    assert!(
                        close(s.pdf, pdf, 2e-3, 1e-6),
                        "{name} wo={wo} wi={}: sample pdf {} vs pdf {pdf}",
                        s.wi,
                        s.pdf
                    );
                    assert!(
                        close3(s.weight, f / pdf, 2e-3, 1e-6),
                        "{name} wo={wo} wi={}: weight {} vs eval/pdf {}",
                        s.wi,
                        s.weight,
                        f / pdf
                    );
                    checked += 1;
                }
            }
            assert!(checked > 500, "{name}: only {checked} samples");
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// Limits and stiff inputs.

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
            let (mean, _) = sampled_albedo(&b, wo, 20000, 9);
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
            let (a, _) = sampled_albedo(&rp, wo, 50000, 4);
            let (b, _) = sampled_albedo(&sp, wo, 50000, 4);
            assert!(close3(a, b, 0.02, 2e-3), "roughplastic α→0 cos {cos}: albedo {a} vs plastic {b}");
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

const EVAL_REFS: &[EvalRef] = &[
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.176278163, 0.718409941, 0.672913936],
        f: [0.0111998357, 0.00582021708, 0.00374683738],
        pdf: 0.0123149892,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.968256513, -0.243572626, 0.0561400081],
        f: [0.00111291592, 0.000575935119, 0.000367790024],
        pdf: 0.00212961202,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.781354268, -0.228107581, 0.580906566],
        wi: [0.0416964422, 0.985148709, 0.166563583],
        f: [0.00114245864, 0.000593383273, 0.000381743419],
        pdf: 0.00214686478,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.781354268, -0.228107581, 0.580906566],
        wi: [-0.437634265, 0.76557301, 0.471565706],
        f: [0.0309669543, 0.0161336884, 0.0104154944],
        pdf: 0.0358472988,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.487087524, 0.123423095, 0.864588042],
        wi: [-0.573214564, -0.547249836, 0.609871035],
        f: [0.00191152736, 0.000989236753, 0.000631878967],
        pdf: 0.00207508192,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.487087524, 0.123423095, 0.864588042],
        wi: [0.485989379, -0.733998694, 0.474405145],
        f: [0.552568078, 0.2864317, 0.183740497],
        pdf: 0.633852363,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.956990472, -0.100707608, 0.272079426],
        wi: [-0.680216199, -0.717895906, -0.14809251],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.956990472, -0.100707608, 0.272079426],
        wi: [0.962725076, 0.0680800916, 0.261773812],
        f: [6.04927826, 3.49014735, 2.37191749],
        pdf: 6.646245,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.867833011, 0.161892662, 0.469741025],
        wi: [0.836016438, -0.452841155, 0.309857068],
        f: [0.000553258404, 0.000286314345, 0.000182865377],
        pdf: 0.000636238488,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.867833011, 0.161892662, 0.469741025],
        wi: [-0.911722582, -0.378526188, 0.159624114],
        f: [0.804409325, 0.446384668, 0.29880321],
        pdf: 1.06382585,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.641718475, 0.329432408, 0.692583343],
        wi: [0.195368043, -0.896201921, 0.398313249],
        f: [0.00209806301, 0.00108737801, 0.000697326206],
        pdf: 0.00258941972,
    },
    EvalRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.641718475, 0.329432408, 0.692583343],
        wi: [-0.659679019, 0.629787258, 0.410111694],
        f: [0.230317771, 0.119402356, 0.0766093209],
        pdf: 0.264711767,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.356574878, 0.481274471, 0.800767906],
        f: [7.32854923e-12, 4.74207609e-12, 4.04373106e-12],
        pdf: 7.70268484e-12,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.905044709, 0.0358106458, 0.423806173],
        f: [4.63630819, 3.38037181, 3.07500672],
        pdf: 4.91815472,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.173662707, -0.983635778, 0.0479783269],
        wi: [-0.703160262, -0.141564821, 0.696796274],
        f: [3.84755422e-12, 2.49370121e-12, 2.13381916e-12],
        pdf: 4.0488498e-12,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.173662707, -0.983635778, 0.0479783269],
        wi: [-0.104765199, 0.958436573, 0.26537443],
        f: [4.45063877, 3.53581667, 3.30616307],
        pdf: 4.84850025,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.957287692, 0.282944588, 0.0595200295],
        wi: [0.290186684, -0.881049201, 0.373555878],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.957287692, 0.282944588, 0.0595200295],
        wi: [-0.918610485, -0.112429446, 0.378832939],
        f: [1.62754881, 1.20214486, 1.09844005],
        pdf: 1.72916675,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.932317558, 0.361637641, 0.00147924618],
        wi: [0.14441082, 0.815883026, 0.559893207],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.932317558, 0.361637641, 0.00147924618],
        wi: [-0.66071372, -0.28560548, 0.694180733],
        f: [2.12655544, 1.44877732, 1.28270698],
        pdf: 2.25551081,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.081026481, -0.727582445, 0.681218391],
        wi: [0.712591048, 0.06488279, -0.69857299],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.081026481, -0.727582445, 0.681218391],
        wi: [-0.0818254546, 0.877886353, 0.471826395],
        f: [0.877580583, 0.572761118, 0.494040072],
        pdf: 0.925795734,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.873999087, -0.360045313, 0.326332605],
        wi: [0.630597361, -0.715215463, -0.301353297],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.873999087, -0.360045313, 0.326332605],
        wi: [0.697556686, -0.15241276, 0.700132145],
        f: [0.187578723, 0.122497097, 0.105716996],
        pdf: 0.197914451,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.381088069, -0.471044576, 0.795543142],
        f: [0.00150829344, 0.00134070532, 0.0011731172],
        pdf: 0.00168554718,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.979352638, -0.085985717, 0.182961383],
        f: [0.38429752, 0.341597795, 0.298898071],
        pdf: 0.526906967,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.585395623, 0.0908521503, 0.805641267],
        wi: [-0.392567797, -0.871259089, 0.294615213],
        f: [0.00121871079, 0.00108329847, 0.000947886147],
        pdf: 0.001484112,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.585395623, 0.0908521503, 0.805641267],
        wi: [-0.257723133, 0.0343707331, -0.96560729],
        f: [0.335090131, 0.390938461, 0.446786851],
        pdf: 1.25749815,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.0988730173, -0.130271386, 0.986536108],
        wi: [0.54993318, -0.582609791, 0.598447432],
        f: [0.00183550245, 0.00163155783, 0.00142761297],
        pdf: 0.00207536598,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.0988730173, -0.130271386, 0.986536108],
        wi: [0.0238977894, 0.06615476, -0.997523154],
        f: [7.86495304, 9.17577839, 10.4866037],
        pdf: 29.4950428,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.033418296, -0.880603626, 0.472673747],
        wi: [-0.120935354, -0.443977941, -0.887839078],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.033418296, -0.880603626, 0.472673747],
        wi: [-0.0358671179, 0.731591244, -0.680799384],
        f: [1.00261855, 1.16972148, 1.33682466],
        pdf: 3.80284882,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.861104901, 0.375160836, 0.343151128],
        wi: [-0.152527082, 0.268856005, -0.951026781],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.861104901, 0.375160836, 0.343151128],
        wi: [0.64788803, -0.249560562, -0.719694814],
        f: [3.36315918, 3.92368555, 4.4842124],
        pdf: 12.7281437,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.481492419, 0.75201515, -0.450153602],
        wi: [-0.826993698, -0.0321760094, -0.561289701],
        f: [0.000566812407, 0.000503833289, 0.000440854114],
        pdf: 0.000643198728,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.481492419, 0.75201515, -0.450153602],
        wi: [0.546445174, -0.720014551, -0.427757779],
        f: [2.72090173, 2.41857958, 2.11625695],
        pdf: 3.15267348,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.791465183, 0.330574667, 0.514104321],
        f: [0.00095534604, 0.000849196513, 0.000743046927],
        pdf: 0.0010902629,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.999713375, -0.00493265174, -0.0234272574],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.781574142, -0.510568426, 0.3584156],
        wi: [-0.359214496, 0.709892081, -0.605820253],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.781574142, -0.510568426, 0.3584156],
        wi: [0.558783079, 0.348401358, -0.752580869],
        f: [10.7770548, 12.5732298, 14.3694067],
        pdf: 18.0982399,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.576548155, 0.114719783, 0.808969466],
        wi: [0.589727407, -0.449269114, 0.671102711],
        f: [0.0213751271, 0.019000113, 0.0166250989],
        pdf: 0.0240365248,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.576548155, 0.114719783, 0.808969466],
        wi: [0.399958156, -0.288673408, -0.869885703],
        f: [0.387205213, 0.451739401, 0.516273618],
        pdf: 0.647410393,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.48247487, 0.227999844, 0.845715124],
        wi: [-0.465185648, 0.280220335, -0.83968975],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.48247487, 0.227999844, 0.845715124],
        wi: [0.304356374, -0.153287589, -0.940143666],
        f: [26.1425877, 30.4996834, 34.856781],
        pdf: 43.6281471,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.148989102, 0.677003354, 0.720741775],
        wi: [0.915437489, -0.0466037046, -0.399752796],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.148989102, 0.677003354, 0.720741775],
        wi: [0.13173507, -0.276356083, 0.951983817],
        f: [0.0121769411, 0.0108239483, 0.00947095454],
        pdf: 0.0135439094,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.0207042313, -0.0195342732, -0.999594791],
        wi: [-0.57044751, -0.25572703, 0.780508376],
        f: [0.004091457, 0.00477336626, 0.005455276],
        pdf: 0.00686256448,
    },
    EvalRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.0207042313, -0.0195342732, -0.999594791],
        wi: [-0.127273279, 0.0712495248, 0.989305321],
        f: [3.96443725, 4.62517643, 5.28591633],
        pdf: 6.60883236,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.766064284, -0.563794669, -0.308676342],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.430430181, 0.081058634, -0.898976839],
        f: [1.69142663, 1.69142663, 1.69142663],
        pdf: 9.90567303,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.562670881, 0.564986771, 0.603482749],
        wi: [-0.0804328575, 0.740742669, -0.66695641],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.562670881, 0.564986771, 0.603482749],
        wi: [0.247303855, -0.536827753, -0.806632981],
        f: [0.45726335, 0.45726335, 0.45726335],
        pdf: 2.67791748,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.719925784, 0.54037772, 0.43554424],
        wi: [-0.889699139, 0.38161477, 0.250610475],
        f: [8.80152639e-19, 8.80152639e-19, 8.80152639e-19],
        pdf: 8.80152535e-19,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.719925784, 0.54037772, 0.43554424],
        wi: [-0.266358763, -0.365661878, -0.891820834],
        f: [1.88647926, 1.88647926, 1.88647926],
        pdf: 11.0479803,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.551003202, -0.168750494, 0.817262958],
        wi: [0.696589386, -0.414430656, -0.585670948],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.551003202, -0.168750494, 0.817262958],
        wi: [0.169263889, 0.0798062777, -0.982334309],
        f: [0.244086564, 0.244086564, 0.244086564],
        pdf: 1.42946863,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.585779948, 0.3585167, 0.726861492],
        wi: [-0.107247414, 0.845856072, 0.522518418],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.585779948, 0.3585167, 0.726861492],
        wi: [-0.23801697, -0.206151958, -0.949130809],
        f: [6.39617348, 6.39617348, 6.39617348],
        pdf: 37.4585533,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.751742355, 0.439823492, -0.491364149],
        wi: [0.858349034, 0.00966555604, -0.512975159],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.751742355, 0.439823492, -0.491364149],
        wi: [-0.727193185, -0.264649922, -0.633364421],
        f: [7.15654945, 7.15654945, 7.15654945],
        pdf: 7.15654945,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.578782401, 0.567293378, 0.585823485],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.433142997, -0.0286837233, -0.900868685],
        f: [10.7093306, 10.7093306, 10.7093306],
        pdf: 10.7093325,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.229964781, 0.147581493, 0.961943815],
        wi: [0.436440699, -0.594366378, -0.675461416],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.229964781, 0.147581493, 0.961943815],
        wi: [-0.0897539568, -0.152224245, -0.984262164],
        f: [38.8443565, 38.8443565, 38.8443565],
        pdf: 38.8443565,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.810793933, 0.100568441, 0.576627424],
        wi: [-0.432876486, 0.898968917, -0.0668792506],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.810793933, 0.100568441, 0.576627424],
        wi: [-0.350936096, -0.0604744623, -0.934444592],
        f: [27.8363094, 27.8363094, 27.8363094],
        pdf: 27.8363094,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.765602962, 0.286010641, 0.576237814],
        wi: [-0.610382774, 0.744981156, -0.269139269],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.765602962, 0.286010641, 0.576237814],
        wi: [0.361744313, -0.00839873625, -0.932239515],
        f: [4.66387892, 4.66387892, 4.66387892],
        pdf: 4.66387939,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.29638612, 0.864804711, 0.405299988],
        wi: [-0.618159302, 0.243561307, 0.747366689],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.29638612, 0.864804711, 0.405299988],
        wi: [0.0767507108, -0.334293033, -0.939338861],
        f: [5.29014254, 5.29014254, 5.29014254],
        pdf: 5.29014301,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.551062337, 0.833956003, -0.0291150389],
        wi: [-0.532276044, -0.37923846, -0.756875421],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.551062337, 0.833956003, -0.0291150389],
        wi: [0.493521496, -0.544791164, -0.677966902],
        f: [0.934823513, 0.934823513, 0.934823513],
        pdf: 0.934823632,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.799561666, -0.593503317, -0.0919508246],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.997447992, 0.00121958783, 0.0713863823],
        f: [0.00082683377, 0.00137805624, 0.00192927872],
        pdf: 0.00451391796,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.749072844, 0.207310637, 0.629215523],
        wi: [-0.367499767, 0.886760211, -0.28035736],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.749072844, 0.207310637, 0.629215523],
        wi: [0.521917345, -0.430791996, 0.736220443],
        f: [0.0693927333, 0.11565455, 0.161916375],
        pdf: 0.207962438,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.493245153, -0.0966760583, 0.864501567],
        wi: [0.190711035, -0.686627096, -0.701550093],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.493245153, -0.0966760583, 0.864501567],
        wi: [-0.00324548152, 0.831444246, 0.555598715],
        f: [0.0519197509, 0.0865329206, 0.12114609],
        pdf: 0.162738368,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.0522807436, 0.603396409, 0.795725767],
        wi: [-0.164057881, -0.797937666, 0.579983183],
        f: [0.0543678738, 0.0906131193, 0.126858369],
        pdf: 0.169019073,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.0522807436, 0.603396409, 0.795725767],
        wi: [0.849232343, 0.240645185, 0.469993961],
        f: [0.0425737165, 0.0709561929, 0.0993386731],
        pdf: 0.13696593,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.940780878, -0.338201644, 0.0234731252],
        wi: [0.312561171, 0.805044734, -0.504190927],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.940780878, -0.338201644, 0.0234731252],
        wi: [0.940096822, 0.340091389, 0.0235756867],
        f: [3.98107586e-05, 6.63512692e-05, 9.28917725e-05],
        pdf: 0.000506278884,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.962785932, -0.270260356, 0.00160928972],
        wi: [0.380001117, 0.719254724, 0.581611377],
        f: [0.000530961435, 0.000884935667, 0.00123891002],
        pdf: 0.000865444774,
    },
    EvalRef {
        model: "plastic",
        adjoint: false,
        wo: [0.962785932, -0.270260356, 0.00160928972],
        wi: [-0.963456143, 0.267861251, 0.00161595793],
        f: [1.47919481e-08, 2.46532466e-08, 3.45145459e-08],
        pdf: 2.40456507e-06,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.922342566, 0.345949303, -0.172056009],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.997479344, 0.00094618673, 0.0709511275],
        f: [0.00129369565, 0.000362332183, 6.81133315e-05],
        pdf: 0.00440113246,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.431488599, -0.840126535, 0.328641132],
        wi: [0.794479809, 0.186263333, 0.578020591],
        f: [0.0698294044, 0.0195574891, 0.00367653184],
        pdf: 0.115393668,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.431488599, -0.840126535, 0.328641132],
        wi: [0.36463461, 0.391137734, 0.845016494],
        f: [0.10546349, 0.0295377169, 0.00555267371],
        pdf: 0.168695629,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.389772564, -0.247362874, 0.887067617],
        wi: [0.994320204, 0.106084248, 0.00857116794],
        f: [6.64442632e-05, 1.86093966e-05, 3.49830384e-06],
        pdf: 0.00225854246,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.389772564, -0.247362874, 0.887067617],
        wi: [0.613082387, 0.194929651, 0.765592854],
        f: [0.112350985, 0.0314667337, 0.00591530139],
        pdf: 0.20173724,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.0202286381, -0.425760028, 0.904609972],
        wi: [0.39361277, -0.4575932, 0.79729383],
        f: [0.117314287, 0.0328568332, 0.00617662072],
        pdf: 0.210252404,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.0202286381, -0.425760028, 0.904609972],
        wi: [0.0163906477, 0.123553044, 0.992202596],
        f: [0.146774486, 0.0411079042, 0.00772770541],
        pdf: 0.261651307,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.908509627, -0.28295393, 0.307485499],
        wi: [0.440996781, -0.0578661676, -0.895641304],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.908509627, -0.28295393, 0.307485499],
        wi: [-0.908261854, 0.282507297, 0.308626038],
        f: [0.0312327445, 0.00874751993, 0.00164441019],
        pdf: 0.0594397038,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.230941183, -0.938809071, 0.255545883],
        wi: [0.624374699, -0.77637621, -0.0860012565],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.230941183, -0.938809071, 0.255545883],
        wi: [-0.229786214, 0.939011707, 0.255842354],
        f: [0.0224102568, 0.00627655955, 0.00117990444],
        pdf: 0.0441531651,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.813194349, -0.34154638, -0.471233511],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [-0.997660525, -0.0160559726, 0.0664506003],
        f: [16.6826191, 16.6836205, 16.6846218],
        pdf: 18.6997108,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.861898036, 0.498985177, 0.0902528],
        wi: [-0.685388844, 0.721645377, -0.0973143452],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.861898036, 0.498985177, 0.0902528],
        wi: [-0.335947064, 0.176487789, -0.925198157],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.646693543, -0.552547484, 0.525812456],
        wi: [0.260671036, 0.118815696, -0.958088431],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.646693543, -0.552547484, 0.525812456],
        wi: [0.893998974, -0.31695535, 0.316709869],
        f: [0.0237847492, 0.0396412499, 0.0554977506],
        pdf: 0.0853486359,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.0481130223, 0.102908567, 0.993526529],
        wi: [-0.10727212, 0.878572101, 0.465407086],
        f: [0.0405737571, 0.0676229298, 0.0946721062],
        pdf: 0.136743039,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.0481130223, 0.102908567, 0.993526529],
        wi: [0.676597704, -0.457543183, 0.576948683],
        f: [0.0521448366, 0.0869080648, 0.121671289],
        pdf: 0.16951552,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.557862822, 0.55946124, 0.613018917],
        wi: [-0.149346864, 0.736912876, 0.659283647],
        f: [0.0590027533, 0.098337926, 0.137673095],
        pdf: 0.184797987,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.557862822, 0.55946124, 0.613018917],
        wi: [0.616056465, -0.639647092, 0.459702109],
        f: [0.477578789, 0.503578186, 0.529577553],
        pdf: 0.800676227,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.764639491, 0.450306495, 0.461032004],
        wi: [0.705347501, -0.652762741, 0.276379642],
        f: [0.0193188116, 0.0321980193, 0.0450772271],
        pdf: 0.071245566,
    },
    EvalRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.764639491, 0.450306495, 0.461032004],
        wi: [-0.327686434, -0.179156578, 0.92764461],
        f: [0.0806777403, 0.134462118, 0.188246489],
        pdf: 0.239134341,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.692216172, 0.0165888849, 0.721499536],
        f: [0.0541485064, 0.0226885565, 0.00998197217],
        pdf: 0.150287688,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        wi: [0.0219259704, -0.688500311, 0.724904528],
        f: [0.0568496883, 0.0246862248, 0.0124484189],
        pdf: 0.161165431,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.274361446, 0.95682533, 0.0959743949],
        wi: [0.537823303, 0.723019595, -0.433576705],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.274361446, 0.95682533, 0.0959743949],
        wi: [-0.000678835988, -0.863288697, 0.504709981],
        f: [0.126040295, 0.0848205611, 0.0960060135],
        pdf: 0.325612217,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.275282156, -0.936227603, 0.218397826],
        wi: [-0.436580376, 0.491615687, -0.753466384],
        f: [0.0, 0.0, 0.0],
        pdf: 0.0,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.275282156, -0.936227603, 0.218397826],
        wi: [0.697252176, -0.353851031, 0.623401035],
        f: [0.0508979559, 0.0212138128, 0.00912643597],
        pdf: 0.141952857,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.243709638, -0.808571014, 0.535554411],
        wi: [-0.836227516, 0.310849032, 0.451770319],
        f: [0.0398227014, 0.0164864808, 0.00688759005],
        pdf: 0.116894923,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.243709638, -0.808571014, 0.535554411],
        wi: [-0.101861152, -0.171860564, 0.979840932],
        f: [0.0958628133, 0.0398729071, 0.0170029216],
        pdf: 0.256153077,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.726868948, -0.493844592, 0.477262036],
        wi: [0.994859554, 0.094811358, 0.0355707061],
        f: [0.00253419578, 0.00110029499, 0.000554582628],
        pdf: 0.0162318032,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.726868948, -0.493844592, 0.477262036],
        wi: [-0.755890665, -0.34420068, 0.556915788],
        f: [0.0538659059, 0.0237795245, 0.0126793617],
        pdf: 0.152767792,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.631195095, -0.754038276, 0.181711394],
        wi: [0.685583208, -0.726851404, 0.0407762405],
        f: [0.0028317275, 0.00132810918, 0.000843931513],
        pdf: 0.0259750281,
    },
    EvalRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.631195095, -0.754038276, 0.181711394],
        wi: [-0.812968872, 0.257821343, 0.522120453],
        f: [0.0632026419, 0.0345050991, 0.0298906416],
        pdf: 0.178212807,
    },
];

const SAMPLE_REFS: &[SampleRef] = &[
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.825206509,
        u: [0.298639855, 0.368411689],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.971711516, 0.694170415, 0.503646553],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.193661349,
        u: [0.566008169, 0.161687824],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.971711516, 0.694170415, 0.503646553],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.124266884,
        u: [0.432936268, 0.562078488],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.971711516, 0.694170415, 0.503646553],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.174343561,
        u: [0.553221086, 0.354901386],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.971711516, 0.694170415, 0.503646553],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.336718362, 0.217548512, 0.91612957],
        u_lobe: 0.978639996,
        u: [0.412119393, 0.503935368],
        wi: [-0.336718351, -0.217548519, 0.916129589],
        weight: [0.951813519, 0.492583364, 0.314683557],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.336718362, 0.217548512, 0.91612957],
        u_lobe: 0.148146169,
        u: [0.71896714, 0.189971379],
        wi: [-0.336718351, -0.217548519, 0.916129589],
        weight: [0.951813519, 0.492583364, 0.314683557],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.336718362, 0.217548512, 0.91612957],
        u_lobe: 0.341560426,
        u: [0.0235212181, 0.339517772],
        wi: [-0.336718351, -0.217548519, 0.916129589],
        weight: [0.951813519, 0.492583364, 0.314683557],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.336718362, 0.217548512, 0.91612957],
        u_lobe: 0.967482459,
        u: [0.978798454, 0.74453004],
        wi: [-0.336718351, -0.217548519, 0.916129589],
        weight: [0.951813519, 0.492583364, 0.314683557],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.109172629, -0.0430353661, 0.993090778],
        u_lobe: 0.870766969,
        u: [0.770834339, 0.178873765],
        wi: [-0.109172627, 0.0430353656, 0.993090749],
        weight: [0.951951146, 0.492635638, 0.314595103],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.109172629, -0.0430353661, 0.993090778],
        u_lobe: 0.0994996328,
        u: [0.414532469, 0.885536467],
        wi: [-0.109172627, 0.0430353656, 0.993090749],
        weight: [0.951951146, 0.492635638, 0.314595103],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.109172629, -0.0430353661, 0.993090778],
        u_lobe: 0.578086027,
        u: [0.736582215, 0.232621103],
        wi: [-0.109172627, 0.0430353656, 0.993090749],
        weight: [0.951951146, 0.492635638, 0.314595103],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.109172629, -0.0430353661, 0.993090778],
        u_lobe: 0.52359758,
        u: [0.709386437, 0.824833947],
        wi: [-0.109172627, 0.0430353656, 0.993090749],
        weight: [0.951951146, 0.492635638, 0.314595103],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0875382787, 0.784241758, 0.614249066],
        u_lobe: 0.873189967,
        u: [0.21638043, 0.801899238],
        wi: [-0.0875382796, -0.784241736, 0.614249051],
        weight: [0.948476255, 0.494190782, 0.319061607],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0875382787, 0.784241758, 0.614249066],
        u_lobe: 0.555085299,
        u: [0.18582836, 0.588608618],
        wi: [-0.0875382796, -0.784241736, 0.614249051],
        weight: [0.948476255, 0.494190782, 0.319061607],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0875382787, 0.784241758, 0.614249066],
        u_lobe: 0.518239386,
        u: [0.958662503, 0.0415392219],
        wi: [-0.0875382796, -0.784241736, 0.614249051],
        weight: [0.948476255, 0.494190782, 0.319061607],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0875382787, 0.784241758, 0.614249066],
        u_lobe: 0.164138282,
        u: [0.983292653, 0.832204886],
        wi: [-0.0875382796, -0.784241736, 0.614249051],
        weight: [0.948476255, 0.494190782, 0.319061607],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0935230639, 0.708530906, 0.699455068],
        u_lobe: 0.539138275,
        u: [0.15698083, 0.323760726],
        wi: [-0.0935230628, -0.708530903, 0.699455082],
        weight: [0.949933648, 0.492898941, 0.316674054],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0935230639, 0.708530906, 0.699455068],
        u_lobe: 0.049319223,
        u: [0.711677294, 0.0785627469],
        wi: [-0.0935230628, -0.708530903, 0.699455082],
        weight: [0.949933648, 0.492898941, 0.316674054],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0935230639, 0.708530906, 0.699455068],
        u_lobe: 0.994604251,
        u: [0.920569838, 0.788828872],
        wi: [-0.0935230628, -0.708530903, 0.699455082],
        weight: [0.949933648, 0.492898941, 0.316674054],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [0.0935230639, 0.708530906, 0.699455068],
        u_lobe: 0.77240589,
        u: [0.3677523, 0.678706173],
        wi: [-0.0935230628, -0.708530903, 0.699455082],
        weight: [0.949933648, 0.492898941, 0.316674054],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [-0.846416453, 0.102735658, 0.522517534],
        u_lobe: 0.0615250469,
        u: [0.626103949, 0.325760832],
        wi: [0.846416473, -0.102735661, 0.522517562],
        weight: [0.946441114, 0.497715443, 0.323854297],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [-0.846416453, 0.102735658, 0.522517534],
        u_lobe: 0.610089071,
        u: [0.420828461, 0.952530783],
        wi: [0.846416473, -0.102735661, 0.522517562],
        weight: [0.946441114, 0.497715443, 0.323854297],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [-0.846416453, 0.102735658, 0.522517534],
        u_lobe: 0.201594616,
        u: [0.768856366, 0.698561856],
        wi: [0.846416473, -0.102735661, 0.522517562],
        weight: [0.946441114, 0.497715443, 0.323854297],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "conductor",
        adjoint: false,
        wo: [-0.846416453, 0.102735658, 0.522517534],
        u_lobe: 0.556562999,
        u: [0.0800462775, 0.164951711],
        wi: [0.846416473, -0.102735661, 0.522517562],
        weight: [0.946441114, 0.497715443, 0.323854297],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.184854491,
        u: [0.607500836, 0.798463031],
        wi: [-0.993352175, -0.0128513193, 0.114395067],
        weight: [0.829925358, 0.574625373, 0.413181096],
        pdf: 17.8228378,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.0958732684,
        u: [0.505167177, 0.406138123],
        wi: [-0.950272024, -0.00197187299, 0.311414719],
        weight: [0.925222039, 0.568511784, 0.394584566],
        pdf: 3.32984757,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.781354268, -0.228107581, 0.580906566],
        u_lobe: 0.67993488,
        u: [0.518266267, 0.248940579],
        wi: [-0.713733196, -0.117365114, 0.690514565],
        weight: [0.945701659, 0.491469085, 0.316402107],
        pdf: 1.29109454,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.781354268, -0.228107581, 0.580906566],
        u_lobe: 0.413250711,
        u: [0.691883306, 0.324964032],
        wi: [-0.773625195, -0.0590575188, 0.630885363],
        weight: [0.94477272, 0.491985559, 0.317455232],
        pdf: 2.05888653,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.487087524, 0.123423095, 0.864588042],
        u_lobe: 0.538258951,
        u: [0.693381993, 0.67099712],
        wi: [0.547510743, -0.0620683581, 0.834493577],
        weight: [0.950264156, 0.491880596, 0.314520955],
        pdf: 1.79371476,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.487087524, 0.123423095, 0.864588042],
        u_lobe: 0.798393943,
        u: [0.25993616, 0.426875979],
        wi: [0.39471361, -0.282574296, 0.874272704],
        weight: [0.947212994, 0.490251005, 0.313354701],
        pdf: 1.31892025,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.956990472, -0.100707608, 0.272079426],
        u_lobe: 0.685901414,
        u: [0.401791351, 0.449171265],
        wi: [0.937059045, 0.0132921459, 0.348917872],
        weight: [0.925538838, 0.518871665, 0.348791957],
        pdf: 4.89049006,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [-0.956990472, -0.100707608, 0.272079426],
        u_lobe: 0.264340716,
        u: [0.737221066, 0.480405428],
        wi: [0.922004223, 0.193516299, 0.335350096],
        weight: [0.913431883, 0.513785243, 0.345831275],
        pdf: 3.40984845,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.867833011, 0.161892662, 0.469741025],
        u_lobe: 0.187950767,
        u: [0.396944273, 0.181835385],
        wi: [-0.783137381, 0.223388612, 0.580339074],
        weight: [0.937620401, 0.490778655, 0.318182915],
        pdf: 0.876621425,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.867833011, 0.161892662, 0.469741025],
        u_lobe: 0.349129783,
        u: [0.901378418, 0.725392277],
        wi: [-0.837598741, -0.477408201, 0.265536606],
        weight: [0.830620348, 0.448760629, 0.296717942],
        pdf: 1.09221101,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.641718475, 0.329432408, 0.692583343],
        u_lobe: 0.424291784,
        u: [0.0138561141, 0.113666579],
        wi: [-0.755079508, 0.564938188, -0.332715631],
        weight: [0.0, 0.0, 0.0],
        pdf: 0.0613141954,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_ggx_aniso",
        adjoint: false,
        wo: [0.641718475, 0.329432408, 0.692583343],
        u_lobe: 0.513996259,
        u: [0.791310549, 0.341026786],
        wi: [-0.510202885, -0.230149761, 0.828688323],
        weight: [0.946960747, 0.490593553, 0.3143785],
        pdf: 0.924059927,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.856279521,
        u: [0.0917742408, 0.527604738],
        wi: [-0.624610364, -0.0125172567, 0.780836344],
        weight: [0.944991231, 0.627399325, 0.547924399],
        pdf: 1.19789994,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.549474325,
        u: [0.657296031, 0.41013626],
        wi: [-0.931039691, 0.0209919494, 0.364313662],
        weight: [0.940531313, 0.703857183, 0.645953655],
        pdf: 5.61814547,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.173662707, -0.983635778, 0.0479783269],
        u_lobe: 0.662556015,
        u: [0.868029508, 0.353527551],
        wi: [-0.150726065, 0.967913687, 0.201059103],
        weight: [0.874299347, 0.724877834, 0.686390638],
        pdf: 7.15063667,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.173662707, -0.983635778, 0.0479783269],
        u_lobe: 0.816265818,
        u: [0.658028525, 0.0170385489],
        wi: [-0.0101783331, 0.954263866, 0.298792422],
        weight: [0.928367794, 0.713433743, 0.660336256],
        pdf: 0.946261168,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.957287692, 0.282944588, 0.0595200295],
        u_lobe: 0.0964073808,
        u: [0.174114093, 0.940075137],
        wi: [-0.645841181, -0.428724051, 0.631731629],
        weight: [0.943051636, 0.639970541, 0.565549612],
        pdf: 0.750241816,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.957287692, 0.282944588, 0.0595200295],
        u_lobe: 0.308850898,
        u: [0.216490526, 0.0964556594],
        wi: [-0.785864472, -0.0373543128, 0.617269516],
        weight: [0.942722142, 0.643561721, 0.570334792],
        pdf: 1.22369373,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.932317558, 0.361637641, 0.00147924618],
        u_lobe: 0.990638222,
        u: [0.923853689, 0.900083543],
        wi: [-0.90472877, -0.396669835, 0.155302763],
        weight: [0.818455398, 0.720042408, 0.693577528],
        pdf: 4.91449738,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [0.932317558, 0.361637641, 0.00147924618],
        u_lobe: 0.553693992,
        u: [0.930855621, 0.639859976],
        wi: [-0.916194022, -0.3683604, 0.157794505],
        weight: [0.82340759, 0.725844502, 0.69956696],
        pdf: 9.25976944,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.081026481, -0.727582445, 0.681218391],
        u_lobe: 0.26525322,
        u: [0.235715309, 0.980583856],
        wi: [-0.532371998, 0.530134916, 0.659952223],
        weight: [0.950524092, 0.615789115, 0.526527345],
        pdf: 0.151250318,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.081026481, -0.727582445, 0.681218391],
        u_lobe: 0.225324739,
        u: [0.370122148, 0.689032863],
        wi: [-0.093753621, 0.57206589, 0.814831614],
        weight: [0.95067668, 0.615732431, 0.526232541],
        pdf: 1.03810501,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.873999087, -0.360045313, 0.326332605],
        u_lobe: 0.367979543,
        u: [0.399697136, 0.684909881],
        wi: [0.699117064, 0.39023149, 0.599128187],
        weight: [0.945147157, 0.626718163, 0.546907425],
        pdf: 1.91476011,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_conductor_beckmann",
        adjoint: false,
        wo: [-0.873999087, -0.360045313, 0.326332605],
        u_lobe: 0.421509143,
        u: [0.111027847, 0.249221313],
        wi: [0.565054178, 0.0542317331, 0.823269427],
        weight: [0.94848156, 0.617730319, 0.531752348],
        pdf: 0.714981437,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.171211028,
        u: [0.728633252, 0.969788998],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.668543994,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.384844551,
        u: [0.570314772, 0.636246314],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.668543994,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.797981472,
        u: [0.629113443, 0.516520267],
        wi: [-0.664972484, -0.0, -0.746867895],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.331456006,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.720502408,
        u: [0.02375502, 0.939792994],
        wi: [-0.664972484, -0.0, -0.746867895],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.331456006,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.208685411, -0.566408269, 0.797265371],
        u_lobe: 0.20161908,
        u: [0.625604207, 0.0281239281],
        wi: [0.139123619, 0.377605528, -0.915455461],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.955974638,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.208685411, -0.566408269, 0.797265371],
        u_lobe: 0.397699456,
        u: [0.215369462, 0.561237559],
        wi: [0.139123619, 0.377605528, -0.915455461],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.955974638,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.208685411, -0.566408269, 0.797265371],
        u_lobe: 0.250427285,
        u: [0.0922808418, 0.793864132],
        wi: [0.139123619, 0.377605528, -0.915455461],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.955974638,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.208685411, -0.566408269, 0.797265371],
        u_lobe: 0.251271583,
        u: [0.559710272, 0.0165485229],
        wi: [0.139123619, 0.377605528, -0.915455461],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.955974638,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.242145898, -0.961901976, 0.126924985],
        u_lobe: 0.784992733,
        u: [0.328389333, 0.128404013],
        wi: [-0.161430597, 0.641268015, -0.750143647],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.505081415,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.242145898, -0.961901976, 0.126924985],
        u_lobe: 0.609476496,
        u: [0.306507487, 0.285816446],
        wi: [-0.161430597, 0.641268015, -0.750143647],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.505081415,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.242145898, -0.961901976, 0.126924985],
        u_lobe: 0.210114371,
        u: [0.393321797, 0.682205547],
        wi: [-0.242145896, 0.961901963, 0.126924992],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.494918585,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.242145898, -0.961901976, 0.126924985],
        u_lobe: 0.401543429,
        u: [0.646447298, 0.727824291],
        wi: [-0.242145896, 0.961901963, 0.126924992],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.494918585,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.707768476, -0.337357528, 0.620688072],
        u_lobe: 0.990316773,
        u: [0.502073558, 0.537183524],
        wi: [0.471845686, 0.224905014, -0.852513552],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.939014435,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.707768476, -0.337357528, 0.620688072],
        u_lobe: 0.65832461,
        u: [0.971304892, 0.701946962],
        wi: [0.471845686, 0.224905014, -0.852513552],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.939014435,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.707768476, -0.337357528, 0.620688072],
        u_lobe: 0.916833726,
        u: [0.158662706, 0.421998099],
        wi: [0.471845686, 0.224905014, -0.852513552],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.939014435,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.707768476, -0.337357528, 0.620688072],
        u_lobe: 0.703513765,
        u: [0.732715785, 0.830018901],
        wi: [0.471845686, 0.224905014, -0.852513552],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.939014435,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.34967455, 0.812017435, 0.467285131],
        u_lobe: 0.41272304,
        u: [0.392367128, 0.0926983951],
        wi: [0.233116373, -0.541345, -0.807838082],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.899191737,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.34967455, 0.812017435, 0.467285131],
        u_lobe: 0.389760596,
        u: [0.642388367, 0.739470291],
        wi: [0.233116373, -0.541345, -0.807838082],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.899191737,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.34967455, 0.812017435, 0.467285131],
        u_lobe: 0.229875646,
        u: [0.620677561, 0.751104291],
        wi: [0.233116373, -0.541345, -0.807838082],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.899191737,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [-0.34967455, 0.812017435, 0.467285131],
        u_lobe: 0.155522515,
        u: [0.0143227008, 0.160124927],
        wi: [0.233116373, -0.541345, -0.807838082],
        weight: [0.26666671, 0.311111122, 0.355555594],
        pdf: 0.899191737,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.798677819, -0.483786617, -0.357860659],
        u_lobe: 0.387262323,
        u: [0.311997893, 0.627263424],
        wi: [-0.798677802, 0.483786613, -0.357860655],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.798677819, -0.483786617, -0.357860659],
        u_lobe: 0.316187377,
        u: [0.0392105084, 0.245283639],
        wi: [-0.798677802, 0.483786613, -0.357860655],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.798677819, -0.483786617, -0.357860659],
        u_lobe: 0.600541859,
        u: [0.45780056, 0.346898963],
        wi: [-0.798677802, 0.483786613, -0.357860655],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: false,
        wo: [0.798677819, -0.483786617, -0.357860659],
        u_lobe: 0.392163578,
        u: [0.137118873, 0.767403675],
        wi: [-0.798677802, 0.483786613, -0.357860655],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 1.0,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.567792064,
        u: [0.900111715, 0.796445605],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.668543994,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.132288855,
        u: [0.451423918, 0.0111465563],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.668543994,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.755090627,
        u: [0.230757836, 0.976588439],
        wi: [-0.664972484, -0.0, -0.746867895],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.331456006,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.225427617,
        u: [0.508212383, 0.491588148],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.668543994,
        eta: 1.0,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.624749176, -0.42556523, 0.654662281],
        u_lobe: 0.881098296,
        u: [0.319640092, 0.0974841874],
        wi: [0.416499466, 0.283710182, -0.863734186],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.943944514,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.624749176, -0.42556523, 0.654662281],
        u_lobe: 0.18571369,
        u: [0.046283899, 0.70736824],
        wi: [0.416499466, 0.283710182, -0.863734186],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.943944514,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.624749176, -0.42556523, 0.654662281],
        u_lobe: 0.686059467,
        u: [0.754661539, 0.780877079],
        wi: [0.416499466, 0.283710182, -0.863734186],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.943944514,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.624749176, -0.42556523, 0.654662281],
        u_lobe: 0.125158722,
        u: [0.0641519964, 0.659079412],
        wi: [0.416499466, 0.283710182, -0.863734186],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.943944514,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.0352044938, 0.0578056135, 0.997706948],
        u_lobe: 0.587662535,
        u: [0.652429421, 0.615597369],
        wi: [0.0234696623, -0.0385370776, -0.998981535],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959999681,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.0352044938, 0.0578056135, 0.997706948],
        u_lobe: 0.949392115,
        u: [0.974621986, 0.31053749],
        wi: [0.0234696623, -0.0385370776, -0.998981535],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959999681,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.0352044938, 0.0578056135, 0.997706948],
        u_lobe: 0.314992148,
        u: [0.02142397, 0.121061307],
        wi: [0.0234696623, -0.0385370776, -0.998981535],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959999681,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.0352044938, 0.0578056135, 0.997706948],
        u_lobe: 0.438174333,
        u: [0.641716259, 0.235680545],
        wi: [0.0234696623, -0.0385370776, -0.998981535],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959999681,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.23788219, -0.54917995, 0.801132602],
        u_lobe: 0.672219024,
        u: [0.500384376, 0.140950356],
        wi: [0.158588141, 0.366119981, -0.916954756],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.956158519,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.23788219, -0.54917995, 0.801132602],
        u_lobe: 0.196911072,
        u: [0.268100137, 0.852795394],
        wi: [0.158588141, 0.366119981, -0.916954756],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.956158519,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.23788219, -0.54917995, 0.801132602],
        u_lobe: 0.926150474,
        u: [0.0471621087, 0.936760073],
        wi: [0.158588141, 0.366119981, -0.916954756],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.956158519,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [-0.23788219, -0.54917995, 0.801132602],
        u_lobe: 0.912686915,
        u: [0.792865684, 0.233278511],
        wi: [0.158588141, 0.366119981, -0.916954756],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.956158519,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.128745412, -0.333324246, 0.933980495],
        u_lobe: 0.139370404,
        u: [0.0357842456, 0.377996805],
        wi: [-0.0858302712, 0.222216174, -0.971212208],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959677339,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.128745412, -0.333324246, 0.933980495],
        u_lobe: 0.579556744,
        u: [0.0246515883, 0.954620959],
        wi: [-0.0858302712, 0.222216174, -0.971212208],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959677339,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.128745412, -0.333324246, 0.933980495],
        u_lobe: 0.672800016,
        u: [0.516681471, 0.491934261],
        wi: [-0.0858302712, 0.222216174, -0.971212208],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959677339,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.128745412, -0.333324246, 0.933980495],
        u_lobe: 0.1047489,
        u: [0.74777896, 0.741532707],
        wi: [-0.0858302712, 0.222216174, -0.971212208],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959677339,
        eta: 1.5,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.103770764, -0.277364474, -0.95514427],
        u_lobe: 0.354328037,
        u: [0.93313023, 0.342067435],
        wi: [-0.155656144, 0.416046679, 0.895922065],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959135175,
        eta: 0.666666687,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.103770764, -0.277364474, -0.95514427],
        u_lobe: 0.21186121,
        u: [0.195822846, 0.331542257],
        wi: [-0.155656144, 0.416046679, 0.895922065],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959135175,
        eta: 0.666666687,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.103770764, -0.277364474, -0.95514427],
        u_lobe: 0.0707345183,
        u: [0.162501508, 0.472520418],
        wi: [-0.155656144, 0.416046679, 0.895922065],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959135175,
        eta: 0.666666687,
    },
    SampleRef {
        model: "dielectric",
        adjoint: true,
        wo: [0.103770764, -0.277364474, -0.95514427],
        u_lobe: 0.552195476,
        u: [0.557531198, 0.132003482],
        wi: [-0.155656144, 0.416046679, 0.895922065],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.959135175,
        eta: 0.666666687,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.899476277,
        u: [0.136341719, 0.683662207],
        wi: [-0.997458696, -0.0, -0.0712470487],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.198649883,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.555497905,
        u: [0.600072557, 0.936903728],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.255664306,
        u: [0.702548876, 0.517539349],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.368538467,
        u: [0.401095871, 0.2023614],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.530176819, -0.285623124, 0.798330741],
        u_lobe: 0.640319798,
        u: [0.169849965, 0.803113144],
        wi: [-0.530176818, 0.285623133, -0.798330724],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.915756285,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.530176819, -0.285623124, 0.798330741],
        u_lobe: 0.184725553,
        u: [0.662262282, 0.586645328],
        wi: [-0.530176818, 0.285623133, -0.798330724],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.915756285,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.530176819, -0.285623124, 0.798330741],
        u_lobe: 0.796776392,
        u: [0.412254342, 0.955208009],
        wi: [-0.530176818, 0.285623133, -0.798330724],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.915756285,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.530176819, -0.285623124, 0.798330741],
        u_lobe: 0.719087363,
        u: [0.449185801, 0.121068011],
        wi: [-0.530176818, 0.285623133, -0.798330724],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.915756285,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.589624261, 0.646749752, 0.4837954],
        u_lobe: 0.521162482,
        u: [0.805854357, 0.742178978],
        wi: [-0.589624286, -0.646749735, -0.483795404],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.827022195,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.589624261, 0.646749752, 0.4837954],
        u_lobe: 0.637074814,
        u: [0.426851452, 0.27846426],
        wi: [-0.589624286, -0.646749735, -0.483795404],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.827022195,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.589624261, 0.646749752, 0.4837954],
        u_lobe: 0.80387915,
        u: [0.671211893, 0.663605201],
        wi: [-0.589624286, -0.646749735, -0.483795404],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.827022195,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.589624261, 0.646749752, 0.4837954],
        u_lobe: 0.558215789,
        u: [0.790653167, 0.588877475],
        wi: [-0.589624286, -0.646749735, -0.483795404],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.827022195,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.617142201, 0.628567277, 0.473327246],
        u_lobe: 0.309738629,
        u: [0.2916703, 0.89842081],
        wi: [0.6171422, -0.628567278, -0.473327249],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.820666552,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.617142201, 0.628567277, 0.473327246],
        u_lobe: 0.711557811,
        u: [0.613626655, 0.450905654],
        wi: [0.6171422, -0.628567278, -0.473327249],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.820666552,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.617142201, 0.628567277, 0.473327246],
        u_lobe: 0.485387087,
        u: [0.105140906, 0.474553602],
        wi: [0.6171422, -0.628567278, -0.473327249],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.820666552,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.617142201, 0.628567277, 0.473327246],
        u_lobe: 0.58781758,
        u: [0.350269796, 0.507232645],
        wi: [0.6171422, -0.628567278, -0.473327249],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.820666552,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.0454909237, -0.0276843372, 0.99858107],
        u_lobe: 0.0770235054,
        u: [0.946022816, 0.794480805],
        wi: [-0.0454909243, 0.0276843365, -0.998581052],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.923076689,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.0454909237, -0.0276843372, 0.99858107],
        u_lobe: 0.812300241,
        u: [0.804603745, 0.208652662],
        wi: [-0.0454909243, 0.0276843365, -0.998581052],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.923076689,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.0454909237, -0.0276843372, 0.99858107],
        u_lobe: 0.132018784,
        u: [0.641929306, 0.827878482],
        wi: [-0.0454909243, 0.0276843365, -0.998581052],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.923076689,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [0.0454909237, -0.0276843372, 0.99858107],
        u_lobe: 0.101979674,
        u: [0.0143813782, 0.946979022],
        wi: [-0.0454909243, 0.0276843365, -0.998581052],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.923076689,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.0410991987, 0.570826787, -0.82004124],
        u_lobe: 0.829049427,
        u: [0.298584141, 0.841520062],
        wi: [0.0410991982, -0.570826769, 0.820041239],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.917504549,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.0410991987, 0.570826787, -0.82004124],
        u_lobe: 0.012972433,
        u: [0.608390358, 0.224755431],
        wi: [0.0410991982, -0.570826769, -0.820041239],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.0824954286,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.0410991987, 0.570826787, -0.82004124],
        u_lobe: 0.6358625,
        u: [0.0250642822, 0.647225837],
        wi: [0.0410991982, -0.570826769, 0.820041239],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.917504549,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: false,
        wo: [-0.0410991987, 0.570826787, -0.82004124],
        u_lobe: 0.099789279,
        u: [0.443619892, 0.0699721133],
        wi: [0.0410991982, -0.570826769, 0.820041239],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.917504549,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.327971719,
        u: [0.469560681, 0.65911393],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.633613987,
        u: [0.523537758, 0.852749245],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.410818732,
        u: [0.144149865, 0.685281469],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.357173001,
        u: [0.934769863, 0.390188984],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.801350117,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.12997783, 0.194247962, 0.97230319],
        u_lobe: 0.959647676,
        u: [0.477986663, 0.822850875],
        wi: [0.129977837, -0.194247961, -0.972303212],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.922979474,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.12997783, 0.194247962, 0.97230319],
        u_lobe: 0.367957138,
        u: [0.608416574, 0.0759192297],
        wi: [0.129977837, -0.194247961, -0.972303212],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.922979474,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.12997783, 0.194247962, 0.97230319],
        u_lobe: 0.20247861,
        u: [0.104033448, 0.402510961],
        wi: [0.129977837, -0.194247961, -0.972303212],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.922979474,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.12997783, 0.194247962, 0.97230319],
        u_lobe: 0.323432766,
        u: [0.557805773, 0.648768605],
        wi: [0.129977837, -0.194247961, -0.972303212],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.922979474,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.0972299382, 0.848528737, 0.520139713],
        u_lobe: 0.0245834674,
        u: [0.121665643, 0.381447153],
        wi: [0.0972299352, -0.848528743, 0.520139694],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.153320819,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.0972299382, 0.848528737, 0.520139713],
        u_lobe: 0.899232731,
        u: [0.188273018, 0.407802445],
        wi: [0.0972299352, -0.848528743, -0.520139694],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.846679211,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.0972299382, 0.848528737, 0.520139713],
        u_lobe: 0.0128226592,
        u: [0.588780481, 0.420808125],
        wi: [0.0972299352, -0.848528743, 0.520139694],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.153320819,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [-0.0972299382, 0.848528737, 0.520139713],
        u_lobe: 0.331199337,
        u: [0.389836799, 0.272728994],
        wi: [0.0972299352, -0.848528743, -0.520139694],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.846679211,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.391659313, 0.901558358, 0.18383555],
        u_lobe: 0.71255554,
        u: [0.933135867, 0.906804808],
        wi: [-0.391659319, -0.90155834, -0.183835551],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.462037504,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.391659313, 0.901558358, 0.18383555],
        u_lobe: 0.366424415,
        u: [0.0116275497, 0.768910975],
        wi: [-0.391659319, -0.90155834, 0.183835551],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.537962496,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.391659313, 0.901558358, 0.18383555],
        u_lobe: 0.461545949,
        u: [0.545242763, 0.655794964],
        wi: [-0.391659319, -0.90155834, 0.183835551],
        weight: [0.899999976, 0.800000012, 0.699999988],
        pdf: 0.537962496,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.391659313, 0.901558358, 0.18383555],
        u_lobe: 0.811604364,
        u: [0.517943199, 0.434422536],
        wi: [-0.391659319, -0.90155834, -0.183835551],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.462037504,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.652558047, 0.175695995, 0.73708813],
        u_lobe: 0.16540972,
        u: [0.154665801, 0.940801017],
        wi: [-0.652558029, -0.175696, -0.737088144],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.908914387,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.652558047, 0.175695995, 0.73708813],
        u_lobe: 0.566851954,
        u: [0.0274341627, 0.318223602],
        wi: [-0.652558029, -0.175696, -0.737088144],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.908914387,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.652558047, 0.175695995, 0.73708813],
        u_lobe: 0.411983559,
        u: [0.834473963, 0.413275008],
        wi: [-0.652558029, -0.175696, -0.737088144],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.908914387,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.652558047, 0.175695995, 0.73708813],
        u_lobe: 0.546818498,
        u: [0.264049877, 0.323142837],
        wi: [-0.652558029, -0.175696, -0.737088144],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.908914387,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.111317013, -0.530244155, -0.840505597],
        u_lobe: 0.488975216,
        u: [0.731393477, 0.572166194],
        wi: [-0.111317016, 0.530244172, 0.8405056],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.918880224,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.111317013, -0.530244155, -0.840505597],
        u_lobe: 0.0889949898,
        u: [0.268844474, 0.320167466],
        wi: [-0.111317016, 0.530244172, 0.8405056],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.918880224,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.111317013, -0.530244155, -0.840505597],
        u_lobe: 0.783153627,
        u: [0.34648484, 0.965639215],
        wi: [-0.111317016, 0.530244172, 0.8405056],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.918880224,
        eta: 1.0,
    },
    SampleRef {
        model: "thin_dielectric",
        adjoint: true,
        wo: [0.111317013, -0.530244155, -0.840505597],
        u_lobe: 0.796685482,
        u: [0.690756037, 0.531592431],
        wi: [-0.111317016, 0.530244172, 0.8405056],
        weight: [0.600000024, 0.699999988, 0.800000012],
        pdf: 0.918880224,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.686128771,
        u: [0.242377563, 0.35319383],
        wi: [-0.839629769, -0.104813188, -0.532950282],
        weight: [0.260263801, 0.303641051, 0.347018391],
        pdf: 2.61090636,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.319638762,
        u: [0.818560916, 0.949831296],
        wi: [-0.994705915, -0.0186597276, 0.101054013],
        weight: [0.561028719, 0.498692244, 0.43635568],
        pdf: 5.23678732,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.585395623, 0.0908521503, 0.805641267],
        u_lobe: 0.1431608,
        u: [0.585038586, 0.62760295],
        wi: [-0.385468841, -0.0497863442, -0.921376765],
        weight: [0.266193867, 0.310559481, 0.354925126],
        pdf: 44.2064476,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.585395623, 0.0908521503, 0.805641267],
        u_lobe: 0.195211983,
        u: [0.0258990399, 0.678211334],
        wi: [-0.311955303, -0.245902821, -0.917723119],
        weight: [0.266169012, 0.310530454, 0.354891986],
        pdf: 0.711695731,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.0988730173, -0.130271386, 0.986536108],
        u_lobe: 0.884736201,
        u: [0.00236496503, 0.228741824],
        wi: [-0.153093696, 0.49655211, -0.854399383],
        weight: [0.265687644, 0.309968889, 0.354250193],
        pdf: 0.0222519878,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.0988730173, -0.130271386, 0.986536108],
        u_lobe: 0.582859396,
        u: [0.231777264, 0.851080421],
        wi: [0.00526760146, 0.0679650009, -0.99767381],
        weight: [0.266654253, 0.311096579, 0.355538964],
        pdf: 18.2331085,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.033418296, -0.880603626, 0.472673747],
        u_lobe: 0.614223758,
        u: [0.322156981, 0.098508836],
        wi: [-0.0789114684, 0.748523712, -0.658396006],
        weight: [0.263269901, 0.307148188, 0.351026505],
        pdf: 2.32117915,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [0.033418296, -0.880603626, 0.472673747],
        u_lobe: 0.134153022,
        u: [0.122613577, 0.71068436],
        wi: [-0.115472369, 0.571812212, -0.812217295],
        weight: [0.265305132, 0.309522599, 0.353740126],
        pdf: 5.9775424,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.861104901, 0.375160836, 0.343151128],
        u_lobe: 0.116887787,
        u: [0.641775855, 0.556234258],
        wi: [0.825173974, -0.306184083, 0.47469905],
        weight: [0.871020615, 0.774240553, 0.677460492],
        pdf: 0.464625567,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.861104901, 0.375160836, 0.343151128],
        u_lobe: 0.111646673,
        u: [0.97444407, 0.987006133],
        wi: [0.942888975, -0.329407573, -0.0495076999],
        weight: [0.0, 0.0, 0.0],
        pdf: 0.224395126,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.481492419, 0.75201515, -0.450153602],
        u_lobe: 0.810452156,
        u: [0.882841649, 0.86611679],
        wi: [0.600297987, -0.736248136, -0.312379628],
        weight: [0.829327226, 0.737179756, 0.645032287],
        pdf: 1.70877206,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: false,
        wo: [-0.481492419, 0.75201515, -0.450153602],
        u_lobe: 0.799682934,
        u: [0.658224758, 0.0261102524],
        wi: [0.582694113, -0.706029356, 0.402480036],
        weight: [1.28657019, 1.50099838, 1.71542692],
        pdf: 0.161360741,
        eta: 0.666666687,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.0320414382,
        u: [0.679908416, 0.892406925],
        wi: [-0.986756921, -0.0137509927, 0.161621958],
        weight: [0.698111653, 0.620543718, 0.542975724],
        pdf: 5.7139082,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.518005677,
        u: [0.562660512, 0.0922028183],
        wi: [-0.96890223, 0.0302409064, -0.245588884],
        weight: [0.52769351, 0.615642369, 0.703591287],
        pdf: 1.04610276,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.781574142, -0.510568426, 0.3584156],
        u_lobe: 0.136980132,
        u: [0.42044763, 0.886512026],
        wi: [0.8303684, 0.524536371, 0.188015863],
        weight: [0.735830069, 0.654071212, 0.572312295],
        pdf: 0.842993796,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.781574142, -0.510568426, 0.3584156],
        u_lobe: 0.867918521,
        u: [0.944507872, 0.193644909],
        wi: [0.760065317, 0.257147312, -0.596804857],
        weight: [0.589529693, 0.687784612, 0.786039531],
        pdf: 0.667819977,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.576548155, 0.114719783, 0.808969466],
        u_lobe: 0.712787463,
        u: [0.925498995, 0.729416258],
        wi: [0.32710433, -0.173375517, -0.928947628],
        weight: [0.599050105, 0.698891759, 0.798733413],
        pdf: 4.4777565,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.576548155, 0.114719783, 0.808969466],
        u_lobe: 0.984634127,
        u: [0.730018547, 0.8198839],
        wi: [0.338431299, -0.1003948, -0.935620129],
        weight: [0.599148393, 0.699006379, 0.798864484],
        pdf: 19.7080116,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.48247487, 0.227999844, 0.845715124],
        u_lobe: 0.274984758,
        u: [0.0119975707, 0.313036177],
        wi: [0.530386031, 0.0656143874, -0.845213294],
        weight: [0.597620189, 0.697223544, 0.796826899],
        pdf: 0.16862154,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [-0.48247487, 0.227999844, 0.845715124],
        u_lobe: 0.257196266,
        u: [0.108771331, 0.255604612],
        wi: [0.404829472, -0.0996200517, -0.908949316],
        weight: [0.598743021, 0.698533475, 0.798324049],
        pdf: 7.56727123,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.148989102, 0.677003354, 0.720741775],
        u_lobe: 0.917925853,
        u: [0.876249706, 0.0917582322],
        wi: [-0.198441759, -0.534163594, -0.821760356],
        weight: [0.597142339, 0.696666062, 0.796189785],
        pdf: 4.0184989,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.148989102, 0.677003354, 0.720741775],
        u_lobe: 0.790122469,
        u: [0.0845788044, 0.358697067],
        wi: [0.00538447127, -0.521423519, -0.853281021],
        weight: [0.597775817, 0.6974051, 0.797034442],
        pdf: 3.88037205,
        eta: 1.5,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.0207042313, -0.0195342732, -0.999594791],
        u_lobe: 0.896395703,
        u: [0.163474711, 0.0569583921],
        wi: [0.164785773, -0.00258795638, 0.986326098],
        weight: [0.599832535, 0.699804604, 0.799776733],
        pdf: 1.20180905,
        eta: 0.666666687,
    },
    SampleRef {
        model: "rough_dielectric_ggx",
        adjoint: true,
        wo: [0.0207042313, -0.0195342732, -0.999594791],
        u_lobe: 0.197986471,
        u: [0.507911092, 0.694974234],
        wi: [-0.0624643788, 0.0570730194, 0.996414065],
        weight: [0.599956751, 0.699949503, 0.799942315],
        pdf: 21.6354198,
        eta: 0.666666687,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.718605446,
        u: [0.675615294, 0.0723383578],
        wi: [-0.413588315, -0.260796964, -0.872312844],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 3.24272084,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.327964189,
        u: [0.455610641, 0.30705601],
        wi: [-0.993913114, 0.019223189, 0.108476706],
        weight: [1.0, 1.0, 1.0],
        pdf: 35.1372757,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.562670881, 0.564986771, 0.603482749],
        u_lobe: 0.01193304,
        u: [0.115153849, 0.0707946161],
        wi: [0.476482004, -0.219707057, 0.85128957],
        weight: [1.0, 1.0, 1.0],
        pdf: 0.231717348,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.562670881, 0.564986771, 0.603482749],
        u_lobe: 0.565156145,
        u: [0.0947148941, 0.396372726],
        wi: [0.24360311, -0.422175199, -0.873169899],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 18.6563492,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.719925784, 0.54037772, 0.43554424],
        u_lobe: 0.00357746789,
        u: [0.521831746, 0.0195227636],
        wi: [-0.782504678, -0.415886968, 0.463383734],
        weight: [1.0, 1.0, 1.0],
        pdf: 0.332440376,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.719925784, 0.54037772, 0.43554424],
        u_lobe: 0.864213823,
        u: [0.196661952, 0.533617062],
        wi: [-0.305321217, -0.377594203, -0.874186158],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 24.0365963,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.551003202, -0.168750494, 0.817262958],
        u_lobe: 0.870557295,
        u: [0.996324486, 0.717647107],
        wi: [0.211671352, -0.261228114, -0.941783011],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 1.18752599,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [-0.551003202, -0.168750494, 0.817262958],
        u_lobe: 0.606329947,
        u: [0.733221872, 0.086764297],
        wi: [0.194500223, 0.0898147747, -0.976781964],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 13.5559473,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.585779948, 0.3585167, 0.726861492],
        u_lobe: 0.839827838,
        u: [0.845106422, 0.283258707],
        wi: [-0.223254085, -0.0454430021, -0.973700523],
        weight: [0.170753345, 0.170753345, 0.170753345],
        pdf: 18.6417904,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.585779948, 0.3585167, 0.726861492],
        u_lobe: 0.0524102518,
        u: [0.0943229344, 0.114952591],
        wi: [-0.627116382, 0.171717986, 0.759761631],
        weight: [1.0, 1.0, 1.0],
        pdf: 0.292735696,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.751742355, 0.439823492, -0.491364149],
        u_lobe: 0.0739958602,
        u: [0.0207368864, 0.38267948],
        wi: [-0.738782585, 0.100687586, -0.666380048],
        weight: [1.0, 1.0, 1.0],
        pdf: 1.35239494,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: false,
        wo: [0.751742355, 0.439823492, -0.491364149],
        u_lobe: 0.907007881,
        u: [0.46448327, 0.262787957],
        wi: [-0.771117866, -0.342662722, -0.536618531],
        weight: [1.0, 1.0, 1.0],
        pdf: 8.63983154,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.861947316,
        u: [0.802493844, 0.25405637],
        wi: [-0.402961791, -0.12318024, -0.906889379],
        weight: [1.0, 1.0, 1.0],
        pdf: 4.80709362,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.72497793,
        u: [0.91904119, 0.417736192],
        wi: [-0.999830067, 0.00393250398, 0.0180117376],
        weight: [0.72244662, 0.72244662, 0.72244662],
        pdf: 42.563797,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.229964781, 0.147581493, 0.961943815],
        u_lobe: 0.698376584,
        u: [0.788016926, 0.642112746],
        wi: [-0.098402068, 0.0443775803, -0.994156778],
        weight: [1.0, 1.0, 1.0],
        pdf: 33.6233482,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.229964781, 0.147581493, 0.961943815],
        u_lobe: 0.261401534,
        u: [0.0871446236, 0.258466693],
        wi: [-0.0894498453, -0.243009061, -0.965890884],
        weight: [1.0, 1.0, 1.0],
        pdf: 18.2676811,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.810793933, 0.100568441, 0.576627424],
        u_lobe: 0.849568079,
        u: [0.754483008, 0.359756918],
        wi: [-0.317070305, -0.0287139099, -0.947967291],
        weight: [1.0, 1.0, 1.0],
        pdf: 23.4573765,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [0.810793933, 0.100568441, 0.576627424],
        u_lobe: 0.248783204,
        u: [0.58456152, 0.932483184],
        wi: [-0.353726298, 0.145955101, -0.923891068],
        weight: [1.0, 1.0, 1.0],
        pdf: 11.2566271,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.765602962, 0.286010641, 0.576237814],
        u_lobe: 0.484719314,
        u: [0.160044587, 0.303370711],
        wi: [0.338270098, -0.232196465, -0.911952972],
        weight: [1.0, 1.0, 1.0],
        pdf: 19.6254635,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.765602962, 0.286010641, 0.576237814],
        u_lobe: 0.19238915,
        u: [0.839950321, 0.735419344],
        wi: [0.799212575, -0.40315941, 0.445782095],
        weight: [1.0, 1.0, 1.0],
        pdf: 1.10567641,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.29638612, 0.864804711, 0.405299988],
        u_lobe: 0.91284758,
        u: [0.810832534, 0.128126912],
        wi: [0.153090775, -0.285991341, -0.945923924],
        weight: [1.0, 1.0, 1.0],
        pdf: 9.61610317,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.29638612, 0.864804711, 0.405299988],
        u_lobe: 0.868856401,
        u: [0.978088335, 0.740341147],
        wi: [0.101754688, -0.140321344, -0.984863341],
        weight: [1.0, 1.0, 1.0],
        pdf: 2.41312313,
        eta: 2.42000008,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.551062337, 0.833956003, -0.0291150389],
        u_lobe: 0.132211189,
        u: [0.307017825, 0.46205395],
        wi: [0.546306849, -0.672431231, -0.499384761],
        weight: [1.0, 1.0, 1.0],
        pdf: 25.221529,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_dielectric_beckmann_aniso",
        adjoint: true,
        wo: [-0.551062337, 0.833956003, -0.0291150389],
        u_lobe: 0.847073602,
        u: [0.474169598, 0.128768228],
        wi: [0.531562865, -0.739940763, -0.412223935],
        weight: [1.0, 1.0, 1.0],
        pdf: 18.6651192,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.947495164,
        u: [0.00784011323, 0.412873184],
        wi: [-0.974820793, -0.13641797, 0.176393256],
        weight: [0.34085381, 0.568089664, 0.795325577],
        pdf: 0.0111537334,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.437389663,
        u: [0.415333354, 0.043319337],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.834271967, 0.834271967, 0.834271967],
        pdf: 0.801350176,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.749072844, 0.207310637, 0.629215523],
        u_lobe: 0.610088813,
        u: [0.544200783, 0.667345213],
        wi: [0.0689335093, 0.327514708, 0.942328155],
        weight: [0.336321235, 0.560535371, 0.784749508],
        pdf: 0.266182333,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.749072844, 0.207310637, 0.629215523],
        u_lobe: 0.0954650258,
        u: [0.632658336, 0.662171795],
        wi: [-0.74907285, -0.207310632, 0.629215539],
        weight: [0.529825091, 0.529825091, 0.529825091],
        pdf: 0.112584673,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.493245153, -0.0966760583, 0.864501567],
        u_lobe: 0.976642763,
        u: [0.0627558623, 0.648783417],
        wi: [-0.843444228, 0.230936363, 0.485046595],
        weight: [0.31198287, 0.51997143, 0.727959991],
        pdf: 0.142073199,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.493245153, -0.0966760583, 0.864501567],
        u_lobe: 0.973207573,
        u: [0.141775869, 0.559136474],
        wi: [-0.710434735, 0.0926312804, 0.69764024],
        weight: [0.326823682, 0.544706106, 0.762588561],
        pdf: 0.204343215,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.0522807436, 0.603396409, 0.795725767],
        u_lobe: 0.285969781,
        u: [0.563517475, 0.720886411],
        wi: [0.0989269242, 0.430553943, 0.897126913],
        weight: [0.331178457, 0.551964104, 0.772749722],
        pdf: 0.26144129,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.0522807436, 0.603396409, 0.795725767],
        u_lobe: 0.978151316,
        u: [0.551380526, 0.144778604],
        wi: [0.0805348903, -0.705863357, 0.703754961],
        weight: [0.32782495, 0.546374917, 0.764924824],
        pdf: 0.20508872,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.940780878, -0.338201644, 0.0234731252],
        u_lobe: 0.174570438,
        u: [0.27474971, 0.402245453],
        wi: [0.940780878, 0.338201642, 0.023473125],
        weight: [0.936799288, 0.936799288, 0.936799288],
        pdf: 0.93253547,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [-0.940780878, -0.338201644, 0.0234731252],
        u_lobe: 0.253087967,
        u: [0.26111146, 0.308654659],
        wi: [0.940780878, 0.338201642, 0.023473125],
        weight: [0.936799288, 0.936799288, 0.936799288],
        pdf: 0.93253547,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.962785932, -0.270260356, 0.00160928972],
        u_lobe: 0.441420828,
        u: [0.671483632, 0.531330064],
        wi: [-0.962785959, 0.270260364, 0.00160928967],
        weight: [0.995347023, 0.995347023, 0.995347023],
        pdf: 0.995325267,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic",
        adjoint: false,
        wo: [0.962785932, -0.270260356, 0.00160928972],
        u_lobe: 0.732326962,
        u: [0.194214412, 0.902576052],
        wi: [-0.962785959, 0.270260364, 0.00160928967],
        weight: [0.995347023, 0.995347023, 0.995347023],
        pdf: 0.995325267,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.190024799,
        u: [0.684634284, 0.405008593],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.762786686, 0.593278527, 0.762786686],
        pdf: 0.805125535,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.657602934,
        u: [0.261970567, 0.124585653],
        wi: [-0.997458696, -0.0, 0.0712470487],
        weight: [0.762786686, 0.593278527, 0.762786686],
        pdf: 0.805125535,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.431488599, -0.840126535, 0.328641132],
        u_lobe: 0.951050548,
        u: [0.807573711, 0.755755731],
        wi: [0.4885602, 0.373785138, 0.788412094],
        weight: [0.623272717, 0.174563289, 0.0328154303],
        pdf: 0.157395378,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.431488599, -0.840126535, 0.328641132],
        u_lobe: 0.940633401,
        u: [0.908098614, 0.565003522],
        wi: [0.809818745, 0.101841159, 0.577773273],
        weight: [0.605104148, 0.169474721, 0.0318588503],
        pdf: 0.115344293,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.389772564, -0.247362874, 0.887067617],
        u_lobe: 0.185706152,
        u: [0.713280042, 0.0469120331],
        wi: [0.327439576, -0.84494859, 0.422900975],
        weight: [0.510090113, 0.142863631, 0.0268563461],
        pdf: 0.111436367,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.389772564, -0.247362874, 0.887067617],
        u_lobe: 0.869362978,
        u: [0.294274415, 0.971031136],
        wi: [-0.316852778, 0.887178481, 0.335438013],
        weight: [0.47753197, 0.13374491, 0.0251421537],
        pdf: 0.0883894712,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.0202286381, -0.425760028, 0.904609972],
        u_lobe: 0.148335082,
        u: [0.393497459, 0.137944282],
        wi: [0.0202286374, 0.425760031, 0.904609978],
        weight: [0.509991944, 0.396660388, 0.509991944],
        pdf: 0.171538308,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [-0.0202286381, -0.425760028, 0.904609972],
        u_lobe: 0.634143442,
        u: [0.492931693, 0.355363129],
        wi: [-0.011100146, -0.289060682, 0.957246423],
        weight: [0.560855806, 0.157081857, 0.0295291692],
        pdf: 0.252433121,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.908509627, -0.28295393, 0.307485499],
        u_lobe: 0.147048866,
        u: [0.955652235, 0.22308358],
        wi: [-0.908509612, 0.282953918, 0.307485491],
        weight: [0.577474236, 0.449146628, 0.577474236],
        pdf: 0.394946158,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.908509627, -0.28295393, 0.307485499],
        u_lobe: 0.560324406,
        u: [0.413562266, 0.138114247],
        wi: [-0.134981096, -0.711073339, 0.690039694],
        weight: [0.625583231, 0.175210401, 0.0329370797],
        pdf: 0.132897928,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.230941183, -0.938809071, 0.255545883],
        u_lobe: 0.276007712,
        u: [0.814354819, 0.852827256],
        wi: [-0.230941176, 0.938809097, 0.255545884],
        weight: [0.599812448, 0.466520816, 0.599812448],
        pdf: 0.457825273,
        eta: 1.0,
    },
    SampleRef {
        model: "plastic_nonlinear",
        adjoint: false,
        wo: [0.230941183, -0.938809071, 0.255545883],
        u_lobe: 0.649201638,
        u: [0.132453359, 0.740907666],
        wi: [-0.639823258, 0.361923158, 0.677965939],
        weight: [0.648744404, 0.181697279, 0.0341565199],
        pdf: 0.117003061,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.211461885,
        u: [0.192594257, 0.68087321],
        wi: [-0.961903632, -0.0114491209, 0.273148894],
        weight: [0.565051734, 0.565352857, 0.56565392],
        pdf: 22.4040775,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.964291138,
        u: [0.238968988, 0.449276432],
        wi: [-0.515993834, -0.079367429, 0.852907479],
        weight: [0.464382738, 0.7739712, 1.08355963],
        pdf: 0.0848640427,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.861898036, 0.498985177, 0.0902528],
        u_lobe: 0.231455867,
        u: [0.769874162, 0.223134077],
        wi: [0.856557012, -0.507374346, 0.0942411572],
        weight: [0.875226378, 0.875265658, 0.875304937],
        pdf: 42.2338448,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.861898036, 0.498985177, 0.0902528],
        u_lobe: 0.56126101,
        u: [0.927252107, 0.421271917],
        wi: [0.864411414, -0.502273202, 0.0226842258],
        weight: [0.60921818, 0.609224558, 0.609230876],
        pdf: 49.2148705,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.646693543, -0.552547484, 0.525812456],
        u_lobe: 0.216855882,
        u: [0.769513009, 0.441687483],
        wi: [0.531262159, -0.0911568776, 0.84228909],
        weight: [0.329965472, 0.549942434, 0.769919455],
        pdf: 0.226984456,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.646693543, -0.552547484, 0.525812456],
        u_lobe: 0.309285957,
        u: [0.364546824, 0.907405041],
        wi: [-0.210359588, 0.787187576, 0.579728067],
        weight: [0.320544451, 0.534240723, 0.747937024],
        pdf: 0.15622814,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.0481130223, 0.102908567, 0.993526529],
        u_lobe: 0.830213124,
        u: [0.847376128, 0.950084382],
        wi: [0.512849271, 0.739790142, 0.435541272],
        weight: [0.292501777, 0.487502933, 0.682504117],
        pdf: 0.127968058,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.0481130223, 0.102908567, 0.993526529],
        u_lobe: 0.420098431,
        u: [0.0432855582, 0.045838913],
        wi: [-0.648721635, -0.643049479, 0.406998307],
        weight: [0.287813693, 0.479689509, 0.671565354],
        pdf: 0.119581737,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.557862822, 0.55946124, 0.613018917],
        u_lobe: 0.522675781,
        u: [0.25369158, 0.939063697],
        wi: [-0.374503493, 0.794263661, 0.478426933],
        weight: [0.305095315, 0.508492231, 0.711889088],
        pdf: 0.134103641,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [-0.557862822, 0.55946124, 0.613018917],
        u_lobe: 0.865223674,
        u: [0.718578383, 0.564236909],
        wi: [0.425563335, 0.100009575, 0.899385273],
        weight: [0.324525952, 0.540876567, 0.757227182],
        pdf: 0.252098769,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.764639491, 0.450306495, 0.461032004],
        u_lobe: 0.950068132,
        u: [0.184492594, 0.801043024],
        wi: [-0.461968035, 0.429843247, 0.775770783],
        weight: [0.335561901, 0.559269845, 0.782977819],
        pdf: 0.19997938,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_beckmann",
        adjoint: false,
        wo: [0.764639491, 0.450306495, 0.461032004],
        u_lobe: 0.178488663,
        u: [0.455130688, 0.544219358],
        wi: [-0.746506155, -0.448311031, 0.491676539],
        weight: [0.504452825, 0.512629688, 0.520806491],
        pdf: 3.29311967,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.515009662,
        u: [0.214230259, 0.047376569],
        wi: [-0.430714905, -0.796213865, 0.424886048],
        weight: [0.323472053, 0.151673555, 0.0963167399],
        pdf: 0.105994821,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.9974587, 0.0, 0.07124705],
        u_lobe: 0.330252235,
        u: [0.97930408, 0.580228717],
        wi: [-0.924843073, -0.349533707, 0.14997144],
        weight: [0.338225126, 0.216564655, 0.232510373],
        pdf: 0.0697518438,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.274361446, 0.95682533, 0.0959743949],
        u_lobe: 0.0104582316,
        u: [0.449538576, 0.203907311],
        wi: [-0.248334989, 0.42757988, 0.869197965],
        weight: [0.369453758, 0.15468125, 0.0678290576],
        pdf: 0.184237078,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.274361446, 0.95682533, 0.0959743949],
        u_lobe: 0.106889525,
        u: [0.686528955, 0.553484504],
        wi: [0.36566782, -0.480213225, 0.797296822],
        weight: [0.324568242, 0.185113907, 0.171500072],
        pdf: 0.329981029,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.275282156, -0.936227603, 0.218397826],
        u_lobe: 0.360515522,
        u: [0.56047277, 0.787504983],
        wi: [0.224594697, 0.859707177, 0.458760083],
        weight: [0.418395519, 0.304324538, 0.370438546],
        pdf: 0.612303257,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.275282156, -0.936227603, 0.218397826],
        u_lobe: 0.871787062,
        u: [0.412663311, 0.283344012],
        wi: [-0.134907708, -0.411775649, 0.901243985],
        weight: [0.376943529, 0.155034438, 0.0628779456],
        pdf: 0.200940341,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.243709638, -0.808571014, 0.535554411],
        u_lobe: 0.0870941711,
        u: [0.299649508, 0.32833568],
        wi: [0.33954826, 0.240439564, 0.909338236],
        weight: [0.364054352, 0.172388345, 0.112233639],
        pdf: 0.288919002,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [-0.243709638, -0.808571014, 0.535554411],
        u_lobe: 0.31065685,
        u: [0.929620654, 0.763864855],
        wi: [0.761197567, 0.398589998, 0.511570394],
        weight: [0.351712435, 0.16593039, 0.107033417],
        pdf: 0.155362546,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.726868948, -0.493844592, 0.477262036],
        u_lobe: 0.984991223,
        u: [0.442034054, 0.33334711],
        wi: [-0.0899243727, -0.320946038, 0.942818761],
        weight: [0.373128831, 0.155960679, 0.0679143742],
        pdf: 0.243604377,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.726868948, -0.493844592, 0.477262036],
        u_lobe: 0.229405071,
        u: [0.247471082, 0.771465222],
        wi: [-0.595720947, 0.596946418, 0.537374616],
        weight: [0.377246559, 0.242222786, 0.260865003],
        pdf: 0.339660347,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.631195095, -0.754038276, 0.181711394],
        u_lobe: 0.127370385,
        u: [0.632585821, 0.124138904],
        wi: [0.161693007, -0.74721241, 0.644615293],
        weight: [0.362510949, 0.148983851, 0.0602100194],
        pdf: 0.140276656,
        eta: 1.0,
    },
    SampleRef {
        model: "rough_plastic_ggx_nonlinear",
        adjoint: false,
        wo: [0.631195095, -0.754038276, 0.181711394],
        u_lobe: 0.0879197066,
        u: [0.735910475, 0.678310424],
        wi: [-0.61178571, 0.462671876, 0.641601801],
        weight: [0.351734012, 0.227021471, 0.245905414],
        pdf: 0.398571432,
        eta: 1.0,
    },
];
