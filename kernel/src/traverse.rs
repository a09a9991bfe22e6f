//! Ray queries against a scene (`Accel::trace`, `Accel::occluded`): each picks the walk for the
//! scene's acceleration structure, the two-level one of `instancing` where the scene has instances,
//! `wide_bvh`'s for a 4-wide BVH (the CPU's), else `bvh::walk`. All three intersect leaves through
//! `bvh::intersect_leaf`; this module sits above them, so none of them depends on another but `bvh`.
use crate::bvh::{self, Accel};
use crate::camera::Ray;
use crate::features;
use crate::shape::Hit;

impl Accel<'_> {
    /// Closest hit along the ray, or `None`. With `any_hit`, returns the first hit found (shadow rays).
    /// Primitive `skip` (or none, with `NONE`) is ignored.
    #[inline]
    pub fn trace(&self, ray: &Ray, any_hit: bool, skip: u32) -> Option<Hit> {
        if features::has(self.features, features::INSTANCING) {
            return crate::instancing::trace(self, ray, any_hit, skip);
        }
        // (The GPU never walks a wide BVH: the host sets `wide` for the CPU alone.)
        #[cfg(not(target_arch = "spirv"))]
        if self.wide {
            return crate::wide_bvh::trace(self, ray, any_hit, skip);
        }
        bvh::walk(self, 0, ray, any_hit, skip, ray.t_max)
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
