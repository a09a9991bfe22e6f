//! `Instancing` → the kernel's buffers (read by `caustic_kernel::instancing`). A BVH over
//! `PRIM_INSTANCE` primitives (the TLAS, from node 0) whose leaves name a group's BVH (a BLAS) and
//! its transforms: each instance, bounded by its group's box moved to the world, and one for the
//! scene's own shapes, without a transform, whose BVH is the one-level scene's. So the kernel's
//! instance leaves only move rays and every primitive is met in a BLAS (one copy of the
//! intersection code). Buffers: primitives `[scene's | instances' | each group's]`, nodes
//! `[TLAS | scene's BVH | each group's BVH]`; each instance's world→object and object→world maps in
//! `tables`. The scene's primitives keep their indices, so lights still name theirs.
use super::bvh::build_bvh;
use super::lights::LightList;
use super::primitives::primitives;
use crate::scene::instancing::Instancing;
use crate::scene::Scene;
use anyhow::Result;
use caustic_kernel::instancing::INSTANCE_FLOATS;
use caustic_kernel::layout::{BvhNode, Primitive, TriangleAttributes, NONE, PRIM_INSTANCE};
use glam::{Mat4, Vec3};

/// Turns the one-level scene (`nodes` over `prims`) into the two-level one when `scene` has
/// instances; returns whether it did (the kernel's `features::INSTANCING`).
pub(crate) fn two_level(
    nodes: &mut Vec<BvhNode>,
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    scene: &Scene,
    blocks: &mut crate::prepare::attribute_buffers::AttributeBlocks,
) -> Result<bool> {
    let groups = build_groups(&scene.instancing, blocks)?;
    let mut tops = proxies(&scene.instancing, &groups);
    if tops.is_empty() {
        return Ok(false);
    }
    let world = !prims.is_empty();
    if world {
        tops.push(Primitive {
            p0: nodes[0].min,
            kind: PRIM_INSTANCE,
            material: NONE,
            p2: nodes[0].max,
            light: NONE,
            flags: NONE,
            ..Default::default()
        });
    } else {
        nodes.clear();
    }
    let mut top_attributes = vec![TriangleAttributes::default(); tops.len()];
    let mut tlas = build_bvh(&mut tops, &mut top_attributes, &mut Vec::new(), &mut [])?;
    let tops_base = prims.len() as u32;
    for n in tlas.iter_mut().filter(|n| n.prim_count > 0) {
        n.first += tops_base;
    }
    // The scene's BVH follows the TLAS: its inner nodes' children move, its leaves' primitives do not.
    let world_root = tlas.len() as u32;
    for n in nodes.iter_mut().filter(|n| n.prim_count == 0) {
        n.first += world_root;
    }
    for p in tops.iter_mut().filter(|p| p.flags == NONE) {
        p.material = world_root;
    }
    tlas.append(nodes);
    *nodes = tlas;
    prims.append(&mut tops);
    attributes.append(&mut top_attributes);
    append_groups(nodes, prims, attributes, &groups);
    Ok(true)
}

/// One group's primitives in BVH order and its BVH (leaf and child indices local to the group).
pub(crate) struct Blas {
    nodes: Vec<BvhNode>,
    prims: Vec<Primitive>,
    attributes: Vec<TriangleAttributes>,
}

/// The BLAS of every group that holds anything (`None` for an empty one, whose instances are left
/// out: they place nothing).
fn build_groups(
    instancing: &Instancing,
    blocks: &mut crate::prepare::attribute_buffers::AttributeBlocks,
) -> Result<Vec<Option<Blas>>> {
    let mut used = vec![false; instancing.groups.len()];
    for i in &instancing.instances {
        used[i.group] = true;
    }
    instancing
        .groups
        .iter()
        .zip(used)
        .map(|(shapes, used)| {
            if !used || shapes.is_empty() {
                return Ok(None);
            }
            // Groups hold no emitters (the loader refuses them), so no light refers to these.
            let mut lights = LightList::default();
            let (mut prims, mut attributes) = primitives(shapes, false, &mut lights, blocks);
            let nodes = build_bvh(&mut prims, &mut attributes, &mut Vec::new(), &mut lights.lights)?;
            Ok(Some(Blas { nodes, prims, attributes }))
        })
        .collect()
}

