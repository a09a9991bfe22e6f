//! Normal and bump mapping (Mitsuba's `normalmap` and `bumpmap`): the shading frame at a hit follows
//! dp/du (Mitsuba's `sh_frame`), the map tilts its normal, and the material's own model is evaluated
//! in the tilted frame. Behaviour follows Mitsuba 3.9.1 where it is particular: light below the
//! tilted normal while above the untilted one (or the reverse) is dropped, `flip_invalid_normals`
//! mirrors a tilted normal that faces away from the viewer about the shading normal, and
//! `use_shadowing_function` multiplies Estevez et al.'s shadowing term ("A Microfacet-Based Shadowing
//! Function to Solve the Bump Terminator Problem", Ray Tracing Gems, 2019). Only scenes with the
//! `TANGENT_FRAMES` feature reach this code.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::frame::Frame;
use crate::glam::Vec3;
use crate::layout::*;
use crate::shape::SurfacePoint;
use crate::texture;

/// A tilted frame in the coordinates of the hit's shading frame. Flat and `repr(C)` with a size of
/// 64 bytes: naga rounds a struct holding a `Vec3` up to 16 bytes, so a nested `Frame` (36 bytes)
/// followed by another member was refused as overlapping ("member at 36 overlaps", on lavapipe).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct Perturbation {
    /// The frame the material's model works in (`s`, `t`, `nt`; its normal mirrored where a
    /// `twosided` inside the map shows its back).
    pub s: Vec3,
    pub t: Vec3,
    pub nt: Vec3,
    /// The tilted normal, never mirrored: the side test and the shadowing term use it.
    pub n: Vec3,
    /// `ACTIVE` (there is a map at all), `SHADOWING` (`use_shadowing_function`).
    pub flags: u32,
    pub _pad: [u32; 3],
}

/// What `integrator::shading_frame` finds at a hit: the shading frame (`s`, `t`, `n`), the geometric
/// normal on its side, the outgoing direction in it, and the tilt of a map (`Perturbation::NONE`
/// without one). Flat and `repr(C)` for the reason given at `Perturbation` (a tuple holding a
/// `Frame` was refused the same way).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct Shading {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
    pub ng: Vec3,
    pub wo: Vec3,
    pub tilt: Perturbation,
}

impl Shading {
    #[inline]
    pub fn new(frame: Frame, ng: Vec3, wo: Vec3, tilt: Perturbation) -> Shading {
        Shading { s: frame.s, t: frame.t, n: frame.n, ng, wo, tilt }
    }

    #[inline]
    pub fn frame(&self) -> Frame {
        Frame { s: self.s, t: self.t, n: self.n }
    }
}

/// What a map needs besides the material and the hit: the scene's textures and tables, and the
/// hit's `dp/du`, `dp/dv` (`shape::tangents`).
pub struct MapContext<'a> {
    pub textures: &'a [Texture],
    pub tables: &'a [f32],
    pub dp_du: Vec3,
    pub dp_dv: Vec3,
}

impl Perturbation {
    pub const ACTIVE: u32 = 1;
    pub const SHADOWING: u32 = 2;
    pub const NONE: Perturbation =
        Perturbation { s: Vec3::X, t: Vec3::Y, nt: Vec3::Z, n: Vec3::Z, flags: 0, _pad: [0; 3] };

    #[inline]
    pub fn active(&self) -> bool {
        self.flags & Self::ACTIVE != 0
    }

    /// The frame the material's model works in.
    #[inline]
    pub fn frame(&self) -> Frame {
        Frame { s: self.s, t: self.t, n: self.nt }
    }

    /// Whether the light direction `wi` is on the same side of the tilted normal as of the shading
    /// normal (Mitsuba's test on its `wo`; there is none on the viewer's side).
    #[inline]
    pub fn keeps_side(&self, wi: Vec3) -> bool {
        wi.z * wi.dot(self.n) > 0.0
    }

