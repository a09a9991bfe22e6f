//! Traversal of a 4-wide BVH, laid out in the node buffer's own records (`BvhNode`), for the CPU.
//!
//! A *group* is four consecutive `BvhNode`s, group `g` at `4g .. 4g + 4`, group 0 the root's. Each
//! record describes one child by its box: a leaf (`prim_count > 0`: primitives `first .. first +
//! prim_count`), an inner child (`prim_count == 0`: its own children are group `first`), or an empty
//! slot (`prim_count == 0`, `first == NONE`). The host collapses its BVH2 into this layout
//! (the host's `wide_bvh` module) for the CPU backend, which sets `SceneView::wide_bvh`.
//!
//! Why on the CPU: the scalar BVH2 walk was 71% of glass's time on one core (`perf` at 793e298,
//! `Accel::trace` and the triangle test). A group tests four boxes as the lanes of `Vec4`s (one SSE
//! instruction where BVH2 spent four scalar ones) and takes half the levels of BVH2's walk. Closest
//! hits pop children nearest first and skip those beyond the closest hit so far. On one core of the
//! 2-core developer machine, glass rendered 1.49× as fast as with BVH2, copper 1.35× (BENCHMARKS.md,
//! "A 4-wide BVH on the CPU"). The GPU keeps BVH2: its layouts were measured on the H100
//! (BENCHMARKS.md, "Three traversal and scheduling changes" and "All 23 scenes against Mitsuba, a
//! BVH layout that lost"); this one has not been yet (the entry points pass `wide_bvh: false`).
//!
//! The hits are BVH2's, with two exceptions, both measure-zero (`tests/tests/wide_bvh.rs`): of two
//! primitives at one distance, or at distances within the triangle test's rounding (coplanar
//! surfaces), either may be reported; and a ray parallel to an axis in the plane of a box's face
//! enters the box, where BVH2 enters it only through its upper face.
use crate::bvh::{intersect_leaf, Accel};
use crate::camera::Ray;
use crate::glam::{Vec2, Vec3, Vec4};
use crate::layout::{BvhNode, NONE};
use crate::shape::{self, Hit};
use spirv_std::arch::IndexUnchecked;

/// Groups a wide BVH may nest (the root's group counts one): its stack then never overflows, since
/// a group pushes at most four children and pops one. The host keeps BVH2 for deeper trees.
pub const WIDE_DEPTH: usize = 24;
/// Entries of the traversal stack: three children left behind per level, and the last group's four.
pub const WIDE_STACK: usize = 3 * WIDE_DEPTH + 1;

/// The conservative factor of `bvh::intersect_aabb`, against rounding in the slab distances.
const SLACK: f32 = 1.000_000_4;

/// `a` where `a < b`, else `b`: a NaN in either yields `b`. On x86-64 that is SSE's `minps`, which
/// glam's `min` is there: one instruction where the compare and select took four (SSE2 has no
/// blend), and 5% of glass on one core (measured). Elsewhere, the compare and select: NEON's `fmin`
/// keeps NaNs and SPIR-V's `FMin` leaves them undefined. (`kernel/tests/wide_bvh.rs` checks the NaN
/// cases on the machine that runs the tests.)
#[inline]
pub fn less_or(a: Vec4, b: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    return a.min(b);
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    return Vec4::select(a.cmplt(b), a, b);
}

/// `a` where `a > b`, else `b` (`maxps`, as `less_or`).
#[inline]
pub fn greater_or(a: Vec4, b: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    return a.max(b);
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    return Vec4::select(a.cmpgt(b), a, b);
}

#[inline]
fn lanes(a: &BvhNode, b: &BvhNode, c: &BvhNode, d: &BvhNode, axis: usize, max: bool) -> Vec4 {
    if max {
        Vec4::new(a.max[axis], b.max[axis], c.max[axis], d.max[axis])
    } else {
        Vec4::new(a.min[axis], b.min[axis], c.min[axis], d.min[axis])
    }
}

