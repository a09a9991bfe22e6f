//! Rough plastic (Mitsuba `roughplastic`): a diffuse base under a rough dielectric coating (isotropic
//! Beckmann or GGX). The coating's microfacet reflection is the glossy lobe; the diffuse lobe is
//! attenuated on the way in and out by the coating's directional transmittance, precomputed over
//! cos θ (`TRANSMITTANCE_RES` entries, linearly interpolated), and brightened by the internal
//! inter-reflections (the coating's hemispherical internal reflectance, also precomputed). One-sided.
use super::fresnel::{fresnel, reflect_about};
use super::microfacet::Microfacet;
use super::plastic::PARAM_SPECULAR_WEIGHT;
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::{Material, MATERIAL_BECKMANN, MATERIAL_NONLINEAR};
use crate::math::INV_PI;
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::Rgb;

/// Entries of the transmittance table, at cos θ = j / (RES - 1) (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const TRANSMITTANCE_RES: u32 = 64;

/// `params` slots filled by `precompute` (the specular weight shares plastic's slot).
pub const PARAM_INTERNAL_REFLECTANCE: usize = 0;

#[derive(Clone, Copy)]
pub struct RoughPlastic<'a> {
    pub distr: Microfacet,
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub diffuse: Rgb,
    pub specular: Rgb,
    /// Hemispherical reflectance of the coating seen from inside.
    pub internal_reflectance: f32,
    /// Prior weight of the glossy lobe in lobe selection (Mitsuba's `specular_sampling_weight`).
    pub specular_weight: f32,
    pub nonlinear: bool,
    /// The external transmittance table: `tables[table .. table + TRANSMITTANCE_RES]`.
    pub tables: &'a [f32],
    pub table: u32,
}

impl<'a> RoughPlastic<'a> {
    /// The coating's transmittance at `cos_theta` ∈ (0, 1], interpolated linearly in the table.
    pub fn transmittance(&self, cos_theta: f32) -> f32 {
        let x = cos_theta * (TRANSMITTANCE_RES - 1) as f32;
        let i = (x as u32).min(TRANSMITTANCE_RES - 2);
        let v0 = self.tables[(self.table + i) as usize];
        let v1 = self.tables[(self.table + i + 1) as usize];
        v0 + (v1 - v0) * (x - i as f32)
    }

    /// Probability of the glossy lobe for a viewer whose transmittance into the coating is `t_o`.
    #[inline]
    pub fn specular_probability(&self, t_o: f32) -> f32 {
        let ps = (1.0 - t_o) * self.specular_weight;
        let pd = t_o * (1.0 - self.specular_weight);
        if ps + pd > 0.0 {
            ps / (ps + pd)
        } else {
            0.0
        }
    }
}

impl<'a> Bxdf<'a> for RoughPlastic<'a> {
    /// Reads `alpha_u` (isotropic), `flags & (MATERIAL_BECKMANN | MATERIAL_NONLINEAR)`, `eta`, `table`
    /// and `params` (see `precompute`); `reflectance` and `specular` are the evaluated diffuse and
    /// specular reflectances.
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, tables: &'a [f32]) -> Self {
        RoughPlastic {
            distr: Microfacet::new(m.alpha_u, m.alpha_u, m.flags & MATERIAL_BECKMANN != 0),
            eta: m.eta,
            diffuse: reflectance,
            specular,
            internal_reflectance: m.params[PARAM_INTERNAL_REFLECTANCE],
            specular_weight: m.params[PARAM_SPECULAR_WEIGHT],
            nonlinear: m.flags & MATERIAL_NONLINEAR != 0,
            tables,
            table: m.table,
        }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE | BsdfFlags::GLOSSY)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    /// Value and density share the half vector, `D`, `G1(wo)` and the viewer's transmittance.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> EvalPdf {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return EvalPdf::ZERO;
        }
        let h = (wo + wi).normalize();
        let d = self.distr.d(h);
        let g1_o = self.distr.smith_g1(wo, h);
        let fresnel = fresnel(wo.dot(h), self.eta).f;
        let glossy = self.specular * (fresnel * d * (g1_o * self.distr.smith_g1(wi, h)) / (4.0 * wo.z));
        let denom = if self.nonlinear {
            Rgb::ONE - self.diffuse * self.internal_reflectance
        } else {
            Rgb::splat(1.0 - self.internal_reflectance)
        };
        let t_o = self.transmittance(wo.z);
        let t = t_o * self.transmittance(wi.z);
        let f = glossy + self.diffuse / denom * (INV_PI / (self.eta * self.eta) * wi.z * t);
        let ps = self.specular_probability(t_o);
        // Visible normals with the reflection Jacobian (wi·h = wo·h): D·G1(wo)/(4 cos θo).
        let glossy_pdf = d * g1_o / (4.0 * wo.z);
        EvalPdf { f, pdf: ps * glossy_pdf + (1.0 - ps) * cosine_hemisphere_pdf(wi.z) }
    }

    /// Picks a lobe with `u_lobe`, warps `u` by it, and weighs by the mixture density.
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let ps = self.specular_probability(self.transmittance(wo.z));
        let wi = if u_lobe < ps {
            reflect_about(wo, self.distr.sample(wo, u).m)
        } else {
            square_to_cosine_hemisphere(u)
        };
        let ep = self.eval_pdf(wo, wi, mode);
        if ep.pdf <= 0.0 {
            return BsdfSample::invalid();
        }
        BsdfSample { wi, weight: ep.f / ep.pdf, pdf: ep.pdf, eta: 1.0, delta: false }
    }
}

