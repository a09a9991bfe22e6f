//! Mitsuba's `shapegroup` + `instance` in the scene description: each group's shapes kept once, in
//! the group's space, and the instances that place them (`Instancing`), which `instance_buffers`
//! turns into a BVH per group under the scene's. Where that does not pay, instances are flattened
//! into ordinary shapes, each group's shape `placed` by its instance (`Scene::flatten_instances`): a
//! group placed once costs no less stored once, and its flattened copy is walked without the detour
//! through a transform.
use crate::scene::shape::{Geometry, Shape};
use anyhow::{bail, Result};
use glam::{Mat3, Mat4};

/// Groups placed fewer times than this are flattened by the loader.
pub const MIN_PLACEMENTS: usize = 2;

/// One placement of a group.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Index into `Instancing::groups`.
    pub group: usize,
    pub to_world: Mat4,
    /// Where the instance came from (file:line), for messages.
    pub origin: String,
}

/// Shapegroups stored once and their instances. Groups hold triangles and disks only: spheres (one
/// primitive each, as large as an instance's record) are flattened by the loader.
#[derive(Clone, Debug, Default)]
pub struct Instancing {
    pub groups: Vec<Vec<Shape>>,
    pub instances: Vec<Instance>,
}

impl Instancing {
    /// Primitives each group stores (triangles and disks), indexed like `groups`.
    pub fn group_primitives(&self) -> Vec<usize> {
        self.groups.iter().map(|g| g.iter().map(|s| primitive_count(&s.geometry)).sum()).collect()
    }
}

fn primitive_count(g: &Geometry) -> usize {
    match g {
        Geometry::Triangles { triangles, .. } => triangles.len(),
        Geometry::Sphere { .. } | Geometry::Disk { .. } => 1,
    }
}

/// Whether `m` can place a group by ray transformation: invertible, finite both ways.
pub fn invertible(m: Mat4) -> bool {
    let det = Mat3::from_mat4(m).determinant();
    det != 0.0 && det.is_finite() && m.inverse().is_finite()
}

/// `shape` of a group, placed by an instance's `to_world` as an ordinary shape.
pub fn placed(shape: &Shape, to_world: Mat4, origin: &str) -> Result<Shape> {
    let geometry = transformed(&shape.geometry, to_world).map_err(|e| anyhow::anyhow!("{origin}: {e}"))?;
    // Mitsuba moves an instance's normals by the inverse transpose, which keeps them facing out
    // under a mirror; the moved vertices of a mesh and axes of a disk face in instead (measured
    // against Mitsuba: 1% dark with a mirrored instance). So a mirror reverses a mesh's winding
    // (`transformed`) and flips a disk.
    let mirrors = Mat3::from_mat4(to_world).determinant() < 0.0;
    let flip = mirrors && matches!(geometry, Geometry::Disk { .. });
    Ok(Shape {
        origin: format!("{} (instanced at {origin})", shape.origin),
        geometry,
        flip_normals: shape.flip_normals ^ flip,
        ..shape.clone()
    })
}

/// World-space geometry moved by `m` (an instance's `to_world`): vertices as points, shading normals
/// by the inverse transpose, a mesh's winding reversed under a mirror; a sphere only under a uniform
/// scale (as `load_shape` requires).
pub fn transformed(geometry: &Geometry, m: Mat4) -> Result<Geometry> {
    Ok(match geometry {
        Geometry::Triangles { triangles, normals, uvs, attributes } => {
            let normal_matrix = Mat3::from_mat4(m).inverse().transpose();
            // Under a mirror, corners 1 and 2 trade places (with their normals and uvs).
            let order = if Mat3::from_mat4(m).determinant() < 0.0 { [0, 2, 1] } else { [0, 1, 2] };
            Geometry::Triangles {
                triangles: triangles.iter().map(|t| order.map(|i| m.transform_point3(t[i]))).collect(),
                normals: normals.as_ref().map(|ns| {
                    ns.iter().map(|t| order.map(|i| (normal_matrix * t[i]).normalize_or_zero())).collect()
                }),
                uvs: uvs.as_ref().map(|us| us.iter().map(|t| order.map(|i| t[i])).collect()),
                attributes: attributes
                    .iter()
                    .map(|a| crate::scene::mesh::CornerAttribute {
                        corners: a.corners.iter().map(|t| order.map(|i| t[i])).collect(),
                        ..a.clone()
                    })
                    .collect(),
            }
        }
        Geometry::Sphere { center, radius, frame } => {
            // A mirror keeps a sphere a sphere: compare the scales' magnitudes.
            let scale = m.to_scale_rotation_translation().0.abs();
            if (scale.x - scale.y).abs() > 1e-4 * scale.x || (scale.x - scale.z).abs() > 1e-4 * scale.x {
                bail!("an instanced sphere may only be scaled uniformly");
            }
            Geometry::Sphere {
                center: m.transform_point3(*center),
                radius: radius * scale.x,
                frame: Mat3::from_mat4(m) * (1.0 / scale.x) * *frame,
            }
        }
        Geometry::Disk { center, u, v } => Geometry::Disk {
            center: m.transform_point3(*center),
            u: m.transform_vector3(*u),
            v: m.transform_vector3(*v),
        },
    })
}
