//! Fresnel reflectance of dielectric and conductor interfaces, and mirror/refracted directions, with
//! Mitsuba 3's conventions: a cosine below zero means the direction lies inside (on the `-z` side),
//! where the relative index of refraction is inverted.

use crate::glam::Vec3;
use crate::math::safe_sqrt;
use crate::spectrum::Rgb;

/// The dielectric Fresnel term of one direction, with what refraction needs.
#[derive(Clone, Copy)]
pub struct DielectricFresnel {
    /// Unpolarised reflectance.
    pub f: f32,
    /// Cosine of the refracted direction, of opposite sign to the incident cosine (0 under total
    /// internal reflection).
    pub cos_theta_t: f32,
    /// Relative index of refraction in the direction of travel (transmitted side over incident side).
    pub eta_it: f32,
    /// Its reciprocal, which is also the factor on the tangential components of the refracted direction.
    pub eta_ti: f32,
}

/// Unpolarised Fresnel reflectance of a dielectric interface with relative IOR `eta` (inside over
/// outside) for a direction with cosine `cos_theta_i` against the normal (negative: inside).
pub fn fresnel(cos_theta_i: f32, eta: f32) -> DielectricFresnel {
    let outside = cos_theta_i >= 0.0;
    let eta_it = if outside { eta } else { 1.0 / eta };
    let eta_ti = if outside { 1.0 / eta } else { eta };
    // Snell's law gives sin²θt = sin²θi / η²; a negative cos²θt is total internal reflection.
    let cos_t2 = 1.0 - (1.0 - cos_theta_i * cos_theta_i) * (eta_ti * eta_ti);
    let ci = cos_theta_i.abs();
    let ct = safe_sqrt(cos_t2);
    // Matched indices reflect nothing; exactly grazing incidence reflects everything (the amplitude
    // ratios below would be 0/0 there).
    let f = if eta == 1.0 {
        0.0
    } else if ci == 0.0 {
        1.0
    } else {
        let a_s = (ci - eta_it * ct) / (ci + eta_it * ct);
        let a_p = (ct - eta_it * ci) / (ct + eta_it * ci);
        0.5 * (a_s * a_s + a_p * a_p)
    };
    let cos_theta_t = if outside { -ct } else { ct };
    DielectricFresnel { f, cos_theta_t, eta_it, eta_ti }
}

/// Unpolarised Fresnel reflectance of a conductor with complex relative IOR `eta + i·k`, for light
/// arriving from outside (`cos_theta_i ≥ 0`). Exact (Moeller's "Optics" form, as Mitsuba uses);
/// with `k = 0` it equals the dielectric `fresnel`.
pub fn fresnel_conductor(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    let c2 = cos_theta_i * cos_theta_i;
    let s2 = 1.0 - c2;
    let s4 = s2 * s2;
    let t1 = eta * eta - k * k - s2;
    let a2_plus_b2 = safe_sqrt(t1 * t1 + 4.0 * k * k * eta * eta);
    let a = safe_sqrt(0.5 * (a2_plus_b2 + t1));
    let term1 = a2_plus_b2 + c2;
    let term2 = 2.0 * cos_theta_i * a;
    // Both ratios are 0/0 only at isolated points, where Mitsuba returns NaN: exactly grazing on an
    // index-matched interface (eta = 1, k = 0: the reflectance's limit is 0) and normal incidence on
    // eta = k = 0 (the p/s ratio's limit is 1).
    let r_s = ratio_or(term1 - term2, term1 + term2, 0.0);
    let term3 = a2_plus_b2 * c2 + s4;
    let term4 = term2 * s2;
    let r_p = r_s * ratio_or(term3 - term4, term3 + term4, 1.0);
    // Rounding can leave a vanishing reflectance (k = 0, eta ≈ 1) a hair below zero.
    (0.5 * (r_s + r_p)).max(0.0)
}

/// `num / den`, or `limit` where the denominator vanishes (then so does the numerator).
#[inline]
fn ratio_or(num: f32, den: f32, limit: f32) -> f32 {
    if den > 0.0 {
        num / den
    } else {
        limit
    }
}

/// `fresnel_conductor` per colour channel.
pub fn fresnel_conductor_rgb(cos_theta_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        fresnel_conductor(cos_theta_i, eta.x, k.x),
        fresnel_conductor(cos_theta_i, eta.y, k.y),
        fresnel_conductor(cos_theta_i, eta.z, k.z),
    )
}

/// Fraction of uniformly diffuse (cosine-weighted) light that a dielectric interface of relative IOR
/// `eta` reflects ("Fdr"), by the same polynomial fits Mitsuba uses: Egan & Hilgeman (1973) for
/// `eta < 1`, d'Eon & Irving (2011) otherwise.
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        0.919317 + inv * (-3.4793 + inv * (6.75335 + inv * (-7.80989 + inv * (4.98554 + inv * -1.36881))))
    }
}

/// Mirror direction about the local normal (+z).
#[inline]
pub fn reflect(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// Mirror direction of `w` about the unit normal `m`.
#[inline]
pub fn reflect_about(w: Vec3, m: Vec3) -> Vec3 {
    m * (2.0 * w.dot(m)) - w
}

/// Refracted direction of `w` through the local interface, given `cos_theta_t` and `eta_ti` from
/// `fresnel(w.z, eta)`.
#[inline]
pub fn refract(w: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    Vec3::new(-eta_ti * w.x, -eta_ti * w.y, cos_theta_t)
}

/// Refracted direction of `w` through a facet with unit normal `m`, given `cos_theta_t` and `eta_ti`
/// from `fresnel(w·m, eta)`.
#[inline]
pub fn refract_about(w: Vec3, m: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    m * (w.dot(m) * eta_ti + cos_theta_t) - w * eta_ti
}
