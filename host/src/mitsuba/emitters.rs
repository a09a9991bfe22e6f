//! Emitter plugins: `area` (attached to a shape).
use super::props::Props;
use super::spectrum::SpectrumUse;
use super::Loader;
use anyhow::Result;

impl Loader {
    /// The radiance of an `<emitter>` nested in a shape, or `None` (with a warning) for other kinds.
    pub(crate) fn load_shape_emitter(&mut self, props: &Props) -> Result<Option<[f32; 3]>> {
        if props.kind != "area" {
            self.warn(&format!("{}: emitter type '{}' is not supported yet; ignored", props.loc, props.kind));
            props.mark_all_used();
            return Ok(None);
        }
        let radiance = props.color("radiance", SpectrumUse::Emission, [1.0; 3])?;
        self.warn_unused(props);
        Ok(Some(radiance))
    }
}
