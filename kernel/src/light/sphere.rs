//! Spherical emitters. Seen from outside they are sampled uniformly inside the subtended cone
//! (Shirley et al. 1996), which is noise-free in the solid angle and stays exact for tiny or distant
//! spheres because `1 - cos θmax` is computed without cancellation. From inside (a sphere enclosing
//! the scene with flipped normals) they are sampled uniformly by area.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{area_sample_pdf, from_area_sample, LightSample};
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::layout::{Light, Primitive, NONE, PRIM_FLAG_FLIP};
use crate::math::{safe_sqrt, vec3, PI};
use crate::sampling::{
    one_minus_cos_from_sin2, square_to_uniform_cone, square_to_uniform_sphere, uniform_cone_pdf,
};
use crate::spectrum::Rgb;

#[inline]
fn orientation(prim: &Primitive) -> f32 {
    if prim.flags & PRIM_FLAG_FLIP != 0 {
        -1.0
    } else {
        1.0
    }
}

pub fn sample(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let centre = vec3(prim.p0);
    let radius = prim.p1[0];
    let to_centre = centre - p;
    let d2 = to_centre.length_squared();
    let r2 = radius * radius;
    if d2 <= r2 {
        return sample_from_inside(light, prim, p, u);
    }
    let d = d2.sqrt();
    let axis = to_centre / d;
    let sin2_max = r2 / d2;
    let one_minus_cos_max = one_minus_cos_from_sin2(sin2_max);
    let local = square_to_uniform_cone(u, one_minus_cos_max);
    let wi = Frame::from_normal(axis).to_world(local);
    // Distance to the near intersection of the sampled direction with the sphere; at the cone's rim
    // rounding can make the discriminant slightly negative, where the ray grazes the sphere.
    let cos_theta = local.z;
    let sin2_theta = local.x * local.x + local.y * local.y;
    let dist = d * cos_theta - safe_sqrt(r2 - d2 * sin2_theta);
    // Every direction in the cone meets the near side, whose outward normal faces `p`: the sphere
    // emits towards `p` unless its normals are flipped. (Deciding this from the sampled point's normal
    // fails for tiny spheres far away, where that point carries more error than the radius.)
    let radiance = if orientation(prim) > 0.0 { super::radiance(light) } else { Rgb::ZERO };
    LightSample {
        wi,
        dist,
        radiance,
        pdf: uniform_cone_pdf(one_minus_cos_max),
        delta: false,
        prim: light.prim,
        light: NONE,
    }
}

fn sample_from_inside(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let dir = square_to_uniform_sphere(u);
    let q = vec3(prim.p0) + dir * prim.p1[0];
    from_area_sample(light, p, q, dir * orientation(prim), area(prim))
}

fn area(prim: &Primitive) -> f32 {
    4.0 * PI * prim.p1[0] * prim.p1[0]
}

pub fn pdf(prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let centre = vec3(prim.p0);
    let radius = prim.p1[0];
    let d2 = (centre - p).length_squared();
    let r2 = radius * radius;
    if d2 <= r2 {
        return area_sample_pdf(area(prim), p, hit_p, hit_n);
    }
    uniform_cone_pdf(one_minus_cos_from_sin2(r2 / d2))
}
