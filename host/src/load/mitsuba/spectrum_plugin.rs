//! Mitsuba's spectrum plugins written out as objects, `<spectrum type="…" name="…">…</spectrum>`,
//! turned into the linear sRGB colour a colour property holds. Measured against Mitsuba 3.9.1
//! (`tests/data/mitsuba_defaults.py`):
//!
//! - `srgb` (`color`, an `<rgb>` in [0, 1], refused outside it as Mitsuba refuses it, emitters too),
//!   `uniform` (`value`), `rawconstant` (`value`, a number or three) and `d65` (`scale`, default 1;
//!   `color`, default white) are the constant colour Mitsuba's rgb variants make of them: the colour,
//!   or the number as a grey, for emission too (where `<spectrum value="v"/>` is `v` times the
//!   equal-energy white);
//! - `regular` (`wavelength_min`, `wavelength_max`, `values`), `irregular` (`wavelengths`, `values`)
//!   and `blackbody` (`temperature`, and
//!   `wavelength_min`/`wavelength_max`, default 360/830 nm: Planck's law in W m⁻² sr⁻¹ nm⁻¹, as
//!   Mitsuba's) are spectra: Mitsuba's rgb variants load them and stop at the first render ("Not
//!   implemented for non-spectral modes"); caustic converts them as it converts a `λ:value` list,
//!   which is what Mitsuba's spectral variants render (checked against `scalar_spectral`).
//!
//! Every other property inside is refused, as Mitsuba refuses an unreferenced one. The values come
//! through `Props`, as every plugin's do.
//!
//! Colour-valued properties are read here too (`Props::color`: `<rgb>`, `<spectrum value>`, `<float>`
//! or such a plugin), since the two read each other: an `srgb` or `d65` plugin's `color` is one.
use super::props::Props;
use super::spectrum::{spectrum_to_rgb, uniform_spectrum_to_rgb, SpectrumUse};
use super::xml::{expand_value_to_xyz, parse_numbers, Loc, XyzError};
use anyhow::{bail, Context, Result};
use glam::Vec3;

/// Planck's law as Mitsuba's `blackbody` evaluates it: radiance per nanometre at `lambda_nm`.
pub fn planck(lambda_nm: f64, temperature: f64) -> f64 {
    const C: f64 = 2.997_924_58e8;
    const H: f64 = 6.626_070_04e-34;
    const K: f64 = 1.380_648_52e-23;
    let lambda = lambda_nm * 1e-9;
    1e-9 * 2.0 * H * C * C / (lambda.powi(5) * ((H * C / K / (lambda * temperature)).exp() - 1.0))
}

/// Refuses a plugin that lacks `name` or gives it with a tag other than `tags`, as Mitsuba does.
fn require(props: &Props, name: &str, tags: &[&str]) -> Result<()> {
    match props.tag_of(name) {
        None => bail!("{}: spectrum '{}' needs '{name}'", props.loc, props.kind),
        Some(tag) if !tags.contains(&tag) => bail!(
            "{}: '{name}' of spectrum '{}' must be <{}>, not <{tag}>",
            props.loc,
            props.kind,
            tags.join("> or <")
        ),
        Some(_) => Ok(()),
    }
}

/// A `<string>` list of numbers (`require`d).
fn numbers(props: &Props, name: &str) -> Result<Vec<f64>> {
    require(props, name, &["string"])?;
    parse_numbers(&props.string(name)?.unwrap_or_default(), &props.loc)
}

/// The colour of the spectrum plugin `props` (the `<spectrum type="…">` element) for a property
/// used as `usage`.
pub fn to_rgb(props: &Props, usage: SpectrumUse) -> Result<[f32; 3]> {
    let loc = &props.loc;
    let rgb = match props.kind.as_str() {
        "srgb" => {
            require(props, "color", &["rgb"])?;
            let c = props.color("color", usage, [0.0; 3])?;
            if c.iter().any(|v| !(0.0..=1.0).contains(v)) {
                bail!("{loc}: spectrum 'srgb' takes a colour in [0, 1] (Mitsuba refuses {c:?}; give a brighter emitter with <rgb>)");
            }
            c
        }
        "uniform" => {
            require(props, "value", &["float"])?;
            [props.float("value", 0.0)?; 3]
        }
        "rawconstant" => match props.tag_of("value") {
            Some("vector" | "point") => props.point("value", Vec3::ZERO)?.to_array(),
            _ => {
                require(props, "value", &["float"])?;
                [props.float("value", 0.0)?; 3]
            }
        },
        "d65" => {
            let scale = props.float("scale", 1.0)?;
            if props.tag_of("color").is_some() {
                require(props, "color", &["rgb"])?;
            }
            props.color("color", usage, [1.0; 3])?.map(|c| c * scale)
        }
        "regular" => {
            for name in ["wavelength_min", "wavelength_max"] {
                require(props, name, &["float"])?;
            }
            let (lo, hi) = (props.float("wavelength_min", 0.0)? as f64, props.float("wavelength_max", 0.0)? as f64);
            let values = numbers(props, "values")?;
            if values.len() < 2 || lo >= hi {
                bail!("{loc}: spectrum 'regular' needs two values or more over wavelength_min < wavelength_max");
            }
            let n = values.len() - 1;
            let wavelengths: Vec<f64> = (0..=n).map(|i| lo + (hi - lo) * i as f64 / n as f64).collect();
            return converted(props, &wavelengths, &values, usage);
        }
        "irregular" => {
            let (wavelengths, values) = (numbers(props, "wavelengths")?, numbers(props, "values")?);
            if wavelengths.len() != values.len() || wavelengths.len() < 2 || wavelengths.windows(2).any(|p| p[0] >= p[1]) {
                bail!("{loc}: spectrum 'irregular' needs as many values as wavelengths, two or more, the wavelengths increasing");
            }
            return converted(props, &wavelengths, &values, usage);
        }
        "blackbody" => {
            require(props, "temperature", &["float"])?;
            let t = props.float("temperature", 0.0)? as f64;
            let (lo, hi) = (props.float("wavelength_min", 360.0)? as f64, props.float("wavelength_max", 830.0)? as f64);
            if t <= 0.0 || lo >= hi {
                bail!("{loc}: spectrum 'blackbody' needs a positive temperature and wavelength_min < wavelength_max");
            }
            // Planck's law is smooth: 1 nm steps (and the range's own ends) interpolate it to 1e-5.
            let mut wavelengths: Vec<f64> = vec![lo];
            wavelengths.extend((lo.floor() as i64 + 1..hi.ceil() as i64).map(|w| w as f64));
            wavelengths.push(hi);
            let values: Vec<f64> = wavelengths.iter().map(|&w| planck(w, t)).collect();
            return converted(props, &wavelengths, &values, usage);
        }
        other => bail!(
            "{loc}: spectrum type '{other}' is not supported (srgb, uniform, rawconstant, d65, regular, irregular, blackbody are)"
        ),
    };
    finish(props)?;
    Ok(rgb)
}

