//! Texture plugins: `bitmap` (image files, sRGB-decoded unless `raw`, bilinear or nearest, wrap modes,
//! the storage precision of `format`: `bitmap_format`) and `checkerboard`, both with `to_uv`, and
//! `mesh_attribute` (where it may be read: `mesh_attributes`), and the constant ones (`rawconstant`,
//! `srgb`, `uniform`, `d65`: one texel). Also colour and scalar parameters that may be a texture.
use super::bitmap_format;
use super::loader::Loader;
use super::props::{Entry, Props};
use super::spectrum::SpectrumUse;
use super::spectrum_plugin;
use crate::scene::rgba;
use crate::scene::{MeshAttributeRef, SceneTexture};
use anyhow::{bail, Result};
use caustic_kernel::layout::*;
use glam::Mat4;

/// A colour parameter: a constant, or a texture (whose mean is kept as the constant for the
/// models that need one number, e.g. a plastic's lobe sampling weights).
#[derive(Clone, Copy, Debug)]
pub struct ColorParam {
    pub rgb: [f32; 3],
    pub texture: u32,
}

/// The rows (u, v) of a 2D affine map from a Mitsuba 4×4 `to_uv` (its x, y and translation parts).
fn to_uv_rows(m: Mat4) -> [[f32; 4]; 2] {
    [0, 1].map(|r| {
        let row = m.row(r);
        [row.x, row.y, row.w, 0.0]
    })
}

/// Mitsuba's `mesh_attribute` (`name`, `scale`): the attribute of the shape it is on, interpolated
/// over the hit triangle (`caustic_kernel::texture::eval_at`). The shape's loader checks that it has
/// the attribute (`Loader::keep_read_attributes`).
fn mesh_attribute(props: &Props) -> Result<SceneTexture> {
    let Some(name) = props.string("name")? else { bail!("{}: mesh_attribute needs a 'name'", props.loc) };
    if !(name.starts_with("vertex_") || name.starts_with("face_")) {
        bail!("{}: a mesh attribute's name starts with 'vertex_' or 'face_' (as Mitsuba requires), not '{name}'", props.loc);
    }
    let scale = props.float("scale", 1.0)?;
    if !scale.is_finite() {
        bail!("{}: mesh_attribute's scale must be a finite number, not {scale}", props.loc);
    }
    let record =
        Texture { kind: TEXTURE_MESH_ATTRIBUTE, color0: [scale, scale, scale, 0.0], ..Default::default() };
    let mesh_attribute = Some(MeshAttributeRef { name, origin: props.loc.to_string() });
    Ok(SceneTexture { record, texels: Vec::new(), mesh_attribute })
}

impl Loader {
    /// Parses a `<texture>` (or resolves a `<ref>` to one) and returns its index.
    pub(crate) fn load_texture(&mut self, props: &Props) -> Result<u32> {
        if props.tag == "ref" {
            let id = props.doc_attr_id()?;
            return match self.named_textures.get(&id) {
                Some(&i) => Ok(i),
                None => bail!("{}: <ref id=\"{id}\"> names no texture defined before it", props.loc),
            };
        }
        let to_uv = to_uv_rows(props.transform("to_uv")?);
        let texture = match props.kind.as_str() {
            "checkerboard" => {
                let color0 = props.color("color0", SpectrumUse::Reflectance, [0.4; 3])?;
                let color1 = props.color("color1", SpectrumUse::Reflectance, [0.2; 3])?;
                let record = Texture {
                    kind: TEXTURE_CHECKERBOARD,
                    to_uv,
                    color0: rgba(color0),
                    color1: rgba(color1),
                    ..Default::default()
                };
                SceneTexture { record, texels: Vec::new(), mesh_attribute: None }
            }
            "bitmap" => self.bitmap(props, to_uv)?,
            "mesh_attribute" => mesh_attribute(props)?,
            // Mitsuba's constant textures (its spectra are textures too: `rawconstant` holds raw
            // values, e.g. a flat normal map): one texel.
            "rawconstant" | "srgb" | "uniform" | "d65" => {
                let rgb = spectrum_plugin::to_rgb(props, SpectrumUse::Reflectance)?;
                let record = Texture {
                    kind: TEXTURE_BITMAP,
                    width: 1,
                    height: 1,
                    flags: TEXTURE_NEAREST,
                    to_uv,
                    ..Default::default()
                };
                SceneTexture { record, texels: rgb.to_vec(), mesh_attribute: None }
            }
            other => {
                bail!(
                    "{}: texture type '{other}' is not supported (bitmap, checkerboard, mesh_attribute, rawconstant, srgb, uniform, d65 are)",
                    props.loc
                )
            }
        };
        self.warn_unused(props);
        self.textures.push(texture);
        Ok(self.textures.len() as u32 - 1)
    }

