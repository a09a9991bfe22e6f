//! Mitsuba's `twosided` with two BSDFs: the front record (flag `MATERIAL_TWO_SIDED`) names the back's
//! record in its flags' high bits (`MATERIAL_BACK_SHIFT`: the index plus one, 0 for none; the record
//! has no spare word), and a hit seen from behind shades with the back's record, whose own
//! `MATERIAL_TWO_SIDED` makes `integrator::shading_frame` mirror its frame. The side is the one
//! `shading_frame` mirrors by, the geometric normal's against the arriving ray (Mitsuba decides by the
//! shading frame's cos θ; the two agree wherever the shading normal is on the geometric one's side),
//! so camera and light paths pick it alike: by the direction they arrive along.
use crate::glam::Vec3;
use crate::layout::{Material, SceneView, MATERIAL_BACK_SHIFT, MATERIAL_TWO_SIDED};
use crate::shape::SurfacePoint;

/// The material-list index of `m`'s back record plus one, 0 where it has none.
#[inline]
pub fn back_plus_one(m: &Material) -> u32 {
    m.flags >> MATERIAL_BACK_SHIFT
}

/// The index of the record that shades material `front` at `sp` for a ray arriving along `dir`: the
/// back's where `front` is a two-sided pair seen from behind, else `front`. An index rather than the
/// record: returning one of two 160-byte records by a runtime test cost scenes without pairs 5–10% on
/// the H100 (the spot light and gold; BENCHMARKS.md, "The path loop chosen per scene": the record was
/// then copied whole instead of read field by field where used).
#[inline]
pub fn seen(scene: &SceneView, front: u32, sp: &SurfacePoint, dir: Vec3) -> u32 {
    let flags = scene.materials[front as usize].flags;
    let back = flags >> MATERIAL_BACK_SHIFT;
    if flags & MATERIAL_TWO_SIDED != 0 && back != 0 && sp.ng.dot(dir) > 0.0 {
        return back - 1;
    }
    front
}
