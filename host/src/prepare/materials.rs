//! Materials and textures in the table buffer: each texture's texels (or its mesh attribute's
//! slot), each material's precomputed or weight table, and the wavelengths dispersive materials draw.
use super::attribute_buffers::AttributeBlocks;
use crate::scene::Scene;
use caustic_kernel::layout::*;

/// A bitmap texture's texels (RGB) where `place_textures` put them in the table buffer.
pub(super) fn texels<'a>(t: &Texture, tables: &'a [f32]) -> &'a [f32] {
    &tables[t.offset as usize..(t.offset + 3 * t.width * t.height) as usize]
}

/// Places each texture's texels in the table buffer.
pub(super) fn place_textures(scene: &Scene, tables: &mut Vec<f32>, blocks: &AttributeBlocks) -> Vec<Texture> {
    scene
        .textures
        .iter()
        .map(|t| {
            let mut record = t.record;
            record.offset = match &t.mesh_attribute {
                Some(a) => blocks.slot_offset(&a.name),
                None => tables.len() as u32,
            };
            tables.extend_from_slice(&t.texels);
            record
        })
        .collect()
}

/// The scene's materials, each table it needs placed in the table buffer: what the kernel
/// precomputes for the model (`caustic_kernel::bsdf::precompute`), or a principled material's
/// weight table, until now an index into the scene's list.
pub(super) fn place_materials(scene: &Scene, tables: &mut Vec<f32>) -> Vec<Material> {
    let mut materials = scene.materials.clone();
    for m in &mut materials {
        if let Some(table) = caustic_kernel::bsdf::precompute(m) {
            m.table = tables.len() as u32;
            tables.extend(table);
        } else if matches!(m.kind, BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN) && m.table != NONE {
            // From its index into the scene's list to its place in the table buffer.
            let weights = scene.weight_tables[m.table as usize];
            m.table = tables.len() as u32;
            tables.extend(weights);
        }
    }
    materials
}

/// Dispersive materials: the wavelengths their paths draw (`caustic_kernel::wavelength`), placed in
/// the table buffer; its offset there (0 without dispersion).
pub(super) fn place_wavelengths(materials: &[Material], tables: &mut Vec<f32>) -> u32 {
    let mut wavelength_table = 0;
    if materials.iter().any(caustic_kernel::wavelength::disperses) {
        use crate::load::mitsuba::spectrum::{cie_xyz_table, XYZ_TO_SRGB};
        wavelength_table = tables.len() as u32;
        tables.extend(caustic_kernel::wavelength::build_table(&cie_xyz_table(), XYZ_TO_SRGB));
    }
    wavelength_table
}
