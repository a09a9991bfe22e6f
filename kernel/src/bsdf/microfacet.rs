//! Microfacet normal distributions (Beckmann and GGX/Trowbridge-Reitz, anisotropic) with Smith's
//! separable shadowing-masking and visible-normal sampling, as Mitsuba 3's `MicrofacetDistribution`
//! with `sample_visible = true` (its default): Walter et al. 2007 for `D` and `G1`, Heitz & d'Eon 2014
//! for sampling visible normals, Jakob 2014 for the Beckmann slope inversion and Heitz 2018 for GGX.
//!
//! `alpha_u` and `alpha_v` are the roughnesses along the frame's tangent (x) and bitangent (y).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::{Vec2, Vec3};
use crate::layout::{Material, MATERIAL_BECKMANN};
use crate::math::{is_finite, is_finite3, safe_sqrt, PI};
use crate::sampling::square_to_concentric_disk;

/// Mitsuba clamps roughness to this: at zero the distribution is a Dirac delta that `D` cannot express.
pub const MIN_ALPHA: f32 = 1e-4;

const INV_SQRT_PI: f32 = 0.564_189_6;

#[derive(Clone, Copy)]
pub struct Microfacet {
    pub alpha_u: f32,
    pub alpha_v: f32,
    pub beckmann: bool,
}

/// A sampled microfacet normal and its density (solid angle, of the normal).
#[derive(Clone, Copy)]
pub struct MicrofacetSample {
    pub m: Vec3,
    pub pdf: f32,
}

impl Microfacet {
    pub fn new(alpha_u: f32, alpha_v: f32, beckmann: bool) -> Self {
        Microfacet { alpha_u: alpha_u.max(MIN_ALPHA), alpha_v: alpha_v.max(MIN_ALPHA), beckmann }
    }

    /// The distribution of a material record: `alpha_u`, `alpha_v` and the `MATERIAL_BECKMANN` flag.
    pub fn from_material(m: &Material) -> Self {
        Self::new(m.alpha_u, m.alpha_v, m.flags & MATERIAL_BECKMANN != 0)
    }

    /// The normal distribution `D(m)` (normalised so that `∫ D(m) cos θm dm = 1`).
    pub fn d(&self, m: Vec3) -> f32 {
        let cos2 = m.z * m.z;
        if m.z <= 0.0 {
            return 0.0;
        }
        let xu = m.x / self.alpha_u;
        let yv = m.y / self.alpha_v;
        let result = if self.beckmann {
            let e = (-(xu * xu + yv * yv) / cos2).exp();
            // Decide before dividing: cos⁴ can underflow where the exponential already has.
            if e <= 0.0 {
                return 0.0;
            }
            e / (PI * self.alpha_u * self.alpha_v * cos2 * cos2)
        } else {
            let t = xu * xu + yv * yv + cos2;
            1.0 / (PI * self.alpha_u * self.alpha_v * t * t)
        };
        // Mitsuba drops vanishingly small values so that later stages never divide by them.
        if is_finite(result) && result * m.z > 1e-20 {
            result
        } else {
            0.0
        }
    }

    /// Smith's shadowing-masking `G1(v, m)` for one direction.
    pub fn smith_g1(&self, v: Vec3, m: Vec3) -> f32 {
        // Neither side sees the back of a facet.
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let au = self.alpha_u * v.x;
        let av = self.alpha_v * v.y;
        let xy = au * au + av * av;
        if xy <= 0.0 {
            return 1.0;
        }
        let abs_z = v.z.abs();
        if self.beckmann {
            // a = 1 / (α tan θ), with Walter et al.'s rational fit (< 0.35 % error), as Mitsuba.
            let a = abs_z / xy.sqrt();
            if a >= 1.6 {
                1.0
            } else {
                (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
            }
        } else {
            // 2 / (1 + sqrt(1 + α² tan² θ)), multiplied through by |cos θ| so that nothing overflows
            // near grazing.
            2.0 * abs_z / (abs_z + (v.z * v.z + xy).sqrt())
        }
    }

    /// Separable shadowing-masking `G1(wo, m)·G1(wi, m)`.
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.smith_g1(wo, m) * self.smith_g1(wi, m)
    }

    /// Density of `sample(w, ·)` producing the normal `m`: the visible normals `D·G1·|w·m|/cos θw`
    /// (`w` in the upper hemisphere).
    pub fn pdf(&self, w: Vec3, m: Vec3) -> f32 {
        self.pdf_with_d(self.d(m), w, m)
    }

    /// `pdf` for a caller that has `d = D(m)` already.
    #[inline]
    pub fn pdf_with_d(&self, d: f32, w: Vec3, m: Vec3) -> f32 {
        if w.z <= 0.0 {
            return 0.0;
        }
        d * self.smith_g1(w, m) * w.dot(m).abs() / w.z
    }