    fn bitmap(&mut self, props: &Props, to_uv: [[f32; 4]; 2]) -> Result<SceneTexture> {
        let Some(name) = props.string("filename")? else { bail!("{}: bitmap needs a 'filename'", props.loc) };
        let path = self.resolve(&name, &props.loc)?;
        let raw = props.boolean("raw", false)?;
        let format = bitmap_format::parse(props)?;
        props.boolean("accel", true)?; // hardware interpolation on CUDA: no value changes
        let mut image = crate::load::image_io::load_linear_rgb(&path, raw)
            .map_err(|e| anyhow::anyhow!("{}: {e:#}", props.loc))?;
        bitmap_format::store(format, &mut image, raw)
            .map_err(|e| anyhow::anyhow!("{}: {}: {e:#}", props.loc, path.display()))?;
        let filter = match props.string("filter_type")?.as_deref() {
            None | Some("bilinear") => 0,
            Some("nearest") => TEXTURE_NEAREST,
            Some(other) => bail!("{}: filter_type must be bilinear or nearest, not '{other}'", props.loc),
        };
        let wrap = match props.string("wrap_mode")?.as_deref() {
            None | Some("repeat") => TEXTURE_WRAP_REPEAT,
            Some("mirror") => TEXTURE_WRAP_MIRROR,
            Some("clamp") => TEXTURE_WRAP_CLAMP,
            Some(other) => bail!("{}: wrap_mode must be repeat, mirror or clamp, not '{other}'", props.loc),
        };
        let record = Texture {
            kind: TEXTURE_BITMAP,
            width: image.width,
            height: image.height,
            flags: filter | (wrap << TEXTURE_WRAP_SHIFT),
            to_uv,
            ..Default::default()
        };
        Ok(SceneTexture { record, texels: image.rgb, mesh_attribute: None })
    }

    /// A colour-valued BSDF parameter that may also be a nested `<texture>` or a `<ref>` to one.
    pub(crate) fn color_param(
        &mut self,
        props: &Props,
        name: &str,
        usage: SpectrumUse,
        default: [f32; 3],
    ) -> Result<ColorParam> {
        let texture_entry = props
            .entries
            .iter()
            .find(|e| e.name.as_deref() == Some(name) && matches!(e.tag.as_str(), "texture" | "ref"));
        let Some(entry) = texture_entry else {
            return Ok(ColorParam { rgb: props.color(name, usage, default)?, texture: NONE });
        };
        props.mark_used(name);
        let index = self.texture_entry(props, entry)?;
        self.note_texture_request(index);
        Ok(ColorParam { rgb: self.texture_mean(index), texture: index })
    }

