//! Mitsuba 3 XML scenes (a documented subset; see the table in docs/mitsuba.md).
//!
//! One file per family of scene elements, as Mitsuba splits its plugins: `shapes`, `bsdfs` (with
//! `blend`, `pplastic` and `bsdf_maps`, normal and bump maps, beside it), `emitters`, `sensors`
//! (sensor, film, filter, sampler), `integrators`; `transform` and `spectrum` parse values; `props`
//! gives typed properties with their source locations; `xml` holds the XML primitives all of these
//! share (locations, attributes, number lists, one-or-three-number vectors) and uses none of them;
//! `loader` holds the state of one load (`Loader`), which each family extends with its plugins.
//! This module holds the document machinery: `<default>`, `$name` substitution, `-D` overrides,
//! `<include>`, `<path>`, `id`/`<ref>` (ids unique, as Mitsuba wants them), and one integrator per
//! scene; `deviations` collects what was substituted or ignored, which `--strict`
//! (`LoadOptions::strict`) refuses.
mod bitmap_format;
mod blend;
mod bsdf_maps;
mod bsdfs;
pub mod cie_tables;
mod conductor_table;
mod deviations;
mod emitters;
mod integrators;
pub mod ior;
mod loader;
mod mesh_attributes;
mod pplastic;
mod props;
mod sensors;
mod shapes;
pub mod spectrum;
mod spectrum_plugin;
mod textures;
mod transform;
mod xml;

use crate::load::options::LoadOptions;
use crate::scene::Scene;
use anyhow::{bail, Context, Result};
use loader::{new_loader, Loader};
use std::path::Path;
use xml::Source;

/// The most `<include>` loads one scene may make, repeats counted (Mitsuba's own scenes make a
/// handful).
const MAX_INCLUDES: u32 = 10_000;

/// Loads a Mitsuba 3 scene; `defines` are `-D name=value` overrides.
pub fn load(path: &Path, defines: &[(String, String)]) -> Result<Scene> {
    load_with(path, defines, LoadOptions::default())
}

/// As `load`; with `options.strict`, any substitution or ignored property is an error.
pub fn load_with(path: &Path, defines: &[(String, String)], options: LoadOptions) -> Result<Scene> {
    let mut loader = new_loader(defines);
    loader.load_file(path)?;
    finish(loader, path, options)
}

/// As `load_with`, for a scene given as XML text rather than a file (the Python module's
/// `load_dict` writes one): `name` stands for the file in messages (`name:line: …`), and relative
/// file names resolve against `dir`. The same loader as a file's, `<include>`s and all.
pub fn load_text_with(
    name: &Path,
    text: &str,
    dir: &Path,
    defines: &[(String, String)],
    options: LoadOptions,
) -> Result<Scene> {
    let mut loader = new_loader(defines);
    loader.load_text(name, text, dir)?;
    finish(loader, name, options)
}

/// The scene of what `loader` loaded (from `path`, which messages name).
fn finish(mut loader: Loader, path: &Path, options: LoadOptions) -> Result<Scene> {
    loader.check_attribute_uses()?;
    let sensor = match loader.sensor.take() {
        Some(s) => s,
        None => {
            loader.warn(&format!(
                "{}: no <sensor>; using Mitsuba's default perspective camera",
                path.display()
            ));
            sensors::default_sensor()
        }
    };
    if options.strict {
        if let Some(e) = loader.deviations.strict_error(path) {
            return Err(e);
        }
    }
    for line in loader.deviations.report(path) {
        loader.warn(&line);
    }
    let mut scene = Scene {
        sensor,
        integrator: loader.integrator.take().unwrap_or_default(),
        materials: loader.materials,
        shapes: loader.shapes,
        instancing: loader.instancing,
        emitters: loader.emitters,
        textures: loader.textures,
        weight_tables: loader.weight_tables,
        aovs: loader.aovs.take(),
        warnings: loader.warnings,
    };
    // The AOV pass reads a primitive's shape from the one-level list (`prepare::primitives::prim_origins`):
    // with AOVs every instance is flattened.
    let min_placements =
        if scene.aovs.is_some() { usize::MAX } else { crate::scene::instancing::MIN_PLACEMENTS };
    scene.flatten_instances(min_placements)?;
    Ok(scene)
}

impl Loader {
    fn load_file(&mut self, path: &Path) -> Result<()> {
        let text = crate::system::files::read_to_string(path, "scene file")?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        self.load_text(path, &text, &dir)
    }

    /// Loads the scene document `text`: the file `path`, or what stands for one in messages, whose
    /// relative file names resolve against `dir`.
    fn load_text(&mut self, path: &Path, text: &str, dir: &Path) -> Result<()> {
        let src = Source::parse(path, text)?;
        let root = src.doc.root_element();
        let loc = src.loc(root);
        if root.tag_name().name() != "scene" {
            bail!("{loc}: expected a <scene> root element, found <{}>", root.tag_name().name());
        }
        self.check_ids(&src)?;
        self.search_paths.insert(0, dir.to_path_buf());
        let result = self.load_scene_children(&src, root);
        self.search_paths.remove(0);
        result
    }

