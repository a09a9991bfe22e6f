//! BVH2 traversal with a fixed-size stack (no recursion on the GPU).

use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::layout::{BvhNode, Primitive, SceneView, NONE};
use crate::math::vec3;
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
/// scene's feature bits (`features::INSTANCING` picks the two-level traversal).
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

    /// Closest hit along the ray, or `None`. With `any_hit`, returns the first hit found (shadow rays).
    /// Primitive `skip` (or none, with `NONE`) is ignored. Scenes with instances take
    /// `instancing::trace`; a wide BVH, `wide_bvh::trace`; the rest, this one-level walk.
    ///
    /// The walk reads the buffers without bounds checks: every child index and leaf range of a BVH
    /// lies inside its buffers (the host's `buffers` module checks each tree it builds), and the stack is
    /// pushed only below `STACK_SIZE`. (A check is a compare and a branch per read, five reads per
    /// inner node, in the loop where the GPU spends most of its time.)
    pub fn trace(&self, ray: &Ray, any_hit: bool, skip: u32) -> Option<Hit> {
        if crate::features::has(self.features, crate::features::INSTANCING) {
            return crate::instancing::trace(self, ray, any_hit, skip);
        }
        if self.wide {
            return crate::wide_bvh::trace(self, ray, any_hit, skip);
        }
        let inv_dir = Vec3::ONE / ray.dir;
        let shear = shape::triangle::RayShear::of(ray);
        let mut stack = [0u32; STACK_SIZE];
        let mut top = 0usize;
        let mut node_index = 0u32;
        let mut best_t = ray.t_max;
        let mut best_prim = u32::MAX;
        let mut best_uv = Vec2::ZERO;
        // Not `is_empty()`: in rust-gpu 0.11 it grew the SPIR-V by 220 KB (measured).
        #[allow(clippy::len_zero)]
        if self.nodes.len() == 0
            || intersect_aabb(&self.nodes[0], ray.origin, inv_dir, ray.t_min, best_t) == MISS
        {
            return None;
        }
        loop {
            // SAFETY: node indices are the root and children, inside `nodes` (see above).
            let node = unsafe { *self.nodes.index_unchecked(node_index as usize) };
            if node.prim_count > 0 {
                let mut i = node.first;
                let end = node.first + node.prim_count;
                while i < end {
                    if i == skip {
                        i += 1;
                        continue;
                    }
                    // SAFETY: leaf ranges lie inside `prims` (see above).
                    let prim = unsafe { self.prims.index_unchecked(i as usize) };
                    if let Some((t, uv)) = shape::intersect(prim, ray, &shear, best_t) {
                        best_t = t;
                        best_prim = i;
                        best_uv = uv;
                        if any_hit {
                            return Some(Hit { t, prim: i, uv, instance: NONE });
                        }
                    }
                    i += 1;
                }
            } else {
                let left = node.first;
                let right = node.first + 1;
                // SAFETY: children lie inside `nodes` (see above).
                let (left_node, right_node) = unsafe {
                    (self.nodes.index_unchecked(left as usize), self.nodes.index_unchecked(right as usize))
                };
                let t_left = intersect_aabb(left_node, ray.origin, inv_dir, ray.t_min, best_t);
                let t_right = intersect_aabb(right_node, ray.origin, inv_dir, ray.t_min, best_t);
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
        if best_prim == u32::MAX {
            None
        } else {
            Some(Hit { t: best_t, prim: best_prim, uv: best_uv, instance: NONE })
        }
    }

    /// Whether anything but primitive `target` (the emitter a shadow ray aims at, or `NONE`) blocks the
    /// open segment of the ray. Ignoring the target makes the test independent of how exactly the
    /// sampled distance to it was computed: near-tangent rays to a sphere light, say, are
    /// ill-conditioned in distance, and a shortened segment could still reach the light itself.
    #[inline]
    pub fn occluded(&self, ray: &Ray, target: u32) -> bool {
        self.trace(ray, true, target).is_some()
    }
}
