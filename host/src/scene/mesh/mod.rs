//! Triangle meshes in Mitsuba's vertex layout: each vertex carries a position and, optionally, a
//! shading normal and a texture coordinate. The loaders for the file formats, and the tessellation
//! of Mitsuba's built-in shapes, are in `load::mesh`.
use anyhow::{bail, Result};
use glam::{Mat3, Mat4, Vec2, Vec3};
use std::path::Path;

mod attributes;

pub use attributes::{Attribute, CornerAttribute};

/// The largest texture coordinate a mesh may carry: past 2^24 an f32 has no fractional part left to
/// address a texel with, and near f32's limit the lookup's arithmetic overflows.
pub const MAX_TEXTURE_COORDINATE: f32 = 16_777_216.0;

/// An indexed triangle mesh. `normals` and `uvs`, when present, run parallel to `positions`, so a
/// vertex whose corners disagree on a normal or uv is stored once per distinct value (Mitsuba
/// welds OBJ corners the same way).
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Vertex indices, three per triangle.
    pub indices: Vec<u32>,
    /// Per-vertex shading normals (unit length, or zero where unknown).
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates in Mitsuba's convention (v = 0 is the top row of an image).
    pub uvs: Option<Vec<Vec2>>,
    /// MTL material of each triangle (index into the loader's materials); empty when not loaded.
    pub triangle_materials: Vec<Option<usize>>,
    /// Named per-vertex and per-face attributes (`vertex_color`, `face_<name>`...; PLY files only).
    pub attributes: Vec<Attribute>,
}

/// A mesh flattened into independent triangles, ready for `scene::Geometry::Triangles`. All three
/// vectors are parallel: triangle `i` has corner normals `normals[i]` and corner uvs `uvs[i]`.
#[derive(Clone, Debug, Default)]
pub struct Triangles {
    pub triangles: Vec<[Vec3; 3]>,
    pub normals: Option<Vec<[Vec3; 3]>>,
    pub uvs: Option<Vec<[Vec2; 3]>>,
    /// The mesh's attributes at each triangle's corners (empty for most meshes).
    pub attributes: Vec<CornerAttribute>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Checks what a loader must guarantee before anyone indexes the mesh: whole triangles, indices
    /// within the vertex list, attribute lists as long as the position list.
    pub fn validate(&self, path: &Path) -> Result<()> {
        if !self.indices.len().is_multiple_of(3) {
            bail!("{}: {} indices do not make whole triangles", path.display(), self.indices.len());
        }
        let vertex_count = self.positions.len();
        if let Some((k, &i)) = self.indices.iter().enumerate().find(|(_, &i)| i as usize >= vertex_count) {
            bail!(
                "{}: triangle {} references vertex {i}, but the mesh has {vertex_count} vertices",
                path.display(),
                k / 3
            );
        }
        if self.normals.as_ref().is_some_and(|n| n.len() != vertex_count) {
            bail!("{}: the normal list does not match the {vertex_count} vertices", path.display());
        }
        if self.uvs.as_ref().is_some_and(|uv| uv.len() != vertex_count) {
            bail!(
                "{}: the texture coordinate list does not match the {vertex_count} vertices",
                path.display()
            );
        }
        for a in &self.attributes {
            let count = if a.per_face() { self.triangle_count() } else { vertex_count };
            if a.values.len() != count * a.dim {
                bail!(
                    "{}: attribute '{}' does not have {} values of {} channels",
                    path.display(),
                    a.name,
                    count,
                    a.dim
                );
            }
            if let Some(v) = a.values.iter().find(|v| !v.is_finite()) {
                bail!("{}: attribute '{}' has a non-finite value {v}", path.display(), a.name);
            }
        }
        if let Some(p) = self.positions.iter().find(|p| !p.is_finite()) {
            bail!("{}: the mesh has a non-finite vertex position {p}", path.display());
        }
        // Every attribute that reaches the kernel, as the positions: a NaN or infinite normal or uv
        // made texture lookups give non-finite samples, counted as black without a word.
        if let Some((v, n)) = self.normals.iter().flatten().enumerate().find(|(_, n)| !n.is_finite()) {
            bail!("{}: vertex {v} has a non-finite normal {n}", path.display());
        }
        let addressable = |uv: &Vec2| uv.is_finite() && uv.abs().max_element() <= MAX_TEXTURE_COORDINATE;
        if let Some((v, uv)) = self.uvs.iter().flatten().enumerate().find(|(_, uv)| !addressable(uv)) {
            bail!(
                "{}: vertex {v} has texture coordinates {uv}: they must be finite and within \
                 ±{MAX_TEXTURE_COORDINATE}",
                path.display()
            );
        }
        Ok(())
    }

