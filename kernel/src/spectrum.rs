//! Colour. Version 1 transports linear sRGB triples, like Mitsuba's `rgb` variants; the hero-wavelength
//! spectral mode for dispersion will add a second `Spectrum` representation behind the same helpers.
use crate::glam::Vec3;

pub type Rgb = Vec3;

/// Luminance (Y) of linear sRGB with Rec. 709 primaries.
#[inline]
pub fn luminance(c: Rgb) -> f32 {
    0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z
}