/// `Accel::trace` over a wide BVH (same arguments; the hits as the module says).
pub(crate) fn trace(accel: &Accel, ray: &Ray, any_hit: bool, skip: u32) -> Option<Hit> {
    // `+ 0.0` turns -0.0 into 0.0: a zero component's inverse is +∞ (see the slabs below).
    let inv_dir = Vec3::ONE / (ray.dir + Vec3::ZERO);
    let shear = shape::triangle::RayShear::of(ray);
    let (ox, oy, oz) = (Vec4::splat(ray.origin.x), Vec4::splat(ray.origin.y), Vec4::splat(ray.origin.z));
    let (ix, iy, iz) = (Vec4::splat(inv_dir.x), Vec4::splat(inv_dir.y), Vec4::splat(inv_dir.z));
    let t_min = Vec4::splat(ray.t_min);
    let mut slots = [0u32; WIDE_STACK];
    let mut entry = [0f32; WIDE_STACK];
    let mut top = 0usize;
    let mut best = Hit { t: ray.t_max, prim: NONE, uv: Vec2::ZERO, instance: NONE };
    let mut group = 0u32;
    loop {
        // The group's four boxes at once.
        let base = 4 * group as usize;
        // SAFETY: every group a slot names lies inside `nodes` (the host's `wide_bvh` builds them so).
        let (a, b, c, d) = unsafe {
            (
                accel.nodes.index_unchecked(base),
                accel.nodes.index_unchecked(base + 1),
                accel.nodes.index_unchecked(base + 2),
                accel.nodes.index_unchecked(base + 3),
            )
        };
        let (x0, x1) = ((lanes(a, b, c, d, 0, false) - ox) * ix, (lanes(a, b, c, d, 0, true) - ox) * ix);
        let (y0, y1) = ((lanes(a, b, c, d, 1, false) - oy) * iy, (lanes(a, b, c, d, 1, true) - oy) * iy);
        let (z0, z1) = ((lanes(a, b, c, d, 2, false) - oz) * iz, (lanes(a, b, c, d, 2, true) - oz) * iz);
        // Each axis's slab, from its nearer to its farther plane, joined into the ray's interval. A
        // ray parallel to an axis (inverse +∞) whose origin lies in a face's plane makes that face's
        // distance 0 · ∞ = NaN; the order of the operands drops it, so that axis constrains nothing
        // and the closed box is entered, as pbrt-v4 does. (BVH2's `intersect_aabb` enters it through
        // its upper face and not its lower one; this walk never misses what BVH2 finds.)
        let near =
            greater_or(less_or(z1, z0), greater_or(less_or(y1, y0), greater_or(less_or(x1, x0), t_min)));
        let far = less_or(
            greater_or(z0, z1),
            less_or(greater_or(y0, y1), less_or(greater_or(x0, x1), Vec4::splat(best.t))),
        );
        let (near, far) = (near.to_array(), (far * SLACK).to_array());
        // Push the children hit, then order the pushed ones so that the nearest is on top.
        let pushed_from = top;
        let mut lane = 0usize;
        while lane < 4 {
            // SAFETY: `lane < 4`, and `base + lane` is in the group read above.
            let (t, t_far, slot) = unsafe {
                (
                    *near.index_unchecked(lane),
                    *far.index_unchecked(lane),
                    accel.nodes.index_unchecked(base + lane),
                )
            };
            if slot.first != NONE && t <= t_far {
                // SAFETY: at most `WIDE_STACK` entries (`WIDE_DEPTH`, checked by the host).
                unsafe {
                    let mut i = top;
                    // Insertion: farther children sink below nearer ones.
                    while i > pushed_from && *entry.index_unchecked(i - 1) < t {
                        *entry.index_unchecked_mut(i) = *entry.index_unchecked(i - 1);
                        *slots.index_unchecked_mut(i) = *slots.index_unchecked(i - 1);
                        i -= 1;
                    }
                    *entry.index_unchecked_mut(i) = t;
                    *slots.index_unchecked_mut(i) = (base + lane) as u32;
                }
                top += 1;
            }
            lane += 1;
        }
        // Pop until an inner child: leaves are intersected on the way.
        loop {
            if top == 0 {
                return if best.prim == NONE { None } else { Some(best) };
            }
            top -= 1;
            // SAFETY: `top` was pushed.
            let (t, slot) = unsafe { (*entry.index_unchecked(top), *slots.index_unchecked(top)) };
            if t > best.t * SLACK {
                continue;
            }
            // SAFETY: pushed slots lie inside `nodes`.
            let node = unsafe { *accel.nodes.index_unchecked(slot as usize) };
            if node.prim_count == 0 {
                group = node.first;
                break;
            }
            if intersect_leaf(accel.prims, node.first, node.prim_count, ray, &shear, skip, any_hit, &mut best)
            {
                return Some(best);
            }
        }
    }
}
