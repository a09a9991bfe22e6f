//! Mitsuba's `.serialized` meshes: a file of one or more meshes, each an uncompressed 4-byte header
//! (format 0x041C, version 3 or 4) followed by a zlib stream, and at the end of the file a table of
//! where each mesh starts plus the mesh count. All numbers are little-endian.
//!
//! Inside a mesh stream: u32 flags, the mesh name (version 4 only, NUL-terminated), u64 vertex and
//! triangle counts, then arrays of positions, normals, uvs and colours (those the flags announce),
//! in f32 or f64, then u32 triangle indices.
use crate::scene::mesh::Mesh;
use anyhow::{anyhow, bail, Context, Result};
use flate2::read::ZlibDecoder;
use glam::{Vec2, Vec3};
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

const FORMAT_MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_UVS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const DOUBLE_PRECISION: u32 = 0x2000;
/// DEFLATE cannot expand data more than about 1032-fold; counts asking for more than that are corrupt
/// (checking first keeps a damaged header from asking for terabytes).
const MAX_DEFLATE_RATIO: u64 = 1032;

/// Loads mesh number `shape_index` of a serialized file; every failure names the file.
///
/// Mitsuba 3 ignores the stream's "face normals" flag (0x0010) and only honours the shape's
/// `face_normals` property; so do we. Vertex colours are skipped.
pub fn load_serialized(path: &Path, shape_index: u32) -> Result<Mesh> {
    let file = crate::system::files::open(path, "serialized mesh")?;
    let mesh = read_mesh(file, shape_index).map_err(|e| {
        anyhow!("{}: invalid serialized mesh (shape_index {shape_index}): {e:#}", path.display())
    })?;
    mesh.validate(path)?;
    Ok(mesh)
}

fn read_mesh(mut file: File, shape_index: u32) -> Result<Mesh> {
    let file_size = file.metadata()?.len();
    let version = read_stream_header(&mut file)?;
    let start = stream_offset(&mut file, file_size, version, shape_index)?;
    file.seek(SeekFrom::Start(start))?;
    let stream_version = read_stream_header(&mut file).context("at the start of the selected mesh")?;
    if stream_version != version {
        bail!("mesh {shape_index} has version {stream_version}, the file {version}");
    }
    let max_unpacked = (file_size - start).saturating_mul(MAX_DEFLATE_RATIO);
    let mut stream = ZlibDecoder::new(BufReader::new(file));
    read_mesh_stream(&mut stream, version, max_unpacked).map_err(|e| {
        match e.downcast_ref::<std::io::Error>() {
            Some(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
                anyhow!("the compressed data ends early (truncated file?)")
            }
            _ => e,
        }
    })
}

/// Reads and checks a mesh header; returns its version.
fn read_stream_header(input: &mut impl Read) -> Result<u16> {
    let mut bytes = [0u8; 4];
    input.read_exact(&mut bytes).context("the file is too short for a header")?;
    let (magic, version) =
        (u16::from_le_bytes([bytes[0], bytes[1]]), u16::from_le_bytes([bytes[2], bytes[3]]));
    if magic != FORMAT_MAGIC {
        bail!("not a serialized mesh (format id {magic:#06x}, expected {FORMAT_MAGIC:#06x})");
    }
    if version != 3 && version != 4 {
        bail!("unsupported version {version} (3 and 4 are known)");
    }
    Ok(version)
}

/// Where mesh `shape_index` starts, from the table at the end of the file: u32 (version 3) or u64
/// (version 4) offsets, then a u32 count. The first mesh starts at 0, which is all that Mitsuba
/// assumes for index 0, so a file without the table still loads its first mesh.
fn stream_offset(file: &mut File, file_size: u64, version: u16, shape_index: u32) -> Result<u64> {
    if shape_index == 0 {
        return Ok(0);
    }
    let entry_size: u64 = if version == 3 { 4 } else { 8 };
    let count = u64::from(read_u32_at(file, file_size.checked_sub(4).context("the file is too short")?)?);
    if u64::from(shape_index) >= count {
        bail!(
            "shape_index {shape_index} is out of range: the file holds {count} meshes (0..{})",
            count.saturating_sub(1)
        );
    }
    let table_size = count * entry_size + 4;
    if table_size > file_size {
        bail!("the table of {count} meshes does not fit in the file (truncated file?)");
    }
    let entry = file_size - 4 - (count - u64::from(shape_index)) * entry_size;
    let offset = if version == 3 { u64::from(read_u32_at(file, entry)?) } else { read_u64_at(file, entry)? };
    if offset + 4 > file_size - table_size {
        bail!("mesh {shape_index} starts at {offset}, past the end of the data");
    }
    Ok(offset)
}

