//! Smooth dielectric interface (Mitsuba `dielectric`): Fresnel-weighted choice between the mirror and
//! the refracted direction, both Dirac deltas. `wo.z < 0` means the viewer is inside, where the
//! relative IOR is inverted. Transmitted radiance is scaled by `1/η²` (solid-angle compression) in
//! radiance transport only, as Mitsuba does.
use super::fresnel::{fresnel, reflect, refract};
use super::{BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::vec3;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct Dielectric {
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub specular_reflectance: Rgb,
    pub specular_transmittance: Rgb,
}

impl<'a> Bxdf<'a> for Dielectric {
    /// Reads `eta` and `specular_transmittance`; `specular` is the evaluated `specular_reflectance`.
    fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let t = vec3([m.specular_transmittance[0], m.specular_transmittance[1], m.specular_transmittance[2]]);
        Dielectric { eta: m.eta, specular_reflectance: specular, specular_transmittance: t }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::TRANSMISSION | BsdfFlags::SPECULAR)
    }

    /// Both lobes are Dirac deltas.
    fn eval(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> Rgb {
        Rgb::ZERO
    }

    fn pdf(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> f32 {
        0.0
    }

    /// Reflects with probability F, refracts otherwise, so that the Fresnel factor cancels in the weight.
    fn sample(&self, wo: Vec3, u_lobe: f32, _u: Vec2, mode: TransportMode) -> BsdfSample {
        let fr = fresnel(wo.z, self.eta);
        // Strict comparison: F = 0 (matched indices) never picks the mirror with probability 0.
        if u_lobe < fr.f {
            return BsdfSample {
                wi: reflect(wo),
                weight: self.specular_reflectance,
                pdf: fr.f,
                eta: 1.0,
                delta: true,
            };
        }
        let scale = if mode == TransportMode::Importance { 1.0 } else { fr.eta_ti * fr.eta_ti };
        BsdfSample {
            wi: refract(wo, fr.cos_theta_t, fr.eta_ti),
            weight: self.specular_transmittance * scale,
            pdf: 1.0 - fr.f,
            eta: fr.eta_it,
            delta: true,
        }
    }
}
