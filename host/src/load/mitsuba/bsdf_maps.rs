//! The BSDF plugins that tilt the shading frame of a nested BSDF: `normalmap` (a `normalmap` texture
//! whose RGB `c` gives the normal `2c − 1` in the shading frame) and `bumpmap` (a height texture,
//! times `scale`), each with Mitsuba 3.9.1's `flip_invalid_normals` and `use_shadowing_function`
//! (both on by default). The nested BSDF's record is copied with the map in its `perturb` fields;
//! `caustic_kernel::bsdf::perturb` renders it. As Mitsuba, a normal map's texture is read as its
//! `raw` property says (sRGB-decoded unless `raw` is true; Mitsuba's documentation asks for `raw`).
use super::loader::Loader;
use super::props::{Entry, Props};
use anyhow::{bail, Result};
use caustic_kernel::layout::*;

impl Loader {
    /// `normalmap` and `bumpmap`.
    pub(crate) fn normal_or_bump_map(&mut self, props: &Props) -> Result<Material> {
        let bump = props.kind == "bumpmap";
        // Children: the nested BSDF, and the texture (any name for `bumpmap`, as Mitsuba takes its
        // one texture child; `normalmap` for `normalmap`). A `<ref>` is either, by what it names.
        let (mut bsdfs, mut textures): (Vec<&Entry>, Vec<&Entry>) = (Vec::new(), Vec::new());
        for e in props.nested("bsdf").into_iter().chain(props.nested("texture")).chain(props.nested("ref")) {
            let is_texture = match e.tag.as_str() {
                "texture" => true,
                "bsdf" => false,
                _ => {
                    let id = self.attribute(e.node, "id", &e.loc)?.unwrap_or_default();
                    if self.named_textures.contains_key(&id) {
                        true
                    } else if self.named_bsdfs.contains_key(&id) {
                        false
                    } else {
                        bail!("{}: <ref id=\"{id}\"> names no BSDF or texture defined before it", e.loc);
                    }
                }
            };
            if is_texture {
                textures.push(e);
            } else {
                bsdfs.push(e);
            }
        }
        let inner_entry = match bsdfs.as_slice() {
            [one] => *one,
            [] => bail!("{}: {} needs one nested <bsdf>", props.loc, props.kind),
            _ => bail!("{}: {} takes one nested BSDF (Mitsuba refuses more)", props.loc, props.kind),
        };
        let texture_entry = if bump {
            match textures.as_slice() {
                [one] => *one,
                [] => bail!("{}: bumpmap needs one nested <texture> (the height)", props.loc),
                _ => bail!("{}: bumpmap takes one texture (Mitsuba refuses more)", props.loc),
            }
        } else {
            match textures.iter().find(|e| e.name.as_deref() == Some("normalmap")) {
                Some(e) => *e,
                None => bail!("{}: normalmap needs a <texture name=\"normalmap\">", props.loc),
            }
        };
        for e in &textures {
            if !std::ptr::eq(*e, texture_entry) {
                bail!("{}: {} takes one texture; this one is not read", e.loc, props.kind);
            }
        }
        let texture_props = self.props(props.src, texture_entry.node)?;
        let texture = self.load_texture(&texture_props)?;
        let record = &self.textures[texture as usize].record;
        if bump && record.kind == TEXTURE_CHECKERBOARD {
            // Mitsuba 3.9.1's checkerboard has no `eval_1_grad`: its render fails.
            bail!(
                "{}: bumpmap needs a bitmap height texture (a checkerboard has no gradient)",
                texture_entry.loc
            );
        }

        let inner_props = self.props(props.src, inner_entry.node)?;
        let index = self.load_bsdf(&inner_props)?;
        let mut m = self.materials[index as usize];
        if m.perturb != 0 {
            bail!("{}: a normalmap or bumpmap inside another is not supported", props.loc);
        }
        let scale = if bump { props.float("scale", 1.0)? } else { 1.0 };
        if !scale.is_finite() {
            bail!("{}: bumpmap scale must be finite, not {scale}", props.loc);
        }
        m.perturb = if bump { PERTURB_BUMP_MAP } else { PERTURB_NORMAL_MAP };
        if props.boolean("flip_invalid_normals", true)? {
            m.perturb |= PERTURB_FLIP_INVALID;
        }
        if props.boolean("use_shadowing_function", true)? {
            m.perturb |= PERTURB_SHADOWING;
        }
        if caustic_kernel::two_sided::back_plus_one(&m) != 0 {
            bail!("{}: a normalmap or bumpmap around a twosided of two BSDFs is not supported", props.loc);
        }
        if m.flags & MATERIAL_TWO_SIDED != 0 {
            m.perturb |= PERTURB_TWO_SIDED_INSIDE;
        }
        m.perturb_texture = texture;
        m.bump_scale = scale;
        Ok(m)
    }
}
