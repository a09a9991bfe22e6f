//! Textured emission (`Light::texture`, under `features::TEXTURED_EMISSION`): the texture's value
//! multiplies the emitter's `radiance`. Area emitters look it up at the emitting point's uv (the
//! surface's own texture coordinates, as a BSDF's textures), spots at the direction's place in the
//! image spread over the cutoff cone, projectors at the direction's place on the image plane
//! (`projector`). Sampling is unchanged (uniform by area, uniform in the cone): the texture enters
//! the weights only.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::radiance;
use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::{Light, SceneView, NONE, PRIM_DISK, PRIM_SPHERE};
use crate::math::vec3;
use crate::shape::{disk, sphere};
use crate::spectrum::Rgb;
use crate::texture;

/// Whether `light`'s emission varies with a texture in this scene.
#[inline]
pub fn is_textured(scene: &SceneView, light: &Light) -> bool {
    features::has(scene.features, features::TEXTURED_EMISSION) && light.texture != NONE
}

/// `radiance · texture(uv)`, or the radiance alone for an untextured emitter.
#[inline]
pub fn value(scene: &SceneView, light: &Light, uv: Vec2) -> Rgb {
    if is_textured(scene, light) {
        radiance(light) * texture::eval(&scene.textures[light.texture as usize], scene.tables, uv)
    } else {
        radiance(light)
    }
}

/// The texture coordinates of a point `q` on primitive `prim` (index), by the shape's own
/// parametrisation: a triangle's interpolated uvs at `q`'s barycentrics, a disk's (r, φ/2π), a
/// sphere's (φ/2π, θ/π), as `shape::surface_point` gives them at a hit.
pub fn surface_uv(scene: &SceneView, prim: u32, q: Vec3) -> Vec2 {
    let pr = scene.prims[prim as usize];
    let (p0, p1, p2) = (vec3(pr.p0), vec3(pr.p1), vec3(pr.p2));
    if pr.kind == PRIM_SPHERE {
        return sphere::uv(sphere::Orientation::of(&pr).to_local((q - p0).normalize()));
    }
    if pr.kind == PRIM_DISK {
        return disk::uv(disk::coordinates(p0, p1, p2, q));
    }
    // Barycentrics of q (on the triangle's plane) from the sub-triangles' signed areas.
    let (e1, e2, d) = (p1 - p0, p2 - p0, q - p0);
    let n = e1.cross(e2);
    let inv = 1.0 / n.length_squared();
    let b1 = d.cross(e2).dot(n) * inv;
    let b2 = e1.cross(d).dot(n) * inv;
    let a = scene.attributes[prim as usize];
    Vec2::from(a.uv0) * (1.0 - b1 - b2) + Vec2::from(a.uv1) * b1 + Vec2::from(a.uv2) * b2
}

/// What an area emitter sends from its point `q` on `prim` (index), facing away from `n`'s side
/// already checked by the caller.
#[inline]
pub fn at_surface_point(scene: &SceneView, light: &Light, prim: u32, q: Vec3) -> Rgb {
    if is_textured(scene, light) {
        value(scene, light, surface_uv(scene, prim, q))
    } else {
        radiance(light)
    }
}

/// A spot's image coordinates of a direction `local` in its frame (beam along +z): the image spans
/// the cone's tangent square, `tan(cutoff)` from the axis to each edge's middle (Mitsuba's `spot`).
#[inline]
pub fn spot_uv(light: &Light, local: Vec3) -> Vec2 {
    let tan_cutoff = light.params[2].tan();
    let s = 0.5 / (local.z * tan_cutoff);
    Vec2::new(0.5 + local.x * s, 0.5 + local.y * s)
}