    /// The shadowing term for light direction `wi`, one without `use_shadowing_function`.
    #[inline]
    pub fn shadowing(&self, wi: Vec3) -> f32 {
        if self.flags & Self::SHADOWING == 0 {
            return 1.0;
        }
        let alpha2 = (0.125 * tan2_theta(self.n)).min(1.0);
        if alpha2 <= 0.0 {
            // An untilted normal shadows nothing (and 0 · ∞ at grazing `wi` would be NaN).
            return 1.0;
        }
        2.0 / (1.0 + (1.0 + alpha2 * tan2_theta(wi)).sqrt())
    }
}

/// A vector with a direction: length neither zero nor infinite nor NaN (written without `is_finite`,
/// whose infinite literal naga refuses).
#[inline]
fn usable(v: Vec3) -> bool {
    let l2 = v.length_squared();
    l2 > 0.0 && l2 <= f32::MAX
}

/// tan²θ of a unit vector in a local frame (∞ at grazing).
#[inline]
fn tan2_theta(v: Vec3) -> f32 {
    let c2 = v.z * v.z;
    (1.0 - c2).max(0.0) / c2
}

/// The `Shading` at `sp` for a ray arriving along `dir`, as `integrator::shading_frame`, with the
/// frame's tangent following `dp_du` and the tilt of `m`'s map there.
pub fn shading_frame(m: &Material, map: &MapContext, sp: &SurfacePoint, dir: Vec3) -> Shading {
    let (dp_du, dp_dv, textures, tables) = (map.dp_du, map.dp_dv, map.textures, map.tables);
    let two_sided = m.flags & MATERIAL_TWO_SIDED != 0;
    let base = Frame::from_tangent(sp.ns, dp_du);
    let inside = m.perturb & PERTURB_TWO_SIDED_INSIDE != 0;
    let (mut frame, mut ng) = (base, sp.ng);
    if two_sided && !inside && ng.dot(dir) > 0.0 {
        // Mitsuba's `twosided` mirrors the local z axis and keeps s and t, so a map it wraps tilts
        // the back's normal by the same local components as the front's.
        frame.n = -frame.n;
        ng = -ng;
    }
    let wo = frame.to_local(-dir);
    let texture = &textures[m.perturb_texture as usize];
    let bump = m.perturb & PERTURB_KIND == PERTURB_BUMP_MAP;
    let mut n = if bump {
        // The displaced surface p + h·n: its tangents gain the height's gradient along the normal.
        let g = texture::luminance_gradient(texture, tables, sp.uv) * m.bump_scale;
        let n0 = base.n;
        let du = dp_du + n0 * (g.x - n0.dot(dp_du));
        let dv = dp_dv + n0 * (g.y - n0.dot(dp_dv));
        let nb = du.cross(dv);
        if usable(nb) {
            let nb = nb.normalize();
            // Towards the geometric normal's side, in the unmirrored frame (as Mitsuba's).
            base.to_local(if sp.ng.dot(nb) < 0.0 { -nb } else { nb })
        } else {
            Vec3::Z
        }
    } else {
        texture::eval(texture, tables, sp.uv) * 2.0 - Vec3::ONE
    };
    if m.perturb & PERTURB_FLIP_INVALID != 0 && wo.z * wo.dot(n) <= 0.0 {
        n = Vec3::new(-n.x, -n.y, n.z);
    }
    // A zero normal (texel (½, ½, ½)) has no direction; Mitsuba's would be NaN: keep the shading one.
    n = if usable(n) { n.normalize() } else { Vec3::Z };
    // The tilted frame's tangent: the shading frame's s made orthogonal to n (normal map); for the
    // bump map Mitsuba orthogonalises the world-space dp/du against the local n, which is what it
    // renders (only anisotropic models see the tangent), so it is done the same way here.
    let mut tilted = Frame::from_tangent(n, if bump { dp_du } else { Vec3::X });
    if inside && two_sided && tilted.to_local(wo).z < 0.0 {
        // A `twosided` inside the map mirrors the tilted frame's z axis.
        tilted.n = -tilted.n;
    }
    let mut flags = Perturbation::ACTIVE;
    if m.perturb & PERTURB_SHADOWING != 0 {
        flags |= Perturbation::SHADOWING;
    }
    let tilt = Perturbation { s: tilted.s, t: tilted.t, nt: tilted.n, n, flags, _pad: [0; 3] };
    Shading::new(frame, ng, wo, tilt)
}
