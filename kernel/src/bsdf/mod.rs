//! BSDFs: the `Bxdf` interface every model implements (one model per file) and `Bsdf`, which picks a
//! material's model. Every model works in the local shading frame (normal = +z) with `wo` pointing
//! towards the viewer (or the previous vertex) and `wi` towards the light; `eval` includes the cosine
//! factor `|cos θi|` so that sampling weights are `eval / pdf`.
pub mod conductor;
pub mod dielectric;
pub mod diffuse;
pub mod fresnel;
pub mod fuzzy_metal;
pub mod microfacet;
pub mod perturb;
pub mod phong;
pub mod plastic;
pub mod principled;
pub mod rough_conductor;
pub mod rough_dielectric;
pub mod rough_plastic;
pub mod thin_dielectric;

use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::*;
use crate::spectrum::{luminance, Rgb};
use crate::texture;

/// Which quantity a path carries (pbrt-v4's `TransportMode`): radiance, traced from the camera, or
/// importance, traced from the lights. Scattering that is not reciprocal depends on it: refraction
/// scales radiance by `1/η²` but not importance, and a BSDF whose `f·cos` is symmetric but `f` is not
/// (fuzzy metal) swaps the cosine. Light tracing passes `Importance`; everything else `Radiance`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum TransportMode {
    Radiance,
    Importance,
}

/// What kinds of lobes a model has (pbrt-v4's `BxDFFlags`): integrators ask it, never the model's
/// kind, whether light sampling can contribute (`has_smooth`) or a vertex can be connected at all.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct BsdfFlags(pub u32);

impl BsdfFlags {
    pub const REFLECTION: u32 = 1;
    pub const TRANSMISSION: u32 = 2;
    pub const DIFFUSE: u32 = 4;
    pub const GLOSSY: u32 = 8;
    /// Dirac-delta lobes: `eval` and `pdf` are zero for them, only `sample` finds them.
    pub const SPECULAR: u32 = 16;

    #[inline]
    pub const fn of(bits: u32) -> Self {
        BsdfFlags(bits)
    }

    /// A lobe that `eval` and `pdf` see (diffuse or glossy): next-event estimation and connections
    /// to the camera can contribute.
    #[inline]
    pub fn has_smooth(self) -> bool {
        self.0 & (Self::DIFFUSE | Self::GLOSSY) != 0
    }

    #[inline]
    pub fn has_specular(self) -> bool {
        self.0 & Self::SPECULAR != 0
    }

    #[inline]
    pub fn has_transmission(self) -> bool {
        self.0 & Self::TRANSMISSION != 0
    }
}

/// A sampled direction with its weight `f·cos/pdf` and solid-angle density.
#[derive(Clone, Copy)]
pub struct BsdfSample {
    pub wi: Vec3,
    pub weight: Rgb,
    pub pdf: f32,
    /// Relative index of refraction across the sampled interface (1 for reflection); Russian
    /// roulette divides it out as Mitsuba does.
    pub eta: f32,
    /// The sampled lobe is a Dirac delta (mirror or refraction): its `pdf` is a discrete
    /// probability, emitters it hits are not weighted against light sampling.
    pub delta: bool,
}

impl BsdfSample {
    pub fn invalid() -> Self {
        BsdfSample { wi: Vec3::Z, weight: Rgb::ZERO, pdf: 0.0, eta: 1.0, delta: false }
    }
}

/// `eval` and `pdf` of one direction pair, from one evaluation (Mitsuba's `eval_pdf`).
#[derive(Clone, Copy)]
pub struct EvalPdf {
    /// `f·|cos θi|`.
    pub f: Rgb,
    pub pdf: f32,
}

impl EvalPdf {
    pub const ZERO: EvalPdf = EvalPdf { f: Rgb::ZERO, pdf: 0.0 };
}

/// One scattering model: what every file in this folder implements. Directions are in the local
/// shading frame (normal +z), `wo` towards the viewer (the previous vertex), `wi` towards the light
/// (the next vertex) whatever the transport mode, as in pbrt-v4. Static dispatch only (rust-gpu has no
/// trait objects): `Bsdf` picks the model by the material's kind.
pub trait Bxdf<'a>: Sized {
    /// The model of a material record whose textured colours are already evaluated: `reflectance` and
    /// `specular` replace the record's `reflectance` and `specular_reflectance`; `tables` holds the
    /// precomputed data some models read (`Material::table`).
    fn from_material(m: &Material, reflectance: Rgb, specular: Rgb, tables: &'a [f32]) -> Self;
    fn flags(&self) -> BsdfFlags;
    /// `f(wo, wi)·|cos θi|` (zero for Dirac lobes).
    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb;
    /// Solid-angle density with which `sample` produces `wi` (zero for Dirac lobes).
    fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32;
    /// Both at once; models override it where the two share work (half vector, `D`, Fresnel).
    fn eval_pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> EvalPdf {
        EvalPdf { f: self.eval(wo, wi, mode), pdf: self.pdf(wo, wi, mode) }
    }
    /// `u_lobe` picks a lobe of multi-lobe models; `u` warps to a direction.
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample;
}