fn read_u32_at(file: &mut File, at: u64) -> Result<u32> {
    let mut bytes = [0u8; 4];
    file.seek(SeekFrom::Start(at))?;
    file.read_exact(&mut bytes)?;
    Ok(u32::from_le_bytes(bytes))
}

fn read_u64_at(file: &mut File, at: u64) -> Result<u64> {
    let mut bytes = [0u8; 8];
    file.seek(SeekFrom::Start(at))?;
    file.read_exact(&mut bytes)?;
    Ok(u64::from_le_bytes(bytes))
}

/// What the start of a mesh stream announces.
struct StreamLayout {
    flags: u32,
    vertex_count: usize,
    triangle_count: usize,
}

impl StreamLayout {
    fn scalar_size(&self) -> u64 {
        if self.flags & DOUBLE_PRECISION != 0 {
            8
        } else {
            4
        }
    }

    fn has(&self, flag: u32) -> bool {
        self.flags & flag != 0
    }

    /// Bytes of vertex and index data that follow the counts.
    fn payload_size(&self) -> u64 {
        let per_vertex = 3
            + 3 * u64::from(self.has(HAS_NORMALS))
            + 2 * u64::from(self.has(HAS_UVS))
            + 3 * u64::from(self.has(HAS_COLORS));
        (self.vertex_count as u64)
            .saturating_mul(per_vertex * self.scalar_size())
            .saturating_add((self.triangle_count as u64).saturating_mul(12))
    }
}

fn read_mesh_stream(stream: &mut impl Read, version: u16, max_unpacked: u64) -> Result<Mesh> {
    let layout = read_stream_layout(stream, version)?;
    if layout.payload_size() > max_unpacked {
        bail!(
            "{} vertices and {} triangles cannot fit in the file (corrupt counts?)",
            layout.vertex_count,
            layout.triangle_count
        );
    }
    let positions = read_vec3s(stream, &layout)?;
    let normals = if layout.has(HAS_NORMALS) {
        Some(read_vec3s(stream, &layout)?.into_iter().map(Vec3::normalize_or_zero).collect())
    } else {
        None
    };
    let uvs = if layout.has(HAS_UVS) {
        Some(read_scalars(stream, &layout, 2)?.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect())
    } else {
        None
    };
    if layout.has(HAS_COLORS) {
        read_scalars(stream, &layout, 3)?;
    }
    let mut index_bytes = vec![0u8; layout.triangle_count * 12];
    stream.read_exact(&mut index_bytes)?;
    let indices = index_bytes.chunks_exact(4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    // Reading on to the end of the stream lets zlib check its checksum, which catches damage that
    // still happens to decompress.
    std::io::copy(stream, &mut std::io::sink())?;
    Ok(Mesh { positions, indices, normals, uvs, triangle_materials: Vec::new(), attributes: Vec::new() })
}

fn read_stream_layout(stream: &mut impl Read, version: u16) -> Result<StreamLayout> {
    let flags = u32::from_le_bytes(read_array(stream)?);
    if version >= 4 {
        skip_name(stream)?;
    }
    let vertex_count = u64::from_le_bytes(read_array(stream)?);
    let triangle_count = u64::from_le_bytes(read_array(stream)?);
    // Indices are u32 unless there are more vertices than u32 can count, which we cannot hold anyway.
    if vertex_count > u64::from(u32::MAX) || triangle_count > u64::from(u32::MAX) {
        bail!("{vertex_count} vertices and {triangle_count} triangles are more than supported");
    }
    Ok(StreamLayout { flags, vertex_count: vertex_count as usize, triangle_count: triangle_count as usize })
}

/// Skips the NUL-terminated mesh name; names are short, so a long run without NUL is corruption.
fn skip_name(stream: &mut impl Read) -> Result<()> {
    for _ in 0..65536 {
        if read_array::<1>(stream)?[0] == 0 {
            return Ok(());
        }
    }
    bail!("the mesh name is not terminated")
}

fn read_array<const N: usize>(stream: &mut impl Read) -> Result<[u8; N]> {
    let mut bytes = [0u8; N];
    stream.read_exact(&mut bytes)?;
    Ok(bytes)
}

/// `dim` values per vertex, in the stream's precision, as f32.
fn read_scalars(stream: &mut impl Read, layout: &StreamLayout, dim: usize) -> Result<Vec<f32>> {
    let size = layout.scalar_size() as usize;
    let mut bytes = vec![0u8; layout.vertex_count * dim * size];
    stream.read_exact(&mut bytes)?;
    Ok(if size == 8 {
        bytes.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")) as f32).collect()
    } else {
        bytes.chunks_exact(4).map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes"))).collect()
    })
}

fn read_vec3s(stream: &mut impl Read, layout: &StreamLayout) -> Result<Vec<Vec3>> {
    Ok(read_scalars(stream, layout, 3)?.chunks_exact(3).map(Vec3::from_slice).collect())
}
