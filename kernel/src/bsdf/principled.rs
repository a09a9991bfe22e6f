//! Mitsuba 3.9.1's `principled`: Burley's "Disney" BSDF (2012, with 2015's transmission) as Mitsuba
//! writes it. Lobes: a diffuse base with retro-reflection, Hanrahan–Krueger "flatness" and sheen
//! (weight `(1 − metallic)(1 − spec_trans)`); a GGX specular reflection whose Fresnel term blends the
//! dielectric one, a Schlick metal tinted by `base_color` and a Schlick `spec_tint`; a GGX rough
//! refraction (weight `(1 − metallic)·spec_trans`, tinted by `√base_color` per crossing); and a GTR1
//! clearcoat. Seen from inside (`wo.z < 0`) only the untinted dielectric interface remains.
//!
//! Sampling picks diffuse, clearcoat, refraction or reflection with Mitsuba's probabilities (the
//! last two split by the dielectric Fresnel term of the sampled visible normal), and the weight is
//! `eval / pdf` of the whole mixture, as Mitsuba's. Where Mitsuba departs from Burley (a clearcoat
//! without the `1/(4 cos θi cos θo)` factor, the clearcoat's Schlick term switching on `eta < 1`),
//! this follows Mitsuba: the point is to render its scenes as it does.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::fresnel::{fresnel, reflect_about, refract_about};
use super::microfacet::Microfacet;
use super::{BsdfFlags, BsdfSample, Bxdf, EvalPdf, TransportMode};
use crate::glam::{Vec2, Vec3};
use crate::layout::{Material, NONE};
use crate::math::{safe_sqrt, sign, sqr, INV_PI, PI};
use crate::sampling::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::spectrum::{luminance, Rgb};

/// The scalar parameters, as the host stores them in a `Material` (`pack`; `from_material` reads them
/// back). `base_color` is `reflectance` (texturable), `roughness` and `anisotropic` are `alpha_u` and
/// `alpha_v` (texturable: their textures' luminance, as Mitsuba's `eval_1`), `metallic` is
/// `specular_reflectance` (texturable, its luminance) and `eta` is `eta`; the rest live in fields
/// this model has no other use for: `params`, `specular_transmittance` and `conductor_eta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledParams {
    pub spec_trans: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub clearcoat: f32,
    pub clearcoat_gloss: f32,
    pub flatness: f32,
    /// Mitsuba's `main_specular_sampling_rate`, `clearcoat_sampling_rate`,
    /// `diffuse_reflectance_sampling_rate`.
    pub spec_rate: f32,
    pub clearcoat_rate: f32,
    pub diffuse_rate: f32,
}

impl PrincipledParams {
    /// Stores the parameters in `m` (see the struct).
    pub fn pack(&self, m: &mut Material) {
        m.params = [self.spec_trans, self.spec_tint, self.sheen, self.sheen_tint];
        m.specular_transmittance = [self.clearcoat, self.clearcoat_gloss, self.flatness, 0.0];
        m.conductor_eta = [self.spec_rate, self.clearcoat_rate, self.diffuse_rate, 0.0];
    }

    pub fn unpack(m: &Material) -> Self {
        let (p, t, r) = (m.params, m.specular_transmittance, m.conductor_eta);
        PrincipledParams {
            spec_trans: p[0],
            spec_tint: p[1],
            sheen: p[2],
            sheen_tint: p[3],
            clearcoat: t[0],
            clearcoat_gloss: t[1],
            flatness: t[2],
            spec_rate: r[0],
            clearcoat_rate: r[1],
            diffuse_rate: r[2],
        }
    }
}

/// The relative index of refraction of Mitsuba's `specular` (its normal-incidence reflectance is
/// `0.08·specular`).
pub fn eta_from_specular(specular: f32) -> f32 {
    2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
}

/// Roughness of the main lobes from `roughness` and `anisotropic` (Burley's mapping, floored at 0.001).
pub fn alphas(roughness: f32, anisotropic: f32) -> (f32, f32) {
    let r2 = roughness * roughness;
    let aspect = safe_sqrt(1.0 - 0.9 * anisotropic);
    ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
}

#[derive(Clone, Copy)]
pub struct Principled {
    pub base_color: Rgb,
    pub roughness: f32,
    pub metallic: f32,
    pub eta: f32,
    pub p: PrincipledParams,
    /// The main reflection and refraction lobes' GGX distribution.
    pub distr: Microfacet,
}

