//! Dispersion: glass whose index of refraction depends on the wavelength, in a renderer that otherwise
//! transports linear sRGB. Owns the wavelength table (its layout, how the host fills it, how paths
//! sample it) and the dispersion law.
//!
//! A path is wavelength-independent until it reaches a dispersive interface; there it draws one
//! wavelength λ (from a dimension of its own) and keeps it to the end: every later dispersive vertex,
//! whichever side of the path (camera or light) it belongs to, refracts at λ. Drawing λ multiplies the
//! path's RGB throughput by `c(λ)/p(λ)`, where `c` is the CIE 1931 colour-matching functions taken to
//! linear sRGB and scaled per channel so that `∫c(λ)dλ = (1, 1, 1)`. So in expectation the white of
//! RGB (1, 1, 1) is split into the equal-energy spectrum and recombined by the film: a dispersive
//! material with zero dispersion renders exactly the RGB image (tested), and a prism fans white light
//! into the spectral colours the CIE observer sees. Colours of other surfaces multiply the RGB weight as
//! everywhere in an RGB renderer. This is hero-wavelength sampling after its secondary wavelengths are
//! terminated, which is what they become at a dispersive Dirac interface anyway.
//!
//! The spectral colours lie outside the sRGB gamut, so `c` has negative lobes (red around 440–540 nm):
//! single samples may be negative in a channel, the mean converges to the (possibly out-of-gamut)
//! linear sRGB value. Splats are signed for that reason (`splat`).
//!
//! Table layout (`FrameParams::wavelength_table`, only present when a material disperses): the
//! inclusive CDF of `WAVELENGTH_BINS` bins of width `WAVELENGTH_STEP`, then `c` at the
//! `WAVELENGTH_BINS + 1` bin edges (RGB triples), linear in between. The bins' masses follow
//! `|c_r| + |c_g| + |c_b|`, so every wavelength where `c` is non-zero can be drawn.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::Vec3;
use crate::layout::{Material, MATERIAL_DISPERSIVE, MATERIAL_SELLMEIER};
use crate::sampling::sample_cdf;
use crate::spectrum::Rgb;

/// Shortest wavelength (nm) of the table: the CIE 1931 tables start there.
pub const WAVELENGTH_MIN: f32 = 360.0;
/// Bin width (nm): the CIE tables' step.
pub const WAVELENGTH_STEP: f32 = 5.0;
/// Bins from 360 to 830 nm.
pub const WAVELENGTH_BINS: u32 = 94;
/// Longest wavelength (nm) of the table.
pub const WAVELENGTH_MAX: f32 = WAVELENGTH_MIN + WAVELENGTH_STEP * WAVELENGTH_BINS as f32;
/// Floats in the table: the CDF, then RGB at every bin edge.
pub const WAVELENGTH_TABLE_LEN: u32 = WAVELENGTH_BINS + 3 * (WAVELENGTH_BINS + 1);

/// The wavelength at which a dispersive material's `eta` is given: the Fraunhofer d line (587.56 nm),
/// where glass catalogues quote `n_d` and Mitsuba's named IORs (≈589 nm) are measured.
pub const LAMBDA_D: f32 = 587.56;
/// The Fraunhofer F and C lines (nm) that define the Abbe number `V_d = (n_d − 1)/(n_F − n_C)`.
pub const LAMBDA_F: f32 = 486.13;
pub const LAMBDA_C: f32 = 656.27;

/// Where a dispersive material keeps its dispersion. Cauchy's law: `params[PARAM_CAUCHY_B]` is the
/// relative coefficient `B` (µm², interior over exterior): `eta(λ) = eta + B·(1/λ² − 1/λ_d²)`, λ in µm.
/// Sellmeier's (`MATERIAL_SELLMEIER`): the interior's `B1..B3` in `conductor_eta`, `C1..C3` (µm²) in
/// `conductor_k`, `n² = 1 + Σ Bᵢλ²/(λ² − Cᵢ)`, divided by the exterior's index in
/// `params[PARAM_EXTERIOR_IOR]`.
pub const PARAM_CAUCHY_B: usize = 0;
pub const PARAM_EXTERIOR_IOR: usize = 1;

/// A drawn wavelength and what drawing it does to the path's throughput, `c(λ)/p(λ)`.
#[derive(Clone, Copy)]
pub struct WavelengthSample {
    pub lambda: f32,
    pub weight: Rgb,
}

