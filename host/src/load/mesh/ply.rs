//! Stanford PLY (ASCII and binary of either byte order) through `ply-rs-bw`, read as Mitsuba's `ply`
//! plugin reads it: positions `x y z`, normals `nx ny nz` when all three are present, texture
//! coordinates from the first complete pair of `u v`, `texture_u texture_v` or `s t` (not flipped),
//! faces from a `vertex_indices` or `vertex_index` list; other properties of vertices and faces
//! become named attributes as Mitsuba names them (`ply_attributes`). Other elements are skipped.
use super::ply_attributes::{self, Field, Group};
use crate::scene::mesh::{Attribute, Mesh};
use anyhow::{anyhow, bail, Result};
use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};
use std::io::{BufRead, BufReader};
use std::path::Path;

/// Loads a PLY mesh and the warnings its attributes raised; every failure and warning names the file.
pub fn load_ply(path: &Path) -> Result<(Mesh, Vec<String>)> {
    let file = crate::system::files::open(path, "PLY mesh")?;
    let mut warnings = Vec::new();
    let mesh = read_ply(BufReader::new(file), &mut warnings)
        .map_err(|e| anyhow!("{}: invalid PLY file: {e:#}", path.display()))?;
    mesh.validate(path)?;
    Ok((mesh, warnings.into_iter().map(|w| format!("{}: {w}", path.display())).collect()))
}

/// Where each vertex property we read is kept in `PlyVertex::values`.
const VERTEX_SLOTS: [&str; 12] =
    ["x", "y", "z", "nx", "ny", "nz", "u", "v", "texture_u", "texture_v", "s", "t"];
const NORMAL_SLOT: usize = 3;
/// First slot of each texture coordinate naming, in Mitsuba's order of preference.
const UV_SLOTS: [usize; 3] = [6, 8, 10];

