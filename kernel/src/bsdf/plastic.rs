//! Smooth plastic (Mitsuba `plastic`): a diffuse base under a smooth dielectric coating. The coating
//! mirrors `F(θo)` (a Dirac delta); the rest enters, scatters diffusely with the internal
//! inter-reflections summed in closed form (internal diffuse Fresnel reflectance `Fdr`), and leaves
//! through `1 - F(θi)`, compressed by `1/η²`. One-sided.
use super::fresnel::{fresnel, reflect};
use super::{BsdfFlags, BsdfSample, Bxdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::{Material, MATERIAL_NONLINEAR};
use crate::math::INV_PI;
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::Rgb;

/// `params` slots filled by `precompute`.
pub const PARAM_FDR_INT: usize = 0;
pub const PARAM_SPECULAR_WEIGHT: usize = 1;

#[derive(Clone, Copy)]
pub struct Plastic {
    /// Interior over exterior index of refraction.
    pub eta: f32,
    pub diffuse: Rgb,
    pub specular: Rgb,
    /// Diffuse Fresnel reflectance of the coating seen from inside.
    pub fdr_int: f32,
    /// Prior weight of the specular lobe in lobe selection (Mitsuba's `specular_sampling_weight`).
    pub specular_weight: f32,
    /// Account for the colour shift of repeated internal scattering (Mitsuba's `nonlinear`).
    pub nonlinear: bool,
}

/// Fills `params[PARAM_FDR_INT]` and `params[PARAM_SPECULAR_WEIGHT]` from `eta`, `reflectance` and
/// `specular_reflectance` (constant values: texture means are the host's fallback there).
#[cfg(not(target_arch = "spirv"))]
pub fn precompute(m: &mut Material) {
    m.params[PARAM_FDR_INT] = super::fresnel::fresnel_diffuse_reflectance(1.0 / m.eta);
    m.params[PARAM_SPECULAR_WEIGHT] = specular_sampling_weight(m.reflectance, m.specular_reflectance);
}

/// Mitsuba's lobe prior: mean specular over mean diffuse plus mean specular (channel means).
#[cfg(not(target_arch = "spirv"))]
pub fn specular_sampling_weight(diffuse: [f32; 4], specular: [f32; 4]) -> f32 {
    let d = (diffuse[0] + diffuse[1] + diffuse[2]) / 3.0;
    let s = (specular[0] + specular[1] + specular[2]) / 3.0;
    // A black material scatters nothing; any weight will do, but not 0/0.
    if d + s > 0.0 {
        s / (d + s)
    } else {
        0.5
    }
}

impl Plastic {
    /// Probability of choosing the mirror lobe when viewed at `cos_theta_o` with reflectance `f_o`.
    #[inline]
    fn specular_probability(&self, f_o: f32) -> f32 {
        let ps = f_o * self.specular_weight;
        let pd = (1.0 - f_o) * (1.0 - self.specular_weight);
        if ps + pd > 0.0 {
            ps / (ps + pd)
        } else {
            0.0
        }
    }

    /// The diffuse base's albedo after the internal inter-reflections, scaled by the `1/η²` of leaving.
    #[inline]
    fn diffuse_term(&self) -> Rgb {
        let denom = if self.nonlinear {
            Rgb::ONE - self.diffuse * self.fdr_int
        } else {
            Rgb::splat(1.0 - self.fdr_int)
        };
        self.diffuse / denom / (self.eta * self.eta)
    }
}

impl<'a> Bxdf<'a> for Plastic {
    /// Reads `eta`, `flags & MATERIAL_NONLINEAR` and `params` (see `precompute`); `reflectance` and
    /// `specular` are the evaluated diffuse and specular reflectances.
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        Plastic {
            eta: m.eta,
            diffuse: reflectance,
            specular,
            fdr_int: m.params[PARAM_FDR_INT],
            specular_weight: m.params[PARAM_SPECULAR_WEIGHT],
            nonlinear: m.flags & MATERIAL_NONLINEAR != 0,
        }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE | BsdfFlags::SPECULAR)
    }

    /// The diffuse lobe only; the mirror is a Dirac delta.
    fn eval(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let f_o = fresnel(wo.z, self.eta).f;
        let f_i = fresnel(wi.z, self.eta).f;
        self.diffuse_term() * ((1.0 - f_o) * (1.0 - f_i) * wi.z * INV_PI)
    }

    /// Density of the diffuse lobe (times its selection probability).
    fn pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let ps = self.specular_probability(fresnel(wo.z, self.eta).f);
        (1.0 - ps) * cosine_hemisphere_pdf(wi.z)
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, _mode: TransportMode) -> BsdfSample {
        if wo.z <= 0.0 {
            return BsdfSample::invalid();
        }
        let f_o = fresnel(wo.z, self.eta).f;
        let ps = self.specular_probability(f_o);
        if u_lobe < ps {
            let weight = self.specular * (f_o / ps);
            return BsdfSample { wi: reflect(wo), weight, pdf: ps, eta: 1.0, delta: true };
        }
        let wi = square_to_cosine_hemisphere(u);
        let pdf = (1.0 - ps) * cosine_hemisphere_pdf(wi.z);
        if pdf <= 0.0 {
            return BsdfSample::invalid();
        }
        let f_i = fresnel(wi.z, self.eta).f;
        let weight = self.diffuse_term() * ((1.0 - f_o) * (1.0 - f_i) / (1.0 - ps));
        BsdfSample { wi, weight, pdf, eta: 1.0, delta: false }
    }
}
