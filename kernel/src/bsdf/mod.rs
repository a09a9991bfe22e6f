//! BSDFs. Every model works in the local shading frame (normal = +z) with `wo` pointing towards the
//! viewer (or the previous vertex) and `wi` towards the light; `eval` includes the cosine factor
//! `|cos θi|` so that sampling weights are `eval / pdf`.
pub mod diffuse;
pub mod phong;

use crate::scene::{Material, BSDF_PHONG};
use crate::spectrum::Rgb;
use crate::glam::{Vec2, Vec3};

/// A sampled direction with its weight `f·cos/pdf` and solid-angle density.
#[derive(Clone, Copy)]
pub struct BsdfSample {
    pub wi: Vec3,
    pub weight: Rgb,
    pub pdf: f32,
    /// Relative index of refraction across the sampled interface (1 for reflection); Russian
    /// roulette divides it out as Mitsuba does.
    pub eta: f32,
}

impl BsdfSample {
    pub fn invalid() -> Self {
        BsdfSample { wi: Vec3::Z, weight: Rgb::ZERO, pdf: 0.0, eta: 1.0 }
    }
}

/// A surface's BSDF: the material record, dispatched on its `kind` with `match`. (The models are built
/// per call from the record rather than held in a data-carrying enum: rust-gpu 0.11 cannot cast between
/// variants of different layouts.)
#[derive(Clone, Copy)]
pub struct Bsdf {
    pub material: Material,
}

impl Bsdf {
    pub fn from_material(m: &Material) -> Bsdf {
        Bsdf { material: *m }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        match self.material.kind {
            BSDF_PHONG => phong::Phong::from_material(&self.material).eval(wo, wi),
            _ => diffuse::Diffuse::from_material(&self.material).eval(wo, wi),
        }
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.material.kind {
            BSDF_PHONG => phong::Phong::from_material(&self.material).pdf(wo, wi),
            _ => diffuse::Diffuse::from_material(&self.material).pdf(wo, wi),
        }
    }

    /// `u_lobe` picks a lobe of multi-lobe models; `u` warps to a direction.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> BsdfSample {
        match self.material.kind {
            BSDF_PHONG => phong::Phong::from_material(&self.material).sample(wo, u_lobe, u),
            _ => diffuse::Diffuse::from_material(&self.material).sample(wo, u),
        }
    }

    /// Whether next-event estimation can contribute (false for purely specular models).
    pub fn has_smooth_component(&self) -> bool {
        true
    }
}

/// Both directions on the outer side of the surface: the reflection models here are one-sided, as in
/// Mitsuba (two-sided materials are mirrored to the front by the integrator).
#[inline]
pub fn same_hemisphere_above(wo: Vec3, wi: Vec3) -> bool {
    wo.z > 0.0 && wi.z > 0.0
}
