//! `load_dict`: Mitsuba 3's dictionary form of a scene, written out as the Mitsuba XML it stands for,
//! which the host's loader then reads as it reads a file (`caustic::load::load_scene_from_text`): there is
//! one loader, and a dictionary is the scene its XML is.
//!
//! Mitsuba's conventions (its `load_dict`): `type` names the plugin; a nested dictionary is a child
//! object, or `{"type": "rgb", "value": …}` / `{"type": "spectrum", "value": …}` a colour,
//! `{"type": "ref", "id": …}` a reference to an object given before; the keys of the scene's objects
//! are their ids (an `id` key gives another), the keys inside an object the names of its properties
//! and children. A bool, int, float or str is a `<boolean>`, `<integer>`, `<float>` or `<string>`;
//! three numbers a `<vector>`; a 4×4 matrix (nested lists, a numpy array, or anything with a 4×4
//! `matrix`, as `mi.ScalarTransform4f`) a `<transform>`. Anything else is refused with a ValueError
//! naming its key path (`scene.shape_1.bsdf.reflectance`), before the loader runs.
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use std::collections::HashMap;
use std::fmt::Display;

/// What stands for the scene's file in the loader's messages (`<dict>:12: …`).
pub const NAME: &str = "<dict>";

/// The XML tag of each plugin, by the family Mitsuba 3.9.1 puts it in (`tests/data/mitsuba_plugins.txt`
/// lists them), with caustic's own (`ibpt`, `bdpt`, `vcm`, `phong`, `fuzzymetal`): a dictionary names the plugin
/// only, and the tag says what kind of object it is. Plugins caustic does not render get their tag
/// too, so that the loader reports them as it would in a file.
#[rustfmt::skip]
const PLUGINS: &[(&str, &[&str])] = &[
    ("shape", &["obj", "ply", "serialized", "sphere", "rectangle", "cube", "disk", "cylinder",
        "shapegroup", "instance", "merge", "bsplinecurve", "linearcurve", "sdfgrid", "ellipsoids",
        "ellipsoidsmesh", "blender"]),
    ("bsdf", &["diffuse", "dielectric", "thindielectric", "roughdielectric", "conductor",
        "roughconductor", "plastic", "roughplastic", "pplastic", "principled", "principledthin",
        "blendbsdf", "mask", "twosided", "bumpmap", "normalmap", "null", "hair", "measured",
        "measured_polarized", "polarizer", "retarder", "circular", "phong", "fuzzymetal"]),
    ("emitter", &["area", "point", "spot", "projector", "directional", "directionalarea", "constant",
        "envmap", "sunsky", "timed_sunsky"]),
    ("sensor", &["perspective", "thinlens", "orthographic", "radiancemeter", "irradiancemeter",
        "distant", "batch"]),
    ("film", &["hdrfilm", "specfilm"]),
    ("rfilter", &["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"]),
    ("sampler", &["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]),
    ("integrator", &["path", "direct", "ptracer", "ibpt", "bdpt", "vcm", "aov", "depth", "moment", "volpath",
        "volpathmis", "prb", "prb_basic", "prb_projective", "direct_projective", "prbvolpath", "stokes",
        "volprim_rf_basic"]),
    ("texture", &["bitmap", "checkerboard", "mesh_attribute", "volume"]),
    ("medium", &["homogeneous", "heterogeneous"]),
    ("phase", &["isotropic", "hg", "rayleigh", "sggx", "tabphase", "blendphase"]),
    ("volume", &["constvolume", "gridvolume"]),
];

/// Mitsuba 3's spectra, which it makes textures: inside an object a `<spectrum type=…>`, which
/// every colour property takes (a light's as a material's); at the scene level, where an object is
/// given to be referenced, a `<texture>`.
const SPECTRA: &[&str] = &["srgb", "d65", "uniform", "rawconstant", "regular", "irregular", "blackbody"];

/// A scene written as XML, with the key path of what each of its lines holds.
pub struct Xml {
    pub text: String,
    /// `scene.shape_1.bsdf` for each line, line 1 first.
    lines: Vec<String>,
}

impl Xml {
    /// `message` (the loader's) with the key path after each `<dict>:LINE` it names: `<dict>:7
    /// (scene.light.emitter): …`.
    pub fn annotate(&self, message: &str) -> String {
        let marker = format!("{NAME}:");
        let mut out = String::with_capacity(message.len());
        let mut rest = message;
        while let Some(at) = rest.find(&marker) {
            let after = &rest[at + marker.len()..];
            let digits = after.find(|c: char| !c.is_ascii_digit()).unwrap_or(after.len());
            out.push_str(&rest[..at + marker.len() + digits]);
            let path =
                after[..digits].parse::<usize>().ok().and_then(|line| self.lines.get(line.wrapping_sub(1)));
            if let Some(path) = path {
                out.push_str(&format!(" ({path})"));
            }
            rest = &after[digits..];
        }
        out.push_str(rest);
        out
    }
}

/// The Mitsuba XML of the scene dictionary `d`, or a ValueError naming the key path of what it
/// cannot write.
pub fn to_xml(d: &Bound<'_, PyDict>) -> PyResult<Xml> {
    let path = "scene";
    let kind = type_of(d, path)?;
    if kind != "scene" {
        return Err(bad(path, format!("load_dict takes a scene ({{'type': 'scene', …}}), not a '{kind}'")));
    }
    let mut writer = Writer { text: String::new(), lines: Vec::new(), ids: HashMap::new() };
    // A reference names an object by its id or, as Mitsuba resolves it when no object has that id,
    // by its key; the XML knows ids only.
    let mut given_ids = Vec::new();
    for (key, value) in d.iter() {
        let (Ok(key), Ok(object)) = (key.extract::<String>(), value.cast::<PyDict>()) else { continue };
        if let Some(id) = object.get_item("id")? {
            if let Ok(id) = id.extract::<String>() {
                given_ids.push(id.clone());
                writer.ids.insert(key, id);
            }
        }
    }
    writer.ids.retain(|key, _| !given_ids.contains(key));
    writer.line(0, path, "<scene version=\"3.0.0\">".to_string());
    for (key, value) in d.iter() {
        let key = key_of(&key, path)?;
        match key.as_str() {
            "type" => {}
            "id" => return Err(bad(&format!("{path}.id"), "the scene takes no id")),
            _ => writer.value(1, &format!("{path}.{key}"), &key, &value, true)?,
        }
    }
    writer.line(0, path, "</scene>".to_string());
    Ok(Xml { text: writer.text, lines: writer.lines })
}

struct Writer {
    text: String,
    lines: Vec<String>,
    /// The ids of the scene's objects given an `id`, by their keys (where no object has the key
    /// as its id).
    ids: HashMap<String, String>,
}

impl Writer {
    fn line(&mut self, depth: usize, path: &str, element: String) {
        for _ in 0..depth {
            self.text.push_str("    ");
        }
        self.text.push_str(&element);
        self.text.push('\n');
        self.lines.push(path.to_string());
    }

    /// A property or child object `key` (at `path`), of the scene where `in_scene`.
    fn value(
        &mut self,
        depth: usize,
        path: &str,
        key: &str,
        value: &Bound<'_, PyAny>,
        in_scene: bool,
    ) -> PyResult<()> {
        let name = attribute(path, key)?;
        // bool before int: Python's bools are ints.
        if let Ok(b) = value.cast::<PyBool>() {
            let v = if b.is_true() { "true" } else { "false" };
            self.line(depth, path, format!("<boolean name=\"{name}\" value=\"{v}\"/>"));
        } else if value.is_instance_of::<PyInt>() {
            let v = value.str()?.to_string();
            self.line(depth, path, format!("<integer name=\"{name}\" value=\"{v}\"/>"));
        } else if let Ok(f) = value.cast::<PyFloat>() {
            self.line(depth, path, format!("<float name=\"{name}\" value=\"{}\"/>", number(f.value())));
        } else if let Ok(s) = value.cast::<PyString>() {
            let v = attribute(path, &string(s, path)?)?;
            self.line(depth, path, format!("<string name=\"{name}\" value=\"{v}\"/>"));
        } else if let Ok(d) = value.cast::<PyDict>() {
            self.object(depth, path, key, d, in_scene)?;
        } else if is_numpy_scalar(value)? {
            // np.float32(0.5), np.int64(3), np.bool_(True): as the Python number they hold.
            return self.value(depth, path, key, &value.call_method0("item")?, in_scene);
        } else {
            self.array(depth, path, &name, value)?;
        }
        Ok(())
    }

    /// Three numbers (a `<vector>`) or a 4×4 matrix (a `<transform>`): nested sequences, a numpy
    /// array, or an object with a `matrix` (`mi.ScalarTransform4f`).
    fn array(&mut self, depth: usize, path: &str, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let py = value.py();
        let unsupported = |detail: String| {
            let kind = value.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".to_string());
            bad(
                path,
                format!(
                    "unsupported value of type {kind}{detail} (a bool, int, float, str, dict, 3 numbers or a \
                     4×4 matrix are)"
                ),
            )
        };
        let source = value.getattr("matrix").unwrap_or_else(|_| value.clone());
        let numpy = py.import("numpy")?;
        let Ok(array) = numpy.call_method1("asarray", (&source, "float64")) else {
            return Err(unsupported(String::new()));
        };
        let shape: Vec<usize> = array.getattr("shape")?.extract()?;
        let numbers: Vec<f64> = match shape[..] {
            [3] | [4, 4] => array.call_method0("ravel")?.call_method0("tolist")?.extract()?,
            _ => {
                let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
                let detail = match dims.len() {
                    0 => String::new(),
                    1 => format!(" of shape ({},)", dims[0]),
                    _ => format!(" of shape ({})", dims.join(", ")),
                };
                return Err(unsupported(detail));
            }
        };
        let text = |sep: &str| numbers.iter().copied().map(number).collect::<Vec<_>>().join(sep);
        if numbers.len() == 3 {
            self.line(depth, path, format!("<vector name=\"{name}\" value=\"{}\"/>", text(", ")));
        } else {
            self.line(depth, path, format!("<transform name=\"{name}\">"));
            self.line(depth + 1, path, format!("<matrix value=\"{}\"/>", text(" ")));
            self.line(depth, path, "</transform>".to_string());
        }
        Ok(())
    }

    /// A nested dictionary: a colour, a reference, a search path, or a plugin object.
    fn object(
        &mut self,
        depth: usize,
        path: &str,
        key: &str,
        d: &Bound<'_, PyDict>,
        in_scene: bool,
    ) -> PyResult<()> {
        let name = attribute(path, key)?;
        let kind = type_of(d, path)?;
        match kind.as_str() {
            "rgb" | "spectrum" | "ref" if in_scene => {
                return Err(bad(
                    path,
                    format!(
                        "{} belongs inside an object (as in Mitsuba, the scene level takes objects)",
                        a(&kind)
                    ),
                ))
            }
            "rgb" => {
                let value = take(&mut only_keys(d, path, &["value"])?, path, "rgb", "value")?;
                let value = numbers_of(&value, path, "value", &[1, 3])?;
                self.line(depth, path, format!("<rgb name=\"{name}\" value=\"{value}\"/>"));
            }
            "spectrum" => {
                let mut given = only_keys(d, path, &["value", "filename"])?;
                let element = match (given.remove("value"), given.remove("filename")) {
                    (Some(value), None) => format!("value=\"{}\"", spectrum_value(&value, path)?),
                    (None, Some(file)) => {
                        let file =
                            file.extract::<String>().map_err(|_| bad(path, "'filename' must be a str"))?;
                        format!("filename=\"{}\"", attribute(path, &file)?)
                    }
                    _ => return Err(bad(path, "a 'spectrum' takes a 'value' or a 'filename' (one of them)")),
                };
                self.line(depth, path, format!("<spectrum name=\"{name}\" {element}/>"));
            }
            "ref" => {
                let id = take(&mut only_keys(d, path, &["id"])?, path, "ref", "id")?;
                let id = id.extract::<String>().map_err(|_| bad(path, "a reference's 'id' must be a str"))?;
                let id = self.ids.get(&id).cloned().unwrap_or(id);
                let id = attribute(path, &id)?;
                self.line(depth, path, format!("<ref name=\"{name}\" id=\"{id}\"/>"));
            }
            "resources" => {
                if !in_scene {
                    return Err(bad(path, "'resources' belongs at the scene level"));
                }
                let dir = take(&mut only_keys(d, path, &["path"])?, path, "resources", "path")?;
                let dir = dir.extract::<String>().map_err(|_| bad(path, "'path' must be a str"))?;
                self.line(depth, path, format!("<path value=\"{}\"/>", attribute(path, &dir)?));
            }
            "scene" => return Err(bad(path, "a scene inside a scene")),
            plugin => {
                let tag = if SPECTRA.contains(&plugin) {
                    if in_scene {
                        "texture"
                    } else {
                        "spectrum"
                    }
                } else {
                    PLUGINS
                        .iter()
                        .find(|(_, plugins)| plugins.contains(&plugin))
                        .map(|(tag, _)| *tag)
                        .ok_or_else(|| {
                            bad(
                                path,
                                format!("unknown plugin type '{plugin}' (Mitsuba 3 has no such plugin)"),
                            )
                        })?
                };
                let mut attributes = format!("type=\"{}\"", attribute(path, plugin)?);
                let id = match d.get_item("id")? {
                    Some(id) => Some(
                        id.extract::<String>()
                            .map_err(|_| bad(&format!("{path}.id"), "an id must be a str"))?,
                    ),
                    None => None,
                };
                if in_scene {
                    // The scene's objects are known by their keys, as Mitsuba knows them.
                    let id = id.unwrap_or_else(|| key.to_string());
                    attributes += &format!(" id=\"{}\"", attribute(path, &id)?);
                } else {
                    attributes += &format!(" name=\"{name}\"");
                    if let Some(id) = id {
                        attributes += &format!(" id=\"{}\"", attribute(path, &id)?);
                    }
                }
                let children: Vec<(String, Bound<'_, PyAny>)> = d
                    .iter()
                    .map(|(k, v)| Ok((key_of(&k, path)?, v)))
                    .collect::<PyResult<Vec<_>>>()?
                    .into_iter()
                    .filter(|(k, _)| k != "type" && k != "id")
                    .collect();
                if children.is_empty() {
                    self.line(depth, path, format!("<{tag} {attributes}/>"));
                } else {
                    self.line(depth, path, format!("<{tag} {attributes}>"));
                    for (k, v) in &children {
                        self.value(depth + 1, &format!("{path}.{k}"), k, v, false)?;
                    }
                    self.line(depth, path, format!("</{tag}>"));
                }
            }
        }
        Ok(())
    }
}

/// `'kind'` with its article: "an 'rgb'" (read letter by letter), "a 'ref'".
fn a(kind: &str) -> String {
    format!("{} '{kind}'", if kind == "rgb" { "an" } else { "a" })
}

/// A ValueError naming the key path.
fn bad(path: &str, message: impl Display) -> PyErr {
    PyValueError::new_err(format!("{path}: {message}"))
}

/// A dictionary's `type`.
fn type_of(d: &Bound<'_, PyDict>, path: &str) -> PyResult<String> {
    match d.get_item("type")? {
        None => Err(bad(path, "a dictionary needs a 'type' (the plugin's name, 'rgb', 'spectrum' or 'ref')")),
        Some(kind) => kind.extract::<String>().map_err(|_| bad(path, "'type' must be a str")),
    }
}

/// A key: a str without `.`, which Mitsuba keeps for object paths.
fn key_of(key: &Bound<'_, PyAny>, path: &str) -> PyResult<String> {
    let Ok(s) = key.cast::<PyString>() else {
        return Err(bad(path, format!("the key {} is not a str", key.repr()?)));
    };
    let key = string(s, path)?;
    if key.is_empty() || key.contains('.') {
        return Err(bad(
            path,
            format!("the key '{key}' {}", if key.is_empty() { "is empty" } else { "contains '.' (use '_')" }),
        ));
    }
    Ok(key)
}

/// `s` as Rust text (a lone surrogate is refused).
fn string(s: &Bound<'_, PyString>, path: &str) -> PyResult<String> {
    s.extract::<String>().map_err(|e| bad(path, e))
}

/// The entries of a dictionary of a fixed form (`rgb`, `ref`, …), by key: those of `allowed` it
/// has; any other key but `type` is refused.
fn only_keys<'py>(
    d: &Bound<'py, PyDict>,
    path: &str,
    allowed: &[&str],
) -> PyResult<HashMap<String, Bound<'py, PyAny>>> {
    let kind = type_of(d, path)?;
    let mut given = HashMap::new();
    for (key, value) in d.iter() {
        let key = key_of(&key, path)?;
        if key == "type" {
            continue;
        }
        if !allowed.contains(&key.as_str()) {
            let keys = allowed.iter().map(|k| format!("'{k}'")).collect::<Vec<_>>().join(", ");
            return Err(bad(&format!("{path}.{key}"), format!("{} takes 'type' and {keys} only", a(&kind))));
        }
        given.insert(key, value);
    }
    Ok(given)
}

/// The entry `key` of a `kind` dictionary's entries (`only_keys`), which it needs.
fn take<'py>(
    given: &mut HashMap<String, Bound<'py, PyAny>>,
    path: &str,
    kind: &str,
    key: &str,
) -> PyResult<Bound<'py, PyAny>> {
    given.remove(key).ok_or_else(|| bad(path, format!("{} needs '{key}'", a(kind))))
}