/// A sampled spectrum's colour, once the plugin has no property left unread.
fn converted(props: &Props, wavelengths: &[f64], values: &[f64], usage: SpectrumUse) -> Result<[f32; 3]> {
    finish(props)?;
    Ok(spectrum_to_rgb(wavelengths, values, usage))
}

/// Refuses a property the plugin does not read, as Mitsuba refuses unreferenced properties.
fn finish(props: &Props) -> Result<()> {
    match props.unused().into_iter().next() {
        Some((loc, group, _)) => bail!("{loc}: {group} does not exist (Mitsuba refuses it)"),
        None => Ok(()),
    }
}

impl Props<'_, '_> {
    /// A colour-valued property (`rgb`, `spectrum` or `float`), converted as Mitsuba's rgb variants do.
    pub fn color(&self, name: &str, usage: SpectrumUse, default: [f32; 3]) -> Result<[f32; 3]> {
        let Some(i) = self.find(name) else { return Ok(default) };
        let e = &self.entries[i];
        // `<spectrum type="…">`: a spectrum plugin written out as an object (no `value` attribute).
        if e.tag == "spectrum" && e.node.attribute("type").is_some() {
            let rgb = to_rgb(&self.nested_props(i)?, usage)?;
            return checked_color(rgb, name, &e.loc);
        }
        let value = self.value_of(i)?;
        let rgb = match e.tag.as_str() {
            "rgb" => expand_value_to_xyz(e.node, Some(value), 0.0, &self.params, &e.loc)
                .map_err(|err| match err {
                    XyzError::Numbers(err) => err,
                    // `value` is given, so no x/y/z attribute is read.
                    XyzError::Count(_) | XyzError::NotANumber(_) => {
                        anyhow::anyhow!("{}: <rgb> needs 1 or 3 numbers", e.loc)
                    }
                })?
                .to_array(),
            "float" => [self.float(name, 0.0)?; 3],
            "spectrum" => parse_spectrum(value, usage, &e.loc)?,
            other => bail!("{}: '{name}' must be <rgb>, <spectrum> or <float>, not <{other}> (textures are not supported yet)", e.loc),
        };
        checked_color(rgb, name, &e.loc)
    }
}

/// A colour property's value, refused where not finite or negative.
fn checked_color(rgb: [f32; 3], name: &str, loc: &Loc) -> Result<[f32; 3]> {
    if rgb.iter().any(|c| !c.is_finite() || *c < 0.0) {
        bail!("{loc}: '{name}' must be finite and non-negative, got {rgb:?}");
    }
    Ok(rgb)
}

/// `<spectrum value="0.5"/>` or `value="400:0.1, 500:0.2, …"`.
fn parse_spectrum(value: &str, usage: SpectrumUse, loc: &Loc) -> Result<[f32; 3]> {
    if !value.contains(':') {
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| anyhow::anyhow!("{loc}: spectrum value '{value}' is not a number"))?;
        return Ok(uniform_spectrum_to_rgb(v, usage));
    }
    let mut wavelengths = Vec::new();
    let mut values = Vec::new();
    for pair in value.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (w, v) =
            pair.split_once(':').with_context(|| format!("{loc}: '{pair}' is not wavelength:value"))?;
        let w: f64 =
            w.trim().parse().map_err(|_| anyhow::anyhow!("{loc}: wavelength '{w}' is not a number"))?;
        let v: f64 = v.trim().parse().map_err(|_| anyhow::anyhow!("{loc}: value '{v}' is not a number"))?;
        if let Some(&last) = wavelengths.last() {
            if w <= last {
                bail!("{loc}: spectrum wavelengths must increase ({w} after {last})");
            }
        }
        wavelengths.push(w);
        values.push(v);
    }
    if wavelengths.is_empty() {
        bail!("{loc}: empty spectrum");
    }
    Ok(spectrum_to_rgb(&wavelengths, &values, usage))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Wien's displacement law: the peak of Planck's law sits at b / T (b = 2.897771955e-3 m K).
    #[test]
    fn planck_peaks_where_wien_says() {
        let t = 5000.0;
        let peak = (300..1200).max_by(|&a, &b| planck(a as f64, t).total_cmp(&planck(b as f64, t))).unwrap();
        assert!((peak as f64 - 2.897_771_955e-3 / t * 1e9).abs() <= 1.0, "peak at {peak} nm");
    }
}
