//! Mitsuba 3.9.1's `principledthin`: Burley's 2015 thin-surface BSDF as Mitsuba writes it. A sheet
//! with no inside: both sides scatter alike (directions are mirrored to the viewer's side first), and
//! light passes through without bending (`eta` of the sample is 1). Lobes: a GGX reflection (weight
//! `spec_trans`, Fresnel of the dielectric `eta`, tinted by `spec_tint` as `principled`'s), a GGX
//! "refraction" that mirrors the reflected direction through the sheet (weight `spec_trans`, tinted by
//! `base_color`, roughness scaled by `0.65·eta − 0.35`), `principled`'s diffuse base with
//! retro-reflection, flatness and sheen (weight `(1 − spec_trans)(1 − diff_trans/2)`), and a Lambertian
//! transmission (weight `(1 − spec_trans)·diff_trans/2`). Sampling picks one of the four with Mitsuba's
//! probabilities (each scaled by its sampling rate), and the weight is `eval / pdf` of the whole.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::fresnel::{fresnel, reflect_about};
use super::microfacet::Microfacet;
use super::principled::{alphas, diffuse_base, r0_of_eta, schlick_weight_eta, tint_of};
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::Material;
use crate::math::{sign, INV_PI};
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::Rgb;

/// The scalar parameters, as the host stores them in a `Material` (`pack`; `from_material` reads them
/// back). `base_color` is `reflectance` (texturable), `roughness` and `anisotropic` are `alpha_u` and
/// `alpha_v` (texturable: their luminance), `eta` is `eta`; the rest live in `params`,
/// `specular_transmittance` and `conductor_eta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinParams {
    pub spec_trans: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub flatness: f32,
    /// Mitsuba's `diff_trans` in [0, 2], stored as given (the model halves it, as Mitsuba).
    pub diff_trans: f32,
    /// Mitsuba's `specular_reflectance_sampling_rate`, `specular_transmittance_sampling_rate`,
    /// `diffuse_reflectance_sampling_rate`, `diffuse_transmittance_sampling_rate`.
    pub spec_refl_rate: f32,
    pub spec_trans_rate: f32,
    pub diff_refl_rate: f32,
    pub diff_trans_rate: f32,
}

impl ThinParams {
    pub fn pack(&self, m: &mut Material) {
        m.params = [self.spec_trans, self.spec_tint, self.sheen, self.sheen_tint];
        m.specular_transmittance = [self.flatness, self.diff_trans, 0.0, 0.0];
        m.conductor_eta =
            [self.spec_refl_rate, self.spec_trans_rate, self.diff_refl_rate, self.diff_trans_rate];
    }

    pub fn unpack(m: &Material) -> Self {
        let (p, t, r) = (m.params, m.specular_transmittance, m.conductor_eta);
        ThinParams {
            spec_trans: p[0],
            spec_tint: p[1],
            sheen: p[2],
            sheen_tint: p[3],
            flatness: t[0],
            diff_trans: t[1],
            spec_refl_rate: r[0],
            spec_trans_rate: r[1],
            diff_refl_rate: r[2],
            diff_trans_rate: r[3],
        }
    }
}

#[derive(Clone, Copy)]
pub struct PrincipledThin {
    pub base_color: Rgb,
    pub roughness: f32,
    pub eta: f32,
    pub p: ThinParams,
    /// The reflection lobe's GGX distribution, and the transmission's (roughness scaled by `eta`).
    pub reflect_distr: Microfacet,
    pub trans_distr: Microfacet,
}

/// Normalised lobe-selection probabilities: specular reflection, specular transmission, diffuse
/// reflection, diffuse transmission.
#[derive(Clone, Copy)]
struct Probabilities {
    spec_reflect: f32,
    spec_trans: f32,
    diff_reflect: f32,
    diff_trans: f32,
}

impl PrincipledThin {
    /// `diff_trans` in [0, 1], as the model uses it.
    #[inline]
    fn diff_trans(&self) -> f32 {
        0.5 * self.p.diff_trans
    }

    fn probabilities(&self) -> Probabilities {
        let (st, dt) = (self.p.spec_trans, self.diff_trans());
        let spec_reflect = 0.5 * st * self.p.spec_refl_rate;
        let spec_trans = 0.5 * st * self.p.spec_trans_rate;
        let diff_reflect = self.p.diff_refl_rate * (1.0 - st) * (1.0 - dt);
        let diff_trans = self.p.diff_trans_rate * (1.0 - st) * dt;
        let total = spec_reflect + spec_trans + diff_reflect + diff_trans;
        let inv = if total > 0.0 { 1.0 / total } else { 0.0 };
        Probabilities {
            spec_reflect: spec_reflect * inv,
            spec_trans: spec_trans * inv,
            diff_reflect: diff_reflect * inv,
            diff_trans: diff_trans * inv,
        }
    }

    /// The reflection's Fresnel term: the dielectric `f` blended by `spec_tint` with a Schlick term
    /// of `base_color`'s tint (`cos_h` against the half vector, on the viewer's side).
    fn fresnel_thin(&self, f: f32, cos_h: f32) -> Rgb {
        let r0 = tint_of(self.base_color) * r0_of_eta(self.eta);
        let schlick = r0 + (Rgb::ONE - r0) * schlick_weight_eta(cos_h, self.eta);
        Rgb::splat(f * (1.0 - self.p.spec_tint)) + schlick * self.p.spec_tint
    }

