//! BSDF plugins: `diffuse`, `phong` (the modified Phong BRDF), `conductor`, `roughconductor`,
//! `dielectric`, `thindielectric`, `roughdielectric`, `plastic`, `roughplastic`, `principled`,
//! `principledthin`, `twosided`, `mask`, `blendbsdf` (`blend`) and `pplastic` (`pplastic`); with Mitsuba 3's parameter names and defaults.
use super::ior;
use super::loader::Loader;
use super::props::Props;
use super::spectrum::SpectrumUse;
use super::textures::ColorParam;
use crate::scene::rgba;
use anyhow::{bail, Result};
use caustic_kernel::bsdf::principled::{eta_from_specular, PrincipledParams};
use caustic_kernel::bsdf::principled_thin::ThinParams;
use caustic_kernel::bsdf::textured_weights::{self, SLOTS, SLOT_ETA};
use caustic_kernel::layout::*;

fn set_reflectance(m: &mut Material, c: ColorParam) {
    m.reflectance = rgba(c.rgb);
    m.reflectance_texture = c.texture;
}

fn set_specular(m: &mut Material, c: ColorParam) {
    m.specular_reflectance = rgba(c.rgb);
    m.specular_texture = c.texture;
}

/// caustic's dispersion extension of the dielectrics (Mitsuba 3 has none): `glass` naming a catalogue
/// glass (`ior::NAMED_GLASSES`, Sellmeier's law; it also sets the interior's index), or `abbe_number`
/// (the glass's Abbe number `V_d`, with `int_ior` as its index at the d line) or `cauchy_b` (Cauchy's
/// `B`, µm², of the interior), which make the interior's index `n_d + B·(1/λ² − 1/λ_d²)`. The exterior
/// stays constant. Mitsuba reads such a scene with a warning about the unknown parameter and renders it
/// without dispersion.
fn dispersion(
    props: &Props,
    m: &mut Material,
    int_ior: f32,
    ext_ior: f32,
    glass: Option<&ior::Glass>,
) -> Result<()> {
    use caustic_kernel::wavelength::*;
    let given = [glass.is_some(), props.has("abbe_number"), props.has("cauchy_b")];
    if given.iter().filter(|&&g| g).count() > 1 {
        bail!("{}: give one of 'glass', 'abbe_number' and 'cauchy_b' for dispersion", props.loc);
    }
    if let Some(g) = glass {
        m.flags |= MATERIAL_DISPERSIVE | MATERIAL_SELLMEIER;
        m.conductor_eta = [g.b[0], g.b[1], g.b[2], 0.0];
        m.conductor_k = [g.c[0], g.c[1], g.c[2], 0.0];
        m.params[PARAM_EXTERIOR_IOR] = ext_ior;
    } else {
        let b = if props.has("abbe_number") {
            let abbe = props.float("abbe_number", 0.0)?;
            if !(abbe > 0.0 && abbe.is_finite()) {
                bail!("{}: 'abbe_number' must be a positive number, not {abbe}", props.loc);
            }
            cauchy_b_from_abbe(int_ior, abbe)
        } else if props.has("cauchy_b") {
            props.float("cauchy_b", 0.0)?
        } else {
            return Ok(());
        };
        if !b.is_finite() {
            bail!("{}: the dispersion coefficient must be finite, not {b}", props.loc);
        }
        if b == 0.0 {
            return Ok(());
        }
        m.flags |= MATERIAL_DISPERSIVE;
        m.params[PARAM_CAUCHY_B] = b / ext_ior;
    }
    for lambda in [WAVELENGTH_MIN, WAVELENGTH_MAX] {
        let eta = eta_at(m, lambda);
        if !(eta > 0.0 && eta.is_finite()) {
            bail!("{}: with this dispersion the index of refraction at {lambda} nm is {eta}", props.loc);
        }
    }
    Ok(())
}

