//! Emitter plugins: `area` and `directionalarea` (attached to a shape; the radiance may be a
//! texture), `point`, `spot`
//! (with an optional `texture`), `projector`, `directional`, `constant` and `envmap` (at most one
//! environment emitter per scene, as in Mitsuba).
use super::loader::{AreaEmission, Loader};
use super::props::Props;
use super::spectrum::SpectrumUse;
use crate::scene::{Emitter, SceneTexture};
use anyhow::{bail, Result};
use caustic_kernel::layout::{Texture, NONE, TEXTURE_BITMAP};
use glam::{Mat3, Vec3};

impl Loader {
    /// The radiance of an `<emitter>` nested in a shape, or `None` (with a warning) for other kinds.
    pub(crate) fn load_shape_emitter(&mut self, props: &Props) -> Result<Option<AreaEmission>> {
        if props.kind != "area" && props.kind != "directionalarea" {
            let message = format!(
                "{}: emitter type '{}' cannot be attached to a shape; ignored",
                props.loc, props.kind
            );
            self.substituted(format!("shape emitter '{}'", props.kind), &props.loc, message);
            props.mark_all_used();
            return Ok(None);
        }
        let radiance = self.color_param(props, "radiance", SpectrumUse::Emission, [1.0; 3])?;
        self.warn_unused(props);
        let texture = (radiance.texture != NONE).then_some(radiance.texture);
        let directional = props.kind == "directionalarea";
        Ok(Some(AreaEmission { radiance: radiance.rgb, texture, directional }))
    }

    /// A top-level `<emitter>`.
    pub(crate) fn load_emitter(&mut self, props: &Props) -> Result<()> {
        let to_world = props.transform("to_world")?;
        let emitter = match props.kind.as_str() {
            "point" => {
                if props.has("position") && props.has("to_world") {
                    bail!("{}: give a point emitter either 'position' or 'to_world', not both", props.loc);
                }
                let position = props.point("position", to_world.w_axis.truncate())?;
                Emitter::Point {
                    position,
                    intensity: props.color("intensity", SpectrumUse::Emission, [1.0; 3])?,
                }
            }
            "spot" => {
                let intensity = props.color("intensity", SpectrumUse::Emission, [1.0; 3])?;
                let texture = self.image_texture(props, "texture")?;
                let cutoff_angle = props.float("cutoff_angle", 20.0)?;
                let beam_width = props.float("beam_width", cutoff_angle * 0.75)?;
                if !(cutoff_angle > 0.0 && cutoff_angle <= 180.0 && beam_width >= 0.0) {
                    bail!("{}: spot needs 0 < cutoff_angle ≤ 180 and beam_width ≥ 0 (degrees)", props.loc);
                }
                Emitter::Spot { to_world, intensity, cutoff_angle, beam_width, texture }
            }
            "projector" => self.projector(props, to_world)?,
            "directional" => {
                if props.has("direction") && props.has("to_world") {
                    bail!(
                        "{}: give a directional emitter either 'direction' or 'to_world', not both",
                        props.loc
                    );
                }
                let direction = props.point("direction", to_world.transform_vector3(Vec3::Z))?;
                if direction.length_squared() == 0.0 {
                    bail!("{}: directional emitter needs a non-zero direction", props.loc);
                }
                Emitter::Directional {
                    direction,
                    irradiance: props.color("irradiance", SpectrumUse::Emission, [1.0; 3])?,
                }
            }
            "constant" => {
                Emitter::Constant { radiance: props.color("radiance", SpectrumUse::Emission, [1.0; 3])? }
            }
            "envmap" => self.envmap(props, Mat3::from_mat4(to_world))?,
            "area" | "directionalarea" => {
                bail!("{}: an {} emitter must be nested in a <shape>", props.loc, props.kind)
            }
            other => {
                let message = format!("{}: emitter type '{other}' is not supported yet; ignored", props.loc);
                self.substituted(format!("emitter '{other}'"), &props.loc, message);
                props.mark_all_used();
                return Ok(());
            }
        };
        if matches!(emitter, Emitter::Constant { .. } | Emitter::Envmap { .. })
            && self.emitters.iter().any(|e| matches!(e, Emitter::Constant { .. } | Emitter::Envmap { .. }))
        {
            bail!("{}: only one environment emitter (constant or envmap) is allowed per scene", props.loc);
        }
        self.warn_unused(props);
        self.emitters.push(emitter);
        Ok(())
    }