/// A number, or a sequence of numbers of one of the `counts`, as an attribute's `a, b, c`.
fn numbers_of(value: &Bound<'_, PyAny>, path: &str, what: &str, counts: &[usize]) -> PyResult<String> {
    let numbers: Vec<f64> = if let Ok(v) = value.extract::<f64>() {
        vec![v]
    } else if let Ok(v) = value.extract::<Vec<f64>>() {
        v
    } else {
        let numpy = value.py().import("numpy")?;
        let flat = numpy.call_method1("asarray", (value, "float64")).and_then(|a| {
            if a.getattr("ndim")?.extract::<usize>()? == 1 {
                a.call_method0("tolist")?.extract::<Vec<f64>>()
            } else {
                Err(PyValueError::new_err(""))
            }
        });
        flat.map_err(|_| bad(path, format!("'{what}' must be a number or a sequence of numbers")))?
    };
    if !counts.contains(&numbers.len()) {
        let counts = counts.iter().map(|c| c.to_string()).collect::<Vec<_>>().join(" or ");
        return Err(bad(path, format!("'{what}' takes {counts} numbers, not {}", numbers.len())));
    }
    Ok(numbers.iter().copied().map(number).collect::<Vec<_>>().join(", "))
}

/// A `spectrum`'s value: a number, or (wavelength, value) pairs, as Mitsuba's `load_dict` takes
/// them, written as the XML's `v` or `λ:v, λ:v, …`.
fn spectrum_value(value: &Bound<'_, PyAny>, path: &str) -> PyResult<String> {
    if let Ok(v) = value.extract::<f64>() {
        return Ok(number(v));
    }
    let pairs: Vec<(f64, f64)> = value
        .extract()
        .map_err(|_| bad(path, "a spectrum's 'value' is a number or a list of (wavelength, value) pairs"))?;
    Ok(pairs.iter().map(|&(w, v)| format!("{}:{}", number(w), number(v))).collect::<Vec<_>>().join(", "))
}