/// `(1 − cos)⁵`, the Schlick weight (the cosine clamped to [0, 1]).
#[inline]
fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// The Schlick weight Mitsuba's principled Fresnel terms use at `cos_i` (against the facet, negative
/// inside) for relative index `eta`: of the incident cosine where the path enters a denser medium,
/// else of the refracted one (1 under total internal reflection).
#[inline]
pub(crate) fn schlick_weight_eta(cos_i: f32, eta: f32) -> f32 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    if eta_it > 1.0 {
        schlick_weight(cos_i.abs())
    } else {
        schlick_weight(safe_sqrt(1.0 - (1.0 - cos_i * cos_i) / (eta_it * eta_it)))
    }
}

/// Normal-incidence reflectance of index ratio `eta`.
#[inline]
pub(crate) fn r0_of_eta(eta: f32) -> f32 {
    sqr((eta - 1.0) / (eta + 1.0))
}

/// Burley's GTR1 (γ = 1) normal distribution of the clearcoat, roughness `alpha`.
#[derive(Clone, Copy)]
struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    fn d(&self, m: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z));
        if d * m.z > 1e-20 {
            d
        } else {
            0.0
        }
    }

    /// Density of `sample`: `D(m)·cos θm`.
    fn pdf(&self, m: Vec3) -> f32 {
        if m.z < 0.0 {
            0.0
        } else {
            m.z * self.d(m)
        }
    }

    fn sample(&self, u: Vec2) -> Vec3 {
        let phi = 2.0 * PI * u.x;
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin_theta = safe_sqrt(1.0 - cos2);
        Vec3::new(phi.cos() * sin_theta, phi.sin() * sin_theta, safe_sqrt(cos2))
    }
}

/// Smith's GGX `G1` of the clearcoat (isotropic `alpha`), zero where `v` sees the back of `m`.
fn smith_ggx1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let c2 = v.z * v.z;
    if c2 <= 0.0 {
        return 0.0;
    }
    let tan2 = (1.0 - c2) / c2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// Whether the facet `m` (upper hemisphere) is seen from the front by `wo` and (reflection) by `wi` or
/// (refraction) from behind by `wi`, with the facet turned to `wo`'s side of the surface.
#[inline]
fn compatible(m: Vec3, wo: Vec3, wi: Vec3, reflection: bool) -> bool {
    let m = m * sign(wo.z);
    wo.dot(m) > 0.0 && (if reflection { wi.dot(m) > 0.0 } else { wi.dot(m) < 0.0 })
}

/// Lobe-selection probabilities (normalised), given the dielectric Fresnel term `f` of the facet.
#[derive(Clone, Copy)]
struct LobeProbabilities {
    diffuse: f32,
    clearcoat: f32,
    transmission: f32,
    reflection: f32,
}

impl Principled {
    /// Weights of the diffuse base and of the refraction lobe.
    #[inline]
    fn weights(&self) -> (f32, f32) {
        let dielectric = 1.0 - self.metallic;
        (dielectric * (1.0 - self.p.spec_trans), dielectric * self.p.spec_trans)
    }

    fn clearcoat_distr(&self) -> Gtr1 {
        Gtr1 { alpha: 0.1 + (0.001 - 0.1) * self.p.clearcoat_gloss }
    }

    fn probabilities(&self, front: bool, f: f32) -> LobeProbabilities {
        let (brdf, bsdf) = self.weights();
        let (diffuse, clearcoat, transmission, reflection) = if front {
            let rate = self.p.spec_rate;
            (
                brdf * self.p.diffuse_rate,
                0.25 * self.p.clearcoat * self.p.clearcoat_rate,
                rate * bsdf * (1.0 - f),
                rate * (1.0 - bsdf * (1.0 - f)),
            )
        } else {
            (0.0, 0.0, 1.0 - f, f)
        };
        let total = diffuse + clearcoat + transmission + reflection;
        let inv = if total > 0.0 { 1.0 / total } else { 0.0 };
        LobeProbabilities {
            diffuse: diffuse * inv,
            clearcoat: clearcoat * inv,
            transmission: transmission * inv,
            reflection: reflection * inv,
        }
    }

    /// `base_color` over its luminance (white where it is black).
    #[inline]
    fn tint(&self) -> Rgb {
        tint_of(self.base_color)
    }

    /// The main reflection's Fresnel term on the front: the dielectric `f`, Schlick metal and tinted
    /// Schlick dielectric, blended by `metallic` and `spec_tint`.
    fn fresnel_front(&self, f: f32, cos_i: f32) -> Rgb {
        let w = schlick_weight_eta(cos_i, self.eta);
        let metal = self.base_color + (Rgb::ONE - self.base_color) * w;
        let eta_it = if cos_i >= 0.0 { self.eta } else { 1.0 / self.eta };
        let r0 = self.tint() * r0_of_eta(eta_it);
        let tinted = r0 + (Rgb::ONE - r0) * w;
        let dielectric = 1.0 - self.metallic;
        Rgb::splat(dielectric * (1.0 - self.p.spec_tint) * f)
            + metal * self.metallic
            + tinted * (dielectric * self.p.spec_tint)
    }

