//! Rough conductor (Mitsuba `roughconductor`): the Cook-Torrance/Walter microfacet reflection
//! `F·D·G / (4 cos θo cos θi)` with the exact conductor Fresnel term, Beckmann or GGX, anisotropic,
//! sampled through visible normals. One-sided.
use super::fresnel::{fresnel_conductor_rgb, reflect_about};
use super::microfacet::Microfacet;
use super::BsdfSample;
use crate::glam::{Vec2, Vec3};
use crate::math::vec3;
use crate::layout::Material;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct RoughConductor {
    pub distr: Microfacet,
    pub eta: Rgb,
    pub k: Rgb,
    pub specular: Rgb,
    /// Importance transport (light tracing); reflection does not depend on it.
    pub adjoint: bool,
}

impl RoughConductor {
    /// Reads `alpha_u`, `alpha_v`, `flags & MATERIAL_BECKMANN`, `conductor_eta`, `conductor_k`;
    /// `specular` is the evaluated `specular_reflectance`.
    pub fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let eta = vec3([m.conductor_eta[0], m.conductor_eta[1], m.conductor_eta[2]]);
        let k = vec3([m.conductor_k[0], m.conductor_k[1], m.conductor_k[2]]);
        RoughConductor { distr: Microfacet::from_material(m), eta, k, specular, adjoint: false }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let h = (wo + wi).normalize();
        let d = self.distr.d(h);
        if d == 0.0 {
            return Rgb::ZERO;
        }
        let g = self.distr.g(wo, wi, h);
        let f = fresnel_conductor_rgb(wo.dot(h), self.eta, self.k);
        // f·cos θi with the 1/cos θi of the BRDF cancelled.
        self.specular * f * (d * g / (4.0 * wo.z))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize();
        if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 {
            return 0.0;
        }
        // Visible-normal density D·G1(wo)·(wo·h)/cos θo times the reflection Jacobian 1/(4 wi·h).
        self.distr.d(h) * self.distr.smith_g1(wo, h) / (4.0 * wo.z)
    }

    pub fn sample(&self, wo: Vec3, _u_lobe: f32, u: Vec2) -> BsdfSample {
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
