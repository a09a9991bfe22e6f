//! Dispersion under BDPT and VCM: one wavelength for a whole pass.
//!
//! `path`, `ptracer` and IBPT let each path draw its wavelength at its first dispersive vertex
//! (`super::disperse`). BDPT and VCM join a camera path to light vertices that other paths left (its
//! own light path's, and under VCM any pixel's within the merging radius), so the two halves of a
//! joined path must refract at the same wavelength. Every path of a pass therefore sees the pass's
//! wavelength λ, drawn from the wavelength table (`wavelength::sample`) with a random number that
//! depends on the pass alone: a rank-1 lattice over the passes (the golden ratio's, in 32-bit fixed
//! point so that it stays exact at any pass index) shifted by a hash of the seed, so successive passes
//! spread over the spectrum and each pass's number is still uniform on [0, 1).
//!
//! A joined path whose vertices include a dispersive one is weighted by `c(λ)/p(λ)` once (`factor`),
//! at the moment it contributes; one without is independent of λ and weighted by one. The throughputs
//! the sub-paths carry stay free of that factor, so Russian roulette and the MIS quantities see the
//! same values as in a scene without dispersion. All strategies of a pass share λ, so their weights sum
//! to one at λ, and the expectation over passes is the spectral integral (`wavelength`).
use crate::features;
use crate::layout::{FrameParams, Material, SceneView};
use crate::rng::{hash2, u32_to_unit_f32};
use crate::spectrum::Rgb;
use crate::wavelength;

/// The golden ratio's inverse in 32-bit fixed point (2³² / φ).
const GOLDEN: u32 = 0x9e37_79b9;
/// What the seed is hashed with for the lattice's shift (no other stream uses it).
const SHIFT_STREAM: u32 = 0x7a5e_d15b;

/// The pass's wavelength (`lambda` 0 where the scene has no dispersive material) and its weight.
#[derive(Clone, Copy)]
pub struct PassWavelength {
    pub lambda: f32,
    pub weight: Rgb,
}

impl PassWavelength {
    /// The wavelength of the pass whose sample is `params.sample_base`.
    #[inline]
    pub fn of(scene: &SceneView, params: &FrameParams) -> Self {
        if !features::has(scene.features, features::DISPERSION) {
            return PassWavelength { lambda: 0.0, weight: Rgb::ONE };
        }
        let bits = hash2(params.seed, SHIFT_STREAM).wrapping_add(params.sample_base.wrapping_mul(GOLDEN));
        let ws = wavelength::sample(scene.tables, params.wavelength_table, u32_to_unit_f32(bits));
        PassWavelength { lambda: ws.lambda, weight: ws.weight }
    }

    /// Makes `material` refract at the pass's wavelength if it disperses; returns whether it does.
    #[inline]
    pub fn disperse(&self, material: &mut Material) -> bool {
        let disperses = self.lambda > 0.0 && wavelength::disperses(material);
        if disperses {
            material.eta = wavelength::eta_at(material, self.lambda);
        }
        disperses
    }

    /// The weight of a joined path: `c(λ)/p(λ)` if any of its vertices `dispersed`, else one.
    #[inline]
    pub fn factor(&self, dispersed: bool) -> Rgb {
        if dispersed {
            self.weight
        } else {
            Rgb::ONE
        }
    }
}
