//! Analytic spheres.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::math::sign;

/// Ray/sphere intersection in the form of "Precision Improvements for Ray/Sphere Intersection"
/// (Haines et al., Ray Tracing Gems ch. 7): the discriminant is computed from the distance of the
/// centre to the ray, which stays accurate for small spheres far away.
pub fn intersect(centre: Vec3, radius: f32, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
    let f = ray.origin - centre;
    let b = -f.dot(ray.dir);
    let l = f + ray.dir * b;
    let r2 = radius * radius;
    let discr = r2 - l.dot(l);
    if discr < 0.0 {
        return None;
    }
    let c = f.dot(f) - r2;
    let q = b + sign(b) * discr.sqrt();
    if q == 0.0 {
        return None;
    }
    let ta = c / q;
    let tb = q;
    let t_near = ta.min(tb);
    let t_far = ta.max(tb);
    if t_near > ray.t_min && t_near < t_max {
        return Some((t_near, Vec2::ZERO));
    }
    if t_far > ray.t_min && t_far < t_max {
        return Some((t_far, Vec2::ZERO));
    }
    None
}

/// Puts a computed hit point back onto the sphere's surface (removes the error of `o + t·d`).
#[inline]
pub fn reproject(centre: Vec3, radius: f32, p: Vec3) -> Vec3 {
    let d = p - centre;
    let len = d.length();
    if len > 0.0 {
        centre + d * (radius / len)
    } else {
        p
    }
}

/// Mitsuba's sphere parametrisation of a unit local position: u the azimuth about +z, v = θ / π.
pub fn uv(local: Vec3) -> Vec2 {
    let phi = local.y.atan2(local.x);
    let phi = if phi < 0.0 { phi + 2.0 * crate::math::PI } else { phi };
    Vec2::new(phi * crate::math::INV_2PI, local.z.clamp(-1.0, 1.0).acos() * crate::math::INV_PI)
}

/// Mitsuba's `dp/du`, `dp/dv` of a sphere of `radius` at the unit local position `local` (derivatives
/// of `uv`: u a full turn in φ, v half a turn in θ); at the poles `dp/du` is zero and `dp/dv` points
/// along +x, as Mitsuba sets them.
pub fn tangents(local: Vec3, radius: f32) -> (Vec3, Vec3) {
    let dp_du = Vec3::new(-local.y, local.x, 0.0) * (2.0 * crate::math::PI * radius);
    let rd = (local.x * local.x + local.y * local.y).sqrt();
    let dir =
        if rd == 0.0 { Vec3::X } else { Vec3::new(local.z * local.x / rd, local.z * local.y / rd, -rd) };
    (dp_du, dir * (crate::math::PI * radius))
}
