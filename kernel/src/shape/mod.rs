//! Geometric primitives: ray intersection and the surface record of a hit.
pub mod disk;
pub mod sphere;
pub mod triangle;

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::layout::{
    Primitive, TriangleAttributes, NONE, PRIM_DISK, PRIM_FLAG_FLIP, PRIM_FLAG_SMOOTH, PRIM_SPHERE,
};
use crate::math::vec3;

/// The nearest hit found so far: distance, primitive and its parametric coordinates
/// (barycentrics b1, b2 for triangles; unused for spheres), and the instance it lies in (where its
/// transforms start in `tables`; `NONE` outside instances: `instancing`).
#[derive(Clone, Copy)]
pub struct Hit {
    pub t: f32,
    pub prim: u32,
    pub uv: Vec2,
    pub instance: u32,
}

/// Intersects one primitive, returning `(t, uv)` inside the ray's interval.
#[inline]
pub fn intersect(prim: &Primitive, ray: &Ray, shear: &triangle::RayShear, t_max: f32) -> Option<(f32, Vec2)> {
    if prim.kind == PRIM_SPHERE {
        sphere::intersect(vec3(prim.p0), prim.p1[0], ray, t_max)
    } else if prim.kind == PRIM_DISK {
        disk::intersect(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2), ray, t_max)
    } else {
        triangle::intersect_sheared(vec3(prim.p0), vec3(prim.p1), vec3(prim.p2), shear.get(ray), ray, t_max)
    }
}

/// What the integrator needs to know about a surface point.
#[derive(Clone, Copy)]
pub struct SurfacePoint {
    pub p: Vec3,
    /// Geometric normal, facing the shape's outside (after `flip_normals`).
    pub ng: Vec3,
    /// Shading normal, on the same side as `ng`.
    pub ns: Vec3,
    /// Size of the primitive's own coordinates (a sphere's radius, a triangle's largest vertex
    /// coordinate): the rounding error of `p` grows with it as well as with `|p|`.
    pub error_scale: f32,
    /// `Primitive::offset_floor`: the offset's absolute part.
    pub offset_floor: f32,
    /// Texture coordinates (Mitsuba's conventions per shape).
    pub uv: Vec2,
    /// A triangle's `TriangleAttributes::mesh_attributes` (`NONE` on other shapes).
    pub mesh_attributes: u32,
    /// The hit's barycentrics b1, b2 on a triangle (mesh attributes are interpolated by them).
    pub bary: Vec2,
}

impl SurfacePoint {
    /// Where textures are looked up at this point.
    #[inline]
    pub fn lookup(&self) -> crate::texture::Lookup {
        crate::texture::Lookup { uv: self.uv, mesh_attributes: self.mesh_attributes, bary: self.bary }
    }
}

/// Reconstructs the surface point of a hit.
pub fn surface_point(
    prim: &Primitive,
    attributes: &[TriangleAttributes],
    hit: &Hit,
    ray: &Ray,
) -> SurfacePoint {
    let flip = if prim.flags & PRIM_FLAG_FLIP != 0 { -1.0 } else { 1.0 };
    if prim.kind == PRIM_SPHERE {
        let centre = vec3(prim.p0);
        let p = sphere::reproject(centre, prim.p1[0], ray.origin + ray.dir * hit.t);
        let n = (p - centre).normalize() * flip;
        let error_scale = prim.p1[0];
        let uv = sphere::uv_at(prim, p);
        return SurfacePoint {
            p,
            ng: n,
            ns: n,
            error_scale,
            offset_floor: prim.offset_floor,
            uv,
            mesh_attributes: NONE,
            bary: Vec2::ZERO,
        };
    }
    if prim.kind == PRIM_DISK {
        let (c, u, v) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
        let n = u.cross(v).normalize() * flip;
        let error_scale = c.abs().max_element().max(u.abs().max_element()).max(v.abs().max_element());
        return SurfacePoint {
            p: disk::point(c, u, v, hit.uv),
            ng: n,
            ns: n,
            error_scale,
            offset_floor: prim.offset_floor,
            uv: disk::uv(hit.uv),
            mesh_attributes: NONE,
            bary: Vec2::ZERO,
        };
    }
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    let b0 = 1.0 - hit.uv.x - hit.uv.y;
    let p = p0 * b0 + p1 * hit.uv.x + p2 * hit.uv.y;
    let ng = (p1 - p0).cross(p2 - p0).normalize() * flip;
    let mut ns = ng;
    let attr = attributes[hit.prim as usize];
    let uv = Vec2::from(attr.uv0) * b0 + Vec2::from(attr.uv1) * hit.uv.x + Vec2::from(attr.uv2) * hit.uv.y;
    if prim.flags & PRIM_FLAG_SMOOTH != 0 {
        let n = attr;
        let interpolated = vec3(n.n0) * b0 + vec3(n.n1) * hit.uv.x + vec3(n.n2) * hit.uv.y;
        if interpolated.length_squared() > 0.0 {
            ns = interpolated.normalize() * flip;
        }
    }
    let error_scale = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
    SurfacePoint {
        p,
        ng,
        ns,
        error_scale,
        offset_floor: prim.offset_floor,
        uv,
        mesh_attributes: attr.mesh_attributes,
        bary: hit.uv,
    }
}

