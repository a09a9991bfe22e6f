//! Colour: paths transport linear sRGB triples, like Mitsuba's `rgb` variants; a path through dispersive
//! glass carries one wavelength as well, with the sRGB weight of that wavelength (`wavelength`).
use crate::glam::Vec3;

pub type Rgb = Vec3;

/// Luminance (Y) of linear sRGB with Rec. 709 primaries.
#[inline]
pub fn luminance(c: Rgb) -> f32 {
    0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z
}
