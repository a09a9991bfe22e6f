//! Spectra in scene files → linear sRGB, as Mitsuba 3's `rgb` variants convert them.
//!
//! A `λ:value` list is integrated against the CIE 1931 matching functions (1000 points over
//! 360–830 nm, linear interpolation, zero outside the listed range), then mapped XYZ → sRGB.
//! Reflectances are weighted by D65 and clamped to [0, 1]; emission spectra are not weighted
//! (an equal-energy emitter comes out as XYZ = (1, 1, 1)) and are only clamped at 0. A uniform
//! `<spectrum value="c"/>` is grey `c` for reflectances, and `c·xyz_to_srgb(1, 1, 1)` for emitters.
//! Spectra in files (Mitsuba's `.spd` format) are read by `read_spd`.
use super::cie_tables::{CIE_MAX, CIE_MIN, CIE_SAMPLES, CIE_X, CIE_Y, CIE_Z, D65};
use anyhow::{bail, Result};
use std::path::Path;

/// What a spectrum describes; it decides the conversion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpectrumUse {
    /// Bounded reflectance-like quantities (D65-weighted, clamped to [0, 1]).
    Reflectance,
    /// Emitted radiance (unweighted, clamped at 0).
    Emission,
    /// Unbounded non-emissive values such as IORs (D65-weighted, clamped at 0).
    Unbounded,
}

const Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;
const D65_NORMALIZATION: f64 = 1.0 / 98.997_417_518_762_55;

/// CIE XYZ → linear sRGB (Rec. 709 primaries, D65 white), by rows.
pub const XYZ_TO_SRGB: [[f64; 3]; 3] =
    [[3.240479, -1.537150, -0.498535], [-0.969256, 1.875991, 0.041556], [0.055648, -0.204043, 1.057311]];

pub fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// The CIE 1931 colour-matching functions at their 5 nm table points, 360–830 nm.
pub fn cie_xyz_table() -> Vec<[f64; 3]> {
    (0..CIE_SAMPLES).map(|i| [CIE_X[i], CIE_Y[i], CIE_Z[i]]).collect()
}

/// Linear interpolation in a 5 nm CIE table; zero outside 360–830 nm.
fn cie_lookup(table: &[f64; CIE_SAMPLES], lambda: f64) -> f64 {
    if !(CIE_MIN..=CIE_MAX).contains(&lambda) {
        return 0.0;
    }
    let t = (lambda - CIE_MIN) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX - CIE_MIN));
    let i = (t as usize).min(CIE_SAMPLES - 2);
    let f = t - i as f64;
    (1.0 - f) * table[i] + f * table[i + 1]
}

/// Converts a sampled spectrum (`wavelengths` ascending, in nm) to linear sRGB.
pub fn spectrum_to_rgb(wavelengths: &[f64], values: &[f64], usage: SpectrumUse) -> [f32; 3] {
    const STEPS: usize = 1000;
    let mut xyz = [0.0f64; 3];
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    for i in 0..STEPS {
        let lambda = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if lambda < first || lambda > last {
            continue;
        }
        let k = wavelengths
            .partition_point(|&w| w <= lambda)
            .saturating_sub(1)
            .min(wavelengths.len().saturating_sub(2));
        let value = if wavelengths.len() == 1 {
            values[0]
        } else {
            let (w0, w1, v0, v1) = (wavelengths[k], wavelengths[k + 1], values[k], values[k + 1]);
            ((lambda - w1) * v0 + (w0 - lambda) * v1) / (w0 - w1)
        };
        let weight =
            if usage == SpectrumUse::Emission { 1.0 } else { cie_lookup(&D65, lambda) * D65_NORMALIZATION };
        xyz[0] += cie_lookup(&CIE_X, lambda) * value * weight;
        xyz[1] += cie_lookup(&CIE_Y, lambda) * value * weight;
        xyz[2] += cie_lookup(&CIE_Z, lambda) * value * weight;
    }
    let scale = (CIE_MAX - CIE_MIN) * Y_NORMALIZATION / STEPS as f64;
    let rgb = xyz_to_srgb([xyz[0] * scale, xyz[1] * scale, xyz[2] * scale]);
    clamp_for(rgb, usage)
}

/// A uniform spectrum `<spectrum value="c"/>`.
pub fn uniform_spectrum_to_rgb(value: f64, usage: SpectrumUse) -> [f32; 3] {
    if usage == SpectrumUse::Emission {
        let white = xyz_to_srgb([1.0, 1.0, 1.0]);
        [(value * white[0]) as f32, (value * white[1]) as f32, (value * white[2]) as f32]
    } else {
        [value as f32; 3]
    }
}

fn clamp_for(rgb: [f64; 3], usage: SpectrumUse) -> [f32; 3] {
    let hi = if usage == SpectrumUse::Reflectance { 1.0 } else { f64::INFINITY };
    rgb.map(|c| c.clamp(0.0, hi) as f32)
}

/// Parses an `.spd` file: one `wavelength value` pair (nm) per line, `#` starts a comment.
/// Wavelengths must increase; at least one pair is needed.
pub fn read_spd(path: &Path) -> Result<(Vec<f64>, Vec<f64>)> {
    let text = crate::system::files::read_to_string(path, "spectrum file")?;
    let mut wavelengths = Vec::new();
    let mut values = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_no = index + 1;
        let data = line.split('#').next().unwrap_or("");
        let fields: Vec<&str> = data.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        let [w, v] = fields[..] else {
            bail!("{}:{line_no}: expected 'wavelength value', found {} fields", path.display(), fields.len());
        };
        let number = |s: &str| -> Result<f64> {
            match s.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => bail!("{}:{line_no}: '{s}' is not a finite number", path.display()),
            }
        };
        let (w, v) = (number(w)?, number(v)?);
        if let Some(&last) = wavelengths.last() {
            if w <= last {
                bail!("{}:{line_no}: wavelengths must increase ({w} after {last})", path.display());
            }
        }
        wavelengths.push(w);
        values.push(v);
    }
    if wavelengths.is_empty() {
        bail!("{}: no 'wavelength value' pairs", path.display());
    }
    Ok((wavelengths, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Values computed independently from Mitsuba 3's definition (same tables, same quadrature).
    #[test]
    fn constant_reflectance_is_nearly_white() {
        let rgb = spectrum_to_rgb(&[360.0, 830.0], &[1.0, 1.0], SpectrumUse::Reflectance);
        for (c, want) in rgb.iter().zip([0.998985, 0.998874, 0.998802]) {
            assert!((*c as f64 - want).abs() < 2e-5, "{rgb:?}");
        }
    }

    #[test]
    fn constant_emission_is_equal_energy_white() {
        let rgb = spectrum_to_rgb(&[360.0, 830.0], &[1.0, 1.0], SpectrumUse::Emission);
        for (c, want) in rgb.iter().zip([1.204884, 0.948228, 0.909267]) {
            assert!((*c as f64 - want).abs() < 2e-5, "{rgb:?}");
        }
    }
}