/// Draws a wavelength from the table at `offset` with the random number `u`.
pub fn sample(tables: &[f32], offset: u32, u: f32) -> WavelengthSample {
    let s = sample_cdf(tables, offset, WAVELENGTH_BINS, u);
    let prev = if s.index == 0 { 0.0 } else { tables[(offset + s.index - 1) as usize] };
    let mass = tables[(offset + s.index) as usize] - prev;
    let lambda = WAVELENGTH_MIN + (s.index as f32 + s.remapped) * WAVELENGTH_STEP;
    let c = rgb_at_edge(tables, offset, s.index).lerp(rgb_at_edge(tables, offset, s.index + 1), s.remapped);
    let pdf = mass / WAVELENGTH_STEP;
    let weight = if pdf > 0.0 { c / pdf } else { Rgb::ZERO };
    WavelengthSample { lambda, weight }
}

/// The density (per nm) with which `sample` draws `lambda`.
pub fn pdf(tables: &[f32], offset: u32, lambda: f32) -> f32 {
    let t = (lambda - WAVELENGTH_MIN) / WAVELENGTH_STEP;
    if !(t >= 0.0) || t >= WAVELENGTH_BINS as f32 {
        return 0.0;
    }
    let i = t as u32;
    let prev = if i == 0 { 0.0 } else { tables[(offset + i - 1) as usize] };
    (tables[(offset + i) as usize] - prev) / WAVELENGTH_STEP
}

#[inline]
fn rgb_at_edge(tables: &[f32], offset: u32, edge: u32) -> Rgb {
    let b = (offset + WAVELENGTH_BINS + 3 * edge) as usize;
    Vec3::new(tables[b], tables[b + 1], tables[b + 2])
}

/// Whether material `m` disperses (its path must carry a wavelength).
#[inline]
pub fn disperses(m: &Material) -> bool {
    m.flags & MATERIAL_DISPERSIVE != 0
}

/// `m`'s relative index of refraction at `lambda` nm (Sellmeier's law, or Cauchy's around the d line).
#[inline]
pub fn eta_at(m: &Material, lambda: f32) -> f32 {
    let um = lambda * 1.0e-3;
    let l2 = um * um;
    if m.flags & MATERIAL_SELLMEIER != 0 {
        let (b, c) = (m.conductor_eta, m.conductor_k);
        let n2 = 1.0 + b[0] * l2 / (l2 - c[0]) + b[1] * l2 / (l2 - c[1]) + b[2] * l2 / (l2 - c[2]);
        return n2.max(0.0).sqrt() / m.params[PARAM_EXTERIOR_IOR];
    }
    let d = LAMBDA_D * 1.0e-3;
    m.eta + m.params[PARAM_CAUCHY_B] * (1.0 / l2 - 1.0 / (d * d))
}

/// The Cauchy coefficient `B` (µm²) of a glass with index `n_d` and Abbe number `abbe`.
pub fn cauchy_b_from_abbe(n_d: f32, abbe: f32) -> f32 {
    let (f, c) = (LAMBDA_F * 1.0e-3, LAMBDA_C * 1.0e-3);
    (n_d - 1.0) / (abbe * (1.0 / (f * f) - 1.0 / (c * c)))
}

/// Fills the table from colour-matching functions `xyz` tabulated at the `WAVELENGTH_BINS + 1` bin
/// edges and the XYZ → linear sRGB matrix `to_rgb` (rows). Native builds only: the host calls it.
#[cfg(not(target_arch = "spirv"))]
pub fn build_table(xyz: &[[f64; 3]], to_rgb: [[f64; 3]; 3]) -> std::vec::Vec<f32> {
    let edges = WAVELENGTH_BINS as usize + 1;
    assert_eq!(xyz.len(), edges, "colour-matching functions at every bin edge");
    let rgb: std::vec::Vec<[f64; 3]> = xyz
        .iter()
        .map(|v| core::array::from_fn(|i| (0..3).map(|j| to_rgb[i][j] * v[j]).sum::<f64>()))
        .collect();
    // ∫c dλ of the piecewise-linear interpolant, per channel (trapezoids), normalised to one.
    let step = WAVELENGTH_STEP as f64;
    let integral: [f64; 3] =
        core::array::from_fn(|i| rgb.windows(2).map(|w| 0.5 * (w[0][i] + w[1][i]) * step).sum::<f64>());
    let c: std::vec::Vec<[f64; 3]> =
        rgb.iter().map(|v| core::array::from_fn(|i| v[i] / integral[i])).collect();
    let abs_sum = |v: &[f64; 3]| v[0].abs() + v[1].abs() + v[2].abs();
    let masses: std::vec::Vec<f64> = c.windows(2).map(|w| abs_sum(&w[0]) + abs_sum(&w[1])).collect();
    let total: f64 = masses.iter().sum();
    let mut table = std::vec::Vec::with_capacity(WAVELENGTH_TABLE_LEN as usize);
    let mut running = 0.0;
    for (i, m) in masses.iter().enumerate() {
        running += m;
        table.push(if i + 1 == masses.len() { 1.0 } else { (running / total) as f32 });
    }
    for v in &c {
        table.extend(v.iter().map(|&x| x as f32));
    }
    table
}