/// The instances as primitives of the scene's BVH: bounds in `p0` and `p2`, the instance's index in
/// `flags` and its group in `material` until `append_groups` and `place_transforms` replace them.
fn proxies(instancing: &Instancing, blases: &[Option<Blas>]) -> Vec<Primitive> {
    let mut out = Vec::new();
    for (index, instance) in instancing.instances.iter().enumerate() {
        let Some(blas) = &blases[instance.group] else { continue };
        let (lo, hi) = world_bounds(&blas.nodes[0], instance.to_world);
        out.push(Primitive {
            p0: lo.to_array(),
            kind: PRIM_INSTANCE,
            p1: [0.0; 3],
            material: instance.group as u32,
            p2: hi.to_array(),
            light: NONE,
            flags: index as u32,
            offset_floor: 0.0,
            _pad: [0; 2],
        });
    }
    out
}

/// The world box of a group-space box under `m`: the box of its eight moved corners.
fn world_bounds(root: &BvhNode, m: Mat4) -> (Vec3, Vec3) {
    let (a, b) = (Vec3::from(root.min), Vec3::from(root.max));
    let mut lo = Vec3::splat(f32::MAX);
    let mut hi = Vec3::splat(f32::MIN);
    for corner in 0..8 {
        let c = Vec3::new(
            if corner & 1 == 0 { a.x } else { b.x },
            if corner & 2 == 0 { a.y } else { b.y },
            if corner & 4 == 0 { a.z } else { b.z },
        );
        let p = m.transform_point3(c);
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (lo, hi)
}

/// Appends every BLAS after the scene's nodes and primitives (rebasing its indices) and points each
/// instance primitive at its group's root.
fn append_groups(
    nodes: &mut Vec<BvhNode>,
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    blases: &[Option<Blas>],
) {
    let mut roots = vec![NONE; blases.len()];
    for (g, blas) in blases.iter().enumerate() {
        let Some(blas) = blas else { continue };
        let (node_base, prim_base) = (nodes.len() as u32, prims.len() as u32);
        roots[g] = node_base;
        nodes.extend(blas.nodes.iter().map(|n| BvhNode {
            first: n.first + if n.prim_count > 0 { prim_base } else { node_base },
            ..*n
        }));
        prims.extend_from_slice(&blas.prims);
        attributes.extend_from_slice(&blas.attributes);
    }
    for p in prims.iter_mut().filter(|p| p.kind == PRIM_INSTANCE && p.flags != NONE) {
        p.material = roots[p.material as usize];
    }
}

/// Writes each instance's maps into `tables` (rows of world→object, then of object→world) and
/// points its primitive at them (the scene's own shapes' stays `NONE`: no transform).
pub(crate) fn place_transforms(prims: &mut [Primitive], tables: &mut Vec<f32>, instancing: &Instancing) {
    for p in prims.iter_mut().filter(|p| p.kind == PRIM_INSTANCE && p.flags != NONE) {
        let to_world = instancing.instances[p.flags as usize].to_world;
        p.flags = tables.len() as u32;
        for m in [to_world.as_dmat4().inverse().as_mat4(), to_world] {
            // Rows of the top 3×4 block (glam stores columns).
            let t = m.transpose();
            for row in [t.x_axis, t.y_axis, t.z_axis] {
                tables.extend(row.to_array());
            }
        }
        debug_assert_eq!(tables.len() as u32 - p.flags, INSTANCE_FLOATS);
    }
}

/// Primitives the instances place, counting each group's once per instance (what flattening would
/// have stored).
pub fn placed_primitives(instancing: &Instancing) -> u64 {
    let per_group = instancing.group_primitives();
    instancing.instances.iter().map(|i| per_group[i.group] as u64).sum()
}
