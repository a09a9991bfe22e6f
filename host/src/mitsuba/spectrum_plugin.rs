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
//! Every other property inside is refused, as Mitsuba refuses an unreferenced one.
use super::spectrum::{spectrum_to_rgb, SpectrumUse};
use super::xml::{expand_value_to_xyz, parse_numbers, substitute, Loc, Params, Source, XyzError};
use anyhow::{bail, Result};

/// Planck's law as Mitsuba's `blackbody` evaluates it: radiance per nanometre at `lambda_nm`.
pub fn planck(lambda_nm: f64, temperature: f64) -> f64 {
    const C: f64 = 2.997_924_58e8;
    const H: f64 = 6.626_070_04e-34;
    const K: f64 = 1.380_648_52e-23;
    let lambda = lambda_nm * 1e-9;
    1e-9 * 2.0 * H * C * C / (lambda.powi(5) * ((H * C / K / (lambda * temperature)).exp() - 1.0))
}

/// One property inside the plugin: its tag, name, `value` (substituted) and place.
#[derive(Clone)]
struct Property<'a, 'input> {
    tag: String,
    name: String,
    value: Option<String>,
    node: roxmltree::Node<'a, 'input>,
    loc: Loc,
}

struct Properties<'a, 'input> {
    kind: String,
    loc: Loc,
    list: Vec<(Property<'a, 'input>, bool)>,
    params: &'a Params,
}

impl<'a, 'input> Properties<'a, 'input> {
    /// The property `name` with tag among `tags`, marked read; `None` if absent.
    fn take(&mut self, name: &str, tags: &[&str]) -> Result<Option<Property<'a, 'input>>> {
        let Some((p, read)) = self.list.iter_mut().find(|(p, _)| p.name == name) else { return Ok(None) };
        *read = true;
        if !tags.contains(&p.tag.as_str()) {
            bail!(
                "{}: '{name}' of spectrum '{}' must be <{}>, not <{}>",
                p.loc,
                self.kind,
                tags.join("> or <"),
                p.tag
            );
        }
        if p.value.is_none() && p.tag != "rgb" && p.tag != "vector" && p.tag != "point" {
            bail!("{}: <{}> needs a 'value' attribute", p.loc, p.tag);
        }
        Ok(Some(p.clone()))
    }

    /// A `<float>`: `default` where absent, an error where absent and required (`None`).
    fn float(&mut self, name: &str, default: Option<f64>) -> Result<f64> {
        let Some(p) = self.take(name, &["float"])? else {
            return default
                .ok_or_else(|| anyhow::anyhow!("{}: spectrum '{}' needs '{name}'", self.loc, self.kind));
        };
        let text = p.value.unwrap_or_default();
        match text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => bail!("{}: '{name}' must be a finite number, not '{text}'", p.loc),
        }
    }

    /// Three numbers given as one of `tags` (`<rgb>`, `<vector>`), or `None` where absent.
    fn triple(&mut self, name: &str, tags: &[&str]) -> Result<Option<[f64; 3]>> {
        let Some(p) = self.take(name, tags)? else { return Ok(None) };
        let v = expand_value_to_xyz(p.node, p.value.as_deref(), 0.0, self.params, &p.loc).map_err(
            |e| match e {
                XyzError::Numbers(e) => e,
                XyzError::Count(n) => anyhow::anyhow!("{}: '{name}' needs 1 or 3 numbers, got {n}", p.loc),
                XyzError::NotANumber(a) => anyhow::anyhow!("{}: '{a}' must be a number", p.loc),
            },
        )?;
        Ok(Some([v.x as f64, v.y as f64, v.z as f64]))
    }

    /// A `<string>`, or `None` where absent.
    fn string(&mut self, name: &str) -> Result<Option<String>> {
        Ok(self.take(name, &["string"])?.and_then(|p| p.value))
    }

    /// The tag `name` is given with (not marking it read).
    fn tag_of(&self, name: &str) -> Option<&str> {
        self.list.iter().find(|(p, _)| p.name == name).map(|(p, _)| p.tag.as_str())
    }

    /// Refuses what no getter read, as Mitsuba refuses unreferenced properties.
    fn finish(&self) -> Result<()> {
        if let Some((p, _)) = self.list.iter().find(|(_, read)| !read) {
            bail!("{}: spectrum '{}' has no property '{}' (<{}>)", p.loc, self.kind, p.name, p.tag);
        }
        Ok(())
    }
}

