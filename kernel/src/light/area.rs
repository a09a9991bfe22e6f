//! Emissive triangles, sampled uniformly by area.
use super::{area_sample_pdf, from_area_sample, LightSample};
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

fn area(prim: &Primitive) -> f32 {
    triangle::area(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2))
}

pub fn sample(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let q = triangle::sample_point(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2), u);
    from_area_sample(light, p, q, normal(prim), area(prim))
}

pub fn pdf(prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    area_sample_pdf(area(prim), p, hit_p, hit_n)
}
