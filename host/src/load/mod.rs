//! Scene files into a `scene::Scene`: Mitsuba 3 XML (`mitsuba`), OBJ with its MTL library
//! (`obj_scene`), the mesh files they name (`mesh`) and texture images (`image_io`); how a file is
//! read (`options`).
//!
//! Uses `scene` and `system`.
pub mod image_io;
pub mod mesh;
pub mod mitsuba;
pub mod obj_scene;
pub mod options;

pub use options::LoadOptions;

use crate::scene::{self, precision};
use anyhow::Result;
use std::path::Path;

/// Loads a scene by its extension: `.xml` (Mitsuba 3) or `.obj` (with its MTL library).
pub fn load_scene(path: &Path, defines: &[(String, String)]) -> Result<scene::Scene> {
    load_scene_with(path, defines, LoadOptions::default())
}

/// As `load_scene`, with options (`--strict`).
pub fn load_scene_with(
    path: &Path,
    defines: &[(String, String)],
    options: LoadOptions,
) -> Result<scene::Scene> {
    let scene = load_scene_unchecked(path, defines, options)?;
    Ok(precision_checked(scene, path))
}

/// As `load_scene_with`, for a Mitsuba 3 scene given as XML text rather than a file (the Python
/// module's `load_dict` writes one): `name` stands for the file in messages, and relative file
/// names resolve against `dir`.
pub fn load_scene_from_text(
    name: &Path,
    text: &str,
    dir: &Path,
    defines: &[(String, String)],
    options: LoadOptions,
) -> Result<scene::Scene> {
    let scene = mitsuba::load_text_with(name, text, dir, defines, options)?;
    Ok(precision_checked(scene, name))
}

/// `scene` (loaded from `path`), warned about where f32 precision ends for it (`precision`).
fn precision_checked(mut scene: scene::Scene, path: &Path) -> scene::Scene {
    if let Some(message) = precision::warning(&scene) {
        scene::warn(&mut scene.warnings, format!("{}: {message}", path.display()));
    }
    scene
}

/// `load_scene_with` without the precision check (`precision`).
fn load_scene_unchecked(
    path: &Path,
    defines: &[(String, String)],
    options: LoadOptions,
) -> Result<scene::Scene> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("xml") => mitsuba::load_with(path, defines, options),
        Some("obj") => {
            let mut warnings = Vec::new();
            if !defines.is_empty() {
                scene::warn(&mut warnings, "-D definitions do not apply to OBJ files".to_string());
            }
            let mut scene = obj_scene::load(path, options.strict)?;
            warnings.append(&mut scene.warnings);
            scene.warnings = warnings;
            Ok(scene)
        }
        _ => anyhow::bail!("{}: unknown scene format (expected .xml or .obj)", path.display()),
    }
}
