//! Triangles: watertight intersection and uniform area sampling.
use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::sampling::square_to_uniform_triangle;

#[inline]
fn component(v: Vec3, axis: u32) -> f32 {
    if axis == 0 {
        v.x
    } else if axis == 1 {
        v.y
    } else {
        v.z
    }
}

/// The per-ray half of the watertight test: the axis along which the ray runs most (`kz`), the two
/// others, and the shear that maps the ray onto +z.
#[derive(Clone, Copy)]
pub struct Shear {
    kx: u32,
    ky: u32,
    kz: u32,
    sx: f32,
    sy: f32,
    sz: f32,
}

impl Shear {
    #[inline]
    pub fn of(d: Vec3) -> Self {
        let ad = d.abs();
        let mut kz = 0u32;
        if ad.y > ad.x {
            kz = 1;
        }
        if ad.z > component(ad, kz) {
            kz = 2;
        }
        let mut kx = if kz == 2 { 0 } else { kz + 1 };
        let mut ky = if kx == 2 { 0 } else { kx + 1 };
        let dz = component(d, kz);
        if dz < 0.0 {
            core::mem::swap(&mut kx, &mut ky);
        }
        Shear { kx, ky, kz, sx: component(d, kx) / dz, sy: component(d, ky) / dz, sz: 1.0 / dz }
    }
}

/// A ray's `Shear` through one traversal. The CPU computes it once per ray (two divisions and the
/// axis choice per triangle were 7% of glass on the 2-core developer machine: BENCHMARKS.md, "The
/// trial times whole passes"); the GPU again per triangle, where six more values live through the
/// traversal cost registers (hoisting it with the visited node lost 12–16% on the H100's mesh
/// scenes: BENCHMARKS.md, "Three traversal and scheduling changes").
#[derive(Clone, Copy)]
pub struct RayShear {
    #[cfg(not(target_arch = "spirv"))]
    shear: Shear,
}

impl RayShear {
    #[inline]
    pub fn of(ray: &Ray) -> Self {
        #[cfg(not(target_arch = "spirv"))]
        return RayShear { shear: Shear::of(ray.dir) };
        #[cfg(target_arch = "spirv")]
        {
            let _ = ray;
            RayShear {}
        }
    }

    #[inline]
    pub fn get(&self, ray: &Ray) -> Shear {
        #[cfg(not(target_arch = "spirv"))]
        {
            let _ = ray;
            self.shear
        }
        #[cfg(target_arch = "spirv")]
        Shear::of(ray.dir)
    }
}

/// Watertight ray/triangle intersection (Woop, Benthin, Wald 2013): rays through shared edges and
/// vertices never slip between adjacent triangles. Returns `(t, (b1, b2))`.
#[inline]
pub fn intersect_sheared(
    p0: Vec3,
    p1: Vec3,
    p2: Vec3,
    shear: Shear,
    ray: &Ray,
    t_max: f32,
) -> Option<(f32, Vec2)> {
    let Shear { kx, ky, kz, sx, sy, sz } = shear;
    let a = p0 - ray.origin;
    let b = p1 - ray.origin;
    let c = p2 - ray.origin;
    let (az, bz, cz) = (component(a, kz), component(b, kz), component(c, kz));
    let ax = component(a, kx) - sx * az;
    let ay = component(a, ky) - sy * az;
    let bx = component(b, kx) - sx * bz;
    let by = component(b, ky) - sy * bz;
    let cx = component(c, kx) - sx * cz;
    let cy = component(c, ky) - sy * cz;

    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if !(t > ray.t_min && t < t_max) {
        return None;
    }
    Some((t, Vec2::new(v * inv_det, w * inv_det)))
}

/// `dp/du`, `dp/dv` of a triangle with texture coordinates `uv0..uv2` (solving the 2×2 system of its
/// edges, as Mitsuba's meshes); where the uv triangle is degenerate, the tangents of
/// `Frame::from_normal` about the (unflipped) face normal, Mitsuba's fallback.
pub fn tangents(p: [Vec3; 3], uv: [Vec2; 3]) -> (Vec3, Vec3) {
    let (dp0, dp1) = (p[1] - p[0], p[2] - p[0]);
    let (duv0, duv1) = (uv[1] - uv[0], uv[2] - uv[0]);
    let det = duv0.x * duv1.y - duv0.y * duv1.x;
    if det == 0.0 {
        let f = crate::frame::Frame::from_normal(dp0.cross(dp1).normalize());
        return (f.s, f.t);
    }
    let inv = 1.0 / det;
    ((dp0 * duv1.y - dp1 * duv0.y) * inv, (dp1 * duv0.x - dp0 * duv1.x) * inv)
}

pub fn area(p0: Vec3, p1: Vec3, p2: Vec3) -> f32 {
    0.5 * (p1 - p0).cross(p2 - p0).length()
}

/// A uniformly distributed point on the triangle (density 1 / area).
pub fn sample_point(p0: Vec3, p1: Vec3, p2: Vec3, u: Vec2) -> Vec3 {
    let b = square_to_uniform_triangle(u);
    p0 * (1.0 - b.x - b.y) + p1 * b.x + p2 * b.y
}