/// Builds the model of `$bsdf`'s record kind as `$model` and evaluates `$body` with it: the one `match`
/// over models. Lambert is the fallback kind. Each arm is guarded by its feature bit, so a specialised
/// kernel keeps only the scene's models. (Measured on the H100 in one run against testing the bit
/// inside each arm, which keeps a ten-way switch: +3–11% on five of six material previews and the
/// Cornell box, −4% on the diamond; BENCHMARKS.md.)
macro_rules! with_model {
    ($bsdf:expr, |$model:ident| $body:expr) => {{
        let b = $bsdf;
        let (m, r, s, t) = (&b.material, b.reflectance, b.specular, b.tables);
        match m.kind {
            BSDF_PHONG if b.uses(BSDF_PHONG) => {
                let $model = phong::Phong::from_material(m, r, s, t);
                $body
            }
            BSDF_CONDUCTOR if b.uses(BSDF_CONDUCTOR) => {
                let $model = conductor::Conductor::from_material(m, r, s, t);
                $body
            }
            BSDF_ROUGH_CONDUCTOR if b.uses(BSDF_ROUGH_CONDUCTOR) => {
                let $model = rough_conductor::RoughConductor::from_material(m, r, s, t);
                $body
            }
            BSDF_DIELECTRIC if b.uses(BSDF_DIELECTRIC) => {
                let $model = dielectric::Dielectric::from_material(m, r, s, t);
                $body
            }
            BSDF_THIN_DIELECTRIC if b.uses(BSDF_THIN_DIELECTRIC) => {
                let $model = thin_dielectric::ThinDielectric::from_material(m, r, s, t);
                $body
            }
            BSDF_ROUGH_DIELECTRIC if b.uses(BSDF_ROUGH_DIELECTRIC) => {
                let $model = rough_dielectric::RoughDielectric::from_material(m, r, s, t);
                $body
            }
            BSDF_PLASTIC if b.uses(BSDF_PLASTIC) => {
                let $model = plastic::Plastic::from_material(m, r, s, t);
                $body
            }
            BSDF_ROUGH_PLASTIC if b.uses(BSDF_ROUGH_PLASTIC) => {
                let $model = rough_plastic::RoughPlastic::from_material(m, r, s, t);
                $body
            }
            BSDF_FUZZY_METAL if b.uses(BSDF_FUZZY_METAL) => {
                let $model = fuzzy_metal::FuzzyMetal::from_material(m, r, s, t);
                $body
            }
            BSDF_PRINCIPLED if b.uses(BSDF_PRINCIPLED) => {
                let $model = principled::Principled::from_material(m, r, s, t);
                $body
            }
            _ => {
                let $model = diffuse::Diffuse::from_material(m, r, s, t);
                $body
            }
        }
    }};
}

/// A surface's BSDF: the material record with its textures evaluated at the hit; each call builds the
/// record's model and forwards to it. (The models are built per call from the record rather than held
/// in a data-carrying enum: rust-gpu 0.11 cannot cast between variants of different layouts.)
#[derive(Clone, Copy)]
pub struct Bsdf<'a> {
    pub material: Material,
    /// `reflectance` and `specular_reflectance` after texture lookup.
    pub reflectance: Rgb,
    pub specular: Rgb,
    /// Precomputed tables some models read (rough plastic).
    pub tables: &'a [f32],
    /// The scene's `features`: models it does not use are never dispatched to.
    pub features: u32,
    /// Normal or bump mapping: where active, the model is evaluated in its tilted frame
    /// (`perturb::shading_frame` makes it).
    pub perturbation: perturb::Perturbation,
}

