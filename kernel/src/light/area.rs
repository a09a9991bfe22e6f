//! Emissive triangles, sampled uniformly by area.
use super::{area_sample_pdf, from_area_sample, LightSample};
use crate::math::vec3;
use crate::scene::{Light, Primitive, PRIM_FLAG_FLIP};
use crate::shape::triangle;
use crate::glam::{Vec2, Vec3};

/// The emitting side's unit normal and the area, from one cross product.
fn normal_and_area(prim: &Primitive) -> (Vec3, f32) {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    let c = (p1 - p0).cross(p2 - p0);
    let len = c.length();
    let n = c / len;
    let n = if prim.flags & PRIM_FLAG_FLIP != 0 { -n } else { n };
    (n, 0.5 * len)
}

pub fn sample(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let q = triangle::sample_point(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2), u);
    let (n, area) = normal_and_area(prim);
    from_area_sample(light, p, q, n, area)
}

pub fn pdf(prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    area_sample_pdf(triangle::area(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2)), p, hit_p, hit_n)
}
