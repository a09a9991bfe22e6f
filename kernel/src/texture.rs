//! Textures (Mitsuba `bitmap` and `checkerboard`), evaluated at a surface's texture coordinates, and
//! `mesh_attribute`, interpolated over the hit triangle (`eval_at`, behind `features::MESH_ATTRIBUTES`).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::{
    Texture, NONE, TEXTURE_BITMAP, TEXTURE_CHECKERBOARD, TEXTURE_MESH_ATTRIBUTE, TEXTURE_NEAREST,
    TEXTURE_WRAP_CLAMP, TEXTURE_WRAP_MIRROR, TEXTURE_WRAP_SHIFT,
};
use crate::math::vec3;
use crate::spectrum::{luminance, Rgb};
use core::num::NonZeroU32;
use spirv_std::arch::IndexUnchecked;

/// Where a texture is looked up: the surface's uv and, on a triangle, its mesh attributes' place in
/// `tables` (`NONE` without) and the hit's barycentrics b1, b2 (`SurfacePoint::lookup`).
#[derive(Clone, Copy)]
pub struct Lookup {
    pub uv: Vec2,
    pub mesh_attributes: u32,
    pub bary: Vec2,
}

impl Lookup {
    /// A lookup by uv alone (no mesh attributes).
    pub fn uv(uv: Vec2) -> Lookup {
        Lookup { uv, mesh_attributes: NONE, bary: Vec2::ZERO }
    }
}

/// `constant` where `texture` is `NONE`, else the texture's value at `at` (`eval_at`).
#[inline]
pub fn eval_or_at(
    textures: &[Texture],
    tables: &[f32],
    texture: u32,
    constant: Rgb,
    at: Lookup,
    features: u32,
) -> Rgb {
    if texture == NONE {
        constant
    } else {
        eval_at(&textures[texture as usize], tables, at, features)
    }
}

/// A texture's value at `at`: a `mesh_attribute` reads the hit triangle's attribute (in a scene
/// with `features::MESH_ATTRIBUTES`), any other texture its uv (`eval`).
#[inline]
pub fn eval_at(t: &Texture, tables: &[f32], at: Lookup, features: u32) -> Rgb {
    if features::has(features, features::MESH_ATTRIBUTES) && t.kind == TEXTURE_MESH_ATTRIBUTE {
        mesh_attribute(t, tables, at)
    } else {
        eval(t, tables, at.uv)
    }
}

/// Mitsuba's `mesh_attribute`: the corners' values blended by the barycentrics, times `scale`; black
/// off a triangle with attributes (the host refuses such scenes, so this is never reached there).
fn mesh_attribute(t: &Texture, tables: &[f32], at: Lookup) -> Rgb {
    if at.mesh_attributes == NONE {
        return Vec3::ZERO;
    }
    let base = (at.mesh_attributes + t.offset) as usize;
    let b0 = 1.0 - at.bary.x - at.bary.y;
    let value = rgb_at(tables, base) * b0
        + rgb_at(tables, base + 3) * at.bary.x
        + rgb_at(tables, base + 6) * at.bary.y;
    value * vec3([t.color0[0], t.color0[1], t.color0[2]])
}

/// Three floats of `tables` from `i`; black where they are not all inside it (which the host's
/// layout never makes): one range test instead of a bounds check per float, each of which the GPU
/// inlines with its panic path (`wrap` says what those cost). (A function, not a closure: naga
/// rejected the SPIR-V of a closure capturing `tables`, "Type '&[f32]' is invalid".)
#[inline]
fn rgb_at(tables: &[f32], i: usize) -> Rgb {
    if i + 2 < tables.len() {
        // SAFETY: `i + 2` is within `tables`, tested above.
        unsafe {
            Vec3::new(
                *tables.index_unchecked(i),
                *tables.index_unchecked(i + 1),
                *tables.index_unchecked(i + 2),
            )
        }
    } else {
        Vec3::ZERO
    }
}

/// A texture's value at texture coordinates `uv` (a `mesh_attribute` has none: black; the host
/// allows it only where `eval_at` looks it up).
pub fn eval(t: &Texture, tables: &[f32], uv: Vec2) -> Rgb {
    if t.kind == TEXTURE_MESH_ATTRIBUTE {
        return Vec3::ZERO;
    }
    let uv = apply_to_uv(t, uv);
    if t.kind == TEXTURE_CHECKERBOARD {
        checkerboard(t, uv)
    } else if t.flags & TEXTURE_NEAREST != 0 {
        bitmap_nearest(t, tables, uv)
    } else {
        bitmap_bilinear(t, tables, uv)
    }
}

#[inline]
fn apply_to_uv(t: &Texture, uv: Vec2) -> Vec2 {
    let (r0, r1) = (t.to_uv[0], t.to_uv[1]);
    Vec2::new(r0[0] * uv.x + r0[1] * uv.y + r0[2], r1[0] * uv.x + r1[1] * uv.y + r1[2])
}

/// Mitsuba's checkerboard: `color0` where the fractional parts of u and v are on the same side of ½.
fn checkerboard(t: &Texture, uv: Vec2) -> Rgb {
    let fu = uv.x - uv.x.floor();
    let fv = uv.y - uv.y.floor();
    if (fu > 0.5) == (fv > 0.5) {
        vec3([t.color0[0], t.color0[1], t.color0[2]])
    } else {
        vec3([t.color1[0], t.color1[1], t.color1[2]])
    }
}

