//! Wavefront OBJ through `tobj`.
use crate::scene::mesh::Mesh;
use anyhow::{Context, Result};
use glam::{Vec2, Vec3};
use std::path::Path;

/// An OBJ file's MTL materials, or the warning saying why they did not load.
pub type Materials = std::result::Result<Vec<tobj::Material>, String>;

/// Loads every object of an OBJ file into one mesh; `with_materials` also reads the MTL library.
/// A library that does not load is not an error: the materials are then `Err` with the warning to
/// give (the caller has the warning list), and the mesh loads all the same.
///
/// Like Mitsuba's `obj` plugin, a vertex is one distinct (position, uv, normal) index triple, and
/// polygons fan out from their first corner. The v coordinate is flipped (Mitsuba's default
/// `flip_tex_coords = true`, which puts OBJ's bottom-left uv origin at an image's top-left);
/// `Mesh::flip_tex_coords` undoes it. One difference: tobj welds vertices within each object or
/// group only, so normals generated for a mesh without them do not blend across group borders.
pub fn load_obj(path: &Path, with_materials: bool) -> Result<(Mesh, Materials)> {
    let options =
        tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    // Both files are read through `files` (regular files only, recorded as inputs), and a material
    // library that does not load says which file and line are at fault.
    let text = crate::system::files::read(path, "OBJ mesh")?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let mtl_error = std::cell::RefCell::new(None::<String>);
    let load_mtl = |name: &Path| -> tobj::MTLLoadResult {
        let mtl = dir.join(name);
        let result = crate::system::files::read(&mtl, "material library").and_then(|bytes| {
            check_mtl_colours(&mtl, &bytes)?;
            tobj::load_mtl_buf(&mut &bytes[..]).map_err(|e| anyhow::anyhow!("{}: {e}", mtl.display()))
        });
        result.map_err(|e| {
            mtl_error.borrow_mut().get_or_insert(format!("{e:#}"));
            tobj::LoadError::MaterialParseError
        })
    };
    let loaded = tobj::load_obj_buf(&mut &text[..], &options, load_mtl);
    let (models, materials) = loaded.with_context(|| format!("cannot load OBJ mesh {}", path.display()))?;
    let materials = if with_materials {
        materials.map_err(|e| {
            let why = mtl_error.into_inner().unwrap_or_else(|| e.to_string());
            format!("{}: material library not loaded ({why}); using defaults", path.display())
        })
    } else {
        Ok(Vec::new())
    };
    let any_normals = models.iter().any(|m| has_one_per_vertex(&m.mesh.normals, 3, &m.mesh));
    let any_uvs = models.iter().any(|m| has_one_per_vertex(&m.mesh.texcoords, 2, &m.mesh));
    let mut mesh =
        Mesh { normals: any_normals.then(Vec::new), uvs: any_uvs.then(Vec::new), ..Default::default() };
    for model in &models {
        append_model(&mut mesh, &model.mesh);
    }
    if mesh.indices.is_empty() {
        anyhow::bail!("{}: the OBJ file has no faces", path.display());
    }
    mesh.validate(path)?;
    mesh.flip_tex_coords();
    Ok((mesh, materials))
}

/// Refuses an MTL colour (`Ka`, `Kd`, `Ks`, `Ke`) of fewer than three numbers, naming the file and
/// line: tobj 4 panics on one (an unwrap inside it, found by tests/tests/fuzz.rs).
fn check_mtl_colours(mtl: &Path, bytes: &[u8]) -> Result<()> {
    for (i, line) in String::from_utf8_lossy(bytes).lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next() {
            if words.count() < 3 {
                anyhow::bail!("{}:{}: '{key}' needs three numbers", mtl.display(), i + 1);
            }
        }
    }
    Ok(())
}

/// Whether `values` holds one `dim`-tuple per vertex of `m` (tobj leaves it short when only some
/// corners reference a normal or texture coordinate).
fn has_one_per_vertex(values: &[f32], dim: usize, m: &tobj::Mesh) -> bool {
    !values.is_empty() && values.len() / dim == m.positions.len() / 3
}

/// Appends one tobj model; attributes it lacks while others have them become zero (a zero normal
/// shades with the face normal).
fn append_model(mesh: &mut Mesh, m: &tobj::Mesh) {
    let base = mesh.positions.len() as u32;
    let vertex_count = m.positions.len() / 3;
    mesh.positions.extend(m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])));
    mesh.indices.extend(m.indices.iter().map(|&i| base + i));
    mesh.triangle_materials.extend(std::iter::repeat_n(m.material_id, m.indices.len() / 3));
    if let Some(normals) = &mut mesh.normals {
        if has_one_per_vertex(&m.normals, 3, m) {
            normals
                .extend(m.normals.chunks_exact(3).map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or_zero()));
        } else {
            normals.extend(std::iter::repeat_n(Vec3::ZERO, vertex_count));
        }
    }
    if let Some(uvs) = &mut mesh.uvs {
        if has_one_per_vertex(&m.texcoords, 2, m) {
            uvs.extend(m.texcoords.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])));
        } else {
            uvs.extend(std::iter::repeat_n(Vec2::ZERO, vertex_count));
        }
    }
}
