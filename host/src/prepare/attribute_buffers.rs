//! Mesh attributes in the table buffer, for `mesh_attribute` textures: each triangle of a shape that
//! keeps attributes gets a block of `MESH_ATTRIBUTE_FLOATS` floats per attribute name the scene's
//! textures read (its slot, `Texture::offset` of those textures), linear RGB at its three corners,
//! and `TriangleAttributes::mesh_attributes` points at it. Triangles of other shapes point nowhere
//! (`NONE`): a scene without `mesh_attribute` textures stores nothing.
use crate::scene::mesh::CornerAttribute;
use crate::scene::Scene;
use caustic_kernel::layout::{MESH_ATTRIBUTE_FLOATS, NONE, TEXTURE_MESH_ATTRIBUTE};

/// The blocks while primitives are packed: offsets are relative to `values` until `place` moves
/// them into the table buffer.
#[derive(Default)]
pub(crate) struct AttributeBlocks {
    /// The attribute names the textures read, in slot order.
    pub names: Vec<String>,
    pub values: Vec<f32>,
}

impl AttributeBlocks {
    pub fn of(scene: &Scene) -> AttributeBlocks {
        let mut names: Vec<String> = Vec::new();
        for t in &scene.textures {
            if let Some(a) = &t.mesh_attribute {
                if !names.contains(&a.name) {
                    names.push(a.name.clone());
                }
            }
        }
        AttributeBlocks { names, values: Vec::new() }
    }

    /// The slot of attribute `name` (a texture's `offset`).
    pub fn slot_offset(&self, name: &str) -> u32 {
        let slot = self.names.iter().position(|n| n == name).expect("every texture's name has a slot");
        slot as u32 * MESH_ATTRIBUTE_FLOATS
    }

    /// Stores triangle `i`'s block of a shape with `attributes` and returns where it starts in
    /// `values`; `NONE` when the shape keeps none. A one-channel attribute is stored as a grey.
    pub fn push_triangle(&mut self, attributes: &[CornerAttribute], i: usize) -> u32 {
        if attributes.is_empty() || self.names.is_empty() {
            return NONE;
        }
        let start = self.values.len() as u32;
        for name in &self.names {
            match attributes.iter().find(|a| &a.name == name) {
                Some(a) => {
                    for corner in a.corners[i] {
                        let rgb = if a.dim == 1 { [corner[0]; 3] } else { [corner[0], corner[1], corner[2]] };
                        self.values.extend(rgb);
                    }
                }
                // Another shape's attribute: never read here (the loader checks what each shape's
                // textures read).
                None => self.values.extend([0.0; MESH_ATTRIBUTE_FLOATS as usize]),
            }
        }
        start
    }

    /// Appends the blocks to `tables` and rebases the triangles' pointers onto them.
    pub fn place(self, tables: &mut Vec<f32>, attributes: &mut [caustic_kernel::layout::TriangleAttributes]) {
        if self.values.is_empty() {
            return;
        }
        let base = tables.len() as u32;
        tables.extend(self.values);
        for a in attributes.iter_mut().filter(|a| a.mesh_attributes != NONE) {
            a.mesh_attributes += base;
        }
    }
}

/// Whether the scene has `mesh_attribute` textures (`features::MESH_ATTRIBUTES`).
pub(crate) fn used(scene: &Scene) -> bool {
    scene.textures.iter().any(|t| t.record.kind == TEXTURE_MESH_ATTRIBUTE)
}