/// Maps an integer texel coordinate into `[0, size)` by the texture's wrap mode, in arithmetic that
/// cannot panic. On the GPU every operation that may panic is a branch of its own, inlined at each
/// lookup: texture lookups made 26% of `bsdf_plastic_default`'s render entry point (the envmap's
/// bilinear lookups) and 48% of `bsdf_thindielectric_glass`'s, whose driver compile took 17 s on an
/// H200, half of it the code of `i32::rem_euclid` (a zero divisor, `MIN % -1`) and `i32::clamp` (its
/// bounds' order) (BENCHMARKS.md, "Where a scene's render entry point goes"). The values are
/// `rem_euclid`'s.
#[inline]
pub fn wrap(i: i32, size: u32, flags: u32) -> u32 {
    let n = size.max(1);
    let mode = (flags >> TEXTURE_WRAP_SHIFT) & 3;
    let w = if mode == TEXTURE_WRAP_CLAMP {
        i.max(0) as u32
    } else if mode == TEXTURE_WRAP_MIRROR {
        let period = euclid_rem(i, 2 * n);
        if period < n {
            period
        } else {
            2 * n - 1 - period
        }
    } else {
        euclid_rem(i, n)
    };
    w.min(n - 1)
}

/// `i.rem_euclid(n)` for `n >= 1`, as unsigned remainders (`rem`): for negative `i`, `!i` is
/// `-(i + 1)`, which cannot overflow.
#[inline]
fn euclid_rem(i: i32, n: u32) -> u32 {
    if i >= 0 {
        rem(i as u32, n)
    } else {
        n - 1 - rem(!i as u32, n)
    }
}

/// `a % n` for `n >= 1` (`a` itself for `n = 0`) by a divisor known not to be zero: no check, no
/// panic path (see `wrap`).
#[inline]
pub fn rem(a: u32, n: u32) -> u32 {
    match NonZeroU32::new(n) {
        Some(d) => a % d,
        None => a,
    }
}

/// Linear RGB of texel (x, y), row 0 at the image's top (v = 0) (black outside the tables: `rgb_at`).
#[inline]
pub fn texel(t: &Texture, tables: &[f32], x: u32, y: u32) -> Rgb {
    rgb_at(tables, (t.offset + 3 * (y * t.width + x)) as usize)
}

fn bitmap_nearest(t: &Texture, tables: &[f32], uv: Vec2) -> Rgb {
    let x = wrap((uv.x * t.width as f32).floor() as i32, t.width, t.flags);
    let y = wrap((uv.y * t.height as f32).floor() as i32, t.height, t.flags);
    texel(t, tables, x, y)
}

/// Bilinear interpolation between texel centres (texel x is centred on u = (x + ½) / width).
fn bitmap_bilinear(t: &Texture, tables: &[f32], uv: Vec2) -> Rgb {
    let px = uv.x * t.width as f32 - 0.5;
    let py = uv.y * t.height as f32 - 0.5;
    let (x0f, y0f) = (px.floor(), py.floor());
    let (fx, fy) = (px - x0f, py - y0f);
    let (x0, y0) = (x0f as i32, y0f as i32);
    let xa = wrap(x0, t.width, t.flags);
    let xb = wrap(x0 + 1, t.width, t.flags);
    let ya = wrap(y0, t.height, t.flags);
    let yb = wrap(y0 + 1, t.height, t.flags);
    let top = texel(t, tables, xa, ya) * (1.0 - fx) + texel(t, tables, xb, ya) * fx;
    let bottom = texel(t, tables, xa, yb) * (1.0 - fx) + texel(t, tables, xb, yb) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// Mitsuba's `eval_1_grad`: the gradient in (u, v) of the texture's luminance, the derivative of the
/// bilinear interpolation within the texel square holding `uv` (through `to_uv`: its transpose takes
/// the gradient back to the surface's uv). Nearest filtering and checkerboards are piecewise constant:
/// zero (Mitsuba's nearest lookup returns zero; its checkerboard has no gradient at all).
pub fn luminance_gradient(t: &Texture, tables: &[f32], uv: Vec2) -> Vec2 {
    if t.kind != TEXTURE_BITMAP || t.flags & TEXTURE_NEAREST != 0 {
        return Vec2::ZERO;
    }
    let st = apply_to_uv(t, uv);
    let px = st.x * t.width as f32 - 0.5;
    let py = st.y * t.height as f32 - 0.5;
    let (x0f, y0f) = (px.floor(), py.floor());
    let (fx, fy) = (px - x0f, py - y0f);
    let (x0, y0) = (x0f as i32, y0f as i32);
    let xa = wrap(x0, t.width, t.flags);
    let xb = wrap(x0 + 1, t.width, t.flags);
    let ya = wrap(y0, t.height, t.flags);
    let yb = wrap(y0 + 1, t.height, t.flags);
    let l = |x, y| luminance(texel(t, tables, x, y));
    let (f00, f10, f01, f11) = (l(xa, ya), l(xb, ya), l(xa, yb), l(xb, yb));
    // Per texel step; through `to_uv`'s transpose, then times the resolution, in Mitsuba's order (the
    // exact chain rule scales first: they differ only where `to_uv` mixes u and v on a non-square
    // texture).
    let dx = (1.0 - fy) * (f10 - f00) + fy * (f11 - f01);
    let dy = (1.0 - fx) * (f01 - f00) + fx * (f11 - f10);
    let (r0, r1) = (t.to_uv[0], t.to_uv[1]);
    let du = r0[0] * dx + r1[0] * dy;
    let dv = r0[1] * dx + r1[1] * dy;
    Vec2::new(du * t.width as f32, dv * t.height as f32)
}
