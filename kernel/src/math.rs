//! Small numeric helpers that behave the same on both backends.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::Vec3;

pub const PI: f32 = core::f32::consts::PI;
pub const INV_PI: f32 = 1.0 / PI;
pub const INV_2PI: f32 = 0.5 / PI;
pub const INV_4PI: f32 = 0.25 / PI;

/// `sqrt(max(x, 0))`: rounding can push an argument that is mathematically ≥ 0 slightly below.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

#[inline]
pub fn sqr(x: f32) -> f32 {
    x * x
}

#[inline]
pub fn max_component(v: Vec3) -> f32 {
    v.x.max(v.y).max(v.z)
}

/// The largest magnitude of the components: path throughputs may have a negative channel once they
/// carry a wavelength (`wavelength`), and such a path still carries light.
#[inline]
pub fn max_abs_component(v: Vec3) -> f32 {
    v.x.abs().max(v.y.abs()).max(v.z.abs())
}

/// Whether `x` is neither NaN nor infinite. Not `f32::is_finite` (it compares with an infinite
/// constant, and naga rejects infinite and NaN literals) and not `x - x == 0` (NVIDIA's Vulkan compiler
/// was measured to get that wrong on the H100, darkening images through the MIS weights): a comparison
/// with the largest finite float is false for NaN and for both infinities.
#[inline]
pub fn is_finite(x: f32) -> bool {
    x.abs() <= f32::MAX
}

#[inline]
pub fn is_finite3(v: Vec3) -> bool {
    is_finite(v.x) && is_finite(v.y) && is_finite(v.z)
}

/// +1 or -1 by the sign bit's meaning for ordinary numbers (`f32::signum` has a NaN literal).
#[inline]
pub fn sign(x: f32) -> f32 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

#[inline]
pub fn vec3(a: [f32; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}
