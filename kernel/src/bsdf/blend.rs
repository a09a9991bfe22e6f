//! Mitsuba's `blendbsdf`: a record of kind `BSDF_BLEND` names two other material records and a weight;
//! the surface scatters as `(1 − w)·first + w·second`. This file owns the record's fields and the
//! mixing rules; `Bsdf` (mod.rs) builds both children and calls these.
//!
//! The record: `eta` holds the weight (already clipped to [0, 1] by the host), `reflectance_texture`
//! a texture whose luminance replaces it (clipped here, as Mitsuba's `eval_weight`), `table` the
//! index of the first child (Mitsuba's `bsdf_0`) in the material list, `specular_texture` that of the
//! second (`bsdf_1`). Children are never blends themselves (the host refuses nested blends: the kernel
//! has no recursion), never masks, never dispersive.
//!
//! `eval` and `pdf` are the weighted sums. `sample` picks a child as Mitsuba does (the second where
//! `u_lobe ≤ w`, reusing `u_lobe` rescaled) and returns the mixture's density and `f·cos / pdf` of the
//! mixture, as Mitsuba does, for a smooth sample. A Dirac sample is the one divergence: Mitsuba also
//! adds the other child's density and value at that direction to the delta lobe's discrete probability
//! and weight, which mixes two measures (a mirror blended 50/50 with white diffuse comes back at
//! `(1 + cos/π)/(1 + cos/π) = 1` but with a 0.5 diffuse at `(1 + 0.5·cos/π)/(1 + cos/π) < 1`, so its
//! reflection is too dark). Here a Dirac sample keeps its child's weight and its probability is scaled
//! by the choice, which is unbiased (`kernel/tests/bsdf_blend.rs` measures both).
use super::{BsdfSample, EvalPdf};
use crate::layout::Material;

/// `u_lobe` rescaled into a child stays below one (models compare it with `<`).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// The material-list indices of a blend record's first and second child.
#[inline]
pub fn children(m: &Material) -> (u32, u32) {
    (m.table, m.specular_texture)
}

/// A blend record of `first` and `second` (material-list indices) with constant weight `weight` of
/// the second (clipped to [0, 1], as Mitsuba's `eval_weight`) or, where `texture` is not `NONE`,
/// that texture's luminance.
#[inline]
pub fn record(first: u32, second: u32, weight: f32, texture: u32) -> Material {
    Material {
        kind: crate::layout::BSDF_BLEND,
        eta: weight.clamp(0.0, 1.0),
        reflectance_texture: texture,
        table: first,
        specular_texture: second,
        ..Default::default()
    }
}

/// Which child a sample takes: the second where `u_lobe ≤ w` (Mitsuba's rule). Returns whether it is
/// the second, the probability of that choice, and `u_lobe` rescaled to [0, 1) for the child.
#[inline]
pub fn choose(u_lobe: f32, w: f32) -> (bool, f32, f32) {
    if u_lobe <= w && w > 0.0 {
        (true, w, (u_lobe / w).min(ONE_MINUS_EPSILON))
    } else {
        let p = 1.0 - w;
        (false, p, ((u_lobe - w) / p).clamp(0.0, ONE_MINUS_EPSILON))
    }
}

/// A sample that keeps its child's weight: a Dirac sample (its probability scaled by the choice's,
/// `p_chosen`), a failed one, or the only model's (`p_chosen` 1).
#[inline]
pub fn scale_choice(bs: BsdfSample, p_chosen: f32) -> BsdfSample {
    if !(bs.pdf > 0.0) {
        return BsdfSample::invalid();
    }
    BsdfSample { pdf: bs.pdf * p_chosen, ..bs }
}

/// A smooth sample `bs` of one child as a sample of the blend: the mixture's density and `f·cos` at
/// `bs.wi` (`mixture`, both children weighted), so the weight is `f·cos / pdf` of the mixture, as
/// Mitsuba's.
#[inline]
pub fn of_mixture(bs: BsdfSample, mixture: EvalPdf) -> BsdfSample {
    if !(mixture.pdf > 0.0) {
        return BsdfSample::invalid();
    }
    BsdfSample { weight: mixture.f / mixture.pdf, pdf: mixture.pdf, ..bs }
}
