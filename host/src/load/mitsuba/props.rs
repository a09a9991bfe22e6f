//! Typed access to a plugin element's properties, each remembered with its file:line for messages.
use super::loader::Loader;
use super::xml::{vector_from_node, Loc, Params, Source};
use anyhow::{bail, Context, Result};
use glam::{Mat4, Vec3};
use std::cell::RefCell;

/// One child element of a plugin: a value (`<float name=…>`) or a nested object (`<bsdf>`, `<ref>`).
pub struct Entry<'a, 'input> {
    pub tag: String,
    pub name: Option<String>,
    /// The `value` attribute after `$name` substitution.
    pub value: Option<String>,
    pub node: roxmltree::Node<'a, 'input>,
    pub loc: Loc,
}

pub struct Props<'a, 'input> {
    pub loc: Loc,
    pub tag: String,
    /// The plugin type (`type` attribute), empty for `<ref>`.
    pub kind: String,
    /// The `id` attribute (the target of a `<ref>`), `$name` substituted as every attribute.
    pub id: Option<String>,
    /// The file it was read from.
    pub src: &'a Source<'input>,
    pub entries: Vec<Entry<'a, 'input>>,
    /// The scene's parameters when the element was read, for `$name` in attributes other than `value`.
    pub(super) params: Params,
    used: RefCell<Vec<bool>>,
}

impl<'a, 'input> Props<'a, 'input> {
    pub fn collect(
        loader: &Loader,
        src: &'a Source<'input>,
        node: roxmltree::Node<'a, 'input>,
    ) -> Result<Self> {
        Self::collect_in(loader.params(), Some(loader), src, node)
    }

    /// The properties of `node` with `$name` substituted from `params`; `<spectrum filename>` is
    /// read where a `loader` (its search paths) is given, refused otherwise.
    fn collect_in(
        params: &Params,
        loader: Option<&Loader>,
        src: &'a Source<'input>,
        node: roxmltree::Node<'a, 'input>,
    ) -> Result<Self> {
        let loc = src.loc(node);
        let mut entries = Vec::new();
        for child in node.children().filter(|n| n.is_element()) {
            let child_loc = src.loc(child);
            let mut value = match child.attribute("value") {
                Some(v) => Some(super::xml::substitute(params, v, &child_loc)?),
                None => None,
            };
            if child.tag_name().name() == "spectrum" {
                if let Some(file) = super::xml::attribute(child, "filename", params, &child_loc)? {
                    let Some(loader) = loader else {
                        bail!("{child_loc}: a spectrum file is not read inside a spectrum");
                    };
                    value = Some(spectrum_file_value(loader, &file, value.is_some(), &child_loc)?);
                }
            }
            entries.push(Entry {
                tag: child.tag_name().name().to_string(),
                name: super::xml::attribute(child, "name", params, &child_loc)?,
                value,
                node: child,
                loc: child_loc,
            });
        }
        let kind = match node.attribute("type") {
            Some(t) => super::xml::substitute(params, t, &loc)?,
            None => String::new(),
        };
        let n = entries.len();
        let id = super::xml::attribute(node, "id", params, &loc)?;
        Ok(Props {
            loc,
            tag: node.tag_name().name().to_string(),
            kind,
            id,
            src,
            entries,
            params: params.clone(),
            used: RefCell::new(vec![false; n]),
        })
    }

    /// The properties of the object nested as entry `i` (a spectrum plugin inside a colour
    /// property), read with this element's parameters.
    pub(super) fn nested_props(&self, i: usize) -> Result<Props<'a, 'input>> {
        Props::collect_in(&self.params, None, self.src, self.entries[i].node)
    }

    /// The tag property `name` is given with (`float`, `rgb`, …), without marking it read.
    pub fn tag_of(&self, name: &str) -> Option<&str> {
        self.entries.iter().find(|e| e.name.as_deref() == Some(name)).map(|e| e.tag.as_str())
    }

    pub(super) fn find(&self, name: &str) -> Option<usize> {
        let i = self.entries.iter().position(|e| e.name.as_deref() == Some(name))?;
        self.used.borrow_mut()[i] = true;
        Some(i)
    }

    /// Whether the element gives the property `name` (without marking it read).
    pub fn has(&self, name: &str) -> bool {
        self.entries.iter().any(|e| e.name.as_deref() == Some(name))
    }

    pub(super) fn value_of(&self, i: usize) -> Result<&str> {
        let e = &self.entries[i];
        e.value.as_deref().with_context(|| format!("{}: <{}> needs a 'value' attribute", e.loc, e.tag))
    }

    pub fn float(&self, name: &str, default: f32) -> Result<f32> {
        let Some(i) = self.find(name) else { return Ok(default) };
        let e = &self.entries[i];
        let v: f32 = self
            .value_of(i)?
            .trim()
            .parse()
            .map_err(|_| anyhow::anyhow!("{}: '{name}' must be a number", e.loc))?;
        if !v.is_finite() {
            bail!("{}: '{name}' must be finite", e.loc);
        }
        Ok(v)
    }

