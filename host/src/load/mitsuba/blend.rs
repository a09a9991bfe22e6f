//! Mitsuba's `blendbsdf`: `weight` (a number, colour or texture, read as its luminance and clipped
//! to [0, 1] as Mitsuba's `eval_weight`; required, as Mitsuba has no default) and exactly two nested
//! BSDFs (`<bsdf>` or `<ref>`, in document order: the first is Mitsuba's `bsdf_0`, weighted `1 − w`).
//! The record (`caustic_kernel::bsdf::blend`) names the two children's places in the material list.
//!
//! A child may be a blend: the kernel mixes the tree's leaves, up to `MAX_LEAVES` of them.
//!
//! What the kernel cannot mix is refused with the child's file and line: a tree of more leaves, a
//! `mask` inside (the kernel reads a mask's opacity on the surface's own record), a dispersive
//! dielectric inside (its wavelength is drawn on the surface's own record), a two-sided child beside
//! a one-sided one (a surface's shading frame is mirrored for all of it), and a `twosided` of two
//! BSDFs (the kernel picks a side on the surface's own record).
//! A leaf with a Dirac lobe beside one with a smooth lobe renders differently from Mitsuba
//! (`caustic_kernel::bsdf::blend`): a substitution, which `--strict` refuses.
use super::loader::Loader;
use super::props::{Entry, Props};
use anyhow::{bail, Result};
use caustic_kernel::bsdf::{blend, MAX_LEAVES};
use caustic_kernel::layout::*;

impl Loader {
    pub(super) fn blend(&mut self, props: &Props) -> Result<Material> {
        // Marks the nested elements as read; the order comes from the entries.
        props.nested("bsdf");
        props.nested("ref");
        let children: Vec<&Entry> = props
            .entries
            .iter()
            .filter(|e| e.tag == "bsdf" || (e.tag == "ref" && e.name.as_deref() != Some("weight")))
            .collect();
        if children.len() != 2 {
            bail!(
                "{}: blendbsdf takes exactly two nested BSDFs (Mitsuba refuses other counts), found {}",
                props.loc,
                children.len()
            );
        }
        let (weight, texture) = self.blend_weight(props)?;
        let mut index = [0u32; 2];
        let mut two_sided = [false; 2];
        for (k, entry) in children.iter().enumerate() {
            let child_props = self.props(props.src, entry.node)?;
            let i = self.load_bsdf(&child_props)?;
            let m = self.materials[i as usize];
            let refusal = if caustic_kernel::two_sided::back_plus_one(&m) != 0 {
                Some("a twosided of two BSDFs inside a blendbsdf is not supported; blend each side's BSDFs inside the twosided")
            } else if m.flags & MATERIAL_MASK != 0 {
                Some("a mask inside a blendbsdf is not supported; put the mask around the blendbsdf")
            } else if m.perturb != 0 {
                Some("a normalmap or bumpmap inside a blendbsdf is not supported; put the map around the blendbsdf")
            } else if caustic_kernel::wavelength::disperses(&m) {
                Some("a dispersive dielectric inside a blendbsdf is not supported")
            } else {
                None
            };
            if let Some(why) = refusal {
                bail!("{}: {why}", entry.loc);
            }
            index[k] = i;
            two_sided[k] = m.flags & MATERIAL_TWO_SIDED != 0;
        }
        if two_sided[0] != two_sided[1] {
            bail!(
                "{}: a blendbsdf of a two-sided and a one-sided BSDF is not supported (caustic mirrors a \
                 surface's shading frame for the whole BSDF); make both two-sided or wrap the blendbsdf",
                props.loc
            );
        }
        let leaves: Vec<u32> = index.iter().flat_map(|&i| self.blend_leaves(i)).collect();
        if leaves.len() > MAX_LEAVES {
            bail!(
                "{}: this tree of blendbsdfs mixes {} BSDFs; caustic mixes at most {MAX_LEAVES} on one surface",
                props.loc,
                leaves.len()
            );
        }
        // Said once, where a tree first mixes the two (a nested blend that does has said so).
        let mixes = |leaves: &[u32]| {
            let kinds = leaves.iter().map(|&i| self.materials[i as usize].kind);
            kinds.clone().any(dirac) && kinds.clone().any(smooth)
        };
        let nested = |i: &&u32| self.materials[**i as usize].kind == BSDF_BLEND;
        let inside = index.iter().filter(nested).any(|&i| mixes(&self.blend_leaves(i)));
        if mixes(&leaves) && !inside {
            let message = format!(
                "{}: blendbsdf of a Dirac lobe and a smooth one: Mitsuba weighs the Dirac samples with the \
                 other BSDF's density (biased), caustic does not; the image differs",
                props.loc
            );
            self.substituted("blendbsdf of a Dirac and a smooth lobe".into(), &props.loc, message);
        }
        let mut m = blend::record(index[0], index[1], weight, texture);
        if two_sided[0] {
            m.flags |= MATERIAL_TWO_SIDED;
        }
        Ok(m)
    }

    /// The leaves of material `i`'s blend tree (itself where it is not a blend), in document order.
    pub(super) fn blend_leaves(&self, i: u32) -> Vec<u32> {
        let m = &self.materials[i as usize];
        if m.kind != BSDF_BLEND {
            return vec![i];
        }
        let (a, b) = blend::children(m);
        let mut leaves = self.blend_leaves(a);
        leaves.extend(self.blend_leaves(b));
        leaves
    }

    /// `weight` as Mitsuba's `eval_1` reads it (`scalar_param`: a texture's luminance, with its
    /// mean; a number; a colour's channel mean); clipped to [0, 1] (the kernel clips a texture's per
    /// hit).
    fn blend_weight(&mut self, props: &Props) -> Result<(f32, u32)> {
        if !props.has("weight") {
            bail!("{}: blendbsdf needs a 'weight' (Mitsuba has no default)", props.loc);
        }
        let (weight, texture) = self.scalar_param(props, "weight", 0.0)?;
        if !weight.is_finite() {
            bail!("{}: blendbsdf weight must be a finite number, not {weight}", props.loc);
        }
        Ok((weight.clamp(0.0, 1.0), texture))
    }
}

/// Models with a Dirac-delta lobe.
fn dirac(kind: u32) -> bool {
    matches!(kind, BSDF_CONDUCTOR | BSDF_DIELECTRIC | BSDF_THIN_DIELECTRIC | BSDF_PLASTIC)
}

/// Models with a lobe `eval` sees (every one but the purely specular).
fn smooth(kind: u32) -> bool {
    !matches!(kind, BSDF_CONDUCTOR | BSDF_DIELECTRIC | BSDF_THIN_DIELECTRIC)
}
