//! BSDFs. Every model works in the local shading frame (normal = +z) with `wo` pointing towards the
//! viewer (or the previous vertex) and `wi` towards the light; `eval` includes the cosine factor
//! `|cos θi|` so that sampling weights are `eval / pdf`.
pub mod conductor;
pub mod dielectric;
pub mod diffuse;
pub mod fresnel;
pub mod fuzzy_metal;
pub mod microfacet;
pub mod phong;
pub mod plastic;
pub mod rough_conductor;
pub mod rough_dielectric;
pub mod rough_plastic;
pub mod thin_dielectric;

use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::*;
use crate::spectrum::Rgb;
use crate::texture;

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

/// Builds the model of `$bsdf`'s record kind and calls the method on it: one `match` (rust-gpu needs
/// the models as plain structs, not a data-carrying enum) shared by `eval`, `pdf` and `sample`. Lambert,
/// the fallback kind, takes its own argument list (its sampling has no lobe choice). Each arm is
/// guarded by its feature bit, so a specialised kernel keeps only the scene's models. (Measured on the
/// H100 in one run against testing the bit inside each arm, which keeps a ten-way switch: +3–11% on
/// five of six material previews and the Cornell box, −4% on the diamond; BENCHMARKS.md.)
macro_rules! dispatch {
    ($bsdf:ident, diffuse => $d:ident($($da:expr),*), other => $f:ident($($a:expr),*)) => {{
        let (m, r, s, t) = (&$bsdf.material, $bsdf.reflectance, $bsdf.specular, $bsdf.tables);
        match m.kind {
            BSDF_PHONG if features::has($bsdf.features, features::bsdf(BSDF_PHONG)) => $bsdf.phong().$f($($a),*),
            BSDF_CONDUCTOR if features::has($bsdf.features, features::bsdf(BSDF_CONDUCTOR)) => conductor::Conductor::from_material(m, r, s, t).$f($($a),*),
            BSDF_ROUGH_CONDUCTOR if features::has($bsdf.features, features::bsdf(BSDF_ROUGH_CONDUCTOR)) => rough_conductor::RoughConductor::from_material(m, r, s, t).$f($($a),*),
            BSDF_DIELECTRIC if features::has($bsdf.features, features::bsdf(BSDF_DIELECTRIC)) => dielectric::Dielectric::from_material(m, r, s, t).$f($($a),*),
            BSDF_THIN_DIELECTRIC if features::has($bsdf.features, features::bsdf(BSDF_THIN_DIELECTRIC)) => thin_dielectric::ThinDielectric::from_material(m, r, s, t).$f($($a),*),
            BSDF_ROUGH_DIELECTRIC if features::has($bsdf.features, features::bsdf(BSDF_ROUGH_DIELECTRIC)) => rough_dielectric::RoughDielectric::from_material(m, r, s, t).$f($($a),*),
            BSDF_PLASTIC if features::has($bsdf.features, features::bsdf(BSDF_PLASTIC)) => plastic::Plastic::from_material(m, r, s, t).$f($($a),*),
            BSDF_ROUGH_PLASTIC if features::has($bsdf.features, features::bsdf(BSDF_ROUGH_PLASTIC)) => rough_plastic::RoughPlastic::from_material(m, r, s, t).$f($($a),*),
            BSDF_FUZZY_METAL if features::has($bsdf.features, features::bsdf(BSDF_FUZZY_METAL)) => fuzzy_metal::FuzzyMetal::from_material(m, r, s, t).$f($($a),*),
            _ => $bsdf.diffuse().$d($($da),*),
        }
    }};
}

/// A surface's BSDF: the material record with its textures evaluated at the hit, dispatched on the
/// record's `kind` with `match`. (The models are built per call from the record rather than held in a
/// data-carrying enum: rust-gpu 0.11 cannot cast between variants of different layouts.)
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
}

impl<'a> Bsdf<'a> {
    /// The BSDF of `m` at texture coordinates `uv` in a scene using `features`.
    pub fn new(m: &Material, textures: &[Texture], tables: &'a [f32], uv: Vec2, features: u32) -> Bsdf<'a> {
        let (mut reflectance, mut specular) = (vec3_of(m.reflectance), vec3_of(m.specular_reflectance));
        if features::has(features, features::TEXTURES) {
            reflectance = texture::eval_or(textures, tables, m.reflectance_texture, reflectance, uv);
            specular = texture::eval_or(textures, tables, m.specular_texture, specular, uv);
        }
        Bsdf { material: *m, reflectance, specular, tables, features }
    }

    /// A BSDF without textures (tests, tools).
    pub fn from_material(m: &Material, tables: &'a [f32]) -> Bsdf<'a> {
        Bsdf {
            material: *m,
            reflectance: vec3_of(m.reflectance),
            specular: vec3_of(m.specular_reflectance),
            tables,
            features: features::ALL,
        }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        dispatch!(self, diffuse => eval(wo, wi), other => eval(wo, wi))
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        dispatch!(self, diffuse => pdf(wo, wi), other => pdf(wo, wi))
    }

    /// `u_lobe` picks a lobe of multi-lobe models; `u` warps to a direction.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> BsdfSample {
        dispatch!(self, diffuse => sample(wo, u), other => sample(wo, u_lobe, u))
    }

    /// Whether next-event estimation can contribute (false for purely specular models).
    pub fn has_smooth_component(&self) -> bool {
        match self.material.kind {
            BSDF_CONDUCTOR | BSDF_DIELECTRIC | BSDF_THIN_DIELECTRIC => false,
            BSDF_FUZZY_METAL => !fuzzy_metal::FuzzyMetal::is_delta(self.material.alpha_u),
            _ => true,
        }
    }

    /// Whether both sides of the surface reflect like the front (Mitsuba's `twosided`).
    pub fn two_sided(&self) -> bool {
        self.material.flags & MATERIAL_TWO_SIDED != 0
    }

    fn diffuse(&self) -> diffuse::Diffuse {
        diffuse::Diffuse { reflectance: self.reflectance }
    }

    fn phong(&self) -> phong::Phong {
        phong::Phong::new(self.reflectance, self.specular, self.material.eta)
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