/// A number as the loader reads it back exactly: the shortest text that parses to `v` (`1.5`,
/// `6.123233995736766e-17`, `inf`, `NaN`).
fn number(v: f64) -> String {
    format!("{v:?}")
}

/// Whether `value` is a numpy scalar (`numpy.generic`); false where numpy is not installed.
fn is_numpy_scalar(value: &Bound<'_, PyAny>) -> PyResult<bool> {
    match value.py().import("numpy") {
        Ok(numpy) => value.is_instance(&numpy.getattr("generic")?),
        Err(_) => Ok(false),
    }
}

/// `value` as an XML attribute's text: escaped, `\t`, `\n` and `\r` as character references (an
/// XML parser reads them as spaces otherwise). A `$` is refused: the loader reads `$name` in every
/// attribute as a scene parameter, which a dictionary does not have.
fn attribute(path: &str, value: &str) -> PyResult<String> {
    let mut out = String::with_capacity(value.len());
    for c in value.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push_str(&format!("&#{};", c as u32)),
            '$' => {
                return Err(bad(
                    path,
                    format!(
                        "'{value}': a '$' cannot be given (the XML loader reads $name as a scene parameter)"
                    ),
                ))
            }
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {
                return Err(bad(path, format!("the character U+{:04X} cannot be written in XML", c as u32)))
            }
            c => out.push(c),
        }
    }
    Ok(out)
}
