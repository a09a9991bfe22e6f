//! Mitsuba's built-in shapes as meshes in their object space, with Mitsuba's uv parameterization.
//!
//! `cylinder` is analytic in Mitsuba; until the kernel intersects it analytically (as it does disks
//! and spheres) we tessellate it with N = `SEGMENTS` segments around. A chord spanning 2π/N of a
//! circle of radius r lies at most r·(1 − cos(π/N)) ≈ 4.7e-6·r inside it for N = 1024, below f32
//! resolution at unit scale; the area falls short by the factor N·sin(π/N)/π ≈ 1 − 1.6e-6.
use crate::scene::mesh::Mesh;
use glam::{Mat4, Vec2, Vec3};
use std::f32::consts::TAU;

/// Segments around the cylinder.
pub const SEGMENTS: u32 = 1024;

/// The angle of segment boundary `i` of `SEGMENTS`; the last boundary is the first again, exactly.
fn boundary_angle(i: u32) -> f32 {
    if i == SEGMENTS {
        0.0
    } else {
        TAU * i as f32 / SEGMENTS as f32
    }
}

/// Mitsuba's `rectangle`: [-1, 1]² in the z = 0 plane, facing +z, uv = xy / 2 + 1/2. Vertex `k`
/// sits at uv (k & 1, k >> 1), split along the same diagonal as Mitsuba's.
pub fn rectangle() -> Mesh {
    let uvs: Vec<Vec2> = (0..4u32).map(|k| Vec2::new((k & 1) as f32, (k >> 1) as f32)).collect();
    Mesh {
        positions: uvs.iter().map(|uv| (*uv * 2.0 - 1.0).extend(0.0)).collect(),
        indices: vec![1, 2, 0, 1, 3, 2],
        normals: None,
        uvs: Some(uvs),
        ..Default::default()
    }
}

/// Mitsuba's `cube`: [-1, 1]³ with outward faces, each face mapped onto [0, 1]² in uv. The corner
/// order of each face (and so the orientation of its uv square) follows Mitsuba's vertex table.
pub fn cube() -> Mesh {
    const FACES: [[[f32; 3]; 4]; 6] = [
        [[1.0, -1.0, -1.0], [1.0, -1.0, 1.0], [-1.0, -1.0, 1.0], [-1.0, -1.0, -1.0]],
        [[1.0, 1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, 1.0, 1.0], [1.0, 1.0, 1.0]],
        [[1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [1.0, -1.0, 1.0]],
        [[1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, -1.0, 1.0]],
        [[-1.0, -1.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, -1.0]],
        [[1.0, 1.0, -1.0], [1.0, -1.0, -1.0], [-1.0, -1.0, -1.0], [-1.0, 1.0, -1.0]],
    ];
    const FACE_UVS: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let mut uvs = Vec::new();
    let mut mesh = Mesh::default();
    for (f, corners) in FACES.iter().enumerate() {
        let base = 4 * f as u32;
        mesh.positions.extend(corners.iter().copied().map(Vec3::from_array));
        uvs.extend(FACE_UVS.iter().copied().map(Vec2::from_array));
        mesh.indices.extend([base, base + 1, base + 2, base + 3, base, base + 2]);
    }
    mesh.uvs = Some(uvs);
    mesh
}

/// Mitsuba's `cylinder` in its own space: radius 1 around the z axis from z = 0 to z = 1, open at
/// both ends, normals outward, uv = (φ/2π, z). Per-vertex normals are the exact radial directions,
/// so interpolated shading matches the analytic surface although the facets are flat.
pub fn unit_cylinder() -> Mesh {
    let mut mesh = Mesh::default();
    let (mut normals, mut uvs) = (Vec::new(), Vec::new());
    for i in 0..=SEGMENTS {
        let phi = boundary_angle(i);
        let radial = Vec3::new(phi.cos(), phi.sin(), 0.0);
        let u = i as f32 / SEGMENTS as f32;
        for z in [0.0, 1.0] {
            mesh.positions.push(radial + Vec3::Z * z);
            normals.push(radial);
            uvs.push(Vec2::new(u, z));
        }
    }
    for i in 0..SEGMENTS {
        let (bottom, top, next_bottom, next_top) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        mesh.indices.extend([bottom, next_bottom, next_top, bottom, next_top, top]);
    }
    mesh.normals = Some(normals);
    mesh.uvs = Some(uvs);
    mesh
}

/// The object-to-local transform Mitsuba puts in front of a cylinder's `to_world`: from the unit
/// cylinder to one of `radius` from `p0` to `p1`. The angle origin (u = 0) lies along the first
/// vector of Mitsuba's orthonormal basis around the axis. None when p0 = p1.
pub fn cylinder_placement(radius: f32, p0: Vec3, p1: Vec3) -> Option<Mat4> {
    let axis = p1 - p0;
    let length = axis.length();
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let n = axis / length;
    let (s, t) = orthonormal_basis(n);
    let frame = Mat4::from_cols(s.extend(0.0), t.extend(0.0), n.extend(0.0), p0.extend(1.0));
    Some(frame * Mat4::from_scale(Vec3::new(radius, radius, length)))
}

/// Two unit vectors completing `n` to a right-handed orthonormal basis, by the branchless
/// construction of Duff et al. 2017 ("Building an Orthonormal Basis, Revisited"), which Mitsuba
/// also uses, so that parameterizations built on it line up with Mitsuba's.
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}
