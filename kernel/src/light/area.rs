//! Area emitters on flat primitives (triangles and disks), sampled uniformly by area.
use super::{area_sample_pdf, from_area_sample, LightSample};
use crate::glam::{Vec2, Vec3};
use crate::layout::{Light, Primitive, PRIM_DISK, PRIM_FLAG_FLIP, PRIM_SPHERE};
use crate::math::{vec3, PI};
use crate::sampling::square_to_uniform_sphere;
use crate::shape::{disk, triangle};

/// A point drawn uniformly by area on a primitive (`sample_position`). (`repr(C)`: fields in this
/// order, as naga wants them.)
#[repr(C)]
#[derive(Clone, Copy)]
pub struct PositionSample {
    pub p: Vec3,
    /// The unit normal of the front side (flipped by `PRIM_FLAG_FLIP`).
    pub n: Vec3,
    /// The primitive's area (the point's density is its inverse).
    pub area: f32,
    /// The coordinate magnitude whose rounding the point carries beyond `|p|` (a sphere's radius;
    /// `shape::offset_scale`).
    pub error_scale: f32,
}

/// A point uniformly distributed by area on a triangle, disk or sphere (`u` in [0, 1)²): where light
/// tracing starts on an area emitter (`emission`) and where an irradiance meter's rays start
/// (`crate::irradiance_meter`).
pub fn sample_position(prim: &Primitive, u: Vec2) -> PositionSample {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    if prim.kind == PRIM_SPHERE {
        let dir = square_to_uniform_sphere(u);
        let orientation = if prim.flags & PRIM_FLAG_FLIP != 0 { -1.0 } else { 1.0 };
        let r = prim.p1[0];
        return PositionSample {
            p: p0 + dir * r,
            n: dir * orientation,
            area: 4.0 * PI * r * r,
            error_scale: r,
        };
    }
    let p = if prim.kind == PRIM_DISK {
        disk::sample_point(p0, p1, p2, u)
    } else {
        triangle::sample_point(p0, p1, p2, u)
    };
    let (n, area) = normal_and_area(prim);
    PositionSample { p, n, area, error_scale: 0.0 }
}

/// The primitive's unnormalised normal (edge cross product, or `u × v` for a disk) and its area.
fn cross_and_area(prim: &Primitive) -> (Vec3, f32) {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    if prim.kind == PRIM_DISK {
        (p1.cross(p2), disk::area(p1, p2))
    } else {
        let c = (p1 - p0).cross(p2 - p0);
        (c, 0.5 * c.length())
    }
}

/// The emitting side's unit normal and the area.
pub(crate) fn normal_and_area(prim: &Primitive) -> (Vec3, f32) {
    let (c, area) = cross_and_area(prim);
    let n = c.normalize();
    let n = if prim.flags & PRIM_FLAG_FLIP != 0 { -n } else { n };
    (n, area)
}

pub fn sample(light: &Light, prim: &Primitive, p: Vec3, u: Vec2) -> LightSample {
    let (p0, p1, p2) = (vec3(prim.p0), vec3(prim.p1), vec3(prim.p2));
    let q = if prim.kind == PRIM_DISK {
        disk::sample_point(p0, p1, p2, u)
    } else {
        triangle::sample_point(p0, p1, p2, u)
    };
    let (n, area) = normal_and_area(prim);
    from_area_sample(light, p, q, n, area)
}

pub fn pdf(prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    // The area alone: MIS weights every emitter hit with this, so no normal is normalised for it.
    area_sample_pdf(cross_and_area(prim).1, p, hit_p, hit_n)
}
