//! The state of loading one scene (`Loader`, shared by the files it includes) and what every plugin's
//! loader asks of it: warnings and deviations (`warn`, `substituted`, `ignored`), `$name`
//! substitution, files found on the search paths (`resolve`), the scene's sensor (`set_sensor`).
//! The plugin families extend `Loader` in their own files; the document machinery is `mitsuba`'s.
use super::deviations::{self, Deviations};
use super::xml::{self, Loc};
use crate::scene::Integrator;
use anyhow::{bail, Result};
use caustic_kernel::layout::Material;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The state of loading one scene (shared by included files).
pub(crate) struct Loader {
    /// `<default>` values and `-D` overrides (the latter win).
    pub(super) params: HashMap<String, String>,
    /// Directories searched for relative file names, most recent `<path>` first.
    pub(super) search_paths: Vec<PathBuf>,
    /// Named BSDFs (`id`), as indices into `materials`.
    pub(super) named_bsdfs: HashMap<String, u32>,
    pub(super) materials: Vec<Material>,
    pub(super) shapes: Vec<crate::scene::Shape>,
    pub(super) emitters: Vec<crate::scene::Emitter>,
    pub(super) textures: Vec<crate::scene::SceneTexture>,
    /// `Scene::weight_tables`.
    pub(super) weight_tables: Vec<[f32; caustic_kernel::bsdf::textured_weights::SLOTS]>,
    /// Named area emitters (`id`) defined at the top level, for shapes that `<ref>` them.
    pub(super) named_area_emitters: HashMap<String, AreaEmission>,
    /// `shapegroup`s by id, as indices into `instancing.groups` (their triangles and disks, in the
    /// group's space) and `group_spheres` (their spheres), for `instance`s to place.
    pub(super) shape_groups: HashMap<String, usize>,
    pub(super) group_spheres: Vec<Vec<crate::scene::Shape>>,
    pub(super) instancing: crate::scene::instancing::Instancing,
    /// Named textures (`id`), as indices into `textures`.
    pub(super) named_textures: HashMap<String, u32>,
    /// Top-level samplers, films and rfilters with an `id`, kept as their file and their element's
    /// text (behind as many newlines as it stood below the file's start, so that messages name the
    /// right line) until a sensor or film `<ref>`s them: Mitsuba resolves such references across
    /// `<include>`d files (its own sampler scenes define the sampler in one file and ref it in another).
    pub(crate) named_sensor_parts: HashMap<String, (std::path::PathBuf, String)>,
    /// The scene's sensor: the first in document order, which Mitsuba renders by default.
    pub(super) sensor: Option<crate::scene::Sensor>,
    /// Where that sensor was given.
    pub(super) sensor_loc: Option<Loc>,
    /// The shape (index into `shapes`) carrying an irradiance meter, and where the meter was given.
    pub(super) meter_shape: Option<(usize, Loc)>,
    pub(super) integrator: Option<Integrator>,
    /// The `aov` or `depth` integrator's outputs (`crate::scene::aov`).
    pub(super) aovs: Option<crate::scene::aov::AovSpec>,
    pub(super) warnings: Vec<String>,
    /// What the scene asks for that the loaded scene does not do (reported or refused at the end).
    pub(super) deviations: Deviations,
    pub(super) include_depth: u32,
    /// Files `<include>`d so far, repeats counted: bounded (`MAX_INCLUDES`), since files that each
    /// include the next twice ask for 2^depth loads within the depth limit.
    pub(super) includes: u32,
    /// Every `id` given so far, in any file of the scene, with where: Mitsuba refuses a duplicate.
    pub(super) ids: HashMap<String, Loc>,
    /// Where the scene's integrator was given: Mitsuba refuses a second.
    pub(super) integrator_loc: Option<Loc>,
    /// `mesh_attribute` textures a parameter asked for (`mesh_attributes`).
    pub(super) attribute_requests: Vec<u32>,
}

/// An area emitter's radiance: uniform, or a texture over the surface's uv (`radiance` then holds
/// its mean); `directional` for Mitsuba's `directionalarea` (along the normal only).
#[derive(Clone, Copy, Debug)]
pub struct AreaEmission {
    pub radiance: [f32; 3],
    pub texture: Option<u32>,
    pub directional: bool,
}

/// A loader with nothing loaded yet; `defines` are `-D name=value` overrides.
pub(super) fn new_loader(defines: &[(String, String)]) -> Loader {
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

    pub(super) fn resolve_dir(&self, value: &str) -> PathBuf {
        let p = Path::new(value);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.search_paths.first().map(|d| d.join(p)).unwrap_or_else(|| p.to_path_buf())
        }
    }

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
}
