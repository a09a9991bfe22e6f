//! Principled weights given as textures. Mitsuba's `principled` and `principledthin` take a texture
//! for every weight; the record has slots for `base_color`, `roughness`, `anisotropic` and
//! `metallic` only, so the host lists the textures of the others in `tables` at the record's `table`
//! (which neither model uses otherwise): `SLOTS` floats, each a texture index, or −1 where the weight
//! is the record's number. The index is stored as a float value, exact below 2²⁴ textures.
use crate::layout::{Material, Texture};
use crate::spectrum::luminance;
use crate::texture::{self, Lookup};

pub const SLOTS: usize = 8;

/// Which field slot `i` replaces: `params[0..4]`, `specular_transmittance[0..3]`, `eta`. The models'
/// `pack` says what they keep there: `principled` its `spec_trans`, `spec_tint`, `sheen`,
/// `sheen_tint`, then `clearcoat`, `clearcoat_gloss`, `flatness` (slot 7 unused: its `eta` is a
/// number in Mitsuba); `principledthin` the same four, then `flatness`, `diff_trans` (slot 6 unused),
/// and its `eta`.
pub const SLOT_ETA: usize = 7;

/// The table of `textures` (an index per slot, `None` for a number).
pub fn table(textures: [Option<u32>; SLOTS]) -> [f32; SLOTS] {
    textures.map(|t| t.map_or(-1.0, |i| i as f32))
}

/// Writes the luminance (Mitsuba's `eval_1`) of each textured weight at `at` into `material`. One
/// loop over the slots, so that the texture lookup is inlined once: unrolled, each of the eight
/// inlined its own copy at every call site, and spirv-opt ran for over 14 minutes on the kernel.
pub fn apply(material: &mut Material, textures: &[Texture], tables: &[f32], at: Lookup, features: u32) {
    let base = material.table as usize;
    let (p, s) = (material.params, material.specular_transmittance);
    let mut w = [p[0], p[1], p[2], p[3], s[0], s[1], s[2], material.eta];
    let mut i = 0;
    while i < SLOTS {
        let t = tables[base + i];
        if t >= 0.0 {
            w[i] = luminance(texture::eval_at(&textures[t as usize], tables, at, features));
        }
        i += 1;
    }
    material.params = [w[0], w[1], w[2], w[3]];
    material.specular_transmittance = [w[4], w[5], w[6], s[3]];
    material.eta = w[SLOT_ETA];
}
