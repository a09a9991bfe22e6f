//! Traversal of a 4-wide BVH, laid out in the node buffer's own records (`BvhNode`), for the CPU.
//!
//! A *group* is four consecutive `BvhNode` records, group `g` at `4g .. 4g + 4`, group 0 the root's,
//! read as one `Group`: four children's bounds in rows of four lanes, then each child's `first` and
//! `prim_count`. A child is a leaf (`prim_count > 0`: primitives `first .. first + prim_count`), an
//! inner child (`prim_count == 0`: its own children are group `first`), or an empty slot
//! (`prim_count == 0`, `first == NONE`). The host collapses its BVH2 into groups (the host's
//! `wide_bvh` module) for the CPU backend, which sets `SceneView::wide_bvh`.
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
use crate::glam::Vec4;
#[cfg(not(target_arch = "spirv"))]
use crate::{
    bvh::{intersect_leaf, Accel},
    camera::Ray,
    glam::{Vec2, Vec3},
    layout::NONE,
    shape::{self, Hit},
};

/// Groups a wide BVH may nest (the root's group counts one): its stack then never overflows, since
/// a group pushes at most four children and pops one. The host keeps BVH2 for deeper trees.
pub const WIDE_DEPTH: usize = 24;
/// Entries of the traversal stack: three children left behind per level, and the last group's four.
pub const WIDE_STACK: usize = 3 * WIDE_DEPTH + 1;

/// The conservative factor of `bvh::intersect_aabb`, against rounding in the slab distances.
#[cfg(not(target_arch = "spirv"))]
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

/// A group as the walk reads it, in the four `BvhNode` records it occupies (128 bytes): its children's
/// bounds by axis, each a row of four lanes (`min` x, y, z, then `max` x, y, z), then their `first`s
/// and `prim_count`s. The host writes groups so (`prepare::wide_bvh::by_lane`): a row is one SSE
/// load where the records' layout took four scalar loads and three shuffles a row.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Group {
    pub bounds: [[f32; 4]; 6],
    pub first: [u32; 4],
    pub prim_count: [u32; 4],
}

/// A child waiting on the walk's stack: where its box is entered, and its `first` and `prim_count`.
#[cfg(not(target_arch = "spirv"))]
#[derive(Clone, Copy)]
struct Pending {
    t: f32,
    first: u32,
    prim_count: u32,
}

/// `Accel::trace` over a wide BVH (same arguments; the hits as the module says). The CPU's alone:
/// the GPU never sets `Accel::wide`, and the walk reads the node buffer as `Group`s.
#[cfg(not(target_arch = "spirv"))]
pub(crate) fn trace(accel: &Accel, ray: &Ray, any_hit: bool, skip: u32) -> Option<Hit> {
    use core::mem::MaybeUninit;
    let groups: &[Group] = bytemuck::cast_slice(accel.nodes);
    // `+ 0.0` turns -0.0 into 0.0: a zero component's inverse is +∞ (see the slabs below).
    let inv_dir = Vec3::ONE / (ray.dir + Vec3::ZERO);
    let shear = shape::triangle::RayShear::of(ray);
    let (ox, oy, oz) = (Vec4::splat(ray.origin.x), Vec4::splat(ray.origin.y), Vec4::splat(ray.origin.z));
    let (ix, iy, iz) = (Vec4::splat(inv_dir.x), Vec4::splat(inv_dir.y), Vec4::splat(inv_dir.z));
    let t_min = Vec4::splat(ray.t_min);
    // Left uninitialised: only entries below `top` are read, each written first (zeroing the stack
    // was a `memset` call per ray, 1-2% of a render on one core).
    let mut stack = [const { MaybeUninit::<Pending>::uninit() }; WIDE_STACK];
    let mut top = 0usize;
    let mut best = Hit { t: ray.t_max, prim: NONE, uv: Vec2::ZERO, instance: NONE };
    let mut group = 0u32;
    loop {
        // SAFETY: every group a child names lies inside the buffer (the host's `wide_bvh` builds them so).
        let g = unsafe { groups.get_unchecked(group as usize) };
        let row = |i: usize| Vec4::from_array(g.bounds[i]);
        let (x0, x1) = ((row(0) - ox) * ix, (row(3) - ox) * ix);
        let (y0, y1) = ((row(1) - oy) * iy, (row(4) - oy) * iy);
        let (z0, z1) = ((row(2) - oz) * iz, (row(5) - oz) * iz);
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
        for lane in 0..4 {
            let t = near[lane];
            if g.first[lane] != NONE && t <= far[lane] {
                let child = Pending { t, first: g.first[lane], prim_count: g.prim_count[lane] };
                // SAFETY: at most `WIDE_STACK` entries (`WIDE_DEPTH`, checked by the host); entries
                // from `pushed_from` to `top` were written by this group.
                unsafe {
                    let mut i = top;
                    // Insertion: farther children sink below nearer ones.
                    while i > pushed_from && stack.get_unchecked(i - 1).assume_init_ref().t < t {
                        *stack.get_unchecked_mut(i) = *stack.get_unchecked(i - 1);
                        i -= 1;
                    }
                    stack.get_unchecked_mut(i).write(child);
                }
                top += 1;
            }
        }
        // Pop until an inner child: leaves are intersected on the way.
        loop {
            if top == 0 {
                return if best.prim == NONE { None } else { Some(best) };
            }
            top -= 1;
            // SAFETY: entry `top` was pushed.
            let child = unsafe { stack.get_unchecked(top).assume_init() };
            if child.t > best.t * SLACK {
                continue;
            }
            if child.prim_count == 0 {
                group = child.first;
                break;
            }
            if intersect_leaf(
                accel.prims,
                child.first,
                child.prim_count,
                ray,
                &shear,
                skip,
                any_hit,
                &mut best,
            ) {
                return Some(best);
            }
        }
    }
}
