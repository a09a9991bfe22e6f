//! Stanford PLY (ASCII and binary of either byte order) through `ply-rs-bw`, read as Mitsuba's `ply`
//! plugin reads it: positions `x y z`, normals `nx ny nz` when all three are present, texture
//! coordinates from the first complete pair of `u v`, `texture_u texture_v` or `s t` (not flipped),
//! faces from a `vertex_indices` or `vertex_index` list. Other elements and properties are skipped.
use super::Mesh;
use anyhow::{anyhow, bail, Context, Result};
use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult};
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

/// Loads a PLY mesh; every failure names the file.
pub fn load_ply(path: &Path) -> Result<Mesh> {
    let file = File::open(path).with_context(|| format!("cannot open PLY mesh {}", path.display()))?;
    let mesh =
        read_ply(BufReader::new(file)).map_err(|e| anyhow!("{}: invalid PLY file: {e:#}", path.display()))?;
    mesh.validate(path)?;
    Ok(mesh)
}

/// Where each vertex property we read is kept in `PlyVertex::values`.
const VERTEX_SLOTS: [&str; 12] =
    ["x", "y", "z", "nx", "ny", "nz", "u", "v", "texture_u", "texture_v", "s", "t"];
const NORMAL_SLOT: usize = 3;
/// First slot of each texture coordinate naming, in Mitsuba's order of preference.
const UV_SLOTS: [usize; 3] = [6, 8, 10];

/// One vertex as read: the properties named in `VERTEX_SLOTS`, missing ones left at zero.
struct PlyVertex {
    values: [f32; VERTEX_SLOTS.len()],
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex { values: [0.0; VERTEX_SLOTS.len()] }
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(slot) = VERTEX_SLOTS.iter().position(|&s| s == name) else {
            return PropertyAccessResult::Ignored;
        };
        match scalar(&property) {
            Some(value) => {
                self.values[slot] = value as f32;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::UnsupportedType,
        }
    }
}

/// One face: its corner indices (a negative index becomes `NEGATIVE_INDEX`).
struct PlyFace {
    corners: Vec<u32>,
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace { corners: Vec::new() }
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if name != "vertex_indices" && name != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        match index_list(property) {
            Some(corners) => {
                self.corners = corners;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::UnsupportedType,
        }
    }
}

/// An element we do not use, parsed only to move past it.
struct Skipped;

impl PropertyAccess for Skipped {
    fn new() -> Self {
        Skipped
    }
}

fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// Stands for a negative vertex index, which no mesh can satisfy.
const NEGATIVE_INDEX: u32 = u32::MAX;

fn index_list(property: Property) -> Option<Vec<u32>> {
    fn to_u32<T: TryInto<u32>>(values: Vec<T>) -> Vec<u32> {
        values.into_iter().map(|v| v.try_into().unwrap_or(NEGATIVE_INDEX)).collect()
    }
    Some(match property {
        Property::ListChar(v) => to_u32(v),
        Property::ListUChar(v) => to_u32(v),
        Property::ListShort(v) => to_u32(v),
        Property::ListUShort(v) => to_u32(v),
        Property::ListInt(v) => to_u32(v),
        Property::ListUInt(v) => v,
        _ => return None,
    })
}

/// Which optional vertex attributes the header declares.
struct VertexLayout {
    has_normals: bool,
    /// First slot of the texture coordinate pair in use.
    uv_slot: Option<usize>,
}

impl VertexLayout {
    fn of(vertex: &ElementDef) -> Result<VertexLayout> {
        let has = |slot: usize| vertex.properties.contains_key(VERTEX_SLOTS[slot]);
        if !(has(0) && has(1) && has(2)) {
            bail!("the vertex element lacks one of the properties x, y, z");
        }
        Ok(VertexLayout {
            has_normals: (NORMAL_SLOT..NORMAL_SLOT + 3).all(has),
            uv_slot: UV_SLOTS.into_iter().find(|&slot| has(slot) && has(slot + 1)),
        })
    }
}