    /// A scalar BSDF parameter given as a nested `<texture>` or a `<ref>` to one (marked used): the
    /// index of a texture whose luminance is the value Mitsuba's `eval_1` takes, and that value's mean;
    /// `None` when `name` is no texture. For a checkerboard that is a grey copy: each colour becomes its
    /// channel mean (Mitsuba reads a colour as one number so), and the two trade places, because
    /// Mitsuba 3.9.1's scalar `eval_1` gives `color0` to the cells where its colour `eval` gives
    /// `color1` (checkerboard.cpp; caustic renders scalar checkerboards as Mitsuba does).
    pub(crate) fn scalar_texture(&mut self, props: &Props, name: &str) -> Result<Option<(u32, f32)>> {
        let Some(entry) = props
            .entries
            .iter()
            .find(|e| e.name.as_deref() == Some(name) && matches!(e.tag.as_str(), "texture" | "ref"))
        else {
            return Ok(None);
        };
        props.mark_used(name);
        let index = self.texture_entry(props, entry)?;
        self.note_texture_request(index);
        let mut texture = self.textures[index as usize].clone();
        if texture.record.kind == TEXTURE_CHECKERBOARD {
            let grey = |c: [f32; 4]| {
                let m = (c[0] + c[1] + c[2]) / 3.0;
                [m, m, m, c[3]]
            };
            let (color0, color1) = (texture.record.color0, texture.record.color1);
            texture.record.color0 = grey(color1);
            texture.record.color1 = grey(color0);
            self.textures.push(texture);
            let grey_index = self.textures.len() as u32 - 1;
            let mean = self.texture_mean(grey_index)[0];
            return Ok(Some((grey_index, mean)));
        }
        let mean = caustic_kernel::spectrum::luminance(glam::Vec3::from(self.texture_mean(index)));
        Ok(Some((index, mean)))
    }

    /// A number-valued parameter that Mitsuba reads as a texture (`props.texture(name)`, then
    /// `eval_1`): a nested texture or `<ref>` (its index and mean, as `scalar_texture`), a `<float>`,
    /// or a constant colour (`<rgb>`, `<spectrum>`), whose `eval_1` is the mean of its three
    /// channels (Mitsuba 3.9.1 renders an `<rgb>` of (1, 0, 0) as 0.3333, not as its luminance
    /// 0.2126: mask opacity, blend weight, rough alpha, principled weights alike); `default` where
    /// absent. The texture index is `NONE` for a constant.
    pub(crate) fn scalar_param(&mut self, props: &Props, name: &str, default: f32) -> Result<(f32, u32)> {
        if let Some((texture, mean)) = self.scalar_texture(props, name)? {
            return Ok((mean, texture));
        }
        let tag = props.entries.iter().find(|e| e.name.as_deref() == Some(name)).map(|e| e.tag.as_str());
        let value = match tag {
            Some("rgb" | "spectrum") => {
                let c = props.color(name, SpectrumUse::Reflectance, [default; 3])?;
                (c[0] + c[1] + c[2]) / 3.0
            }
            _ => props.float(name, default)?,
        };
        Ok((value, NONE))
    }

    /// Refuses a texture with a value whose luminance is not a positive finite number (an index of
    /// refraction read through `eval_1`): bilinear filtering between such texels stays positive.
    pub(crate) fn positive_texture(&self, index: u32, props: &Props, what: &str) -> Result<()> {
        let t = &self.textures[index as usize];
        let values: Vec<[f32; 3]> = if t.record.kind == TEXTURE_CHECKERBOARD {
            [t.record.color0, t.record.color1].iter().map(|c| [c[0], c[1], c[2]]).collect()
        } else {
            t.texels.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
        };
        for c in values {
            let l = caustic_kernel::spectrum::luminance(glam::Vec3::from(c));
            if !(l > 0.0 && l.is_finite() && c.iter().all(|v| v.is_finite() && *v >= 0.0)) {
                bail!(
                    "{}: a textured {what} must be positive everywhere; the texture holds {c:?}",
                    props.loc
                );
            }
        }
        Ok(())
    }

    fn texture_entry(&mut self, props: &Props, entry: &Entry) -> Result<u32> {
        let p = self.props(props.src, entry.node)?;
        self.load_texture(&p)
    }

    /// The mean colour of a texture (checkerboard: of its two colours).
    pub(crate) fn texture_mean(&self, index: u32) -> [f32; 3] {
        self.textures[index as usize].mean()
    }
}