/// Roughness below this is treated as this: keeps microfacet densities finite in f32.
const MIN_ALPHA: f32 = 1.0e-4;

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
            "diffuse" => {
                let mut m = Material { kind: BSDF_DIFFUSE, ..Default::default() };
                let reflectance =
                    self.color_param(props, "reflectance", SpectrumUse::Reflectance, [0.5; 3])?;
                set_reflectance(&mut m, reflectance);
                m
            }
            "phong" => self.phong(props)?,
            "fuzzymetal" => self.fuzzy_metal(props)?,
            "conductor" | "roughconductor" => self.conductor(props)?,
            "dielectric" | "thindielectric" | "roughdielectric" => self.dielectric(props)?,
            "plastic" | "roughplastic" => self.plastic(props)?,
            "principled" => self.principled(props)?,
            "principledthin" => self.principled_thin(props)?,
            "blendbsdf" => self.blend(props)?,
            "pplastic" => self.pplastic(props)?,
            "twosided" => self.twosided(props)?,
            "mask" => self.mask(props)?,
            // Mitsuba's `null`: a surface light passes straight through (the boundary of an emitter
            // or of nothing). A mask of opacity 0 is exactly that (`kernel/src/mask.rs`), its nested
            // model never evaluated.
            "null" => Material {
                kind: BSDF_DIFFUSE,
                flags: MATERIAL_MASK,
                opacity: 0.0,
                opacity_texture: NONE,
                ..Default::default()
            },
            "normalmap" | "bumpmap" => self.normal_or_bump_map(props)?,
            other => {
                let message = format!(
                    "{}: bsdf type '{other}' is not supported yet; rendering it as grey diffuse",
                    props.loc
                );
                self.substituted(format!("bsdf '{other}'"), &props.loc, message);
                props.mark_all_used();
                Material { kind: BSDF_DIFFUSE, reflectance: [0.5, 0.5, 0.5, 0.0], ..Default::default() }
            }
        })
    }

    /// caustic's own type for "Ray Tracing in One Weekend"'s metal: `reflectance` (the book's albedo,
    /// texturable) and `fuzz` in [0, 1] (0: a mirror).
    fn fuzzy_metal(&mut self, props: &Props) -> Result<Material> {
        let albedo = self.color_param(props, "reflectance", SpectrumUse::Reflectance, [1.0; 3])?;
        let fuzz = props.float("fuzz", 0.0)?;
        if !(0.0..=1.0).contains(&fuzz) {
            bail!("{}: fuzzymetal fuzz must be in [0, 1] (the book clamps it to 1), got {fuzz}", props.loc);
        }
        let mut m = Material { kind: BSDF_FUZZY_METAL, alpha_u: fuzz, ..Default::default() };
        set_reflectance(&mut m, albedo);
        Ok(m)
    }

    fn phong(&mut self, props: &Props) -> Result<Material> {
        let kd = self.color_param(props, "diffuse_reflectance", SpectrumUse::Reflectance, [0.5; 3])?;
        let ks = self.color_param(props, "specular_reflectance", SpectrumUse::Reflectance, [0.2; 3])?;
        let exponent = props.float("exponent", 30.0)?;
        if !(0.0..=1.0e6).contains(&exponent) {
            bail!("{}: phong exponent must be in [0, 1e6], got {exponent}", props.loc);
        }
        if (0..3).any(|c| kd.rgb[c] + ks.rgb[c] > 1.0 + 1e-6) {
            self.warn(&format!(
                "{}: phong with diffuse + specular reflectance > 1 does not conserve energy",
                props.loc
            ));
        }
        let mut m = Material { kind: BSDF_PHONG, eta: exponent, ..Default::default() };
        set_reflectance(&mut m, kd);
        set_specular(&mut m, ks);
        Ok(m)
    }

    /// Mitsuba's `mask`: `opacity` (number, colour or texture; its luminance, default 0.5) and one
    /// nested BSDF, which the material record copies (`caustic_kernel::mask` renders it).
    fn mask(&mut self, props: &Props) -> Result<Material> {
        let nested: Vec<_> = props.nested("bsdf").into_iter().chain(props.nested("ref")).collect();
        let inner_entry = match nested.as_slice() {
            [one] => *one,
            [] => bail!("{}: mask needs a nested <bsdf>", props.loc),
            _ => bail!("{}: mask takes one nested BSDF (Mitsuba refuses more)", props.loc),
        };
        let inner_props = self.props(props.src, inner_entry.node)?;
        let index = self.load_bsdf(&inner_props)?;
        let mut m = self.materials[index as usize];
        if m.flags & MATERIAL_MASK != 0 {
            bail!("{}: a mask inside a mask is not supported", props.loc);
        }
        if caustic_kernel::two_sided::back_plus_one(&m) != 0 {
            bail!("{}: a mask around a twosided of two BSDFs is not supported", props.loc);
        }
        // A number as Mitsuba reads it (`Texture::eval_1`: `scalar_param`).
        let (opacity, texture) = self.scalar_param(props, "opacity", 0.5)?;
        m.flags |= MATERIAL_MASK;
        m.opacity = opacity.clamp(0.0, 1.0);
        m.opacity_texture = texture;
        Ok(m)
    }

    /// Mitsuba's `twosided`: one nested BSDF (`<bsdf>` or `<ref>`) on both sides, or two, the first on
    /// the front and the second, mirrored, on the back (`caustic_kernel::two_sided`: the front's record
    /// names the back's).
    fn twosided(&mut self, props: &Props) -> Result<Material> {
        // Marks the nested elements as read; the order comes from the entries.
        props.nested("bsdf");
        props.nested("ref");
        let children: Vec<_> = props.entries.iter().filter(|e| e.tag == "bsdf" || e.tag == "ref").collect();
        let mut sides = Vec::new();
        for entry in &children {
            let child_props = self.props(props.src, entry.node)?;
            let index = self.load_bsdf(&child_props)?;
            let m = self.materials[index as usize];
            if self.transmits(&m) {
                bail!("{}: twosided cannot wrap a transmissive BSDF ('{}')", props.loc, child_props.kind);
            }
            sides.push((m, entry));
        }
        match sides.as_slice() {
            [] => bail!("{}: twosided needs a nested <bsdf>", props.loc),
            [(front, _)] => Ok(Material { flags: front.flags | MATERIAL_TWO_SIDED, ..*front }),
            [(front, _), (back, _)] => {
                for (m, entry) in &sides {
                    let refusal = if m.flags & MATERIAL_TWO_SIDED != 0 {
                        Some("a twosided inside a twosided of two BSDFs is not supported")
                    } else if m.flags & MATERIAL_MASK != 0 {
                        Some("a mask inside a twosided of two BSDFs is not supported")
                    } else if m.perturb != 0 {
                        Some("a normalmap or bumpmap inside a twosided of two BSDFs is not supported")
                    } else {
                        None
                    };
                    if let Some(why) = refusal {
                        bail!("{}: {why}", entry.loc);
                    }
                }
                let back_index = self.materials.len() as u32;
                if back_index >= u32::MAX >> MATERIAL_BACK_SHIFT {
                    bail!("{}: too many materials for a twosided's back ({back_index})", props.loc);
                }
                // The back's own record, mirrored by its flag; the front's names it.
                self.materials.push(Material { flags: back.flags | MATERIAL_TWO_SIDED, ..*back });
                let flags = front.flags | MATERIAL_TWO_SIDED | ((back_index + 1) << MATERIAL_BACK_SHIFT);
                Ok(Material { flags, ..*front })
            }
            _ => bail!("{}: twosided takes one or two nested BSDFs (Mitsuba refuses more)", props.loc),
        }
    }

    /// `distribution`, `alpha` / `alpha_u`, `alpha_v` of the rough models (Mitsuba's default: Beckmann,
    /// α = 0.1); sets the material's roughness fields and flags.
    pub(super) fn microfacet(&mut self, props: &Props, m: &mut Material) -> Result<()> {
        match props.string("distribution")?.map(|d| d.to_lowercase()).as_deref() {
            None | Some("beckmann") => m.flags |= MATERIAL_BECKMANN,
            Some("ggx") => {}
            Some(other) => bail!("{}: distribution must be beckmann or ggx, not '{other}'", props.loc),
        }
        // As Mitsuba: either `alpha`, or both of `alpha_u` and `alpha_v`.
        let (has_u, has_v) = (props.has("alpha_u"), props.has("alpha_v"));
        if (has_u || has_v) && props.has("alpha") {
            bail!("{}: give either 'alpha' or 'alpha_u'/'alpha_v', not both", props.loc);
        }
        if has_u != has_v {
            bail!("{}: 'alpha_u' and 'alpha_v' must be given together", props.loc);
        }
        // Each may be a texture (its luminance; `caustic_kernel::bsdf::Bsdf::new`), whose mean stands
        // in where one number is needed, or a colour (its channels' mean: `scalar_param`).
        let mut param = |name: &str, default: f32| self.scalar_param(props, name, default);
        let alpha = param("alpha", 0.1)?;
        let (alpha_u, alpha_u_texture) = if has_u { param("alpha_u", 0.1)? } else { alpha };
        let (alpha_v, alpha_v_texture) = if has_v { param("alpha_v", 0.1)? } else { alpha };
        for (name, a) in [("alpha_u", alpha_u), ("alpha_v", alpha_v)] {
            if !(0.0..=10.0).contains(&a) {
                bail!("{}: {name} must be in [0, 10], got {a}", props.loc);
            }
        }
        (m.alpha_u_texture, m.alpha_v_texture) = (alpha_u_texture, alpha_v_texture);
        if !props.boolean("sample_visible", true)? {
            self.warn(&format!("{}: sample_visible=false is not supported; caustic always samples visible normals (same image, less noise)", props.loc));
        }
        m.alpha_u = alpha_u.max(MIN_ALPHA);
        m.alpha_v = alpha_v.max(MIN_ALPHA);
        Ok(())
    }

    fn conductor(&mut self, props: &Props) -> Result<Material> {
        let rough = props.kind == "roughconductor";
        let mut m = Material {
            kind: if rough { BSDF_ROUGH_CONDUCTOR } else { BSDF_CONDUCTOR },
            ..Default::default()
        };
        if rough {
            self.microfacet(props, &mut m)?;
        }
        // As Mitsuba: a given `eta` (or `material` none, the default) selects `eta`/`k` (defaults 0
        // and 1, a perfect mirror), and `material` is then not used; otherwise the named material.
        let material = props.string("material")?.unwrap_or_else(|| "none".to_string());
        // Either may be a texture, read as a colour (Mitsuba's `eval`): `eta`'s index goes to
        // `param_texture`, `k`'s to `reflectance_texture`, which conductors have no other use for.
        let (eta, k) = if props.has("eta") || material == "none" {
            (
                self.color_param(props, "eta", SpectrumUse::Unbounded, [0.0; 3])?,
                self.color_param(props, "k", SpectrumUse::Unbounded, [1.0; 3])?,
            )
        } else {
            let dirs = ior::with_ancestors(&self.search_paths);
            let (eta, k) = ior::conductor_eta_k(&material, &dirs)
                .map_err(|e| anyhow::anyhow!("{}: {e:#}", props.loc))?;
            (ColorParam { rgb: eta, texture: NONE }, ColorParam { rgb: k, texture: NONE })
        };
        (m.conductor_eta, m.param_texture) = (rgba(eta.rgb), eta.texture);
        (m.conductor_k, m.reflectance_texture) = (rgba(k.rgb), k.texture);
        set_specular(
            &mut m,
            self.color_param(props, "specular_reflectance", SpectrumUse::Reflectance, [1.0; 3])?,
        );
        Ok(m)
    }

    /// An `int_ior` / `ext_ior` property (a `<float>` or a named material), range-checked.
    fn ior(&self, props: &Props, name: &str, default: &str) -> Result<f32> {
        let value = ior::ior_property(props, name, default)?;
        if !(value > 0.0 && value < 100.0) {
            bail!("{}: {name} must be in (0, 100), got {value}", props.loc);
        }
        Ok(value)
    }

    fn relative_ior(&self, props: &Props, int_default: &str) -> Result<f32> {
        let int_ior = self.ior(props, "int_ior", int_default)?;
        let ext_ior = self.ior(props, "ext_ior", "air")?;
        Ok(int_ior / ext_ior)
    }

    fn dielectric(&mut self, props: &Props) -> Result<Material> {
        let kind = match props.kind.as_str() {
            "dielectric" => BSDF_DIELECTRIC,
            "thindielectric" => BSDF_THIN_DIELECTRIC,
            _ => BSDF_ROUGH_DIELECTRIC,
        };
        // caustic's `glass` names the interior's glass, its index and its dispersion.
        let glass = match props.string("glass")? {
            Some(name) => Some(ior::named_glass(&name).ok_or_else(|| {
                anyhow::anyhow!(
                    "{}: no glass is known by the name '{name}' (one of: {})",
                    props.loc,
                    ior::glass_names()
                )
            })?),
            None => None,
        };
        if glass.is_some() && props.has("int_ior") {
            bail!("{}: give 'int_ior' or 'glass', not both (the glass has its own index)", props.loc);
        }
        let ext_ior = self.ior(props, "ext_ior", "air")?;
        let mut m = Material { kind, ..Default::default() };
        let int_ior = match glass {
            Some(_) => {
                // The glass's index at the d line, for anything that asks without a wavelength.
                dispersion(props, &mut m, 0.0, ext_ior, glass)?;
                caustic_kernel::wavelength::eta_at(&m, caustic_kernel::wavelength::LAMBDA_D) * ext_ior
            }
            None => {
                let int_ior = self.ior(props, "int_ior", "bk7")?;
                m.eta = int_ior / ext_ior;
                dispersion(props, &mut m, int_ior, ext_ior, None)?;
                int_ior
            }
        };
        m.eta = int_ior / ext_ior;
        if kind == BSDF_ROUGH_DIELECTRIC {
            self.microfacet(props, &mut m)?;
        }
        set_specular(
            &mut m,
            self.color_param(props, "specular_reflectance", SpectrumUse::Reflectance, [1.0; 3])?,
        );
        // A texture is read as a colour (Mitsuba's `eval`) from `param_texture`.
        let transmittance =
            self.color_param(props, "specular_transmittance", SpectrumUse::Reflectance, [1.0; 3])?;
        (m.specular_transmittance, m.param_texture) = (rgba(transmittance.rgb), transmittance.texture);
        Ok(m)
    }

    fn plastic(&mut self, props: &Props) -> Result<Material> {
        let rough = props.kind == "roughplastic";
        let mut m = Material {
            kind: if rough { BSDF_ROUGH_PLASTIC } else { BSDF_PLASTIC },
            eta: self.relative_ior(props, "polypropylene")?,
            ..Default::default()
        };
        if rough {
            self.microfacet(props, &mut m)?;
            // Its precomputed transmittance table is for one roughness.
            if m.alpha_u_texture != NONE || m.alpha_v_texture != NONE {
                let message = format!(
                    "{}: a textured alpha of roughplastic is not supported; using the texture's mean, {}",
                    props.loc, m.alpha_u
                );
                self.substituted("textured roughplastic alpha".into(), &props.loc, message);
                (m.alpha_u_texture, m.alpha_v_texture) = (NONE, NONE);
            }
        }
        set_reflectance(
            &mut m,
            self.color_param(props, "diffuse_reflectance", SpectrumUse::Reflectance, [0.5; 3])?,
        );
        set_specular(
            &mut m,
            self.color_param(props, "specular_reflectance", SpectrumUse::Reflectance, [1.0; 3])?,
        );
        if props.boolean("nonlinear", false)? {
            m.flags |= MATERIAL_NONLINEAR;
        }
        Ok(m)
    }

    /// Mitsuba's `principled` (`caustic_kernel::bsdf::principled`): `base_color` (colour or
    /// texture), every weight a number or a texture (read as its luminance, as Mitsuba's `eval_1`;
    /// those beyond the record's slots through `weight_tables`), `eta` or `specular` (numbers, not
    /// both, as Mitsuba), and the three sampling rates.
    fn principled(&mut self, props: &Props) -> Result<Material> {
        let base = self.color_param(props, "base_color", SpectrumUse::Reflectance, [0.5; 3])?;
        let mut m = Material { kind: BSDF_PRINCIPLED, ..Default::default() };
        set_reflectance(&mut m, base);
        let roughness;
        let anisotropic;
        let metallic;
        (roughness, m.alpha_u_texture) = self.principled_weight(props, "roughness", 0.5)?;
        (anisotropic, m.alpha_v_texture) = self.principled_weight(props, "anisotropic", 0.0)?;
        (metallic, m.specular_texture) = self.principled_weight(props, "metallic", 0.0)?;
        (m.alpha_u, m.alpha_v) = (roughness, anisotropic);
        m.specular_reflectance = [metallic, metallic, metallic, 0.0];
        let mut slots = [None; SLOTS];
        let mut weight = |slot, name, default| self.slot_weight(props, &mut slots, slot, name, default);
        // The slots' order is `PrincipledParams::pack`'s.
        let p = PrincipledParams {
            spec_trans: weight(0, "spec_trans", 0.0)?,
            spec_tint: weight(1, "spec_tint", 0.0)?,
            sheen: weight(2, "sheen", 0.0)?,
            sheen_tint: weight(3, "sheen_tint", 0.0)?,
            clearcoat: weight(4, "clearcoat", 0.0)?,
            clearcoat_gloss: weight(5, "clearcoat_gloss", 0.0)?,
            flatness: weight(6, "flatness", 0.0)?,
            spec_rate: props.float("main_specular_sampling_rate", 1.0)?,
            clearcoat_rate: props.float("clearcoat_sampling_rate", 1.0)?,
            diffuse_rate: props.float("diffuse_reflectance_sampling_rate", 1.0)?,
        };
        let rates = [p.spec_rate, p.clearcoat_rate, p.diffuse_rate];
        if rates.iter().any(|r| !(r.is_finite() && *r >= 0.0)) || p.spec_rate + p.diffuse_rate <= 0.0 {
            bail!(
                "{}: principled sampling rates must be finite and non-negative, and the main specular and \
                 diffuse ones not both zero (got {rates:?})",
                props.loc
            );
        }
        // Mitsuba's lobe switch: a weight given (as a texture, or a number other than 0) turns its
        // lobe on; that of the transmission also nudges an index of 1 (`eta` 1, `specular` 0), which
        // cannot refract, to a plausible one.
        let has_spec_trans = slots[0].is_some() || p.spec_trans != 0.0;
        m.eta = match (props.has("eta"), props.has("specular")) {
            (true, true) => bail!(
                "{}: principled takes 'eta' or 'specular' (the same reflectance), not both, as Mitsuba",
                props.loc
            ),
            (true, false) => {
                let eta = props.float("eta", 1.5)?;
                if !(eta > 0.0 && eta.is_finite()) {
                    bail!("{}: principled eta must be a positive number, not {eta}", props.loc);
                }
                if has_spec_trans && eta == 1.0 {
                    1.001
                } else {
                    eta
                }
            }
            (false, _) => {
                let specular = props.float("specular", 0.5)?;
                let specular = if has_spec_trans && specular == 0.0 { 1e-3 } else { specular };
                let eta = eta_from_specular(specular);
                if !((0.0..12.5).contains(&specular) && eta > 0.0 && eta.is_finite()) {
                    bail!("{}: principled specular must be in [0, 12.5), not {specular}", props.loc);
                }
                eta
            }
        };
        let weights = [roughness, anisotropic, metallic, p.spec_trans, p.spec_tint, p.sheen, p.sheen_tint];
        let weights = weights.into_iter().chain([p.clearcoat, p.clearcoat_gloss, p.flatness]);
        if weights.clone().any(|w| !w.is_finite()) {
            bail!("{}: principled weights must be finite numbers", props.loc);
        }
        p.pack(&mut m);
        self.place_weight_textures(&mut m, slots);
        Ok(m)
    }

    /// Mitsuba's `principledthin` (`caustic_kernel::bsdf::principled_thin`): `base_color` (colour or
    /// texture), every weight and `eta` a number or a texture (its luminance; as `principled`), and
    /// the four sampling rates; Mitsuba's defaults.
    fn principled_thin(&mut self, props: &Props) -> Result<Material> {
        let base = self.color_param(props, "base_color", SpectrumUse::Reflectance, [0.5; 3])?;
        let mut m = Material { kind: BSDF_PRINCIPLED_THIN, ..Default::default() };
        set_reflectance(&mut m, base);
        (m.alpha_u, m.alpha_u_texture) = self.principled_weight(props, "roughness", 0.5)?;
        (m.alpha_v, m.alpha_v_texture) = self.principled_weight(props, "anisotropic", 0.0)?;
        let mut slots = [None; SLOTS];
        let mut weight = |slot, name, default| self.slot_weight(props, &mut slots, slot, name, default);
        // The slots' order is `ThinParams::pack`'s.
        m.eta = weight(SLOT_ETA, "eta", 1.5)?;
        let p = ThinParams {
            spec_trans: weight(0, "spec_trans", 0.0)?,
            spec_tint: weight(1, "spec_tint", 0.0)?,
            sheen: weight(2, "sheen", 0.0)?,
            sheen_tint: weight(3, "sheen_tint", 0.0)?,
            flatness: weight(4, "flatness", 0.0)?,
            diff_trans: weight(5, "diff_trans", 0.0)?,
            spec_refl_rate: props.float("specular_reflectance_sampling_rate", 1.0)?,
            spec_trans_rate: props.float("specular_transmittance_sampling_rate", 1.0)?,
            diff_refl_rate: props.float("diffuse_reflectance_sampling_rate", 1.0)?,
            diff_trans_rate: props.float("diffuse_transmittance_sampling_rate", 1.0)?,
        };
        let rates = [p.spec_refl_rate, p.spec_trans_rate, p.diff_refl_rate, p.diff_trans_rate];
        if rates.iter().any(|r| !(r.is_finite() && *r >= 0.0)) || rates.iter().sum::<f32>() <= 0.0 {
            bail!(
                "{}: principledthin sampling rates must be finite and non-negative, and not all zero (got {rates:?})",
                props.loc
            );
        }
        if !(m.eta > 0.0 && m.eta.is_finite()) {
            bail!("{}: principledthin eta must be a positive number, not {}", props.loc, m.eta);
        }
        let weights = [
            m.alpha_u,
            m.alpha_v,
            p.spec_trans,
            p.spec_tint,
            p.sheen,
            p.sheen_tint,
            p.flatness,
            p.diff_trans,
        ];
        if weights.iter().any(|w| !w.is_finite()) {
            bail!("{}: principledthin weights must be finite numbers", props.loc);
        }
        p.pack(&mut m);
        self.place_weight_textures(&mut m, slots);
        Ok(m)
    }

    /// A principled weight beyond the record's own slots (`principled_weight`): a texture is noted
    /// in `slots[slot]`.
    fn slot_weight(
        &mut self,
        props: &Props,
        slots: &mut [Option<u32>; SLOTS],
        slot: usize,
        name: &str,
        default: f32,
    ) -> Result<f32> {
        let (value, texture) = self.principled_weight(props, name, default)?;
        slots[slot] = (texture != NONE).then_some(texture);
        Ok(value)
    }

    /// Lists a principled record's textured weights beyond its own slots, if it has any, in
    /// `weight_tables` (the record's numbers keep the textures' means).
    fn place_weight_textures(&mut self, m: &mut Material, slots: [Option<u32>; SLOTS]) {
        if slots.iter().any(Option::is_some) {
            m.table = self.weight_tables.len() as u32;
            self.weight_tables.push(textured_weights::table(slots));
        }
    }

    /// A principled weight: a number, a colour or a texture, as Mitsuba's `eval_1` reads it
    /// (`scalar_param`; Blender's exporter writes `spec_tint` and `sheen_tint` as `<rgb>`).
    fn principled_weight(&mut self, props: &Props, name: &str, default: f32) -> Result<(f32, u32)> {
        self.scalar_param(props, name, default)
    }
}

impl Loader {
    /// Whether material `m` transmits (Mitsuba's `twosided` refuses it then): a dielectric, a principled
    /// material with its transmission lobe, a blend of either.
    fn transmits(&self, m: &Material) -> bool {
        match m.kind {
            BSDF_DIELECTRIC | BSDF_THIN_DIELECTRIC | BSDF_ROUGH_DIELECTRIC => true,
            BSDF_PRINCIPLED => PrincipledParams::unpack(m).spec_trans > 0.0,
            // Mitsuba's thin sheet always has its diffuse transmission lobe.
            BSDF_PRINCIPLED_THIN => true,
            BSDF_BLEND => {
                let (a, b) = caustic_kernel::bsdf::blend::children(m);
                self.transmits(&self.materials[a as usize]) || self.transmits(&self.materials[b as usize])
            }
            _ => false,
        }
    }
}
