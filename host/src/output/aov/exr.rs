//! Multi-channel EXR files: the image's R, G, B and a film's AOV channels in one layer, as Mitsuba
//! writes an `aov` render (f32 samples; EXR keeps channels sorted by name), and reading every
//! channel of such a file back by name.
use crate::output::film::Film;
use anyhow::{bail, Context, Result};
use exr::prelude::*;
use std::path::Path;

/// Writes `film`'s image and AOV channels (non-finite values written as 0, as `session::sanitize`
/// does for the image) with its comment.
pub fn write(film: &Film, path: &Path) -> Result<()> {
    let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
    let mut list: Vec<AnyChannel<FlatSamples>> = ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(c, name)| {
            AnyChannel::new(*name, FlatSamples::F32(film.rgb.iter().map(|p| finite(p[c])).collect()))
        })
        .collect();
    for channel in &film.aovs {
        if list.iter().any(|c| c.name.to_string() == channel.name) {
            bail!("{}: two channels named '{}'", path.display(), channel.name);
        }
        let values = channel.values.iter().map(|&v| finite(v)).collect();
        list.push(AnyChannel::new(channel.name.as_str(), FlatSamples::F32(values)));
    }
    let channels = AnyChannels::sort(list.into());
    let mut layer = Layer::new(
        (film.width as usize, film.height as usize),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        channels,
    );
    layer.attributes.comments = film.comment.as_deref().map(Text::from);
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    crate::system::files::write(path, bytes.get_ref())
}

/// Channels by name, each with its samples (row-major).
pub type NamedChannels = Vec<(String, Vec<f32>)>;

/// Every channel of the first layer of an EXR file as f32 (half and integer samples converted), by
/// name in the file's (sorted) order; with the layer's width and height.
pub fn read_channels(path: &Path) -> Result<(u32, u32, NamedChannels)> {
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(crate::load::image_io::read_exr(path)?))
        .with_context(|| format!("cannot read EXR image {}", path.display()))?;
    let size = image.layer_data.size;
    let channels = image
        .layer_data
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect();
    Ok((size.width() as u32, size.height() as u32, channels))
}
