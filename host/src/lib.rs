//! caustic's host: scene loading (Mitsuba 3 XML, OBJ/MTL), BVH construction, the GPU (wgpu) and CPU
//! backends, render sessions, progressive rendering, image output, comparison and error-against-time
//! curves. No shading code lives here: all of it is in `caustic-kernel`.
pub mod backend;
pub mod buffers;
pub mod checkpoint;
pub mod compare;
pub mod convergence;
pub mod film;
pub mod image_io;
pub mod interrupt;
pub mod memory;
pub mod mesh;
pub mod mitsuba;
pub mod obj_scene;
pub mod render;
pub mod scene;
pub mod session;
pub mod tev;

use anyhow::Result;
use std::path::Path;

/// Loads a scene by its extension: `.xml` (Mitsuba 3) or `.obj` (with its MTL library).
pub fn load_scene(path: &Path, defines: &[(String, String)]) -> Result<scene::Scene> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("xml") => mitsuba::load(path, defines),
        Some("obj") => {
            let mut warnings = Vec::new();
            if !defines.is_empty() {
                scene::warn(&mut warnings, "-D definitions do not apply to OBJ files".to_string());
            }
            let mut scene = obj_scene::load(path)?;
            warnings.append(&mut scene.warnings);
            scene.warnings = warnings;
            Ok(scene)
        }
        _ => anyhow::bail!("{}: unknown scene format (expected .xml or .obj)", path.display()),
    }
}
