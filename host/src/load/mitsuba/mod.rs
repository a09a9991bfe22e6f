//! Mitsuba 3 XML scenes (a documented subset; see the table in docs/mitsuba.md).
//!
//! One file per family of scene elements, as Mitsuba splits its plugins: `shapes`, `bsdfs` (with
//! `blend`, `pplastic` and `bsdf_maps`, normal and bump maps, beside it), `emitters`, `sensors`
//! (sensor, film, filter, sampler), `integrators`; `transform` and `spectrum` parse values; `props`
//! gives typed properties with their source locations; `xml` holds the XML primitives all of these
//! share (locations, attributes, number lists, one-or-three-number vectors) and uses none of them.
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
use crate::scene::{Integrator, Scene};
use anyhow::{bail, Context, Result};
use caustic_kernel::layout::Material;
use deviations::Deviations;
use props::Props;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use xml::{Loc, Source};

/// The most `<include>` loads one scene may make, repeats counted (Mitsuba's own scenes make a
/// handful).
const MAX_INCLUDES: u32 = 10_000;

/// The state of loading one scene (shared by included files).
pub(crate) struct Loader {
    /// `<default>` values and `-D` overrides (the latter win).
    params: HashMap<String, String>,
    /// Directories searched for relative file names, most recent `<path>` first.
    search_paths: Vec<PathBuf>,
    /// Named BSDFs (`id`), as indices into `materials`.
    named_bsdfs: HashMap<String, u32>,
    materials: Vec<Material>,
    shapes: Vec<crate::scene::Shape>,
    emitters: Vec<crate::scene::Emitter>,
    textures: Vec<crate::scene::SceneTexture>,
    /// `Scene::weight_tables`.
    weight_tables: Vec<[f32; caustic_kernel::bsdf::textured_weights::SLOTS]>,
    /// Named area emitters (`id`) defined at the top level, for shapes that `<ref>` them.
    named_area_emitters: HashMap<String, emitters::AreaEmission>,
    /// `shapegroup`s by id, as indices into `instancing.groups` (their triangles and disks, in the
    /// group's space) and `group_spheres` (their spheres), for `instance`s to place.
    shape_groups: HashMap<String, usize>,
    group_spheres: Vec<Vec<crate::scene::Shape>>,
    instancing: crate::scene::instancing::Instancing,
    /// Named textures (`id`), as indices into `textures`.
    named_textures: HashMap<String, u32>,
    /// Top-level samplers, films and rfilters with an `id`, kept as their file and their element's
    /// text (behind as many newlines as it stood below the file's start, so that messages name the
    /// right line) until a sensor or film `<ref>`s them: Mitsuba resolves such references across
    /// `<include>`d files (its own sampler scenes define the sampler in one file and ref it in another).
    pub(crate) named_sensor_parts: HashMap<String, (std::path::PathBuf, String)>,
    /// The scene's sensor: the first in document order, which Mitsuba renders by default.
    sensor: Option<crate::scene::Sensor>,
    /// Where that sensor was given.
    sensor_loc: Option<Loc>,
    /// The shape (index into `shapes`) carrying an irradiance meter, and where the meter was given.
    meter_shape: Option<(usize, Loc)>,
    integrator: Option<Integrator>,
    /// The `aov` or `depth` integrator's outputs (`crate::scene::aov`).
    aovs: Option<crate::scene::aov::AovSpec>,
    warnings: Vec<String>,
    /// What the scene asks for that the loaded scene does not do (reported or refused at the end).
    deviations: Deviations,
    include_depth: u32,
    /// Files `<include>`d so far, repeats counted: bounded (`MAX_INCLUDES`), since files that each
    /// include the next twice ask for 2^depth loads within the depth limit.
    includes: u32,
    /// Every `id` given so far, in any file of the scene, with where: Mitsuba refuses a duplicate.
    ids: HashMap<String, Loc>,
    /// Where the scene's integrator was given: Mitsuba refuses a second.
    integrator_loc: Option<Loc>,
    /// `mesh_attribute` textures a parameter asked for (`mesh_attributes`).
    attribute_requests: Vec<u32>,
}

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