/// One vertex as read: the properties named in `VERTEX_SLOTS`, missing ones left at zero, and the
/// others in header order (lists as NaN: they are never attributes).
struct PlyVertex {
    values: [f32; VERTEX_SLOTS.len()],
    extras: Vec<f32>,
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex { values: [0.0; VERTEX_SLOTS.len()], extras: Vec::new() }
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(slot) = VERTEX_SLOTS.iter().position(|&s| s == name) else {
            self.extras.push(scalar(&property).map_or(f32::NAN, |v| v as f32));
            return PropertyAccessResult::Set;
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

/// One face: its corner indices (a negative index becomes `NEGATIVE_INDEX`) and its other
/// properties in header order (as `PlyVertex::extras`).
struct PlyFace {
    corners: Vec<u32>,
    extras: Vec<f32>,
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace { corners: Vec::new(), extras: Vec::new() }
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if !FACE_INDICES.contains(&name) {
            self.extras.push(scalar(&property).map_or(f32::NAN, |v| v as f32));
            return PropertyAccessResult::Set;
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

const FACE_INDICES: [&str; 2] = ["vertex_indices", "vertex_index"];

/// The properties of `def` other than `known`, in header order (what `extras` holds).
fn extra_fields(def: &ElementDef, known: &[&str]) -> Vec<Field> {
    let integer = |t: &ScalarType| !matches!(t, ScalarType::Float | ScalarType::Double);
    def.properties
        .values()
        .filter(|p| !known.contains(&p.name.as_str()))
        .map(|p| match &p.data_type {
            PropertyType::Scalar(t) => Field { name: p.name.clone(), integer: integer(t), list: false },
            PropertyType::List(_, t) => Field { name: p.name.clone(), integer: integer(t), list: true },
        })
        .collect()
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

fn read_ply<R: BufRead>(input: R, warnings: &mut Vec<String>) -> Result<Mesh> {
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
    let vertex_fields = extra_fields(vertex_def, &VERTEX_SLOTS);
    let face_fields = extra_fields(face_def, &FACE_INDICES);
    let vertex_groups = ply_attributes::groups("vertex_", &vertex_fields, warnings)?;
    let face_groups = ply_attributes::groups("face_", &face_fields, warnings)?;
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
    let mut mesh = assemble(&vertices, &faces, &layout);
    let extras = |e: &[f32], expected: usize| e.len() == expected;
    if !vertices.iter().all(|v| extras(&v.extras, vertex_fields.len()))
        || !faces.iter().all(|f| extras(&f.extras, face_fields.len()))
    {
        bail!("an element's properties were not all read");
    }
    for g in vertex_groups {
        mesh.attributes.push(attribute(g, vertices.iter().map(|v| v.extras.as_slice())));
    }
    // A polygon's value goes to each triangle of its fan (as many as `assemble` made).
    let fanned = faces
        .iter()
        .filter(|f| f.corners.len() >= 3)
        .flat_map(|f| std::iter::repeat_n(f.extras.as_slice(), f.corners.len() - 2));
    for g in face_groups {
        mesh.attributes.push(attribute(g, fanned.clone()));
    }
    Ok(mesh)
}

/// The values of attribute `group` from each record's `extras`.
fn attribute<'a>(group: Group, records: impl Iterator<Item = &'a [f32]>) -> Attribute {
    let values = records.flat_map(|e| group.fields.iter().map(move |&i| e[i])).collect();
    Attribute { name: group.name, dim: group.fields.len(), values }
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
        let mesh = read_ply(text.as_bytes(), &mut Vec::new()).unwrap();
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
        assert!(read_ply(bytes.as_slice(), &mut Vec::new())
            .unwrap_err()
            .to_string()
            .contains("after the last element"));
    }

    fn attribute<'a>(mesh: &'a Mesh, name: &str) -> &'a Attribute {
        mesh.attributes.iter().find(|a| a.name == name).unwrap_or_else(|| panic!("no {name}"))
    }

    #[test]
    fn uchar_colours_are_read_as_numbers_and_float_ones_as_they_are() {
        // Mitsuba 3.9.1 reads uchar 255 as 255.0 (its `attribute_buffer`), and warns.
        let header = |ty: &str| {
            format!(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                 property {ty} red\nproperty {ty} green\nproperty {ty} blue\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n"
            )
        };
        let mut warnings = Vec::new();
        let text = header("uchar") + "0 0 0 255 128 0\n1 0 0 0 255 64\n0 1 0 10 20 30\n3 0 1 2\n";
        let mesh = read_ply(text.as_bytes(), &mut warnings).unwrap();
        let color = attribute(&mesh, "vertex_color");
        assert_eq!(
            (color.dim, color.values.as_slice()),
            (3, &[255.0, 128.0, 0.0, 0.0, 255.0, 64.0, 10.0, 20.0, 30.0][..])
        );
        assert!(warnings.iter().any(|w| w.contains("integer")), "{warnings:?}");
        let mut warnings = Vec::new();
        let text = header("float") + "0 0 0 1 0.5 0\n1 0 0 0 1 0.25\n0 1 0 0.1 0.2 0.3\n3 0 1 2\n";
        let mesh = read_ply(text.as_bytes(), &mut warnings).unwrap();
        assert_eq!(attribute(&mesh, "vertex_color").values[..3], [1.0, 0.5, 0.0]);
        assert!(warnings.is_empty(), "{warnings:?}");
    }

    #[test]
    fn alpha_makes_four_channels_and_face_attributes_follow_the_fan() {
        let text =
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                    property float r\nproperty float g\nproperty float b\nproperty float a\nelement face 2\n\
                    property list uchar int vertex_indices\nproperty float wear_x\nproperty float tint_r\n\
                    property float tint_g\nproperty float tint_b\nend_header\n\
                    0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n1 1 0 0 0 1 1\n0 1 0 1 1 1 0.5\n\
                    4 0 1 2 3 0.25 1 2 3\n3 0 2 3 0.75 4 5 6\n";
        let mesh = read_ply(text.as_bytes(), &mut Vec::new()).unwrap();
        assert_eq!(mesh.triangle_count(), 3);
        assert_eq!(attribute(&mesh, "vertex_color").dim, 4);
        assert_eq!(attribute(&mesh, "vertex_color").values[12..], [1.0, 1.0, 1.0, 0.5]);
        // The quad's value on both triangles of its fan, then the triangle's.
        assert_eq!(attribute(&mesh, "face_wear").values, [0.25, 0.25, 0.75]);
        assert_eq!(attribute(&mesh, "face_tint_color").values, [1.0, 2.0, 3.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        // Spread over the corners: the face value at all three, the vertex values per corner.
        let t = mesh.triangles();
        let wear = t.attributes.iter().find(|a| a.name == "face_wear").unwrap();
        assert_eq!(wear.corners[2], [[0.75, 0.0, 0.0, 0.0]; 3]);
        let color = t.attributes.iter().find(|a| a.name == "vertex_color").unwrap();
        assert_eq!(color.corners[1], [[1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0], [1.0, 1.0, 1.0, 0.5]]);
    }

    #[test]
    fn a_mesh_without_extra_properties_has_no_attributes() {
        let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                    property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n\
                    element face 1\nproperty list uchar int vertex_indices\nend_header\n\
                    0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n";
        let mesh = read_ply(text.as_bytes(), &mut Vec::new()).unwrap();
        assert!(mesh.attributes.is_empty());
        assert!(mesh.triangles().attributes.is_empty());
    }

    #[test]
    fn binary_attributes_are_read() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                          property float z\nproperty uchar w_0\nelement face 1\nproperty list uchar int vertex_indices\n\
                          property uchar k_0\nend_header\n"
            .to_vec();
        for (p, w) in [([0f32, 0.0, 0.0], 64u8), ([1.0, 0.0, 0.0], 128), ([0.0, 1.0, 0.0], 255)] {
            p.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
            bytes.push(w);
        }
        bytes.push(3);
        [0i32, 1, 2].iter().for_each(|i| bytes.extend(i.to_le_bytes()));
        bytes.push(128);
        let mesh = read_ply(bytes.as_slice(), &mut Vec::new()).unwrap();
        assert_eq!(attribute(&mesh, "vertex_w").values, [64.0, 128.0, 255.0]);
        assert_eq!(attribute(&mesh, "face_k").values, [128.0]);
    }
}
