//! "Ray Tracing in One Weekend"'s fuzzy metal (caustic's `fuzzymetal`): the mirror direction
//! displaced by a point drawn uniformly in a ball of radius `fuzz`, absorbed when that lands below the
//! surface. The book defines the model by this sampling procedure only; its density has a closed form
//! (below), so the model also evaluates and takes part in next-event estimation and MIS.
//!
//! With `r` the mirror direction of `wo` and `s² = |ω × r|²`, the direction `ω` of `r + fuzz·B`
//! (`B` uniform in the unit ball) has the solid-angle density
//! `p(ω) = (t₊³ − t₋³) / (4π fuzz³)` where `t±` bound the chord of the ball `|x − r| ≤ fuzz` along `ω`;
//! with `t₊ t₋ = 1 − fuzz²` and `t₊ − t₋ = 2√(fuzz² − s²)` this is
//! `√(fuzz² − s²) (3 + fuzz² − 4s²) / (2π fuzz³)` for `ω·r > 0`, `s < fuzz`, and 0 elsewhere
//! (`fuzz ≤ 1`, as the book clamps it, keeps the origin outside the ball).
//!
//! `eval = albedo · p(ω)` (the cosine included): the model is energy-conserving but not reciprocal —
//! `f·cos θi`, not `f`, is symmetric — so importance transport (`TransportMode::Importance`) uses `f(wi, wo)`.
//! One-sided like Mitsuba's conductors; `fuzz = 0` is a Dirac mirror of reflectance `albedo`.
use super::fresnel::reflect;
use super::{same_hemisphere_above, BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::sampling::square_to_uniform_sphere;
use crate::spectrum::Rgb;
use core::f32::consts::PI;
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

#[derive(Clone, Copy)]
pub struct FuzzyMetal {
    pub albedo: Rgb,
    /// Radius of the displacement ball, in [0, 1].
    pub fuzz: f32,
}

impl FuzzyMetal {
    /// Whether the model is the plain mirror (fuzz 0), which only sampling can use.
    pub fn is_delta(fuzz: f32) -> bool {
        fuzz <= 0.0
    }

    /// Solid-angle density of the displaced direction `wi` around the mirror direction `r`.
    fn density(&self, r: Vec3, wi: Vec3) -> f32 {
        let f = self.fuzz;
        let s2 = wi.cross(r).length_squared();
        if wi.dot(r) <= 0.0 || s2 >= f * f {
            return 0.0;
        }
        (f * f - s2).sqrt() * (3.0 + f * f - 4.0 * s2) / (2.0 * PI * f * f * f)
    }

    /// `wi.z / wo.z` in importance transport, 1 in radiance transport.
    fn adjoint_factor(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if mode == TransportMode::Importance {
            wi.z / wo.z
        } else {
            1.0
        }
    }
}

impl<'a> Bxdf<'a> for FuzzyMetal {
    /// Reads `alpha_u` as the fuzz; `reflectance` is the evaluated albedo.
    fn from_material(m: &Material, reflectance: Rgb, _specular: Rgb, _tables: &[f32]) -> Self {
        FuzzyMetal { albedo: reflectance, fuzz: m.alpha_u }
    }

    fn flags(&self) -> BsdfFlags {
        let lobe = if Self::is_delta(self.fuzz) { BsdfFlags::SPECULAR } else { BsdfFlags::GLOSSY };
        BsdfFlags::of(BsdfFlags::REFLECTION | lobe)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if Self::is_delta(self.fuzz) || !same_hemisphere_above(wo, wi) {
            return Rgb::ZERO;
        }
        self.albedo * (self.density(reflect(wo), wi) * self.adjoint_factor(wo, wi, mode))
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> f32 {
        if Self::is_delta(self.fuzz) || !same_hemisphere_above(wo, wi) {
            return 0.0;
        }
        self.density(reflect(wo), wi)
    }

    /// The book's procedure: `u_lobe` sets the radius (cube root: uniform in volume), `u` the
    /// direction of the displacement.
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let r = reflect(wo);
        if Self::is_delta(self.fuzz) {
            return BsdfSample { wi: r, weight: self.albedo, pdf: 1.0, eta: 1.0, delta: true };
        }
        let d = r + square_to_uniform_sphere(u) * (self.fuzz * u_lobe.powf(1.0 / 3.0));
        let len = d.length();
        // Below the surface the book absorbs the ray; a zero vector (fuzz 1, measure zero) likewise.
        if !(d.z > 0.0 && len > 1.0e-6) {
            return BsdfSample::invalid();
        }
        let wi = d / len;
        let pdf = self.density(r, wi);
        if pdf <= 0.0 {
            return BsdfSample::invalid();
        }
        BsdfSample {
            wi,
            weight: self.albedo * self.adjoint_factor(wo, wi, mode),
            pdf,
            eta: 1.0,
            delta: false,
        }
    }
}