    /// Samples a normal visible from `w` (upper hemisphere): stretch `w` to the unit-roughness
    /// configuration, sample a slope there, rotate back and unstretch.
    pub fn sample(&self, w: Vec3, u: Vec2) -> MicrofacetSample {
        let ws = Vec3::new(self.alpha_u * w.x, self.alpha_v * w.y, w.z).normalize();
        let sin2 = ws.x * ws.x + ws.y * ws.y;
        // Azimuth of the stretched direction; arbitrary (0) at the pole.
        let (mut cos_phi, mut sin_phi) = (1.0, 0.0);
        if sin2 > 4.0 * f32::EPSILON {
            let inv = 1.0 / sin2.sqrt();
            cos_phi = (ws.x * inv).clamp(-1.0, 1.0);
            sin_phi = (ws.y * inv).clamp(-1.0, 1.0);
        }
        let slope = if self.beckmann { beckmann_visible_slope(ws.z, u) } else { ggx_visible_slope(ws.z, u) };
        let sx = (cos_phi * slope.x - sin_phi * slope.y) * self.alpha_u;
        let sy = (sin_phi * slope.x + cos_phi * slope.y) * self.alpha_v;
        let len2 = sx * sx + sy * sy + 1.0;
        if !is_finite(len2) {
            return MicrofacetSample { m: Vec3::Z, pdf: 0.0 };
        }
        let m = Vec3::new(-sx, -sy, 1.0) / len2.sqrt();
        if !is_finite3(m) {
            return MicrofacetSample { m: Vec3::Z, pdf: 0.0 };
        }
        MicrofacetSample { m, pdf: self.pdf(w, m) }
    }
}

/// Slope of a visible normal of the unit-roughness GGX distribution seen at `cos_theta` (azimuth 0),
/// by Heitz 2018: a uniform point on the projected disk of the visible half of the unit hemisphere,
/// lifted to the hemisphere, is the normal.
fn ggx_visible_slope(cos_theta: f32, u: Vec2) -> Vec2 {
    let p = square_to_concentric_disk(u);
    // The visible region's projection is half a disk plus half an ellipse of semi-axis cos θ:
    // squeeze the lower half accordingly.
    let s = 0.5 * (1.0 + cos_theta);
    let x = p.x;
    let y = (1.0 - s) * safe_sqrt(1.0 - x * x) + s * p.y;
    let z = safe_sqrt(1.0 - x * x - y * y);
    // (x, y, z) is in the frame of the view direction; the slope of that normal in the surface frame:
    let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
    let norm = 1.0 / (sin_theta * y + cos_theta * z);
    Vec2::new((cos_theta * y - sin_theta * z) * norm, x * norm)
}

/// Slope of a visible normal of the unit-roughness Beckmann distribution seen at `cos_theta`
/// (azimuth 0), by inverting the slope's marginal CDF numerically in the erf domain (Jakob 2014):
/// a guess exact at grazing incidence, then three Newton steps; the other slope is a Gaussian.
fn beckmann_visible_slope(cos_theta: f32, u: Vec2) -> Vec2 {
    let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
    let tan_theta = sin_theta / cos_theta;
    // cot θ is unbounded at normal incidence; beyond 1e7 erf and exp have long saturated.
    let cot_theta = if sin_theta > 1e-7 * cos_theta { cos_theta / sin_theta } else { 1e7 };
    let maxval = erf(cot_theta);
    let ux = u.x.clamp(1e-6, 1.0 - 1e-6);
    let uy = u.y.clamp(1e-6, 1.0 - 1e-6);
    let mut x = maxval - (maxval + 1.0) * erf(safe_sqrt(-ux.ln()));
    // The CDF's normalisation.
    let target = ux * (1.0 + maxval + INV_SQRT_PI * tan_theta * (-cot_theta * cot_theta).exp());
    let mut i = 0;
    while i < 3 {
        let slope = erfinv(x);
        let value = 1.0 + x + INV_SQRT_PI * tan_theta * (-slope * slope).exp() - target;
        let derivative = 1.0 - slope * tan_theta;
        x -= value / derivative;
        i += 1;
    }
    Vec2::new(erfinv(x), erfinv(2.0 * uy - 1.0))
}

/// The error function, Abramowitz & Stegun 7.1.26 (absolute error below 1.5e-7).
pub fn erf(x: f32) -> f32 {
    let ax = x.abs();
    let t = 1.0 / (1.0 + 0.327_591_1 * ax);
    let poly =
        t * (0.254_829_6 + t * (-0.284_496_74 + t * (1.421_413_7 + t * (-1.453_152 + t * 1.061_405_4))));
    let y = 1.0 - poly * (-ax * ax).exp();
    if x < 0.0 {
        -y
    } else {
        y
    }
}

/// Inverse error function, Giles 2010's single-precision approximation. The argument is kept inside
/// (-1, 1), where the result stays finite (|erfinv| < 4).
pub fn erfinv(x: f32) -> f32 {
    let x = x.clamp(-0.999_999_9, 0.999_999_9);
    let mut w = -((1.0 - x) * (1.0 + x)).ln();
    let p = if w < 5.0 {
        w -= 2.5;
        let mut p = 2.810_226_4e-8;
        p = 3.432_739_4e-7 + p * w;
        p = -3.523_387_7e-6 + p * w;
        p = -4.391_506_5e-6 + p * w;
        p = 2.185_808_7e-4 + p * w;
        p = -1.253_725e-3 + p * w;
        p = -4.177_681_6e-3 + p * w;
        p = 2.466_407_3e-1 + p * w;
        1.501_409_4 + p * w
    } else {
        w = w.sqrt() - 3.0;
        let mut p = -2.002_142_6e-4;
        p = 1.009_505_6e-4 + p * w;
        p = 1.349_343_2e-3 + p * w;
        p = -3.673_428_4e-3 + p * w;
        p = 5.739_507_7e-3 + p * w;
        p = -7.622_461e-3 + p * w;
        p = 9.438_870_5e-3 + p * w;
        p = 1.001_674 + p * w;
        2.832_976_8 + p * w
    };
    p * x
}