    /// Diffuse, retro-reflection, flatness and sheen: `f·cos θi` on the front.
    fn eval_base(&self, wo: Vec3, wi: Vec3, h: Vec3, brdf: f32) -> Rgb {
        // Sheen (Mitsuba's scalar_rgb) is weighted by (1 − metallic) alone, not by the transmission.
        let sheen_weight = if self.metallic < 1.0 { 1.0 - self.metallic } else { 0.0 };
        let p = &self.p;
        let (ci, co, cos_d) = (wo.z.abs(), wi.z.abs(), h.dot(wi));
        diffuse_base(
            self.base_color,
            self.roughness,
            p.flatness,
            p.sheen,
            p.sheen_tint,
            ci,
            co,
            cos_d,
            brdf,
            sheen_weight,
        )
    }
}

/// `base_color` over its luminance (white where it is black).
#[inline]
pub(crate) fn tint_of(base_color: Rgb) -> Rgb {
    let lum = luminance(base_color);
    if lum > 0.0 {
        base_color / lum
    } else {
        Rgb::ONE
    }
}

/// Burley's diffuse base, `f·cos θi`: diffuse with retro-reflection blended by `flatness` with the
/// Hanrahan–Krueger term (weight `weight`), and sheen (weight `sheen_weight`), for the cosines `ci`
/// (viewer), `co` (light) and `cos_d` (light against the half vector). `principled` and
/// `principledthin` share it.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn diffuse_base(
    base_color: Rgb,
    roughness: f32,
    flatness: f32,
    sheen: f32,
    sheen_tint: f32,
    ci: f32,
    co: f32,
    cos_d: f32,
    weight: f32,
    sheen_weight: f32,
) -> Rgb {
    let (f_i, f_o) = (schlick_weight(ci), schlick_weight(co));
    let f_diff = (1.0 - 0.5 * f_i) * (1.0 - 0.5 * f_o);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (f_o + f_i + f_o * f_i * (rr - 1.0));
    let fss90 = 0.5 * rr;
    let fss = (1.0 + (fss90 - 1.0) * f_o) * (1.0 + (fss90 - 1.0) * f_i);
    let f_ss = 1.25 * (fss * (1.0 / (co + ci) - 0.5) + 0.5);
    let mut value =
        base_color * (weight * co * INV_PI * ((f_diff + f_retro) * (1.0 - flatness) + f_ss * flatness));
    if sheen > 0.0 && sheen_weight > 0.0 {
        let sheen_color = Rgb::ONE + (tint_of(base_color) - Rgb::ONE) * sheen_tint;
        value += sheen_color * (sheen * sheen_weight * schlick_weight(cos_d.abs()) * co);
    }
    value
}

