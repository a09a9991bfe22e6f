//! BSDF plugins: `diffuse`, `phong` (the modified Phong BRDF), `twosided`.
use super::props::Props;
use super::spectrum::SpectrumUse;
use super::Loader;
use anyhow::{bail, Result};
use caustic_kernel::scene::{Material, BSDF_DIFFUSE, BSDF_PHONG};

fn rgba(c: [f32; 3]) -> [f32; 4] {
    [c[0], c[1], c[2], 0.0]
}

impl Loader {
    /// Parses a `<bsdf>` (or resolves a `<ref>`) and returns its index in the material list.
    pub(crate) fn load_bsdf(&mut self, props: &Props) -> Result<u32> {
        if props.tag == "ref" {
            let id = props.doc_attr_id()?;
            return match self.named_bsdfs.get(&id) {
                Some(&i) => Ok(i),
                None => bail!("{}: <ref id=\"{id}\"> names no BSDF defined before it", props.loc),
            };
        }
        let material = self.parse_material(props)?;
        self.warn_unused(props);
        self.materials.push(material);
        Ok(self.materials.len() as u32 - 1)
    }

    fn parse_material(&mut self, props: &Props) -> Result<Material> {
        Ok(match props.kind.as_str() {
            "diffuse" => Material {
                kind: BSDF_DIFFUSE,
                diffuse: rgba(props.color("reflectance", SpectrumUse::Reflectance, [0.5; 3])?),
                ..Default::default()
            },
            "phong" => {
                let kd = props.color("diffuse_reflectance", SpectrumUse::Reflectance, [0.5; 3])?;
                let ks = props.color("specular_reflectance", SpectrumUse::Reflectance, [0.2; 3])?;
                let exponent = props.float("exponent", 30.0)?;
                if !(0.0..=1.0e6).contains(&exponent) {
                    bail!("{}: phong exponent must be in [0, 1e6], got {exponent}", props.loc);
                }
                if (0..3).any(|c| kd[c] + ks[c] > 1.0 + 1e-6) {
                    self.warn(&format!("{}: phong with diffuse + specular reflectance > 1 does not conserve energy", props.loc));
                }
                Material { kind: BSDF_PHONG, exponent, diffuse: rgba(kd), specular: rgba(ks), ..Default::default() }
            }
            "twosided" => {
                let nested = props.nested("bsdf");
                let refs = props.nested("ref");
                let inner_entry = match (nested.first(), refs.first()) {
                    (Some(e), _) | (None, Some(e)) => *e,
                    (None, None) => bail!("{}: twosided needs a nested <bsdf>", props.loc),
                };
                let inner_props = self.props(&props.path, props.doc, inner_entry.node)?;
                let index = self.load_bsdf(&inner_props)?;
                let mut m = self.materials[index as usize];
                m.two_sided = 1;
                m
            }
            other => {
                self.warn(&format!("{}: bsdf type '{other}' is not supported yet; rendering it as grey diffuse", props.loc));
                props.mark_all_used();
                Material { kind: BSDF_DIFFUSE, diffuse: [0.5, 0.5, 0.5, 0.0], ..Default::default() }
            }
        })
    }
}
