//! Orthonormal shading frames.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::Vec3;

/// An orthonormal basis whose `n` axis is the shading normal; BSDFs work in its local coordinates
/// (z up), as in pbrt and Mitsuba.
#[derive(Clone, Copy)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// Builds a frame around a unit normal without branches that lose precision near the poles
    /// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
    pub fn from_normal(n: Vec3) -> Self {
        let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// Mitsuba's shading frame: `s` is `dp_du` made orthogonal to the unit normal `n` (Gram–Schmidt),
    /// `t = n × s`; where `dp_du` has no part orthogonal to `n` (zero, or along `n`; also NaN), the
    /// frame of `from_normal`, as Mitsuba's fallback for a zero `dp_du`. (A part below 1e-5 of
    /// `dp_du`'s length is rounding noise: Mitsuba normalises it into an arbitrary, non-orthogonal
    /// tangent, caustic falls back.)
    pub fn from_tangent(n: Vec3, dp_du: Vec3) -> Self {
        let s = dp_du - n * n.dot(dp_du);
        let len2 = s.length_squared();
        if len2 > 1e-10 * dp_du.length_squared() && len2 <= f32::MAX {
            let s = s / len2.sqrt();
            Frame { s, t: n.cross(s), n }
        } else {
            Self::from_normal(n)
        }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}
