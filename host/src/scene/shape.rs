//! A shape of the scene: its geometry in world space (`Geometry`: triangles, a sphere or a disk) and
//! what covers it (`Shape`: material, emission, orientation). `Scene` lists them, and so does each
//! shapegroup of `instancing`.
use glam::{Mat3, Vec2, Vec3};

#[derive(Clone, Debug)]
pub enum Geometry {
    /// World-space triangles, with optional per-corner shading normals.
    Triangles {
        triangles: Vec<[Vec3; 3]>,
        normals: Option<Vec<[Vec3; 3]>>,
        uvs: Option<Vec<[Vec2; 3]>>,
        /// Named attributes at the corners (`mesh_attribute` textures read them): only those the
        /// shape's textures use are kept, so most shapes have none.
        attributes: Vec<crate::scene::mesh::CornerAttribute>,
    },
    Sphere {
        center: Vec3,
        radius: f32,
        /// The orientation of `to_world` (orthonormal, mirrored where its determinant is negative):
        /// Mitsuba's uv and tangents of a sphere turn with it.
        frame: Mat3,
    },
    /// Mitsuba's analytic disk: `center + a·u + b·v` for `a² + b² ≤ 1`, facing `u × v`.
    Disk { center: Vec3, u: Vec3, v: Vec3 },
}

#[derive(Clone, Debug)]
pub struct Shape {
    /// Where the shape came from, for messages (file:line or a name).
    pub origin: String,
    pub geometry: Geometry,
    /// Index into `Scene::materials`.
    pub material: u32,
    /// Uniform emitted radiance (linear sRGB) of an area emitter on this shape; with
    /// `emission_texture`, the texture's mean (what selection by power uses).
    pub emission: Option<[f32; 3]>,
    /// The texture (index into `Scene::textures`) giving the area emitter's radiance over the
    /// surface's uv, if textured.
    pub emission_texture: Option<u32>,
    /// Mitsuba's `directionalarea`: the emitter sends its radiance along the surface's normal only
    /// (light tracing alone carries that light; path tracing sees a black surface, as in Mitsuba).
    pub emission_directional: bool,
    pub flip_normals: bool,
}
