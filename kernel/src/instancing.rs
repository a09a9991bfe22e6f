//! Two-level traversal for Mitsuba's `shapegroup` + `instance` (`features::INSTANCING`): a
//! shapegroup's primitives are stored once, under their own BVH (a BLAS, nodes and primitives after
//! the scene's own in the same buffers), and a BVH over instances (the TLAS, from node 0) has
//! `PRIM_INSTANCE` leaves that name a BLAS root and their transforms in `tables`
//! (`layout::Primitive`); the scene's own shapes are one more BLAS, placed without a transform, so
//! that the intersection code is inlined once (the host's `instance_buffers` lays them out).
//! At an instance, the ray moves into the group's space and the BLAS is walked; the direction is
//! transformed but not renormalized, so that `t` means the same point in both spaces (also under a
//! non-uniform scale) and hits compare with the world's directly. Hits in an instance carry its
//! transforms (`Hit::instance`); `surface_point` and `tangents` take them back to the world.
//! Instanced groups hold triangles and disks (the host flattens spheres, whose intersection assumes
//! a unit direction, and emitters are refused in groups).
use crate::bvh::{intersect_aabb, Accel, MISS, STACK_SIZE};
use crate::camera::Ray;
use crate::glam::{Vec2, Vec3, Vec4};
use crate::layout::{Primitive, SceneView, NONE};
use crate::shape::{self, Hit, SurfacePoint};

/// Floats of one instance's record in `tables`: the rows of its world→object and object→world
/// affine maps (3×4 each).
pub const INSTANCE_FLOATS: u32 = 24;

/// One instance's affine maps, read from `tables` at `offset`.
#[derive(Clone, Copy)]
struct Transforms {
    to_object: [Vec4; 3],
    to_world: [Vec4; 3],
}

impl Transforms {
    /// (No closure for the rows: one capturing `offset` was a pointer in a struct, which SPIR-V's
    /// logical addressing refuses.)
    #[inline]
    fn load(tables: &[f32], offset: u32) -> Self {
        Transforms {
            to_object: [row(tables, offset), row(tables, offset + 4), row(tables, offset + 8)],
            to_world: [row(tables, offset + 12), row(tables, offset + 16), row(tables, offset + 20)],
        }
    }
}

#[inline]
fn row(tables: &[f32], o: u32) -> Vec4 {
    let o = o as usize;
    Vec4::new(tables[o], tables[o + 1], tables[o + 2], tables[o + 3])
}

#[inline]
fn point(rows: &[Vec4; 3], p: Vec3) -> Vec3 {
    let h = p.extend(1.0);
    Vec3::new(rows[0].dot(h), rows[1].dot(h), rows[2].dot(h))
}

#[inline]
fn vector(rows: &[Vec4; 3], v: Vec3) -> Vec3 {
    Vec3::new(rows[0].truncate().dot(v), rows[1].truncate().dot(v), rows[2].truncate().dot(v))
}

/// A normal of the group's space in the world: by the inverse transpose of object→world, which is
/// the transpose of world→object. Under a mirror this keeps outward normals outward, as Mitsuba
/// (and the flattened geometry, whose winding the host reverses) does.
#[inline]
fn normal(rows: &[Vec4; 3], n: Vec3) -> Vec3 {
    (rows[0].truncate() * n.x + rows[1].truncate() * n.y + rows[2].truncate() * n.z).normalize()
}

/// The ray in the group's space: same `t` for the same point.
#[inline]
fn ray_to_object(x: &Transforms, ray: &Ray) -> Ray {
    Ray { origin: point(&x.to_object, ray.origin), dir: vector(&x.to_object, ray.dir), ..*ray }
}

/// The children of inner node `node` to visit: the nearer hit one, and the farther when both boxes
/// are hit (else `NONE`); `(NONE, NONE)` when neither is. (Returned, not pushed here: each walk
/// keeps its stack to itself.)
#[inline]
fn descend(accel: &Accel, node: u32, ray: &Ray, inv_dir: Vec3, best_t: f32) -> (u32, u32) {
    let left = accel.nodes[node as usize].first;
    let right = left + 1;
    let t_left = intersect_aabb(&accel.nodes[left as usize], ray.origin, inv_dir, ray.t_min, best_t);
    let t_right = intersect_aabb(&accel.nodes[right as usize], ray.origin, inv_dir, ray.t_min, best_t);
    let (hit_left, hit_right) = (t_left != MISS, t_right != MISS);
    if hit_left && hit_right {
        if t_left <= t_right {
            (left, right)
        } else {
            (right, left)
        }
    } else if hit_left {
        (left, NONE)
    } else if hit_right {
        (right, NONE)
    } else {
        (NONE, NONE)
    }
}

