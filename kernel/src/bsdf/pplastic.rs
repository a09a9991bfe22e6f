//! Mitsuba 3.9.1's `pplastic` in its unpolarized (RGB) form: a rough dielectric coating over a diffuse
//! base without the internal scattering of `roughplastic`. The glossy lobe is the coating's microfacet
//! reflection `specular·F·D·G / (4 cos θo)` (Beckmann or GGX, dielectric Fresnel of the facet); the
//! diffuse lobe is the base's Lambert term scaled by the coating's transmittance on the way in and out,
//! `(1 − F(cos θo))(1 − F(cos θi))`. Sampling picks the glossy lobe with the host's fixed probability
//! (Mitsuba's `specular_sampling_weight`, from the mean reflectances) through visible normals, else the
//! cosine hemisphere; the weight is `eval / pdf` of the whole. One-sided. (Mitsuba's polarized variants
//! also rotate Mueller matrices; caustic is an RGB renderer and follows the unpolarized code.)
use super::fresnel::{fresnel, reflect_about};
use super::microfacet::Microfacet;
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::INV_PI;
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::Rgb;

/// Where the record keeps the probability of sampling the glossy lobe (`params`).
pub const PARAM_SPECULAR_WEIGHT: usize = 0;

#[derive(Clone, Copy)]
pub struct PPlastic {
    pub distr: Microfacet,
    pub eta: f32,
    pub diffuse: Rgb,
    pub specular: Rgb,
    pub specular_probability: f32,
}

impl<'a> Bxdf<'a> for PPlastic {
    /// Reads `alpha_u`, `alpha_v`, `flags & MATERIAL_BECKMANN`, `eta` and
    /// `params[PARAM_SPECULAR_WEIGHT]`; `reflectance` and `specular` are the evaluated diffuse and
    /// specular reflectances.
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        PPlastic {
            distr: Microfacet::from_material(m),
            eta: m.eta,
            diffuse: reflectance,
            specular,
            specular_probability: m.params[PARAM_SPECULAR_WEIGHT],
        }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::GLOSSY | BsdfFlags::DIFFUSE)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    /// The same in both transport modes (every term is symmetric).
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> EvalPdf {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return EvalPdf::ZERO;
        }
        let h = (wo + wi).normalize();
        let d = self.distr.d(h);
        let g1_o = self.distr.smith_g1(wo, h);
        let glossy = self.specular * (fresnel(wo.dot(h), self.eta).f * d * g1_o * self.distr.smith_g1(wi, h))
            / (4.0 * wo.z);
        let transmitted = (1.0 - fresnel(wi.z, self.eta).f) * (1.0 - fresnel(wo.z, self.eta).f);
        let f = glossy + self.diffuse * (transmitted * INV_PI * wi.z);
        // Visible normals: D·G1(wo)·(wo·h)/cos θo times the reflection Jacobian 1/(4 wi·h).
        let glossy_pdf = if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 { 0.0 } else { d * g1_o / (4.0 * wo.z) };
        let p = self.specular_probability;
        EvalPdf { f, pdf: p * glossy_pdf + (1.0 - p) * cosine_hemisphere_pdf(wi.z) }
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let wi = if u_lobe < self.specular_probability {
            let ms = self.distr.sample(wo, u);
            if ms.pdf <= 0.0 {
                return BsdfSample::invalid();
            }
            reflect_about(wo, ms.m)
        } else {
            square_to_cosine_hemisphere(u)
        };
        let e = self.eval_pdf(wo, wi, mode);
        if !(e.pdf > 0.0) {
            return BsdfSample::invalid();
        }
        BsdfSample { wi, weight: e.f / e.pdf, pdf: e.pdf, eta: 1.0, delta: false }
    }
}
