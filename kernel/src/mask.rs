//! Null interfaces: surfaces that paths may cross without scattering. Mitsuba flags two such lobes:
//! the `mask` BSDF's (a surface that is there with probability `opacity` and otherwise lets light
//! through unchanged: a leaf cut out of a card by an alpha texture) and `thindielectric`'s
//! transmission (a pane of negligible thickness: light goes straight through with weight
//! `specular_transmittance`, with probability 1 − R, R the pane's summed reflectance). caustic decides
//! the crossing where a path meets the surface, before any BSDF: with its probability the path
//! continues straight on with its depth and its last scattering vertex unchanged (the crossing is no
//! scattering event: Mitsuba's `volpath` treats null lobes so, and `max_depth` counts only real
//! bounces there too), its throughput times the crossing's weight; otherwise the surface scatters:
//! a mask's nested BSDF with weight 1 (`opacity · f / opacity`), a pane's mirror reflection alone
//! (`Crossing::reflect_only`). Shadow rays are attenuated by what crosses each null interface
//! (`transmittance`: 1 − opacity, (1 − R)·T at a pane), so next-event estimation and BSDF sampling
//! estimate the same light and MIS between them stays unbiased.
//!
//! Mitsuba's own `path` integrator differs, and is biased on such scenes (its `mask` documentation
//! recommends `volpath`): it counts the crossing as a bounce, weighs the emitter behind a mask
//! against light sampling from the mask's point (which cannot sample that path), and its shadow rays
//! stop at any mask or pane. caustic renders what Mitsuba's `volpath` renders. (A `thindielectric`
//! inside a `blendbsdf` is no null interface: the blend scatters, both lobes a bounce.)
use crate::bsdf::thin_dielectric::ThinDielectric;
use crate::bsdf::{Bxdf, Component};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::instancing::surface_point;
use crate::layout::{Material, SceneView, BSDF_THIN_DIELECTRIC, MATERIAL_MASK, NONE};
use crate::rng::Sampler;
use crate::shape::{offset_origin, SurfacePoint};
use crate::spectrum::{luminance, Rgb};

/// Most null interfaces one path or shadow ray crosses: bounds the loops on the GPU. A path that
/// meets more ends there (a shadow ray is then blocked); real scenes (foliage) cross tens.
pub const MAX_PASSES: u32 = 256;

/// Whether `m` is a mask (only when the scene has null interfaces: the test folds away on the GPU
/// otherwise).
#[inline]
pub fn is_mask(scene: &SceneView, m: &Material) -> bool {
    features::has(scene.features, features::MASK) && m.flags & MATERIAL_MASK != 0
}

/// Whether paths may cross `m`: a mask or a thin dielectric, in a scene with null interfaces.
#[inline]
pub fn is_null(scene: &SceneView, m: &Material) -> bool {
    features::has(scene.features, features::MASK)
        && (m.flags & MATERIAL_MASK != 0 || m.kind == BSDF_THIN_DIELECTRIC)
}

/// The opacity of mask material `m` at `uv`, in [0, 1]: `opacity`, or the luminance of its texture
/// (as Mitsuba's `eval_1` of a colour texture); 1 where `m` is no mask.
#[inline]
pub fn opacity(scene: &SceneView, m: &Material, uv: Vec2) -> f32 {
    if m.flags & MATERIAL_MASK == 0 {
        return 1.0;
    }
    let o = if m.opacity_texture != NONE && features::has(scene.features, features::TEXTURES) {
        luminance(crate::texture::eval(&scene.textures[m.opacity_texture as usize], scene.tables, uv))
    } else {
        m.opacity
    };
    o.clamp(0.0, 1.0)
}

/// The pane of thin-dielectric material `m` at `sp`, its textures looked up there.
#[inline]
fn pane(scene: &SceneView, m: &Material, sp: &SurfacePoint) -> ThinDielectric {
    let c = Component::new(m, scene.textures, scene.tables, sp.lookup(), scene.features);
    ThinDielectric::from_material(&c.material, c.reflectance, c.specular, scene.tables)
}

/// What a path arriving along `dir` at null interface `m` (`is_null`) does, decided by `u`.
#[derive(Clone, Copy)]
pub struct Crossing {
    /// It goes straight on, its throughput times `weight`.
    pub through: bool,
    pub weight: Rgb,
    /// It stays at a pane: its BSDF sample must take the reflection (the choice of lobe is made), so
    /// the caller samples with `u_lobe` 0 (`ThinDielectric::sample` reflects below R).
    pub reflect_only: bool,
}