/// The colour of `<spectrum type="kind">` at `node` for a property used as `usage`.
pub fn to_rgb(
    src: &Source,
    node: roxmltree::Node,
    kind: &str,
    usage: SpectrumUse,
    params: &Params,
    loc: &Loc,
) -> Result<[f32; 3]> {
    let mut list = Vec::new();
    for child in node.children().filter(|n| n.is_element()) {
        let child_loc = src.loc(child);
        let Some(name) = child.attribute("name") else {
            bail!("{child_loc}: <{}> inside a spectrum needs a 'name'", child.tag_name().name());
        };
        let value = child.attribute("value").map(|v| substitute(params, v, &child_loc)).transpose()?;
        let tag = child.tag_name().name().to_string();
        let name = substitute(params, name, &child_loc)?;
        list.push((Property { tag, name, value, node: child, loc: child_loc }, false));
    }
    let mut props = Properties { kind: kind.to_string(), loc: loc.clone(), list, params };
    let rgb = match kind {
        "srgb" => {
            let Some(c) = props.triple("color", &["rgb"])? else { bail!("{loc}: spectrum 'srgb' needs 'color'") };
            if c.iter().any(|v| !(0.0..=1.0).contains(v)) {
                bail!("{loc}: spectrum 'srgb' takes a colour in [0, 1] (Mitsuba refuses {c:?}; give a brighter emitter with <rgb>)");
            }
            c
        }
        "uniform" => [props.float("value", None)?; 3],
        "rawconstant" => match props.tag_of("value") {
            Some("vector" | "point") => props.triple("value", &["vector", "point"])?.unwrap_or_default(),
            _ => [props.float("value", None)?; 3],
        },
        "d65" => {
            let scale = props.float("scale", Some(1.0))?;
            props.triple("color", &["rgb"])?.unwrap_or([1.0; 3]).map(|c| c * scale)
        }
        "regular" => {
            let lo = props.float("wavelength_min", None)?;
            let hi = props.float("wavelength_max", None)?;
            let Some(text) = props.string("values")? else { bail!("{loc}: spectrum 'regular' needs 'values'") };
            let values = parse_numbers(&text, loc)?;
            if values.len() < 2 || lo >= hi {
                bail!("{loc}: spectrum 'regular' needs two values or more over wavelength_min < wavelength_max");
            }
            let n = values.len() - 1;
            let wavelengths: Vec<f64> = (0..=n).map(|i| lo + (hi - lo) * i as f64 / n as f64).collect();
            props.finish()?;
            return Ok(spectrum_to_rgb(&wavelengths, &values, usage));
        }
        "irregular" => {
            let (Some(w), Some(v)) = (props.string("wavelengths")?, props.string("values")?) else {
                bail!("{loc}: spectrum 'irregular' needs 'wavelengths' and 'values'");
            };
            let (wavelengths, values) = (parse_numbers(&w, loc)?, parse_numbers(&v, loc)?);
            if wavelengths.len() != values.len() || wavelengths.len() < 2 || wavelengths.windows(2).any(|p| p[0] >= p[1]) {
                bail!("{loc}: spectrum 'irregular' needs as many values as wavelengths, two or more, the wavelengths increasing");
            }
            props.finish()?;
            return Ok(spectrum_to_rgb(&wavelengths, &values, usage));
        }
        "blackbody" => {
            let t = props.float("temperature", None)?;
            let lo = props.float("wavelength_min", Some(360.0))?;
            let hi = props.float("wavelength_max", Some(830.0))?;
            if t <= 0.0 || lo >= hi {
                bail!("{loc}: spectrum 'blackbody' needs a positive temperature and wavelength_min < wavelength_max");
            }
            // Planck's law is smooth: 1 nm steps (and the range's own ends) interpolate it to 1e-5.
            let mut wavelengths: Vec<f64> = vec![lo];
            wavelengths.extend((lo.floor() as i64 + 1..hi.ceil() as i64).map(|w| w as f64));
            wavelengths.push(hi);
            let values: Vec<f64> = wavelengths.iter().map(|&w| planck(w, t)).collect();
            props.finish()?;
            return Ok(spectrum_to_rgb(&wavelengths, &values, usage));
        }
        other => bail!(
            "{loc}: spectrum type '{other}' is not supported (srgb, uniform, rawconstant, d65, regular, irregular, blackbody are)"
        ),
    };
    props.finish()?;
    Ok(rgb.map(|c| c as f32))
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
