//! Lambertian reflection (Mitsuba `diffuse`).
use super::{same_hemisphere_above, BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::INV_PI;
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct Diffuse {
    pub reflectance: Rgb,
}

impl<'a> Bxdf<'a> for Diffuse {
    /// Reads the evaluated `reflectance`.
    fn from_material(_m: &Material, reflectance: Rgb, _specular: Rgb, _tables: &[f32]) -> Self {
        Diffuse { reflectance }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> Rgb {
        if !same_hemisphere_above(wo, wi) {
            return Rgb::ZERO;
        }
        self.reflectance * (INV_PI * wi.z)
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> f32 {
        if !same_hemisphere_above(wo, wi) {
            return 0.0;
        }
        cosine_hemisphere_pdf(wi.z)
    }

    fn sample(&self, wo: Vec3, _u_lobe: f32, u: Vec2, _mode: TransportMode) -> BsdfSample {
        let wi = square_to_cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wi.z);
        if wo.z <= 0.0 || pdf <= 0.0 {
            return BsdfSample::invalid();
        }
        // f·cos/pdf = (ρ/π)·cos / (cos/π) = ρ exactly: no division, no noise from it.
        BsdfSample { wi, weight: self.reflectance, pdf, eta: 1.0, delta: false }
    }
}
