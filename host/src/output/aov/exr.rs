//! Multi-channel EXR files, as Mitsuba writes an `aov` render and `Film::save` writes a film with
//! AOVs (the image's R, G, B and the AOV channels in one layer, f32 samples, sorted by name): every
//! channel of such a file read back by name.
use anyhow::{Context, Result};
use exr::prelude::*;
use std::path::Path;

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