impl<'a> Bxdf<'a> for Principled {
    /// `reflectance` is the evaluated `base_color`, `specular` the evaluated `metallic` (a texture's
    /// luminance); the rest as `PrincipledParams` says.
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, _tables: &[f32]) -> Self {
        let metallic = if m.specular_texture != NONE { luminance(specular) } else { specular.x };
        let (ax, ay) = alphas(m.alpha_u, m.alpha_v);
        Principled {
            base_color: reflectance,
            roughness: m.alpha_u,
            metallic,
            eta: m.eta,
            p: PrincipledParams::unpack(m),
            distr: Microfacet::new(ax, ay, false),
        }
    }

    fn flags(&self) -> BsdfFlags {
        let t = if self.weights().1 > 0.0 { BsdfFlags::TRANSMISSION } else { 0 };
        BsdfFlags::of(BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE | BsdfFlags::GLOSSY | t)
    }

    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_pdf(wo, wi, mode).f
    }

    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        self.eval_pdf(wo, wi, mode).pdf
    }

    fn eval_pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> EvalPdf {
        let (brdf, bsdf) = self.weights();
        let front = wo.z > 0.0;
        // From inside only the refracting interface scatters: nothing without it (where Mitsuba's
        // `pdf` still reports the interface's reflection, which its `sample` never draws).
        if wo.z == 0.0 || (!front && bsdf <= 0.0) {
            return EvalPdf::ZERO;
        }
        let reflect = wo.z * wi.z > 0.0;
        let refract = wo.z * wi.z < 0.0;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let h = wo + wi * (if reflect { 1.0 } else { eta_path });
        let len2 = h.length_squared();
        if !(len2 > 0.0) {
            return EvalPdf::ZERO;
        }
        let h = h / len2.sqrt();
        let h = h * sign(h.z);
        let (wo_h, wi_h) = (wo.dot(h), wi.dot(h));
        let f = fresnel(wo_h, self.eta).f;
        let reflect_ok = reflect && compatible(h, wo, wi, true);
        let refract_ok = refract && compatible(h, wo, wi, false);
        let d = self.distr.d(h);
        let g = self.distr.g(wo, wi, h);

        let mut value = Rgb::ZERO;
        if reflect_ok && f > 0.0 {
            let fr = if front { self.fresnel_front(f, wo_h) } else { Rgb::splat(bsdf * f) };
            value += fr * (d * g / (4.0 * wo.z.abs()));
        }
        if refract_ok && bsdf > 0.0 && f < 1.0 {
            // Radiance is compressed into a smaller solid angle on the denser side.
            let scale = if mode == TransportMode::Radiance { 1.0 / (eta_path * eta_path) } else { 1.0 };
            let t = scale * (1.0 - f) * d * g * eta_path * eta_path * wo_h * wi_h
                / (wo.z * sqr(wo_h + eta_path * wi_h));
            let sqrt_base = Rgb::new(
                safe_sqrt(self.base_color.x),
                safe_sqrt(self.base_color.y),
                safe_sqrt(self.base_color.z),
            );
            value += sqrt_base * (bsdf * t.abs());
        }
        if reflect_ok && front && self.p.clearcoat > 0.0 {
            let f_cc = 0.04 + 0.96 * schlick_weight_eta(wo_h, self.eta);
            let d_cc = self.clearcoat_distr().d(h);
            let g_cc = smith_ggx1(wo, h, 0.25) * smith_ggx1(wi, h, 0.25);
            value += Rgb::splat(0.25 * self.p.clearcoat * f_cc * d_cc * g_cc * wi.z.abs());
        }
        if reflect && front && brdf > 0.0 {
            value += self.eval_base(wo, wi, h, brdf);
        }

        let prob = self.probabilities(front, f);
        let jacobian = if reflect {
            1.0 / (4.0 * wi_h)
        } else {
            eta_path * eta_path * wi_h / sqr(wo_h + eta_path * wi_h)
        }
        .abs();
        let mut pdf = 0.0;
        let visible = self.distr.pdf_with_d(d, wo * sign(wo.z), h);
        if reflect_ok {
            pdf += (prob.reflection * visible + prob.clearcoat * self.clearcoat_distr().pdf(h)) * jacobian;
        }
        if reflect {
            pdf += prob.diffuse * cosine_hemisphere_pdf(wi.z);
        }
        if refract_ok {
            pdf += prob.transmission * visible * jacobian;
        }
        EvalPdf { f: value, pdf }
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        let front = wo.z > 0.0;
        if wo.z == 0.0 || (!front && self.weights().1 <= 0.0) {
            return BsdfSample::invalid();
        }
        // On the front the diffuse and clearcoat probabilities do not depend on the facet's Fresnel
        // term (the two specular lobes share a fixed total), so the facet is drawn only when needed.
        let p = self.probabilities(front, 0.5);
        // The lobe's direction, its relative index, and whether it is valid for the lobe: on the
        // right side of the surface, and facing its facet as eval's facet tests require (Mitsuba
        // discards the others, which the pdf does not count).
        let (wi, eta, valid) = if u_lobe < p.diffuse {
            let wi = square_to_cosine_hemisphere(u);
            (wi, 1.0, wi.z > 0.0)
        } else if u_lobe < p.diffuse + p.clearcoat {
            let m = self.clearcoat_distr().sample(u);
            let wi = reflect_about(wo, m);
            (wi, 1.0, wo.z * wi.z > 0.0 && compatible(m, wo, wi, true))
        } else {
            let ms = self.distr.sample(wo * sign(wo.z), u);
            if ms.pdf <= 0.0 {
                return BsdfSample::invalid();
            }
            let m = ms.m;
            let fr = fresnel(wo.dot(m), self.eta);
            let p = self.probabilities(front, fr.f);
            if u_lobe < p.diffuse + p.clearcoat + p.transmission {
                let wi = refract_about(wo, m, fr.cos_theta_t, fr.eta_ti);
                (wi, fr.eta_it, wo.z * wi.z < 0.0 && compatible(m, wo, wi, false))
            } else {
                let wi = reflect_about(wo, m);
                (wi, 1.0, wo.z * wi.z > 0.0 && compatible(m, wo, wi, true))
            }
        };
        if !valid {
            return BsdfSample::invalid();
        }
        let e = self.eval_pdf(wo, wi, mode);
        if !(e.pdf > 0.0) {
            return BsdfSample::invalid();
        }
        BsdfSample { wi, weight: e.f / e.pdf, pdf: e.pdf, eta, delta: false }
    }
}
