//! Mitsuba's `mask` BSDF: a surface that is there with probability `opacity` and otherwise lets light
//! through unchanged (a leaf cut out of a card by an alpha texture). caustic decides it where a path
//! meets the surface, before any BSDF: with probability `1 − opacity` the path continues straight on,
//! with its throughput, its depth and its last scattering vertex unchanged (the pass-through is no
//! scattering event: Mitsuba's `volpath` treats the mask's null lobe so, and `max_depth` counts only
//! real bounces there too); otherwise the nested BSDF scatters with weight 1 (`opacity · f / opacity`).
//! Shadow rays are attenuated by `1 − opacity` at every mask they cross (`transmittance`), so next-event
//! estimation and BSDF sampling estimate the same light and MIS between them stays unbiased.
//!
//! Mitsuba's own `path` integrator differs, and is biased on such scenes (its `mask` documentation
//! recommends `volpath`): it counts the pass-through as a bounce, weighs the emitter behind a mask
//! against light sampling from the mask's point (which cannot sample that path), and its shadow rays
//! stop at any mask. caustic renders what Mitsuba's `volpath` renders.
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::instancing::surface_point;
use crate::layout::{Material, SceneView, MATERIAL_MASK, NONE};
use crate::rng::Sampler;
use crate::shape::{offset_origin, SurfacePoint};
use crate::spectrum::luminance;

/// Most masks one path or shadow ray passes through: bounds the loops on the GPU. A path that meets
/// more ends there (a shadow ray is then blocked); real scenes (foliage) cross tens.
pub const MAX_PASSES: u32 = 256;

/// Whether `m` is a mask (only when the scene has masks: the test folds away on the GPU otherwise).
#[inline]
pub fn is_mask(scene: &SceneView, m: &Material) -> bool {
    features::has(scene.features, features::MASK) && m.flags & MATERIAL_MASK != 0
}

/// The opacity of mask material `m` at `uv`, in [0, 1]: `opacity`, or the luminance of its texture
/// (as Mitsuba's `eval_1` of a colour texture).
#[inline]
pub fn opacity(scene: &SceneView, m: &Material, uv: Vec2) -> f32 {
    let o = if m.opacity_texture != NONE && features::has(scene.features, features::TEXTURES) {
        luminance(crate::texture::eval(&scene.textures[m.opacity_texture as usize], scene.tables, uv))
    } else {
        m.opacity
    };
    o.clamp(0.0, 1.0)
}

/// The fraction of light that crosses the open segment of `shadow` (ignoring primitive `target`, as
/// `Accel::occluded`): 0 at any surface that is no mask, `1 − opacity` at each mask.
pub fn transmittance(scene: &SceneView, accel: &Accel, shadow: &Ray, target: u32) -> f32 {
    if !features::has(scene.features, features::MASK) {
        return if accel.occluded(shadow, target) { 0.0 } else { 1.0 };
    }
    // Each surface in turn, nearest first: `t_min` (excluded) advances past each mask crossed.
    let mut r = *shadow;
    let mut t = 1.0f32;
    let mut passes = 0;
    while passes < MAX_PASSES {
        let Some(hit) = accel.trace(&r, false, target) else { return t };
        let prim = scene.prims[hit.prim as usize];
        let m = scene.materials[prim.material as usize];
        if m.flags & MATERIAL_MASK == 0 {
            return 0.0;
        }
        let sp = surface_point(scene, &prim, &hit, &r);
        t *= 1.0 - opacity(scene, &m, sp.uv);
        if t <= 0.0 {
            return 0.0;
        }
        r.t_min = hit.t;
        passes += 1;
    }
    0.0
}

/// Whether a path meeting material `m` at `sp` passes through it (a mask, with probability
/// `1 − opacity`). Decision `k` draws dimension `path::DIM_MASK + k` from a copy of `sampler`, so the
/// caller's dimensions are undisturbed; `k` counts every decision of the path (a number drawn twice
/// would correlate them). Integrators whose paths stop at `MAX_PASSES` decisions check `k` after.
#[inline]
pub fn passes(scene: &SceneView, m: &Material, sp: &SurfacePoint, sampler: &Sampler, k: &mut u32) -> bool {
    if !is_mask(scene, m) {
        return false;
    }
    let mut s = *sampler;
    s.set_dimension(crate::integrator::path::DIM_MASK + *k);
    *k += 1;
    s.next_1d() >= opacity(scene, m, sp.uv)
}

/// The ray that goes on along `dir` from the mask at `sp` it passed through.
#[inline]
pub fn onward(sp: &SurfacePoint, dir: Vec3) -> Ray {
    Ray { origin: offset_origin(sp, sp.ng, dir), dir, t_min: 0.0, t_max: f32::MAX }
}