/// `Accel::trace` in a scene with instances: the TLAS, whose leaves are all `PRIM_INSTANCE`s, each
/// walked in its group's space (the scene's own shapes' as they are: `flags` is `NONE`).
pub fn trace(accel: &Accel, ray: &Ray, any_hit: bool, skip: u32) -> Option<Hit> {
    let inv_dir = Vec3::ONE / ray.dir;
    let mut stack = [0u32; STACK_SIZE];
    let mut top = 0usize;
    let mut best = Hit { t: ray.t_max, prim: NONE, uv: Vec2::ZERO, instance: NONE };
    if intersect_aabb(&accel.nodes[0], ray.origin, inv_dir, ray.t_min, best.t) == MISS {
        return None;
    }
    let mut node_index = 0u32;
    loop {
        let node = accel.nodes[node_index as usize];
        if node.prim_count > 0 {
            let mut i = node.first;
            while i < node.first + node.prim_count {
                let instance: Primitive = accel.prims[i as usize];
                let mut local = *ray;
                if instance.flags != NONE {
                    local = ray_to_object(&Transforms::load(accel.tables, instance.flags), ray);
                }
                if let Some(h) = crate::bvh::walk(accel, instance.material, &local, any_hit, skip, best.t) {
                    best = Hit { instance: instance.flags, ..h };
                    if any_hit {
                        return Some(best);
                    }
                }
                i += 1;
            }
        } else {
            let (next, later) = descend(accel, node_index, ray, inv_dir, best.t);
            if later != NONE && top < STACK_SIZE {
                stack[top] = later;
                top += 1;
            }
            if next != NONE {
                node_index = next;
                continue;
            }
        }
        if top == 0 {
            break;
        }
        top -= 1;
        node_index = stack[top];
    }
    if best.prim == NONE {
        None
    } else {
        Some(best)
    }
}

/// `shape::surface_point` of any hit: one in an instance is reconstructed in the group's space and
/// moved to the world (point, normals; the rounding size grows with the map's scale and offset).
pub fn surface_point(scene: &SceneView, prim: &Primitive, hit: &Hit, ray: &Ray) -> SurfacePoint {
    let instanced = crate::features::has(scene.features, crate::features::INSTANCING) && hit.instance != NONE;
    // One call of `shape::surface_point` for both cases (each call inlines all of it in SPIR-V).
    let mut local_ray = *ray;
    if instanced {
        local_ray = ray_to_object(&Transforms::load(scene.tables, hit.instance), ray);
    }
    let local = shape::surface_point(prim, scene.attributes, hit, &local_ray);
    if !instanced {
        return local;
    }
    let x = Transforms::load(scene.tables, hit.instance);
    let w = &x.to_world;
    let scale = w[0]
        .truncate()
        .abs()
        .dot(Vec3::ONE)
        .max(w[1].truncate().abs().dot(Vec3::ONE))
        .max(w[2].truncate().abs().dot(Vec3::ONE));
    let offset = Vec3::new(w[0].w, w[1].w, w[2].w).abs().max_element();
    SurfacePoint {
        p: point(w, local.p),
        ng: normal(&x.to_object, local.ng),
        ns: normal(&x.to_object, local.ns),
        error_scale: local.error_scale * scale + offset,
        ..local
    }
}

/// `shape::tangents` of any hit: dp/du and dp/dv of a hit in an instance are those of the group's
/// space moved by the linear part of object→world (exact: they are linear in the vertices).
/// `sp` is only read for spheres, which are never instanced.
pub fn tangents(scene: &SceneView, prim: &Primitive, hit: &Hit, sp: &SurfacePoint) -> (Vec3, Vec3) {
    let (du, dv) = shape::tangents(prim, scene.attributes, hit, sp);
    if !(crate::features::has(scene.features, crate::features::INSTANCING) && hit.instance != NONE) {
        return (du, dv);
    }
    let x = Transforms::load(scene.tables, hit.instance);
    (vector(&x.to_world, du), vector(&x.to_world, dv))
}
