//! Warping uniform samples to distributions, with their densities.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::{Vec2, Vec3};
use crate::math::{safe_sqrt, INV_PI, PI};

/// Uniform point on the unit disk by Shirley–Chiu's concentric map (keeps strata compact).
pub fn square_to_concentric_disk(u: Vec2) -> Vec2 {
    let a = 2.0 * u.x - 1.0;
    let b = 2.0 * u.y - 1.0;
    if a == 0.0 && b == 0.0 {
        return Vec2::ZERO;
    }
    let (r, phi) =
        if a * a > b * b { (a, (PI / 4.0) * (b / a)) } else { (b, (PI / 2.0) - (PI / 4.0) * (a / b)) };
    Vec2::new(r * phi.cos(), r * phi.sin())
}

/// Cosine-weighted direction on the hemisphere around +z (Malley's method).
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = square_to_concentric_disk(u);
    let z = safe_sqrt(1.0 - d.x * d.x - d.y * d.y);
    Vec3::new(d.x, d.y, z)
}

#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    if cos_theta > 0.0 {
        cos_theta * INV_PI
    } else {
        0.0
    }
}

/// Uniform direction on the unit sphere.
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.y;
    let r = safe_sqrt(1.0 - z * z);
    let phi = 2.0 * PI * u.x;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `1 - cos θmax` of the cone subtended by a sphere with `sin² θmax = sin2_max`, without the
/// cancellation that `1 - sqrt(1 - s)` suffers for tiny or distant spheres.
#[inline]
pub fn one_minus_cos_from_sin2(sin2_max: f32) -> f32 {
    sin2_max / (1.0 + safe_sqrt(1.0 - sin2_max))
}

/// Uniform direction inside the cone around +z with `1 - cos θmax = one_minus_cos_max`.
/// Parameterised by `1 - cos θ` so that very narrow cones keep full precision.
pub fn square_to_uniform_cone(u: Vec2, one_minus_cos_max: f32) -> Vec3 {
    let one_minus_cos = u.x * one_minus_cos_max;
    let cos_theta = 1.0 - one_minus_cos;
    let sin_theta = safe_sqrt(one_minus_cos * (2.0 - one_minus_cos));
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

#[inline]
pub fn uniform_cone_pdf(one_minus_cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * one_minus_cos_max)
}

/// Uniform barycentric coordinates (b1, b2) on a triangle.
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let su0 = safe_sqrt(u.x);
    Vec2::new(1.0 - su0, u.y * su0)
}

/// Power heuristic with β = 2 (Veach), written to stay finite when one pdf is huge or zero.
#[inline]
pub fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
    if pdf_a <= 0.0 {
        return 0.0;
    }
    if pdf_b <= 0.0 {
        return 1.0;
    }
    if pdf_b > f32::MAX {
        return 0.0;
    }
    let r = pdf_b / pdf_a;
    1.0 / (1.0 + r * r)
}

/// A point of [0, 1) with density proportional to the line from `a` at 0 to `b` at 1 (both ≥ 0),
/// by inverting its CDF `((2 − x)·a·x + b·x²) / (a + b)` in the form that stays accurate when `a`
/// or `b` is 0; `u` itself (uniform) when both are.
#[inline]
pub fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    let sum = a + b;
    if sum > 0.0 {
        let root = ((1.0 - u) * a * a + u * b * b).sqrt();
        (u * sum / (a + root)).min(0.99999994)
    } else {
        u
    }
}

/// The density `sample_linear` draws `x` with: `2·((1 − x)·a + x·b) / (a + b)`, or 1 when both are 0.
#[inline]
pub fn linear_pdf(x: f32, a: f32, b: f32) -> f32 {
    let sum = a + b;
    if sum > 0.0 {
        2.0 * ((1.0 - x) * a + x * b) / sum
    } else {
        1.0
    }
}

/// A sampled 1D table: the index of the chosen bin and the position inside it, rescaled to [0, 1).
#[derive(Clone, Copy)]
pub struct TableSample {
    pub index: u32,
    pub remapped: f32,
}

/// Samples a piecewise-constant distribution given its inclusive CDF `cdf[0..n]` (cdf[n-1] = 1) by
/// binary search; the sample is remapped so that it can be reused inside the chosen bin.
pub fn sample_cdf(cdf: &[f32], first: u32, count: u32, u: f32) -> TableSample {
    let mut lo = 0u32;
    let mut hi = count - 1;
    while lo < hi {
        let mid = (lo + hi) / 2;
        if cdf[(first + mid) as usize] <= u {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    let prev = if lo == 0 { 0.0 } else { cdf[(first + lo - 1) as usize] };
    let width = cdf[(first + lo) as usize] - prev;
    let remapped = if width > 0.0 { ((u - prev) / width).clamp(0.0, 0.99999994) } else { 0.5 };
    TableSample { index: lo, remapped }
}