/// `dp/du` and `dp/dv` at a hit (Mitsuba's parametrisation of each shape; a triangle's from its
/// texture coordinates, which are the barycentric default when the mesh has none, so that its
/// `dp/du` is then `p1 − p0` as Mitsuba's). Only normal and bump mapping ask for them.
pub fn tangents(
    prim: &Primitive,
    attributes: &[TriangleAttributes],
    hit: &Hit,
    sp: &SurfacePoint,
) -> (Vec3, Vec3) {
    if prim.kind == PRIM_SPHERE {
        return sphere::tangents_at(prim, sp.p);
    }
    if prim.kind == PRIM_DISK {
        return disk::tangents(vec3(prim.p1), vec3(prim.p2), hit.uv);
    }
    let a = attributes[hit.prim as usize];
    triangle::tangents(
        [vec3(prim.p0), vec3(prim.p1), vec3(prim.p2)],
        [Vec2::from(a.uv0), Vec2::from(a.uv1), Vec2::from(a.uv2)],
    )
}

/// Ray origins leave surfaces by `(f + max(|p|∞, the primitive's own coordinates)) · RAY_EPSILON`
/// (`offset_scale`), relative to the magnitudes whose rounding a hit point carries (a point
/// interpolated from a triangle's vertices, or reprojected onto a sphere, is off its surface by a
/// few roundings of the largest of them) plus `f`, the scene's size up to 1 (`Primitive::offset_floor`).
/// For scenes of size 1 and more this is Mitsuba's `(1 + |p|∞) · 1500 · 2⁻²⁴`; below, its absolute
/// 8.9e-5 shrinks with the scene (in a box scaled by 1e-4 it was larger than every feature: single
/// pixels off by |z| 29; now the box renders the unit box's image at any scale down to 1e-4).
/// The factor and the absolute part stay Mitsuba's, far above the rounding bound (pbrt's is about
/// 7 · 2⁻²⁴ for a triangle's point): rays leaving near-tangentially (a shading normal tilted from the
/// facet) re-hit neighbouring facets with smaller offsets, and the smooth-shaded diamond furnace
/// (Mitsuba 1.0000) came out 0.9982 without the absolute part, 0.9971 at 64 · 2⁻²⁴ of |p|, and 0.9970
/// at 1500 · 2⁻²⁴ of the triangle's longest edge plus 64 · 2⁻²⁴ of |p|. Where a shape's size comes
/// near the offset at its distance from the origin, the host warns at load time
/// (the host's `precision` module).
pub const RAY_EPSILON: f32 = 1500.0 / 16_777_216.0;

/// The size whose rounding errors a point `p` on a primitive of coordinates up to `error_scale`
/// carries, plus the offset's absolute part `floor`; the ray offset is `RAY_EPSILON` times it.
#[inline]
pub fn offset_scale(p: Vec3, error_scale: f32, floor: f32) -> f32 {
    floor + p.abs().max_element().max(error_scale)
}

/// Moves a ray origin off a surface along its geometric normal, towards the side `dir` leaves by, so
/// that the new ray does not re-hit the surface it starts on (by `RAY_EPSILON · offset_scale`).
#[inline]
pub fn offset_origin(sp: &SurfacePoint, ng: Vec3, dir: Vec3) -> Vec3 {
    let p = sp.p;
    let eps = offset_scale(p, sp.error_scale, sp.offset_floor) * RAY_EPSILON;
    if ng.dot(dir) >= 0.0 {
        p + ng * eps
    } else {
        p - ng * eps
    }
}