/// A loader with nothing loaded yet; `defines` are `-D name=value` overrides.
fn new_loader(defines: &[(String, String)]) -> Loader {
    Loader {
        params: defines.iter().cloned().collect(),
        search_paths: Vec::new(),
        named_bsdfs: HashMap::new(),
        materials: Vec::new(),
        shapes: Vec::new(),
        emitters: Vec::new(),
        textures: Vec::new(),
        weight_tables: Vec::new(),
        named_textures: HashMap::new(),
        named_sensor_parts: HashMap::new(),
        named_area_emitters: HashMap::new(),
        shape_groups: HashMap::new(),
        group_spheres: Vec::new(),
        instancing: Default::default(),
        sensor: None,
        sensor_loc: None,
        meter_shape: None,
        integrator: None,
        aovs: None,
        warnings: Vec::new(),
        deviations: Deviations::default(),
        include_depth: 0,
        includes: 0,
        ids: HashMap::new(),
        integrator_loc: None,
        attribute_requests: Vec::new(),
    }
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
    pub(crate) fn warn(&mut self, message: &str) {
        crate::scene::warn(&mut self.warnings, message.to_string());
    }

    /// Records an element replaced by a stand-in or left out; `group` names the kind of element
    /// (`bsdf 'mask'`), so that 500 of them are reported once.
    pub(crate) fn substituted(&mut self, group: String, loc: &Loc, message: String) {
        self.deviations.push(deviations::Kind::Substituted, group, loc, message);
    }

    /// Records a property or nested element that is not read.
    pub(crate) fn ignored(&mut self, group: String, loc: &Loc, message: String) {
        self.deviations.push(deviations::Kind::Ignored, group, loc, message);
    }

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

    /// Replaces `$name` references by their values.
    pub(crate) fn substitute(&self, value: &str, loc: &Loc) -> Result<String> {
        xml::substitute(&self.params, value, loc)
    }

    /// Attribute `name` of `node` with its `$name` references substituted, as Mitsuba substitutes in
    /// every attribute (`<ref id="$material"/>` picks a BSDF by parameter).
    pub(crate) fn attribute(&self, node: roxmltree::Node, name: &str, loc: &Loc) -> Result<Option<String>> {
        xml::attribute(node, name, &self.params, loc)
    }

    /// The scene's parameters as read so far.
    pub(crate) fn params(&self) -> &xml::Params {
        &self.params
    }

    /// Finds a file named in the scene: absolute, or relative to the search paths.
    pub(crate) fn resolve(&self, name: &str, loc: &Loc) -> Result<PathBuf> {
        let p = Path::new(name);
        if p.is_absolute() {
            if p.exists() {
                return Ok(p.to_path_buf());
            }
        } else {
            for dir in &self.search_paths {
                let candidate = dir.join(p);
                if candidate.exists() {
                    return Ok(candidate);
                }
            }
        }
        bail!(
            "{loc}: file not found: {name} (searched {})",
            self.search_paths.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
        )
    }

    fn resolve_dir(&self, value: &str) -> PathBuf {
        let p = Path::new(value);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.search_paths.first().map(|d| d.join(p)).unwrap_or_else(|| p.to_path_buf())
        }
    }

    pub(crate) fn props<'a, 'input>(
        &self,
        src: &'a Source<'input>,
        node: roxmltree::Node<'a, 'input>,
    ) -> Result<Props<'a, 'input>> {
        Props::collect(self, src, node)
    }

    /// Records every property and nested element of `props` that the plugin did not read.
    /// Takes `sensor` (given at `loc`) as the scene's unless one came before it: Mitsuba lists a
    /// scene's sensors in document order (those in shapes among them) and renders the first.
    pub(crate) fn set_sensor(&mut self, sensor: crate::scene::Sensor, loc: &Loc) {
        if let Some(first) = &self.sensor_loc {
            let message =
                format!("{loc}: a second sensor; the first, at {first}, is the one rendered (as Mitsuba)");
            self.warn(&message);
            return;
        }
        if let crate::scene::Projection::IrradianceMeter { shape } = sensor.projection {
            self.meter_shape = Some((shape, loc.clone()));
        }
        self.sensor = Some(sensor);
        self.sensor_loc = Some(loc.clone());
    }

    pub(crate) fn warn_unused(&mut self, props: &Props) {
        for (loc, group, message) in props.unused() {
            self.ignored(group, &loc, message);
        }
    }
}
