//! Analytic disks (Mitsuba's `disk`): the image of the unit disk under an affine map,
//! `{c + a·u + b·v : a² + b² ≤ 1}` (an ellipse when `to_world` scales unevenly), with Mitsuba's
//! parametrisation uv = (r, φ/2π) in the disk's own coordinates (a, b).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::math::{INV_2PI, PI};
use crate::sampling::square_to_concentric_disk;

/// Ray/disk intersection: the plane hit, then the disk's own coordinates `(a, b)` of the hit point
/// (returned as the hit's uv) tested against the unit circle.
pub fn intersect(centre: Vec3, u: Vec3, v: Vec3, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
    let n = u.cross(v);
    let denom = n.dot(ray.dir);
    if denom == 0.0 {
        return None;
    }
    let t = n.dot(centre - ray.origin) / denom;
    if !(t > ray.t_min && t < t_max) {
        return None;
    }
    let ab = local(centre, u, v, n, ray.origin + ray.dir * t);
    if ab.length_squared() > 1.0 {
        return None;
    }
    Some((t, ab))
}

/// The coordinates `(a, b)` of `p − c = a·u + b·v` (p on the plane; `n = u × v`).
#[inline]
fn local(centre: Vec3, u: Vec3, v: Vec3, n: Vec3, p: Vec3) -> Vec2 {
    let q = p - centre;
    let inv = 1.0 / n.length_squared();
    Vec2::new(q.cross(v).dot(n) * inv, u.cross(q).dot(n) * inv)
}

/// The disk coordinates `(a, b)` of a point `p` on the disk's plane.
#[inline]
pub fn coordinates(centre: Vec3, u: Vec3, v: Vec3, p: Vec3) -> Vec2 {
    local(centre, u, v, u.cross(v), p)
}

/// The point with disk coordinates `ab`: exactly on the plane, without the error of `o + t·d`.
#[inline]
pub fn point(centre: Vec3, u: Vec3, v: Vec3, ab: Vec2) -> Vec3 {
    centre + u * ab.x + v * ab.y
}

/// Mitsuba's disk uv: the radius and the angle from `u` towards `v` as a fraction of a turn.
pub fn uv(ab: Vec2) -> Vec2 {
    let phi = ab.y.atan2(ab.x);
    let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
    Vec2::new(ab.length(), phi * INV_2PI)
}

/// Mitsuba's `dp/du`, `dp/dv` of the disk at disk coordinates `ab` (derivatives of `uv`: u the
/// radius, v the angle as a fraction of a turn); both zero at the centre, as Mitsuba's.
pub fn tangents(u: Vec3, v: Vec3, ab: Vec2) -> (Vec3, Vec3) {
    let r = ab.length();
    let inv_r = if r > 0.0 { 1.0 / r } else { 0.0 };
    let (cos_phi, sin_phi) = (ab.x * inv_r, ab.y * inv_r);
    (u * cos_phi + v * sin_phi, (v * cos_phi - u * sin_phi) * (2.0 * PI * r))
}

pub fn area(u: Vec3, v: Vec3) -> f32 {
    PI * u.cross(v).length()
}

/// A uniformly distributed point on the disk (density 1 / area: the affine map keeps uniformity).
pub fn sample_point(centre: Vec3, u: Vec3, v: Vec3, s: Vec2) -> Vec3 {
    point(centre, u, v, square_to_concentric_disk(s))
}
