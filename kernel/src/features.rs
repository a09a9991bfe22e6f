//! Per-scene specialization: one bit per optional code path (each BSDF model, each emitter kind,
//! textures, the direct integrator). The host sets the bits of what a scene uses; on the GPU the mask
//! is a specialization constant, so the driver compiles the kernel with the unused paths folded away
//! (fewer registers, higher occupancy) and a scene pays nothing for features it does not use. On the
//! CPU it is an ordinary value: the same branches are taken, so both backends still run one kernel.
//! A cleared bit only ever removes a path the scene cannot reach.
use crate::layout::{BSDF_BLEND, BSDF_PPLASTIC, BSDF_PRINCIPLED_THIN, LIGHT_ENVMAP, LIGHT_PROJECTOR};

/// Every path compiled in: every bit but `INSTANCING` and `DIRECT_INTEGRATOR`, which say how the
/// buffers are laid out and which per-pixel loop runs.
pub const ALL: u32 = !(INSTANCING | DIRECT_INTEGRATOR);

/// The bit of BSDF model `kind` (`BSDF_*`, bits 0–11).
#[inline]
pub const fn bsdf(kind: u32) -> u32 {
    1 << kind
}

/// The bit of a material record of kind `kind`: its model's (`BLEND` for a blend, `PPLASTIC` for
/// the model beyond bit 11).
#[inline]
pub const fn material(kind: u32) -> u32 {
    if kind == BSDF_BLEND {
        BLEND
    } else if kind == BSDF_PPLASTIC {
        PPLASTIC
    } else {
        bsdf(kind)
    }
}

/// The bit of emitter kind `kind` (`LIGHT_*`, bits 12–19; `LIGHT_PROJECTOR` takes the last).
#[inline]
pub const fn light(kind: u32) -> u32 {
    1 << (12 + kind)
}

/// Bitmap and checkerboard textures on BSDF parameters.
pub const TEXTURES: u32 = 1 << 20;
/// Mitsuba's `direct` integrator. Set exactly when the scene's integrator is `direct`, also under
/// `CAUSTIC_SPECIALIZE=0`: `render_pixel` chooses its loop by this bit alone, so that a kernel
/// specialised for `direct` leaves out the path tracer's loop, and one for `path` the direct one (the
/// regenerating path loop's registers cost `integrator_direct_both` 23% on the H100: BENCHMARKS.md,
/// "Pass length and path regeneration").
pub const DIRECT_INTEGRATOR: u32 = 1 << 21;
/// Light tracing (`ptracer`).
pub const LIGHT_TRACER: u32 = 1 << 22;
/// Dispersive dielectrics: paths carry a wavelength (`wavelength`).
pub const DISPERSION: u32 = 1 << 23;
/// Null interfaces, `mask` materials and thin dielectrics: paths and shadow rays cross surfaces
/// (`mask`).
pub const MASK: u32 = 1 << 24;
/// Shading frames follow dp/du: for normal and bump maps (`normalmap`, `bumpmap`: the BSDF is then
/// evaluated in a perturbed frame, `bsdf::perturb`) and for anisotropic roughness, which Mitsuba
/// orients along dp/du (`integrator::shading_frame`). Without it the frame's tangent is any one
/// (`Frame::from_normal`): isotropic models do not see it.
pub const TANGENT_FRAMES: u32 = 1 << 25;
/// `blendbsdf` records: a surface's BSDF is a weighted pair of models (`bsdf::blend`). (Bit 25 is
/// taken by tangent frames.)
pub const BLEND: u32 = 1 << 26;
/// Mitsuba's `pplastic` (`bsdf::pplastic`), whose kind lies past the models' bits.
pub const PPLASTIC: u32 = 1 << 27;
/// Emitters whose emission a texture modulates (`Light::texture`: textured area lights, spots with
/// an image, projectors' irradiance; `light::textured`).
pub const TEXTURED_EMISSION: u32 = 1 << 28;
/// Shapegroups stored once and placed by instances: traversal starts at a BVH over `PRIM_INSTANCE`
/// primitives (`instancing`). Without it, the one-level walk of `bvh` runs as it always did. Unlike
/// the other bits this one says how the buffers are laid out: the host sets it exactly when they are
/// two-level.
pub const INSTANCING: u32 = 1 << 29;
/// `mesh_attribute` textures on BSDF parameters: lookups read the hit triangle's attributes
/// (`texture::eval_at`).
pub const MESH_ATTRIBUTES: u32 = 1 << 30;
/// Mitsuba's `irradiancemeter` sensor: camera rays leave a shape's surface (`irradiance_meter`).
pub const IRRADIANCE_METER: u32 = 1 << 31;

// The kinds must fit their bit ranges.
const _: () = assert!(
    BSDF_PRINCIPLED_THIN < 12
        && BSDF_BLEND >= 12
        && BSDF_PPLASTIC >= 12
        && LIGHT_ENVMAP < 8
        && LIGHT_PROJECTOR < 8
);

#[inline]
pub fn has(features: u32, bits: u32) -> bool {
    features & bits != 0
}
