//! The scene's shapes as the kernel's primitive records (triangles, spheres, disks) with their
//! per-triangle attributes, in scene order, and the area lights on them; for AOVs, each
//! primitive's shape as Mitsuba numbers it.
use super::lights::LightList;
use crate::scene::{rgba, Geometry, Scene, Shape};
use caustic_kernel::layout::*;
use caustic_kernel::spectrum::luminance;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;

fn arr(v: Vec3) -> [f32; 3] {
    v.to_array()
}

/// Mitsuba's barycentric texture coordinates for meshes without any.
const DEFAULT_UVS: [Vec2; 3] = [Vec2::ZERO, Vec2::X, Vec2::Y];

/// Primitive records and their attributes in scene order, and the area lights on them.
pub(crate) fn primitives(
    shapes: &[Shape],
    light_tracing: bool,
    lights: &mut LightList,
    blocks: &mut super::attribute_buffers::AttributeBlocks,
) -> (Vec<Primitive>, Vec<TriangleAttributes>) {
    let mut prims = Vec::new();
    let mut attributes = Vec::new();
    for shape in shapes {
        // Mitsuba's `directionalarea` lights nothing that path tracing finds (its `eval` and light
        // samples are zero): outside light tracing its shape is an ordinary (black) surface.
        let emission = shape.emission.filter(|_| !shape.emission_directional || light_tracing);
        if emission.is_some() {
            lights.begin_emitter();
        }
        let flags_base = if shape.flip_normals { PRIM_FLAG_FLIP } else { 0 };
        let mut push = |mut prim: Primitive, attr: TriangleAttributes, area: f32, light_kind: u32| {
            prim.light = NONE;
            if let Some(radiance) = emission {
                // A textured emitter's radiance is the texture's (the kernel multiplies by 1); its
                // power, the mean's.
                let light = Light {
                    kind: light_kind,
                    prim: prims.len() as u32,
                    table: NONE,
                    radiance: if shape.emission_texture.is_some() { [1.0; 4] } else { rgba(radiance) },
                    texture: shape.emission_texture.unwrap_or(NONE),
                    flags: if shape.emission_directional { LIGHT_FLAG_DIRECTIONAL_AREA } else { 0 },
                    ..Default::default()
                };
                // Power: π·A·L, or A·L along the normal alone.
                let lobe = if shape.emission_directional { 1.0 } else { PI };
                prim.light = lights.push(light, lobe * area * luminance(Vec3::from(radiance)));
            }
            prims.push(prim);
            attributes.push(attr);
        };
        match &shape.geometry {
            Geometry::Triangles { triangles, normals, uvs, attributes: corner_attributes } => {
                for (i, t) in triangles.iter().enumerate() {
                    // In f64: squaring an f32 cross product overflows for edges over about 1e9.5.
                    let area = crate::scene::mesh::triangle_area(*t) as f32;
                    let mut flags = flags_base;
                    let uv = uvs.as_ref().map_or(DEFAULT_UVS, |u| u[i]);
                    let mut attr = TriangleAttributes {
                        uv0: uv[0].to_array(),
                        uv1: uv[1].to_array(),
                        uv2: uv[2].to_array(),
                        mesh_attributes: blocks.push_triangle(corner_attributes, i),
                        ..Default::default()
                    };
                    if let Some(c) = normals {
                        let gn = crate::scene::mesh::face_normal(*t).unwrap_or(Vec3::Z);
                        // Flat triangles skip interpolation: a scene pays nothing for normals it does not need.
                        if c[i].iter().any(|n| n.dot(gn) < 1.0 - 1e-6) {
                            flags |= PRIM_FLAG_SMOOTH;
                            (attr.n0, attr.n1, attr.n2) = (arr(c[i][0]), arr(c[i][1]), arr(c[i][2]));
                        }
                    }
                    let prim = Primitive {
                        p0: arr(t[0]),
                        kind: PRIM_TRIANGLE,
                        p1: arr(t[1]),
                        material: shape.material,
                        p2: arr(t[2]),
                        light: NONE,
                        flags,
                        offset_floor: 0.0,
                        _pad: [0; 2],
                    };
                    push(prim, attr, area, LIGHT_AREA);
                }
            }
            Geometry::Sphere { center, radius, frame } => {
                let (tilt, p2) = sphere_orientation(frame);
                let prim = Primitive {
                    p0: arr(*center),
                    kind: PRIM_SPHERE,
                    p1: [*radius, tilt[0], tilt[1]],
                    material: shape.material,
                    p2,
                    light: NONE,
                    flags: flags_base,
                    offset_floor: 0.0,
                    _pad: [0; 2],
                };
                push(prim, TriangleAttributes::default(), 4.0 * PI * radius * radius, LIGHT_SPHERE);
            }
            Geometry::Disk { center, u, v } => {
                let prim = Primitive {
                    p0: arr(*center),
                    kind: PRIM_DISK,
                    p1: arr(*u),
                    material: shape.material,
                    p2: arr(*v),
                    light: NONE,
                    flags: flags_base,
                    offset_floor: 0.0,
                    _pad: [0; 2],
                };
                push(prim, TriangleAttributes::default(), PI * u.cross(*v).length(), LIGHT_AREA);
            }
        }
    }
    (prims, attributes)
}

