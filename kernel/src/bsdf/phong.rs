//! The modified Phong BRDF (Lafortune & Willems 1994):
//! `f = kd/π + ks·(n+2)/(2π)·cosⁿα`, α the angle between `wi` and the mirror direction of `wo`.
//! With `kd + ks ≤ 1` it conserves energy; the `1/π` and `(n+2)/(2π)` normalisations are exactly what
//! makes that hold (dropping the π over-brightens the image by π).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{same_hemisphere_above, BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::{INV_2PI, INV_PI};
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::{luminance, Rgb};

#[derive(Clone, Copy)]
pub struct Phong {
    pub kd: Rgb,
    pub ks: Rgb,
    pub exponent: f32,
    /// Probability of sampling the specular lobe, from the lobes' luminance.
    pub specular_prob: f32,
}

/// Mirror direction of `wo` about the local normal (+z).
#[inline]
fn reflect_local(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

impl Phong {
    pub fn new(kd: Rgb, ks: Rgb, exponent: f32) -> Self {
        let (ld, ls) = (luminance(kd), luminance(ks));
        let specular_prob = if ld + ls > 0.0 { ls / (ld + ls) } else { 0.0 };
        Phong { kd, ks, exponent, specular_prob }
    }

    /// `cos α` between `wi` and the mirror direction of `wo`, clamped at 0.
    #[inline]
    fn cos_alpha(&self, wo: Vec3, wi: Vec3) -> f32 {
        reflect_local(wo).dot(wi).max(0.0)
    }
}

impl<'a> Bxdf<'a> for Phong {
    /// Reads `eta` (the exponent); `reflectance` and `specular` are the evaluated `kd` and `ks`.
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        Phong::new(reflectance, specular, m.eta)
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

    /// Value and density share `cosⁿα`.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> EvalPdf {
        if !same_hemisphere_above(wo, wi) {
            return EvalPdf::ZERO;
        }
        let ca = self.cos_alpha(wo, wi);
        let power = if ca > 0.0 { ca.powf(self.exponent) } else { 0.0 };
        let specular = (self.exponent + 2.0) * INV_2PI * power;
        let ps = self.specular_prob;
        let lobe_pdf = (self.exponent + 1.0) * INV_2PI * power;
        EvalPdf {
            f: (self.kd * INV_PI + self.ks * specular) * wi.z,
            pdf: (1.0 - ps) * cosine_hemisphere_pdf(wi.z) + ps * lobe_pdf,
        }
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let wi = if u_lobe < self.specular_prob {
            // cos α = u^(1/(n+1)) distributes directions as cosⁿα around the mirror direction.
            let cos_a = u.x.powf(1.0 / (self.exponent + 1.0));
            let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
            let phi = 2.0 * crate::math::PI * u.y;
            let lobe = Frame::from_normal(reflect_local(wo));
            lobe.to_world(Vec3::new(sin_a * phi.cos(), sin_a * phi.sin(), cos_a))
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