    /// `wo`, `wi` mirrored so that `wo` is on the front, and the half vector of `wo` and `wi` turned
    /// up (`None` when there is none).
    #[inline]
    fn frame(wo: Vec3, wi: Vec3) -> (Vec3, Vec3, Vec3, bool) {
        let s = sign(wo.z);
        let (wo, wi) = (wo * s, wi * s);
        let h = wo + Vec3::new(wi.x, wi.y, wi.z.abs());
        let len2 = h.length_squared();
        (wo, wi, if len2 > 0.0 { h / len2.sqrt() } else { Vec3::Z }, len2 > 0.0)
    }
}

impl<'a> Bxdf<'a> for PrincipledThin {
    /// `reflectance` is the evaluated `base_color`; the rest as `ThinParams` says.
    fn from_material(m: &Material, reflectance: Rgb, _specular: Rgb, _tables: &[f32]) -> Self {
        let (ax, ay) = alphas(m.alpha_u, m.alpha_v);
        let scaled = (0.65 * m.eta - 0.35) * m.alpha_u;
        let (tx, ty) = alphas(scaled, m.alpha_v);
        PrincipledThin {
            base_color: reflectance,
            roughness: m.alpha_u,
            eta: m.eta,
            p: ThinParams::unpack(m),
            reflect_distr: Microfacet::new(ax, ay, false),
            trans_distr: Microfacet::new(tx, ty, false),
        }
    }

    fn flags(&self) -> BsdfFlags {
        let t = if self.p.spec_trans > 0.0 || self.p.diff_trans > 0.0 { BsdfFlags::TRANSMISSION } else { 0 };
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE | BsdfFlags::GLOSSY | t)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    /// The same in both transport modes: nothing bends.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> EvalPdf {
        if wo.z == 0.0 {
            return EvalPdf::ZERO;
        }
        let (wo, wi, h, has_h) = Self::frame(wo, wi);
        let (ci, co) = (wo.z, wi.z);
        let (reflect, refract) = (co > 0.0, co < 0.0);
        let (st, dt) = (self.p.spec_trans, self.diff_trans());
        // The facet faces the viewer and (reflection) the light, or (transmission) turns its back on it.
        let facing = has_h && wo.dot(h) > 0.0;
        let spec_reflect = facing && reflect && wi.dot(h) > 0.0;
        let spec_trans = facing && refract && wi.dot(h) < 0.0;

        let mut value = Rgb::ZERO;
        let f = fresnel(wo.dot(h), self.eta).f;
        if spec_reflect && st > 0.0 {
            let d = &self.reflect_distr;
            value += self.fresnel_thin(f, wo.dot(h)) * (st * d.d(h) * d.g(wo, wi, h) / (4.0 * ci));
        }
        if spec_trans && st > 0.0 {
            let d = &self.trans_distr;
            value += self.base_color * (st * (1.0 - f) * d.d(h) * d.g(wo, wi, h) / (4.0 * ci));
        }
        if reflect && st < 1.0 && dt < 1.0 {
            let weight = (1.0 - st) * (1.0 - dt);
            value += diffuse_base(
                self.base_color,
                self.roughness,
                self.p.flatness,
                self.p.sheen,
                self.p.sheen_tint,
                ci,
                co,
                h.dot(wi),
                weight,
                weight,
            );
        }
        if refract && st < 1.0 && dt > 0.0 {
            value += self.base_color * ((1.0 - st) * dt * INV_PI * co.abs());
        }

        let prob = self.probabilities();
        let mut pdf = 0.0;
        if spec_reflect || spec_trans {
            // Both lobes draw the facet of the mirrored direction `(wi.x, wi.y, |wi.z|)`.
            let jacobian = (1.0 / (4.0 * Vec3::new(wi.x, wi.y, wi.z.abs()).dot(h))).abs();
            if spec_reflect {
                pdf += prob.spec_reflect * self.reflect_distr.pdf(wo, h) * jacobian;
            } else {
                pdf += prob.spec_trans * self.trans_distr.pdf(wo, h) * jacobian;
            }
        }
        if reflect {
            pdf += prob.diff_reflect * cosine_hemisphere_pdf(co);
        }
        if refract {
            pdf += prob.diff_trans * cosine_hemisphere_pdf(-co);
        }
        EvalPdf { f: value, pdf }
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if wo.z == 0.0 {
            return BsdfSample::invalid();
        }
        let s = sign(wo.z);
        let wo_f = wo * s;
        let p = self.probabilities();
        let (wi, valid) = if u_lobe < p.spec_reflect + p.spec_trans {
            let reflection = u_lobe < p.spec_reflect;
            let distr = if reflection { self.reflect_distr } else { self.trans_distr };
            let ms = distr.sample(wo_f, u);
            let mut wi = reflect_about(wo_f, ms.m);
            if !reflection {
                wi.z = -wi.z;
            }
            let facing = wo_f.dot(ms.m) > 0.0;
            let ok =
                if reflection { wi.dot(ms.m) > 0.0 && wi.z > 0.0 } else { wi.dot(ms.m) < 0.0 && wi.z < 0.0 };
            (wi, ms.pdf > 0.0 && facing && ok)
        } else if u_lobe < p.spec_reflect + p.spec_trans + p.diff_reflect {
            (square_to_cosine_hemisphere(u), true)
        } else {
            (-square_to_cosine_hemisphere(u), true)
        };
        if !valid {
            return BsdfSample::invalid();
        }
        let wi = wi * s;
        let e = self.eval_pdf(wo, wi, mode);
        if !(e.pdf > 0.0) {
            return BsdfSample::invalid();
        }
        BsdfSample { wi, weight: e.f / e.pdf, pdf: e.pdf, eta: 1.0, delta: false }
    }
}