/// The record's words for a sphere's frame (`caustic_kernel::shape::sphere::Orientation`): a
/// mirrored frame is stored as the rotation of its x-negated self, the quaternion with w ≥ 0 (its
/// `w − 1` is then small near the identity).
fn sphere_orientation(frame: &Mat3) -> ([f32; 2], [f32; 3]) {
    let mirrored = frame.determinant() < 0.0;
    let rotation = if mirrored { *frame * Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0)) } else { *frame };
    let mut q = glam::Quat::from_mat3(&rotation).normalize();
    if q.w < 0.0 {
        q = -q;
    }
    caustic_kernel::shape::sphere::Orientation::words(q.x, q.y, q.z, q.w, mirrored)
}

/// Per primitive in scene order (as `primitives` pushes them): Mitsuba's shape index and the
/// primitive's index within its shape (a triangle's in its mesh; 0 for analytic shapes).
pub(super) fn prim_origins(scene: &Scene) -> Vec<[u32; 2]> {
    let is_mesh: Vec<bool> =
        scene.shapes.iter().map(|s| matches!(s.geometry, Geometry::Triangles { .. })).collect();
    let shape_index = shape_indices(&is_mesh);
    let mut origins = Vec::new();
    for (shape, &index) in scene.shapes.iter().zip(&shape_index) {
        let count = match &shape.geometry {
            Geometry::Triangles { triangles, .. } => triangles.len() as u32,
            Geometry::Sphere { .. } | Geometry::Disk { .. } => 1,
        };
        origins.extend((0..count).map(|i| [index, i]));
    }
    origins
}

/// Mitsuba's numbering of the shapes (`shape_index`, from 1), measured on Mitsuba 3.9.1: its parser
/// merges the meshes into one list after the other shapes, so the analytic shapes (sphere, disk)
/// come first in file order, then the meshes (every triangle shape: rectangle, cube, OBJ, PLY, …)
/// in reverse file order (the order of Mitsuba's hash table of meshes, seen with four to twelve
/// shapes). Meshes that share a BSDF and emitter Mitsuba merges into one shape; caustic does not.
pub fn shape_indices(is_mesh: &[bool]) -> Vec<u32> {
    let mut index = vec![0u32; is_mesh.len()];
    let mut next = 1;
    for (i, _) in is_mesh.iter().enumerate().filter(|(_, m)| !**m) {
        index[i] = next;
        next += 1;
    }
    for (i, _) in is_mesh.iter().enumerate().rev().filter(|(_, m)| **m) {
        index[i] = next;
        next += 1;
    }
    index
}