impl Crossing {
    /// The path meets the surface, as at any that is no null interface.
    pub const MEETS: Crossing = Crossing { through: false, weight: Rgb::ONE, reflect_only: false };
}

/// The crossing of `m` at `sp` for a path along `dir` and a uniform `u`: through a mask with
/// probability 1 − opacity (weight 1); else, at a pane, through with probability 1 − R (weight the
/// pane's transmittance), `u` rescaled for the second choice.
pub fn cross(scene: &SceneView, m: &Material, sp: &SurfacePoint, dir: Vec3, u: f32) -> Crossing {
    let o = opacity(scene, m, sp.uv);
    if u >= o {
        return Crossing { through: true, weight: Rgb::ONE, reflect_only: false };
    }
    if m.kind != BSDF_THIN_DIELECTRIC {
        return Crossing::MEETS;
    }
    let pane = pane(scene, m, sp);
    let r = pane.reflectance(sp.ns.dot(dir));
    if u >= o * r {
        Crossing { through: true, weight: pane.specular_transmittance, reflect_only: false }
    } else {
        Crossing { through: false, weight: Rgb::ONE, reflect_only: true }
    }
}

/// The light that crosses null interface `m` at `sp` along `dir` (`is_null`): 1 − opacity through a
/// mask, plus opacity · (1 − R) · T through a pane (Mitsuba's `eval_null_transmission`).
#[inline]
pub fn null_transmission(scene: &SceneView, m: &Material, sp: &SurfacePoint, dir: Vec3) -> Rgb {
    let o = opacity(scene, m, sp.uv);
    let mut t = Rgb::splat(1.0 - o);
    if m.kind == BSDF_THIN_DIELECTRIC {
        let pane = pane(scene, m, sp);
        t += pane.specular_transmittance * (o * (1.0 - pane.reflectance(sp.ns.dot(dir))));
    }
    t
}

/// The light that crosses the open segment of `shadow` (ignoring primitive `target`, as
/// `Accel::occluded`): none past any surface that is no null interface, `null_transmission` at each
/// that is.
pub fn transmittance(scene: &SceneView, accel: &Accel, shadow: &Ray, target: u32) -> Rgb {
    if !features::has(scene.features, features::MASK) {
        return if accel.occluded(shadow, target) { Rgb::ZERO } else { Rgb::ONE };
    }
    // Each surface in turn, nearest first: `t_min` (excluded) advances past each one crossed.
    let mut r = *shadow;
    let mut t = Rgb::ONE;
    let mut passes = 0;
    while passes < MAX_PASSES {
        let Some(hit) = accel.trace(&r, false, target) else { return t };
        let prim = scene.prims[hit.prim as usize];
        let m = scene.materials[prim.material as usize];
        if !is_null(scene, &m) {
            return Rgb::ZERO;
        }
        let sp = surface_point(scene, &prim, &hit, &r);
        t *= null_transmission(scene, &m, &sp, r.dir);
        if crate::math::max_component(t) <= 0.0 {
            return Rgb::ZERO;
        }
        r.t_min = hit.t;
        passes += 1;
    }
    Rgb::ZERO
}

/// The crossing of `m` at `sp` for a path along `dir`; where `m` is no null interface (`is_null`),
/// `Crossing::MEETS` (and nothing drawn). Decision `k` draws dimension `path::DIM_MASK + k` from a
/// copy of `sampler`, so the caller's dimensions are undisturbed; `k` counts every decision of the
/// path (a number drawn twice would correlate them). Integrators whose paths stop at `MAX_PASSES`
/// decisions check `k` after. (Not an `Option`: rust-gpu 0.11 cannot lay one out around this struct.)
#[inline]
pub fn crossing(
    scene: &SceneView,
    m: &Material,
    sp: &SurfacePoint,
    dir: Vec3,
    sampler: &Sampler,
    k: &mut u32,
) -> Crossing {
    if !is_null(scene, m) {
        return Crossing::MEETS;
    }
    let mut s = *sampler;
    s.set_dimension(crate::integrator::path::DIM_MASK + *k);
    *k += 1;
    cross(scene, m, sp, dir, s.next_1d())
}

/// The ray that goes on along `dir` from the null interface at `sp` it crossed.
#[inline]
pub fn onward(sp: &SurfacePoint, dir: Vec3) -> Ray {
    Ray { origin: offset_origin(sp, sp.ng, dir), dir, t_min: 0.0, t_max: f32::MAX }
}
