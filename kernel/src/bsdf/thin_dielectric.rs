//! Thin dielectric sheet (Mitsuba `thindielectric`): a slab of negligible thickness whose
//! inter-reflections are summed in closed form. Light is either mirrored or passes straight through
//! (no refraction, so `eta = 1`); both lobes are Dirac deltas, on either side alike. Transmission is
//! Mitsuba's `Null` lobe (the ray continues unchanged).

use super::fresnel::{fresnel, reflect};
use super::{BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::vec3;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct ThinDielectric {
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub specular_reflectance: Rgb,
    pub specular_transmittance: Rgb,
}

impl ThinDielectric {
    /// Total reflectance of the slab: `R + T R T + T R³ T + … = 2R / (1 + R)` for one interface's `R`.
    pub fn reflectance(&self, cos_theta: f32) -> f32 {
        let r = fresnel(cos_theta.abs(), self.eta).f;
        r * 2.0 / (1.0 + r)
    }
}

impl<'a> Bxdf<'a> for ThinDielectric {
    /// Reads `eta` and `specular_transmittance`; `specular` is the evaluated `specular_reflectance`.
    fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let t = vec3([m.specular_transmittance[0], m.specular_transmittance[1], m.specular_transmittance[2]]);
        ThinDielectric { eta: m.eta, specular_reflectance: specular, specular_transmittance: t }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::TRANSMISSION | BsdfFlags::SPECULAR)
    }

    fn eval(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> Rgb {
        Rgb::ZERO
    }

    fn pdf(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> f32 {
        0.0
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, _u: Vec2, _mode: TransportMode) -> BsdfSample {
        let r = self.reflectance(wo.z);
        if u_lobe < r {
            BsdfSample { wi: reflect(wo), weight: self.specular_reflectance, pdf: r, eta: 1.0, delta: true }
        } else {
            BsdfSample { wi: -wo, weight: self.specular_transmittance, pdf: 1.0 - r, eta: 1.0, delta: true }
        }
    }
}
