//! Named mesh attributes (Mitsuba's `vertex_<name>` and `face_<name>`, e.g. `vertex_color`): the
//! values a mesh file gives per vertex or per face, kept beside the mesh's positions, and the same
//! values spread over the corners of each kept triangle, which is what the renderer interpolates
//! (`mesh_attribute` textures). Only PLY files carry them (`ply_attributes` names them).

/// One attribute of a `Mesh`: `dim` floats per vertex (`vertex_` names) or per triangle (`face_`
/// names; a polygon's value is repeated on each triangle of its fan).
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    pub name: String,
    /// Channels: 1, 3, or 4 (a colour with alpha).
    pub dim: usize,
    /// `dim` values per vertex or per triangle, in order.
    pub values: Vec<f32>,
}

impl Attribute {
    pub fn per_face(&self) -> bool {
        self.name.starts_with("face_")
    }

    /// The attribute's value at vertex or triangle `i`, zero-padded to four channels.
    pub fn value(&self, i: usize) -> [f32; 4] {
        let mut v = [0.0; 4];
        v[..self.dim].copy_from_slice(&self.values[i * self.dim..(i + 1) * self.dim]);
        v
    }
}

/// An attribute at the three corners of every triangle of a `Triangles` list (parallel to it): a
/// face attribute has the same value at all three.
#[derive(Clone, Debug, PartialEq)]
pub struct CornerAttribute {
    pub name: String,
    pub dim: usize,
    pub corners: Vec<[[f32; 4]; 3]>,
}

impl CornerAttribute {
    /// The mean over the triangles' corners (each triangle weighted equally), padded channels zero.
    pub fn mean(&self) -> [f32; 4] {
        let n = (3 * self.corners.len()).max(1) as f64;
        [0, 1, 2, 3].map(|c| (self.corners.iter().flatten().map(|v| v[c] as f64).sum::<f64>() / n) as f32)
    }
}