    pub fn integer(&self, name: &str, default: i64) -> Result<i64> {
        let Some(i) = self.find(name) else { return Ok(default) };
        let e = &self.entries[i];
        self.value_of(i)?
            .trim()
            .parse()
            .map_err(|_| anyhow::anyhow!("{}: '{name}' must be an integer", e.loc))
    }

    pub fn boolean(&self, name: &str, default: bool) -> Result<bool> {
        let Some(i) = self.find(name) else { return Ok(default) };
        // Any case, as Mitsuba's parser reads it (Blender's exporter writes `True`).
        match self.value_of(i)?.trim() {
            v if v.eq_ignore_ascii_case("true") || v == "1" => Ok(true),
            v if v.eq_ignore_ascii_case("false") || v == "0" => Ok(false),
            other => bail!("{}: '{name}' must be true or false, not '{other}'", self.entries[i].loc),
        }
    }

    pub fn string(&self, name: &str) -> Result<Option<String>> {
        let Some(i) = self.find(name) else { return Ok(None) };
        Ok(Some(self.value_of(i)?.to_string()))
    }

    pub fn point(&self, name: &str, default: Vec3) -> Result<Vec3> {
        let Some(i) = self.find(name) else { return Ok(default) };
        let e = &self.entries[i];
        vector_from_node(e.node, e.value.as_deref(), &self.params, &e.loc)
    }

    pub fn transform(&self, name: &str) -> Result<Mat4> {
        let Some(i) = self.find(name) else { return Ok(Mat4::IDENTITY) };
        let e = &self.entries[i];
        super::transform::parse(self.src, e.node, &self.params, &e.loc)
    }

    /// Nested objects with the given tag (e.g. `bsdf`, `emitter`, `ref`), marked as used.
    pub fn nested(&self, tag: &str) -> Vec<&Entry<'a, 'input>> {
        let mut out = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            if e.tag == tag {
                self.used.borrow_mut()[i] = true;
                out.push(e);
            }
        }
        out
    }

    /// The id a `<ref>` points to.
    pub fn doc_attr_id(&self) -> Result<String> {
        self.id.clone().with_context(|| format!("{}: <{}> needs an 'id'", self.loc, self.tag))
    }

    /// Marks the entry named `name` as read (for values a plugin consumes without the typed getters).
    pub fn mark_used(&self, name: &str) {
        self.find(name);
    }

    /// For plugins that are skipped whole: their parameters need no separate warnings.
    pub fn mark_all_used(&self) {
        self.used.borrow_mut().iter_mut().for_each(|u| *u = true);
    }

    /// The entries no plugin code asked for: where, the group they are reported under (the entry
    /// and its plugin: `<float name="radius"> of rfilter 'box'`), and the message.
    pub fn unused(&self) -> Vec<(Loc, String, String)> {
        let used = self.used.borrow();
        self.entries
            .iter()
            .zip(used.iter())
            .filter(|(_, u)| !**u)
            .map(|(e, _)| {
                let group = match &e.name {
                    Some(n) => format!("<{} name=\"{n}\"> of {} '{}'", e.tag, self.tag, self.kind),
                    None => format!("<{}> inside {} '{}'", e.tag, self.tag, self.kind),
                };
                let message = format!("{}: {group} is not supported; ignored", e.loc);
                (e.loc.clone(), group, message)
            })
            .collect()
    }
}

/// `<spectrum filename="…"/>` (Mitsuba's irregular spectrum from a file): the file's `wavelength
/// value` pairs (`spectrum::read_spd`, the format of Mitsuba's `.spd` files) as the
/// `value="λ:v, …"` they stand for, so that both forms are converted alike.
fn spectrum_file_value(loader: &Loader, file: &str, has_value: bool, loc: &Loc) -> Result<String> {
    if has_value {
        bail!("{loc}: <spectrum> takes a 'value' or a 'filename', not both");
    }
    let path = loader.resolve(file, loc)?;
    let (wavelengths, values) =
        super::spectrum::read_spd(&path).with_context(|| format!("{loc}: spectrum file"))?;
    let pairs: Vec<String> = wavelengths.iter().zip(&values).map(|(w, v)| format!("{w}:{v}")).collect();
    Ok(pairs.join(", "))
}

impl Loader {
    pub(crate) fn props<'a, 'input>(
        &self,
        src: &'a Source<'input>,
        node: roxmltree::Node<'a, 'input>,
    ) -> Result<Props<'a, 'input>> {
        Props::collect(self, src, node)
    }

    /// Records every property and nested element of `props` that the plugin did not read.
    pub(crate) fn warn_unused(&mut self, props: &Props) {
        for (loc, group, message) in props.unused() {
            self.ignored(group, &loc, message);
        }
    }
}
