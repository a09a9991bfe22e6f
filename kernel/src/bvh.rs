//! The scene's BVH as the kernel reads it (`Accel`), the slab test, the one loop over a leaf's
//! primitives that every walk shares (`intersect_leaf`), and the BVH2 walk with a fixed-size stack
//! (no recursion on the GPU). Which walk a ray takes is `traverse`'s choice.

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::layout::{BvhNode, Primitive, SceneView, NONE};
use crate::math::vec3;
use crate::shape::triangle::RayShear;
use crate::shape::{self, Hit};
use spirv_std::arch::IndexUnchecked;

/// Distance reported for a missed box. (naga rejects infinite float literals, so no `f32::INFINITY`.)
pub(crate) const MISS: f32 = f32::MAX;

/// Depth of the traversal stack. The host rejects BVHs deeper than this, so it never overflows.
pub const STACK_SIZE: usize = 48;

/// Slab test; returns the entry distance, or `MISS` when the box is missed. A ray parallel to an axis
/// in the plane of a face makes that slab's distance 0 · ∞ = NaN: on the CPU the box is then entered
/// through its upper face and not its lower one (`tests/tests/wide_bvh.rs`; `wide_bvh` enters both).
#[inline]
pub(crate) fn intersect_aabb(node: &BvhNode, origin: Vec3, inv_dir: Vec3, t_min: f32, t_max: f32) -> f32 {
    let t0 = (vec3(node.min) - origin) * inv_dir;
    let t1 = (vec3(node.max) - origin) * inv_dir;
    let near = t0.min(t1).max_element().max(t_min);
    let far = t0.max(t1).min_element().min(t_max);
    // The factor makes the test conservative against rounding in the slab distances.
    if near <= far * 1.000_000_4 {
        near
    } else {
        MISS
    }
}

/// The BVH and primitive buffers of a scene, with the instances' transforms (in `tables`) and the
/// scene's feature bits (`features::INSTANCING` picks the two-level traversal). Its ray queries,
/// `trace` and `occluded`, are `traverse`'s.
#[derive(Clone, Copy)]
pub struct Accel<'a> {
    pub nodes: &'a [BvhNode],
    pub prims: &'a [Primitive],
    pub tables: &'a [f32],
    pub features: u32,
    /// `nodes` is a 4-wide BVH (`wide_bvh`; never with instances).
    pub wide: bool,
}

impl<'a> Accel<'a> {
    #[inline]
    pub fn of(scene: &SceneView<'a>) -> Self {
        Accel {
            nodes: scene.nodes,
            prims: scene.prims,
            tables: scene.tables,
            features: scene.features,
            wide: scene.wide_bvh,
        }
    }
}

/// The BVH2 walk from node `root` (a scene's BVH at 0, an instanced group's at its root) for the
/// closest hit nearer than `t_max` (the first found, with `any_hit`), primitive `skip` ignored:
/// `Accel::trace` without instances or a wide BVH, and each instance's walk of its group.
///
/// The walk reads the buffers without bounds checks: every child index and leaf range of a BVH
/// lies inside its buffers (the host's `prepare::bvh` checks each tree it builds, instanced
/// groups included), and the stack is pushed only below `STACK_SIZE`. (A check is a compare and a
/// branch per read, five reads per inner node, in the loop where the GPU spends most of its time.)
#[inline]
pub(crate) fn walk(accel: &Accel, root: u32, ray: &Ray, any_hit: bool, skip: u32, t_max: f32) -> Option<Hit> {
    let inv_dir = Vec3::ONE / ray.dir;
    let shear = shape::triangle::RayShear::of(ray);
    let mut stack = [0u32; STACK_SIZE];
    let mut top = 0usize;
    let mut node_index = root;
    let mut best = Hit { t: t_max, prim: NONE, uv: Vec2::ZERO, instance: NONE };
    // Not `is_empty()`: in rust-gpu 0.11 it grew the SPIR-V by 220 KB (measured).
    #[allow(clippy::len_zero)]
    if accel.nodes.len() == 0
        || intersect_aabb(&accel.nodes[root as usize], ray.origin, inv_dir, ray.t_min, best.t) == MISS
    {
        return None;
    }
    loop {
        // SAFETY: node indices are the root and children, inside `nodes` (see above).
        let node = unsafe { *accel.nodes.index_unchecked(node_index as usize) };
        if node.prim_count > 0 {
            if intersect_leaf(accel.prims, node.first, node.prim_count, ray, &shear, skip, any_hit, &mut best)
            {
                return Some(best);
            }
        } else {
            let left = node.first;
            let right = node.first + 1;
            // SAFETY: children lie inside `nodes` (see above).
            let (left_node, right_node) = unsafe {
                (accel.nodes.index_unchecked(left as usize), accel.nodes.index_unchecked(right as usize))
            };
            let t_left = intersect_aabb(left_node, ray.origin, inv_dir, ray.t_min, best.t);
            let t_right = intersect_aabb(right_node, ray.origin, inv_dir, ray.t_min, best.t);
            let hit_left = t_left != MISS;
            let hit_right = t_right != MISS;
            if hit_left && hit_right {
                // Visit the nearer child first; the farther one waits on the stack.
                let (first, second) = if t_left <= t_right { (left, right) } else { (right, left) };
                if top < STACK_SIZE {
                    // SAFETY: `top < STACK_SIZE`.
                    unsafe { *stack.index_unchecked_mut(top) = second };
                    top += 1;
                }
                node_index = first;
                continue;
            } else if hit_left {
                node_index = left;
                continue;
            } else if hit_right {
                node_index = right;
                continue;
            }
        }
        if top == 0 {
            break;
        }
        top -= 1;
        // SAFETY: `top` was pushed, so below `STACK_SIZE`.
        node_index = unsafe { *stack.index_unchecked(top) };
    }
    if best.prim == NONE {
        None
    } else {
        Some(best)
    }
}

/// Intersects `ray` with the leaf's primitives `first .. first + count` (but `skip`), narrowing
/// `best` to each hit nearer than its `t`; true as soon as one is found with `any_hit` (`best` is
/// then that hit). The one leaf loop of every walk: BVH2's, the wide BVH's and instanced groups'.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn intersect_leaf(
    prims: &[Primitive],
    first: u32,
    count: u32,
    ray: &Ray,
    shear: &RayShear,
    skip: u32,
    any_hit: bool,
    best: &mut Hit,
) -> bool {
    let mut i = first;
    let end = first + count;
    while i < end {
        if i != skip {
            // SAFETY: leaf ranges lie inside `prims` (the host checks every tree it builds).
            let prim = unsafe { prims.index_unchecked(i as usize) };
            if let Some((t, uv)) = shape::intersect(prim, ray, shear, best.t) {
                *best = Hit { t, prim: i, uv, instance: NONE };
                if any_hit {
                    return true;
                }
            }
        }
        i += 1;
    }
    false
}
