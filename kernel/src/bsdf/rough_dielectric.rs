//! Rough dielectric interface (Mitsuba `roughdielectric`): Walter et al. 2007's microfacet reflection
//! and refraction, Beckmann or GGX, anisotropic, sampled through visible normals with the lobe chosen
//! by the facet's Fresnel term. `wo.z < 0` means the viewer is inside (relative IOR inverted).
//! Transmission carries the `1/η²` of radiance transport in radiance transport only (`TransportMode`).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::fresnel::{fresnel, reflect_about, refract_about};
use super::microfacet::Microfacet;
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::{sign, sqr, vec3};
use crate::spectrum::Rgb;

#[derive(Clone, Copy)]
pub struct RoughDielectric {
    pub distr: Microfacet,
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub specular_reflectance: Rgb,
    pub specular_transmittance: Rgb,
}

/// The microfacet normal that relates `wo` and `wi`, oriented to the outside, with the relative IOR
/// (`wi`'s side over `wo`'s) of a refraction; `reflect` tells the two configurations apart.
#[derive(Clone, Copy)]
struct HalfVector {
    m: Vec3,
    reflect: bool,
    /// Relative IOR seen from `wo`'s side (`η` outside, `1/η` inside).
    eta: f32,
    valid: bool,
}

impl RoughDielectric {
    /// Generalised half vector `wo + η·wi` (η = 1 for reflection), flipped to the upper hemisphere.
    fn half_vector(&self, wo: Vec3, wi: Vec3) -> HalfVector {
        let reflect = wo.z * wi.z > 0.0;
        let eta = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let h = wo + wi * (if reflect { 1.0 } else { eta });
        let len2 = h.length_squared();
        if len2 <= 0.0 {
            return HalfVector { m: Vec3::Z, reflect, eta, valid: false };
        }
        let m = h / len2.sqrt();
        let m = if m.z < 0.0 { -m } else { m };
        HalfVector { m, reflect, eta, valid: true }
    }

    /// `|d wh / d wi|`: the Jacobian from the facet normal to the scattered direction.
    #[inline]
    fn jacobian(reflect: bool, eta: f32, wo_m: f32, wi_m: f32) -> f32 {
        if reflect {
            1.0 / (4.0 * wi_m).abs()
        } else {
            (eta * eta * wi_m / sqr(wo_m + eta * wi_m)).abs()
        }
    }
}

impl<'a> Bxdf<'a> for RoughDielectric {
    /// Reads `alpha_u`, `alpha_v`, `flags & MATERIAL_BECKMANN`, `eta`, `specular_transmittance`;
    /// `specular` is the evaluated `specular_reflectance`.
    fn from_material(m: &Material, _reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let t = vec3([m.specular_transmittance[0], m.specular_transmittance[1], m.specular_transmittance[2]]);
        RoughDielectric {
            distr: Microfacet::from_material(m),
            eta: m.eta,
            specular_reflectance: specular,
            specular_transmittance: t,
        }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::TRANSMISSION | BsdfFlags::GLOSSY)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    /// Value and density share the half vector, `D` and the facet's Fresnel term.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> EvalPdf {
        if wo.z == 0.0 {
            return EvalPdf::ZERO;
        }
        let hv = self.half_vector(wo, wi);
        if !hv.valid {
            return EvalPdf::ZERO;
        }
        let m = hv.m;
        let (wo_m, wi_m) = (wo.dot(m), wi.dot(m));
        let d = self.distr.d(m);
        let g = self.distr.g(wo, wi, m);
        let fresnel = fresnel(wo_m, self.eta).f;
        let f = if d == 0.0 || g == 0.0 {
            Rgb::ZERO
        } else if hv.reflect {
            self.specular_reflectance * (fresnel * d * g / (4.0 * wo.z.abs()))
        } else {
            // Radiance is compressed into a smaller solid angle on the denser side.
            let scale = if mode == TransportMode::Importance { 1.0 } else { 1.0 / (hv.eta * hv.eta) };
            let value = scale * (1.0 - fresnel) * d * g * hv.eta * hv.eta * wo_m * wi_m
                / (wo.z * sqr(wo_m + hv.eta * wi_m));
            self.specular_transmittance * value.abs()
        };
        // Facets seen from the wrong side have no density (the same test G1 makes in eval and sample).
        let pdf = if wo_m * wo.z <= 0.0 || wi_m * wi.z <= 0.0 {
            0.0
        } else {
            let lobe = if hv.reflect { fresnel } else { 1.0 - fresnel };
            self.distr.pdf_with_d(d, wo * sign(wo.z), m)
                * lobe
                * Self::jacobian(hv.reflect, hv.eta, wo_m, wi_m)
        };
        EvalPdf { f, pdf }
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z == 0.0 {
            return BsdfSample::invalid();
        }
        // Visible normals are sampled as seen from the viewer's side, mirrored to the top.
        let ms = self.distr.sample(wo * sign(wo.z), u);
        if ms.pdf <= 0.0 {
            return BsdfSample::invalid();
        }
        let m = ms.m;
        let fr = fresnel(wo.dot(m), self.eta);
        let reflect = u_lobe < fr.f;
        let (wi, weight, lobe, eta) = if reflect {
            (reflect_about(wo, m), self.specular_reflectance, fr.f, 1.0)
        } else {
            let scale = if mode == TransportMode::Importance { 1.0 } else { fr.eta_ti * fr.eta_ti };
            (
                refract_about(wo, m, fr.cos_theta_t, fr.eta_ti),
                self.specular_transmittance * scale,
                1.0 - fr.f,
                fr.eta_it,
            )
        };
        // A scattered direction on the wrong side of the macrosurface (G1 = 0) ends the path, as in
        // Mitsuba where it carries zero weight.
        let g1 = self.distr.smith_g1(wi, m);
        if g1 <= 0.0 || lobe <= 0.0 {
            return BsdfSample::invalid();
        }
        let pdf = ms.pdf * lobe * Self::jacobian(reflect, eta, wo.dot(m), wi.dot(m));
        BsdfSample { wi, weight: weight * g1, pdf, eta, delta: false }
    }
}
