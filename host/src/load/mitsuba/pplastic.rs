//! Mitsuba's `pplastic` in its unpolarized form (`caustic_kernel::bsdf::pplastic`):
//! `diffuse_reflectance` (0.5) and `specular_reflectance` (1), colours or textures; `eta` (a number, or
//! a texture whose luminance is read, each of its values positive) or `int_ior`/`ext_ior` (polypropylene over air,
//! positive and different, as Mitsuba requires; not both ways, as Mitsuba); the rough models'
//! `distribution` (Beckmann by default) and `alpha`/`alpha_u`/`alpha_v`. The probability of sampling
//! the glossy lobe is Mitsuba's: the specular reflectance's mean over the sum of both means (a texture's
//! mean over its texels, each colour's over its channels).
use super::loader::Loader;
use super::props::Props;
use super::spectrum::SpectrumUse;
use anyhow::{bail, Result};
use caustic_kernel::bsdf::pplastic::PARAM_SPECULAR_WEIGHT;
use caustic_kernel::layout::*;

impl Loader {
    pub(super) fn pplastic(&mut self, props: &Props) -> Result<Material> {
        let mut m = Material { kind: BSDF_PPLASTIC, ..Default::default() };
        m.eta = if props.has("eta") {
            if props.has("int_ior") || props.has("ext_ior") {
                bail!("{}: pplastic takes 'eta' or 'int_ior'/'ext_ior', not both (as Mitsuba)", props.loc);
            }
            // A texture is read as Mitsuba's `eval_1` reads it (its luminance) from `param_texture`;
            // its mean stands in where one number is needed.
            let eta = match self.scalar_texture(props, "eta")? {
                Some((texture, mean)) => {
                    self.positive_texture(texture, props, "pplastic eta")?;
                    m.param_texture = texture;
                    mean
                }
                None => props.float("eta", 0.0)?,
            };
            if !(eta > 0.0 && eta.is_finite()) {
                bail!("{}: pplastic eta must be a positive number, not {eta}", props.loc);
            }
            eta
        } else {
            let int_ior = super::ior::ior_property(props, "int_ior", "polypropylene")?;
            let ext_ior = super::ior::ior_property(props, "ext_ior", "air")?;
            if !(int_ior > 0.0 && ext_ior > 0.0 && int_ior != ext_ior && (int_ior / ext_ior).is_finite()) {
                bail!(
                    "{}: pplastic's interior and exterior indices must be positive and differ (as Mitsuba), got {int_ior} and {ext_ior}",
                    props.loc
                );
            }
            int_ior / ext_ior
        };
        self.microfacet(props, &mut m)?;
        let diffuse = self.color_param(props, "diffuse_reflectance", SpectrumUse::Reflectance, [0.5; 3])?;
        let specular = self.color_param(props, "specular_reflectance", SpectrumUse::Reflectance, [1.0; 3])?;
        let mean = |c: &super::textures::ColorParam, loader: &Self| -> f32 {
            let rgb = if c.texture == NONE { c.rgb } else { loader.texture_mean(c.texture) };
            (rgb[0] + rgb[1] + rgb[2]) / 3.0
        };
        let (d_mean, s_mean) = (mean(&diffuse, self), mean(&specular, self));
        let weight = s_mean / (d_mean + s_mean);
        if !weight.is_finite() {
            bail!("{}: pplastic's diffuse and specular reflectances are both black", props.loc);
        }
        m.params[PARAM_SPECULAR_WEIGHT] = weight;
        (m.reflectance, m.reflectance_texture) = (crate::scene::rgba(diffuse.rgb), diffuse.texture);
        (m.specular_reflectance, m.specular_texture) = (crate::scene::rgba(specular.rgb), specular.texture);
        Ok(m)
    }
}