    /// Applies `to_world` to positions and (through the inverse transpose) to normals.
    pub fn transform(&mut self, to_world: Mat4) {
        if to_world == Mat4::IDENTITY {
            return;
        }
        for p in &mut self.positions {
            *p = to_world.transform_point3(*p);
        }
        if let Some(normals) = &mut self.normals {
            let normal_matrix = Mat3::from_mat4(to_world).inverse().transpose();
            for n in normals {
                *n = (normal_matrix * *n).normalize_or_zero();
            }
        }
    }

    /// Mirrors the v texture coordinate (Mitsuba's `flip_tex_coords`).
    pub fn flip_tex_coords(&mut self) {
        for uv in self.uvs.iter_mut().flatten() {
            uv.y = 1.0 - uv.y;
        }
    }

    /// Swaps two corners of every triangle, turning its geometric normal around.
    pub fn reverse_winding(&mut self) {
        for tri in self.indices.chunks_exact_mut(3) {
            tri.swap(1, 2);
        }
    }

    /// Smooth normals where the file has none: each vertex averages the normals of its faces,
    /// weighted by the face's angle at the vertex (Thürmer & Wüthrich 1998), as Mitsuba does.
    /// Mitsuba computes them after `to_world`, so callers transform first.
    pub fn ensure_normals(&mut self) {
        if self.normals.is_some() {
            return;
        }
        let mut sums = vec![Vec3::ZERO; self.positions.len()];
        for tri in self.indices.chunks_exact(3) {
            let p = [0, 1, 2].map(|k| self.positions[tri[k] as usize]);
            let n = face_normal(p).unwrap_or(Vec3::ZERO);
            for k in 0..3 {
                let e1 = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
                let e2 = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
                sums[tri[k] as usize] += n * e1.dot(e2).clamp(-1.0, 1.0).acos();
            }
        }
        // A zero sum (faces cancelling out) stays zero; `triangles` then falls back to the face normal.
        self.normals = Some(sums.into_iter().map(Vec3::normalize_or_zero).collect());
    }

    /// The triangles with their corner attributes, as they are (no transform). Degenerate
    /// (zero-area or non-finite) triangles are dropped together with their attributes.
    pub fn triangles(&self) -> Triangles {
        let mut out = Triangles {
            triangles: Vec::with_capacity(self.triangle_count()),
            normals: self.normals.as_ref().map(|_| Vec::with_capacity(self.triangle_count())),
            uvs: self.uvs.as_ref().map(|_| Vec::with_capacity(self.triangle_count())),
            attributes: self
                .attributes
                .iter()
                .map(|a| CornerAttribute { name: a.name.clone(), dim: a.dim, corners: Vec::new() })
                .collect(),
        };
        for (k, tri) in self.indices.chunks_exact(3).enumerate() {
            let corner = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
            let p = corner.map(|i| self.positions[i]);
            let Some(face_normal) = face_normal(p) else { continue };
            out.triangles.push(p);
            if let (Some(out), Some(normals)) = (out.normals.as_mut(), self.normals.as_ref()) {
                // A corner without a usable normal (zero in the file, or a cancelled sum) takes the
                // face's own, so that shading never sees a zero or NaN normal.
                out.push(corner.map(|i| {
                    if normals[i].is_finite() && normals[i] != Vec3::ZERO {
                        normals[i]
                    } else {
                        face_normal
                    }
                }));
            }
            if let (Some(out), Some(uvs)) = (out.uvs.as_mut(), self.uvs.as_ref()) {
                out.push(corner.map(|i| uvs[i]));
            }
            for (out, a) in out.attributes.iter_mut().zip(&self.attributes) {
                out.corners.push(if a.per_face() { [a.value(k); 3] } else { corner.map(|i| a.value(i)) });
            }
        }
        out
    }

    /// World-space triangles under `to_world` (see `transform` and `triangles`).
    pub fn transformed(&self, to_world: Mat4) -> Triangles {
        let mut world = self.clone();
        world.transform(to_world);
        world.triangles()
    }
}

/// The unit face normal of the triangle `p`, or None if the triangle is degenerate: zero area, or
/// not finite. `Mesh::triangles` drops those, and `obj_scene` indexes the kept triangles by the same
/// test, so both call this one. Computed in f64: the squared length of an f32 cross product
/// overflows for edges over about 1e9.5 (a rectangle scaled by 1e10 was dropped as degenerate).
pub fn face_normal(p: [Vec3; 3]) -> Option<Vec3> {
    let n = cross64(p);
    let area2 = n.length_squared();
    (area2 > 0.0 && area2.is_finite()).then(|| (n / area2.sqrt()).as_vec3())
}

/// The triangle's area, computed in f64 (see `face_normal`).
pub fn triangle_area(p: [Vec3; 3]) -> f64 {
    0.5 * cross64(p).length()
}

fn cross64(p: [Vec3; 3]) -> glam::DVec3 {
    let [a, b, c] = p.map(|v| v.as_dvec3());
    (b - a).cross(c - a)
}