    /// Mitsuba's `projector`: `irradiance` (a colour or a texture; the image's resolution sets the
    /// aspect ratio, 1 for a colour), `scale`, `fov`/`fov_axis` (or `focal_length`), `to_world`.
    fn projector(&mut self, props: &Props, to_world: glam::Mat4) -> Result<Emitter> {
        let irradiance = self.color_param(props, "irradiance", SpectrumUse::Emission, [1.0; 3])?;
        let scale = props.float("scale", 1.0)?;
        if scale.is_nan() || scale < 0.0 {
            bail!("{}: projector scale must be non-negative", props.loc);
        }
        let (texture, rgb, aspect) = if irradiance.texture == NONE {
            (None, irradiance.rgb, 1.0)
        } else {
            let t = &self.textures[irradiance.texture as usize].record;
            // A procedural texture has no resolution: Mitsuba's is 1×1 for it.
            let aspect = if t.kind == TEXTURE_BITMAP { t.width as f64 / t.height as f64 } else { 1.0 };
            (Some(irradiance.texture), [1.0; 3], aspect)
        };
        let fov_x = super::sensors::horizontal_fov(props, aspect)?;
        Ok(Emitter::Projector {
            to_world,
            irradiance: rgb.map(|c| c * scale),
            texture,
            fov_x,
            aspect: aspect as f32,
        })
    }

    /// A texture-valued parameter that must be an image (nested `<texture>` or `<ref>`), as Mitsuba's
    /// spot `texture`: a constant there is refused with its line.
    fn image_texture(&mut self, props: &Props, name: &str) -> Result<Option<u32>> {
        if !props.has(name) {
            return Ok(None);
        }
        let param = self.color_param(props, name, SpectrumUse::Reflectance, [1.0; 3])?;
        if param.texture == NONE {
            bail!(
                "{}: '{name}' must be a spatially varying texture (bitmap or checkerboard), as in Mitsuba",
                props.loc
            );
        }
        Ok(Some(param.texture))
    }

    fn envmap(&mut self, props: &Props, to_world: Mat3) -> Result<Emitter> {
        let Some(name) = props.string("filename")? else { bail!("{}: envmap needs a 'filename'", props.loc) };
        let path = self.resolve(&name, &props.loc)?;
        let image = crate::load::image_io::load_linear_rgb(&path, false)
            .map_err(|e| anyhow::anyhow!("{}: {e:#}", props.loc))?;
        if image.height < 2 {
            bail!("{}: envmap {} must be at least 2 pixels high", props.loc, path.display());
        }
        let scale = props.float("scale", 1.0)?;
        if scale < 0.0 {
            bail!("{}: envmap scale must be non-negative", props.loc);
        }
        if (to_world.transpose() * to_world - Mat3::IDENTITY).to_cols_array().iter().any(|v| v.abs() > 1e-3) {
            self.warn(&format!(
                "{}: envmap to_world is not a rotation; directions are mapped by its inverse",
                props.loc
            ));
        }
        let mis_compensation = props.boolean("mis_compensation", false)?;
        let record =
            Texture { kind: TEXTURE_BITMAP, width: image.width, height: image.height, ..Default::default() };
        self.textures.push(SceneTexture { record, texels: image.rgb, mesh_attribute: None });
        Ok(Emitter::Envmap { texture: self.textures.len() as u32 - 1, to_world, scale, mis_compensation })
    }
}
