//! Analytic spheres.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::layout::Primitive;
use crate::math::sign;

/// A sphere's orientation in its record (Mitsuba keeps the rotation of `to_world`, which its uv and
/// tangents follow): the unit quaternion's vector part in `p1[1]`, `p1[2]`, `p2[0]`, its real part
/// minus one in `p2[1]`, and 1 in `p2[2]` where the frame is mirrored (its local x negated before the
/// rotation). An all-zero record is the identity, so primitives written without a frame stay
/// upright. The centre is `p0`, the radius `p1[0]`.
#[derive(Clone, Copy)]
pub struct Orientation {
    v: Vec3,
    w: f32,
    mirror: f32,
}

impl Orientation {
    #[inline]
    pub fn of(prim: &Primitive) -> Orientation {
        Orientation {
            v: Vec3::new(prim.p1[1], prim.p1[2], prim.p2[0]),
            w: prim.p2[1] + 1.0,
            mirror: if prim.p2[2] > 0.5 { -1.0 } else { 1.0 },
        }
    }

    /// The record's words for rotation quaternion `(x, y, z, w)` and `mirrored`: `(p1[1], p1[2])` and
    /// `p2` (host side).
    pub fn words(x: f32, y: f32, z: f32, w: f32, mirrored: bool) -> ([f32; 2], [f32; 3]) {
        ([x, y], [z, w - 1.0, if mirrored { 1.0 } else { 0.0 }])
    }

    /// `v` rotated by the quaternion (or its inverse, `sign` −1 on the vector part).
    #[inline]
    fn rotate(&self, v: Vec3, sign: f32) -> Vec3 {
        let u = self.v * sign;
        let t = u.cross(v) * 2.0;
        v + t * self.w + u.cross(t)
    }

    /// A world-space offset from the centre in the sphere's own frame.
    #[inline]
    pub fn to_local(&self, d: Vec3) -> Vec3 {
        let l = self.rotate(d, -1.0);
        Vec3::new(l.x * self.mirror, l.y, l.z)
    }

    /// A direction of the sphere's own frame in world space.
    #[inline]
    pub fn to_world(&self, l: Vec3) -> Vec3 {
        self.rotate(Vec3::new(l.x * self.mirror, l.y, l.z), 1.0)
    }
}

/// Texture coordinates of a point `p` on the sphere `prim` (`uv` in its own frame).
#[inline]
pub fn uv_at(prim: &Primitive, p: Vec3) -> Vec2 {
    let centre = Vec3::new(prim.p0[0], prim.p0[1], prim.p0[2]);
    uv(Orientation::of(prim).to_local((p - centre) / prim.p1[0]))
}

/// `dp/du`, `dp/dv` at a point `p` on the sphere `prim` (`tangents` in its own frame, in world space).
#[inline]
pub fn tangents_at(prim: &Primitive, p: Vec3) -> (Vec3, Vec3) {
    let centre = Vec3::new(prim.p0[0], prim.p0[1], prim.p0[2]);
    let o = Orientation::of(prim);
    let (du, dv) = tangents(o.to_local((p - centre) / prim.p1[0]), prim.p1[0]);
    (o.to_world(du), o.to_world(dv))
}

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