fn read_ply<R: BufRead>(input: R) -> Result<Mesh> {
    let mut reader = Reader::new(input);
    let header = Parser::<Skipped>::new().read_header(&mut reader)?;
    let Some(vertex_def) = header.elements.get("vertex") else { bail!("no 'vertex' element") };
    let layout = VertexLayout::of(vertex_def)?;
    let Some(face_def) = header.elements.get("face") else { bail!("no 'face' element") };
    if !face_def.properties.contains_key("vertex_indices")
        && !face_def.properties.contains_key("vertex_index")
    {
        bail!("the face element has neither a 'vertex_indices' nor a 'vertex_index' list");
    }
    // Elements follow in header order, each through the parser of its own element type.
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for (name, def) in &header.elements {
        match name.as_str() {
            "vertex" => {
                vertices = Parser::<PlyVertex>::new().read_payload_for_element(&mut reader, def, &header)?
            }
            "face" => faces = Parser::<PlyFace>::new().read_payload_for_element(&mut reader, def, &header)?,
            _ => {
                Parser::<Skipped>::new().read_payload_for_element(&mut reader, def, &header)?;
            }
        }
    }
    reject_trailing_data(reader.get_mut(), &header)?;
    if let Some(k) = faces.iter().position(|f| f.corners.contains(&NEGATIVE_INDEX)) {
        bail!("face {k} has a negative vertex index");
    }
    Ok(assemble(&vertices, &faces, &layout))
}

/// Data after the last element means the header's counts do not describe the file (Mitsuba
/// refuses such files too); trailing blank space in an ASCII file is harmless.
fn reject_trailing_data<R: BufRead>(rest: &mut R, header: &Header) -> Result<()> {
    let mut trailing = Vec::new();
    rest.read_to_end(&mut trailing)?;
    let harmless = header.encoding == Encoding::Ascii && trailing.iter().all(u8::is_ascii_whitespace);
    if !trailing.is_empty() && !harmless {
        bail!("{} bytes of data after the last element declared in the header", trailing.len());
    }
    Ok(())
}

/// Builds the mesh: polygons fan out from their first corner; faces of fewer than three corners
/// enclose no area and are skipped.
fn assemble(vertices: &[PlyVertex], faces: &[PlyFace], layout: &VertexLayout) -> Mesh {
    let attribute =
        |v: &PlyVertex, slot: usize| Vec3::new(v.values[slot], v.values[slot + 1], v.values[slot + 2]);
    let mut mesh = Mesh {
        positions: vertices.iter().map(|v| attribute(v, 0)).collect(),
        normals: layout
            .has_normals
            .then(|| vertices.iter().map(|v| attribute(v, NORMAL_SLOT).normalize_or_zero()).collect()),
        uvs: layout
            .uv_slot
            .map(|slot| vertices.iter().map(|v| Vec2::new(v.values[slot], v.values[slot + 1])).collect()),
        ..Default::default()
    };
    for face in faces.iter().filter(|f| f.corners.len() >= 3) {
        let first = face.corners[0];
        for pair in face.corners[1..].windows(2) {
            mesh.indices.extend([first, pair[0], pair[1]]);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_with_extra_properties_fans_into_two_triangles() {
        let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                    property uchar red\nproperty float s\nproperty float t\nelement face 1\nproperty uchar flags\n\
                    property list uchar int vertex_index\nend_header\n\
                    0 0 0 255 0 0\n1 0 0 255 1 0\n1 1 0 255 1 1\n0 1 0 255 0 1\n7 4 0 1 2 3\n";
        let mesh = read_ply(text.as_bytes()).unwrap();
        assert_eq!(mesh.indices, vec![0, 1, 2, 0, 2, 3]);
        assert!(mesh.normals.is_none());
        assert_eq!(mesh.uvs.unwrap()[2], Vec2::new(1.0, 1.0));
    }

    #[test]
    fn trailing_binary_data_is_an_error() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
                          property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
            .to_vec();
        bytes.extend([0u8; 12 + 3]);
        assert!(read_ply(bytes.as_slice()).unwrap_err().to_string().contains("after the last element"));
    }
}
