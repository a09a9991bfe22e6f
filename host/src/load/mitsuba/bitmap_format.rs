//! The storage precision of Mitsuba's `bitmap` texture (its `format`, 3.9.1's
//! `src/textures/bitmap.cpp`), applied to the linear texels caustic keeps in f32:
//!
//! - `auto` (the default) stores 8-bit files as 8-bit (decoded from sRGB texel by texel at lookup:
//!   the values caustic decodes at load), 16-bit files in half precision, float files (EXR, HDR) in
//!   f32;
//! - `variant`: f32 (caustic's own storage: nothing changes);
//! - `float16` (or the older `fp16`): half precision, rounded to nearest (values past 65504 would
//!   become infinite: refused);
//! - `uint8`: 8 bits per channel: a float file's values are clamped to [0, 1] and rounded to
//!   multiples of 1/255; a 16-bit sRGB file's encoded values are rounded so and decoded again.
//!   Mitsuba's own conversion departs from the nearest step by up to one step, depending on the
//!   texel's position (dithered, by its look: `tests/tests/bitmap_format.rs`); caustic takes the
//!   nearest.
//!
//! Mitsuba's `accel` (hardware interpolation, CUDA only) changes no value caustic computes: read and
//! accepted. Its `bitmap` and `data` properties hand over in-memory images from Python or C++; a scene
//! file cannot give them.
use super::props::Props;
use crate::load::image_io::{linear_to_srgb, srgb_to_linear, LinearImage, SampleDepth};
use anyhow::{bail, Result};
use exr::prelude::f16;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StorageFormat {
    Auto,
    Variant,
    Float16,
    UInt8,
}

/// The `format` of a bitmap (default `auto`), as Mitsuba spells it.
pub fn parse(props: &Props) -> Result<StorageFormat> {
    Ok(match props.string("format")?.as_deref() {
        None | Some("auto") => StorageFormat::Auto,
        Some("variant") => StorageFormat::Variant,
        Some("float16" | "fp16") => StorageFormat::Float16,
        Some("uint8") => StorageFormat::UInt8,
        Some(other) => bail!(
            "{}: format must be auto, variant, float16 (or fp16) or uint8, not '{other}' (as Mitsuba)",
            props.loc
        ),
    })
}

/// What `auto` stores an image of `depth` as.
fn resolve(format: StorageFormat, depth: SampleDepth) -> StorageFormat {
    match (format, depth) {
        (StorageFormat::Auto, SampleDepth::Int8) => StorageFormat::UInt8,
        (StorageFormat::Auto, SampleDepth::Int16) => StorageFormat::Float16,
        (StorageFormat::Auto, SampleDepth::Float) => StorageFormat::Variant,
        (f, _) => f,
    }
}

/// Rounds `image`'s texels to what Mitsuba stores under `format` (`raw`: the file's integers were
/// not sRGB-decoded). The error says which texel half precision cannot hold.
pub fn store(format: StorageFormat, image: &mut LinearImage, raw: bool) -> Result<()> {
    match resolve(format, image.depth) {
        StorageFormat::Variant | StorageFormat::Auto => {}
        StorageFormat::Float16 => {
            for (i, v) in image.rgb.iter_mut().enumerate() {
                let h = f16::from_f32(*v).to_f32();
                if !h.is_finite() {
                    let texel = i / 3;
                    bail!(
                        "texel ({}, {}) holds {v}, beyond half precision's 65504 (format float16)",
                        texel % image.width as usize,
                        texel / image.width as usize
                    );
                }
                *v = h;
            }
        }
        // 8-bit files are stored as they are.
        StorageFormat::UInt8 if image.depth == SampleDepth::Int8 => {}
        StorageFormat::UInt8 => {
            let encoded = image.depth == SampleDepth::Int16 && !raw;
            for v in &mut image.rgb {
                *v = if encoded { srgb_to_linear(to_u8(linear_to_srgb(*v))) } else { to_u8(*v) };
            }
        }
    }
    Ok(())
}

/// `v` clamped to [0, 1] and rounded to the nearest multiple of 1/255.
fn to_u8(v: f32) -> f32 {
    (v.clamp(0.0, 1.0) * 255.0).round() / 255.0
}