/// Fills `params[PARAM_INTERNAL_REFLECTANCE]` and `params[PARAM_SPECULAR_WEIGHT]` and returns the
/// external transmittance table (`TRANSMITTANCE_RES` floats) for the host to append to `tables` and
/// point `m.table` at. Reads `alpha_u`, `flags & MATERIAL_BECKMANN`, `eta`, and the constant
/// `reflectance` / `specular_reflectance` for the lobe prior.
#[cfg(not(target_arch = "spirv"))]
pub fn precompute(m: &mut Material) -> std::vec::Vec<f32> {
    let distr = Microfacet::new(m.alpha_u, m.alpha_u, m.flags & MATERIAL_BECKMANN != 0);
    let eta = m.eta;
    let mut table = std::vec::Vec::with_capacity(TRANSMITTANCE_RES as usize);
    let mut internal = 0.0f64;
    for j in 0..TRANSMITTANCE_RES {
        let mu = (j as f32 / (TRANSMITTANCE_RES - 1) as f32).max(1e-6);
        let w = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        table.push(precomp::transmittance(&distr, w, eta) as f32);
        internal += precomp::reflectance(&distr, w, 1.0 / eta) * mu as f64;
    }
    // Mitsuba's estimate of 2∫R(μ)μ dμ: twice the mean over the same equispaced cosines.
    m.params[PARAM_INTERNAL_REFLECTANCE] = (2.0 * internal / TRANSMITTANCE_RES as f64) as f32;
    m.params[PARAM_SPECULAR_WEIGHT] =
        super::plastic::specular_sampling_weight(m.reflectance, m.specular_reflectance);
    table
}

/// Directional transmittance and reflectance of a rough dielectric interface (single scattering),
/// integrated over visible normals with a tensor-product Gauss-Legendre rule as Mitsuba does
/// (32² nodes for eta > 1, else 128²).
#[cfg(not(target_arch = "spirv"))]
mod precomp {
    use super::super::fresnel::{fresnel, reflect_about, refract_about};
    use super::super::microfacet::Microfacet;
    use crate::glam::{Vec2, Vec3};

    fn resolution(eta: f32) -> usize {
        if eta > 1.0 {
            32
        } else {
            128
        }
    }

    /// `∫ G1(wt, m)·(1 - F) dP(m)` over normals visible from `w`, `wt` the refracted direction.
    pub fn transmittance(distr: &Microfacet, w: Vec3, eta: f32) -> f64 {
        let (nodes, weights) = gauss_legendre(resolution(eta));
        let mut sum = 0.0;
        for (a, wa) in nodes.iter().zip(&weights) {
            for (b, wb) in nodes.iter().zip(&weights) {
                let m = distr.sample(w, Vec2::new((0.5 * a + 0.5) as f32, (0.5 * b + 0.5) as f32)).m;
                let fr = fresnel(w.dot(m), eta);
                let wt = refract_about(w, m, fr.cos_theta_t, fr.eta_ti);
                if wt.z * w.z < 0.0 {
                    sum += (distr.smith_g1(wt, m) * (1.0 - fr.f)) as f64 * wa * wb * 0.25;
                }
            }
        }
        sum
    }

    /// `∫ G1(wr, m)·F dP(m)` over normals visible from `w`, `wr` the reflected direction.
    pub fn reflectance(distr: &Microfacet, w: Vec3, eta: f32) -> f64 {
        let (nodes, weights) = gauss_legendre(resolution(eta));
        let mut sum = 0.0;
        for (a, wa) in nodes.iter().zip(&weights) {
            for (b, wb) in nodes.iter().zip(&weights) {
                let m = distr.sample(w, Vec2::new((0.5 * a + 0.5) as f32, (0.5 * b + 0.5) as f32)).m;
                let wr = reflect_about(w, m);
                if wr.z > 0.0 && w.z > 0.0 {
                    sum += (distr.smith_g1(wr, m) * fresnel(w.dot(m), eta).f) as f64 * wa * wb * 0.25;
                }
            }
        }
        sum
    }

    /// Nodes and weights of the `n`-point Gauss-Legendre rule on [-1, 1] (Newton on P_n from
    /// Chebyshev guesses).
    pub fn gauss_legendre(n: usize) -> (std::vec::Vec<f64>, std::vec::Vec<f64>) {
        let mut nodes = std::vec![0.0; n];
        let mut weights = std::vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let step = p / d;
                x -= step;
                if step.abs() <= 1e-15 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            dp = if d != 0.0 { d } else { dp };
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[i] = x;
            nodes[n - 1 - i] = -x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        (nodes, weights)
    }

    /// `P_n(x)` and its derivative by the three-term recurrence.
    fn legendre(n: usize, x: f64) -> (f64, f64) {
        let (mut p0, mut p1) = (1.0, x);
        for k in 2..=n {
            let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
            p0 = p1;
            p1 = p2;
        }
        let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
        (p1, d)
    }
}
