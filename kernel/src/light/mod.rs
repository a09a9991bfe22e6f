//! Emitters: selection proportional to power, direction sampling and densities for next-event
//! estimation and multiple importance sampling.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

pub mod area;
pub mod sphere;

use crate::math::vec3;
use crate::sampling::sample_cdf;
use crate::scene::{Light, Primitive, LIGHT_SPHERE};
use crate::spectrum::Rgb;
use crate::glam::{Vec2, Vec3};

/// A direction towards a point on an emitter, with what arrives along it.
#[derive(Clone, Copy)]
pub struct LightSample {
    /// Unit direction from the shading point towards the emitter.
    pub wi: Vec3,
    /// Distance to the sampled emitter point.
    pub dist: f32,
    /// Emitted radiance towards the shading point (zero when its back faces it).
    pub radiance: Rgb,
    /// Solid-angle density at the shading point, including the selection probability.
    pub pdf: f32,
}

impl LightSample {
    pub fn none() -> Self {
        LightSample { wi: Vec3::Z, dist: 0.0, radiance: Rgb::ZERO, pdf: 0.0 }
    }
}

/// The emitter's uniform radiance.
#[inline]
pub fn radiance(light: &Light) -> Rgb {
    vec3([light.radiance[0], light.radiance[1], light.radiance[2]])
}

/// Radiance leaving an emitting surface with normal `n` in direction `w`: area emitters are one-sided.
#[inline]
pub fn emitted(light: &Light, n: Vec3, w: Vec3) -> Rgb {
    if n.dot(w) > 0.0 {
        radiance(light)
    } else {
        Rgb::ZERO
    }
}

/// Converts the density `1/area` of a point seen at squared distance `dist2` under `cos_light` into
/// a solid-angle density.
#[inline]
fn area_to_solid_angle(area: f32, dist2: f32, cos_light: f32) -> f32 {
    if cos_light <= 0.0 || area <= 0.0 {
        0.0
    } else {
        dist2 / (cos_light * area)
    }
}

/// The light sample for a point `q` (normal `n`) drawn uniformly from an emitting surface of area
/// `area`, as seen from `p`.
pub(crate) fn from_area_sample(light: &Light, p: Vec3, q: Vec3, n: Vec3, area: f32) -> LightSample {
    let d = q - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return LightSample::none();
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let pdf = area_to_solid_angle(area, dist2, n.dot(wi).abs());
    if pdf <= 0.0 {
        return LightSample::none();
    }
    LightSample { wi, dist, radiance: emitted(light, n, -wi), pdf }
}

/// Solid-angle density at `p` of uniform area sampling that produced `hit_p` (normal `hit_n`).
pub(crate) fn area_sample_pdf(area: f32, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let d = hit_p - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return 0.0;
    }
    area_to_solid_angle(area, dist2, hit_n.dot(d).abs() / dist2.sqrt())
}

/// Picks one of the `count` emitters with probability proportional to its power and samples a direction towards it.
pub fn sample(
    lights: &[Light],
    prims: &[Primitive],
    tables: &[f32],
    count: u32,
    cdf_offset: u32,
    p: Vec3,
    u_select: f32,
    u: Vec2,
) -> LightSample {
    if count == 0 {
        return LightSample::none();
    }
    let chosen = sample_cdf(tables, cdf_offset, count, u_select);
    let light = lights[chosen.index as usize];
    let prim = prims[light.prim as usize];
    let mut s = if light.kind == LIGHT_SPHERE {
        sphere::sample(&light, &prim, p, u)
    } else {
        area::sample(&light, &prim, p, u)
    };
    s.pdf *= light.pmf;
    s
}

/// Solid-angle density with which `sample` would have produced the direction from `p` to the point
/// `hit_p` (normal `hit_n`) on the emitting primitive of `light`, including the selection probability.
pub fn pdf(light: &Light, prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let pdf = if light.kind == LIGHT_SPHERE {
        sphere::pdf(prim, p, hit_p, hit_n)
    } else {
        area::pdf(prim, p, hit_p, hit_n)
    };
    pdf * light.pmf
}
