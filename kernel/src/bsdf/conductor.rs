//! Smooth conductor (Mitsuba `conductor`): a perfect mirror whose reflectance is the exact conductor
//! Fresnel term of the complex IOR `eta + i·k`, per channel, times `specular_reflectance`.
//! One-sided: light arriving from below is absorbed.
use super::fresnel::{fresnel_conductor_rgb, reflect};
use super::{BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::vec3;
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct Conductor {
    pub eta: Rgb,
    pub k: Rgb,
    pub specular: Rgb,
}

impl<'a> Bxdf<'a> for Conductor {
    /// Reads `conductor_eta`, `conductor_k`; `specular` is the evaluated `specular_reflectance`.
    fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let eta = vec3([m.conductor_eta[0], m.conductor_eta[1], m.conductor_eta[2]]);
        let k = vec3([m.conductor_k[0], m.conductor_k[1], m.conductor_k[2]]);
        Conductor { eta, k, specular }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::SPECULAR)
    }

    /// The mirror lobe is a Dirac delta: nothing to evaluate for a given pair of directions.
    fn eval(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> Rgb {
        Rgb::ZERO
    }

    fn pdf(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> f32 {
        0.0
    }

    fn sample(&self, wo: Vec3, _u_lobe: f32, _u: Vec2, _mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let weight = self.specular * fresnel_conductor_rgb(wo.z, self.eta, self.k);
        BsdfSample { wi: reflect(wo), weight, pdf: 1.0, eta: 1.0, delta: true }
    }
}
