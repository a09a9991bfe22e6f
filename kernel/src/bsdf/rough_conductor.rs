//! Rough conductor (Mitsuba `roughconductor`): the Cook-Torrance/Walter microfacet reflection
//! `F·D·G / (4 cos θo cos θi)` with the exact conductor Fresnel term, Beckmann or GGX, anisotropic,
//! sampled through visible normals. One-sided.
use super::fresnel::{fresnel_conductor_rgb, reflect_about};
use super::microfacet::Microfacet;
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::vec3;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct RoughConductor {
    pub distr: Microfacet,
    pub eta: Rgb,
    pub k: Rgb,
    pub specular: Rgb,
}

impl<'a> Bxdf<'a> for RoughConductor {
    /// Reads `alpha_u`, `alpha_v`, `flags & MATERIAL_BECKMANN`, `conductor_eta`, `conductor_k`;
    /// `specular` is the evaluated `specular_reflectance`.
    fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let eta = vec3([m.conductor_eta[0], m.conductor_eta[1], m.conductor_eta[2]]);
        let k = vec3([m.conductor_k[0], m.conductor_k[1], m.conductor_k[2]]);
        RoughConductor { distr: Microfacet::from_material(m), eta, k, specular }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::GLOSSY)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    /// Value and density share the half vector, `D` and `G1(wo)`.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> EvalPdf {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return EvalPdf::ZERO;
        }
        let h = (wo + wi).normalize();
        let d = self.distr.d(h);
        if d == 0.0 {
            return EvalPdf::ZERO;
        }
        let g1_o = self.distr.smith_g1(wo, h);
        let g = g1_o * self.distr.smith_g1(wi, h);
        let fresnel = fresnel_conductor_rgb(wo.dot(h), self.eta, self.k);
        // f·cos θi with the 1/cos θi of the BRDF cancelled.
        let f = self.specular * fresnel * (d * g / (4.0 * wo.z));
        // Visible-normal density D·G1(wo)·(wo·h)/cos θo times the reflection Jacobian 1/(4 wi·h).
        let pdf = if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 { 0.0 } else { d * g1_o / (4.0 * wo.z) };
        EvalPdf { f, pdf }
    }

    fn sample(&self, wo: Vec3, _u_lobe: f32, u: Vec2, _mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let ms = self.distr.sample(wo, u);
        let wi = reflect_about(wo, ms.m);
        let wi_m = wi.dot(ms.m);
        if ms.pdf <= 0.0 || wi.z <= 0.0 || wi_m <= 0.0 {
            return BsdfSample::invalid();
        }
        // With visible normals, f·cos/pdf reduces to F·G1(wi).
        let f = fresnel_conductor_rgb(wo.dot(ms.m), self.eta, self.k);
        let weight = self.specular * f * self.distr.smith_g1(wi, ms.m);
        BsdfSample { wi, weight, pdf: ms.pdf / (4.0 * wi_m), eta: 1.0, delta: false }
    }
}
