//! Triangle meshes from files (OBJ through `tobj`), with Mitsuba's normal conventions.
use anyhow::{bail, Context, Result};
use glam::{Mat4, Vec3};
use std::path::Path;

/// A triangle mesh in object space: positions indexed per corner, plus optional per-corner normals.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Corner position indices, three per triangle.
    pub indices: Vec<u32>,
    /// Per-corner normals (three per triangle) when the file provides them.
    pub corner_normals: Option<Vec<Vec3>>,
    /// MTL material of each triangle (index into `materials`), when loaded with materials.
    pub triangle_materials: Vec<Option<usize>>,
}

/// Loads every object of an OBJ file into one mesh. `with_materials` also reads the MTL library.
pub fn load_obj(path: &Path, with_materials: bool) -> Result<(Mesh, Vec<tobj::Material>)> {
    let options = tobj::LoadOptions { triangulate: true, single_index: false, ignore_points: true, ignore_lines: true };
    let (models, materials) = tobj::load_obj(path, &options).with_context(|| format!("cannot load OBJ mesh {}", path.display()))?;
    let materials = if with_materials {
        materials.unwrap_or_else(|e| {
            eprintln!("warning: {}: material library not loaded ({e}); using defaults", path.display());
            Vec::new()
        })
    } else {
        Vec::new()
    };
    let mut mesh = Mesh::default();
    let mut normals = Vec::new();
    let mut all_have_normals = true;
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])));
        for &i in &m.indices {
            if i as usize >= m.positions.len() / 3 {
                bail!("{}: object '{}' references vertex {} of {}", path.display(), model.name, i + 1, m.positions.len() / 3);
            }
            mesh.indices.push(base + i);
        }
        let tri_count = m.indices.len() / 3;
        mesh.triangle_materials.extend(std::iter::repeat(m.material_id).take(tri_count));
        if m.normal_indices.len() == m.indices.len() && !m.normals.is_empty() {
            for &ni in &m.normal_indices {
                let k = ni as usize * 3;
                if k + 2 >= m.normals.len() {
                    bail!("{}: object '{}' references a missing normal", path.display(), model.name);
                }
                normals.push(Vec3::new(m.normals[k], m.normals[k + 1], m.normals[k + 2]));
            }
        } else {
            all_have_normals = false;
        }
    }
    if mesh.indices.is_empty() {
        bail!("{}: the mesh has no triangles", path.display());
    }
    if all_have_normals {
        mesh.corner_normals = Some(normals);
    }
    Ok((mesh, materials))
}

impl Mesh {
    /// Smooth normals where the file has none, weighting each face by its angle at the vertex
    /// (Thürmer & Wüthrich), as Mitsuba does.
    pub fn ensure_normals(&mut self) {
        if self.corner_normals.is_some() {
            return;
        }
        let mut vertex_normals = vec![Vec3::ZERO; self.positions.len()];
        for tri in self.indices.chunks_exact(3) {
            let p = [0, 1, 2].map(|k| self.positions[tri[k] as usize]);
            let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
            for k in 0..3 {
                let e1 = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
                let e2 = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
                let angle = e1.dot(e2).clamp(-1.0, 1.0).acos();
                vertex_normals[tri[k] as usize] += n * angle;
            }
        }
        let corner: Vec<Vec3> = self.indices.iter().map(|&i| vertex_normals[i as usize].normalize_or_zero()).collect();
        self.corner_normals = Some(corner);
    }

    /// World-space triangles and corner normals under `to_world` (normals by the inverse transpose).
    /// Degenerate (zero-area or non-finite) triangles are dropped.
    pub fn transformed(&self, to_world: Mat4) -> (Vec<[Vec3; 3]>, Option<Vec<[Vec3; 3]>>) {
        let normal_matrix = to_world.inverse().transpose();
        let mut triangles = Vec::with_capacity(self.indices.len() / 3);
        let mut normals = self.corner_normals.as_ref().map(|_| Vec::with_capacity(self.indices.len() / 3));
        for (t, tri) in self.indices.chunks_exact(3).enumerate() {
            let p = [0, 1, 2].map(|k| to_world.transform_point3(self.positions[tri[k] as usize]));
            let area2 = (p[1] - p[0]).cross(p[2] - p[0]).length_squared();
            if !(area2 > 0.0 && area2.is_finite()) {
                continue;
            }
            triangles.push(p);
            if let (Some(out), Some(cn)) = (normals.as_mut(), self.corner_normals.as_ref()) {
                out.push([0, 1, 2].map(|k| normal_matrix.transform_vector3(cn[3 * t + k]).normalize_or_zero()));
            }
        }
        (triangles, normals)
    }
}