impl<'a> Bsdf<'a> {
    /// The BSDF of `m` at texture coordinates `uv` in a scene using `features`, tilted by
    /// `perturbation` (`Perturbation::NONE` without a map).
    pub fn new(
        m: &Material,
        textures: &[Texture],
        tables: &'a [f32],
        uv: Vec2,
        features: u32,
        perturbation: perturb::Perturbation,
    ) -> Bsdf<'a> {
        let (mut reflectance, mut specular) = (vec3_of(m.reflectance), vec3_of(m.specular_reflectance));
        let mut material = *m;
        if features::has(features, features::TEXTURES) {
            reflectance = texture::eval_or(textures, tables, m.reflectance_texture, reflectance, uv);
            specular = texture::eval_or(textures, tables, m.specular_texture, specular, uv);
            // Textured roughness: the texture's luminance, as Mitsuba's `eval_1` (the loader gives a
            // checkerboard grey colours, so that this is their mean, as Mitsuba takes it).
            if m.alpha_u_texture != NONE {
                material.alpha_u =
                    luminance(texture::eval(&textures[m.alpha_u_texture as usize], tables, uv));
            }
            if m.alpha_v_texture != NONE {
                material.alpha_v =
                    luminance(texture::eval(&textures[m.alpha_v_texture as usize], tables, uv));
            }
        }
        Bsdf { material, reflectance, specular, tables, features, perturbation }
    }

    /// A BSDF without textures (tests, tools).
    pub fn from_material(m: &Material, tables: &'a [f32]) -> Bsdf<'a> {
        Bsdf {
            material: *m,
            reflectance: vec3_of(m.reflectance),
            specular: vec3_of(m.specular_reflectance),
            tables,
            features: features::ALL,
            perturbation: perturb::Perturbation::NONE,
        }
    }

    pub fn flags(&self) -> BsdfFlags {
        with_model!(self, |model| model.flags())
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if self.is_perturbed() {
            let p = &self.perturbation;
            if !p.keeps_side(wi) {
                return Rgb::ZERO;
            }
            let (f, w) = (p.frame(), p.shadowing(wi));
            return with_model!(self, |model| model.eval(f.to_local(wo), f.to_local(wi), mode)) * w;
        }
        with_model!(self, |model| model.eval(wo, wi, mode))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if self.is_perturbed() {
            let p = &self.perturbation;
            if !p.keeps_side(wi) {
                return 0.0;
            }
            let f = p.frame();
            return with_model!(self, |model| model.pdf(f.to_local(wo), f.to_local(wi), mode));
        }
        with_model!(self, |model| model.pdf(wo, wi, mode))
    }

    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> EvalPdf {
        if self.is_perturbed() {
            let p = &self.perturbation;
            if !p.keeps_side(wi) {
                return EvalPdf::ZERO;
            }
            let f = p.frame();
            let mut ep = with_model!(self, |model| model.eval_pdf(f.to_local(wo), f.to_local(wi), mode));
            ep.f *= p.shadowing(wi);
            return ep;
        }
        with_model!(self, |model| model.eval_pdf(wo, wi, mode))
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: TransportMode) -> BsdfSample {
        if self.is_perturbed() {
            let p = &self.perturbation;
            let f = p.frame();
            let mut bs = with_model!(self, |model| model.sample(f.to_local(wo), u_lobe, u, mode));
            bs.wi = f.to_world(bs.wi);
            if bs.pdf <= 0.0 || !p.keeps_side(bs.wi) {
                return BsdfSample::invalid();
            }
            bs.weight *= p.shadowing(bs.wi);
            return bs;
        }
        with_model!(self, |model| model.sample(wo, u_lobe, u, mode))
    }

    /// Whether a normal or bump map tilts the frame (never in scenes without `NORMAL_MAPPING`).
    #[inline]
    fn is_perturbed(&self) -> bool {
        features::has(self.features, features::NORMAL_MAPPING) && self.perturbation.active()
    }

    /// Whether the scene uses BSDF model `kind` (`features`).
    #[inline]
    fn uses(&self, kind: u32) -> bool {
        features::has(self.features, features::bsdf(kind))
    }

    /// Whether both sides of the surface reflect like the front (Mitsuba's `twosided`).
    pub fn two_sided(&self) -> bool {
        self.material.flags & MATERIAL_TWO_SIDED != 0
    }
}

/// Fills a material's precomputed parameters (native builds only: the host calls it while building the
/// scene buffers) and returns the table the model reads at `Material::table`, if it needs one.
#[cfg(not(target_arch = "spirv"))]
pub fn precompute(m: &mut Material) -> Option<std::vec::Vec<f32>> {
    match m.kind {
        BSDF_PLASTIC => {
            plastic::precompute(m);
            None
        }
        BSDF_ROUGH_PLASTIC => Some(rough_plastic::precompute(m)),
        _ => None,
    }
}

#[inline]
fn vec3_of(c: [f32; 4]) -> Rgb {
    Vec3::new(c[0], c[1], c[2])
}

/// Both directions on the outer side of the surface: the reflection models here are one-sided, as in
/// Mitsuba (two-sided materials are mirrored to the front by the integrator).
#[inline]
pub fn same_hemisphere_above(wo: Vec3, wi: Vec3) -> bool {
    wo.z > 0.0 && wi.z > 0.0
}