    /// Refuses an `id` given twice (here or in an earlier file of the scene), as Mitsuba does;
    /// `<ref id>` refers to an id and does not give one.
    /// Ids are compared after `$name` substitution, with this file's own `<default>`s (read before
    /// anything else in it) known.
    fn check_ids(&mut self, src: &Source) -> Result<()> {
        let mut params = self.params.clone();
        let root = src.doc.root_element();
        for d in root.children().filter(|n| n.is_element() && n.tag_name().name() == "default") {
            if let (Some(name), Some(value)) = (d.attribute("name"), d.attribute("value")) {
                params.entry(name.to_string()).or_insert_with(|| value.to_string());
            }
        }
        for node in src.doc.descendants().filter(|n| n.is_element() && n.tag_name().name() != "ref") {
            let loc = src.loc(node);
            let Some(id) = xml::attribute(node, "id", &params, &loc)? else { continue };
            if let Some(first) = self.ids.get(&id) {
                bail!("{loc}: duplicate id \"{id}\" (first given at {first})");
            }
            self.ids.insert(id, loc);
        }
        Ok(())
    }

    fn load_scene_children(&mut self, src: &Source, root: roxmltree::Node) -> Result<()> {
        self.register_named_area_emitters(src, root)?;
        for node in root.children().filter(|n| n.is_element()) {
            let loc = src.loc(node);
            match node.tag_name().name() {
                "default" => {
                    let name = xml::attr(node, "name", &loc)?;
                    let value = xml::attr(node, "value", &loc)?;
                    self.params.entry(name.to_string()).or_insert_with(|| value.to_string());
                }
                "include" => {
                    let file =
                        self.resolve(&self.substitute(xml::attr(node, "filename", &loc)?, &loc)?, &loc)?;
                    self.include_depth += 1;
                    self.includes += 1;
                    if self.include_depth > 32 {
                        bail!("{loc}: <include> nested more than 32 deep (a cycle?)");
                    }
                    if self.includes > MAX_INCLUDES {
                        bail!("{loc}: the scene includes more than {MAX_INCLUDES} files in all (repeats counted)");
                    }
                    if let Some(signal) = crate::system::interrupt::requested() {
                        bail!("{loc}: loading stopped by signal {signal}");
                    }
                    self.load_file(&file).with_context(|| format!("{loc}: in the file included here"))?;
                    self.include_depth -= 1;
                }
                "path" => {
                    let value = self.substitute(xml::attr(node, "value", &loc)?, &loc)?;
                    let dir = self.resolve_dir(&value);
                    self.search_paths.insert(1.min(self.search_paths.len()), dir);
                }
                "bsdf" => {
                    let props = self.props(src, node)?;
                    let index = self.load_bsdf(&props)?;
                    if let Some(id) = props.id {
                        self.named_bsdfs.insert(id, index);
                    }
                }
                "shape" => {
                    let props = self.props(src, node)?;
                    self.load_shape(&props)?;
                }
                "texture" => {
                    let props = self.props(src, node)?;
                    let index = self.load_texture(&props)?;
                    if let Some(id) = props.id {
                        self.named_textures.insert(id, index);
                    }
                }
                "emitter" => {
                    let props = self.props(src, node)?;
                    let surface = matches!(props.kind.as_str(), "area" | "directionalarea");
                    if !(surface && props.id.is_some()) {
                        self.load_emitter(&props)?;
                    }
                }
                "sampler" | "film" | "rfilter" if node.attribute("id").is_some() => {
                    let id = self.attribute(node, "id", &loc)?.unwrap_or_default();
                    let text = &src.doc.input_text()[node.range()];
                    let placed = "\n".repeat(loc.line.saturating_sub(1) as usize) + text;
                    self.named_sensor_parts.insert(id, (src.path.clone(), placed));
                }
                "sensor" => {
                    let props = self.props(src, node)?;
                    let sensor = self.load_sensor(&props)?;
                    self.set_sensor(sensor, &loc);
                }
                "integrator" => {
                    if let Some(first) = &self.integrator_loc {
                        bail!("{loc}: a second <integrator> (the first is at {first}); a scene takes one");
                    }
                    let props = self.props(src, node)?;
                    self.integrator = Some(self.load_integrator(&props)?);
                    self.integrator_loc = Some(loc);
                }
                other => {
                    let message = format!("{loc}: <{other}> is not supported yet; ignored");
                    self.ignored(format!("<{other}>"), &loc, message);
                }
            }
        }
        Ok(())
    }

    /// Top-level named area emitters, registered before the shapes that `<ref>` them load: Mitsuba
    /// resolves references across the whole file, so a shape may name an emitter defined below it.
    fn register_named_area_emitters(&mut self, src: &Source, root: roxmltree::Node) -> Result<()> {
        let named = root.children().filter(|n| {
            n.is_element()
                && n.tag_name().name() == "emitter"
                && matches!(n.attribute("type"), Some("area" | "directionalarea"))
        });
        for node in named {
            let props = self.props(src, node)?;
            if let Some(id) = props.id.clone() {
                if let Some(radiance) = self.load_shape_emitter(&props)? {
                    self.named_area_emitters.insert(id, radiance);
                }
            }
        }
        Ok(())
    }
}
