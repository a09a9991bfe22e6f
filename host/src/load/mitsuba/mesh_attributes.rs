//! Where `mesh_attribute` textures may be read, and the check that each shape has what its textures
//! read. The kernel looks them up on BSDF colours (`reflectance`, `specular_reflectance`,
//! `base_color`: Mitsuba's `eval`, a one-channel attribute a grey), and on roughness, principled
//! weights and blend weights (Mitsuba's `eval_1`, which in 3.9.1's scalar variants throws for an
//! attribute of other than one channel: refused here). A shape keeps only the attributes its
//! textures read. Elsewhere (masks, normal and bump maps, emitters, a mean standing in for a texture)
//! they are refused with the texture's file and line.
use super::loader::Loader;
use super::props::Props;
use crate::scene::Geometry;
use anyhow::{bail, Result};
use caustic_kernel::layout::{
    Material, BSDF_BLEND, BSDF_PRINCIPLED, BSDF_PRINCIPLED_THIN, NONE, TEXTURE_MESH_ATTRIBUTE,
};

impl Loader {
    fn is_mesh_attribute(&self, texture: u32) -> bool {
        texture != NONE && self.textures[texture as usize].record.kind == TEXTURE_MESH_ATTRIBUTE
    }

    /// Records that a BSDF or emitter parameter asked for texture `texture` (`color_param`,
    /// `scalar_texture`): a mesh attribute asked for must end up where the kernel reads it.
    pub(crate) fn note_texture_request(&mut self, texture: u32) {
        if self.is_mesh_attribute(texture) {
            self.attribute_requests.push(texture);
        }
    }

    /// The mesh attribute textures material `m` has the kernel read, each with whether it is read
    /// as one number (`eval_1`).
    fn attribute_reads(&self, m: u32) -> Vec<(u32, bool)> {
        let record = &self.materials[m as usize];
        // A blend tree's nodes (their weights) and leaves.
        let mut records = vec![record];
        let mut k = 0;
        while k < records.len() {
            if records[k].kind == BSDF_BLEND {
                let (a, b) = caustic_kernel::bsdf::blend::children(records[k]);
                records.extend([&self.materials[a as usize], &self.materials[b as usize]]);
            }
            k += 1;
        }
        let mut reads = Vec::new();
        for r in records {
            reads.extend(self.fields(r));
        }
        reads.retain(|&(t, _)| self.is_mesh_attribute(t));
        reads
    }

    /// Checks that a shape with material `material` has every attribute its textures read, with a
    /// channel count Mitsuba accepts there, and drops the attributes nothing reads.
    pub(crate) fn keep_read_attributes(
        &self,
        props: &Props,
        geometry: &mut Geometry,
        material: u32,
    ) -> Result<()> {
        let reads = self.attribute_reads(material);
        let empty = Vec::new();
        let attributes = match &*geometry {
            Geometry::Triangles { attributes, .. } => attributes,
            _ => &empty,
        };
        for &(texture, scalar) in &reads {
            let a =
                self.textures[texture as usize].mesh_attribute.as_ref().expect("a mesh_attribute texture");
            let Some(found) = attributes.iter().find(|c| c.name == a.name) else {
                let have: Vec<&str> = attributes.iter().map(|c| c.name.as_str()).collect();
                let have = if have.is_empty() { "none".to_string() } else { have.join(", ") };
                bail!(
                    "{}: mesh_attribute '{}': the shape at {} has no such attribute (it has: {have})",
                    a.origin,
                    a.name,
                    props.loc
                );
            };
            if scalar && found.dim != 1 {
                bail!(
                    "{}: mesh_attribute '{}' has {} channels where one number is read (Mitsuba 3.9.1's eval_1 refuses it too)",
                    a.origin,
                    a.name,
                    found.dim
                );
            }
            if !scalar && found.dim != 1 && found.dim != 3 {
                bail!(
                    "{}: mesh_attribute '{}' has {} channels; a colour reads 1 or 3 (Mitsuba 3.9.1 refuses it too)",
                    a.origin,
                    a.name,
                    found.dim
                );
            }
        }
        if let Geometry::Triangles { attributes, .. } = geometry {
            let read: Vec<&str> = reads
                .iter()
                .filter_map(|&(t, _)| self.textures[t as usize].mesh_attribute.as_ref())
                .map(|a| a.name.as_str())
                .collect();
            attributes.retain(|c| read.contains(&c.name.as_str()));
        }
        Ok(())
    }

    /// At the end of loading: every mesh attribute a parameter asked for is read by the kernel (not
    /// replaced by a mean), and none sits on a mask, a normal or bump map.
    pub(crate) fn check_attribute_uses(&self) -> Result<()> {
        let read: Vec<u32> =
            (0..self.materials.len() as u32).flat_map(|m| self.attribute_reads(m)).map(|r| r.0).collect();
        let elsewhere = self.materials.iter().flat_map(|m| [m.opacity_texture, m.perturb_texture]);
        let refused = self.attribute_requests.iter().copied().filter(|t| !read.contains(t)).chain(elsewhere);
        if let Some(t) = refused.into_iter().find(|&t| self.is_mesh_attribute(t)) {
            let a = self.textures[t as usize].mesh_attribute.as_ref().expect("a mesh_attribute texture");
            bail!(
                "{}: mesh_attribute '{}' is read on BSDF colours, roughness, principled weights and blend weights only (not by masks, normal or bump maps, emitters, or parameters caustic replaces by a mean)",
                a.origin,
                a.name
            );
        }
        Ok(())
    }
}

impl Loader {
    /// The textures of one record the kernel reads (`caustic_kernel::bsdf::Component::new` and the
    /// blend weight), each with whether it is read as one number.
    fn fields(&self, m: &Material) -> Vec<(u32, bool)> {
        if m.kind == BSDF_BLEND {
            // The weight; `specular_texture` holds a child's index there.
            return vec![(m.reflectance_texture, true)];
        }
        let mut fields = vec![
            (m.reflectance_texture, false),
            // The principled model's metallic weight.
            (m.specular_texture, m.kind == BSDF_PRINCIPLED),
            (m.alpha_u_texture, true),
            (m.alpha_v_texture, true),
        ];
        // The principled models' other textured weights (`textured_weights`).
        if matches!(m.kind, BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN) && m.table != NONE {
            let slots = self.weight_tables[m.table as usize].iter().filter(|&&t| t >= 0.0);
            fields.extend(slots.map(|&t| (t as u32, true)));
        }
        fields
    }
}
