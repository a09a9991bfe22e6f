//! Mitsuba's `blendbsdf`: a record of kind `BSDF_BLEND` names two other material records and a weight;
//! the surface scatters as `(1 − w)·first + w·second`. A child may be a blend itself: the tree is
//! expanded into its leaves, each weighted by the product of the weights on its way down (`expand`),
//! and the surface scatters as their weighted sum. This file owns the record's fields and the mixing
//! rules; `Bsdf` (mod.rs) builds the leaves and calls these.
//!
//! The record: `eta` holds the weight (already clipped to [0, 1] by the host), `reflectance_texture`
//! a texture whose luminance replaces it (clipped here, as Mitsuba's `eval_weight`), `table` the
//! index of the first child (Mitsuba's `bsdf_0`) in the material list, `specular_texture` that of the
//! second (`bsdf_1`). Leaves are never masks, never dispersive, never normal- or bump-mapped, and a
//! tree has at most `MAX_LEAVES` of them (the host refuses the rest).
//!
//! `eval` and `pdf` are the weighted sums. `sample` picks the leaf that Mitsuba's choices down the
//! tree pick (it takes `bsdf_1` where `u_lobe ≤ w` and reuses `u_lobe` rescaled), and returns the mixture's density and `f·cos / pdf` of the
//! mixture, as Mitsuba does, for a smooth sample. A Dirac sample is the one divergence: Mitsuba also
//! adds the other child's density and value at that direction to the delta lobe's discrete probability
//! and weight, which mixes two measures (a mirror blended 50/50 with white diffuse comes back at
//! `(1 + cos/π)/(1 + cos/π) = 1` but with a 0.5 diffuse at `(1 + 0.5·cos/π)/(1 + cos/π) < 1`, so its
//! reflection is too dark). Here a Dirac sample keeps its leaf's weight and its probability is scaled
//! by the choice, which is unbiased (`kernel/tests/bsdf_blend.rs` measures both).
use super::{BsdfSample, EvalPdf, MAX_LEAVES};
use crate::layout::{Material, Texture, BSDF_BLEND, NONE};
use crate::spectrum::luminance;
use crate::texture::{self, Lookup};

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

/// A blend record's weight of its second child at `at`: the constant, or its texture's luminance
/// clipped to [0, 1] (Mitsuba's `eval_weight`).
#[inline]
pub fn weight(m: &Material, textures: &[Texture], tables: &[f32], at: Lookup, features: u32) -> f32 {
    if crate::features::has(features, crate::features::TEXTURES) && m.reflectance_texture != NONE {
        let t = &textures[m.reflectance_texture as usize];
        luminance(texture::eval_at(t, tables, at, features)).clamp(0.0, 1.0)
    } else {
        m.eta
    }
}

/// Expands the blend tree of `root` into its leaves (material-list indices) and their weights at
/// `at`, returning how many. A slot holding a blend is replaced by its second child, weighted `w`,
/// followed by its first, weighted `1 − w` (the slots after move up by one), until no slot holds a
/// blend (or the slots are full: the host keeps trees within them). The leaves end in the order in
/// which Mitsuba's choices lay them along `u_lobe` (`choose`).
#[allow(clippy::too_many_arguments)]
pub fn expand(
    root: &Material,
    materials: &[Material],
    textures: &[Texture],
    tables: &[f32],
    at: Lookup,
    features: u32,
    leaves: &mut [u32; MAX_LEAVES],
    weights: &mut [f32; MAX_LEAVES],
) -> u32 {
    // Slot 0 starts as the root itself (`NONE`), so that one loop reads every node's weight.
    leaves[0] = NONE;
    weights[0] = 1.0;
    let mut count = 1u32;
    let mut k = 0u32;
    while k < count {
        let index = leaves[k as usize];
        let node = if index == NONE { *root } else { materials[index as usize] };
        if node.kind == BSDF_BLEND && (count as usize) < MAX_LEAVES {
            let (a, b) = children(&node);
            let w = weight(&node, textures, tables, at, features);
            let parent = weights[k as usize];
            let mut j = count;
            while j > k + 1 {
                leaves[j as usize] = leaves[j as usize - 1];
                weights[j as usize] = weights[j as usize - 1];
                j -= 1;
            }
            leaves[k as usize] = b;
            weights[k as usize] = parent * w;
            leaves[k as usize + 1] = a;
            weights[k as usize + 1] = parent * (1.0 - w);
            count += 1;
        } else {
            k += 1;
        }
    }
    count
}

/// Which leaf a sample takes, the probability of that choice, and `u_lobe` rescaled to [0, 1) for
/// the leaf.
#[derive(Clone, Copy)]
pub struct Choice {
    pub leaf: u32,
    pub probability: f32,
    pub u: f32,
}

/// Picks a leaf with the probability of its weight: the one whose interval of the weights laid end
/// to end holds `u_lobe` (the last of positive weight where rounding leaves `u_lobe` past the end).
/// In `expand`'s order this is Mitsuba's choice down the tree, `u_lobe` rescaled as Mitsuba rescales
/// it at each node.
#[inline]
pub fn choose(u_lobe: f32, weights: &[f32; MAX_LEAVES], count: u32) -> Choice {
    let mut choice = Choice { leaf: 0, probability: 0.0, u: 0.0 };
    let mut start = 0.0;
    let mut i = 0;
    while i < count {
        let w = weights[i as usize];
        if w > 0.0 {
            choice =
                Choice { leaf: i, probability: w, u: ((u_lobe - start) / w).clamp(0.0, ONE_MINUS_EPSILON) };
            if u_lobe < start + w {
                break;
            }
            start += w;
        }
        i += 1;
    }
    choice
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
