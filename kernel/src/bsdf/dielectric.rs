//! Smooth dielectric interface (Mitsuba `dielectric`): Fresnel-weighted choice between the mirror and
//! the refracted direction, both Dirac deltas. `wo.z < 0` means the viewer is inside, where the
//! relative IOR is inverted. Transmitted radiance is scaled by `1/η²` (solid-angle compression) in
//! radiance transport only, as Mitsuba does.
use super::fresnel::{fresnel, reflect, refract};
use super::BsdfSample;
use crate::glam::{Vec2, Vec3};
use crate::math::vec3;
use crate::layout::Material;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct Dielectric {
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub specular_reflectance: Rgb,
    pub specular_transmittance: Rgb,
    /// Importance transport: no `1/η²` on refraction.
    pub adjoint: bool,
}

impl Dielectric {
    /// Reads `eta` and `specular_transmittance`; `specular` is the evaluated `specular_reflectance`.
    pub fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let t = vec3([m.specular_transmittance[0], m.specular_transmittance[1], m.specular_transmittance[2]]);
        Dielectric { eta: m.eta, specular_reflectance: specular, specular_transmittance: t, adjoint: false }
    }

    /// Both lobes are Dirac deltas.
    pub fn eval(&self, _wo: Vec3, _wi: Vec3) -> Rgb {
        Rgb::ZERO
    }

    pub fn pdf(&self, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    /// Reflects with probability F, refracts otherwise, so that the Fresnel factor cancels in the weight.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, _u: Vec2) -> BsdfSample {
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
        let scale = if self.adjoint { 1.0 } else { fr.eta_ti * fr.eta_ti };
        BsdfSample {
            wi: refract(wo, fr.cos_theta_t, fr.eta_ti),
            weight: self.specular_transmittance * scale,
            pdf: 1.0 - fr.f,
            eta: fr.eta_it,
            delta: true,
        }
    }
}
