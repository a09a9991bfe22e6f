//! Emissive triangles, sampled uniformly by area.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{emitted, LightSample};
use crate::math::vec3;
use crate::scene::{Light, Primitive, PRIM_FLAG_FLIP};
use crate::shape::triangle;
use crate::glam::{Vec2, Vec3};

fn normal(prim: &Primitive) -> Vec3 {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    let n = (p1 - p0).cross(p2 - p0).normalize();
    if prim.flags & PRIM_FLAG_FLIP != 0 {
        -n
    } else {
        n
    }
}

/// Converts the area density `1/A` at a point seen from `p` into a solid-angle density.
#[inline]
fn area_to_solid_angle(area: f32, dist2: f32, cos_light: f32) -> f32 {
    if cos_light <= 0.0 || area <= 0.0 {
        0.0
    } else {
        dist2 / (cos_light * area)
    }
}

pub fn sample(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    let q = triangle::sample_point(p0, p1, p2, u);
    let d = q - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return LightSample::none();
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let n = normal(prim);
    let cos_light = -n.dot(wi);
    let pdf = area_to_solid_angle(triangle::area(p0, p1, p2), dist2, cos_light);
    if pdf <= 0.0 {
        return LightSample::none();
    }
    LightSample { wi, dist, radiance: emitted(light, n, -wi), pdf }
}

pub fn pdf(prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let d = hit_p - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return 0.0;
    }
    let cos_light = -hit_n.dot(d) / dist2.sqrt();
    area_to_solid_angle(triangle::area(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2)), dist2, cos_light)
}
